"""The wheel-rail force element: its parameters, its tables, and a numpy reference of the kernel.

:func:`build_tables` turns a wheel/rail profile pair on a :class:`~axlebox.mbs.wheelrail.geometry.
TrackLayout` into the two plain arrays the numba kernel
:func:`axlebox.mbs.wheelrail.element_kernel.wheel_rail_force` reads (method and frames in that module's
docstring):

1. :func:`~axlebox.mbs.wheelrail.geometry.contact_table` of the rigid wheelset (``n_geom`` lateral
   displacements y in ``[-y_max, y_max]``): roll0, z0, contact points, contact angles, rolling
   radii, curvatures, per side; and its :func:`~axlebox.mbs.wheelrail.geometry.contact_regions`:
   each wheel cut into up to NPT regions (tread, flange root, flange) at the single-point
   contact's jumps of more than ``split_angle``, with each region's own closest point and its
   gap in the rigid wheelset's touching pose (the kernel's multi-point contact).  Each wheel's
   rows continue ``y_field`` beyond the table's end on its own field side
   (:func:`~axlebox.mbs.wheelrail.geometry.field_extension`: the wheel touching alone, the roll
   held), where a gauge opening under a wheelset held against a curve's outer rail takes the
   inner wheel; the table's flange-side end stays the wheelset's (``P_UFL``: past it the kernel
   reports the wheel off its table).
2. Per side, the wheel's own look-up offset ``u(y) = y + s l0 (cos roll0 - 1) + k r0 sin roll0``
   (``k`` 0 for ``index="centre"``, 1 for ``"tread"``; monotone, checked) and every column
   resampled linearly onto one uniform grid of ``n_grid`` points in u covering both sides.
3. Optionally (``smooth_y > 0``) each region's contact geometry (point, angle, radius,
   curvatures; not the touching pose nor the gaps) is smoothed over u by a Gaussian of
   standard deviation ``smooth_y`` (the equivalent-contact idea of Arnold & Netter 1998, Math.
   Comput. Model. Dyn. Syst. 4(2) 162-184, as SIMPACK's "equivalent elastic" contact does it).
   Why: a single-point Hertz element sees a step where the contact point jumps across the tread
   (S1002 on 60E1 1:40 at u = 0.09 mm: 7 mm of contact position, B from 0.77 to 3.35 /m, the
   static penetration at 60 kN from 67 to 86 um within one 0.03 mm grid step), and a wheelset
   crossing it is struck like a rail joint: bursts of 100 m/s^2 at the P1 resonance on a healthy
   car.  A real patch there is 10-20 mm wide and spans both candidate regions; the load moves
   from one to the other while their gap difference stays under the penetration (about 80 um),
   i.e. over 2-4 mm of u for contact angles 0.02-0.04 rad apart, which a Gaussian of 1 mm
   spreads it over.  Away from the jumps the columns change by ``smooth_y^2 f''/2``: 2 um of
   rolling radius on the tread (``tests/test_wheelrail_element.py``).  The touching pose and
   the gaps stay exact: smoothed across the flange's jumps (where the wheelset's height rises
   with a slope 10 times the tread's) they would leave the pose 0.1-0.5 mm off touching; and a
   jump that is a region border needs no smoothing, both regions carry load across it.
4. At each grid point: Hertz (:mod:`axlebox.mbs.wheelrail.hertz`) with the relative curvatures
   ``A = kappa_wheel_x / 2`` (straight rail) and ``B = (kappa_wheel_y + kappa_rail_y) / 2``
   floored at ``B_min`` (a conformal contact is not Hertzian; S1002/60E1 stays above 0.27/m),
   ``K_H`` of ``N = K_H pen^1.5`` and, from the semi-axes at N = 1 N (``a ~ N^(1/3)``),
   ``a_hat = a_1 K_H^(1/3)`` so that ``a = a_hat sqrt(pen)`` (likewise b); Kalker's
   C11, C22, C23, C33 at ``a_hat / b_hat`` (:func:`axlebox.mbs.wheelrail.kalker.creep_coefficients`).
5. With the same profiles on both sides, each column is made exactly mirror-symmetric
   (``L(u) = +-R(-u)``, the average of the two computed sides), so that mirrored states give
   mirrored forces to rounding.

Tables depend on the profiles, the layout and the geometry/elastic fields of
:class:`WheelRailParams`; they are cached in memory and in ``$AXLEBOX_CACHE/wheelrail`` (or
``~/.cache/axlebox/wheelrail``) by a hash of all of those (as :mod:`axlebox.geometry.mesh` caches meshes).
``par`` (friction, law, damping...) is rebuilt from the parameters on every call: cheap.
"""
from __future__ import annotations

