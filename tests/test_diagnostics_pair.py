"""Two channels: the time lag, the paper's criterion and the pair analysis
(bearing/diagnostics/lag.py, criterion.py, pair.py).

Signals are built with known answers: a delay made exactly (integer shift, or a phase ramp in
the frequency ___domain for a fractional one), and a pair whose side A carries outer-ring impulses
while side B carries a delayed, attenuated, resonance-filtered copy, both in wheel-rail-like
noise.  The paper's criterion (section "Difference analyses ...", Fig. 14, conclusions (2)-(3)):
a VF difference in 0.8e4-7.49e4 Hz^2 means a pseudo-fault; the side with the larger RMS and SPM
is the real fault; the decision procedure around it (criterion.decide) is tested rule by rule
on stand-in evidence.
"""
import dataclasses
import json
from types import SimpleNamespace

import numpy as np
import pytest

from axlebox._params import ParameterError
from axlebox.bearing.diagnostics.criterion import (REL_RANGE_DEFAULT, VF_METRO, VF_RANGE_PAPER,
                                                   Criterion, decide, vf_difference)
from axlebox.bearing.diagnostics.lag import impulse_lag, time_lag
from axlebox.bearing.diagnostics.pair import analyse_pair
from axlebox.bearing.diagnostics.spectral import fc_vf
from axlebox.bearing.diagnostics.synthetic import impulse_train, resonance, wheel_rail_noise
from axlebox.bearing.diagnostics.verdict import (RULES, SIDES, Evidence, LagReading, LineEvidence,
                                                 LineReading, ShaftOrders, VFReading)
from axlebox.bearing.frequencies import orders, shaft_hz
from axlebox.bearing.models.params import BearingParams

FS = 10_000.0                               # the paper's field system samples at 10 kHz
SHAFT = shaft_hz(48.0)                      # the paper's validation speed, 0.42 m wheels
ORDERS = orders(BearingParams())            # the DTRB: BPFO 44.06 Hz at 48 km/h (paper 43.93)
BORE = 0.130
BPFO = ORDERS.BPFO * SHAFT


def frac_delay(x, d):
    """x delayed by d samples (any real d) by a linear phase in the frequency ___domain (circular)."""
    X = np.fft.rfft(x)
    return np.fft.irfft(X * np.exp(-2j * np.pi * np.fft.rfftfreq(x.size) * d), x.size)


# ---------------------------------------------------------------------------------------- lag


@pytest.fixture(scope="module")
def ringing():
    """Impulses at BPFO ringing a 2.5 kHz mode, 1 s."""
    rng = np.random.default_rng(7)
    return resonance(impulse_train(int(FS), FS, BPFO, rng), FS, 2500.0, 0.05)


@pytest.mark.parametrize("d", [7, 12, -5, 3.25, 12.4, -8.6, 0.5])
@pytest.mark.parametrize("band", [None, (1500.0, 3500.0)])
def test_lag_of_a_delayed_attenuated_copy_within_a_tenth_of_a_sample(ringing, d, band):
    """b = 0.3 x a delayed by d samples (integer: a shift; fractional: a phase ramp), each with
    its own noise 26 dB below a.  Reference: d itself, by construction.  Tolerance 0.1 sample
    (the issue); measured errors are 0.001-0.05 sample."""
    rng = np.random.default_rng(abs(int(10 * d)))
    s = 0.05 * ringing.std()
    a = ringing + s * rng.standard_normal(ringing.size)
    moved = np.roll(ringing, d) if float(d).is_integer() else frac_delay(ringing, d)
    b = 0.3 * moved + 0.3 * s * rng.standard_normal(ringing.size)
    r = time_lag(a, b, FS, band=band, max_lag_s=0.5 / BPFO)
    assert abs(r.delay_b_samples - d) < 0.1
    assert abs(r.lag_s - abs(d) / FS) < 0.1 / FS
    assert r.lag_samples >= 0 and r.lag_s >= 0
    assert r.leading == ("a" if d > 0 else "b")
    assert 0.9 < r.peak <= 1.0 + 1e-12        # the envelopes are the same up to noise


