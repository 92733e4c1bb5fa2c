"""The floating-frame multibody core against invariants and closed forms."""
import numpy as np
import pytest
from conftest import craig_bampton_bar
from scipy.integrate import solve_ivp

from axlebox._params import ParameterError
from axlebox.fem import interfaces
from axlebox.mbs.solver import ffrf_numpy as fn
from axlebox.mbs.solver import integrate
from axlebox.mbs.solver.body import add_point_masses, flexible, rigid
from axlebox.mbs.solver.elements import Bushing, Load
from axlebox.mbs.solver.system import System


@pytest.fixture(scope="module")
def bar():
    """A 1 m steel bar, Craig-Bampton: end_a clamped-ready (RBE2), end_b loaded (RBE3)."""
    return craig_bampton_bar(8)


def _spinning_bar(rb, n_modes):
    body = flexible("bar", rb, n_modes=n_modes)
    s = System(gravity=(0, 0, 0))
    q0 = np.zeros(n_modes)
    q0[:2] = (0.02, 0.01)
    s.add_body(body, r=(0.1, 0.2, 0.3), rotation=(0.3, 0.2, 0.1), v=(1.0, -0.5, 0.2),
               omega=(2.0, 5.0, -3.0), q=q0, qd=np.linspace(0.5, -0.3, n_modes))
    return s.assemble()


def test_free_flexible_body_keeps_momentum_and_energy(bar):
    """No loads, no damping: linear and angular momentum are invariants of the exact equations
    (1e-8 relative), energy too (1e-4); RK4 at 1e-5 s resolves the modes kept (< 900 Hz)."""
    _, _, rb = bar
    model = _spinning_bar(rb, 4)
    y0 = model.y0.copy()
    E0, (P0, H0) = model.energy(y0)["total"], model.momentum(y0)
    run = integrate.simulate(model, 1.0, integrate.Settings(method="rk4", dt=1e-5,
                                                            output_rate_hz=1000, state_rate_hz=10))
    assert run.ok, run.message
    E1, (P1, H1) = model.energy(run.y_end)["total"], model.momentum(run.y_end)
    assert np.linalg.norm(P1 - P0) / np.linalg.norm(P0) < 1e-8
    assert np.linalg.norm(H1 - H0) / np.linalg.norm(H0) < 1e-8
    assert abs(E1 - E0) / E0 < 1e-4
    # the elastic coordinates did move: the test exercises the coupling, not a rigid drift
    q = np.array([model.body_state(0, y)["q"] for y in run.states])
    assert np.ptp(q[:, 0]) > 0.02


def test_numba_kernel_matches_numpy_twin(bar):
    """Accelerations of the numba kernel equal M^-1 (Q - h) from the einsum twin."""
    _, _, rb = bar
    model = _spinning_bar(rb, 8)
    body = model.bodies[0]
    y = model.y0
    dy = model.rhs(0.0, y)
    st = model.body_state(0, y)
    M = fn.mass_matrix(body, st["A"], st["q"])
    h = fn.quadratic_velocity(body, st["A"], st["q"], st["omega"], st["qd"])
    Q = np.zeros(6 + body.n_modes)
    Q[6:] = -body.K @ st["q"] - body.D @ st["qd"]
    acc = np.linalg.solve(M, Q - h)
    iv = model.S.bi[0, 1]
    np.testing.assert_allclose(dy[iv:iv + 6 + body.n_modes], acc, rtol=1e-9, atol=1e-9 * np.abs(acc).max())


