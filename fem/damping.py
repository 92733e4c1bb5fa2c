"""Damping of the reduced body in its orthonormal modal coordinates."""
from __future__ import annotations

import numpy as np

from axlebox._params import ParameterError


def modal(frequencies_hz: np.ndarray, zeta: float | np.ndarray = 0.01) -> np.ndarray:
    """``D = diag(2 zeta_k omega_k)`` for mass-normalised modes (zeta: scalar or per mode)."""
    zeta = np.broadcast_to(np.asarray(zeta, float), np.shape(frequencies_hz))
    if np.any(zeta < 0) or np.any(zeta >= 1):
        raise ParameterError(f"zeta = {zeta.tolist()!r} is not allowed: expected 0 <= zeta < 1")
    return np.diag(2 * zeta * 2 * np.pi * np.asarray(frequencies_hz))


def rayleigh(M: np.ndarray, K: np.ndarray, alpha: float, beta: float) -> np.ndarray:
    """``D = alpha M + beta K`` (zeta_k = alpha / (2 omega_k) + beta omega_k / 2)."""
    if alpha < 0 or beta < 0:
        raise ParameterError(f"rayleigh (alpha, beta) = ({alpha!r}, {beta!r}) is not allowed: "
                             "expected both >= 0")
    return alpha * M + beta * K


def rayleigh_from_two(f1_hz: float, f2_hz: float, zeta: float) -> tuple[float, float]:
    """``alpha, beta`` giving damping ratio ``zeta`` at both ``f1`` and ``f2``."""
    w1, w2 = 2 * np.pi * f1_hz, 2 * np.pi * f2_hz
    return 2 * zeta * w1 * w2 / (w1 + w2), 2 * zeta / (w1 + w2)
