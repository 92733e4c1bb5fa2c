"""Bodies described from track-following frames (mbs/kernel/trajectory.py) move as they would
described from the inertial frame: a body's inertial motion does not depend on the frame its
coordinates are measured from (Shabana, Zaazaa and Sugiyama, *Railroad Vehicle Dynamics: A
Computational Approach*, CRC 2008, ch. 4: the trajectory coordinates' inertial terms are exact
when none is dropped).  Each case runs the same free bodies twice, once off a line (inertial
states) and once on a line whose frames travel a canted 50 m curve (turning 0.5 rad) at a speed
that changes, from the same inertial state, and compares the inertial motion: every
centrifugal, Coriolis, Euler and cant term must be there and right for the two to agree.

Where a cant ramp begins or ends the frames' roll rate steps (the ramp is linear in s), so the
position rates step there, and a fixed step straddling it makes a first-order error: about
``h |d omega_F| (|r| + |u| T)``.  The run through the transition is held to that bound."""
import numpy as np
import pytest
from conftest import craig_bampton_bar

from axlebox.mbs.solver import integrate
from axlebox.mbs.solver.body import flexible, rigid
from axlebox.mbs.solver.elements import Bushing
from axlebox.mbs.solver.system import System
from axlebox.mbs.track.line import Line, Segment
from axlebox.mbs.vehicle.speed import SpeedProfile

LINE = Line([Segment("tangent", 2.0), Segment("transition", 10.0),
             Segment("curve", 60.0, radius=50.0, hand="right", superelevation=0.15)])
IN_CURVE = 18.0                   # m: where the frames start for the runs inside the curve
V = 10.0
PROFILE = SpeedProfile((0.0, 0.8, 2.0), (V, 14.0, 12.0))        # speeds up, then brakes


def _model(build, start=None, init=None):
    s = System(gravity=(0.0, 0.0, -9.81), speed=V, profile=PROFILE)
    build(s, init)
    if start is not None:
        s.on_line(LINE, start)
    return s.assemble()


def _run(model, duration=2.0, dt=2e-4):
    run = integrate.simulate(model, duration, integrate.Settings(method="rk4", dt=dt,
                                                                output_rate_hz=50,
                                                                state_rate_hz=50))
    assert run.ok, run.message
    return run


def _inertial(model, run):
    """Per snapshot and body: position, axle (y axis), velocity, angular velocity (inertial
    axes) and modal coordinates (a spinning body's non-spinning frame may turn about its axle
    differently from one description to the other; nothing physical does)."""
    out = []
    for t, y in zip(run.state_time, run.states):
        row = []
        for k in range(len(model.bodies)):
            st = model.inertial(k, t, y)
            row.append({"r": st["r"], "axle": st["A"][:, 1], "v": st["v"],
                        "omega": st["A"] @ st["omega"], "q": model.body_state(k, y)["q"]})
        out.append(row)
    return out


def _pair(build, start, dt=2e-4, duration=2.0):
    """The on-line run from ``start`` and the off-line run from its inertial initial state."""
    on = _model(build, start)
    init = [{**on.inertial(k, 0.0, on.y0), "elements": on.system.elements}
            for k in range(len(on.bodies))]
    off = _model(build, None, init)
    return (on, _run(on, duration, dt)), (off, _run(off, duration, dt))


def _worst(a, b):
    return {key: max(float(np.abs(x[k][key] - z[k][key]).max(initial=0.0))
                     for x, z in zip(a, b) for k in range(len(x)))
            for key in ("r", "axle", "v", "omega", "q")}


def _exact(build, tol):
    (m1, r1), (m0, r0) = _pair(build, IN_CURVE)
    worst = _worst(_inertial(m1, r1), _inertial(m0, r0))
    for key, t in tol.items():
        assert worst[key] < t, (key, worst)
    # the frames did turn, and the states on them are not the inertial ones
    assert abs(LINE.at(IN_CURVE + 25.0).psi - LINE.at(IN_CURVE).psi) > 0.4
    assert np.abs(r1.states[-1, :2] - r0.states[-1, :2]).max() > 1.0


