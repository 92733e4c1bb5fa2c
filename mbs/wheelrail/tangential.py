"""Tangential wheel-rail contact: FASTSIM, Shen-Hedrick-Elkins, and creepages from kinematics.

Sign convention (as :mod:`axlebox.mbs.wheelrail.kalker`): creepages are the velocity of the wheel's
material point minus the rail's at the contact over the reference speed V, in the contact
frame t1 (rolling direction), t2 (lateral, in the tangent plane), n = t1 x t2 (normal, into
the wheel); spin ``phi = (omega_wheel - omega_rail).n / V`` in 1/m.  Forces ``Fx, Fy`` act on
the wheel along t1, t2 and ``Mz`` about n; they oppose the creepage.

* :func:`fastsim` - Kalker's FASTSIM (the numba kernel in :mod:`.fastsim_kernel`), inputs
  checked here and the flexibilities from Kalker's coefficients (:func:`flexibilities`).
  ``update="cutback"`` is Kalker's 1982 slip step (trial traction scaled back onto the bound),
  first order in the element length; ``update="rotate"`` (default) turns the traction
  direction by the exact solution of the slip-direction equation over each step, second
  order, so that a 16 x 16 grid stays within about 1 % of the converged result where the
  cut-back needs about 40 elements per strip (``benchmarks/fastsim.py``).  Both converge to the
  same continuous simplified theory and are identical while nothing slips.
  ``flex="separate"`` (default) divides each rigid-slip term by its own flexibility, so the
  linear limit is Kalker's linear law for any mix of xi, eta, phi (e.g. the eta + phi of a
  tread contact); ``flex="weighted"`` is Kalker's 1982 single flexibility
  ``L = (|xi| L1 + |eta| L2 + c |phi| L3) / sqrt(xi^2 + eta^2 + c^2 phi^2)``, exact for one
  creepage at a time only (L2 and L3 differ by some 35 % on a circle), but with the saturated
  force exactly opposite the rigid slip, where "separate" leans by the ratio L1/L2 (about
  3 deg at xi = eta on a circle).
  :func:`fastsim_numpy` is the same algorithm vectorised over the strips in numpy (kept for
  the benchmark and as an independent check of the kernel).
* :func:`shen_hedrick_elkins` - Kalker's linear law saturated by Shen, Hedrick & Elkins (1983).
* :func:`creepages` - from the relative velocity and angular velocity at a contact;
  :func:`wheelset_creepages` - the classical linearised wheelset formulas.
"""
from __future__ import annotations

import math
from typing import NamedTuple

import numpy as np

from axlebox._params import ParameterError

from . import fastsim_kernel as _k
from .kalker import creep_coefficients, linear_creep_forces

__all__ = ["NX", "NY", "UPDATE", "BOUNDS", "UPDATES", "FLEXES", "flexibilities", "fastsim",
           "fastsim_traction", "fastsim_numpy", "shen_hedrick_elkins", "Creepage", "creepages",
           "wheelset_creepages", "Traction"]

NX = 16            # elements per strip; with NY strips the discretisation error is about
NY = 16            # 0.3 % of mu N at tread creepages (benchmarks/fastsim.py)
UPDATE = "rotate"
BOUNDS = {"parabolic": 0, "elliptic": 1}
UPDATES = {"cutback": 0, "rotate": 1}
FLEXES = ("separate", "weighted")


class Traction(NamedTuple):
    """FASTSIM's traction field on the (ny, nx) element centres, and the totals."""

    x: np.ndarray        # rolling direction, leading edge at +a_y, m
    y: np.ndarray        # lateral, m
    px: np.ndarray       # tangential traction on the wheel, Pa
    py: np.ndarray
    pn: np.ndarray       # normal pressure, Pa
    slip: np.ndarray     # True where the element slips
    Fx: float
    Fy: float
    Mz: float


class Creepage(NamedTuple):
    xi: np.ndarray       # longitudinal, -
    eta: np.ndarray      # lateral, -
    phi: np.ndarray      # spin, 1/m


