"""Tangential contact: Kalker's coefficients, FASTSIM, Shen-Hedrick-Elkins, creepages."""
import numpy as np
import pytest
from scipy.integrate import quad

from axlebox._params import ParameterError
from axlebox.mbs.wheelrail import kalker
from axlebox.mbs.wheelrail import tangential as tg

# a realistic tread contact: semi-axes 6 mm x 4 mm, 70 kN, steel
A_, B_, N_, MU, G_, NU = 6e-3, 4e-3, 7e4, 0.3, 8.1e10, 0.28

# ---------------------------------------------------------------- Kalker's coefficients
# shared/REFERENCE_DATA.md "Wheel-rail contact": Kalker 1990 Table E.3, nu = 0.25
REF_NU_QUARTER = {0.1: (3.31, 2.52, 0.473, 8.28), 0.2: (3.37, 2.63, 0.603, 4.27),
                  0.5: (3.62, 3.01, 0.929, 1.93), 0.8: (3.91, 3.41, 1.25, 1.37),
                  1.0: (4.12, 3.67, 1.47, 1.19), 1.25: (4.36, 3.99, 1.75, 1.04),
                  2.0: (5.10, 4.90, 2.62, 0.819), 5.0: (7.78, 8.14, 6.63, 0.601),
                  10.0: (11.7, 12.8, 14.6, 0.526)}


@pytest.mark.parametrize("ab", sorted(REF_NU_QUARTER))
def test_kalker_reproduces_reference_data_column_exactly(ab):
    C = kalker.creep_coefficients(ab, 0.25)
    np.testing.assert_allclose(C, REF_NU_QUARTER[ab], rtol=1e-12)


def test_kalker_interpolation_reproduces_every_table_node():
    for j, nu in enumerate(kalker.NU_NODES):
        C = np.array(kalker.creep_coefficients(kalker.AB_NODES, nu))
        for i, name in enumerate(("C11", "C22", "C23", "C33")):
            np.testing.assert_allclose(C[i], kalker.TABLE_E3[name][:, j], rtol=1e-12)
    # Kalker's table has C11 = C22 for nu = 0 (a property, not an interpolation artefact)
    np.testing.assert_allclose(*kalker.creep_coefficients(np.geomspace(0.1, 10, 31), 0.0)[:2])


def test_kalker_is_smooth_across_the_circle():
    # one spline through both branches: value and slope continuous at a/b = 1 (the table's
    # own slope there is about 0.5 - 1.4 per unit ln(a/b)); one-sided slopes agree to 1 %
    h = 1e-4
    for nu in (0.0, 0.28, 0.5):
        lo, mid, hi = (np.array(kalker.creep_coefficients(np.exp(s), nu)) for s in (-h, 0, h))
        left, right = (mid - lo) / h, (hi - mid) / h
        np.testing.assert_allclose(left, right, rtol=1e-2)
        np.testing.assert_allclose(lo, hi, rtol=2e-3)


def test_kalker_spline_does_not_overshoot_between_nodes():
    s = np.log(kalker.AB_NODES)
    fine = np.linspace(s[0], s[-1], 1201)
    i = np.clip(np.searchsorted(s, fine) - 1, 0, len(s) - 2)
    for j, nu in enumerate(kalker.NU_NODES):
        C = kalker.creep_coefficients(np.exp(fine), nu)
        for c, name in zip(C, ("C11", "C22", "C23", "C33")):
            t = kalker.TABLE_E3[name][:, j]
            lo, hi = np.minimum(t[i], t[i + 1]), np.maximum(t[i], t[i + 1])
            assert np.all(c >= lo * (1 - 1e-3)) and np.all(c <= hi * (1 + 1e-3))