def _add(s, init, k, body, **kw):
    """``s.add_body`` with the build's state, or the given inertial one (``init[k]``)."""
    if init is not None:
        st = init[k]
        w = st["A"].T @ st["A"] @ st["omega"]
        kw.update(r=st["r"], rotation=st["A"], v=st["v"], omega=w)
    s.add_body(body, **kw)


def block(s, init):
    """An asymmetric rigid body tumbling and falling: Euler's equations and the frames' terms."""
    _add(s, init, 0, rigid("block", 120.0, (4.0, 9.0, 11.0)), r=(0.5, 0.3, 1.0),
         rotation=(0.1, -0.2, 0.3), v=(V + 0.4, 0.3, 1.0), omega=(0.8, -0.6, 1.1))


def wheelset_on_a_spring(s, init):
    """A wheelset spinning at 22 rad/s (its non-spinning frame, the Resal frame of
    mbs/solver/body.py) held by a bushing to a block that flies free: the gyroscopic moments with
    the frames' yaw rate, and a force element between two bodies on two frames."""
    _add(s, init, 0, rigid("ws", 1200.0, (700.0, 120.0, 700.0), spin=True), r=(0.0, 0.0, 0.46),
         v=(V, 0.0, 0.0), omega=(0.05, V / 0.46, -0.03))
    _add(s, init, 1, rigid("frame", 2000.0, (900.0, 1500.0, 2000.0)), r=(1.2, 0.0, 0.7),
         v=(V, 0.05, 0.0))
    # on the block's marker first: the bushing's axes are the block's (a spinning body's
    # non-spinning frame is free to turn about the axle from one description to the other)
    b = Bushing("joint", s.marker("frame", at=(-1.2, 0.0, -0.24)), s.marker("ws"),
                k=(2e6, 3e6, 4e6, 0, 0, 0), c=(2e3,) * 3 + (0, 0, 0))
    if init is not None:              # unloaded where the line's build had it
        b.offset = init[0]["elements"][0].offset
    s.add(b)


def test_a_free_tumbling_body_moves_the_same_from_the_track_frames():
    _exact(block, {"r": 1e-9, "axle": 1e-10, "v": 1e-9, "omega": 1e-9})


def test_a_spinning_wheelset_on_a_spring_moves_the_same_from_the_track_frames():
    _exact(wheelset_on_a_spring, {"r": 1e-9, "axle": 1e-10, "v": 1e-8, "omega": 1e-8})


def test_through_a_transition_the_kink_costs_what_one_step_across_it_does():
    """From tangent track through the transition into the curve: the error stays within the
    first-order bound of the two cant kinks (where in a step a kink falls sets how much of it
    is made, so it does not fall steadily with the step)."""
    errs = []
    for dt in (2e-4, 5e-5):
        (m1, r1), (m0, r0) = _pair(block, 0.0, dt=dt, duration=1.5)
        errs.append(_worst(_inertial(m1, r1), _inertial(m0, r0)))
        d_omega = 14.0 * 0.15 / 10.0 / 1.5            # roll-rate step at the faster speed, rad/s
        bound = 2 * dt * d_omega * (1.2 + 15.0 * 1.5)
        assert errs[-1]["r"] < bound, (errs[-1], bound)


@pytest.fixture(scope="module")
def bar():
    return craig_bampton_bar(4)[2]


def test_a_free_flexible_body_moves_and_deforms_the_same_from_the_track_frames(bar):
    """A vibrating, tumbling flexible bar (FFRF, 4 modes): the modal inertia coupling sees the
    frames' motion through the inertial angular velocity alone."""
    def build(s, init):
        _add(s, init, 0, flexible("bar", bar, n_modes=4), r=(0.2, 0.1, 0.5),
             rotation=(0.3, 0.2, 0.1), v=(V, -0.5, 0.2), omega=(2.0, 5.0, -3.0),
             q=np.r_[0.002, 0.001, 0.0, 0.0], qd=np.linspace(0.05, -0.03, 4))
    _exact(build, {"r": 1e-9, "axle": 1e-9, "v": 1e-8, "omega": 1e-8, "q": 1e-10})
