"""Copy or source (bearing/diagnostics/coherence.py): whether a fault line seen on both sides is
one impulse train, or two.

The estimator against closed forms (two amplitude-modulated carriers whose modulations differ by
a known frequency: the coherence of the segments' cross-spectra is a Dirichlet kernel), its
symmetry, and the pair analysis on synthetic pairs with known answers
(bearing/diagnostics/families.py): a fault and its copy are one train, two faults with their own
slip and jitter are two.  The families at size are tests/test_families.py.
"""
import json
import math

import numpy as np
import pytest

from axlebox._params import ParameterError
from axlebox.bearing.catalogue import lookup
from axlebox.bearing.diagnostics.clock import angle_clock
from axlebox.bearing.diagnostics.coherence import C_COPY, timing
from axlebox.bearing.diagnostics.criterion import Criterion
from axlebox.bearing.diagnostics.families import copy_case, two_source_case
from axlebox.bearing.diagnostics.pair import analyse_pair

FS = 10_000.0
BAND = (2000.0, 4000.0)
REL = Criterion(mode="relative")
C_INDEPENDENT, Z_MIN = REL.c_independent, REL.z_min        # the defaults, 0.2 and 5
B6205 = lookup("6205")


def am(f_mod, T=8.0, carrier=3000.0, m=0.5, phase=0.0):
    """A carrier modulated at ``f_mod``: its envelope is exactly ``1 + m cos(2 pi f_mod t + phase)``."""
    t = np.arange(int(T * FS)) / FS
    return (1 + m * np.cos(2 * np.pi * f_mod * t + phase)) * np.cos(2 * np.pi * carrier * t)


