"""FASTSIM (Kalker 1982) in numba: plain floats and arrays in, plain floats out.

J.J. Kalker, "A fast algorithm for the simplified theory of rolling contact", Vehicle System
Dynamics 11 (1982) 1-13.  The simplified theory ties the tangential surface displacement
difference u (wheel minus rail) to the traction p on the wheel by ``u = L p``; in steady
rolling the slip (wheel relative to rail, per unit rolling distance) is ``s = w - du/dx``
with the rigid slip ``w = (xi - phi y, eta + phi x)`` and the rail's material entering at the
leading edge ``x = +a_y`` of each strip with ``u = 0``.  Where it sticks (s = 0) the traction
grows along the strip as ``dp/dx = w / L``; where that would exceed the traction bound
``g = mu p_n`` the element slips and ``|p| = g``.

Slip step (``rotate``): 0 is Kalker's: the trial traction (previous traction plus the
adhesion increment) is cut back onto the bound along its own direction, which is the implicit
Euler step of the slip equations and first order in the element length.  1 keeps ``|p| = g``
but turns the direction e by the exact solution of ``de/dzeta = -(w - (w.e) e)/g`` (zeta the
marching distance, the slip-zone form of ``dp/dzeta = -w/L + slip``) with w and g frozen at
the middle of the step: second order, and as robust where g -> 0 at the trailing edge
(the direction then snaps to -w, as in Kalker's step).

Flexibilities (one per rigid-slip term, so that the linear limit is Kalker's linear law for
any mix of xi, eta, phi; for a single creepage this is Kalker's original weighted L)::

    L1 = 8 a / (3 C11 G),   L2 = 8 a / (3 C22 G),   L3 = pi a sqrt(a/b) / (4 C23 G)

Layout: ``ny`` strips of equal width ``dy = 2b/ny`` with centres ``y_j``, each strip split into
``nx`` equal elements on its own length ``2 a_y``, ``a_y = a sqrt(1 - y_j^2/b^2)``.  Traction is
evaluated at element centres and the rigid slip integrated exactly between them (first step
``dx/2`` from the leading edge), so in full adhesion every element holds the exact traction and
the midpoint sums over x are exact for the linear (xi, eta) traction profiles and second
order for the quadratic (phi) one: the linear-limit error of Fx(xi) and Fy(eta) is the
midpoint rule across the strips alone, ``+1/(2 ny^2)`` relative.  The pressure is scaled so
that its discrete sum is exactly N, so that full sliding gives exactly ``mu N``.

Traction bound ``elliptic`` (0 = parabolic): Kalker's FASTSIM takes ``p_n`` parabolic,
``p_n = 2N/(pi a b) (1 - x^2/a^2 - y^2/b^2)``; ``elliptic = 1`` uses the Hertz pressure
``p_n = 3N/(2 pi a b) sqrt(1 - x^2/a^2 - y^2/b^2)``.

Outputs: ``Fx, Fy`` the force on the wheel along the rolling and lateral directions and
``Mz = sum (x py - y px) dA`` the moment about the contact normal (sign convention of
:mod:`axlebox.mbs.wheelrail.kalker`).
"""
from __future__ import annotations

from collections import namedtuple
from math import exp, sqrt

import numpy as np
from numba import njit

#: the (ny, nx) maps of one contact patch (:func:`fastsim_traction`): element centres ``X``,
#: ``Y``, tangential traction ``PX``, ``PY``, normal pressure ``PN`` and the slip flag ``SLIP``
#: (1 = slip); a named tuple numba compiles, passed whole or as None (forces only)
Maps = namedtuple("Maps", ["X", "Y", "PX", "PY", "PN", "SLIP"])


@njit(cache=True, inline="always")
def _rotate(px, py, qx, qy, wx, wy, h, g, g_strip, u_mid, elliptic):
    """Slip step with the traction direction e turned by the exact solution of
    ``de/dzeta = -(w - (w.e) e) / g`` for w, g frozen at the step's midpoint (zeta the
    marching distance): the angle theta between e and -w obeys
    ``tan(theta/2) = tan(theta0/2) exp(-|w| h / g)``.  Returns ``g e`` at the new centre."""
    pn = sqrt(px * px + py * py)
    if pn > 0.0:
        e0x = px / pn
        e0y = py / pn
    else:                                 # slip from the first step on: start along the trial
        tn = sqrt(qx * qx + qy * qy)
        e0x = qx / tn
        e0y = qy / tn
    wn = sqrt(wx * wx + wy * wy)
    if wn == 0.0:                         # no rigid slip: the bound shrank, direction kept
        return g * e0x, g * e0y
    dx_ = -wx / wn
    dy_ = -wy / wn
    c0 = e0x * dx_ + e0y * dy_
    s0 = dx_ * e0y - dy_ * e0x
    shape_mid = sqrt(max(1.0 - u_mid * u_mid, 0.0)) if elliptic else 1.0 - u_mid * u_mid
    gm = g_strip * shape_mid
    # gm = 0 only without normal load: the direction then snaps to -w
    t1 = s0 / max(1.0 + c0, 1e-300) * exp(-wn * h / gm) if gm > 0.0 else 0.0
    r = 1.0 / (1.0 + t1 * t1)
    c1 = (1.0 - t1 * t1) * r
    s1 = 2.0 * t1 * r
    return g * (c1 * dx_ - s1 * dy_), g * (s1 * dx_ + c1 * dy_)


