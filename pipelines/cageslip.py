"""The cages' slip over a car run: ``s = 1 - omega_cage / (FTF omega_shaft)``, each bearing row's
cage speed against the speed it would turn at rolling without slip (the fundamental train
frequency's order FTF of the file's bearing, outer ring standing) at the wheelset's shaft speed,
averaged over windows of the run (Harris and Kotzalas, Rolling Bearing Analysis, 5th ed., vol. 2,
ch. 6: cage speed and skidding).  Under traction the rollers are driven harder through the load
zone and the cages lag (slip grows with the acceleration and the speed)."""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from axlebox.bearing import catalogue, resultfile

from .readers import _file_config


@dataclass(frozen=True)
class CageSlip:
    """``t`` (s, window centres), ``speed_kmh`` (the wheelset's rolling speed there) and
    ``slip[row]`` (1, one a window) of ``bearing``."""

    bearing: str
    t: np.ndarray
    speed_kmh: np.ndarray
    slip: np.ndarray        # (2, windows)


def cage_slip(path, window_s: float = 0.5) -> list[CageSlip]:
    """Each bearing's cage slip, by row, in windows of ``window_s`` (the file's bearings and
    shafts; empty for a run without them)."""
    out = []
    with resultfile.reading(path) as f:
        cfg = _file_config(f, path)
        if cfg is None or "bearings" not in f or "shafts" not in f or not hasattr(cfg, "wheelset"):
            return out
        ftf = catalogue.of(cfg.bearing, "the file's [bearing]").orders.FTF
        t = f["time"][()]
        fs = 1.0 / np.median(np.diff(t))
        n = max(1, int(round(window_s * fs)))
        for name in sorted(f["bearings"]):
            ws = f"ws{name[len('bearing'):-1]}"
            if f"shafts/{ws}/speed" not in f:
                continue
            w = f[f"shafts/{ws}/speed"][()]
            cage = np.abs(f[f"bearings/{name}/cage"][:, 2:4])
            k = w.size // n
            wm = w[:k * n].reshape(k, n).mean(axis=1)
            cm = cage[:k * n].reshape(k, n, 2).mean(axis=1)
            out.append(CageSlip(name, t[:k * n].reshape(k, n).mean(axis=1),
                                wm * cfg.wheelset.r0 * 3.6, (1.0 - cm / (ftf * wm[:, None])).T))
    return out


def table(slips: list[CageSlip]) -> str:
    """The slips as text: a row a bearing row, a column a window (%)."""
    if not slips:
        return ""
    s0 = slips[0]
    if s0.t.size == 0:          # a run shorter than one window: nothing to average
        return "cage slip: none to report (the run is shorter than one window)"
    head = "cage slip, % (1 - cage speed / its rolling speed), windows at " + ", ".join(
        f"{t:.2f} s ({v:.0f} km/h)" for t, v in zip(s0.t, s0.speed_kmh))
    rows = [f"  {s.bearing} row {r + 1}: " + " ".join(f"{100 * x:5.2f}" for x in s.slip[r])
            for s in slips for r in range(2)]
    return "\n".join([head, *rows])