@pytest.mark.parametrize("spin", [False, True])
def test_rigid_closed_form_matches_the_full_mass_matrix_solve(bar, spin):
    """A rigid body whose frame is not at its centre of mass (the FE bar, its origin at one end;
    a spinning one too): the kernel's closed-form rigid path (Euler about the centre of mass,
    J_c = J_o - (|S|^2 I - S S^T)/m) gives M^-1 (Q - h) of the twin to 1e-9, with a load and
    moment on the body.  A point mass at one end moves the centre off the frame."""
    _, _, rb = bar
    body = flexible("bar", rb, rigid_only=True, spin=spin)
    add_point_masses(body, {"end_a": 6.0})
    assert np.linalg.norm(body.mc) > 0.05 * body.mass          # the frame is far off the centre
    s = System(gravity=(0, 0, -9.81))
    s.add_body(body, r=(0.1, 0.2, 0.3), rotation=(0.3, 0.2, 0.1), v=(1.0, -0.5, 0.2),
               omega=(2.0, 5.0, -3.0))
    m = s.marker("bar", at=(0.4, 0.01, -0.02))
    s.add(Load("push", m, force=(30.0, -20.0, 50.0), moment=(3.0, 1.0, -2.0)))
    model = s.assemble()
    y = model.y0
    dy = model.rhs(0.0, y)
    st = model.body_state(0, y)
    M = fn.mass_matrix(body, st["A"], st["q"])
    h = fn.quadratic_velocity(body, st["A"], st["q"], st["omega"], st["qd"])
    x = st["A"] @ np.array([0.4, 0.01, -0.02])
    F, Mo = np.array([30.0, -20.0, 50.0]), np.array([3.0, 1.0, -2.0])
    g = np.array([0, 0, -9.81])
    Q = np.concatenate([F + body.mass * g,
                        st["A"].T @ (np.cross(x, F) + Mo + np.cross(st["A"] @ body.mc, g))])
    acc = np.linalg.solve(M, Q - h)
    iv = model.S.bi[0, 1]
    np.testing.assert_allclose(dy[iv:iv + 6], acc, rtol=1e-9, atol=1e-9 * np.abs(acc).max())


def test_torque_free_symmetric_top_precesses_at_eulers_rate():
    """Axisymmetric rigid body, I1 = I2: in the body frame omega turns about the symmetry axis at
    Omega_p = (I3 - I1) / I1 w3 (Euler's equations, closed form; Goldstein, Classical
    Mechanics, 3rd ed., sec. 5.6)."""
    I1, I3 = 3.0, 5.0
    w0 = np.array([0.3, 0.0, 4.0])
    s = System(gravity=(0, 0, 0))
    s.add_body(rigid("top", 10.0, (I1, I1, I3)), omega=w0)
    model = s.assemble()
    T = 2.0
    run = integrate.simulate(model, T, integrate.Settings(method="rk4", dt=1e-4, output_rate_hz=100,
                                                          state_rate_hz=100))
    w = np.array([model.body_state(0, y)["omega"] for y in run.states])
    Op = (I3 - I1) / I1 * w0[2]
    exact = np.column_stack([0.3 * np.cos(Op * run.state_time), 0.3 * np.sin(Op * run.state_time),
                             np.full(run.state_time.size, 4.0)])
    np.testing.assert_allclose(w, exact, atol=1e-8)


def test_asymmetric_body_follows_eulers_equations_and_keeps_angular_momentum():
    """Tumbling asymmetric body against scipy's DOP853 on Euler's equations; |H| in space fixed."""
    J = np.array([1.0, 2.0, 3.0])
    w0 = np.array([0.1, 3.0, 0.2])        # near the unstable middle axis: a demanding case
    s = System(gravity=(0, 0, 0))
    s.add_body(rigid("box", 5.0, J), omega=w0)
    model = s.assemble()
    run = integrate.simulate(model, 3.0, integrate.Settings(method="rk4", dt=1e-4, output_rate_hz=100,
                                                            state_rate_hz=100))

    def euler(t, w):
        return [(J[1] - J[2]) / J[0] * w[1] * w[2], (J[2] - J[0]) / J[1] * w[2] * w[0],
                (J[0] - J[1]) / J[2] * w[0] * w[1]]
    ref = solve_ivp(euler, (0, 3.0), w0, method="DOP853", rtol=1e-12, atol=1e-12,
                    t_eval=run.state_time)
    w = np.array([model.body_state(0, y)["omega"] for y in run.states])
    np.testing.assert_allclose(w, ref.y.T, atol=1e-7)
    H = np.array([model.momentum(y)[1] for y in run.states])
    np.testing.assert_allclose(H, np.tile(H[0], (len(H), 1)), atol=1e-9)


