"""The B-type metro motor car, built from a validated config (:mod:`.config`): on tangent track,
or on the line of ``[[track.layout]]``, each body then described from its track frame
(:mod:`axlebox.mbs.kernel.trajectory`; the car is built as on tangent track, x along it).

Bodies: carbody; two bogie frames (``frame1`` front at x = 0, ``frame2`` at ``-bogie_distance``);
four wheelsets ``ws1..ws4`` (spinning frames, see :mod:`axlebox.mbs.solver.body`); eight axle-boxes
``ab<i><L|R>``; four gearboxes ``gb<i>`` hung between the axle (bushing at the gear seat, free to
turn about the axle) and the frame (a vertical hanger link).  Any of the frames, wheelsets and
axle-boxes is flexible when named in ``bodies.flexible`` (then its reduced body's modes below
``bodies.fmax_hz`` are kept), otherwise rigid with the same FE mass properties (or, without
reduced bodies at all, the config's masses and inertias).

Track frame: x forward, y left, z up, z = 0 at the crown of the rails.  Suspension:

* wheelset-axle-box: one bushing per bearing row at the journal row centres, radial and axial
  stiffness, spin and tilt free (two rows give the box its tilt stiffness) - the coupling issue
  replaces it with the DTRB model;
* primary: two coil springs per axle-box (its front and rear seats), each half the box's
  ``kx, ky, kz`` and vertical damping;
* secondary per bogie: two air springs (``kx, ky, kz``, vertical damper ``cz`` alongside), a
  lateral damper, an anti-roll bar (roll bushing), a traction rod (longitudinal link) and a
  lateral bump stop;
* the static loads are preloads so the nominal geometry is near equilibrium;
  :func:`axlebox.mbs.vehicle.statics.equilibrium` removes the rest.

Speed: the car starts at ``run.speed_kmh`` (every body at that speed, the wheelsets rolling
freely) and, without a profile, coasts.  Along a speed profile that changes (``run.profile``,
:mod:`axlebox.mbs.vehicle.speed`) it is driven as a metro motor car is, by torques at its four
wheelsets (traction, and electric braking the same way): each wheelset's torque reacts on its
gearbox (on the frame where there is none), so the wheelsets' spin follows with the creep their
contacts give and the car with the creep forces (:class:`~axlebox.mbs.solver.elements.Drive`: the
profile's acceleration times the car's mass, a quarter a wheelset, plus a gain on the
wheelset's speed against the profile's, :data:`DRIVE_HZ`).  The gain is on the wheelset's own
speed, where the torque acts through the stiff creep: on the carbody's, across the suspension,
it excites the car's longitudinal modes; and none on position, which would tie the car to a
point along the track and spoil its statics (the car is neutral along the track).  Prescribing
the carbody's motion instead would pull the car through its suspension and leave the wheels
braking it, the reverse of a motor car.  The ballasted track's bodies under the wheels follow
the profile by forces of their own.
"""
from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

from axlebox.fem.bodyfile import ReducedBody
from axlebox.fem.damping import modal as modal_damping

from ..solver.body import Body, add_point_masses, flexible, mode_count, rigid
from ..solver.elements import BumpStop, Bushing, Drive, Spring
from ..track import bed as trackbed
from ..solver.system import System
from ..wheelrail.element_kernel import COL_C0Z, COL_KH, COL_PZ, P_L0

if TYPE_CHECKING:
    from .config import CarConfig

G = 9.81
SIDES = (("L", 1.0), ("R", -1.0))
ROW_OFFSET = 0.04          # m, bearing row centres from the journal centre (160 mm unit / 4)


def _rotz_pi():
    return np.diag([-1.0, -1.0, 1.0])