import dataclasses
import hashlib
import math
import os
import tempfile

import numpy as np
from scipy.ndimage import gaussian_filter1d

from axlebox._cache import cache_dir
from axlebox._params import ParameterError, check_ranges, choice, digest, param, require

from . import element_kernel as ek
from . import fastsim_kernel as fk
from .geometry import TrackLayout, contact_regions, contact_table, field_extension, region_splits
from .hertz import contact_stiffness, effective_modulus, hertz
from .kalker import creep_coefficients
from .profile import Profile

__all__ = ["WheelRailParams", "WheelRailTables", "build_tables", "make_par",
           "wheel_force_reference", "LAWS", "INDEXES", "TABLE_VERSION"]

TABLE_VERSION = 2
LAWS = {"fastsim": ek.LAW_FASTSIM, "kalker": ek.LAW_KALKER, "she": ek.LAW_SHE}
INDEXES = {"centre": 0, "tread": 1}
BOUNDS = {"parabolic": 0, "elliptic": 1}
UPDATES = {"cutback": 0, "rotate": 1}
# fields that shape the tables (the rest only enter par)
_TABLE_FIELDS = ("E", "nu", "index", "y_max", "n_geom", "n_grid", "step", "B_min", "smooth_y",
                 "split_angle", "y_field")
_BLOCKS = ek.NPC * np.arange(ek.NPT)
# the columns taken from the geometry (the rest follow from them by Hertz and Kalker), and of
# those the ones smoothed: each region's contact geometry, not the touching pose nor the gaps
# (step 3)
_GEOMETRY = np.concatenate([np.arange(ek.COL_PY)]
                           + [o + np.r_[ek.COL_PY:ek.COL_B + 1, ek.COL_GAP] for o in _BLOCKS])
_SMOOTHED = np.concatenate([o + np.arange(ek.COL_PY, ek.COL_B + 1) for o in _BLOCKS])
# mirror sign of each column: lateral quantities change sign, the others do not
_MIRROR = np.ones(ek.NCOL)
_MIRROR[[ek.COL_ROLL0, ek.COL_C0Y, *(ek.COL_PY + _BLOCKS)]] = -1.0
_MEMO: dict = {}
# the kernel's slot constants (COL_*, P_*, OUT_*, LAW_*, NCOL, N_PAR, N_OUT), re-exported here
globals().update({k: v for k, v in vars(ek).items()
                  if k.startswith(("COL_", "P_", "OUT_", "LAW_")) or k in ("NCOL", "N_PAR", "N_OUT")})


