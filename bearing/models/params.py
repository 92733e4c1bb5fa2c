"""Parameters of the roller bearings: the fields every model shares (:class:`RollerBearing`, which
the shared parts read) and the double-row tapered roller axle-box bearing's (DTRB,
:class:`BearingParams`).

The bearing table (Table 1) of the paper, W. Zhao, J. Ding, X. Liao, W. Liu, "Investigation on
coaxial pseudo-fault characteristics induced by the outer ring defect in the single-sided axle-box
bearing of wheelset in urban rail vehicles", Scientific Reports (2025),
doi:10.1038/s41598-025-93857-x, was not available to us; the defaults are Z = 20 rollers a row
(derived from the paper's cage and BPFO frequencies at 48 km/h, 2.196 Hz and 43.93 Hz:
BPFO / cage = 20.0) and an assumed 130 x 230 x 160 mm tapered-roller unit (typical values
consistent with Z = 20, no published data sheet).  All values are SI; angles in radians (the
defaults are written ``radians(deg)``).
"""
from __future__ import annotations

from dataclasses import dataclass
from math import cos, pi, radians, sin

from axlebox._params import ParameterError, check_ranges, choice, param, require

from ..kernel.layout import DAMPING_LAWS

SCHEMES = ("dynamic", "quasi-dynamic")           # the schemes a model runs by, its ``model`` field
CAGE_MODES = ("dynamic", "kinematic")
# s: the quasi-dynamic scheme's largest step whatever its method and model: held by accuracy
# (the defect's passage), not stability (bearing/kernel/quasidynamic.py)
QD_DT_MAX = 1e-4
QD_METHODS = ("leapfrog", "imex", "imex2")       # its step is the same whatever the method


def quasi_dynamic_steps() -> dict:
    """A model's ``DT_MAX["quasi-dynamic"]``: :data:`QD_DT_MAX` by each method's name."""
    return dict.fromkeys(QD_METHODS, QD_DT_MAX)


#: what each model's parameters give (a field or a property of its own): the shared parts read
#: them (the quasi-static model, the fault orders, the defects, the nominal state, the catalogue);
#: :class:`RollerBearing` declares each as a property that refuses, naming the model's class,
#: until the model gives it (tests/test_bearing_models.py reads the readers)
GIVEN_BY_MODEL = ("rows", "alpha_o", "alpha_i", "alpha_m", "clearance_n", "L_e", "D_o", "D_i")


