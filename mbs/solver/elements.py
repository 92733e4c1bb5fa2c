"""Force elements between markers: what the user builds a system from.

Each element names its markers by the integer handles :meth:`axlebox.mbs.solver.system.System.marker` returns,
checks its values (a bad one raises :class:`~axlebox._params.ParameterError` naming the element,
the field and what is allowed) and packs itself into one row of the element table that
:mod:`axlebox.mbs.kernel.elements` evaluates.

=============  ==========================================================================
``Bushing``    6-DOF linear spring-damper in marker 1's frame: translations and small
               rotations (primary and secondary springs, air springs, the anti-roll bar as
               a roll-only bushing, the axle-box joint with the spin left free); optional
               preload (force at zero deflection, e.g. the static spring load)
``Spring``     point-to-point spring-damper along the line between the markers, linear or
               with a piecewise-linear force-deflection table (dampers, traction rods)
``BumpStop``   clearance, then ``k over^e`` along one axis of marker 1 (lateral stops)
``Load``       force (and moment) on one marker, ``F0 + A sin(omega t + phase)`` in a
               time window (tests, load histories)
``Drive``      traction and braking along the system's speed profile: the force the
               profile's acceleration asks of a mass (feed-forward) plus a gain on a
               marker's speed against the profile's, as a torque about marker 1's axle
               (reaction on marker 2) or a force along x on marker 1
=============  ==========================================================================
"""
from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from axlebox._params import ParameterError

from ..kernel import elements as ke


def _vec(name, what, value, n, *, nonneg=False):
    a = np.asarray(value, float).ravel()
    if a.shape == (1,):
        a = np.full(n, a[0])
    if a.shape != (n,) or not np.all(np.isfinite(a)):
        raise ParameterError(f"{name}.{what} = {value!r} is not allowed: expected {n} finite numbers")
    if nonneg and np.any(a < 0):
        raise ParameterError(f"{name}.{what} = {value!r} is not allowed: expected values >= 0")
    return a


@dataclass
class Bushing:
    name: str
    m1: int
    m2: int
    k: tuple = (0, 0, 0, 0, 0, 0)          # N/m (x, y, z), N m/rad (rx, ry, rz)
    c: tuple = (0, 0, 0, 0, 0, 0)          # N s/m, N m s/rad
    preload: tuple = (0, 0, 0, 0, 0, 0)    # force/moment on marker 2 at zero deflection
    offset: tuple | None = None            # unloaded relative position of m2 in m1's frame;
    #                                        None: as placed (System.assemble fills it in)

    def pack(self):
        row = np.zeros(ke.EL_WIDTH)
        row[ke.B_D0:ke.B_D0 + 3] = _vec(self.name, "offset", self.offset or (0, 0, 0), 3)
        row[ke.B_K:ke.B_K + 6] = _vec(self.name, "k", self.k, 6, nonneg=True)
        row[ke.B_C:ke.B_C + 6] = _vec(self.name, "c", self.c, 6, nonneg=True)
        row[ke.B_F0:ke.B_F0 + 6] = _vec(self.name, "preload", self.preload, 6)
        return (ke.BUSHING, self.m1, self.m2, 0), row


@dataclass
class Spring:
    name: str
    m1: int
    m2: int
    k: float = 0.0                 # N/m (ignored when a table is given)
    c: float = 0.0                 # N s/m
    length: float | None = None    # free length L0, m; None: as placed
    preload: float = 0.0           # N, > 0 pushes the markers apart
    table: tuple = field(default_factory=tuple)   # ((deflection m, force N), ...) ascending

    def pack(self):
        row = np.zeros(ke.EL_WIDTH)
        for what in ("k", "c", "length"):
            v = getattr(self, what) or 0.0
            if not (np.isfinite(v) and v >= 0):
                raise ParameterError(f"{self.name}.{what} = {v!r} is not allowed: expected a number >= 0")
        row[ke.S_K], row[ke.S_C] = self.k, self.c
        row[ke.S_L0], row[ke.S_F0] = self.length or 0.0, self.preload
        if self.table:
            tab = np.asarray(self.table, float)
            nmax = (ke.EL_WIDTH - ke.S_TAB) // 2
            if tab.ndim != 2 or tab.shape[1] != 2 or not 2 <= len(tab) <= nmax \
                    or np.any(np.diff(tab[:, 0]) <= 0):
                raise ParameterError(f"{self.name}.table is not allowed: expected 2..{nmax} "
                                     "(deflection, force) pairs with deflections increasing")
            row[ke.S_NPT] = len(tab)
            row[ke.S_TAB:ke.S_TAB + 2 * len(tab)] = tab.ravel()
        return (ke.SPRING, self.m1, self.m2, 0), row


