"""Off-screen mode-shape pictures (pyvista) and the HTML index of a body report."""
from __future__ import annotations

import html
import os
from pathlib import Path

import numpy as np

from axlebox._files import write_text
from axlebox.fem import bodyfile


def _pyvista():
    # no display: let VTK pick its off-screen (EGL / OSMesa) window instead of X
    if not os.environ.get("DISPLAY"):
        os.environ.setdefault("PYVISTA_OFF_SCREEN", "true")
        # go straight to EGL when it is there, instead of failing on X first (a warning)
        import ctypes.util
        if ctypes.util.find_library("EGL"):
            os.environ.setdefault("VTK_DEFAULT_OPENGL_WINDOW", "vtkEGLRenderWindow")
    import pyvista as pv
    pv.OFF_SCREEN = True
    return pv


def surface(points: np.ndarray, cells: np.ndarray, shapes: np.ndarray):
    """Outer surface of a tet10 mesh, its curved faces subdivided into triangles.

    The mode shapes ride along as point arrays ``m<k>`` so that VTK interpolates
    them onto the subdivision points.
    """
    pv = _pyvista()
    grid = pv.UnstructuredGrid({pv.CellType.QUADRATIC_TETRA: cells}, points)
    for k, u in enumerate(shapes):
        grid.point_data[f"m{k}"] = u
    return grid.extract_surface(nonlinear_subdivision=1, algorithm="dataset_surface")


def render_modes(body: bodyfile.ReducedBody, out_dir: Path, *, modes=None,
                 amplitude: float = 0.06, size=(800, 600)) -> list[Path]:
    """One PNG per mode: deformed surface coloured by ``|u|`` over the undeformed edges.

    The shape is scaled so its peak displacement is ``amplitude`` times the
    body's largest dimension.
    """
    pv = _pyvista()
    out_dir.mkdir(parents=True, exist_ok=True)
    modes = range(body.n_modes) if modes is None else modes
    surf = surface(body.mesh_points, body.mesh_cells, body.mode_shapes[list(modes)])
    edges = surf.extract_feature_edges(feature_angle=40, boundary_edges=True,
                                       non_manifold_edges=False, manifold_edges=False)
    extent = np.ptp(body.mesh_points, axis=0).max()
    paths = []
    plotter = pv.Plotter(off_screen=True, window_size=list(size))
    for j, k in enumerate(modes):
        u = np.asarray(surf.point_data[f"m{j}"])
        mag = np.linalg.norm(u, axis=1)
        scale = amplitude * extent / max(mag.max(), 1e-300)
        warped = surf.copy()
        warped.points = surf.points + scale * u
        warped.point_data["|u| (normalised)"] = mag / max(mag.max(), 1e-300)
        # one render a picture, the screenshot's: adding actors and setting the camera each
        # render otherwise (six or seven a picture, 12 of the demo's 17 s of pictures)
        plotter.suppress_rendering = True
        plotter.clear()
        plotter.add_mesh(edges, color="black", line_width=1, opacity=0.35)
        plotter.add_mesh(warped, scalars="|u| (normalised)", cmap="viridis", clim=(0, 1),
                         show_scalar_bar=True, scalar_bar_args={"title": "|u| (normalised)"})
        plotter.add_text(f"{body.name}  mode {k + 1}  {body.frequencies_hz[k]:.1f} Hz",
                         font_size=12, color="black")
        plotter.set_background("white")
        plotter.view_isometric()
        plotter.camera.zoom(1.2)
        plotter.suppress_rendering = False
        plotter.render()
        path = out_dir / f"{body.name}_mode{k + 1:02d}.png"
        plotter.screenshot(str(path))
        paths.append(path)
    plotter.close()
    return paths


def write_index(entries: list[tuple[bodyfile.ReducedBody, list[Path], list[str]]], out_dir: Path) -> Path:
    """``index.html`` with each body's summary and a row per mode: number, Hz, label, picture."""
    esc = html.escape
    parts = ["<!doctype html><html><head><meta charset='utf-8'><title>axlebox modal bodies</title>",
             "<style>body{font-family:sans-serif;margin:2em}table{border-collapse:collapse}"
             "td,th{border:1px solid #ccc;padding:4px 8px;text-align:right}img{width:400px}</style>",
             "</head><body><h1>Modal bodies</h1>"]
    for body, pngs, labels in entries:
        ref = body.reference_frequencies_hz
        couplings = ", ".join(f"{n} ({d.get('coupling')})" for n, d in body.nodes.items())
        parts.append(f"<h2>{esc(body.name)}</h2><p>method {esc(body.method)}, mass {body.mass:.1f} kg, "
                     f"centre of mass {np.round(body.center_of_mass, 4).tolist()} m, principal "
                     f"inertia {np.round(np.linalg.eigvalsh(body.inertia), 2).tolist()} kg m&sup2;, "
                     f"{body.meta.get('n_dof', '?')} FE DOF, interfaces: {esc(couplings)}</p>")
        parts.append("<table><tr><th>mode</th><th>frequency Hz</th><th>full FE Hz</th><th>label</th>"
                     "<th>shape</th></tr>")
        for k, png in enumerate(pngs):
            full = f"{ref[k]:.2f}" if ref is not None and k < len(ref) else ""
            lab = labels[k] if k < len(labels) else ""
            parts.append(f"<tr><td>{k + 1}</td><td>{body.frequencies_hz[k]:.2f}</td><td>{full}</td>"
                         f"<td>{esc(lab)}</td><td><img src='{esc(png.name)}' alt='mode {k + 1}'></td></tr>")
        parts.append("</table>")
    parts.append("</body></html>")
    return write_text(out_dir / "index.html", "\n".join(parts))


def report(body_dir: str | Path, out_dir: str | Path, *, max_modes: int | None = None,
           log=print) -> Path:
    """Render every ``*.h5`` reduced body in ``body_dir`` into ``out_dir``."""
    from . import modeid
    body_dir, out_dir = Path(body_dir), Path(out_dir)
    files = sorted(body_dir.glob("*.h5")) if body_dir.is_dir() else [body_dir]
    if not files or not files[0].exists():
        raise FileNotFoundError(f"bodies report: no reduced-body files (*.h5) in {str(body_dir)!r}")
    entries = []
    for f in files:
        body = bodyfile.read(f)
        n = body.n_modes if max_modes is None else min(max_modes, body.n_modes)
        labels = (modeid.classify(body.mesh_points, body.mode_shapes[:n])
                  if body.name == "wheelset" else [])
        pngs = render_modes(body, out_dir, modes=range(n))
        log(f"report: {body.name}: {len(pngs)} mode pictures")
        entries.append((body, pngs, labels))
    path = write_index(entries, out_dir)
    log(f"report: wrote {path}")
    return path