def _body(name: str, kind: str, cfg: CarConfig, reduced: dict | None, *, spin: bool = False) -> Body:
    """Flexible or rigid body ``name`` of reduced body ``kind`` (wheelset, axlebox, frame)."""
    flex = name in cfg.bodies.flexible
    rb: ReducedBody | None = (reduced or {}).get(kind)
    if rb is None:
        sec = getattr(cfg, kind)
        return rigid(name, sec.mass, sec.inertia, spin=spin)
    if not flex:
        return flexible(name, rb, rigid_only=True, spin=spin)
    body = flexible(name, rb, n_modes=mode_count(rb, getattr(cfg.bodies, f"fmax_{kind}_hz")), spin=spin)
    # the config's modal damping ratio of this kind of body replaces the file's (the modes are
    # mass-normalised until point masses are added, so D = diag(2 zeta omega))
    body.D = modal_damping(body.frequencies_hz, getattr(cfg.bodies, f"zeta_{kind}"))
    return body


def _axlebox_assembly(ab: Body, cfg: CarConfig) -> Body:
    """The parts of the axle-box assembly its housing mesh lacks, as point masses on the housing's
    nodes: the bearing cup on the two bore spiders, the end cover on the outboard one (row 2),
    the adapter on the two spring seats."""
    a = cfg.axlebox
    if not ab.nodes:                    # config mass: the parts' masses add at its centre
        ab.mass += a.cup_mass + a.cover_mass + a.adapter_mass
        return ab
    return add_point_masses(ab, {"bore_row1": a.cup_mass / 2,
                                 "bore_row2": a.cup_mass / 2 + a.cover_mass,
                                 "spring_front": a.adapter_mass / 2,
                                 "spring_rear": a.adapter_mass / 2})


def _marker(s: System, body: Body, node: str, at, align: bool = False, place: bool = False) -> int:
    """Marker following ``node`` when the body has it (its elastic motion), else at ``at``;
    ``place``: at ``at`` even on the node (a point of the node's rigid spider)."""
    if node in body.nodes:
        return s.marker(body.name, node=node, at=at if place else None, align=align)
    return s.marker(body.name, at=at, align=align)


TIE_HZ = 300.0              # the track layers' ties along, across and in rotation (unloaded)
#: Hz, the drives' speed gain over the mass each drives (kd = 2 pi DRIVE_HZ M / 4): it trims
#: what the feed-forward leaves (rolling resistance, the creep's share) within about 1/(2 pi
#: DRIVE_HZ) s
DRIVE_HZ = 0.5
TRACK_FOLLOW_HZ = 5.0       # the ballasted track bodies' own following of the profile


def _track_under(s: System, cfg: CarConfig, name: str, x: float, y: float, V: float) -> int:
    """The ballasted track under wheel ``name`` (:mod:`axlebox.mbs.track.bed`): rail, sleeper and ballast
    bodies below the contact at ``(x, y)``, moving with the car, each spring preloaded with the
    weight above it so that the unloaded track rests as built; returns the rail's marker.  The
    ground springs hold nothing along the track (the bodies travel with the wheel); the layers
    are tied along, across and in rotation at :data:`TIE_HZ` (no load reaches those directions)."""
    m = trackbed.lumped(cfg.track)
    w = 2 * np.pi * TIE_HZ
    # each layer (top down) and the spring under it
    layers = (("rail", m.m_rail, 0.0, m.k_pad, m.c_pad),
              ("sleeper", m.m_sleeper, -0.2, m.k_ballast, m.c_ballast),
              ("ballast", m.m_ballast, -0.5, m.k_subgrade, m.c_subgrade))
    marks = []
    for layer, mass, z, _, _ in layers:
        body = f"{layer}_{name}"
        s.add_body(rigid(body, mass, [mass * 0.01] * 3), r=(x, y, z), v=(V, 0, 0))
        marks.append(s.marker(body))
    ground = s.marker(None, at=(x, y, -0.8))
    weight = 0.0
    for (layer, mass, _, k, c), top, low in zip(layers, marks, marks[1:] + [ground]):
        weight += mass * G
        kt, ct = mass * w * w, 0.1 * mass * w            # ties: 300 Hz, 5 % damping
        kr, cr = 0.01 * kt, 0.01 * ct
        s.add(Bushing(f"{layer}_support_{name}", low, top,
                      k=(0.0 if low == ground else kt, kt, k, kr, kr, kr),
                      c=(0.0 if low == ground else ct, ct, c, cr, cr, cr),
                      preload=(0, 0, weight, 0, 0, 0)))
    s.add(Bushing(f"rail_bending_{name}", ground, marks[0], k=(0, 0, m.k_bend, 0, 0, 0)))
    return marks[0]