def _refuse(field: str, value, allowed: str):
    raise ParameterError(f"tangential.{field} = {value!r} is not allowed: {allowed}")


def _checked(field: str, value, lo: float, lo_open: bool, hi: float = np.inf,
             allowed: str = ""):
    if isinstance(value, (float, int)) and not isinstance(value, bool):
        # plain numbers (np.float64 included) skip numpy: the wrapper's per-call cost
        v = float(value)
        if not (math.isfinite(v) and (v > lo if lo_open else v >= lo) and v <= hi):
            _refuse(field, value, allowed)
        return v
    arr = np.asarray(value, dtype=float)
    bad = ~np.isfinite(arr) | (arr > hi) | ((arr <= lo) if lo_open else (arr < lo))
    if np.any(bad):
        _refuse(field, value, allowed)
    return arr


def _contact(a, b, N, mu, G, nu):
    """Validated contact data as float arrays (messages name field, value and range)."""
    return (_checked("a", a, 0.0, True, allowed="expected a semi-axis > 0 m"),
            _checked("b", b, 0.0, True, allowed="expected a semi-axis > 0 m"),
            _checked("N", N, 0.0, False, allowed="expected a normal load >= 0 N (a negative "
                                                 "load means wheel and rail have separated)"),
            _checked("mu", mu, 0.0, True, allowed="expected a friction coefficient > 0"),
            _checked("G", G, 0.0, True, allowed="expected a shear modulus > 0 Pa"),
            _checked("nu", nu, 0.0, False, 0.5, allowed="expected a Poisson ratio in [0, 0.5]"))


def _creep(xi, eta, phi):
    return tuple(_checked(f, v, -np.inf, False, allowed="expected a finite creepage")
                 for f, v in (("xi", xi), ("eta", eta), ("phi", phi)))


def _grid(bound: str, update: str, nx, ny, flex: str = "separate"):
    if flex not in FLEXES:
        _refuse("flex", flex, f"expected one of {', '.join(map(repr, FLEXES))}")
    if bound not in BOUNDS:
        _refuse("bound", bound, f"expected one of {', '.join(map(repr, BOUNDS))}")
    if update not in UPDATES:
        _refuse("update", update, f"expected one of {', '.join(map(repr, UPDATES))}")
    for field, v in (("nx", nx), ("ny", ny)):
        if isinstance(v, bool) or not isinstance(v, (int, np.integer)) or v < 1:
            _refuse(field, v, "expected an integer >= 1")
    return BOUNDS[bound], UPDATES[update]


def flexibilities(a, b, G, nu, xi=None, eta=None, phi=None):
    """FASTSIM flexibilities ``(L1, L2, L3)`` (m/Pa), Kalker 1982 (:mod:`.fastsim_kernel`)::

        L1 = 8a / (3 C11 G),  L2 = 8a / (3 C22 G),  L3 = pi a sqrt(a/b) / (4 C23 G)

    chosen so that FASTSIM in full adhesion gives Kalker's linear Fx(xi), Fy(eta), Fy(phi).
    Given the creepages, all three are replaced by Kalker's weighted single flexibility
    ``(|xi| L1 + |eta| L2 + c |phi| L3) / sqrt(xi^2 + eta^2 + c^2 phi^2)``, c = sqrt(a b).
    """
    scalar = all(isinstance(v, float) for v in (a, b, G))
    if not scalar:
        a, b, G = np.asarray(a, float), np.asarray(b, float), np.asarray(G, float)
    C11, C22, C23, _ = creep_coefficients(a / b, nu)
    L1, L2, L3 = (8.0 * a / (3.0 * C11 * G), 8.0 * a / (3.0 * C22 * G),
                  math.pi * a * (a / b) ** 0.5 / (4.0 * C23 * G))
    if xi is None:
        return L1, L2, L3
    cphi = np.sqrt(a * b) * np.abs(phi)
    norm = np.sqrt(np.square(xi) + np.square(eta) + np.square(cphi))
    L = np.where(norm > 0.0, (np.abs(xi) * L1 + np.abs(eta) * L2 + cphi * L3)
                 / np.where(norm > 0.0, norm, 1.0), L1)
    return L, L, L