@dataclasses.dataclass(frozen=True)
class WheelRailParams:
    """Material, friction, creep law and table resolution of the wheel-rail element (SI)."""

    E: float = param(2.1e11, 1e9, 1e12, unit="Pa", doc="Young's modulus, wheel and rail steel")
    nu: float = param(0.28, 0.0, 0.5, unit="", doc="Poisson ratio (Kalker's nu = 0.25 ... 0.3)")
    G: float = param(8.2e10, 1e9, 1e12, unit="Pa", doc="shear modulus, E/(2(1 + nu))")
    mu: float = param(0.3, 0.0, 1.0, unit="", doc="friction coefficient (dry rail)")
    chi: float = param(0.3, 0.0, 10.0, unit="s/m",
                       doc="Hunt-Crossley damping; Lankarani & Nikravesh 1990 "
                           "chi = 3 (1 - e^2) / (4 v0): e = 0.9 at v0 = 0.5 m/s")
    v_min: float = param(0.5, 1e-3, 10.0, unit="m/s", doc="floor of V in the creepages")
    law: str = choice("fastsim", LAWS, doc="creep force law: 'fastsim' (Kalker's FASTSIM), "
                      "'kalker' (linear) or 'she' (Shen-Hedrick-Elkins)")
    nx: int = param(8, 2, 400, unit="", doc="FASTSIM elements per strip")
    ny: int = param(8, 2, 400, unit="", doc="FASTSIM strips")
    bound: str = "parabolic"        # FASTSIM traction bound: 'parabolic' (Kalker) | 'elliptic'
    update: str = choice("cutback", UPDATES, doc="FASTSIM slip step: 'cutback' (Kalker's, "
                          "continuous in the creepages, as an implicit Newton needs) or 'rotate' "
                          "(second order in the grid, jumps at stick-slip changes; tangential.py)")
    index: str = "tread"            # look-up offset: 'tread' | 'centre' (element_kernel.py)
    y_max: float = param(0.012, 0.002, 0.03, doc="half range of the geometry table")
    n_geom: int = param(601, 21, 10001, unit="", doc="points of the geometry table")
    n_grid: int = param(1201, 11, 100001, unit="",
                        doc="points of the uniform look-up grid over the rigid wheelset's range "
                            "(its step continues over the field sides' reach)")
    step: float = param(2e-5, 1e-6, 1e-4, doc="grid of the minimum-gap search")
    B_min: float = param(0.1, 1e-3, 10.0, unit="1/m", doc="floor of the relative curvature B")
    y_field: float = param(0.012, 0.0, 0.03, doc="reach of each wheel's table beyond y_max on its "
                                             "field side (the wheel touching alone)")
    smooth_y: float = param(1.0e-3, 0.0, 0.005, doc="Gaussian smoothing of each contact region's "
                                                 "geometry over u (0: exact tables)")
    split_angle: float = param(0.1, 0.01, 1.0, unit="rad",
                               doc="contact-angle jump of the single-point contact that makes a "
                                   "border between two contact regions of the wheel")

    def __post_init__(self):
        check_ranges(self)
        for field in ("nx", "ny", "n_geom", "n_grid"):
            v = getattr(self, field)
            require(isinstance(v, (int, np.integer)) and not isinstance(v, bool), self, field,
                    "expected an integer")
        for field, allowed in (("law", LAWS), ("bound", BOUNDS), ("update", UPDATES),
                               ("index", INDEXES)):
            require(getattr(self, field) in allowed, self, field,
                    f"expected one of {', '.join(map(repr, allowed))}")


@dataclasses.dataclass(eq=False)
class WheelRailTables:
    """What the kernel reads: ``tab`` (n_grid, 2 NCOL) and ``par`` (N_PAR,), plus the grid."""

    tab: np.ndarray
    par: np.ndarray
    u: np.ndarray                    # the uniform look-up grid, m
    params: WheelRailParams
    layout: TrackLayout
    names: tuple
    key: str

    def column(self, col: int, side: int, region: int = 0) -> np.ndarray:
        """Column ``col`` (``COL_*``) of side 0 (left) or 1 (right) on the grid ``u``; for a
        region's column (``COL_PY`` on) that of ``region`` (0 tread ... NPT - 1 flange)."""
        if region and col < ek.COL_PY:
            raise ParameterError(f"region = {region!r} is not allowed for column {col}: the "
                                 f"touching pose (columns 0-{ek.COL_PY - 1}) is the wheel's")
        return self.tab[:, side * ek.NCOL + col + region * ek.NPC]

    def with_params(self, params: WheelRailParams) -> "WheelRailTables":
        """The same tables with another ``par`` (friction, law, damping, FASTSIM grid)."""
        for f in _TABLE_FIELDS:
            if getattr(params, f) != getattr(self.params, f):
                raise ParameterError(f"WheelRailParams.{f} = {getattr(params, f)!r} changes the "
                                     f"tables (built with {getattr(self.params, f)!r}): "
                                     f"call build_tables")
        return dataclasses.replace(self, par=make_par(params, self.par), params=params)