def test_kalker_is_continuous_at_the_table_edges_and_tends_to_the_asymptotes():
    for nu in (0.0, 0.28, 0.5):
        for edge in (0.1, 10.0):
            inside = np.array(kalker.creep_coefficients(edge, nu))
            outside = np.array(kalker.creep_coefficients(edge * (0.999 if edge < 1 else 1.001), nu))
            np.testing.assert_allclose(outside, inside, rtol=5e-3)
        # slender ellipse a << b: C11 -> pi^2 / (4 (1 - nu)), C22 -> pi^2 / 4 (Kalker 1990)
        C11, C22, _, _ = kalker.creep_coefficients(1e-5, nu)
        assert C11 == pytest.approx(np.pi ** 2 / (4 * (1 - nu)), rel=1e-3)
        assert C22 == pytest.approx(np.pi ** 2 / 4, rel=1e-3)


def test_kalker_nu_interpolation_lies_between_the_columns():
    for ab in (0.3, 1.0, 3.0):
        c0, c25, c50 = (np.array(kalker.creep_coefficients(ab, nu)) for nu in (0.0, 0.25, 0.5))
        c30 = np.array(kalker.creep_coefficients(ab, 0.3))
        assert np.all((c30 - c25) * (c50 - c25) >= 0) and np.all(np.abs(c30 - c25) <= np.abs(c50 - c25))


def test_linear_law_signs_and_values():
    # Kalker's law with the circle's coefficients (a/b = 1, nu = 1/4: 4.12, 3.67, 1.47, 1.19)
    a = b = 5e-3
    Fx, Fy, Mz = kalker.linear_creep_forces(1e-3, 2e-3, 0.5, a, b, 8e10, 0.25)
    c = 5e-3
    assert Fx == pytest.approx(-8e10 * c ** 2 * 4.12 * 1e-3, rel=1e-12)
    assert Fy == pytest.approx(-8e10 * (c ** 2 * 3.67 * 2e-3 + c ** 3 * 1.47 * 0.5), rel=1e-12)
    assert Mz == pytest.approx(8e10 * (c ** 3 * 1.47 * 2e-3 - c ** 4 * 1.19 * 0.5), rel=1e-12)


# ---------------------------------------------------------------- FASTSIM
@pytest.mark.parametrize("bound", ["parabolic", "elliptic"])
@pytest.mark.parametrize("ab", [0.5, 1.0, 2.0])
def test_fastsim_linear_limit_is_kalkers_linear_law(ab, bound):
    # 2 %: the discretisation error of the adhesion limit is 1/(2 ny^2) = 0.2 % (Fx, Fy(eta))
    a, b = 5e-3 * np.sqrt(ab), 5e-3 / np.sqrt(ab)
    C11, C22, C23, _ = kalker.creep_coefficients(ab, NU)
    c = np.sqrt(a * b)
    s = 1e-6
    Fx = tg.fastsim(s, 0, 0, a, b, N_, MU, G_, NU, bound=bound)[0]
    Fy_eta = tg.fastsim(0, s, 0, a, b, N_, MU, G_, NU, bound=bound)[1]
    Fy_phi = tg.fastsim(0, 0, s, a, b, N_, MU, G_, NU, bound=bound)[1]
    assert Fx / (-G_ * c ** 2 * C11 * s) == pytest.approx(1.0, abs=0.02)
    assert Fy_eta / (-G_ * c ** 2 * C22 * s) == pytest.approx(1.0, abs=0.02)
    assert Fy_phi / (-G_ * c ** 3 * C23 * s) == pytest.approx(1.0, abs=0.02)


@pytest.mark.parametrize("bound", ["parabolic", "elliptic"])
def test_fastsim_saturates_at_mu_n(bound):
    # full sliding: every element at the bound, whose discrete sum is mu N by construction
    Fx, Fy, _ = tg.fastsim(0.1, 0, 0, A_, B_, N_, MU, G_, NU, bound=bound)
    assert -Fx == pytest.approx(MU * N_, rel=0.01) and abs(Fy) < 1e-9 * MU * N_
    Fx, Fy, _ = tg.fastsim(0.05, -0.05, 0.2, A_, B_, N_, MU, G_, NU, bound=bound)
    assert np.hypot(Fx, Fy) == pytest.approx(MU * N_, rel=0.01)
    assert Fx < 0 < Fy