def fastsim(xi, eta, phi, a, b, N, mu, G, nu, bound="parabolic", nx=NX, ny=NY, update=UPDATE,
            flex="separate"):
    """Kalker's FASTSIM: ``(Fx, Fy, Mz)`` on the wheel for creepages xi, eta, spin phi (1/m).

    ``a`` (rolling direction), ``b`` semi-axes (m); ``N`` normal load (N); ``mu`` friction
    coefficient; ``G`` combined shear modulus (Pa); ``nu`` Poisson ratio; ``bound``
    ``"parabolic"`` (Kalker's) or ``"elliptic"`` (Hertz pressure); ``nx`` elements per strip,
    ``ny`` strips; ``update`` the slip step and ``flex`` the flexibilities (module
    docstring).  Scalars give floats; arrays (broadcast) give arrays, one contact each.
    """
    elliptic, rotate = _grid(bound, update, nx, ny, flex)
    xi, eta, phi = _creep(xi, eta, phi)
    a, b, N, mu, G, nu = _contact(a, b, N, mu, G, nu)
    L1, L2, L3 = flexibilities(a, b, G, nu, *((xi, eta, phi) if flex == "weighted" else ()))
    args = (xi, eta, phi, a, b, N, mu, L1, L2, L3)
    if all(isinstance(v, float) for v in args):
        return _k.fastsim_forces(*args, elliptic, rotate, nx, ny)
    args = np.broadcast_arrays(*args)
    if args[0].ndim == 0:
        return _k.fastsim_forces(*(float(v) for v in args), elliptic, rotate, nx, ny)
    shape = args[0].shape
    flat = [np.ascontiguousarray(v, dtype=float).ravel() for v in args]
    out = _k.fastsim_batch(*flat, elliptic, rotate, nx, ny, np.empty((flat[0].size, 3)))
    return tuple(out[:, i].reshape(shape) for i in range(3))


def fastsim_traction(xi, eta, phi, a, b, N, mu, G, nu, bound="parabolic", nx=NX, ny=NY,
                     update=UPDATE, flex="separate"):
    """FASTSIM's traction and stick/slip map (:class:`Traction`) of one contact (scalars)."""
    elliptic, rotate = _grid(bound, update, nx, ny, flex)
    xi, eta, phi = (float(v) for v in _creep(xi, eta, phi))
    a, b, N, mu, G, nu = (float(v) for v in _contact(a, b, N, mu, G, nu))
    L1, L2, L3 = (float(v) for v in flexibilities(
        a, b, G, nu, *((xi, eta, phi) if flex == "weighted" else ())))
    maps = _k.empty_traction(nx, ny)
    Fx, Fy, Mz = _k.fastsim_traction(xi, eta, phi, a, b, N, mu, L1, L2, L3, elliptic, rotate,
                                     nx, ny, maps)
    X, Y, PX, PY, PN, SLIP = maps
    return Traction(X, Y, PX, PY, PN, SLIP.astype(bool), Fx, Fy, Mz)