def static_wheel_load(cfg: CarConfig) -> float:
    """An eighth of the car's weight (N): what each wheel carries at rest on level track."""
    return G * (cfg.carbody.mass + 2 * cfg.frame.mass + 4 * cfg.wheelset.mass
                + 8 * cfg.axlebox.mass + 4 * cfg.gearbox.mass) / 8


def build(cfg: CarConfig, tables, track=None, reduced: dict[str, ReducedBody] | None = None,
          bearings: dict | None = None) -> System:
    """The car as a :class:`~axlebox.mbs.solver.system.System` (not yet in equilibrium: see mbs.statics).

    ``bearings``: ``(k, side) -> (tag, P, D, y0)`` (the model's kernel tag, parameters, defect
    table, roller and cage states) puts a bearing between wheelset k's journal and its axle-box
    on that side instead of the row bushings (:func:`axlebox.pipelines.simulate.build_model`
    makes them)."""
    V = cfg.run.speed_kmh / 3.6
    geo, prim, sec, gb, jt = cfg.geometry, cfg.primary, cfg.secondary, cfg.gearbox, cfg.joint
    r0 = cfg.wheelset.r0
    profile = cfg.speed_profile()
    s = System(gravity=(0.0, 0.0, -G), speed=V, profile=profile if profile.accelerates else None)
    s.set_wheel_rail(tables.tab, tables.par)
    if track is not None:
        s.track = track
    ic = tables.tab.shape[0] // 2
    # wheel centre height: touching, centred, then lowered by the Hertz approach under an
    # eighth of the weight (the statics start inside the contact, where it has stiffness)
    K_H = float(tables.tab[ic, COL_KH])
    sink = (static_wheel_load(cfg) / K_H) ** (2 / 3)
    z_ws = float(tables.tab[ic, COL_C0Z]) - sink
    l0 = float(tables.par[P_L0])                   # nominal wheel centre half distance
    # free rolling: the spin that makes the longitudinal creepage vanish at the loaded contact
    spin = V / (z_ws - float(tables.tab[ic, COL_PZ]))
    xb = (0.0, -geo.bogie_distance)
    a = geo.wheelbase / 2

    # carbody
    W_cb = cfg.carbody.mass * G
    s.add_body(rigid("carbody", cfg.carbody.mass, cfg.carbody.inertia),
               r=(xb[1] / 2, 0, cfg.carbody.cg_height - sink), v=(V, 0, 0))
    # carbody floor sensors (1.1 m above rail, assumed) over each bogie centre and mid-car
    for name, xs in (("carbody_b1", xb[0]), ("carbody_centre", xb[1] / 2), ("carbody_b2", xb[1])):
        s.sensor(name, s.marker("carbody", at=(xs - xb[1] / 2, 0, 1.1 - cfg.carbody.cg_height)))
    gear_y = -1.0 if gb.side == "R" else 1.0
    for j in (1, 2):
        fr = _body(f"frame{j}", "frame", cfg, reduced)
        if fr.nodes:                                # equipment the FE frame leaves out
            extra = max(cfg.frame.mass - fr.mass, 0.0)
            add_point_masses(fr, {"secondary_L": extra / 3, "secondary_R": extra / 3,
                                  "traction_centre": extra / 3})
        zf = cfg.frame.cg_height - sink - (fr.mc[2] / fr.mass if fr.nodes else 0.0)
        fi = s.add_body(fr, r=(xb[j - 1], 0, zf), v=(V, 0, 0))
        W_f = fr.mass * G
        F_h = gb.mass * G * gb.arm / gb.hanger_arm if gb.mass > 0 else 0.0
        P_box = (W_cb / 2 + W_f + 2 * F_h) / 4          # static load on each axle-box's springs
        # secondary suspension
        for side, sg in SIDES:
            fm = _marker(s, fr, f"secondary_{side}", (0, sg * geo.air_spring_y, 0.15), align=True)
            cm = s.marker("carbody", at=(xb[j - 1] - xb[1] / 2, sg * geo.air_spring_y,
                                         geo.air_spring_height - cfg.carbody.cg_height))
            s.add(Bushing(f"air_spring{j}{side}", fm, cm, k=(sec.kx, sec.ky, sec.kz, 0, 0, 0),
                          c=(0, 0, sec.cz, 0, 0, 0), preload=(0, 0, W_cb / 4, 0, 0, 0)))
        tc = _marker(s, fr, "traction_centre", (0, 0, -0.15), align=True)
        p_tc, _ = s.initial_marker_pose(tc)
        rel = p_tc - s.init[s.index("carbody")].r
        ctc = s.marker("carbody", at=rel)
        s.add(Bushing(f"anti_roll{j}", tc, ctc, k=(0, 0, 0, sec.anti_roll, 0, 0)))
        s.add(BumpStop(f"bumpstop{j}", tc, ctc, axis=1, clearance=sec.bumpstop_clearance,
                       k=sec.bumpstop_k))
        crod = s.marker("carbody", at=rel + (0.6, 0, 0))
        s.add(Spring(f"traction_rod{j}", tc, crod, k=sec.traction_k))
        dl = s.marker("carbody", at=rel + (0, -0.5, 0))
        df = s.marker(fr.name, at=p_tc - s.init[fi].r + (0, 0.5, 0))
        s.add(Spring(f"lateral_damper{j}", df, dl, c=sec.cy))

        for k, xa in ((2 * j - 1, a), (2 * j, -a)):
            x = xb[j - 1] + xa
            ws = _body(f"ws{k}", "wheelset", cfg, reduced, spin=True)
            s.add_body(ws, r=(x, 0, z_ws), v=(V, 0, 0), omega=(0, spin, 0))
            for side, sg in SIDES:
                ab = _axlebox_assembly(_body(f"ab{k}{side}", "axlebox", cfg, reduced), cfg)
                W_ab = ab.mass * G
                s.add_body(ab, r=(x, sg * geo.journal_y, z_ws), v=(V, 0, 0),
                           rotation=None if sg > 0 else _rotz_pi())
                if bearings is not None and (k, side) in bearings:
                    # one marker a ring at the bearing centre: the bore's row-1 spider and the
                    # journal's, placed there (the bearing's rows are the kernel's own)
                    om = _marker(s, ab, "bore_row1", (0, 0, 0), align=True, place=True)
                    im = _marker(s, ws, f"journal_{side}_row1", (0, sg * geo.journal_y, 0),
                                 place=True)
                    s.bearing(f"bearing{k}{side}", im, om, *bearings[(k, side)])
                else:
                    for row, dy in (("row1", -ROW_OFFSET), ("row2", ROW_OFFSET)):
                        # on the row centres (the housing's bore nodes sit 10 mm outboard of them)
                        am = _marker(s, ab, f"bore_{row}", (0, dy, 0), align=True, place=True)
                        wm = _marker(s, ws, f"journal_{side}_{row}",
                                     (0, sg * (geo.journal_y + dy), 0), place=True)
                        s.add(Bushing(f"joint{k}{side}_{row}", am, wm,
                                      k=(jt.k_radial, jt.k_axial, jt.k_radial, 0, 0, 0),
                                      c=(jt.c,) * 3 + (0, 0, 0),
                                      preload=(0, 0, -(P_box + W_ab) / 2, 0, 0, 0)))
                for seat, sx in (("spring_front", 0.25), ("spring_rear", -0.25)):
                    bm = _marker(s, ab, seat, (sx, 0, 0.04))
                    p_seat = s.initial_marker_pose(bm)[0]
                    # the spring's top on the frame's primary seat spider, above the box seat
                    fm = _marker(s, fr, f"primary_{1 if xa > 0 else 2}_{side}",
                                 p_seat - s.init[fi].r + (0, 0, 0.1), align=True, place=True)
                    s.add(Bushing(f"primary{k}{side}_{seat}", fm, bm,
                                  k=(prim.kx / 2, prim.ky / 2, prim.kz / 2, 0, 0, 0),
                                  c=(0, 0, prim.cz / 2, 0, 0, 0), preload=(0, 0, -P_box / 2, 0, 0, 0)))
                s.sensor(f"ws{k}_{side}", _marker(s, ab, cfg.sensors.node, (0, 0, 0.175)))
                # the tables' nominal contact line (the FE tread spider sits at the FE wheel's)
                tread = _marker(s, ws, f"tread_{side}", (0, sg * l0, -r0), place=True)
                rail = (_track_under(s, cfg, f"ws{k}_{side}", x, sg * l0, V)
                        if cfg.track.model == "ballasted" else -1)
                s.wheel(f"ws{k}_{side}", tread, 0 if sg > 0 else 1, r0, track=rail)
            if gb.mass > 0:
                toward = -1.0 if xa > 0 else 1.0            # towards the bogie centre
                yg = gear_y * 0.42
                gbody = rigid(f"gb{k}", gb.mass, gb.inertia)
                s.add_body(gbody, r=(x + toward * gb.arm, yg, z_ws), v=(V, 0, 0))
                gm = _marker(s, ws, "gear", (0, yg, 0), place=True)
                bm = s.marker(f"gb{k}", at=(-toward * gb.arm, 0, 0))
                s.add(Bushing(f"gear_bearing{k}", gm, bm, k=(1e8, 1e8, 1e8, 1e7, 0, 1e7),
                              c=(1e3,) * 3 + (1e2, 0, 1e2),
                              preload=(0, 0, gb.mass * G - F_h, 0, 0, 0)))
                hm = s.marker(f"gb{k}", at=(toward * (gb.hanger_arm - gb.arm), 0, 0))
                p_h = s.initial_marker_pose(hm)[0]
                fh = s.marker(fr.name, at=p_h - s.init[fi].r + (0, 0, 0.3))
                s.add(Spring(f"hanger{k}", fh, hm, k=gb.hanger_k, c=gb.hanger_c, preload=-F_h))
    if profile.accelerates:
        _drives(s, z_ws - float(tables.tab[ic, COL_PZ]))
    line = cfg.line(s0=2 * l0)           # the cant measured between the nominal contact lines
    if line is not None:
        s.on_line(line, cfg.track.start)
    return s