def _full_fe_tip_deflection(fe, itf, F):
    """Full FE static solution (all DOFs, same RBE couplings): end_a master fixed, force F
    at end_b's master; returns end_b's master translation."""
    from axlebox.fem.linsolve import Factor
    cond = interfaces.condense(fe, itf)
    K = (cond.T.T @ fe.K @ cond.T).tocsr()
    a, b = cond.master_slice(0), cond.master_slice(1)
    keep = np.setdiff1d(np.arange(K.shape[0]), np.arange(a.start, a.stop))
    f = np.zeros(K.shape[0])
    f[b.start:b.start + 3] = F
    fac = Factor(K[keep][:, keep].tocsc())
    u = np.zeros(K.shape[0])
    u[keep] = fac.solve(f[keep])
    fac.free()
    return u[b.start:b.start + 3]


def test_cantilever_settles_to_the_full_fe_static_deflection(bar):
    """Craig-Bampton bar held at end_a by a stiff 6-DOF bushing to ground, static tip load:
    the damped dynamic run settles within 1 % of the full FE static deflection (the constraint
    modes make the CB static response exact; the bushing's compliance is 1e-5 of the bar's)."""
    fe, itf, rb = bar
    F = np.array([0.0, 300.0, -1500.0])
    exact = _full_fe_tip_deflection(fe, itf, F)
    body = flexible("bar", rb)
    w = 2 * np.pi * body.frequencies_hz
    body.D = np.diag(2 * 0.3 * w)      # heavy modal damping: the slowest clamped shape creeps in at ~0.12 s
    s = System(gravity=(0, 0, 0))
    s.add_body(body)
    ground = s.marker(None, at=(-0.5, 0, 0))
    clamp = s.marker("bar", node="end_a")
    tip = s.marker("bar", node="end_b")
    s.add(Bushing("clamp", ground, clamp, k=(1e11,) * 3 + (1e10,) * 3, c=(1e5,) * 3 + (1e4,) * 3))
    s.add(Load("tip", tip, force=F))
    model = s.assemble()
    run = integrate.simulate(model, 2.0, integrate.Settings(method="galpha", dt=1e-4,
                                                            output_rate_hz=1000, state_rate_hz=100))
    assert run.ok, run.message
    st = model.body_state(0, run.y_end)
    u_tip = st["r"] + st["A"] @ (body.nodes["end_b"][0] + body.nodes["end_b"][1][:3] @ st["q"]) \
        - np.array([0.5, 0, 0])
    np.testing.assert_allclose(u_tip, exact, rtol=0.01, atol=0.01 * np.abs(exact).max())
    assert abs(exact[2]) > 1e-3                         # a deflection worth measuring (mm)


def test_output_rate_above_step_rate_is_refused():
    with pytest.raises(ParameterError, match="output_rate_hz"):
        integrate.Settings(dt=1e-3, output_rate_hz=10_000)
    with pytest.raises(ParameterError, match="method"):
        integrate.Settings(method="euler")
    with pytest.raises(ParameterError, match="mass"):
        rigid("carbody", -1.0, (1, 1, 1))


def test_divergence_names_time_and_body():
    """A bushing far too stiff for the explicit step blows up; the run stops, says when and
    which body, and keeps what it computed."""
    s = System(gravity=(0, 0, -9.81))
    s.add_body(rigid("block", 1.0, (0.01, 0.01, 0.01)), r=(0, 0, 0.0))
    g = s.marker(None)
    m = s.marker("block")
    s.add(Bushing("too stiff", g, m, k=(1e12,) * 3 + (0,) * 3))
    model = s.assemble()
    run = integrate.simulate(model, 0.1, integrate.Settings(method="rk4", dt=1e-4, output_rate_hz=1e4))
    assert not run.ok
    assert "block" in run.message and "t = " in run.message
    assert 0 < run.time.size < 1001