def test_no_load_no_force():
    for update in tg.UPDATES:
        assert tg.fastsim(1e-3, 1e-3, 0.5, A_, B_, 0.0, MU, G_, NU, update=update) == (0, 0, 0)
    assert tg.shen_hedrick_elkins(1e-3, 1e-3, 0.5, A_, B_, 0.0, MU, G_, NU) == (0, 0, 0)


def test_weighted_flexibility_saturates_opposite_the_creepage():
    # Kalker's single weighted L: the trial traction always points along -(xi, eta)
    Fx, Fy, _ = tg.fastsim(0.05, 0.03, 0, A_, B_, N_, MU, G_, NU, flex="weighted")
    assert np.arctan2(-Fy, -Fx) == pytest.approx(np.arctan2(0.03, 0.05), abs=1e-9)


@pytest.mark.parametrize("update", ["rotate", "cutback"])
@pytest.mark.parametrize("bound", ["parabolic", "elliptic"])
def test_fastsim_mirror_symmetry(update, bound):
    # y -> -y maps (xi, eta, phi) to (xi, -eta, -phi) and (Fx, Fy, Mz) to (Fx, -Fy, -Mz)
    kw = dict(bound=bound, update=update)
    for xi, eta, phi in [(2e-3, 1e-3, 0.3), (-1e-3, 4e-3, -1.5), (5e-4, -2e-3, 0.8)]:
        F = np.array(tg.fastsim(xi, eta, phi, A_, B_, N_, MU, G_, NU, **kw))
        M = np.array(tg.fastsim(xi, -eta, -phi, A_, B_, N_, MU, G_, NU, **kw))
        np.testing.assert_allclose(M, F * [1, -1, -1], rtol=1e-12, atol=1e-12 * MU * N_)
        # xi -> -xi without spin: Fx changes sign, Fy and Mz do not
        P = np.array(tg.fastsim(xi, eta, 0, A_, B_, N_, MU, G_, NU, **kw))
        Q = np.array(tg.fastsim(-xi, eta, 0, A_, B_, N_, MU, G_, NU, **kw))
        np.testing.assert_allclose(Q, P * [-1, 1, 1], rtol=1e-12, atol=1e-12 * MU * N_)


def _sweep(n=60, seed=3):
    rng = np.random.default_rng(seed)
    return (rng.uniform(-0.01, 0.01, n), rng.uniform(-0.01, 0.01, n), rng.uniform(-1, 1, n))


def test_fastsim_default_grid_is_converged_to_one_percent():
    # doubling nx and ny changes no force by more than 1 % of mu N at tread creepages
    xi, eta, phi = _sweep()
    for bound in ("parabolic", "elliptic"):
        F = np.array(tg.fastsim(xi, eta, phi, A_, B_, N_, MU, G_, NU, bound=bound))
        R = np.array(tg.fastsim(xi, eta, phi, A_, B_, N_, MU, G_, NU, bound=bound,
                                nx=2 * tg.NX, ny=2 * tg.NY))
        assert np.max(np.hypot(*(F - R)[:2])) < 0.01 * MU * N_
        assert np.max(np.abs(F - R)[2]) < 0.01 * MU * N_ * np.sqrt(A_ * B_)


def test_cutback_update_is_continuous_in_the_creepage_and_rotate_is_not():
    """Newton in the implicit integrator needs forces continuous in the state.  Sweeping xi
    finely at fixed lateral and spin creepage (8 x 8 grid, where the trial traction turns away
    from the previous one): Kalker's cut-back changes by at most twice the typical step between
    neighbouring samples (it meets the bound continuously), while the rotation step jumps, by
    0.1-0.6 % of mu N at once, where an element turns from stick to slip (its direction turns
    by a finite angle)."""
    s = np.linspace(-3e-3, 3e-3, 20001)
    for eta, phi in ((2e-3, 2.0), (-5e-4, 1.0), (0.0, 3.0)):
        for update, smooth in (("cutback", True), ("rotate", False)):
            F = np.array(tg.fastsim(s, eta, phi, A_, B_, N_, MU, G_, NU, update=update,
                                    nx=8, ny=8))
            step = np.hypot(*np.diff(F[:2], axis=1))
            assert (step.max() < 2 * np.median(step)) == smooth, (update, eta, phi)