@dataclass(frozen=True)
class RollerBearing:
    """The fields every roller-bearing model shares (its rollers, pitch, cage and pockets,
    masses, materials, friction, damping, scheme); each model's class gives them its own
    defaults and adds its own (:class:`BearingParams`, bearing/models/dcrb.py).  What the shared
    parts read beyond these fields and each model gives its own way (:data:`GIVEN_BY_MODEL`: the
    contact angles, the clearance, the contact length, the raceway diameters) is declared here
    too, as properties that refuse until a model's class replaces them."""

    Z: int = param(20, 3, 80, unit="", doc="rollers a row")
    D_m: float = param(0.180, 0.02, 1.0, doc="pitch diameter")
    D_b: float = param(0.0234, 0.002, 0.2, doc="mean roller diameter")
    L_b: float = param(0.040, 0.002, 0.3, doc="roller length")
    row_offset: float = param(0.040, 0.0, 0.5, doc="axial distance of each row from the bearing centre")
    M_r: float = param(0.135, 1e-4, 10.0, unit="kg", doc="roller mass")
    M_c: float = param(0.30, 1e-3, 20.0, unit="kg", doc="cage mass, each row")
    E_r: float = param(2.08e11, 1e9, 1e12, unit="Pa", doc="Young's modulus of rollers and rings")
    nu_r: float = param(0.3, 0.0, 0.5, unit="", doc="Poisson's ratio of rollers and rings")
    E_c: float = param(8.0e9, 1e8, 1e12, unit="Pa", doc="Young's modulus of the cage (glass-filled PA66)")
    nu_c: float = param(0.35, 0.0, 0.5, unit="", doc="Poisson's ratio of the cage")
    mu_race: float = param(0.005, 0.0, 0.5, unit="", doc="roller-raceway friction, lubricated")
    # rib (roller end) contact, Eqs. (3c), (4b), (8)
    h_r: float = param(0.006, 0.0, 0.1, doc="rib contact height above the roller axis (Fig. 3d)")
    R_e: float = param(0.50, 0.01, 10.0, doc="sphere radius of the roller's end face at the rib")
    mu_rib: float = param(0.03, 0.0, 0.5, unit="", doc="roller end - rib sliding friction")
    # cage (roller-guided, Eqs. 9-11, 13)
    alpha_c: float = param(radians(5.0), 0.0, radians(45.0), unit="rad", doc="pocket pressing slope angle")
    s_p: float = param(0.30e-3, 0.0, 5e-3, doc="circumferential pocket clearance, both sides together")
    s_pa: float = param(0.50e-3, 0.0, 10e-3, doc="axial pocket clearance (side beams), both ends together")
    mu_cage: float = param(0.05, 0.0, 0.5, unit="", doc="roller-cage sliding friction")
    # friction regularisation and contact damping
    v_s: float = param(0.01, 1e-5, 1.0, unit="m/s", doc="slip speed over which friction builds up "
                       "to mu Q (regularised Coulomb)")
    damping: str = choice("ratio", DAMPING_LAWS, "contact damping law: 'ratio' (zeta), 'paper' "
                          "(c_rule x K) or 'stiffness' (beta x the tangent stiffness)")
    zeta: float = param(0.10, 0.0, 5.0, unit="", doc="contact damping ratio (damping='ratio'); "
                        "assumed, an underdamped lubricated contact (see benchmarks/README.md)")
    c_rule: float = param(1e-3, 0.0, 1.0, unit="s", doc="the paper's C = c_rule x K (damping='paper')")
    beta: float = param(2.5e-5, 0.0, 1.0, unit="s", doc="C = beta x k, k the contact's tangent "
                        "stiffness (damping='stiffness'); the paper cites 2.5e-5 to 0.25 s of the "
                        "stiffness for bearing contacts (below its Eq. 4, its ref. 6)")
    cage: str = choice("dynamic", CAGE_MODES, "cage rotation: a dynamic state, or kinematic (the "
                       "paper's Eq. 2)")
    model: str = choice("dynamic", SCHEMES, "'dynamic': the paper's model, every roller and cage "
                        "with its six DOF; 'quasi-dynamic': the rollers' contact equilibrium solved "
                        "each step, spins and cage rotation as states (bearing/kernel/quasidynamic.py; for "
                        "studies, not for the defect's mechanism)")

    def __post_init__(self):
        if isinstance(self.Z, bool) or not isinstance(self.Z, int):
            raise ParameterError(f"{type(self).__name__}.Z = {self.Z!r} is not allowed: "
                                 "expected an integer >= 3")
        check_ranges(self)
        require(self.D_b < 0.5 * self.D_m, self, "D_b", f"must be below half the pitch diameter "
                f"D_m = {self.D_m:g} m")
        # the rollers must fit around the pitch circle
        require(self.Z * self.D_b < pi * self.D_m, self, "Z",
                f"{self.Z} rollers of {self.D_b * 1e3:g} mm do not fit on a "
                f"{self.D_m * 1e3:g} mm pitch circle")
        require(self.h_r < self.r_b, self, "h_r", f"must be below the roller radius {self.r_b:g} m")

    @property
    def gamma(self) -> float:
        """D_b / D_m."""
        return self.D_b / self.D_m

    @property
    def r_b(self) -> float:
        return 0.5 * self.D_b

    @property
    def J_r(self) -> tuple[float, float]:
        """Roller moments of inertia (axial, diametral) as a solid cylinder (kg m^2)."""
        r, L = self.r_b, self.L_b
        return 0.5 * self.M_r * r * r, self.M_r * (3 * r * r + L * L) / 12

    @property
    def J_c(self) -> tuple[float, float]:
        """Cage moments of inertia (polar, diametral) as a thin ring on the pitch circle (kg m^2)."""
        R, L = 0.5 * self.D_m, self.L_b
        return self.M_c * R * R, self.M_c * (0.5 * R * R + L * L / 12)

    # --- what each model gives (:data:`GIVEN_BY_MODEL`): its own field or property replaces each
    def _not_given(self, name: str, what: str):
        raise NotImplementedError(f"{type(self).__name__} does not give {name} ({what}): a bearing "
                                  "model's parameters declare it, as a field or a property "
                                  "(bearing/models/params.py, RollerBearing)")

    @property
    def rows(self) -> int:
        """The rows of rollers (an integer >= 1): the kernels' arrays are sized by it and its
        rows placed about the centre by it (bearing/kernel/layout.py ``row_y``: two rows at
        ``-+ row_offset``, one at the centre)."""
        return self._not_given("rows", "the rows of rollers, an integer >= 1")

    @property
    def alpha_o(self) -> float:
        """The outer raceway's contact angle (rad): its contact normal from the radial plane
        (0 for radial contacts); the fault orders' and the quasi-static model's angle."""
        return self._not_given("alpha_o", "the outer raceway's contact angle, rad")

    @property
    def alpha_i(self) -> float:
        """The inner raceway's contact angle (rad), as :attr:`alpha_o`."""
        return self._not_given("alpha_i", "the inner raceway's contact angle, rad")

    @property
    def alpha_m(self) -> float:
        """The roller axis's angle from the bearing axis (rad; 0 for a cylindrical roller)."""
        return self._not_given("alpha_m", "the roller axis's angle from the bearing axis, rad")

    @property
    def clearance_n(self) -> float:
        """The clearance of one roller along the outer raceway's contact normal, rings
        concentric (m)."""
        return self._not_given("clearance_n", "one roller's clearance along the outer contact "
                               "normal, m")

    @property
    def L_e(self) -> float:
        """The raceway contact line's effective length (m): the contact stiffness's and the
        defects' (a defect lies on it)."""
        return self._not_given("L_e", "the raceway contact line's effective length, m")

    @property
    def D_o(self) -> float:
        """The outer raceway's diameter at the contact (m): an outer-ring defect's angle."""
        return self._not_given("D_o", "the outer raceway's diameter at the contact, m")

    @property
    def D_i(self) -> float:
        """The inner raceway's diameter at the contact (m): an inner-ring defect's angle."""
        return self._not_given("D_i", "the inner raceway's diameter at the contact, m")