@njit(cache=True)
def _fastsim(xi, eta, phi, a, b, N, mu, L1, L2, L3, elliptic, rotate, nx, ny, maps):
    """The march over all strips; ``maps`` the patch's :class:`Maps` to fill, or None (forces
    only)."""
    dy = 2.0 * b / ny
    du = 2.0 / nx
    # pressure scale: the discrete sum of p_n dA is N exactly
    cx = 0.0                                  # sum over one strip of the shape in u = x/a_y
    for k in range(nx):
        u = 1.0 - (k + 0.5) * du
        cx += sqrt(1.0 - u * u) if elliptic else 1.0 - u * u
    cx *= du
    cy = 0.0
    for j in range(ny):
        v = -1.0 + (j + 0.5) * dy / b
        w2 = 1.0 - v * v
        cy += w2 if elliptic else w2 * sqrt(w2)
    P = N / (a * dy * cx * cy) if cy > 0.0 else 0.0
    ex = xi / L1
    ey = eta / L2
    es = phi / L3
    Fx = 0.0
    Fy = 0.0
    Mz = 0.0
    for j in range(ny):
        y = -b + (j + 0.5) * dy
        v = y / b
        w = sqrt(1.0 - v * v)
        ay = a * w
        dx = ay * du
        g_strip = mu * P * (w if elliptic else w * w)
        wx = ex - es * y                      # x rigid slip / flexibility, constant on a strip
        px = 0.0
        py = 0.0
        sx = 0.0
        sy = 0.0
        sm = 0.0
        for k in range(nx):
            u = 1.0 - (k + 0.5) * du
            x = ay * u
            h = 0.5 * dx if k == 0 else dx
            # adhesion step: dp = -w/L over [x, x + h], w_y linear in x: exact at the midpoint
            wy = ey + es * (x + 0.5 * h)
            qx = px - wx * h
            qy = py - wy * h
            shape = sqrt(1.0 - u * u) if elliptic else 1.0 - u * u
            g = g_strip * shape
            t2 = qx * qx + qy * qy
            slip = t2 > g * g
            if not slip:
                px = qx
                py = qy
            elif rotate == 0:
                # Kalker 1982: cut the trial traction back to the bound along its own direction
                f = g / sqrt(t2)
                px = qx * f
                py = qy * f
            else:
                px, py = _rotate(px, py, qx, qy, wx, wy, h, g, g_strip, u + 0.5 * h / ay,
                                 elliptic)
            sx += px
            sy += py
            sm += x * py - y * px
            if maps is not None:
                maps.X[j, k] = x
                maps.Y[j, k] = y
                maps.PX[j, k] = px
                maps.PY[j, k] = py
                maps.PN[j, k] = P * (w if elliptic else w * w) * shape
                maps.SLIP[j, k] = slip
        dA = dx * dy
        Fx += sx * dA
        Fy += sy * dA
        Mz += sm * dA
    return Fx, Fy, Mz


@njit(cache=True)
def fastsim_forces(xi, eta, phi, a, b, N, mu, L1, L2, L3, elliptic, rotate, nx, ny):
    """``(Fx, Fy, Mz)`` of one contact (module docstring); all arguments plain numbers."""
    return _fastsim(xi, eta, phi, a, b, N, mu, L1, L2, L3, elliptic, rotate, nx, ny, None)


@njit(cache=True)
def fastsim_traction(xi, eta, phi, a, b, N, mu, L1, L2, L3, elliptic, rotate, nx, ny, maps):
    """As :func:`fastsim_forces`, also filling the patch's :class:`Maps` ``maps``
    (:func:`empty_traction`)."""
    return _fastsim(xi, eta, phi, a, b, N, mu, L1, L2, L3, elliptic, rotate, nx, ny, maps)


@njit(cache=True)
def fastsim_batch(xi, eta, phi, a, b, N, mu, L1, L2, L3, elliptic, rotate, nx, ny, out):
    """Many contacts: 1-D arrays of equal length in, ``out[i] = (Fx, Fy, Mz)`` of contact i."""
    for i in range(xi.shape[0]):
        fx, fy, mz = _fastsim(xi[i], eta[i], phi[i], a[i], b[i], N[i], mu[i], L1[i], L2[i],
                              L3[i], elliptic, rotate, nx, ny, None)
        out[i, 0] = fx
        out[i, 1] = fy
        out[i, 2] = mz
    return out


def empty_traction(nx: int, ny: int) -> Maps:
    """The :class:`Maps` :func:`fastsim_traction` fills (X, Y, PX, PY, PN float64; SLIP uint8)."""
    return Maps(*(np.zeros((ny, nx)) for _ in range(5)), np.zeros((ny, nx), dtype=np.uint8))
