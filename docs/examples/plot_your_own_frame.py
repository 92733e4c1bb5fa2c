"""
A bogie frame of your own, from CAD into the car
================================================

A frame made in CAD (here with gmsh's OpenCASCADE kernel, written as STEP as any CAD system
would), its interfaces declared by where they are, reduced by Craig-Bampton as the built-in
bodies are (``axlebox bodies build --geometry frame.step --spec frame.toml``), its modes shown,
and the car run for a moment on it (``[bodies] frame = ...``).  The frame: two hollow side
beams over the journals, one hollow cross beam, the primary and air-spring seat pads and a
traction-centre block, with the built-in frame's interface heights so that the car's springs
meet it where they meet the built-in one.
"""

import tempfile
from pathlib import Path

import gmsh
import matplotlib.pyplot as plt
import numpy as np

from axlebox import configs
from axlebox.mbs.solver import integrate
from axlebox.pipelines import simulate
from axlebox.pipelines.bodies import build_user_body
from axlebox.pipelines.render import render_modes

work = Path(tempfile.mkdtemp())

# The part: x forward, y left, z up, the origin at the frame's centre on the side beams' axis.
L, Y, B, H, T = 2.9, 1.0, 0.20, 0.30, 0.016        # side beams: length, y, width, height, wall
X1, S, PAD = 1.1, 0.18, 0.03                        # primary seats at x = +-X1, S square, PAD thick
gmsh.initialize(interruptible=False)
gmsh.option.setNumber("General.Terminal", 0)
occ = gmsh.model.occ
solids, holes = [], []
for y in (Y, -Y):
    solids.append(occ.addBox(-L / 2, y - B / 2, -H / 2, L, B, H))
    holes.append(occ.addBox(-L / 2 + T, y - B / 2 + T, -H / 2 + T, L - 2 * T, B - 2 * T, H - 2 * T))
    for x in (X1, -X1):
        solids.append(occ.addBox(x - S / 2, y - S / 2, -H / 2 - PAD, S, S, PAD + 0.005))
    solids.append(occ.addBox(-0.2, y - B / 2, H / 2 - 0.005, 0.4, B, PAD + 0.005))   # air-spring seat
cross = (0.5, 0.25)                                  # the cross beam's x and z extent
solids.append(occ.addBox(-cross[0] / 2, -Y, -cross[1] / 2, cross[0], 2 * Y, cross[1]))
holes.append(occ.addBox(-cross[0] / 2 + T, -Y + B / 2, -cross[1] / 2 + T, cross[0] - 2 * T, 2 * Y - B,
                        cross[1] - 2 * T))
solids.append(occ.addBox(-0.15, -0.15, -H / 2, 0.3, 0.3, H / 2 - cross[1] / 2 + 0.005))   # traction
fused, _ = occ.fuse([(3, solids[0])], [(3, s) for s in solids[1:]])
occ.cut(fused, [(3, h) for h in holes])
occ.synchronize()
gmsh.option.setString("Geometry.OCCTargetUnit", "M")      # the model is in metres; STEP says so
gmsh.write(str(work / "frame.step"))
gmsh.finalize()

# %%
# The spec: what the part is, and its seven interfaces by the names the car attaches to, each a
# flat box around its face.
zb, zt = -H / 2 - PAD, H / 2 + PAD
places = {}
for axle, x in ((1, X1), (2, -X1)):
    for side, y in (("L", Y), ("R", -Y)):
        places[f"primary_{axle}_{side}"] = [x - S / 2, y - S / 2, zb, x + S / 2, y + S / 2, zb]
for side, y in (("L", Y), ("R", -Y)):
    places[f"secondary_{side}"] = [-0.2, y - B / 2, zt, 0.2, y + B / 2, zt]
places["traction_centre"] = [-0.15, -0.15, -H / 2, 0.15, 0.15, -H / 2]
spec = ['[body]\nkind = "frame"\nname = "my_frame"\n', "[mesh]\nsize = 0.08\n",
        "[reduction]\nmethod = \"craig-bampton\"\nmodes = 12\n"]
spec += [f"[interfaces.{n}]\nbox = {b}\ncoupling = \"rbe3\"\n" for n, b in places.items()]
(work / "frame.toml").write_text("\n".join(spec))
body, path = build_user_body(work / "frame.toml", geometry=work / "frame.step", out_dir=work)
print("lowest elastic modes, Hz:", np.round(body.frequencies_hz[:6], 1))

# %%
# Its first elastic mode, rendered off-screen as ``axlebox bodies report`` renders every body's.
(png,) = render_modes(body, work / "modes", modes=[0])
plt.figure(figsize=(8, 6))
plt.imshow(plt.imread(png))
plt.axis("off")

# %%
# In the car: the validation case with this frame in the front bogie, flexible; the statics
# find the car's rest on it, and a few milliseconds run.
cfg = simulate.load_config(configs.path("validation_48kmh"), duration=0.005,
                           overrides={"bodies": {"frame": str(path), "flexible": ["frame1"]}})
model, y0 = simulate.build_model(cfg, log=lambda *_: None)
run = integrate.simulate(model, 0.005, cfg.settings(), y0=y0)
print(f"5 ms of the car on my_frame: {'finished' if run.ok else run.message}")
