"""The plain-numpy twin of the DTRB kernel (axlebox.bearing.kernel.numpy_twin) against the numba kernel, and
both closed-form line integrals against quadrature."""
import numpy as np
import pytest
from scipy.integrate import quad

from axlebox.bearing.kernel import dispatch
from axlebox.bearing import defects, models

from axlebox.bearing.statics import equilibrium

from axlebox.bearing.kernel import layout
from axlebox.bearing.kernel.contact import line_integrals
from axlebox.bearing.kernel.evaluate import rates
from axlebox.bearing.kernel.numpy_twin import dtrb_rhs_numpy, line_integrals_numpy
from axlebox.bearing.kernel.layout import CPHI, CTX, CTZ, CX, CY, CZ, ETA, PHI, PSI, RHO, TH_S, TH_T
from axlebox.bearing.models.params import BearingParams

OMEGA = 2 * np.pi * 5.05
RTOL = 1e-9


@pytest.fixture(scope="module")
def start():
    """Default bearing with a 2 mm defect on row 2 at angle 0, quasi-static under 54 kN."""
    p = BearingParams()
    P = models.pack(p)
    D = defects.table((defects.Defect(W=2e-3),), p)
    y, uo = equilibrium.static_state(p, P, D, (0.0, 0.0, -54e3), OMEGA)
    return p, P, D, y, equilibrium.ring_motion(OMEGA, uo)


def perturbed(p, y, ring, seed=1):
    """The start shaken: rollers, cages (into pocket walls and side beams) and rings moving."""
    rng = np.random.default_rng(seed)
    y = y.copy()
    rol, cag = layout.views(y, p.Z)
    sh = rol.shape[:2]
    for q, scale in ((RHO, 1e-6), (ETA, 1e-6), (PHI, 1e-3), (TH_T, 1e-4), (TH_S, 1e-4), (PSI, 1e-2)):
        rol[..., q] += scale * rng.standard_normal(sh)
    for q, scale in ((RHO, 1e-3), (ETA, 1e-3), (PHI, 0.1), (TH_T, 0.1), (TH_S, 0.1), (PSI, 1.0)):
        rol[..., 6 + q] += scale * rng.standard_normal(sh)
    cag[:, CX] += 0.2e-3
    cag[:, CY] += 0.3e-3
    cag[:, CZ] += 0.05e-3 * rng.standard_normal(2)
    cag[:, CTX] += 1e-3
    cag[:, CTZ] -= 5e-4
    cag[:, CPHI] += 1e-3 * rng.standard_normal(2)
    cag[:, 6:12] += np.array([1e-3, -2e-3, 5e-4, 0.05, -0.05, 0.3]) * rng.standard_normal((2, 6))
    ring = ring.copy()
    ring[0, [3, 5, 9, 11]] = 1e-4, -5e-5, 0.02, -0.03
    ring[1, [3, 4, 5]] = -8e-5, 0.01, 6e-5
    ring[1, 6:12] = 1e-3, -2e-3, 5e-3, 0.1, 0.2, -0.1
    return y, ring


TAG = dispatch.tag(BearingParams())


def both(y, ring, P, D):
    yd, F, Qc, _ = rates(TAG, 0.0, y, ring, P, D)
    return (yd, F, Qc), dtrb_rhs_numpy(0.0, y, ring, P, D)


def assert_same(y, ring, P, D):
    ref, out = both(y, ring, P, D)
    for name, a, b in zip(("ydot", "F", "Qc"), out, ref):
        assert a.shape == b.shape, name
        assert np.all(np.isfinite(a)), name
        err = np.abs(a - b).max()
        assert err <= RTOL * max(np.abs(b).max(), 1e-300), (name, err, np.abs(b).max())
    return ref


def test_quasi_static_start(start):
    p, P, D, y, ring = start
    _, F, Qc = assert_same(y, ring, P, D)
    assert abs(F[1, 2] - 54e3) < 1.0          # the bearing carries the 54 kN on the outer ring


