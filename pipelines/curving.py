"""What a vehicle engineer reads of a car's run on a line (issue 69): a curving table and a plot
along the line, from the result file alone (its config gives the line).

Per wheel: the guiding and vertical forces Y and Q in the circular part of the curve, and the
largest 2 m sliding mean of Y/Q over the run against Nadal's flange-climb limit (EN 14363; by how
much it stays below: the margin ``1 - (Y/Q) / limit``); per wheelset: the largest 2 m mean of its
sum of guiding forces against Prud'homme's limit, its lateral displacement on the track and its
angle of attack in the circular part; per bearing: each row's axial load (track y, on the outer
ring), radial load and the load zone's centre in the circular part.  "In the circular part": the
mean over the outputs at which the wheelset's contacts are inside a ``kind = 'curve'`` segment of
the line after the irregularity's fade-in; a run that never gets there (or tangent track) has its
means over the whole run after the fade-in, and the table says which.
"""
from __future__ import annotations

import html
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from axlebox.bearing import resultfile
from axlebox.mbs.vehicle import config as vconfig

from .readers import TRACK_FADE_IN_S


@dataclass(frozen=True)
class WheelRow:
    name: str
    Y: float            # N, mean in the circular part, towards the rail's field side
    Q: float            # N, mean in the circular part
    YQ_max: float       # the largest 2 m sliding mean of Y/Q over the run (after the fade-in)
    margin: float       # 1 - YQ_max / Nadal's limit


@dataclass(frozen=True)
class WheelsetRow:
    name: str
    sum_Y: float        # N, mean in the circular part (track y)
    sum_Y_max: float    # N, the largest |2 m sliding mean| over the run (after the fade-in)
    y: float            # m, lateral displacement on the track, mean in the circular part
    psi: float          # rad, angle of attack (yaw against the track), mean in the circular part


@dataclass(frozen=True)
class BearingRow:
    name: str
    axial: tuple        # N, (first row, last row), on the outer ring along track y
    radial: tuple       # N
    zone: tuple         # rad, the load zone's centre from the top towards the front


@dataclass(frozen=True)
class Curving:
    wheels: list
    wheelsets: list
    bearings: list
    nadal: float        # Nadal's limit of Y/Q at the wheel's flange angle and mu
    prudhomme: float    # N, Prud'homme's limit of sum Y at the static wheel load
    where: str          # what the means are over, in words

    @property
    def nadal_margin(self) -> float:
        """The smallest of the wheels' margins to Nadal's limit."""
        return min(w.margin for w in self.wheels)


@dataclass(frozen=True)
class Record:
    """What the table and the plot read of a car's result file, read once (:func:`read`)."""
    cfg: object          # the run's CarConfig
    t: np.ndarray
    wheels: list         # wheel names, sorted
    x: dict              # wheel -> its contacts' chainage on the line, m
    YQ: dict             # wheel -> (Y, Q, Y/Q, Y/Q 2 m mean)
    nadal: float
    sets: list           # wheelset names, sorted
    sum_Y: dict          # wheelset -> (sum Y, its 2 m mean)
    prudhomme: float
    attitude: dict       # wheelset -> (lateral displacement, angle of attack)
    rows: dict           # bearing -> (its row loads, its wheelset's name)


def read(path) -> Record | None:
    """The curving outputs of a car's result file (None for a rig's, or one without the
    wheel-rail safety outputs)."""
    with resultfile.reading(path) as f:
        if "wheelrail" not in f or "time" not in f:
            return None
        wr = f["wheelrail"]
        wheels = sorted(n for n in wr if "YQ" in wr[n])
        if not wheels:
            return None
        cfg = vconfig.loads(str(f.attrs.get("config", "")), f"{Path(path).name}'s config")
        sets = sorted(n for n in wr if "sum_Y" in wr[n])
        br = f.get("bearings") or {}
        return Record(
            cfg, f["time"][()], wheels,
            {n: wr[f"{n}/contact_point"][:, 0] + cfg.track.start for n in wheels},
            {n: wr[f"{n}/YQ"][()] for n in wheels}, float(wr[f"{wheels[0]}/YQ"].attrs["nadal_limit"]),
            sets, {k: wr[f"{k}/sum_Y"][()] for k in sets},
            float(wr[f"{sets[0]}/sum_Y"].attrs["prudhomme_limit_N"]) if sets else float("nan"),
            {k: wr[f"{k}/attitude"][()] for k in sets if "attitude" in wr[k]},
            {n: (br[f"{n}/row_loads"][()], str(br[f"{n}/row_loads"].attrs.get("wheelset", "")))
             for n in br if "row_loads" in br[n]})


