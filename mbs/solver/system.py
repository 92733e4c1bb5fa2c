"""Assemble bodies, markers, elements, wheels and sensors into a :class:`Model`: the packed
arrays the numba kernels run on, the state layout and the initial state.

    sys = System(gravity=(0, 0, -9.81), speed=13.3)
    b = sys.add_body(flexible("ws1", rb, spin=True), r=(0, 0, 0.42), omega=(0, 13.3 / 0.42, 0))
    m1 = sys.marker("ws1", node="journal_L_row1")
    m2 = sys.marker("ab1L", node="bore_row1")
    sys.add(Bushing("joint", m2, m1, k=(1e9, 5e8, 1e9, 0, 0, 0)))
    model = sys.assemble()
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy.spatial.transform import Rotation

from axlebox._params import ParameterError
from axlebox.bearing import defects

from . import ffrf_numpy as fn
from .body import Body
from ..kernel.body import BF_GRAV, BF_JINV, BF_M, BF_MC, BF_P0, BF_WIDTH
from ..kernel.elements import EL_WIDTH
from ..kernel.system import Arrays, Work, lanes
from ..kernel.trajectory import FR_N
from ..kernel.wheels import N_WHOUT

#: s, the track irregularity fades in over this time from the start of a run (so a run's first
#: TRACK_RAMP_S are left out of what is diagnosed and rated)
TRACK_RAMP_S = 0.5


@dataclass
class _Init:
    r: np.ndarray
    p: np.ndarray          # quaternion (w, x, y, z)
    v: np.ndarray
    omega: np.ndarray      # body frame; omega[1] = spin rate on a spinning body
    q: np.ndarray
    qd: np.ndarray


def quaternion(rotation) -> np.ndarray:
    """Unit quaternion (w, x, y, z) of a rotation matrix (3, 3) or small angles (rx, ry, rz) rad
    (applied as a rotation vector)."""
    if rotation is None:
        return np.array([1.0, 0.0, 0.0, 0.0])
    R = np.asarray(rotation, float)
    rot = Rotation.from_matrix(R) if R.shape == (3, 3) else Rotation.from_rotvec(R)
    x, y, z, w = rot.as_quat()
    return np.array([w, x, y, z])


class System:
    """A multibody system under construction (names are unique; ``None`` body is the ground)."""

    def __init__(self, gravity=(0.0, 0.0, -9.81), speed: float = 0.0, profile=None):
        """``speed`` (m/s): the contact's reference speed; ``profile``: a
        :class:`~axlebox.mbs.vehicle.speed.SpeedProfile` that replaces it over time."""
        self.gravity = np.asarray(gravity, float)
        self.speed = float(speed)
        self.profile = profile
        self.bodies: list[Body] = []
        self.init: list[_Init] = []
        self.markers: list[tuple[int, str | None, np.ndarray, str]] = []
        self.elements: list = []
        self.sensors: dict[str, int] = {}
        self.wheels: list[tuple[str, int, int, float, int]] = []
        self.wheel_tables: tuple[np.ndarray, np.ndarray] | None = None
        self.track = None
        self.wheel_records: dict[str, tuple] = {}   # wheel name -> (values, slopes, ds)
        self.track_ramp = TRACK_RAMP_S
        self.bearings: list[tuple] = []
        self.bearing_tag = None
        self.line = None
        self.line_start = 0.0

    def on_line(self, line, start: float) -> None:
        """Run on ``line`` (:class:`axlebox.mbs.track.line.Line`), the body frame's origin ``x = 0``
        starting at chainage ``start`` (m).  The system is built as on tangent track (x forward
        along the car, every body at the running speed); assembled, each body is then described
        from its track frame at its own ``x`` (:mod:`axlebox.mbs.kernel.trajectory`), at rest on
        it but for what the build gave beyond the running speed, and a ground marker is the
        track's point at its ``x``."""
        self.line, self.line_start = line, float(start)

    # -- building -------------------------------------------------------------------------
    def index(self, name: str) -> int:
        for i, b in enumerate(self.bodies):
            if b.name == name:
                return i
        raise ParameterError(f"body = {name!r} is not allowed: no such body (have "
                             f"{[b.name for b in self.bodies]})")

    def add_body(self, body: Body, *, r=(0, 0, 0), rotation=None, v=(0, 0, 0), omega=(0, 0, 0),
                 q=None, qd=None) -> int:
        if any(b.name == body.name for b in self.bodies):
            raise ParameterError(f"body = {body.name!r} is not allowed: the name is taken")
        n = body.n_modes
        self.bodies.append(body)
        self.init.append(_Init(np.asarray(r, float), quaternion(rotation), np.asarray(v, float),
                               np.asarray(omega, float),
                               np.zeros(n) if q is None else np.asarray(q, float),
                               np.zeros(n) if qd is None else np.asarray(qd, float)))
        return len(self.bodies) - 1

    def marker(self, body: str | None, node: str | None = None, at=None, name: str = "",
               align: bool = False) -> int:
        """A marker on ``body`` at its ``node`` (flexible: follows the node's elastic motion)
        or at the body-frame point ``at``; ``body=None``: a ground point ``at``.  ``align``:
        the marker's axes are the inertial axes in the initial pose (else the body's)."""
        if body is None:
            self.markers.append((-1, None, np.asarray(at if at is not None else (0, 0, 0), float),
                                 name, np.eye(3)))
            return len(self.markers) - 1
        b = self.index(body)
        if node is not None:
            pos, _ = self.bodies[b].node(node)
            x0 = np.asarray(pos, float) if at is None else np.asarray(at, float)
        else:
            x0 = np.asarray(at if at is not None else (0, 0, 0), float)
        if x0.shape != (3,) or not np.all(np.isfinite(x0)):
            raise ParameterError(f"marker {name or body!r}: at = {at!r} is not allowed: expected "
                                 "3 numbers (m)")
        R0 = fn.quat_to_A(self.init[b].p).T if align else np.eye(3)
        self.markers.append((b, node, x0, name, R0))
        return len(self.markers) - 1

    def add(self, element):
        for m in (element.m1, getattr(element, "m2", element.m1), getattr(element, "aux", element.m1)):
            if not 0 <= m < len(self.markers):
                raise ParameterError(f"{element.name}: marker {m!r} does not exist")
        self.elements.append(element)
        return element

    def sensor(self, name: str, marker: int) -> None:
        self.sensors[name] = marker

    def bearing(self, name: str, inner: int, outer: int, tag, P: np.ndarray, D: np.ndarray,
                y0: np.ndarray) -> None:
        """A bearing between the journal marker ``inner`` (on a spinning body) and the bore marker
        ``outer``: its model's kernel tag (bearing/models/__init__.py ``tag``; one model for all of a
        system's bearings), parameter vector ``P`` and defect table ``D`` (bearing/kernel/layout.py,
        bearing/defects.py), its roller and cage states starting at ``y0``."""
        b = self.markers[inner][0]
        if b < 0 or not self.bodies[b].spin:
            raise ParameterError(f"bearing {name!r}: inner = marker {inner} is not allowed: "
                                 "expected a marker on a spinning body (the wheelset)")
        if any(x[0] == name for x in self.bearings):
            raise ParameterError(f"bearing = {name!r} is not allowed: the name is taken")
        if self.bearings and tag != self.bearing_tag:
            raise ParameterError(f"bearing {name!r}: tag = {tag!r} is not allowed: the system's "
                                 f"bearings are {self.bearing_tag!r}; expected one model for all")
        for x in self.bearings:     # the bearings run in parallel: each loads its own markers
            if {inner, outer} & {x[1], x[2]}:
                raise ParameterError(f"bearing {name!r}: markers ({inner}, {outer}) are not "
                                     f"allowed: bearing {x[0]!r} uses ({x[1]}, {x[2]}); expected "
                                     "markers of its own")
        self.bearing_tag = tag
        self.bearings.append((name, inner, outer, b, np.asarray(P, float),
                              np.asarray(D, float).reshape(-1, defects.WIDTH),
                              np.asarray(y0, float)))

    def wheel(self, name: str, marker: int, side: int, r_c: float, track: int = -1) -> None:
        """A wheel-rail contact at the tread marker ``marker``; ``side`` 0 left, 1 right;
        ``r_c`` the height of the wheel centre above the marker (the rolling radius); ``track``:
        the marker of the rail body under it (mbs/track/bed.py), whose height adds to the rail's
        and which takes the contact's vertical force, or -1 for rigid rails."""
        self.wheels.append((name, marker, side, float(r_c), int(track)))

    # -- packing --------------------------------------------------------------------------
    def assemble(self) -> "Model":
        if not self.bodies:
            raise ParameterError("bodies = [] is not allowed: a system needs at least one body")
        nb = len(self.bodies)
        npos = [7 + int(b.spin) + b.n_modes for b in self.bodies]
        nvel = [6 + b.n_modes for b in self.bodies]
        nq = sum(npos)
        bi = np.zeros((nb, 5), np.int64)
        bf = np.zeros((nb, BF_WIDTH))
        goff = np.zeros(nb, np.int64)
        inv_parts, off = [], 0
        y0 = np.zeros(nq + sum(nvel))
        ip, iv = 0, nq
        for k, (b, ini) in enumerate(zip(self.bodies, self.init)):
            n = b.n_modes
            bi[k] = (ip, iv, n, int(b.spin), off)
            goff[k] = iv - nq
            bf[k, BF_M] = b.mass
            bf[k, BF_MC:BF_MC + 3] = b.mc
            bf[k, BF_P0:BF_P0 + 9] = b.P0.ravel()
            c = b.mc / b.mass                # inertia about the centre of mass: the rigid path
            J_c = b.inertia_origin - b.mass * (c @ c * np.eye(3) - np.outer(c, c))
            bf[k, BF_JINV:BF_JINV + 9] = np.linalg.inv(J_c).ravel()
            bf[k, BF_GRAV] = 1.0
            if n:
                part = np.concatenate([b.Ct.ravel(), b.Q.ravel(), b.R.ravel(), b.Me.ravel(),
                                       b.K.ravel(), b.D.ravel(), np.linalg.inv(b.Me).ravel()])
                inv_parts.append(part)
                off += part.size
            s = int(b.spin)
            y0[ip:ip + 3] = ini.r
            y0[ip + 3:ip + 7] = ini.p
            y0[ip + 7 + s:ip + 7 + s + n] = ini.q
            y0[iv:iv + 3] = ini.v
            y0[iv + 3:iv + 6] = ini.omega
            y0[iv + 6:iv + 6 + n] = ini.qd
            ip += npos[k]
            iv += nvel[k]
        inv = np.concatenate(inv_parts) if inv_parts else np.zeros(1)
        line = np.zeros(1)
        if self.line is not None:
            line = self._to_line(y0, bi, bf)

        mk_i = np.zeros((len(self.markers), 2), np.int64)
        mk_f = np.zeros((max(len(self.markers), 1), 12))
        shp_parts, so = [], 0
        for m, (b, node, x0, _, R0) in enumerate(self.markers):
            mk_f[m, :3] = x0
            mk_f[m, 3:] = R0.ravel()
            mk_i[m] = (b, -1)
            if b >= 0 and node is not None and self.bodies[b].n_modes:
                _, sh = self.bodies[b].node(node)
                mk_i[m, 1] = so
                shp_parts.append(np.ascontiguousarray(sh, float).ravel())
                so += sh.size
        shp = np.concatenate(shp_parts) if shp_parts else np.zeros(1)

        self._fill_offsets()
        rows = [e.pack() for e in self.elements]
        el_i = np.array([r[0] for r in rows], np.int64).reshape(-1, 4)
        el_f = np.array([r[1] for r in rows]).reshape(-1, EL_WIDTH)

        from ..kernel.wheels import G_DS, G_GRAV, G_LINE, G_PROF, G_RAMP, G_S0, G_TRACK, G_V, N_GLOB
        glob = np.zeros(N_GLOB)
        glob[G_RAMP] = self.track_ramp
        glob[G_GRAV:G_GRAV + 3] = self.gravity
        glob[G_V] = self.speed
        if self.profile is not None:
            glob = np.concatenate([glob[:G_PROF], self.profile.pack()])
        trk = np.zeros((8, 2))
        if self.track is not None:
            tr = self.track
            # the record's own node values and Hermite slopes (periodic): the kernel's look-up
            # then reproduces TrackIrregularity.at
            trk = np.ascontiguousarray(np.vstack(tr.grid() + tr.at(tr.s, derivative=True)))
            glob[G_S0], glob[G_DS], glob[G_TRACK] = 0.0, tr.ds, 1.0
        wh_i = np.array([(m, side, self.markers[m][0], tm) for _, m, side, _, tm in self.wheels],
                        np.int64).reshape(-1, 4)
        unknown = set(self.wheel_records) - {w[0] for w in self.wheels}
        if unknown:
            raise ParameterError(f"wheel_records: {', '.join(sorted(unknown))} is not allowed: "
                                 f"expected wheels of the system ({', '.join(w[0] for w in self.wheels)})")
        recs = [self.wheel_records.get(name) for name, *_ in self.wheels]
        nw = max([r[0].size for r in recs if r is not None], default=1)
        wrk = np.zeros((max(len(self.wheels), 1), 2, nw))
        wh_f = np.zeros((len(self.wheels), 2))       # ds 0: the wheel has no record
        for w, (r, (*_, rc, _tm)) in enumerate(zip(recs, self.wheels)):
            wh_f[w, 0] = rc
            if r is not None:          # one grid size for all: the kernel's table is rectangular
                values, slopes, ds = r
                if values.size != nw:
                    raise ParameterError(f"wheel_records[{self.wheels[w][0]!r}] has {values.size} "
                                         f"points, not allowed: every wheel's record needs {nw}")
                wrk[w, 0], wrk[w, 1], wh_f[w, 1] = values, slopes, ds
        if self.wheels and self.wheel_tables is None:
            raise ParameterError("wheels need wheel-rail tables: call set_wheel_rail() first")
        wtab, wpar = self.wheel_tables if self.wheel_tables is not None else (np.zeros((1, 1)), np.zeros(1))
        sens_names = list(self.sensors)
        sens = np.array([self.sensors[s] for s in sens_names], np.int64)
        B, y0 = self._pack_bearings(y0)
        if self.line is not None:
            glob[G_LINE] = 1.0
        S = Arrays(bi, bf, inv, goff, mk_i, mk_f, shp, el_i, el_f, glob, wh_i, wh_f,
                   np.ascontiguousarray(wtab, float), np.ascontiguousarray(wpar, float), trk, wrk, sens,
                   line, np.array([(x[1], x[2], x[3]) for x in self.bearings], np.int64).reshape(-1, 3),
                   lanes(bi))
        return Model(self, S, y0, nq, sens_names, [w[0] for w in self.wheels], B)

    def _to_line(self, y0: np.ndarray, bi: np.ndarray, bf: np.ndarray) -> np.ndarray:
        """The bodies' built states turned into states on their track frames (:meth:`on_line`),
        in place; their places along the car into ``bf``; returns the packed line."""
        from ..kernel.body import BF_X
        from ..kernel.trajectory import FR_W, frame_motion, pack
        v0 = self.profile.speed(0.0) if self.profile is not None else self.speed
        line = pack(self.line, self.line_start)
        F = np.zeros(FR_N)
        for k in range(bi.shape[0]):
            ip, iv = int(bi[k, 0]), int(bi[k, 1])
            bf[k, BF_X] = y0[ip]
            frame_motion(line, self.line_start + y0[ip], v0, F)
            w = F[FR_W:FR_W + 3]
            r = np.array([0.0, y0[ip + 1], y0[ip + 2]])
            y0[ip] = 0.0
            # at rest on the frame but for what the build gave beyond the running speed (the
            # wheelsets' spin): the frame point's velocity and the frame's rate added
            y0[iv:iv + 3] += np.cross(w, r)
            y0[iv + 3:iv + 6] += fn.quat_to_A(y0[ip + 3:ip + 7]).T @ w
        return line

    def _pack_bearings(self, y0):
        """The bearings (mbs/kernel/bearings.py ``Bearings``, with every array their kernels
        write) and their states appended to ``y0``."""
        from axlebox.bearing.kernel import implicit
        from axlebox.bearing.kernel.evaluate import work
        from axlebox.bearing.kernel.layout import CAGE_OUT, LOAD, N_Q, N_ROWS, RING, RINGS, Z
        from axlebox.bearing.kernel.quasidynamic import QD_WIDTH

        from ..kernel.bearings import BR_WIDTH, TH, Bearings, NoBearings
        if not self.bearings:
            return NoBearings(), y0
        nbr = len(self.bearings)
        idx = np.zeros((nbr, BR_WIDTH), np.int64)
        D_parts, off, d0 = [np.zeros((0, defects.WIDTH))], y0.size, 0
        for k, (_, mi, mo, b, _P, D, yb) in enumerate(self.bearings):
            idx[k] = (mi, mo, b, off, yb.size, d0, D.shape[0])
            D_parts.append(D)
            off += yb.size
            d0 += D.shape[0]
        P = np.stack([x[4] for x in self.bearings])
        nz, nrow, ns = int(P[0, Z]), int(P[0, N_ROWS]), self.bearings[0][6].size
        y0 = np.concatenate([y0] + [x[6] for x in self.bearings])
        D = np.concatenate(D_parts) if d0 else np.zeros((1, defects.WIDTH))
        z = np.zeros
        return Bearings(self.bearing_tag, idx, P, D, z((nbr, RINGS, RING)), z((nbr, TH)),
                        z((nbr, RINGS, LOAD)), z((nbr, nrow, nz, N_Q)), z((nbr, nrow, CAGE_OUT)),
                        work(nz, ns, QD_WIDTH, (nbr,)), implicit.scratch(nz, nrow, (nbr,))), y0

    def initial_marker_pose(self, m: int) -> tuple[np.ndarray, np.ndarray]:
        """Position and axes of marker ``m`` in the initial (undeformed) configuration."""
        b, _, x0, _, R0 = self.markers[m]
        if b < 0:
            return x0, R0
        A = fn.quat_to_A(self.init[b].p)
        return self.init[b].r + A @ x0, A @ R0

    def _fill_offsets(self) -> None:
        """Elements placed without a free length or offset are unloaded as placed."""
        from .elements import Bushing, Spring
        for e in self.elements:
            if isinstance(e, Bushing) and e.offset is None:
                p1, R1 = self.initial_marker_pose(e.m1)
                p2, _ = self.initial_marker_pose(e.m2)
                e.offset = tuple(R1.T @ (p2 - p1))
            elif isinstance(e, Spring) and e.length is None:
                p1, _ = self.initial_marker_pose(e.m1)
                p2, _ = self.initial_marker_pose(e.m2)
                e.length = float(np.linalg.norm(p2 - p1))

    def set_wheel_rail(self, tab: np.ndarray, par: np.ndarray) -> None:
        self.wheel_tables = (tab, par)