def make_par(params: WheelRailParams, grid_par: np.ndarray) -> np.ndarray:
    """``par`` from ``params`` and the grid slots (P_U0 ... P_INDEX) of an existing ``par``."""
    par = np.zeros(ek.N_PAR)
    par[:ek.P_MU] = grid_par[:ek.P_MU]
    par[ek.P_MU], par[ek.P_G], par[ek.P_NU] = params.mu, params.G, params.nu
    par[ek.P_LAW] = LAWS[params.law]
    par[ek.P_NX], par[ek.P_NY] = params.nx, params.ny
    par[ek.P_ELLIPTIC], par[ek.P_ROTATE] = BOUNDS[params.bound], UPDATES[params.update]
    par[ek.P_CHI], par[ek.P_VMIN] = params.chi, params.v_min
    return par


def _profile_key(p: Profile) -> str:
    h = hashlib.sha256(np.ascontiguousarray(p.y).tobytes())
    h.update(np.ascontiguousarray(p.z).tobytes())
    h.update(f"{p.kind}|{p.flange_back!r}".encode())
    return h.hexdigest()[:16]


def build_tables(wheel: Profile, rail: Profile, layout: TrackLayout | None = None,
                 params: WheelRailParams | None = None, *, wheel_right: Profile | None = None,
                 rail_right: Profile | None = None, cache: bool = True) -> WheelRailTables:
    """Tables of the element for ``wheel`` on ``rail`` (left side; the right side uses the same
    pair unless ``wheel_right`` / ``rail_right`` are given).  Steps in the module docstring."""
    layout = layout or TrackLayout()
    params = params or WheelRailParams()
    if not isinstance(layout, TrackLayout):
        raise ParameterError(f"layout = {layout!r} is not allowed: expected a TrackLayout")
    if not isinstance(params, WheelRailParams):
        raise ParameterError(f"params = {params!r} is not allowed: expected WheelRailParams")
    profiles = (wheel, rail, wheel_right or wheel, rail_right or rail)
    for name, p in zip(("wheel", "rail", "wheel_right", "rail_right"), profiles):
        kind = name.split("_")[0]
        if not isinstance(p, Profile) or p.kind != kind:
            what = f"a {p.kind} profile" if isinstance(p, Profile) else type(p).__name__
            raise ParameterError(f"{name} = {getattr(p, 'name', p)!r} is not allowed: expected "
                                 f"a {kind} Profile, got {what}")
    if profiles[2].flange_back != wheel.flange_back:
        raise ParameterError(f"wheel_right.flange_back = {profiles[2].flange_back!r} is not "
                             f"allowed: expected the left wheel's {wheel.flange_back!r}")
    key = digest("wheelrail-tables", TABLE_VERSION, [_profile_key(p) for p in profiles],
                 wheel_right is None and rail_right is None, layout,
                 {f: getattr(params, f) for f in _TABLE_FIELDS})
    if key not in _MEMO:
        path = cache_dir("wheelrail") / f"tables-{key}.npz"
        if cache and path.exists():
            with np.load(path) as z:
                _MEMO[key] = (z["tab"], z["grid_par"], z["u"])
        else:
            _MEMO[key] = _compute(wheel, rail, layout, params, wheel_right, rail_right)
            if cache:
                path.parent.mkdir(parents=True, exist_ok=True)
                fd, tmp = tempfile.mkstemp(suffix=".npz", dir=path.parent)
                os.close(fd)
                tab, grid_par, u = _MEMO[key]
                np.savez(tmp, tab=tab, grid_par=grid_par, u=u)
                os.replace(tmp, path)          # complete files only
    tab, grid_par, u = _MEMO[key]
    # copies: a caller that edits its tables must not edit the cache
    return WheelRailTables(tab=tab.copy(), par=make_par(params, grid_par), u=u.copy(), params=params,
                           layout=layout, names=(wheel.name, rail.name), key=key)