def test_perturbed_contacts(start):
    p, P, D, y, ring = start
    y, ring = perturbed(p, y, ring)
    _, _, Qc = assert_same(y, ring, P, D)
    for q in (layout.Q_O, layout.Q_I, layout.Q_A, layout.Q_CR1, layout.Q_CR2, layout.Q_SIDE):
        assert (Qc[..., q] > 0).any(), q      # every contact law is exercised


@pytest.mark.parametrize("kw", [dict(damping="paper"), dict(cage="kinematic"),
                                dict(damping="paper", cage="kinematic"),
                                dict(damping="stiffness", beta=5e-5)])
def test_variants(start, kw):
    p, _, D, y0, ring0 = start
    p2 = BearingParams(**kw)
    P2 = models.pack(p2)
    assert_same(y0, ring0, P2, D)
    for seed in (1, 2):
        y, ring = perturbed(p2, y0, ring0, seed)
        assert_same(y, ring, P2, D)


def test_defect(start):
    p, P, D, y, ring = start
    none = defects.table((), p)
    rol, _ = layout.views(y, p.Z)
    assert rol[1, 0, PHI] == 0.0             # roller k = 0 of row 2 sits in the defect's middle
    _, _, Q = assert_same(y, ring, P, D)
    _, _, Q0 = assert_same(y, ring, P, none)
    assert Q0[1, 0, 0] > 1e3 and Q[1, 0, 0] < Q0[1, 0, 0]
    assert np.array_equal(Q[0], Q0[0])        # row 1 has no defect

    # at the defect's edge (shallow), and a short defect covering part of the contact line
    d = defects.Defect(W=2e-3)
    y2 = y.copy()
    layout.views(y2, p.Z)[0][1, 0, PHI] = -0.5 * d.tau(p) + 0.03 * d.tau(p)
    short = defects.table((defects.Defect(W=2e-3, L=8e-3, offset=-6e-3),), p)
    for Dx in (D, short):
        _, _, Qd = assert_same(y2, ring, P, Dx)
        _, _, Qn = assert_same(y2, ring, P, none)
        assert 0.0 < Qd[1, 0, 0] < Qn[1, 0, 0]
    y3, ring3 = perturbed(p, y, ring)
    assert_same(y3, ring3, P, short)


@pytest.mark.parametrize("r_e", [0.0, 0.3e-3])
def test_a_defect_with_edges_is_the_rollers_centre_path_over_them(start, r_e):
    """profile = 'edges' (bearing/defects.py): a rigid roller of radius r_b pivoting on the pit's
    edges, rounded to r_e, drops by rho - sqrt(rho^2 - (d - r_e)^2), rho = r_b + r_e, at arc
    distance d from the nearer edge; with sharp edges its middle is Eq. (14)'s depth A, and the
    path breaks there by the closed-form slope (W/2 - r_e) / sqrt(rho^2 - (W/2 - r_e)^2)."""
    from axlebox.bearing.kernel import numpy_twin
    p, P, _, y, ring = start
    d = defects.Defect(W=2e-3, profile="edges", edge_radius=r_e)
    D = defects.table((d,), p)
    tau, R, rho = d.tau(p), 0.5 * p.D_o, p.r_b + r_e
    x = np.linspace(0.0, tau, 2001)[1:-1]
    arc = np.minimum(x, tau - x) * R
    e = np.clip(arc - r_e, 0.0, None)
    ref = e ** 2 / (rho + np.sqrt(rho ** 2 - e ** 2))          # rho - sqrt(rho^2 - e^2)
    ref = np.minimum(ref, D[0, 4])           # capped at the chord's W/2 (the arc is a hair longer)
    got = np.array([defects.depth_under(D, layout.OUTER_RING, 1, D[0, 2] + xi, 0.0)[0] for xi in x])
    np.testing.assert_allclose(got, ref, rtol=1e-12, atol=1e-18)
    phi = np.zeros((2, x.size))
    phi[1] = D[0, 2] + x
    np.testing.assert_allclose(numpy_twin._defect(D, 0.0, phi, 0.0)[0][1], got, rtol=1e-12, atol=1e-18)
    if r_e == 0.0:
        assert got.max() == pytest.approx(defects.Defect(W=2e-3).depth(p), rel=1e-3)
    half = 0.5 * tau * R - r_e
    slope = np.gradient(got, x * R)
    mid = x.size // 2
    assert slope[mid - 3] == pytest.approx(half / np.sqrt(rho ** 2 - half ** 2), rel=0.01)
    assert slope[mid + 3] == pytest.approx(-half / np.sqrt(rho ** 2 - half ** 2), rel=0.01)
    # the whole kernel, numba against numpy, with a roller over the pit's trailing half
    y2 = y.copy()
    layout.views(y2, p.Z)[0][1, 0, PHI] = 0.2 * d.tau(p)
    assert_same(y2, ring, P, D)