def test_both_slip_updates_converge_to_the_same_simplified_theory():
    # Kalker's cut-back is first order in 1/nx, the rotation second order: fine grids agree
    xi, eta, phi = _sweep(20)
    kw = dict(nx=400, ny=16)
    R = np.array(tg.fastsim(xi, eta, phi, A_, B_, N_, MU, G_, NU, update="rotate", **kw))
    C = np.array(tg.fastsim(xi, eta, phi, A_, B_, N_, MU, G_, NU, update="cutback", **kw))
    assert np.max(np.hypot(*(R - C)[:2])) < 2e-3 * MU * N_


def _simplified_theory_pure_xi(xi, a, b, N, mu, G, nu):
    """Kalker's simplified theory, pure creepage, parabolic bound, solved in closed form on
    each strip (stick from the leading edge up to x* = d - a_y, d = xi/(L1 k), slip behind),
    then integrated over y: the continuum limit FASTSIM must converge to."""
    L1 = tg.flexibilities(a, b, G, nu)[0]
    k = mu * 2.0 * N / (np.pi * a * b) / a ** 2          # bound g = k (a_y^2 - x^2)
    d = abs(xi) / (L1 * k)

    def strip(y):
        ay = a * np.sqrt(1.0 - (y / b) ** 2)
        if d >= 2.0 * ay:
            return k * 4.0 * ay ** 3 / 3.0                   # the whole strip slips
        xs = d - ay
        return abs(xi) / L1 * (2 * ay - d) ** 2 / 2 + k * (ay ** 2 * xs - xs ** 3 / 3 + 2 * ay ** 3 / 3)

    yk = b * np.sqrt(max(0.0, 1.0 - (d / (2 * a)) ** 2))
    val = 2.0 * quad(strip, 0.0, b, points=[yk] if 0 < yk < b else None, limit=200)[0]
    return -np.sign(xi) * val


def test_fastsim_converges_to_the_closed_form_simplified_theory():
    for xi in (1e-4, 1e-3, 2e-3, 4e-3, 1e-2):
        ref = _simplified_theory_pure_xi(xi, A_, B_, N_, MU, G_, NU)
        F = tg.fastsim(xi, 0, 0, A_, B_, N_, MU, G_, NU)[0]
        Ff = tg.fastsim(xi, 0, 0, A_, B_, N_, MU, G_, NU, nx=64, ny=64)[0]
        assert abs(F - ref) < 3e-3 * MU * N_
        assert abs(Ff - ref) < 3e-4 * MU * N_


def test_fastsim_pure_creepage_follows_johnson_vermeulen_on_a_circle():
    # Johnson & Vermeulen (1964), J. Appl. Mech. 31, 338-340: F/(mu N) = 1 - (1 - tau)^3 for
    # tau < 1, here with the initial slope of Kalker's linear theory, tau = G c^2 C11 xi/(3 mu N)
    # (the form Shen, Hedrick & Elkins adopted).  FASTSIM's strips saturate one after the
    # other while the formula is one cubic: they differ by up to 1.1 % of mu N; 3 %.
    a = b = 5e-3
    C11 = kalker.creep_coefficients(1.0, NU)[0]
    xi_sat = 3 * MU * N_ / (G_ * a * b * C11)
    tau = np.linspace(0.05, 1.2, 24)
    F = -tg.fastsim(tau * xi_sat, 0, 0, a, b, N_, MU, G_, NU)[0] / (MU * N_)
    jv = 1 - (1 - np.minimum(tau, 1.0)) ** 3
    np.testing.assert_allclose(F, jv, atol=0.03)


@pytest.mark.parametrize("update", ["rotate", "cutback"])
@pytest.mark.parametrize("bound", ["parabolic", "elliptic"])
def test_numpy_version_agrees_with_the_kernel(bound, update):
    xi, eta, phi = _sweep(40)
    kw = dict(bound=bound, update=update, nx=13, ny=11)
    F = np.array(tg.fastsim(xi, eta, phi, A_, B_, N_, MU, G_, NU, **kw))
    P = np.array(tg.fastsim_numpy(xi, eta, phi, A_, B_, N_, MU, G_, NU, **kw))
    np.testing.assert_allclose(P, F, rtol=0, atol=1e-10 * MU * N_)