def _record(src) -> Record | None:
    """``src`` read (a result file's path), or as it is (a :class:`Record`, or None: what
    :func:`read` gives for a file without curving outputs)."""
    return src if src is None or isinstance(src, Record) else read(src)


def _in_curve(line, chainage) -> np.ndarray:
    """Which of the chainages lie inside a circular segment of the line."""
    inside = np.zeros(np.shape(chainage), bool)
    for sg, s0, s1 in zip(line.segments, line.starts[:-1], line.starts[1:]):
        if sg.kind == "curve":
            inside |= (chainage >= s0) & (chainage <= s1)
    return inside


def table(src) -> Curving | None:
    """The curving table of a car's result file or its :class:`Record` (None for a rig's, or one
    without the wheel-rail safety outputs)."""
    r = _record(src)
    if r is None:
        return None
    t, wheels = r.t, r.wheels
    after = t >= min(TRACK_FADE_IN_S, t[-1])
    line = r.cfg.line()
    curve = {n: (_in_curve(line, r.x[n]) if line is not None else np.zeros(t.shape, bool)) & after
             for n in wheels}
    any_curve = any(c.any() for c in curve.values())

    def steady(names):
        """The outputs at which all of ``names``' contacts are in the circular part."""
        if not any_curve or not names:
            return after
        k = np.logical_and.reduce([curve[n] for n in names])
        return k if k.any() else after

    def of(ws):
        return [n for n in wheels if n.startswith(f"{ws}_")]
    out_w = []
    for n in wheels:
        k = steady([n])
        yq_max = float(np.max(r.YQ[n][after, 3]))
        out_w.append(WheelRow(n, float(r.YQ[n][k, 0].mean()), float(r.YQ[n][k, 1].mean()), yq_max,
                              1.0 - yq_max / r.nadal))
    out_s = []
    for s in r.sets:
        k = steady(of(s))
        a = r.attitude.get(s)
        out_s.append(WheelsetRow(s, float(r.sum_Y[s][k, 0].mean()),
                                 float(np.max(np.abs(r.sum_Y[s][after, 1]))),
                                 float(a[k, 0].mean()) if a is not None else float("nan"),
                                 float(a[k, 1].mean()) if a is not None else float("nan")))
    out_b = []
    for n, (rows, ws) in r.rows.items():
        m = rows[steady(of(ws))].mean(0)
        out_b.append(BearingRow(n, (m[0], m[1]), (m[2], m[3]), (m[4], m[5])))
    where = ("in the circular part of the curve, after the irregularity's fade-in" if any_curve
             else "over the whole run after the irregularity's fade-in (no circular curve reached)")
    return Curving(out_w, out_s, out_b, r.nadal, r.prudhomme, where)


def summary(c: Curving) -> str:
    """One line for the command's log: the wheel nearest to flange climb and the wheelset
    nearest to shifting the track, against their limits."""
    w = max(c.wheels, key=lambda r: r.YQ_max)
    s = max(c.wheelsets, key=lambda r: r.sum_Y_max)
    return (f"curving: largest Y/Q {w.YQ_max:.2f} ({w.name}; Nadal's limit {c.nadal:.2f}, "
            f"{100 * w.margin:.0f} % below), largest sum Y {s.sum_Y_max / 1e3:.1f} kN ({s.name}; "
            f"Prud'homme's limit {c.prudhomme / 1e3:.1f} kN); {s.name} "
            f"{1e3 * s.y:+.1f} mm, angle of attack {1e3 * s.psi:+.2f} mrad {c.where}")


def _cells(values) -> str:
    return "<tr>" + "".join(f"<td class=num>{v}</td>" if i else f"<td>{v}</td>"
                            for i, v in enumerate(values)) + "</tr>"