def fastsim_numpy(xi, eta, phi, a, b, N, mu, G, nu, bound="parabolic", nx=NX, ny=NY,
                  update=UPDATE, flex="separate"):
    """FASTSIM in plain numpy, vectorised over the strips (and over contacts: inputs are
    broadcast and a trailing strip axis is added).  Same algorithm, layout and results as the
    kernel; for benchmarking and cross-checking, not for the time loop."""
    elliptic, rotate = _grid(bound, update, nx, ny, flex)
    xi, eta, phi = _creep(xi, eta, phi)
    a, b, N, mu, G, nu = _contact(a, b, N, mu, G, nu)
    L1, L2, L3 = flexibilities(a, b, G, nu, *((xi, eta, phi) if flex == "weighted" else ()))
    xi, eta, phi, a, b, N, mu, L1, L2, L3 = (v[..., None] for v in np.broadcast_arrays(
        xi, eta, phi, a, b, N, mu, L1, L2, L3))

    def shape_of(u):
        return np.sqrt(np.maximum(1.0 - u * u, 0.0)) if elliptic else 1.0 - u * u

    du = 2.0 / nx
    dy = 2.0 * b / ny
    y = -b + (np.arange(ny) + 0.5) * dy                   # strip centres, (..., ny)
    w = np.sqrt(1.0 - (y / b) ** 2)
    wp = w if elliptic else w * w                         # pressure factor of each strip
    u_c = 1.0 - (np.arange(nx) + 0.5) * du                # x / a_y at the element centres
    P = N / (a * dy * (shape_of(u_c).sum() * du) * np.sum(w * wp, axis=-1, keepdims=True))
    ay = a * w
    dx = ay * du
    g_strip = mu * P * wp
    ex, ey, es = xi / L1, eta / L2, phi / L3
    wx = ex - es * y
    px = np.zeros(np.broadcast_shapes(y.shape, xi.shape))
    py = np.zeros_like(px)
    sx, sy, sm = np.zeros_like(px), np.zeros_like(px), np.zeros_like(px)
    for k in range(nx):
        x = ay * u_c[k]
        h = 0.5 * dx if k == 0 else dx
        wy = ey + es * (x + 0.5 * h)
        qx, qy = px - wx * h, py - wy * h
        g = g_strip * shape_of(u_c[k])
        t = np.sqrt(qx * qx + qy * qy)
        slip = t * t > g * g
        if rotate:
            pn = np.sqrt(px * px + py * py)
            first = pn == 0.0
            e0x = np.where(first, qx, px) / np.where(first, np.where(t > 0, t, 1.0), pn)
            e0y = np.where(first, qy, py) / np.where(first, np.where(t > 0, t, 1.0), pn)
            wn = np.sqrt(wx * wx + wy * wy)
            still = wn == 0.0
            dxw, dyw = -wx / np.where(still, 1.0, wn), -wy / np.where(still, 1.0, wn)
            c0 = e0x * dxw + e0y * dyw
            s0 = dxw * e0y - dyw * e0x
            gm = g_strip * shape_of(u_c[k] + 0.5 * h / ay)
            rate = np.divide(wn * h, gm, out=np.full(np.shape(gm * wn), np.inf), where=gm > 0)
            t1 = s0 / np.maximum(1.0 + c0, 1e-300) * np.exp(-rate)
            r = 1.0 / (1.0 + t1 * t1)
            c1, s1 = (1.0 - t1 * t1) * r, 2.0 * t1 * r
            ux = np.where(still, e0x, c1 * dxw - s1 * dyw)
            uy = np.where(still, e0y, s1 * dxw + c1 * dyw)
            px, py = np.where(slip, g * ux, qx), np.where(slip, g * uy, qy)
        else:
            f = np.where(slip, g / np.where(t > 0.0, t, 1.0), 1.0)
            px, py = qx * f, qy * f
        sx, sy, sm = sx + px, sy + py, sm + (x * py - y * px)
    dA = dx * dy
    return tuple(np.sum(s * dA, axis=-1)[()] for s in (sx, sy, sm))