_LAG_BITS = """
import sys, numpy as np
from axlebox.bearing.diagnostics.lag import impulse_lag, time_lag
from axlebox.bearing.diagnostics.synthetic import impulse_train, resonance
fs, bpfo = 10_000.0, float(sys.argv[1])
rng = np.random.default_rng(11)
a = resonance(impulse_train(30_000, fs, bpfo, rng), fs, 2500.0, 0.05) + 0.05 * rng.standard_normal(30_000)
b = 0.3 * np.roll(a, 9) + 0.02 * rng.standard_normal(30_000)
r, q = time_lag(a, b, fs), impulse_lag(a, b, fs, 1.0 / bpfo)
print(repr((r.peak, r.delay_b_samples, q.peak, q.delay_b_samples)))
"""


def test_the_lag_has_the_same_bits_whatever_blas_threads_the_process_runs():
    """A sweep analyses its cases on dask workers, whose BLAS runs on one thread, and a rerun
    in the main process, whose BLAS runs on every core: a long np.dot is split by the thread
    count, and the lag's correlation peak differed in its last bit between the two (seen in
    study_fast's summary).  The same pair in a process with one BLAS thread and in one with
    BLAS's default must give the same bits (3 s records: long enough for BLAS to split)."""
    import os
    import subprocess
    import sys
    outs = []
    for one in (True, False):
        env = {k: v for k, v in os.environ.items()
               if k not in ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS")}
        if one:
            env.update(OPENBLAS_NUM_THREADS="1", OMP_NUM_THREADS="1", MKL_NUM_THREADS="1")
        else:
            env.update(OPENBLAS_NUM_THREADS="4", OMP_NUM_THREADS="4", MKL_NUM_THREADS="4")
        p = subprocess.run([sys.executable, "-c", _LAG_BITS, repr(BPFO)], env=env,
                           capture_output=True, text=True, check=True)
        outs.append(p.stdout.strip())
    assert outs[0] == outs[1]


def test_lag_is_antisymmetric_and_zero_for_identical_channels(ringing):
    """Swapping the channels negates the delay (correlate(b, a)[k] = correlate(a, b)[-k]); a
    channel against itself has lag 0, no leader and correlation 1 (Cauchy-Schwarz equality)."""
    b = 0.5 * frac_delay(ringing, 4.3)
    ab, ba = time_lag(ringing, b, FS), time_lag(b, ringing, FS)
    assert ab.delay_b_samples == pytest.approx(-ba.delay_b_samples, abs=1e-3)
    assert (ab.leading, ba.leading) == ("a", "b")
    same = time_lag(ringing, ringing, FS)
    assert same.lag_samples < 1e-3 and same.leading == "none"
    assert same.peak == pytest.approx(1.0, abs=1e-9)


def test_lag_refuses_bad_input(ringing):
    with pytest.raises(ParameterError, match="same length"):
        time_lag(ringing, ringing[:-1], FS)
    with pytest.raises(ParameterError, match="max_lag_s"):
        time_lag(ringing, ringing, FS, max_lag_s=0.0)


def test_impulse_lag_reads_a_delayed_copy_to_the_sample_and_names_no_side_on_noise():
    """Side b: side a's impulses ``d`` samples later with noise of its own; the arrival picked on
    the synchronously averaged envelopes is d to within a sample, the bootstrap agrees, and
    swapping the channels swaps the sign.  Against pure noise no side is named."""
    rng = np.random.default_rng(5)
    n, d = int(3 * FS), 9
    hits = resonance(impulse_train(n + d, FS, BPFO, rng), FS, 2500.0, 0.05)
    a = hits[d:] + 0.05 * hits.std() * rng.standard_normal(n)
    b = hits[:n] + 0.05 * hits.std() * rng.standard_normal(n)
    r = impulse_lag(a, b, FS, 1 / BPFO)
    assert r.leading == "a" and abs(r.delay_b_samples - d) <= 1, r
    assert r.n_impulses > 100 and r.agreement > 0.99 and r.method == "impulses"
    back = impulse_lag(b, a, FS, 1 / BPFO)
    assert back.leading == "b" and abs(back.delay_b_samples + d) <= 1
    noise = impulse_lag(rng.standard_normal(n), rng.standard_normal(n), FS, 1 / BPFO)
    assert noise.leading == "none", noise
    with pytest.raises(ParameterError, match="period_s"):
        impulse_lag(a, b, FS, 0.0)


# ------------------------------------------------------------------------- synthetic pairs


def pair(seed, n=int(4 * FS), snr_db=6.0, gain_b=0.3, delay=12, floor_db=None):
    """Side A: impulses at BPFO (1 % jitter) ringing a 600 Hz mode, +snr_db over the noise.
    Side B: A's impulse response delayed by ``delay`` samples (1.2 ms, the paper's typical lag),
    filtered by a 546 Hz mode (the wheelset's second bending, which the paper finds modulating
    the pseudo-fault) and scaled to ``gain_b`` of A's RMS; the same noise level on both sides.
    B's impulses are weaker against the noise, so B's spectrum is the more dispersed (the
    paper's pseudo-fault side, Fig. 12 and 14).  ``floor_db``: a white sensor floor that much
    below the wheel-rail noise (None: none, so bands above 1 kHz hold only the impulses)."""
    rng = np.random.default_rng(seed)
    a = resonance(impulse_train(n, FS, BPFO, rng), FS, 600.0, 0.05)
    b = resonance(np.roll(a, delay), FS, 546.0, 0.05)
    b *= gain_b * a.std() / b.std()
    na, nb = wheel_rail_noise(n, FS, rng), wheel_rail_noise(n, FS, rng)
    if floor_db is not None:
        w = 10 ** (floor_db / 20) * na.std()
        na, nb = na + w * rng.standard_normal(n), nb + w * rng.standard_normal(n)
    s = a.std() / na.std() / 10 ** (snr_db / 20)
    return a + s * na, b + s * nb, s * na, s * nb


CRITERIA = {"absolute (paper range)": Criterion(),
            "relative": Criterion(mode="relative")}
NOISE = {"wheel-rail noise": None, "and a -40 dB sensor floor": -40.0}


@pytest.fixture(scope="module", params=list(NOISE))
def synthetic(request):
    return request.param, pair(seed=3, floor_db=NOISE[request.param])


@pytest.mark.parametrize("name", CRITERIA)
def test_impulses_are_real_and_their_transmitted_copy_pseudo(synthetic, name):
    noise, (a, b, _, _) = synthetic
    res = analyse_pair(a, b, FS, SHAFT, ORDERS, BORE, CRITERIA[name], names=("A", "B"))
    assert res.verdict.words["left"] == "real fault", res.verdict.words
    assert res.verdict.words["right"] == "pseudo-fault", res.verdict.words
    # what the verdict rests on, each against the paper's description:
    lo, hi = CRITERIA[name].range
    assert lo <= res.m <= hi                      # conclusion (3): the VF difference in range
    assert res.left.rms > res.right.rms and res.left.spm_db > res.right.spm_db
    assert res.right.VF > res.left.VF             # the pseudo-fault side is more dispersed
    assert "BPFO" in res.left.detected
    if NOISE[noise] is None:
        # B's impulses alone above 1 kHz: its envelope shows the BPFO lines too (with the
        # sensor floor they sink below it at -4.5 dB to the noise: "no fault line found here")
        assert "BPFO" in res.right.detected
    assert res.lag.leading == "a"                 # the transmitted side lags (Fig. 13)
    # the VF difference: |VF_A - VF_B| in Hz^2, relative = 1 - VF_min / VF_max (identities)
    assert res.vf_diff == pytest.approx(abs(res.left.VF - res.right.VF), rel=1e-12)
    if CRITERIA[name].mode == "relative":
        assert res.m == pytest.approx(1 - res.left.VF / res.right.VF, rel=1e-12)
    json.dumps(res.to_dict(), allow_nan=False)


def test_swapping_the_sides_swaps_the_verdicts(synthetic):
    """The criterion has no favourite side: B on the left, A on the right."""
    _, (a, b, _, _) = synthetic
    res = analyse_pair(b, a, FS, SHAFT, ORDERS, BORE)
    assert (res.verdict.words["left"], res.verdict.words["right"]) == ("pseudo-fault", "real fault")
    assert res.lag.leading == "b"


@pytest.mark.parametrize("name", CRITERIA)
def test_noise_on_both_sides_is_healthy(synthetic, name):
    _, (_, _, na, nb) = synthetic
    res = analyse_pair(na, nb, FS, SHAFT, ORDERS, BORE, CRITERIA[name])
    assert res.verdict.words["left"] == res.verdict.words["right"] == "healthy", res.verdict.words
    assert not res.left.detected and not res.right.detected
    # independent noises: the envelope correlation stays near 0 (about 1/sqrt(samples per
    # correlation length)), below what the criterion needs to quote a lag
    assert abs(res.lag.peak) < Criterion().lag_min_peak
    # two realisations of one noise: VF within a few % (Welch scatter), far below the relative range
    assert vf_difference(res.left.VF, res.right.VF, Criterion(mode="relative")) < 0.5 * REL_RANGE_DEFAULT[0]


def test_a_louder_transmitted_side_is_named_by_its_lag():
    """The study's 1 mm, 40 km/h case (README): the transmitted copy arrives 1.2 ms later but
    1.5 times as strong (the healthy journal carrying more of the wheelset's bending), so RMS
    and SPM are larger on the healthy side.  The paper's RMS and SPM alone (``lag="off"``) name
    the wrong side; ``veto`` leaves both undecided; ``decide`` (the default) names A, whose
    impulses lead in every bootstrap resample.  Whatever the lag policy, the default criterion
    names A too: A's line stands higher in most bands (the copy passed the 546 Hz mode only)."""
    a, b, _, _ = pair(seed=3, gain_b=1.5)
    got, ours = {}, {}
    for policy in ("decide", "veto", "off"):
        res = analyse_pair(a, b, FS, SHAFT, ORDERS, BORE,
                           Criterion(mode="relative", lag=policy, source="paper"))
        got[policy] = (res.verdict.words["left"], res.verdict.words["right"])
        ours[policy] = res.redecide(Criterion(mode="relative", lag=policy)).words["left"]
    assert res.right.rms > res.left.rms and res.right.spm_db > res.left.spm_db
    assert res.lag.leading == "a" and res.lag.agreement == 1.0 and res.lag.n_impulses > 100
    assert got == {"decide": ("real fault", "pseudo-fault"), "veto": ("undecided", "undecided"),
                   "off": ("pseudo-fault", "real fault")}
    assert ours == {p: "real fault" for p in got}
    ev = res.evidence[0]
    assert ev.votes["left"] >= 2 * ev.votes["right"]


def test_a_vf_band_takes_each_sides_fc_and_vf_over_that_band_alone(synthetic):
    """``Criterion.vf_band``: both sides' FC and VF are :func:`fc_vf`'s over that band (the
    synthetic pair rings 546 and 600 Hz modes in wheel-rail noise), shown in the summary and the
    JSON; the verdict does not take them again.  ``redecide`` under another band takes them
    again from the kept signals: equal to a fresh analysis under that criterion."""
    _, (a, b, _, _) = synthetic
    band = Criterion(mode="relative", vf_band=(0.0, 1000.0))
    res = analyse_pair(a, b, FS, SHAFT, ORDERS, BORE, band)
    for c, x in ((res.left, a), (res.right, b)):
        assert (c.FC, c.VF, c.MSF) == fc_vf(x, FS, None, (0.0, 1000.0))
        assert c.FC < 1000.0 and c.vf_band == (0.0, 1000.0)
    whole = analyse_pair(a, b, FS, SHAFT, ORDERS, BORE, Criterion(mode="relative"))
    assert whole.left.VF > res.left.VF and whole.right.VF > res.right.VF   # the tail cut off
    assert "over 0-1000 Hz" in res.summary() and "over the whole band" in whole.summary()
    d = json.loads(json.dumps(res.to_dict(), allow_nan=False))
    assert d["criterion"]["vf_band"] == [0.0, 1000.0] and d["left"]["vf_band"] == [0.0, 1000.0]
    assert res.redecide(whole.criterion) == whole.verdict
    assert whole.redecide(band) == res.verdict
    again = whole.in_vf_band((0.0, 1000.0))
    assert (again.left.VF, again.right.VF, again.m, again.verdict) == (res.left.VF, res.right.VF,
                                                                       res.m, res.verdict)


def test_the_papers_band_is_where_its_rk4_step_keeps_a_ring():
    """The reasoning behind ``VF_BAND_PAPER`` (criterion.py's docstring), from the classical
    RK4's stability polynomial at the paper's 1e-4 s step: the share of a free oscillation's
    amplitude kept over one period, and the numerical damping ratio it amounts to."""
    from axlebox.bearing.diagnostics.criterion import PAPER_RK4_STEP, VF_BAND_PAPER

    def kept(f):
        z = 2j * np.pi * f * PAPER_RK4_STEP
        return abs(1 + z + z ** 2 / 2 + z ** 3 / 6 + z ** 4 / 24) ** (1.0 / (f * PAPER_RK4_STEP))

    for f, share, zeta in ((1000.0, 0.996, 0.0007), (1500.0, 0.971, 0.005), (2000.0, 0.894, 0.018),
                           (2500.0, 0.732, 0.05), (3000.0, 0.492, 0.11)):
        assert kept(f) == pytest.approx(share, abs=6e-4)
        assert -np.log(kept(f)) / (2 * np.pi) == pytest.approx(zeta, rel=0.15)
    assert VF_BAND_PAPER == (0.0, 1000.0) and kept(VF_BAND_PAPER[1]) > 0.99 > kept(1500.0)


def test_pair_figure_is_written(synthetic, tmp_path):
    from PIL import Image
    _, (a, b, _, _) = synthetic
    res = analyse_pair(a, b, FS, SHAFT, ORDERS, BORE)
    res.plot(tmp_path / "pair.png")
    img = np.asarray(Image.open(tmp_path / "pair.png").convert("L"), dtype=float)
    assert img.shape[0] > 500 and img.var() > 100          # not blank


def test_pair_refuses_bad_records(synthetic):
    _, (a, b, _, _) = synthetic
    with pytest.raises(ParameterError, match="same length"):
        analyse_pair(a, b[:-10], FS, SHAFT, ORDERS, BORE)
    short = int(0.5 * FS)       # FTF = 2.2 Hz at 48 km/h: two periods need 0.91 s
    with pytest.raises(ParameterError, match=r"too short.*FTF.*two periods"):
        analyse_pair(a[:short], b[:short], FS, SHAFT, ORDERS, BORE)
    bad = a.copy()
    bad[100] = np.nan
    with pytest.raises(ParameterError, match=r"left channel 'left'\[100\]"):
        analyse_pair(bad, b, FS, SHAFT, ORDERS, BORE)


# -------------------------------------------------------------- the criterion's decision table


def side(VF, rms, spm_db, lines=("BPFO",)):
    """A stand-in ChannelResult: only what decide() reads."""
    return SimpleNamespace(VF=VF, rms=rms, spm_db=spm_db,
                           lines={"BPFO": SimpleNamespace(detected="BPFO" in lines, snr_db=20.0)})


def timing(decision, c_min=None):
    """A stand-in :class:`.coherence.Timing` with its decision (whatever the thresholds)."""
    return SimpleNamespace(decide=lambda **kw: decision, coherent_fraction=lambda **kw: c_min,
                           to_dict=lambda **kw: {"decision": decision, "c_min": c_min})


def line(bearing="both", seen=("left", "right"), decision="coherent", best=(30.0, 30.0),
         votes=None):
    """A stand-in line's evidence: BPFO of ``bearing`` seen on ``seen``."""
    return LineEvidence("BPFO", bearing, {s: s in seen for s in SIDES}, {s: 20.0 for s in SIDES},
                        timing(decision) if len(seen) == 2 and bearing == "both" else None, None,
                        best_snr_db=dict(zip(SIDES, best)), votes=votes or {})


def test_paper_range_and_its_relative_mapping():
    """The paper's range (Fig. 14, conclusion 3) and the relative lower bound: 0.8e4 over the VF
    of a flat PSD on 0-200 Hz and 300-800 Hz (where the paper's healthy side has its energy,
    Fig. 12).  Closed form for that PSD: weights 2/7, 5/7; FC = (2*100 + 5*550)/7;
    E[f^2] = 2/7 * 200^2/3 + 5/7 * (800^3 - 300^3)/(3*500); VF = E[f^2] - FC^2 = 57 161 Hz^2."""
    assert VF_RANGE_PAPER == (0.8e4, 7.49e4)
    FC = (2 * 100 + 5 * 550) / 7
    VF = 2 / 7 * 200 ** 2 / 3 + 5 / 7 * (800 ** 3 - 300 ** 3) / 1500 - FC ** 2
    assert VF_METRO == pytest.approx(VF, rel=1e-3)          # the constant is rounded to 3 digits
    assert REL_RANGE_DEFAULT[0] == pytest.approx(0.8e4 / VF, abs=0.005)
    assert REL_RANGE_DEFAULT[1] == 1.0                      # 1 - VF_min/VF_max < 1 always


IN_RANGE = (side(2e4, 2.0, 40), side(5e4, 1.0, 30))          # VF difference 3e4 Hz^2, in range
BELOW = (side(2e4, 2.0, 40), side(2.5e4, 1.0, 30))           # 5e3, below the paper's range


@pytest.mark.parametrize("sides,lines,words,rule", [
    # whose line: nothing seen -> healthy whatever the VF difference
    (IN_RANGE, [line(seen=())], ("healthy", "healthy"), "no fault line"),
    # a line of both sides' bearing seen on one side only is that side's; the other a
    # pseudo-fault where the VF difference says one is present, else healthy
    (IN_RANGE, [line(seen=("left",))], ("real fault", "pseudo-fault"), "one side owns the lines"),
    (IN_RANGE, [line(seen=("right",))], ("undecided", "undecided"), "one side only, not the louder"),
    (BELOW, [line(seen=("right",))], ("undecided", "undecided"), "one side only, spectra alike"),
    # a line at the left bearing's own order (the bearings differ), wherever it is seen: the
    # right side carries it, a pseudo-fault whatever the VF difference
    (BELOW, [line("left", seen=("right",))], ("real fault", "pseudo-fault"),
     "one side owns the lines"),
    # seen on both sides, two impulse trains: each side's own, both standing clear of a healthy
    # bearing's level; one faint: only the other is called; both faint: neither
    (IN_RANGE, [line(decision="independent")], ("faults on both sides",) * 2, "each side owns a line"),
    (IN_RANGE, [line(decision="independent", best=(30.0, 12.0))], ("real fault", "undecided"),
     "second line faint"),
    (IN_RANGE, [line(decision="independent", best=(11.0, 12.0))], ("undecided", "undecided"),
     "both lines faint"),
    (IN_RANGE, [line(decision="independent", best=(14.0, 10.0))], ("real fault", "undecided"),
     "second line faint"),
    # distinct bearings, each its own line
    (BELOW, [line("left", seen=("left",)), line("right", seen=("right",))],
     ("faults on both sides",) * 2, "each side owns a line"),
    # one train (a copy), the source by where the line rings: left higher in 12 bands of 14
    (BELOW, [line(votes={"left": 12, "right": 2})], ("real fault", "pseudo-fault"), "ringing"),
    # a copy and no sure lag or ringing: the paper's criterion, RMS and SPM larger on the left
    (IN_RANGE, [line()], ("real fault", "pseudo-fault"), "RMS and SPM"),
    (IN_RANGE, [line(decision="inconclusive")], ("real fault", "pseudo-fault"), "RMS and SPM"),
    ((side(2e4, 2.0, 30), side(5e4, 1.0, 40)), [line()], ("undecided",) * 2, "indicators disagree"),
    (BELOW, [line()], ("undecided",) * 2, "VF below the range"),
    ((side(1e4, 2.0, 40), side(1e5, 1.0, 30)), [line()], ("undecided",) * 2, "VF above the range"),
])
def test_decision_table(sides, lines, words, rule):
    v = decide(*sides, None, Criterion(), lines)
    assert (v.words["left"], v.words["right"], v.rule) == words + (rule,)
    assert v.rule in RULES and RULES[v.rule] in v.sentence("left")
    json.dumps(v.to_dict(), allow_nan=False)
    json.dumps(v.row(), allow_nan=True)


def test_the_evidence_is_typed_and_frozen():
    """decide() reads the evidence once into a frozen, typed :class:`.verdict.Evidence`; the
    verdict is read by attributes (no ``(word, sentence)`` tuple), and its row holds the rule
    and the evidence's fields, not only the sentence."""
    v = decide(*IN_RANGE, impulses_lag("a"), Criterion(), [line(votes={"left": 12, "right": 2})])
    ev = v.evidence
    assert isinstance(ev, Evidence) and isinstance(ev.vf, VFReading) and isinstance(ev.lag, LagReading)
    assert all(isinstance(r, LineReading) for r in ev.lines)
    assert all(isinstance(o, ShaftOrders) for o in ev.orders.values())
    assert ev.lines[0].how == "coherent" and ev.lines[0].sources == ()
    assert ev.vf.m == pytest.approx(3e4) and ev.vf.in_range and ev.vf.where == "in"
    assert ev.lag.leading == "left" and ev.ringing == "left" and ev.larger == {"rms": "left",
                                                                               "spm_db": "left"}
    assert ev.criterion == Criterion() and ev.rotor == "wheel"
    for target, name in ((ev, "rotor"), (ev.vf, "m"), (ev.lines[0], "how"), (v, "evidence"),
                         (ev.lag, "leading")):
        with pytest.raises(dataclasses.FrozenInstanceError):
            setattr(target, name, None)
    with pytest.raises(TypeError):
        v["left"]                               # the old (word, sentence) reading is gone
    assert not hasattr(v, "items")
    row = v.row("verdict_")
    assert row["verdict_rule"] == "lag" and row["verdict_real"] == "left"
    assert row["verdict_vf_m"] == pytest.approx(3e4) and row["verdict_lag_leading"] == "left"
    assert row["verdict_lines"] == "BPFO seen left, right: none by coherent"
    assert all(isinstance(x, (str, float, int)) for x in row.values())
    d = v.to_dict()
    assert d["rule"] == "lag" and d["evidence"]["vf"]["in_range"] and d["evidence"]["rotor"] == "wheel"
    assert d["evidence"]["lines"][0]["how"] == "coherent"


def test_thresholds_on_the_criterion_move_the_verdict_their_way():
    """Each threshold of step 3 is a field of Criterion: the same two own lines (30 and 12 dB
    over their floors) are faults on both sides when a second fault needs 12 dB or less; with
    15 (the default) the 18 dB between them name the clearer side real; once ``clearer_db``
    exceeds those 18 dB neither is named."""
    lines = [line(decision="independent", best=(30.0, 12.0))]
    got = {}
    for kw in ({"second_db": 12.0}, {}, {"clearer_db": 17.9}, {"clearer_db": 18.1}):
        v = decide(*IN_RANGE, None, Criterion(**kw), lines)
        got[tuple(kw.items())] = (v.words["left"], v.words["right"], v.rule)
    assert list(got.values()) == [
        ("faults on both sides", "faults on both sides", "each side owns a line"),
        ("real fault", "undecided", "second line faint"),
        ("real fault", "undecided", "second line faint"),
        ("undecided", "undecided", "both lines faint")]
    # the ringing's fewest bands: 12 of 14 bands name the left side, unless 13 are needed
    copy = [line(votes={"left": 12, "right": 2})]
    assert decide(*BELOW, None, Criterion(), copy).rule == "ringing"
    assert decide(*BELOW, None, Criterion(ringing_bands=13), copy).rule == "VF below the range"


def impulses_lag(leading, n=40, agreement=1.0):
    """A stand-in LagResult read on the impulses (what :func:`.lag.impulse_lag` returns when it
    names a side)."""
    return SimpleNamespace(leading=leading, lag_s=1.2e-3, peak=0.5, method="impulses",
                           n_impulses=n, agreement=agreement)


def test_a_copys_source_by_its_lag_and_where_it_rings():
    """One fault and its copy: the impulses' lag names the source (the paper's conclusion 2:
    the real side leads) whatever RMS and SPM say; where the lines ring agrees, or is silent;
    where it names the other side the verdict is undecided, not a guess."""
    left, right = IN_RANGE
    v = decide(left, right, impulses_lag("b"), Criterion(), [line()])
    assert (v.words["left"], v.words["right"], v.rule, v.real) == ("pseudo-fault", "real fault",
                                                                  "lag", "right")
    assert "right leads by 1.2 ms" in v.sentence("right")
    v = decide(left, right, impulses_lag("b"), Criterion(), [line(votes={"left": 2, "right": 9})])
    assert v.rule == "lag" and v.real == "right"
    v = decide(left, right, impulses_lag("b"), Criterion(), [line(votes={"left": 9, "right": 2})])
    assert v.words == {"left": "undecided", "right": "undecided"}
    assert v.rule == "lag and ringing disagree"
    # a tie in the bands is no evidence: the lag decides
    v = decide(left, right, impulses_lag("a"), Criterion(), [line(votes={"left": 3, "right": 3})])
    assert v.real == "left" and v.rule == "lag"


def test_the_lag_policies_of_the_papers_criterion():
    """The paper's criterion alone (``source="paper"``), RMS and SPM larger on the left while
    the right side's impulses come first (the study's 1 mm, 40 km/h case, README): ``decide``
    (default) names the leading side real; ``veto`` leaves both undecided; ``off`` is the
    paper's RMS and SPM alone.  Where RMS and SPM disagree, ``decide`` and ``veto`` name the
    leading side, ``off`` stays undecided.  A lag by correlation never decides against the
    indicators (it vetoes) and below ``lag_min_peak`` it is not used at all."""
    left, right = IN_RANGE
    lag = impulses_lag("b")

    def words(l_, r_, lag_, **kw):
        v = decide(l_, r_, lag_, Criterion(source="paper", **kw), [line()])
        return v.words["left"], v.words["right"], v.rule
    assert words(left, right, lag) == ("pseudo-fault", "real fault", "lag")
    assert words(left, right, lag, lag="veto") == ("undecided", "undecided", "lag contradicts")
    assert words(left, right, lag, lag="off") == ("real fault", "pseudo-fault", "RMS and SPM")
    corr = SimpleNamespace(leading="b", lag_s=1.2e-3, peak=0.8, method="correlation")
    assert words(left, right, corr)[:2] == ("undecided", "undecided")
    weak = SimpleNamespace(leading="b", lag_s=1.2e-3, peak=0.1, method="correlation")
    assert words(left, right, weak)[:2] == ("real fault", "pseudo-fault")
    split_l, split_r = side(2e4, 2.0, 30), side(5e4, 1.0, 40)   # RMS says left, SPM right
    for lead, real in (("a", "left"), ("b", "right")):
        for policy in ("decide", "veto"):
            v = decide(split_l, split_r, impulses_lag(lead),
                       Criterion(source="paper", lag=policy), [line()])
            assert v.words[real] == "real fault" and v.rule == "lag", v
        assert words(split_l, split_r, impulses_lag(lead), lag="off")[0] == "undecided"
    for policy in ("decide", "veto", "off"):
        assert words(left, right, impulses_lag("a"), lag=policy)[0] == "real fault"


def test_relative_mode_is_invariant_to_a_frequency_scale():
    """VF scales with the square of a frequency scale k (a machine k times faster): the relative
    difference does not move, the absolute one moves by k^2."""
    left, right = IN_RANGE
    rel = Criterion(mode="relative")
    k2 = 7.5 ** 2
    fast_l, fast_r = side(2e4 * k2, 2.0, 40), side(5e4 * k2, 1.0, 30)
    assert vf_difference(fast_l.VF, fast_r.VF, rel) == pytest.approx(vf_difference(2e4, 5e4, rel))
    assert vf_difference(fast_l.VF, fast_r.VF) == pytest.approx(k2 * 3e4)
    assert decide(fast_l, fast_r, None, rel, [line()]).words == \
        decide(left, right, None, rel, [line()]).words == {"left": "real fault", "right": "pseudo-fault"}
    assert decide(fast_l, fast_r, None, Criterion(), [line()]).rule == "VF above the range"


@pytest.mark.parametrize("kw,field", [({"mode": "ratio"}, "mode"), ({"vf_range": (7e4, 8e3)}, "vf_range"),
                                      ({"rel_range": (-0.1, 1)}, "rel_range"),
                                      ({"compare": ("loudness",)}, "compare"), ({"lines": ()}, "lines"),
                                      ({"lag": "trust"}, "lag"), ({"lines": ("BSF",)}, "lines"),
                                      ({"source": "RMS"}, "source"), ({"source_ratio": 1.0}, "source_ratio"),
                                      ({"second_db": -1.0}, "second_db"),
                                      ({"clearer_db": float("nan")}, "clearer_db"),
                                      ({"c_independent": 1.0}, "c_independent"),
                                      ({"rho_min_db": -3.0}, "rho_min_db"),
                                      ({"z_min": float("inf")}, "z_min"),
                                      ({"ringing_bands": 0}, "ringing_bands"),
                                      ({"gate_ratio": 1.0}, "gate_ratio"),
                                      ({"shaft_p_fa": 0.0}, "shaft_p_fa"),
                                      ({"vf_band": (1000.0, 500.0)}, "vf_band"),
                                      ({"vf_band": (0.0, float("nan"))}, "vf_band")])
def test_criterion_refuses_bad_settings(kw, field):
    with pytest.raises(ParameterError, match=f"Criterion.{field}"):
        Criterion(**kw)