def test_traction_map_sticks_at_the_leading_edge_and_slips_behind():
    tr = tg.fastsim_traction(2e-3, 1e-3, 0.2, A_, B_, N_, MU, G_, NU)
    assert (tr.Fx, tr.Fy, tr.Mz) == pytest.approx(tg.fastsim(2e-3, 1e-3, 0.2, A_, B_, N_, MU,
                                                             G_, NU), rel=1e-12)
    mid = tg.NY // 2
    assert not tr.slip[mid, 0] and tr.slip[mid, -1]           # leading edge is column 0
    assert np.all(np.hypot(tr.px, tr.py) <= MU * tr.pn * (1 + 1e-12))
    dA = np.diff(tr.x, axis=1)[:, :1] * -1 * np.diff(tr.y[:2, 0])   # element areas per strip
    assert np.sum(tr.pn * dA) == pytest.approx(N_, rel=1e-12)
    more = tg.fastsim_traction(4e-3, 2e-3, 0.4, A_, B_, N_, MU, G_, NU)
    assert more.slip.sum() > tr.slip.sum()


# ---------------------------------------------------------------- Shen-Hedrick-Elkins
def test_she_is_linear_for_small_creepage_and_saturates():
    lin = np.array(kalker.linear_creep_forces(1e-7, -2e-7, 1e-5, A_, B_, G_, NU))
    she = np.array(tg.shen_hedrick_elkins(1e-7, -2e-7, 1e-5, A_, B_, N_, MU, G_, NU))
    np.testing.assert_allclose(she, lin, rtol=1e-3)
    for xi, eta in [(0.05, 0.0), (0.03, -0.04), (0.0, 0.2)]:
        Fx, Fy, _ = tg.shen_hedrick_elkins(xi, eta, 0.0, A_, B_, N_, MU, G_, NU)
        assert np.hypot(Fx, Fy) == pytest.approx(MU * N_, rel=1e-12)
    # the saturation curve is continuous with zero slope at beta = 3
    C11 = kalker.creep_coefficients(A_ / B_, NU)[0]
    xi3 = 3 * MU * N_ / (G_ * A_ * B_ * C11)
    below = -tg.shen_hedrick_elkins(xi3 * (1 - 1e-6), 0, 0, A_, B_, N_, MU, G_, NU)[0]
    assert below == pytest.approx(MU * N_, rel=1e-10)


def test_she_mirrors():
    F = np.array(tg.shen_hedrick_elkins(2e-3, 1e-3, 0.3, A_, B_, N_, MU, G_, NU))
    M = np.array(tg.shen_hedrick_elkins(2e-3, -1e-3, -0.3, A_, B_, N_, MU, G_, NU))
    np.testing.assert_allclose(M, F * [1, -1, -1], rtol=1e-12)
    Q = np.array(tg.shen_hedrick_elkins(-2e-3, 1e-3, 0.0, A_, B_, N_, MU, G_, NU))
    P = np.array(tg.shen_hedrick_elkins(2e-3, 1e-3, 0.0, A_, B_, N_, MU, G_, NU))
    np.testing.assert_allclose(Q, P * [-1, 1, 1], rtol=1e-12)


# ---------------------------------------------------------------- creepages
def _rot_z(psi):
    c, s = np.cos(psi), np.sin(psi)
    return np.array([[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]])