@dataclass
class BumpStop:
    name: str
    m1: int
    m2: int
    axis: int = 1                  # 0 x, 1 y, 2 z of marker 1's frame
    clearance: float = 0.03        # m
    k: float = 1e6                 # N/m^exponent
    exponent: float = 1.0
    c: float = 0.0

    def pack(self):
        if self.axis not in (0, 1, 2):
            raise ParameterError(f"{self.name}.axis = {self.axis!r} is not allowed: expected 0, 1 or 2")
        for what in ("clearance", "k", "c"):
            v = getattr(self, what)
            if not (np.isfinite(v) and v >= 0):
                raise ParameterError(f"{self.name}.{what} = {v!r} is not allowed: expected a number >= 0")
        if not 1.0 <= self.exponent <= 5.0:
            raise ParameterError(f"{self.name}.exponent = {self.exponent!r} is not allowed: "
                                 "expected a number in [1, 5]")
        row = np.zeros(ke.EL_WIDTH)
        row[ke.P_GAP], row[ke.P_K], row[ke.P_EXP], row[ke.P_C] = (self.clearance, self.k,
                                                                 self.exponent, self.c)
        return (ke.BUMPSTOP, self.m1, self.m2, self.axis), row


@dataclass
class Load:
    name: str
    m1: int
    force: tuple = (0, 0, 0)            # F0, N (inertial)
    amplitude: tuple = (0, 0, 0)        # A, N
    omega: float = 0.0                  # rad/s
    phase: float = 0.0                  # rad
    t_on: float = 0.0
    t_off: float = np.inf
    moment: tuple = (0, 0, 0)           # N m, constant while on

    def pack(self):
        row = np.zeros(ke.EL_WIDTH)
        row[ke.L_F0:ke.L_F0 + 3] = _vec(self.name, "force", self.force, 3)
        row[ke.L_A:ke.L_A + 3] = _vec(self.name, "amplitude", self.amplitude, 3)
        row[ke.L_M0:ke.L_M0 + 3] = _vec(self.name, "moment", self.moment, 3)
        if not self.t_off > self.t_on:
            raise ParameterError(f"{self.name}.t_off = {self.t_off!r} is not allowed: expected "
                                 f"a time after t_on = {self.t_on!r} s")
        row[ke.L_OM], row[ke.L_PH], row[ke.L_T0] = self.omega, self.phase, self.t_on
        row[ke.L_T1] = min(self.t_off, 1e300)
        return (ke.LOAD, self.m1, self.m1, 0), row


@dataclass
class Drive:
    """Traction or braking that drives marker ``aux`` along the speed profile
    (:mod:`axlebox.mbs.vehicle.speed`, kernel: :func:`axlebox.mbs.kernel.elements._drive`):
    ``F = mass a(t) + kd (v(t) - v_aux)``; ``radius > 0``: the torque
    ``F radius + inertia a / radius`` about marker 1's y axis (a wheelset's axle; the spin's own
    inertia ``inertia``), its reaction on marker 2 (the gearbox or frame); ``radius = 0``: the
    force along the track on marker 1 (``m2`` unused)."""

    name: str
    m1: int
    m2: int
    aux: int
    mass: float                    # kg it accelerates
    radius: float = 0.0            # m, the rolling radius (0: a force, not a torque)
    inertia: float = 0.0           # kg m^2, the spin inertia about the axle
    kd: float = 0.0                # N s/m, on marker aux's speed against the profile's

    def pack(self):
        for what in ("mass", "radius", "inertia", "kd"):
            v = getattr(self, what)
            if not (np.isfinite(v) and v >= 0):
                raise ParameterError(f"{self.name}.{what} = {v!r} is not allowed: expected a number >= 0")
        row = np.zeros(ke.EL_WIDTH)
        row[ke.D_M], row[ke.D_R], row[ke.D_J] = self.mass, self.radius, self.inertia
        row[ke.D_KD] = self.kd
        return (ke.DRIVE, self.m1, self.m2, self.aux), row