@dataclass(frozen=True)
class BearingParams(RollerBearing):
    """The DTRB: the paper's double-row tapered roller bearing (module docstring)."""

    rows = 2                                   # back to back (bearing/models/dtrb.py)

    alpha_o: float = param(radians(10.0), 0.0, radians(45.0), unit="rad", doc="cup (outer) contact angle")
    alpha_i: float = param(radians(7.5), 0.0, radians(45.0), unit="rad", doc="cone (inner) contact angle")
    u_r: float = param(0.05e-3, 0.0, 1e-3, doc="radial (diametral) clearance, mounted")
    u_a: float = param(0.30e-3, 0.0, 3e-3, doc="axial clearance, mounted")
    # the rib (cone back face) contact, Eqs. (3c), (4b), (8); assumed values for a 180 mm TDO unit
    alpha_f: float = param(radians(8.75), 0.0, radians(30.0), unit="rad",
                           doc="rib contact normal from the bearing axis (square to the roller axis)")

    @property
    def L_e(self) -> float:
        """Effective contact length, Eq. (6): L_b / cos((alpha_o - alpha_i) / 2)."""
        return self.L_b / cos(0.5 * (self.alpha_o - self.alpha_i))

    @property
    def alpha_m(self) -> float:
        """Angle of the roller axis from the bearing axis: the mean of cup and cone angles."""
        return 0.5 * (self.alpha_o + self.alpha_i)

    @property
    def D_o(self) -> float:
        """Outer raceway diameter at the contact (Eq. 14's D_o)."""
        return self.D_m + self.D_b * cos(self.alpha_o)

    @property
    def D_i(self) -> float:
        """Inner raceway (cone) diameter at the contact, Eq. (14)'s D_o for the inner ring."""
        return self.D_m - self.D_b * cos(self.alpha_i)

    @property
    def clearance_n(self) -> float:
        """Clearance along the cup contact normal, one row, rings concentric (m).

        For a rigid tapered unit the radial and axial clearances are one gap read in two
        directions (``u_a = u_r cot(alpha)``); the larger reading is kept, so each stated
        clearance is at least reached: ``max(u_r cos(alpha_o), u_a sin(alpha_o)) / 2``.
        """
        return 0.5 * max(self.u_r * cos(self.alpha_o), self.u_a * sin(self.alpha_o))