def _compute(wheel, rail, layout, params, wheel_right, rail_right):
    ct = contact_table(wheel, rail, layout, y_max=params.y_max, n=params.n_geom,
                       wheel_right=wheel_right, rail_right=rail_right, step=params.step)
    splits = region_splits(ct, params.split_angle)
    prof = dict(wheel_right=wheel_right, rail_right=rail_right, step=params.step)
    rails = (rail, rail_right or rail)
    r0 = layout.r0
    l0 = 0.5 * layout.back_to_back - wheel.flange_back
    k_index = INDEXES[params.index]
    raw, u_side, u_flange = [], [], []
    for k, s in enumerate((1.0, -1.0)):
        # this wheel's rows: the rigid wheelset's, then its own beyond them on its field side
        tk = field_extension(wheel, rail, ct, k, params.y_field, **prof) if params.y_field else ct
        reg = contact_regions(wheel, rail, tk, splits=splits, side=k, **prof)
        y, roll, z0 = tk.y, tk.roll, tk.z
        raw.append(np.zeros((len(y), ek.NCOL)))
        rail_k = rails[k].canted(layout.cant)
        c0y = y + s * l0 * (np.cos(roll) - 1.0)
        u = c0y + k_index * r0 * np.sin(roll)
        if np.any(np.diff(u) <= 0.0):
            raise ParameterError(f"WheelRailParams.index = {params.index!r} is not allowed for "
                                 f"{wheel.name} on {rail.name}: the look-up offset of side "
                                 f"{'LR'[k]} is not monotone in y (try 'centre')")
        u_side.append(u)
        u_flange.append(s * u[-1 if k == 0 else 0])
        raw[k][:, ek.COL_ROLL0] = roll
        raw[k][:, ek.COL_Z0] = z0
        raw[k][:, ek.COL_C0Y] = c0y
        raw[k][:, ek.COL_C0Z] = r0 + z0 + s * l0 * np.sin(roll)
        for p in range(ek.NPT):
            o = p * ek.NPC
            raw[k][:, o + ek.COL_PY] = reg.y_track[:, k, p]
            raw[k][:, o + ek.COL_PZ] = rail_k.height(reg.y_rail[:, k, p])
            raw[k][:, o + ek.COL_DELTA] = reg.delta[:, k, p]
            raw[k][:, o + ek.COL_R] = reg.r[:, k, p]
            raw[k][:, o + ek.COL_A] = 0.5 * reg.kappa_wheel_x[:, k, p]
            raw[k][:, o + ek.COL_B] = 0.5 * (reg.kappa_wheel_y[:, k, p] + reg.kappa_rail_y[:, k, p])
            raw[k][:, o + ek.COL_GAP] = reg.gap[:, k, p]
    # the grid's step: n_grid points over the rigid wheelset's range, continued over the reach
    U_flange = min(u_flange)
    du = 2.0 * U_flange / (params.n_grid - 1)
    U = min(-u_side[0][0], u_side[1][-1])
    m = int(np.floor(U / du + 1e-9))
    grid = du * np.arange(-m, m + 1)
    tab = np.zeros((grid.size, 2 * ek.NCOL))
    for k in range(2):
        for j in _GEOMETRY:
            tab[:, k * ek.NCOL + j] = np.interp(grid, u_side[k], raw[k][:, j])
    if params.smooth_y > 0.0:
        cols = [k * ek.NCOL + j for k in range(2) for j in _SMOOTHED]
        tab[:, cols] = gaussian_filter1d(tab[:, cols], params.smooth_y / (grid[1] - grid[0]),
                                         axis=0, mode="nearest")
    if wheel_right is None and rail_right is None:
        left = tab[:, :ek.NCOL]
        right_mirrored = tab[::-1, ek.NCOL:] * _MIRROR
        left = 0.5 * (left + right_mirrored)
        tab = np.concatenate([left, left[::-1] * _MIRROR], axis=1)
    E_star = effective_modulus(params.E, params.nu)
    for k in range(2):
        for p in range(ek.NPT):
            o = k * ek.NCOL + p * ek.NPC
            col = {j: o + j for j in range(ek.COL_PY, ek.COL_GAP + 1)}
            tab[:, col[ek.COL_B]] = np.maximum(tab[:, col[ek.COL_B]], params.B_min)
            A, B = tab[:, col[ek.COL_A]], tab[:, col[ek.COL_B]]
            KH = contact_stiffness(A, B, E_star)
            unit = hertz(A, B, 1.0, E_star)                   # semi-axes at N = 1 N
            tab[:, col[ek.COL_KH]] = KH
            tab[:, col[ek.COL_AHAT]] = unit.a * np.cbrt(KH)
            tab[:, col[ek.COL_BHAT]] = unit.b * np.cbrt(KH)
            C = creep_coefficients(tab[:, col[ek.COL_AHAT]] / tab[:, col[ek.COL_BHAT]], params.nu)
            for j, c in enumerate((ek.COL_C11, ek.COL_C22, ek.COL_C23, ek.COL_C33)):
                tab[:, col[c]] = C[j]
    grid_par = np.zeros(ek.P_MU)
    grid_par[ek.P_U0], grid_par[ek.P_DU], grid_par[ek.P_NGRID] = grid[0], grid[1] - grid[0], len(grid)
    grid_par[ek.P_R0], grid_par[ek.P_L0], grid_par[ek.P_INDEX] = r0, l0, k_index
    grid_par[ek.P_UFL] = U_flange
    return np.ascontiguousarray(tab), grid_par, grid