TRACK_LAYERS = ("rail_", "sleeper_", "ballast_")


def _drives(s: System, r_roll: float) -> None:
    """Traction and braking along the speed profile (module docstring): a drive a wheelset, its
    torque reacting on the wheelset's gearbox (else its bogie frame), a quarter of the car's mass
    each; a force a track body.  ``r_roll``: the wheels' rolling radius at the loaded contact."""
    names = [b.name for b in s.bodies]
    car = [b for b in s.bodies if not b.name.startswith(TRACK_LAYERS)]
    M = sum(b.mass for b in car)
    wheelsets = [b for b in car if b.spin]
    w = 2 * np.pi * DRIVE_HZ
    share = M / len(wheelsets)
    for ws in wheelsets:
        k = ws.name[2:]
        react = f"gb{k}" if f"gb{k}" in names else f"frame{(int(k) + 1) // 2}"
        J = float(ws.P0[0, 0] + ws.P0[2, 2])          # about the axle: int rho (x^2 + z^2)
        m = s.marker(ws.name, name=f"drive_{ws.name}")
        s.add(Drive(f"drive{k}", m, s.marker(react, name=f"drive_reaction{k}"), m, mass=share,
                    radius=r_roll, inertia=J, kd=share * w))
    wt = 2 * np.pi * TRACK_FOLLOW_HZ
    for b in s.bodies:
        if b.name.startswith(TRACK_LAYERS):
            m = s.marker(b.name, name=f"drive_{b.name}")
            s.add(Drive(f"drive_{b.name}", m, m, m, mass=b.mass, kd=b.mass * wt))