def _exact_wheelset(y_dot, psi, psi_dot, V, r_L, r_R, r0, d_L, d_R, l):
    """Rigid wheelset in 3-D (x forward, y left, z up): creepages by the generic function."""
    Rz = _rot_z(psi)
    y_axle = Rz @ [0.0, 1.0, 0.0]
    omega = (V / r0) * y_axle + np.array([0.0, 0.0, psi_dot])
    v_c = np.array([V, y_dot, 0.0])
    out = []
    for side, r, d in ((+1, r_L, d_L), (-1, r_R, d_R)):
        rho = side * l * y_axle - r * np.array([0.0, 0.0, 1.0])
        dv = v_c + np.cross(omega, rho)                       # the rail does not move
        n = np.array([0.0, -side * np.sin(d), np.cos(d)])     # leans towards the track centre
        t1 = np.array([1.0, 0.0, 0.0])
        out.append(tg.creepages(dv, omega, t1, np.cross(n, t1), n, V))
    return out


def test_generic_creepages_reproduce_the_linearised_wheelset_formulas():
    V, r0, l = 20.0, 0.42, 0.7465
    base = dict(r_L=r0 + 0.002, r_R=r0 - 0.002, r0=r0, d_L=0.06, d_R=0.03, l=l)
    errs = []
    for scale in (1.0, 0.5):
        motion = dict(y_dot=0.05 * scale, psi=1e-3 * scale, psi_dot=0.03 * scale)
        r_L = r0 + 0.004 * scale
        r_R = r0 - 0.004 * scale
        kw = dict(base, r_L=r_L, r_R=r_R)
        exact = _exact_wheelset(V=V, **motion, **kw)
        lin = tg.wheelset_creepages(motion["y_dot"], motion["psi"], motion["psi_dot"], V, r_L,
                                    r_R, r0, kw["d_L"], kw["d_R"], l)
        for e, s in zip(exact, lin):
            # second-order terms: psi^2/2 ~ 5e-7, psi * xi ~ 1e-5 (creepages here ~ 1e-2, 1e-3)
            np.testing.assert_allclose(e, s, rtol=0, atol=2e-5 * scale ** 2)
        errs.append(max(np.max(np.abs(np.subtract(e, s))) for e, s in zip(exact, lin)))
    # the difference is second order in the motion: halving it quarters the difference
    assert errs[1] < 0.3 * errs[0]


def test_creepages_of_pure_rolling_are_zero():
    V, r0 = 30.0, 0.46
    L, R = tg.wheelset_creepages(0.0, 0.0, 0.0, V, r0, r0, r0, 0.0, 0.0, 0.75)
    assert np.allclose(L, 0) and np.allclose(R, 0)


# ---------------------------------------------------------------- bad input
@pytest.mark.parametrize("kwargs, field", [
    (dict(N=-1.0), "N"), (dict(mu=0.0), "mu"), (dict(mu=-0.2), "mu"), (dict(a=0.0), "a"),
    (dict(b=-1e-3), "b"), (dict(nu=0.6), "nu"), (dict(nu=-0.1), "nu"), (dict(G=0.0), "G"),
    (dict(bound="hertzian"), "bound"), (dict(update="euler"), "update"),
    (dict(flex="single"), "flex"), (dict(nx=0), "nx"), (dict(ny=2.5), "ny"),
    (dict(xi=np.nan), "xi"),
])
def test_fastsim_refuses_bad_input_naming_the_field(kwargs, field):
    args = dict(xi=1e-3, eta=0.0, phi=0.0, a=A_, b=B_, N=N_, mu=MU, G=G_, nu=NU)
    args.update(kwargs)
    with pytest.raises(ParameterError, match=rf"\b{field} = "):
        tg.fastsim(**args)


def test_other_functions_refuse_bad_input():
    with pytest.raises(ParameterError, match=r"\bN = "):
        tg.shen_hedrick_elkins(1e-3, 0, 0, A_, B_, -5.0, MU, G_, NU)
    with pytest.raises(ParameterError, match=r"\bmu = "):
        tg.shen_hedrick_elkins(1e-3, 0, 0, A_, B_, N_, 0.0, G_, NU)
    with pytest.raises(ParameterError, match=r"\bnu = "):
        kalker.creep_coefficients(1.0, 0.55)
    with pytest.raises(ParameterError, match=r"\ba_over_b = "):
        kalker.creep_coefficients(-1.0, 0.3)
    with pytest.raises(ParameterError, match=r"\bV = "):
        tg.creepages([1, 0, 0], [0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1], 0.0)