# ----------------------------------------------------------------------------- numpy reference

def wheel_force_reference(side, c, e, v_c, omega, V, z_rail, y_rail, dz_rail, dy_rail,
                          tables: WheelRailTables) -> np.ndarray:
    """The element of :func:`axlebox.mbs.wheelrail.element_kernel.wheel_rail_force` in numpy (vectors,
    ``np.interp``, a rotation matrix, ``np.cross``, the contact point from the meridian plane's
    unit vector), returning its ``out`` array.  FASTSIM runs as the interpreted Python source of
    the kernel (``_fastsim.py_func``): it is checked against the independent numpy FASTSIM in
    ``tests/test_tangential.py``; here it is the element around it that is checked."""
    par, P = tables.par, ek
    s = 1.0 if side == 0 else -1.0
    c, e, v_c, omega = (np.asarray(v, dtype=float) for v in (c, e, v_c, omega))
    phi = math.atan2(e[2], math.hypot(e[0], e[1]))
    l0, r0 = par[P.P_L0], par[P.P_R0]
    u = c[1] - s * l0 - y_rail + par[P.P_INDEX] * r0 * math.sin(phi)
    grid = tables.u
    clamped = (P.CLAMP_FLANGE if s * u > par[P.P_UFL] else
               P.CLAMP_FIELD if not grid[0] <= u <= grid[-1] else 0.0)

    def at(j, region=0):
        return float(np.interp(u, grid, tables.column(j, side, region)))

    rail = np.array([0.0, y_rail, z_rail])
    c0 = rail + np.array([c[0], s * l0 + at(P.COL_C0Y), at(P.COL_C0Z)])
    dphi = phi - at(P.COL_ROLL0)
    R = np.array([[1.0, 0.0, 0.0], [0.0, math.cos(dphi), -math.sin(dphi)],
                  [0.0, math.sin(dphi), math.cos(dphi)]])
    Vr = max(V, par[P.P_VMIN])
    out = np.zeros(ek.N_OUT)
    F_sum, M_sum, rows = np.zeros(3), np.zeros(3), []
    for k in range(ek.NPT):
        col = {j: at(j, k) for j in range(ek.COL_PY, ek.COL_GAP + 1)}
        p = rail + np.array([c[0], col[P.COL_PY], col[P.COL_PZ]])
        d = col[P.COL_DELTA]
        n = np.array([0.0, -s * math.sin(d), math.cos(d)])
        t1 = np.array([1.0, 0.0, 0.0])
        t2 = np.cross(n, t1)
        dp = (c - c0) + (R - np.eye(3)) @ (p - c0)
        pen = -dp @ n - col[P.COL_GAP] * math.cos(d)
        m = -(n - (n @ e) * e)
        m /= np.linalg.norm(m)                      # from the axle to the point, in the meridian
        p[0] = c[0] + ((p - c) @ e) * e[0] + col[P.COL_R] * m[0]
        v_p = v_c + np.cross(omega, p - c)
        pen_dot = -(v_p - np.array([0.0, dy_rail, dz_rail])) @ n
        xi, eta, spin = v_p @ t1 / Vr, v_p @ t2 / Vr, omega @ n / Vr
        N = a = b = Fx = Fy = Mz = 0.0
        if pen > 0.0:
            N = max(col[P.COL_KH] * pen ** 1.5 * (1.0 + par[P.P_CHI] * pen_dot), 0.0)
            a, b = col[P.COL_AHAT] * math.sqrt(pen), col[P.COL_BHAT] * math.sqrt(pen)
            Fx, Fy, Mz = _law_reference(xi, eta, spin, a, b, N, par, col)
        F = N * n + Fx * t1 + Fy * t2
        F_sum += F
        M_sum += np.cross(p - c, F) + Mz * n
        out[P.OUT_NPT + k], out[P.OUT_DPT + k], out[P.OUT_YPT + k] = N, d, p[1]
        rows.append((N, pen, {P.OUT_N: N, P.OUT_PEN: pen, P.OUT_XI: xi, P.OUT_ETA: eta,
                              P.OUT_SPIN: spin, P.OUT_FX: Fx, P.OUT_FY: Fy, P.OUT_A: a,
                              P.OUT_B: b, P.OUT_DELTA: d, P.OUT_MZ: Mz, P.OUT_PENDOT: pen_dot,
                              P.OUT_R: col[P.COL_R]}, p))
    N, pen, best, p = max(rows, key=lambda row: (row[0], row[1]))   # the most loaded region
    out[P.OUT_F:P.OUT_F + 3], out[P.OUT_M:P.OUT_M + 3] = F_sum, M_sum
    out[P.OUT_P:P.OUT_P + 3] = p
    for slot, v in best.items():
        out[slot] = v
    out[P.OUT_CLAMP] = clamped
    return out


