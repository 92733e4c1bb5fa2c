"""Kinematic fault frequencies of a rolling bearing with a stationary outer ring.

With ``g = (D_b / D_m) cos(alpha)`` and shaft frequency ``f_s`` (Harris and
Kotzalas, Rolling Bearing Analysis, 5th ed., vol. 1, sec. 8.2; the paper's
``omega_c = (1 - D_b/D_m) omega_w / 2`` below Eq. 2 is the same with alpha = 0):

* FTF  = f_s (1 - g) / 2                 cage
* BPFO = Z f_s (1 - g) / 2               a roller passing a point of the outer ring
* BPFI = Z f_s (1 + g) / 2               a roller passing a point of the inner ring
* BSF  = f_s D_m / (2 D_b) (1 - g^2)     roller spin
"""
from __future__ import annotations

from dataclasses import dataclass
from math import cos, pi

from axlebox._params import ParameterError

from .models.params import RollerBearing


@dataclass(frozen=True)
class FaultOrders:
    """Fault frequencies as multiples of the shaft frequency."""

    FTF: float
    BPFO: float
    BPFI: float
    BSF: float

    def at(self, shaft_hz: float) -> dict[str, float]:
        """The lines in Hz at shaft frequency ``shaft_hz``: the four orders and ``2BSF``, the
        rolling element's defect frequency (it strikes both races once per spin turn)."""
        out = {k: v * shaft_hz for k, v in vars(self).items()}
        out["2BSF"] = 2.0 * out["BSF"]
        return out


def orders(p: RollerBearing, alpha: float | None = None) -> FaultOrders:
    """Fault orders at contact angle ``alpha`` (default: the cup angle ``alpha_o``)."""
    a = p.alpha_o if alpha is None else alpha
    g = p.gamma * cos(a)
    return FaultOrders(FTF=0.5 * (1 - g), BPFO=0.5 * p.Z * (1 - g), BPFI=0.5 * p.Z * (1 + g),
                       BSF=0.5 / p.gamma * (1 - g * g))


def shaft_hz(speed_kmh: float, r_wheel: float = 0.42) -> float:
    """Wheelset rotation frequency (Hz) at vehicle speed ``speed_kmh`` on wheels of radius ``r_wheel``."""
    if not speed_kmh > 0:
        raise ParameterError(f"speed = {speed_kmh!r} km/h is not allowed: expected a speed > 0")
    if not r_wheel > 0:
        raise ParameterError(f"r_wheel = {r_wheel!r} m is not allowed: expected a radius > 0")
    return speed_kmh / 3.6 / (2 * pi * r_wheel)