@pytest.mark.parametrize("kwargs, match", [
    ({"profile": "flat"}, r"Defect.profile = 'flat' is not allowed: expected one of half-sine, edges"),
    ({"edge_radius": 1e-4}, r"Defect.edge_radius = 0.0001 is not allowed: an edge radius needs"),
    ({"profile": "edges", "edge_radius": 1e-3}, r"edge_radius = 0.001 is not allowed: expected less than"),
    ({"profile": "edges", "kind": "roller"}, r"Defect.profile = 'edges' is not allowed: the edges'"),
])
def test_bad_defect_profiles_are_refused(kwargs, match):
    with pytest.raises(defects.ParameterError, match=match):
        defects.Defect(W=2e-3, **kwargs)


N = 10.0 / 9.0
H = 0.02
LINE_CASES = {
    "uniform": (1e-5, 0.0, -H, H),
    "nearly uniform": (1e-5, 0.05 * 1e-5 / (2 * H), -H, H),
    "nearly uniform, off centre": (1e-5, 0.05 * 1e-5 / (H + 0.05 * 0.5 * H), -H, 0.0),  # kap h = 0.05 u_mid
    "strongly tilted": (1e-5, 4e-4, -H, H),
    "strongly tilted, negative": (1e-5, -4e-4, -0.5 * H, H),
    "partially negative": (1e-6, 2e-4, -H, H),
    "partially negative, falling": (2e-6, -3e-4, -H, 0.5 * H),
    "fully negative": (-1e-5, 2e-4, -H, H),
    "fully negative, uniform": (-1e-6, 0.0, -H, H),
}


def quad_integrals(d0, kap, a, b, n):
    u = lambda s: max(d0 + kap * s, 0.0) ** n    # noqa: E731
    pts = [-d0 / kap] if kap != 0.0 and a < -d0 / kap < b else None
    kw = dict(points=pts, epsrel=1e-13, limit=200)
    i0 = quad(u, a, b, epsabs=1e-300, **kw)[0]
    # the first moment may vanish by symmetry: an absolute floor far below max|s| i0
    return i0, quad(lambda s: s * u(s), a, b, epsabs=1e-14 * max(abs(a), abs(b)) * i0 + 1e-300, **kw)[0]


@pytest.mark.parametrize("case", LINE_CASES)
def test_line_integrals(case):
    d0, kap, a, b = LINE_CASES[case]
    r0, r1 = quad_integrals(d0, kap, a, b, N)
    # scales: i0 itself; for the first moment, max|s| i0 (it may vanish by symmetry)
    s0 = abs(r0)
    s1 = max(abs(a), abs(b)) * abs(r0)
    for i0, i1 in (line_integrals(d0, kap, a, b, N), line_integrals_numpy(d0, kap, a, b, N)):
        if "fully negative" in case:
            assert float(i0) == 0.0 and float(i1) == 0.0
            continue
        assert abs(i0 - r0) <= RTOL * s0, (i0, r0)
        assert abs(i1 - r1) <= RTOL * s1, (i1, r1)
    assert line_integrals(d0, kap, b, a, N) == (0.0, 0.0)