def _law_reference(xi, eta, spin, a, b, N, par, col):
    P = ek
    law, mu, G = int(par[P.P_LAW]), par[P.P_MU], par[P.P_G]
    C11, C22, C23, C33 = (col[j] for j in (P.COL_C11, P.COL_C22, P.COL_C23, P.COL_C33))
    if N <= 0.0:
        return 0.0, 0.0, 0.0
    if law == P.LAW_FASTSIM:
        L = (8 * a / (3 * C11 * G), 8 * a / (3 * C22 * G), math.pi * a * math.sqrt(a / b) / (4 * C23 * G))
        return fk._fastsim.py_func(xi, eta, spin, a, b, N, mu, *L, int(par[P.P_ELLIPTIC]),
                                   int(par[P.P_ROTATE]), int(par[P.P_NX]), int(par[P.P_NY]), None)
    # Kalker 1990 App. E linear law, c = sqrt(ab)
    cc = math.sqrt(a * b)
    lin = np.array([-G * cc ** 2 * C11 * xi, -G * cc ** 2 * C22 * eta - G * cc ** 3 * C23 * spin,
                    G * cc ** 3 * C23 * eta - G * cc ** 4 * C33 * spin])
    if law == P.LAW_SHE:
        beta = math.hypot(lin[0], lin[1]) / (mu * N) if mu > 0 else math.inf
        bc = min(beta, 3.0)
        eps = (bc - bc ** 2 / 3 + bc ** 3 / 27) / beta if beta > 1e-12 else 1.0 - beta / 3.0
        lin = lin * (eps if mu > 0 else 0.0)
    return tuple(float(v) for v in lin)