def _block_on_spring(k, m, z0, c=0.0):
    s = System(gravity=(0, 0, 0))
    s.add_body(rigid("block", m, (0.01, 0.01, 0.01)), r=(0, 0, z0))
    g = s.marker(None)
    blk = s.marker("block")
    s.add(Bushing("spring", g, blk, k=(k,) * 3 + (0,) * 3, c=(c,) * 3 + (0,) * 3,
                  offset=(0, 0, 0)))
    return s.assemble()


def test_leapfrog_oscillates_at_its_closed_form_frequency_and_keeps_its_energy():
    """Undamped, the central-difference step turns a mode of frequency w into one of
    ``w_h = (2 / h) asin(w h / 2)`` with no amplitude error, and keeps the discrete energy
    ``m v_{n-1/2} v_{n+1/2} / 2 + k z_n^2 / 2`` exactly (Hughes, The Finite Element Method,
    1987, sec. 9.1; Belytschko, Liu and Moran 2000, sec. 6.2).  At ``w h = 0.8`` that is 3.0 %
    fast: the period over 40 cycles matches it to 0.1 %, not the exact one."""
    k, m, z0 = 4e4, 1.0, 0.01
    w = np.sqrt(k / m)                     # 200 rad/s
    h = 0.8 / w
    model = _block_on_spring(k, m, z0)
    run = integrate.simulate(model, 40 * 2 * np.pi / w, integrate.Settings(
        method="leapfrog", dt=h, output_rate_hz=1 / h, state_rate_hz=1 / h))
    assert run.ok, run.message
    z, t = run.states[:, 2], run.state_time
    up = np.flatnonzero((z[:-1] < 0) & (z[1:] >= 0))
    tc = t[up] - z[up] * (t[up + 1] - t[up]) / (z[up + 1] - z[up])
    period = np.diff(tc).mean()
    w_h = 2 / h * np.arcsin(w * h / 2)
    assert abs(period / (2 * np.pi / w_h) - 1) < 1e-3
    assert abs(period / (2 * np.pi / w) - 1) > 0.025
    v = run.states[1:, model.nq + 2]                    # v_{n-1/2}, n = 1, 2, ...
    E = 0.5 * m * v[:-1] * v[1:] + 0.5 * k * z[1:-1] ** 2
    np.testing.assert_allclose(E, E[0], rtol=1e-9)
    assert abs(E[0] / (0.5 * k * z0 ** 2) - 1) < (w * h) ** 2 / 4


def test_leapfrog_with_damping_follows_its_modified_equation():
    """The damping force sees the velocity half a step late, ``c u(t - h/2) ~ c u - (c h/2) u'``:
    the step solves ``(m - c h/2) z'' + c z' + k z = 0``, a first-order error in h (frequency
    up by ``zeta w h / 2``: on the car's 2.7 kHz axle-box mode at 1e-5 s, 2e-6).  Against the
    closed form of the true equation the error halves with the step; against that of the
    modified one it is far smaller and falls at second order."""
    k, m, z0 = 4e4, 1.0, 0.01
    w = np.sqrt(k / m)
    zeta = 0.05
    c = 2 * zeta * w * m
    model = _block_on_spring(k, m, z0, c=c)

    def free(t, mass):
        wn = np.sqrt(k / mass)
        z = c / (2 * mass * wn)
        wd = wn * np.sqrt(1 - z ** 2)
        return z0 * np.exp(-z * wn * t) * (np.cos(wd * t) + z * wn / wd * np.sin(wd * t))

    true, modified = [], []
    for h in (2e-4, 1e-4, 5e-5):
        run = integrate.simulate(model, 0.2, integrate.Settings(method="leapfrog", dt=h,
                                                                output_rate_hz=1e3,
                                                                state_rate_hz=1e3))
        t, z = run.state_time, run.states[:, 2]
        true.append(np.abs(z - free(t, m)).max())
        modified.append(np.abs(z - free(t, m - 0.5 * c * h)).max())
    assert all(1.8 < a / b < 2.2 for a, b in zip(true, true[1:])), true
    assert all(3.5 < a / b < 4.5 for a, b in zip(modified, modified[1:])), modified
    assert all(a < 0.1 * b for a, b in zip(modified, true))