def shen_hedrick_elkins(xi, eta, phi, a, b, N, mu, G, nu):
    """Kalker's linear forces saturated after Shen, Hedrick & Elkins (1983), vectorised.

    Z.Y. Shen, J.K. Hedrick, J.A. Elkins, "A comparison of alternative creep force models for
    rail vehicle dynamic analysis", Proc. 8th IAVSD Symposium, 1983::

        F_R = sqrt(Fx^2 + Fy^2),  beta = F_R / (mu N)
        F'  = mu N (beta - beta^2/3 + beta^3/27)   for beta < 3,   mu N otherwise

    and Fx, Fy are scaled by ``eps = F'/F_R``.  The spin moment is scaled by the same eps
    (linear for small creepage, and bounded once the forces saturate; the 1983 paper scales
    only the forces).  With ``F_R = 0`` (e.g. eta and phi cancelling) eps = 1.
    """
    xi, eta, phi = _creep(xi, eta, phi)
    a, b, N, mu, G, nu = _contact(a, b, N, mu, G, nu)
    Fx, Fy, Mz = linear_creep_forces(xi, eta, phi, a, b, G, nu)
    FR = np.hypot(Fx, Fy)
    muN = mu * N
    beta = np.divide(FR, muN, out=np.full(np.shape(FR), np.inf), where=muN > 0.0)
    bc = np.minimum(beta, 3.0)
    sat = bc - bc ** 2 / 3.0 + bc ** 3 / 27.0                # = 1 at beta = 3, flat beyond
    # eps = F'/F_R = sat / beta, which tends to 1 as beta -> 0
    eps = np.where(beta > 1e-12, sat / np.where(beta > 1e-12, beta, 1.0), 1.0 - beta / 3.0)
    eps = np.where(muN > 0.0, eps, 0.0)
    return tuple(np.asarray(v)[()] for v in (Fx * eps, Fy * eps, Mz * eps))


def creepages(dv, omega, t1, t2, n, V) -> Creepage:
    """Creepages at a contact: ``xi = dv.t1/V``, ``eta = dv.t2/V``, ``phi = omega.n/V``.

    ``dv``: velocity of the wheel's material point at the contact minus the rail's (m/s);
    ``omega``: angular velocity of the wheel minus the rail's (rad/s); ``t1, t2, n``: the
    contact frame (unit vectors: rolling direction, lateral in the tangent plane, normal
    into the wheel); ``V``: the reference (rolling) speed, m/s.  Vectors are (..., 3) arrays.
    """
    V = np.asarray(V, dtype=float)
    if not np.all(np.isfinite(V)) or np.any(V <= 0.0):
        _refuse("V", V, "expected a reference speed > 0 m/s (creepages need rolling)")
    dv, omega, t1, t2, n = (np.asarray(v, dtype=float) for v in (dv, omega, t1, t2, n))
    return Creepage(*(np.asarray(np.sum(p * q, axis=-1) / V)[()]
                      for p, q in ((dv, t1), (dv, t2), (omega, n))))


def wheelset_creepages(y_dot, psi, psi_dot, V, r_L, r_R, r0, delta_L, delta_R, l):
    """Classical linearised creepages of a wheelset on straight track: ``(left, right)``.

    Axes x forward, y to the left, z up; wheelset yaw psi (about z), lateral velocity y_dot,
    spinning at ``V / r0``; contact points at lateral distance l from the centre on rolling
    radii r_L, r_R with contact angles delta_L, delta_R (the normal leans towards the track
    centre).  The contact frame of each wheel is t1 = x, t2 = n x t1, n the rail normal.
    First order in the small motions (cf. Garg & Dukkipati, *Dynamics of Railway Vehicle
    Systems*, 1984; Wickens, *Fundamentals of Rail Vehicle Dynamics*, 2003)::

        xi_L,R  = (1 - r_L,R / r0) -+ l psi_dot / V
        eta_L,R = (y_dot / V - psi) cos(delta_L,R)
        phi_L,R = -+ sin(delta_L,R) / r0 + psi_dot cos(delta_L,R) / V

    (the cos(delta) factors are ~1 on the tread and are often dropped).
    """
    V = np.asarray(V, dtype=float)
    if not np.all(np.isfinite(V)) or np.any(V <= 0.0):
        _refuse("V", V, "expected a forward speed > 0 m/s")
    r0 = _checked("r0", r0, 0.0, True, allowed="expected a nominal rolling radius > 0 m")
    lat = y_dot / V - psi
    cL, cR = np.cos(delta_L), np.cos(delta_R)
    left = Creepage(1.0 - r_L / r0 - l * psi_dot / V, lat * cL,
                    -np.sin(delta_L) / r0 + psi_dot * cL / V)
    right = Creepage(1.0 - r_R / r0 + l * psi_dot / V, lat * cR,
                     np.sin(delta_R) / r0 + psi_dot * cR / V)
    return left, right