class Model:
    """Packed arrays (``S``), the bearings (``B``, mbs/kernel/bearings.py), work arrays (``W``),
    the initial state ``y0`` and helpers."""

    def __init__(self, system: System, S, y0, nq, sensors, wheels, B=None):
        from ..kernel.bearings import NoBearings
        self.system = system
        self.S = S
        self.B = NoBearings() if B is None else B
        self.y0 = y0
        self.nq = nq
        self.sensor_names = sensors
        self.wheel_names = wheels
        bi = S.bi
        nb, nm, ne = bi.shape[0], S.mk_i.shape[0], S.el_i.shape[0]
        ngen = int(sum(6 + b.n_modes for b in system.bodies))
        from ..kernel.bearings import BR_ROWS
        self.bearing_names = [x[0] for x in system.bearings]
        self.n_body_states = int(y0.size - sum(x[6].size for x in system.bearings))
        ne = ne + BR_ROWS * len(self.bearing_names)
        z = np.zeros
        self.W = Work(z((nb, 3, 3)), z((nb, 3)), z((nb, 3)), z((nb, 3)), z((nb, 3)),
                      z((max(nm, 1), 3)), z((max(nm, 1), 3)), z((max(nm, 1), 3)), z((max(nm, 1), 3, 3)),
                      z((max(nm, 1), 3)), z((max(nm, 1), 3)), z((max(nm, 1), 3)), z(ngen),
                      z((max(ne, 1), 6)), z((max(len(wheels), 1), N_WHOUT)), z((max(len(sensors), 1), 3)),
                      z((nb, FR_N)), z(FR_N), z((max(len(system.bearings), 1), 2, 6)))

    @property
    def bodies(self) -> list[Body]:
        return self.system.bodies

    @property
    def bearing_rows(self) -> int:
        """The rows of the car's bearings (their model's; 0 without bearings)."""
        from axlebox.bearing.kernel.layout import N_ROWS
        return int(self.B.P[0, N_ROWS]) if self.bearing_names else 0

    @property
    def n_states(self) -> int:
        return self.y0.size

    def rhs(self, t: float, y: np.ndarray) -> np.ndarray:
        from ..kernel import system as ks
        dy = np.zeros_like(y)
        t, y = float(t), np.ascontiguousarray(y, float)
        if self.bearing_names:
            ks.rhs(t, y, dy, self.S, self.W, self.B)
        else:
            # without bearings the right-hand side is its two parts, which the run's kernels
            # share: the statics compiles nothing a run does not (the same operations, bits)
            ks.kinematics(t, y, dy, self.S, self.W)
            ks.dynamics(t, y, dy, self.S, self.W)
        return dy

    def kinematics(self, t: float, y: np.ndarray) -> None:
        """The frames, markers and element forces at ``(t, y)`` into ``self.W`` (the first part
        of :meth:`rhs`, without the bearings' rates or the bodies' accelerations)."""
        from ..kernel.system import kinematics
        kinematics(float(t), np.ascontiguousarray(y, float), np.zeros(y.size), self.S, self.W)

    def inertial(self, k: int, t: float, y: np.ndarray) -> dict:
        """Body ``k``'s inertial kinematics at ``(t, y)``: position ``r``, axes ``A``, velocity
        ``v`` (inertial axes), angular velocity ``omega`` (body axes; a spinning body's with its
        spin) - on a line, from its states on its track frame (mbs/kernel/trajectory.py)."""
        self.kinematics(t, y)
        W = self.W
        return {"r": W.rb[k].copy(), "A": W.Ab[k].copy(), "v": W.vb[k].copy(),
                "omega": W.omb[k].copy()}

    def body_state(self, k: int, y: np.ndarray) -> dict:
        """Unpacked state of body ``k``: r, p, A, beta, q, v, omega, qd."""
        bi = self.S.bi
        ip, iv, n, s = (int(x) for x in bi[k, :4])
        p = y[ip + 3:ip + 7]
        return {"r": y[ip:ip + 3], "p": p, "A": fn.quat_to_A(p), "beta": y[ip + 7] if s else 0.0,
                "q": y[ip + 7 + s:ip + 7 + s + n], "v": y[iv:iv + 3], "omega": y[iv + 3:iv + 6],
                "qd": y[iv + 6:iv + 6 + n]}

    def state_owner(self, i: int) -> str:
        """Which body (and which coordinate) state index ``i`` belongs to."""
        bi = self.S.bi
        for k, b in enumerate(self.bodies):
            ip, iv, n, s = (int(x) for x in bi[k, :4])
            if ip <= i < ip + 7 + s + n:
                j = i - ip
                what = ("x", "y", "z", "p0", "p1", "p2", "p3")[j] if j < 7 else \
                    ("spin angle" if s and j == 7 else f"q{j - 7 - s + 1}")
                return f"body {b.name!r} ({what})"
            if iv <= i < iv + 6 + n:
                j = i - iv
                what = ("vx", "vy", "vz", "wx", "wy", "wz")[j] if j < 6 else f"qd{j - 5}"
                return f"body {b.name!r} ({what})"
        from axlebox.bearing.kernel.layout import N_CAGE, N_ROLLER

        from ..kernel.bearings import BR_N, BR_OFF
        rows = self.bearing_rows
        for k, name in enumerate(self.bearing_names):
            off, n = int(self.B.idx[k, BR_OFF]), int(self.B.idx[k, BR_N])
            if off <= i < off + n:
                j = i - off
                nr = n - rows * N_CAGE
                what = (f"row {j // (nr // rows) + 1}, roller {(j % (nr // rows)) // N_ROLLER + 1}"
                        if j < nr else f"row {(j - nr) // N_CAGE + 1} cage")
                return f"bearing {name!r} ({what})"
        return f"state {i}"

    def energy(self, y: np.ndarray) -> dict:
        """Kinetic, elastic (modal) and gravitational potential energy of the bodies (J);
        force elements' energy is not included."""
        T = U = Vg = 0.0
        for k, b in enumerate(self.bodies):
            st = self.body_state(k, y)
            T += fn.kinetic_energy(b, st["A"], st["q"], st["v"], st["omega"], st["qd"])
            U += 0.5 * st["q"] @ b.K @ st["q"]
            S = b.mc + b.Ct @ st["q"]
            Vg -= self.system.gravity @ (b.mass * st["r"] + st["A"] @ S)
        return {"kinetic": T, "elastic": U, "gravity": Vg, "total": T + U + Vg}

    def momentum(self, y: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """Total linear momentum and angular momentum about the inertial origin."""
        P, H = np.zeros(3), np.zeros(3)
        for k, b in enumerate(self.bodies):
            st = self.body_state(k, y)
            p, h = fn.momenta(b, st["r"], st["A"], st["q"], st["v"], st["omega"], st["qd"])
            P += p
            H += h
        return P, H

    def coupling_pattern(self) -> tuple[np.ndarray, np.ndarray, int]:
        """Sparsity of dF/dy from which bodies the elements and wheels couple, and column groups
        for finite differences (columns of bodies with disjoint neighbourhoods share a group)."""
        bi = self.S.bi
        nb = bi.shape[0]
        adj = np.eye(nb, dtype=bool)
        mk_body = self.S.mk_i[:, 0]
        pairs = [(e.m1, getattr(e, "m2", e.m1)) for e in self.system.elements]
        pairs += [(e.m1, e.aux) for e in self.system.elements if hasattr(e, "aux")]   # drives
        pairs += [(w[1], w[4]) for w in self.system.wheels if w[4] >= 0]    # wheel on its rail
        for m1, m2 in pairs:
            b1, b2 = mk_body[m1], mk_body[m2]
            if b1 >= 0 and b2 >= 0:
                adj[b1, b2] = adj[b2, b1] = True
        N = self.n_states
        owner = np.empty(N, np.int64)
        local = np.empty(N, np.int64)
        for k in range(nb):
            ip, iv, n, s = (int(x) for x in bi[k, :4])
            owner[ip:ip + 7 + s + n] = k
            local[ip:ip + 7 + s + n] = np.arange(7 + s + n)
            owner[iv:iv + 6 + n] = k
            local[iv:iv + 6 + n] = 7 + s + n + np.arange(6 + n)
        pattern = adj[owner][:, owner]
        # greedy colouring of bodies: two bodies share a class if no body touches both
        reach = adj.astype(int) @ adj.astype(int) > 0
        cls = -np.ones(nb, np.int64)
        for k in np.argsort([-(7 + 6 + 2 * b.n_modes) for b in self.bodies], kind="stable"):
            used = {cls[j] for j in range(nb) if reach[k, j] and cls[j] >= 0}
            c = 0
            while c in used:
                c += 1
            cls[k] = c
        size = np.zeros(cls.max() + 1, np.int64)
        for k in range(nb):
            size[cls[k]] = max(size[cls[k]], int(np.sum(owner == k)))
        base = np.concatenate([[0], np.cumsum(size)])
        groups = base[cls[owner]] + local
        return pattern, groups.astype(np.int64), int(base[-1])

    def state_scales(self) -> tuple[np.ndarray, np.ndarray]:
        """Finite-difference scales and Newton absolute tolerances per state."""
        N = self.n_states
        scale = np.ones(N)
        atol = np.full(N, 1e-9)
        bi = self.S.bi
        for k in range(bi.shape[0]):
            ip, iv, n, s = (int(x) for x in bi[k, :4])
            scale[ip + 7 + s:ip + 7 + s + n] = 1e-3
            scale[iv + 6:iv + 6 + n] = 1e-2
            atol[iv:iv + 6 + n] = 1e-6
        return scale, atol