def table_html(c: Curving, label: str = "") -> str:
    """The curving table as HTML: wheels, wheelsets and bearings, with the limits and the
    margin to Nadal's."""
    esc = html.escape
    head = lambda cols: "<tr>" + "".join(f"<th>{esc(h)}</th>" for h in cols) + "</tr>"  # noqa: E731
    parts = [f"<p>{esc(label)}Means {esc(c.where)}. Y/Q and sum Y also as the largest 2 m sliding "
             f"mean over the run (EN 14363). Nadal's limit {c.nadal:.2f}: the wheels stay "
             f"{100 * c.nadal_margin:.0f} % below it at the closest; Prud'homme's limit "
             f"{c.prudhomme / 1e3:.1f} kN.</p>", "<table>",
             head(["wheel", "Y kN", "Q kN", "largest Y/Q (2 m)", "margin to Nadal"])]
    parts += [_cells([esc(w.name), f"{w.Y / 1e3:.2f}", f"{w.Q / 1e3:.2f}", f"{w.YQ_max:.3f}",
                      f"{100 * w.margin:.0f} %"]) for w in c.wheels]
    parts += ["</table>", "<table>", head(["wheelset", "sum Y kN", "largest |sum Y| (2 m) kN",
                                            "of Prud'homme's", "lateral displacement mm",
                                            "angle of attack mrad"])]
    parts += [_cells([esc(s.name), f"{s.sum_Y / 1e3:.2f}", f"{s.sum_Y_max / 1e3:.2f}",
                      f"{100 * s.sum_Y_max / c.prudhomme:.0f} %", f"{s.y * 1e3:.2f}",
                      f"{s.psi * 1e3:.2f}"]) for s in c.wheelsets]
    parts.append("</table>")
    if c.bearings:
        parts += ["<table>", head(["bearing", "axial row 1 kN", "axial last row kN",
                                   "radial row 1 kN", "radial last row kN",
                                   "load zone centre row 1 deg", "last row deg"])]
        parts += [_cells([esc(b.name), *(f"{v / 1e3:.2f}" for v in (*b.axial, *b.radial)),
                          *(f"{np.degrees(v):.1f}" for v in b.zone)]) for b in c.bearings]
        parts.append("</table>")
    return "\n".join(parts)


def figure(src, out: Path) -> Path | None:
    """The plot along the line of a car's result (file or :class:`Record`) on one: the line's
    curvature and cant, each wheel's Y/Q (2 m mean) with Nadal's limit, each wheelset's sum Y
    (2 m mean) with Prud'homme's, angles of attack, and the bearings' row axial loads, against
    the chainage of the front wheelset (None off a line)."""
    from matplotlib.figure import Figure
    r = _record(src)
    line = r.cfg.line() if r is not None else None
    if line is None:
        return None
    x = r.x[r.wheels[0]]
    fig = Figure(figsize=(10, 11), layout="constrained")
    ax = fig.subplots(5 if r.rows else 4, 1, sharex=True)
    s = np.linspace(max(0.0, x.min()), min(line.length, x.max()), 800)
    g = line.at(s)
    ax[0].plot(s, 1e3 * g.kappa, label="curvature 1/km")
    ax[0].plot(s, 1e3 * g.e, label="cant mm (right rail over left)")
    ax[0].set_ylabel("line")
    for n in r.wheels:
        ax[1].plot(x, r.YQ[n][:, 3], lw=0.8, label=n)
    ax[1].axhline(r.nadal, color="k", ls="--", label=f"Nadal {r.nadal:.2f}")
    ax[1].set_ylabel("Y/Q (2 m mean)")
    for n in r.sets:
        ax[2].plot(x, r.sum_Y[n][:, 1] / 1e3, lw=0.8, label=n)
    if r.sets:
        for sg in (1, -1):
            ax[2].axhline(sg * r.prudhomme / 1e3, color="k", ls="--")
    ax[2].set_ylabel("sum Y kN (2 m mean)")
    for n, a in r.attitude.items():
        ax[3].plot(x, 1e3 * a[:, 1], lw=0.8, label=n)
    ax[3].set_ylabel("angle of attack mrad")
    if r.rows:
        for n, (rows, _) in r.rows.items():
            ax[4].plot(x, rows[:, 0] / 1e3, lw=0.6, label=f"{n} row 1")
            ax[4].plot(x, rows[:, 1] / 1e3, lw=0.6, ls=":", label=f"{n} last row")
        ax[4].set_ylabel("bearing axial kN")
    ax[-1].set_xlabel(f"chainage of {r.wheels[0].rsplit('_', 1)[0]}'s contacts, m")
    for a in ax:
        a.grid(alpha=0.3)
        a.legend(fontsize=6, ncol=4, loc="best")
    out = Path(out)
    fig.savefig(out, dpi=110)
    return out