def test_a_diverged_compression_passes_nan_on_instead_of_raising():
    """A NaN compression (a state that diverged) with no tilt used to reach the closed form's
    division by ``kap`` and stop the run with numba's ZeroDivisionError; it must come back as
    NaN, so that the integrators' finite check ends the run with its own message."""
    from axlebox.bearing.kernel.contact import line_stiffness
    for kap in (0.0, 1e-3):
        assert all(np.isnan(line_integrals(np.nan, kap, -H, H, N)))
        assert all(np.isnan(line_stiffness(np.nan, kap, -H, H, N)))


def test_line_integrals_vectorised():
    d0, kap, a, b = (np.array(v) for v in zip(*LINE_CASES.values()))
    i0, i1 = line_integrals_numpy(d0, kap, a, b, N)
    for k in range(len(d0)):
        j0, j1 = line_integrals(d0[k], kap[k], a[k], b[k], N)
        assert abs(i0[k] - j0) <= 1e-13 * abs(j0) and abs(i1[k] - j1) <= 1e-13 * max(abs(j0), 1e-300)


def test_inner_ring_defect(start):
    """An inner-ring defect (kind 1, on the cone, turning with the shaft): the twins agree with it
    alone, with an outer-ring defect beside it, and on a shaken state; the roller in it carries
    less on the cone, the other row nothing different; turning the shaft by the defect's width
    takes the roller out of it.  From the healthy bearing's quasi-static start (the fixture's
    has roller 1 of row 2 sunk into its outer-ring defect, clear of the cone)."""
    p, P, _, _, _ = start
    inner = defects.Defect(W=2e-3, kind="inner")
    Di = defects.table((inner,), p)
    both_kinds = defects.table((inner, defects.Defect(W=2e-3)), p)
    none = defects.table((), p)
    y, uo = equilibrium.static_state(p, P, none, (0.0, 0.0, -54e3), OMEGA)
    ring = equilibrium.ring_motion(OMEGA, uo)
    _, _, Q = assert_same(y, ring, P, Di)
    _, _, Q0 = assert_same(y, ring, P, none)
    assert Q0[1, 0, layout.Q_I] > 1e3 and Q[1, 0, layout.Q_I] < Q0[1, 0, layout.Q_I]
    assert np.array_equal(Q[0], Q0[0])
    _, _, Qb = assert_same(y, ring, P, both_kinds)
    assert Qb[1, 0, layout.Q_I] < Q0[1, 0, layout.Q_I]
    turned = ring.copy()
    turned[0, 4] = inner.tau(p)                # the shaft turned on by the defect's window
    _, _, Qt = assert_same(y, turned, P, Di)
    _, _, Qt0 = assert_same(y, turned, P, none)
    assert np.array_equal(Qt, Qt0)
    y3, ring3 = perturbed(p, y, ring)
    assert_same(y3, ring3, P, both_kinds)


def test_roller_defect(start):
    """A defect on roller 1 of row 2 (kind 2, turning with its spin): under the cup at its angle,
    under the cone half a turn on; the twins agree in both places, beside an outer-ring defect,
    and on a shaken state; only that roller's contact changes."""
    p, P, _, _, _ = start
    none = defects.table((), p)
    y, uo = equilibrium.static_state(p, P, none, (0.0, 0.0, -54e3), OMEGA)
    ring = equilibrium.ring_motion(OMEGA, uo)
    assert layout.views(y, p.Z)[0][1, 0, PSI] == 0.0
    _, _, Q0 = assert_same(y, ring, P, none)
    for angle, q in ((0.0, layout.Q_O), (np.pi, layout.Q_I)):
        D = defects.table((defects.Defect(W=2e-3, kind="roller", roller=1, angle=angle),), p)
        _, _, Q = assert_same(y, ring, P, D)
        assert 0.0 <= Q[1, 0, q] < Q0[1, 0, q]
        other = np.ones(Q.shape[:2], bool)
        other[1, 0] = False
        assert np.array_equal(Q[other], Q0[other])
    D = defects.table((defects.Defect(W=2e-3, kind="roller", roller=3, angle=0.5),
                       defects.Defect(W=2e-3)), p)
    y3, ring3 = perturbed(p, y, ring)
    layout.views(y3, p.Z)[0][1, 2, PSI] = 0.5            # roller 3 on its defect at the cup
    assert_same(y3, ring3, P, D)
