"""Parameters of the double-row tapered roller axle-box bearing (DTRB).

Table 1 of the paper is missing from its text; the defaults follow
../shared/REFERENCE_DATA.md: Z = 20 rollers a row (derived from the paper's
cage and BPFO frequencies) and an assumed 130 x 230 x 160 mm unit.  All values
are SI; angles in radians (the defaults are written ``radians(deg)``).
"""
from __future__ import annotations

from dataclasses import dataclass
from math import cos, pi, radians

from geometry._params import ParameterError, check_ranges, param, require


@dataclass(frozen=True)
class BearingParams:
    Z: int = param(20, 3, 80, unit="", doc="rollers a row")
    D_m: float = param(0.180, 0.02, 1.0, doc="pitch diameter")
    D_b: float = param(0.0234, 0.002, 0.2, doc="mean roller diameter")
    L_b: float = param(0.040, 0.002, 0.3, doc="roller length")
    alpha_o: float = param(radians(10.0), 0.0, radians(45.0), unit="rad", doc="cup (outer) contact angle")
    alpha_i: float = param(radians(7.5), 0.0, radians(45.0), unit="rad", doc="cone (inner) contact angle")
    row_offset: float = param(0.040, 0.0, 0.5, doc="axial distance of each row from the bearing centre")
    u_r: float = param(0.05e-3, 0.0, 1e-3, doc="radial (diametral) clearance, mounted")
    u_a: float = param(0.30e-3, 0.0, 3e-3, doc="axial clearance, mounted")
    M_r: float = param(0.135, 1e-4, 10.0, unit="kg", doc="roller mass")
    M_c: float = param(0.30, 1e-3, 20.0, unit="kg", doc="cage mass, each row")
    E_r: float = param(2.08e11, 1e9, 1e12, unit="Pa", doc="Young's modulus of rollers and rings")
    nu_r: float = param(0.3, 0.0, 0.5, unit="", doc="Poisson's ratio of rollers and rings")
    E_c: float = param(8.0e9, 1e8, 1e12, unit="Pa", doc="Young's modulus of the cage (glass-filled PA66)")
    nu_c: float = param(0.35, 0.0, 0.5, unit="", doc="Poisson's ratio of the cage")
    mu_race: float = param(0.005, 0.0, 0.5, unit="", doc="roller-raceway friction, lubricated")

    def __post_init__(self):
        if isinstance(self.Z, bool) or not isinstance(self.Z, int):
            raise ParameterError(f"BearingParams.Z = {self.Z!r} is not allowed: "
                                 "expected an integer >= 3")
        check_ranges(self)
        require(self.D_b < 0.5 * self.D_m, self, "D_b", f"must be below half the pitch diameter "
                f"D_m = {self.D_m:g} m")
        # the rollers must fit around the pitch circle
        require(self.Z * self.D_b < pi * self.D_m, self, "Z",
                f"{self.Z} rollers of {self.D_b * 1e3:g} mm do not fit on a "
                f"{self.D_m * 1e3:g} mm pitch circle")

    @property
    def gamma(self) -> float:
        """D_b / D_m."""
        return self.D_b / self.D_m

    @property
    def L_e(self) -> float:
        """Effective contact length, Eq. (6): L_b / cos((alpha_o - alpha_i) / 2)."""
        return self.L_b / cos(0.5 * (self.alpha_o - self.alpha_i))

    @property
    def r_b(self) -> float:
        return 0.5 * self.D_b