@pytest.mark.parametrize("delta", [0.0, 0.05, 0.2, 0.5])
def test_coherence_of_two_drifting_lines_is_the_dirichlet_kernel(delta):
    """Side B's modulation runs ``delta`` Hz faster than A's 40 Hz one: segment j's cross-spectrum
    turns by ``2 pi delta t_j``, so the segments' coherence is ``|mean_j exp(2 pi i delta
    t_j)|^2``, a Dirichlet kernel in ``delta`` (both lines noise-free: the coherent fraction is
    the coherence itself)."""
    f = 40.0
    t = timing(am(f), am(f + delta), FS, f, [BAND], [BAND], n_periods=8)
    h = t.pairs[0].harmonics[0]
    nper = int(round(8 * FS / f))
    step = nper - nper // 2
    starts = np.arange(1 + (int(8.0 * FS) - nper) // step) * step / FS
    expect = abs(np.mean(np.exp(2j * np.pi * delta * starts))) ** 2
    assert h.k == 1 and h.f == pytest.approx(f, abs=FS / nper)
    assert h.g2 == pytest.approx(expect, abs=0.02)
    assert h.c == pytest.approx(h.g2, rel=0.02)           # no noise: g2_copy is 1
    want = "independent" if h.c <= C_INDEPENDENT else "partly coherent" if h.c <= C_COPY else "coherent"
    assert t.decision == want, (delta, h)
    assert (delta == 0.0) == (want == "coherent")


@pytest.mark.parametrize("delta, p", [(0.0, 0.15), (1.0, 0.5)])
def test_a_copy_whose_strength_changes_is_still_one_train(delta, p):
    """Side B carries A's 40 Hz modulation (``delta`` = 0: a copy) over the record's first
    ``p`` only, then its carrier alone: a copy whose path stops carrying the line, as the accelerating
    car's healthy side stops carrying the copy's 5th harmonic (coherence.py).  The segments'
    coherence is then the Cauchy-Schwarz bound ``(sum_j u_j)^2 / (K sum_j u_j^2)``, ``u_j`` the
    share of segment j's Hann weight before the change (about ``p``): what a copy in step with
    its source gives when its strength changes.  The copy's reference ``g2_copy`` is that bound,
    so the coherent fraction is 1 and the line one train; B's line ``delta`` Hz off A's (its own
    timing) still reads ``|sum_j u_j exp(2 pi i delta t_j)|^2 / (sum_j u_j)^2``, the Dirichlet
    kernel over the segments that hold it (half the record, two turns of the phase: about 0):
    two trains.  (With the stationary reference
    ``rho_a / (1 + rho_a) rho_b / (1 + rho_b)``, 1 here, the copy read a fraction of 0.15:
    independent, a healthy side called faulty.)"""
    f, T = 40.0, 8.0
    t = np.arange(int(T * FS)) / FS
    gate = t < p * T
    b = np.where(gate, am(f + delta), np.cos(2 * np.pi * 3000.0 * t))
    tm = timing(am(f), b, FS, f, [BAND], [BAND], n_periods=8)
    h = tm.pairs[0].harmonics[0]
    nper = int(round(8 * FS / f))
    step = nper - nper // 2
    starts = np.arange(1 + (t.size - nper) // step) * step
    w = np.hanning(nper + 2)[1:-1]
    u = np.array([np.sum(w * gate[j:j + nper]) / np.sum(w) for j in starts])
    bound = np.sum(u) ** 2 / (u.size * np.sum(u ** 2))
    assert bound == pytest.approx(p, abs=0.01)
    assert h.g2_copy == pytest.approx(bound, rel=0.03)
    expect = abs(np.sum(u * np.exp(2j * np.pi * delta * starts / FS))) ** 2 / np.sum(u) ** 2
    assert h.c == pytest.approx(expect, abs=0.03)
    assert tm.decision == ("coherent" if delta == 0.0 else "independent"), h


@pytest.mark.parametrize("tau", [0.0, 5e-3, 10e-3])
def test_a_delayed_copy_turns_on_the_shaft_clock_as_its_delay_says(tau):
    """A line locked to the shaft (order 8.72, the DTRB's BPFO) while the shaft speeds up from 2
    to 8 Hz over 8 s, and its copy ``tau`` later in time: on the shaft's clock the copy's segment
    ``j`` turns by ``2 pi O f(t) tau`` (a fixed delay in time is a share of a turn that grows with
    the speed), so the segments' coherence is ``|mean_j <exp(2 pi i O f(t) tau)>_j|^2``, each
    segment's term its Hann-weighted mean over the instants it spans, 1 for no delay.  What the
    copy test cannot tell from two trains drifting apart: the reason for the second look
    (pipelines/speed.py)."""
    O, f0, f1, T = 8.72, 2.0, 8.0, 8.0
    t = np.arange(int(T * FS)) / FS

    def theta(s):
        return f0 * s + 0.5 * (f1 - f0) / T * s ** 2

    a = (1 + 0.5 * np.cos(2 * np.pi * O * theta(t))) * np.cos(2 * np.pi * 3000.0 * t)
    b = (1 + 0.5 * np.cos(2 * np.pi * O * theta(t - tau))) * np.cos(2 * np.pi * 3000.0 * t)
    angle = theta(t)
    f_mean = (angle[-1] - angle[0]) * FS / (angle.size - 1)
    with angle_clock(angle, FS) as clock:
        h = timing(a, b, FS, O * f_mean, [BAND], [BAND], n_periods=8).pairs[0].harmonics[0]
    nper = int(round(8 * FS / (O * f_mean)))
    w = np.hanning(nper + 2)[1:-1]
    turn = [np.sum(w * np.exp(2j * np.pi * O * (f0 + (f1 - f0) * clock.t_k[j:j + nper] / T) * tau))
            / np.sum(w) for j in range(0, t.size - nper + 1, nper - nper // 2)]
    expect = abs(np.mean(turn)) ** 2
    assert h.g2 == pytest.approx(expect, abs=0.005)
    assert h.c == pytest.approx(h.g2, rel=1e-3)            # no noise, one strength: g2_copy is 1
    assert (tau == 0.0) == (expect > 0.99) and (tau < 0.01 or expect < 0.5)


def test_timing_is_symmetric_and_refuses_bad_input():
    """Swapping the channels swaps rho_a and rho_b and leaves the coherence as it was."""
    rng = np.random.default_rng(1)
    a = am(40.0) + 0.3 * rng.standard_normal(int(8 * FS))
    b = am(40.0, phase=1.0) * 0.5 + 0.3 * rng.standard_normal(int(8 * FS))
    ab = timing(a, b, FS, 40.0, [BAND], [BAND]).pairs[0].harmonics[0]
    ba = timing(b, a, FS, 40.0, [BAND], [BAND]).pairs[0].harmonics[0]
    assert (ab.g2, ab.c, ab.z) == pytest.approx((ba.g2, ba.c, ba.z), rel=1e-9)
    assert (ab.rho_a_db, ab.rho_b_db) == pytest.approx((ba.rho_b_db, ba.rho_a_db), rel=1e-9)
    assert ab.c == pytest.approx(1.0, abs=0.05) and ab.is_usable()
    with pytest.raises(ParameterError, match="same length"):
        timing(a, b[:-1], FS, 40.0, [BAND], [BAND])
    with pytest.raises(ParameterError, match="f_line"):
        timing(a, b, FS, 4000.0, [BAND], [BAND])
    with pytest.raises(ParameterError, match="bands"):
        timing(a, b, FS, 40.0, [], [BAND])


def _pair(case):
    shaft = case.params["f_fault"] / B6205.orders.BPFO
    return analyse_pair(case.a, case.b, case.fs, shaft, B6205.orders, B6205.bore, REL)


@pytest.mark.parametrize("seed", [2, 7, 16])
def test_a_fault_and_its_copy_are_one_train(seed):
    """A copy keeps its source's timing through the path: every usable harmonic of every pair of
    the two sides' own bands is coherent (fraction over ``C_COPY``), and the copy's side is the
    pseudo-fault."""
    case = copy_case(seed)
    res = _pair(case)
    ev = next(e for e in res.evidence if e.line == "BPFO")
    assert ev.timing is not None and ev.timing.decision == "coherent", ev.timing.to_dict()
    use = [h for p in ev.timing.pairs for h in p.harmonics if h.is_usable()]
    assert use and min(h.c for h in use) > C_COPY
    assert (res.verdict.words["left"], res.verdict.words["right"]) == ("real fault", "pseudo-fault")
    json.dumps(res.to_dict(), allow_nan=False)


@pytest.mark.parametrize("seed", [1, 4, 8])
def test_two_faults_are_two_trains(seed):
    """Two faults, each its own slip and jitter: their lines' relative phase wanders over the
    10 s, the coherent fraction falls under ``C_INDEPENDENT`` and both sides are called."""
    res = _pair(two_source_case(seed))
    ev = next(e for e in res.evidence if e.line == "BPFO")
    assert ev.timing.decision == "independent" and ev.timing.c_min <= C_INDEPENDENT
    assert res.verdict.words == {"left": "faults on both sides", "right": "faults on both sides"}
    assert res.verdict.rule == "each side owns a line"
    assert "own timing" in res.verdict.sentence("left")


def test_the_copy_or_source_thresholds_are_the_criterions():
    """``Criterion.c_independent``, ``rho_min_db`` and ``z_min`` decide whether two lines are two
    trains.  Two faults (least coherent fraction about 0.008) are both called under the
    defaults and with ``c_independent`` just over that fraction; just under it, or with
    ``z_min`` or ``rho_min_db`` out of reach (no significant, no usable harmonic), the same
    evidence reads one train and its copy: no longer faults on both sides."""
    from dataclasses import replace
    res = _pair(two_source_case(1))
    both = {"left": "faults on both sides", "right": "faults on both sides"}
    c = res.verdict.evidence.lines[0].c_min
    assert res.verdict.words == both and 0 < c <= C_INDEPENDENT
    assert res.redecide(replace(REL, c_independent=1.01 * c)).words == both
    for kw, how in (({"c_independent": 0.99 * c}, "partly coherent"), ({"z_min": 1e6}, "coherent"),
                    ({"rho_min_db": 200.0}, "inconclusive")):
        v = res.redecide(replace(REL, **kw))
        r = v.evidence.lines[0]
        assert r.line.line == "BPFO" and r.how == how and r.sources == ()
        assert v.words != both and v.rule != "each side owns a line"
        assert v.to_dict()["evidence"]["lines"][0]["timing"]["decision"] == how


def test_the_fisher_test_never_fires_on_copies():
    """z of a copy's harmonics: the Fisher transform's deviation of the coherence from what a
    copy in the measured noise would give (Bendat and Piersol, sec. 9.2.3).  The noise is taken
    from the ring beside the line, which holds the line's own spread too, so ``g2_copy`` is
    biased low and a copy's z mostly negative: on the copies of six seeds (over 2000 usable
    harmonics of every pair of their own bands) no z reaches Z_MIN."""
    zs = []
    for seed in range(6):
        res = _pair(copy_case(seed))
        ev = next(e for e in res.evidence if e.line == "BPFO")
        zs += [h.z for p in ev.timing.pairs for h in p.harmonics if h.is_usable()]
    assert len(zs) > 100 and max(zs) < Z_MIN and math.isfinite(sum(zs))
