"""
Free-free modes of a steel bar against Euler-Bernoulli
======================================================

The finite-element path every modal body takes (gmsh mesh, scikit-fem stiffness and mass, the
free-free eigenproblem with its six rigid modes checked, not assumed), on a body with a closed
form: a free-free bar bends at :math:`f_k = (\\beta_k L)^2 / (2\\pi L^2) \\sqrt{EI / \\rho A}`
with :math:`\\cos\\beta L \\cosh\\beta L = 1` (Blevins, *Formulas for Natural Frequency and Mode
Shape*, Table 8-1).  The first bending shape is rendered off-screen with pyvista.
"""

import matplotlib.pyplot as plt
import numpy as np
import pyvista as pv

from axlebox.fem import assembly, eigen
from axlebox.geometry import beam, mesh

pv.OFF_SCREEN = True

# A 2 m bar, 40 x 60 mm, meshed with quadratic tetrahedra of 20 mm (L / depth = 50: shear and
# rotary inertia lower the third mode by under 1 %).
p = beam.BeamParams(length=2.0, width=0.04, height=0.06)
fe = assembly.assemble(mesh.mesh_model("beam", beam.build, p, 0.02))
modes = eigen.free_free_modes(fe, 12)
print(f"{fe.ndof} DOF; rigid modes: {len(modes.rigid_frequencies_hz)}")

# %%
# Bending in y (the 40 mm direction): the modes whose kinetic energy is over 90 % along y.
E, rho = 2.1e11, 7850.0
Ms = fe.scalar_mass()
fy, shapes = [], []
for f, phi in zip(modes.frequencies_hz, modes.shapes.T):
    u = fe.field(phi)
    e = np.array([u[:, a] @ (Ms @ u[:, a]) for a in range(3)])
    if e[1] / e.sum() > 0.9:
        fy.append(f)
        shapes.append(u)
beta_L = np.array([4.73004074, 7.85320462, 10.99560784])
I, A = p.height * p.width ** 3 / 12, p.width * p.height
exact = beta_L ** 2 / (2 * np.pi * p.length ** 2) * np.sqrt(E * I / (rho * A))
for k, (f, g) in enumerate(zip(fy[:3], exact), 1):
    print(f"bending {k}: FE {f:8.2f} Hz, Euler-Bernoulli {g:8.2f} Hz, {100 * (f / g - 1):+.2f} %")
assert abs(fy[0] / exact[0] - 1) < 0.005

# %%
# The first bending shape, rendered off-screen.
points = fe.points
u = shapes[0]
grid = pv.PolyData(points + 0.2 * u / np.abs(u).max())      # 0.2 m at the largest
plotter = pv.Plotter(off_screen=True, window_size=(900, 300))
plotter.add_mesh(grid, scalars=np.linalg.norm(u, axis=1), point_size=4,
                 render_points_as_spheres=True, show_scalar_bar=False)
plotter.add_mesh(pv.PolyData(points), color="lightgrey", point_size=2)
plotter.view_xy()                          # bending in y: seen from above
plotter.camera.zoom(2.5)
image = plotter.screenshot(return_img=True)
plotter.close()
plt.figure(figsize=(9, 3))
plt.imshow(image)
plt.axis("off")
plt.title(f"first bending in y, {fy[0]:.1f} Hz")