def test_leapfrog_run_continued_from_its_end_state_goes_on_as_if_unbroken():
    """The leapfrog's end state holds its velocities half a step behind; ``continued=True``
    picks them up as such: 0.1 s + 0.1 s equals 0.2 s to the last bit, and a fresh start from
    the same state (a half kick again) does not."""
    k, m = 4e4, 1.0
    model = _block_on_spring(k, m, 0.01, c=20.0)
    s = integrate.Settings(method="leapfrog", dt=1e-4, output_rate_hz=1e3, state_rate_hz=1e3)
    whole = integrate.simulate(model, 0.2, s)
    first = integrate.simulate(model, 0.1, s)
    second = integrate.simulate(model, 0.1, s, y0=first.y_end, t0=0.1, continued=True)
    np.testing.assert_array_equal(second.y_end, whole.y_end)
    np.testing.assert_array_equal(second.states, whole.states[100:])
    fresh = integrate.simulate(model, 0.1, s, y0=first.y_end, t0=0.1)
    assert not np.array_equal(fresh.y_end, whole.y_end)


@pytest.mark.parametrize("method", ["leapfrog", "rk4", "galpha"])
def test_streamed_outputs_are_the_kept_runs(method):
    """``sink``: the outputs handed over chunk by chunk, in order, joined, are the kept run's to
    the last bit (chunks of 0.0123 s = 123 outputs, a snapshot every 7th: neither divides the
    other), and nothing is kept; a diverging run hands over what it computed, the output that
    showed the divergence included, as the kept run keeps it."""
    model = _block_on_spring(4e4, 1.0, 0.01, c=20.0)
    s = integrate.Settings(method=method, dt=1e-4, output_rate_hz=1e4, state_rate_hz=1e4 / 7)
    kept = integrate.simulate(model, 0.1, s, chunk=0.0123)
    got, starts = {}, []

    def sink(k0, arrays):
        starts.append(k0)
        for name, a in arrays.items():
            got.setdefault(name, []).append(a.copy())
    streamed = integrate.simulate(model, 0.1, s, chunk=0.0123, sink=sink)
    assert starts == list(range(0, 1001, 123)) and streamed.time.size == 0
    joined = {name: np.concatenate(parts) for name, parts in got.items()}
    np.testing.assert_array_equal(joined["out_t"], kept.time)
    np.testing.assert_array_equal(joined["out_y"], kept.states)
    np.testing.assert_array_equal(joined["out_el"][:, :1], kept.elements)
    np.testing.assert_array_equal(streamed.y_end, kept.y_end)

    s = System(gravity=(0, 0, -9.81))          # as test_divergence_names_time_and_body
    s.add_body(rigid("block", 1.0, (0.01, 0.01, 0.01)), r=(0, 0, 0.0))
    s.add(Bushing("too stiff", s.marker(None), s.marker("block"), k=(1e12,) * 3 + (0,) * 3))
    model = s.assemble()
    st = integrate.Settings(method="rk4", dt=1e-4, output_rate_hz=1e4)
    kept = integrate.simulate(model, 0.1, st, chunk=0.0005)
    got = []
    streamed = integrate.simulate(model, 0.1, st, chunk=0.0005,
                                  sink=lambda k0, a: got.append(a["out_t"].copy()))
    assert not kept.ok and streamed.message == kept.message
    np.testing.assert_array_equal(np.concatenate(got), kept.time)
