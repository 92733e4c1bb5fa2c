"""Name the modes of a wheelset: torsion and bending orders of the axle.

Definitions (stated so they can be checked): the axle centre line is sampled
at 41 stations between the journals as the mean displacement of the material
within 50 mm of the axis.  A mode is *axle bending* when the centre line's
peak transverse deflection is at least 30 % of the body's peak displacement;
its *order* is the number of nodes (sign changes of the dominant transverse
component, ignoring stations below 5 % of its peak) less one.  A mode is
*torsion* when the two wheel rims turn about the axle in opposite senses
and the centre line barely moves.
"""
from __future__ import annotations

import numpy as np


def axle_profile(points: np.ndarray, shape: np.ndarray, y_max: float = 1.0, n: int = 41):
    r = np.hypot(points[:, 0], points[:, 2])
    near = r < 0.05
    ys = np.linspace(-y_max, y_max, n)
    prof = np.full((n, 3), np.nan)
    for i, y in enumerate(ys):
        sel = near & (np.abs(points[:, 1] - y) < 0.03)
        if sel.any():
            prof[i] = shape[sel].mean(axis=0)
    return ys, prof[~np.isnan(prof[:, 0])]


def classify(points: np.ndarray, shapes: np.ndarray, r_wheel: float = 0.42) -> list[str]:
    """A label per mode: ``bending-<order>``, ``torsion`` or ``other``."""
    r = np.hypot(points[:, 0], points[:, 2])
    rim = (r > 0.85 * r_wheel) & (r < 0.98 * r_wheel)
    left, right = rim & (points[:, 1] > 0), rim & (points[:, 1] < 0)
    labels = []
    for u in shapes:
        peak = np.abs(u).max()
        _, prof = axle_profile(points, u)
        trans = prof[:, [0, 2]]
        d = int(np.argmax(np.abs(trans).max(axis=0)))
        v = trans[:, d]
        if np.abs(v).max() >= 0.3 * peak:
            v = v[np.abs(v) > 0.05 * np.abs(v).max()]
            nodes = int(np.sum(np.diff(np.sign(v)) != 0))
            labels.append(f"bending-{nodes - 1}" if nodes >= 2 else "other")
            continue
        sl, sr = (np.mean(np.cross(points[m], u[m])[:, 1] / r[m] ** 2) for m in (left, right))
        if sl * sr < 0 and min(abs(sl), abs(sr)) * r_wheel > 0.3 * peak:
            labels.append("torsion")
        else:
            labels.append("other")
    return labels


def first_of(labels: list[str], frequencies_hz: np.ndarray, label: str) -> float | None:
    """Frequency of the lowest mode carrying ``label``."""
    for lab, f in zip(labels, frequencies_hz):
        if lab == label:
            return float(f)
    return None
