"""The verdicts on two channels: a small decision procedure, :func:`decide`, that returns a
:class:`.verdict.Verdict` (the rule that decided and the evidence it read);
:func:`.verdict.sentence` renders it.

The paper's criterion (section "Difference analyses of vibration characteristics ...", Fig. 14,
conclusions (2)-(3)): if the difference of the frequency variances (VF, Eq. 18) of the two
axle-box signals of a wheelset lies in 0.8e4-7.49e4 Hz^2, a pseudo-fault is present on one
side; the side with the larger RMS and SPM (Eq. 17) is the real fault, the other the
pseudo-fault.  It names the source of one fault seen on both sides; it cannot say whether there
is a fault, nor whether both bearings have one.  :func:`decide` asks those first, from the fault
lines' evidence (:class:`.verdict.LineEvidence`, built by :mod:`.pair`), read once into a frozen
:class:`.verdict.Evidence` from which the rule follows:

1. *No line* (rule ``no fault line``): none of ``Criterion.lines`` (BPFO outer ring, BPFI inner
   ring, 2BSF a rolling element with its cage sidebands; :mod:`.faultlines`) is detected on
   either side, for either side's bearing -> both healthy; ``wheel lines only`` where lines at
   whole multiples of the shaft's rate stand there (:mod:`.wheel`: a wheel flat's comb, a
   polygon's line; a fault line found on one is the shaft's, :func:`.faultlines.mask_sidebands`),
   named in the evidence and the sentence; ``shaft lines only`` on a machine's record (``rotor
   = "shaft"``: a speed given as ``--rpm`` or ``--shaft-hz``, its rotor's unbalance and
   misalignment).
2. *Whose line*.  Each line seen gets its source side(s) (``how`` in the evidence):

   * ``bearing order``: where the two sides' bearings differ (the CWRU motor's 6205 and 6203),
     a line at one bearing's order is that bearing's, on whichever side it is seen;
   * ``one side only``: a line of a bearing type both sides share, seen on one side only (the
     other side was searched again in the band where the line stands highest);
   * seen on both sides, the copy-or-source test (:mod:`.coherence`): two impulse trains
     (``own timing``: a harmonic whose line-to-noise ratio reaches ``Criterion.rho_min_db``
     (15 dB) on both sides, whose coherence lies ``Criterion.z_min`` (5) standard deviations
     under a copy's and whose coherent fraction is ``Criterion.c_independent`` (0.2) or less)
     are a fault on each side; otherwise one fault and its copy (``coherent``, ``partly coherent``,
     ``inconclusive``: a weak line is never shown to be its own, the safe side).

3. *Both own*: each side's own line must stand ``second_db`` (15 dB) over its floor in its best
   band (:func:`.guided.band_scan`) -> faults on both sides (``each side owns a line``).  Every
   bearing shows its own pass lines faintly (rollers passing the load zone; the model's healthy
   bearings, no-defect runs at 20-80 km/h, reach 13 dB with a detected line, benchmarks/
   README.md "Copy or source"), so a fainter own line beside the other side's clear one is
   ``second line faint``: the side whose own line stands ``Criterion.clearer_db`` (3 dB, twice
   the scatter of a line's SNR read over a median floor of some 40 bins) over the other's is real,
   the faint one undecided; lines within 3 dB of each other, neither clear, are ``both lines
   faint`` (both undecided): a healthy bearing called faulty is the worst error.
4. *One owns* (``one side owns the lines``): that side the real fault; the other a pseudo-fault
   where it shows a line (a copy, or the other bearing's line carried) or where the VF
   difference lies in the range (the paper's sign of a pseudo-fault), else healthy.  A line of
   a bearing type both sides share, seen on one side only with nothing on the other, is its
   side's fault only where the paper's signs agree: the two spectra differ (VF difference not
   below the range, else ``one side only, spectra alike``) and its side is the louder (every
   indicator of ``Criterion.compare`` larger, else ``one side only, not the louder``); both
   undecided otherwise.  A healthy bearing shows its own pass lines too (the model's no-defect
   car at 20 km/h shows BPFO with two harmonics on its quieter side, 13 dB over the floor),
   while a defect raises its side's vibration and changes its spectrum (the paper's Figs. 11,
   14).
5. *One fault and its copy*, the source named (``Criterion.source = "ringing"``, default):

   * by the impulses' lag (``lag``; the paper, Fig. 13 and conclusion 2: the healthy side lags
     by 1.1-4.2 ms; :func:`.lag.impulse_lag`: at least five impulses, 90 % of the bootstrap
     agreeing; with ``Criterion.lag = "decide"``) and by where the line rings (``ringing``: the
     side whose line stands higher in at least ``source_ratio`` times as many bands of the grid
     as the other's, and in at least ``ringing_bands`` (3), :func:`.pair.band_votes`: a copy is
     its source through a path that passes some bands and stops others).  Where both speak and
     disagree: ``lag and ringing disagree``, both undecided (the lag is ambiguous by whole fault
     periods; a path resonance can lift a copy over its source in that band);
   * else by the paper's criterion: the VF difference ``m`` against the range, below (``VF below
     the range``) or above (``VF above the range``) -> both undecided; in range, the side where
     every indicator of ``Criterion.compare`` (RMS and SPM) is larger (``RMS and SPM``), unless
     they disagree (``indicators disagree``) or a lag by envelope correlation contradicts
     them (``lag contradicts``); the side named must show the line (``no line on the source``).

   ``Criterion.source = "paper"`` is the paper's criterion alone for this step (what
   :mod:`axlebox.pipelines.conclusions` checks the paper's claims with), the lag entering by
   ``Criterion.lag``: ``"decide"`` (a lag read on the impulses names the real side whatever
   RMS and SPM say, the paper's conclusion 1: amplitudes alone cannot tell the two apart),
   ``"veto"`` (a leading side that contradicts RMS and SPM makes both undecided, and breaks
   their tie) or ``"off"`` (RMS and SPM alone, the lag quoted).  A lag by correlation is used
   only from ``lag_min_peak``, and only to veto.

Carrying the range to another machine.  VF is in Hz^2, so the paper's range belongs to the metro
car's frequencies: a machine whose resonances sit k times higher has VF (and VF differences) k^2
times larger.  Two settings:

* ``mode="absolute"``: ``m = |VF_L - VF_R|`` against ``vf_range`` (Hz^2; default the paper's);
  choose the range for the machine, e.g. the paper's scaled by the ratio of the VF of a flat
  spectrum over the band the machine's signals fill to ``VF_METRO`` below (the CWRU rig's
  accelerometers fill 0-6 kHz: 3e6 / 5.72e4 = 52, tests/test_diagnose_cli.py).
* ``mode="relative"``: ``m = |VF_L - VF_R| / max(VF_L, VF_R) = 1 - VF_min / VF_max``, in
  [0, 1): the share of the more dispersed side's variance the other lacks.  It is unchanged when
  all frequencies scale together and does not depend on the sampling rate once the band holds
  the signal.  Mapping the paper's range: the paper gives the VF differences, not the levels;
  its healthy side's spectrum lies in 0-200 Hz and 300-800 Hz (Fig. 12), whose VF, for a flat
  PSD over those bands, is ``VF_METRO = 5.72e4 Hz^2``.  So the lower bound is ``0.8e4 / 5.72e4 =
  0.14``.  The upper bound 7.49e4 / 5.72e4 = 1.31 exceeds what ``m`` can reach (``dVF <=
  VF_max``): it was the largest difference simulated, not a limit, so the relative upper bound
  is 1.

The band of FC and VF (``vf_band``).  Eq. 18 integrates the PSD over whatever band the record
holds, so VF and its difference grow with the band: a 10 kHz record of the metro car's axle
box holds the bearing's 2-5 kHz ringing, which the paper's co-simulation (its bearing stepped
at 1e-4 s) carried little of.  ``vf_band = (lo, hi)`` takes FC and VF over that band of each
side's PSD alone; None (the default) over the whole record.

The paper's band, :data:`VF_BAND_PAPER` = 0-1 kHz, read from the paper before any count was
made with it:

* its spectra: the healthy side's energy lies in 0-200 and 300-800 Hz (Fig. 12, the text under
  it), the defect side's lines "decrease with frequency" over the same axes; :data:`VF_METRO`
  already rests on that band;
* its integration: the DTRB's equations by a fixed-step Runge-Kutta at 1e-4 s (its validation
  section, before Table 1), exchanged with SIMPACK through SIMAT at that step.  The classical RK4 keeps a
  free oscillation at f per step by ``|R(i 2 pi f h)|``, ``R(z) = 1 + z + z^2/2 + z^3/6 +
  z^4/24``: over one period it keeps 99.6 % at 1 kHz, 97.1 % at 1.5 kHz, 89.4 % at 2 kHz,
  73.2 % at 2.5 kHz and 49.2 % at 3 kHz (a numerical damping ratio of 0.07 %, 0.5 %, 1.8 %,
  5 % and 11 %; tests/test_diagnostics_pair.py computes them).  Up to 1 kHz the paper's
  bearing rang as ours does; from 2 kHz on its integrator damped the ring as hard as the
  structure's own 2 % would, and the axle box's 2-5 kHz modes, which hold half our defect
  side's power, reached its spectra weakened or not at all.

So the band where the paper's spectra and its integration agree with ours is 0-1 kHz; 0-0.8,
0-1.5, 0-2.5 kHz and the whole band are its sensitivity (benchmarks/vf_band.py).
"""
from __future__ import annotations



from axlebox._params import ParameterError

# the thresholds are declared in .thresholds; they are re-exported here, where the procedure reads them
from .thresholds import (ANALYSIS, COMPARABLE, FAULT_LINES, LAG_POLICIES, MODES,  # noqa: F401
                         OPTIONS, PAPER, PAPER_ALONE, PAPER_RK4_STEP, REL_RANGE_DEFAULT, SOURCE_RULES,
                         VF_BAND_PAPER, VF_METRO, VF_RANGE_PAPER, Criterion)
from .kind import kinds
from .verdict import (LINES_ONLY, ROTORS, SIDES, Evidence, LagReading, LineEvidence, LineReading,
                      ShaftOrders, Verdict, VFReading)


def vf_difference(vf_left: float, vf_right: float, criterion: Criterion = PAPER) -> float:
    """The criterion's ``m``: ``|VF_L - VF_R|`` (Hz^2) or, in relative mode, that over the larger VF."""
    d = abs(vf_left - vf_right)
    if criterion.mode == "absolute":
        return float(d)
    top = max(vf_left, vf_right)
    return float(d / top) if top > 0 else 0.0


def _reading(ev: LineEvidence, criterion: Criterion) -> LineReading:
    """How one line is read (module docstring, step 2): its source side(s) and how they were
    found, and its least coherent fraction under the criterion's thresholds."""
    c_min = None if ev.timing is None else ev.timing.coherent_fraction(
        rho_min_db=criterion.rho_min_db, z_min=criterion.z_min)
    seen = [s for s in SIDES if ev.seen[s]]
    if not seen:
        return LineReading(ev, (), "not seen", c_min)
    if ev.bearing in SIDES:
        return LineReading(ev, (ev.bearing,), "bearing order", c_min)
    if len(seen) == 1:
        return LineReading(ev, (seen[0],), "one side only", c_min)
    decision = "inconclusive" if ev.timing is None else ev.timing.decide(**criterion.coherence)
    if decision == "independent":
        return LineReading(ev, SIDES, "own timing", c_min)
    return LineReading(ev, (), decision, c_min)


def evidence_from_channels(left, right, lines) -> list[LineEvidence]:
    """Line evidence from two :class:`.channel.ChannelResult` alone (no timing, no shares): each
    of ``lines`` of a bearing both sides share, and each carried line."""
    ch = {"left": left, "right": right}
    out = []
    for n in lines:
        def seen(r, key):
            return key in r and r[key].detected
        out.append(LineEvidence(n, "both", {s: seen(ch[s].lines, n) for s in SIDES},
                                {s: _snr(ch[s].lines, n) for s in SIDES}))
        for b, o in (("left", "right"), ("right", "left")):
            carried = getattr(ch[o], "carried", {})
            if n in carried:        # bearing b's line, searched on side o too
                out.append(LineEvidence(n, b, {b: False, o: seen(carried, n)},
                                        {b: float("nan"), o: _snr(carried, n)}))
    return out


def _snr(found: dict, key: str) -> float:
    return float(found[key].snr_db) if key in found else float("nan")


def decide(left, right, lag=None, criterion: Criterion = PAPER,
           lines: list[LineEvidence] | None = None, gate=None, rotor: str = "wheel",
           orders=None, spread: float = 0.0) -> Verdict:
    """The :class:`.verdict.Verdict` on two :class:`.channel.ChannelResult` (``FC``/``VF``,
    ``rms``, ``spm_db``, ``lines``), an optional :class:`.lag.LagResult` whose channel ``a`` is
    ``left``, and the lines' evidence (default :func:`evidence_from_channels`: no timing, so a
    line seen on both sides is a copy); ``gate``: the wheel's strikes blanked before (the
    :class:`.gate.Gate`), quoted in the evidence; ``rotor``: what turns the shaft, ``"wheel"``
    (a vehicle) or ``"shaft"`` (a machine's rotor), the words of the whole orders' lines.  The
    :class:`.verdict.Evidence` is read once, here; the rule follows from it alone.  Each side
    called faulty gets its fault's kind (:mod:`.kind`), from ``orders`` (side -> its bearing's
    FaultOrders; None: the lines alone) and ``spread``, the shaft speed's range over its mean as
    the record was read (0 on the shaft's clock or at a constant speed)."""
    if rotor not in ROTORS:
        raise ParameterError(f"rotor = {rotor!r} is not allowed: expected one of " + ", ".join(ROTORS))
    ch = {"left": left, "right": right}
    lines = evidence_from_channels(left, right, criterion.lines) if lines is None else \
        [ev for ev in lines if ev.line in criterion.lines]
    read = tuple(_reading(ev, criterion) for ev in lines)
    owns = {s: [r for r in read if s in r.sources] for s in SIDES}
    strength = None
    if owns["left"] and owns["right"]:
        strength = {s: float(max(r.line.best_snr_db.get(s, r.line.snr_db[s]) for r in owns[s]))
                    for s in SIDES}
    copies = [r.line for r in read if all(r.line.seen.values()) and not r.sources]
    ev = Evidence(
        lines=read,
        vf=VFReading(float(left.VF), float(right.VF), vf_difference(left.VF, right.VF, criterion),
                     tuple(criterion.range), criterion.unit),
        indicators={c: {s: float(getattr(ch[s], c)) for s in SIDES} for c in criterion.compare},
        larger={c: ("left" if getattr(left, c) > getattr(right, c) else "right")
                for c in criterion.compare},
        lag=_lag_reading(lag, criterion),
        orders={s: ShaftOrders(tuple(getattr(ch[s], "wheel_env", ())),
                               tuple(getattr(ch[s], "wheel_spec", ()))) for s in SIDES},
        rotor=rotor, criterion=criterion, gate=gate, strength_db=strength,
        ringing=_ringing(copies, criterion) if criterion.source == "ringing" else None)
    words, rule, real = _rule(ev)
    words = dict(zip(SIDES, words))
    return Verdict(words, rule, real, ev, kinds(ev, words, real, orders, spread))


def _named(real: str, other: str) -> tuple[str, str]:
    """The words: ``real`` a real fault, the other side ``other``."""
    return tuple("real fault" if s == real else other for s in SIDES)


UNDECIDED = ("undecided", "undecided")


def _rule(ev: Evidence) -> tuple[tuple[str, str], str, str | None]:
    """``(words, rule, real side)`` from the evidence alone (module docstring, steps 1-5)."""
    crit = ev.criterion
    shows = {s: ev.shown(s) for s in SIDES}
    if not shows["left"] and not shows["right"]:
        return ("healthy", "healthy"), LINES_ONLY[ev.rotor] if ev.shaft_lines else "no fault line", None
    st = ev.strength_db
    if st is not None:
        if min(st.values()) >= crit.second_db:
            return ("faults on both sides",) * 2, "each side owns a line", None
        s = max(SIDES, key=st.get)
        if st[s] < min(st.values()) + crit.clearer_db:
            return UNDECIDED, "both lines faint", None
        return _named(s, "undecided"), "second line faint", s
    other = {"left": "right", "right": "left"}
    for s in SIDES:
        owns, o = ev.owned(s), other[s]
        if owns and not ev.owned(o):
            alone = all(r.how == "one side only" for r in owns)
            if alone and not shows[o]:
                if ev.vf.m < ev.vf.range[0]:
                    return UNDECIDED, "one side only, spectra alike", None
                if any(d[s] <= d[o] for d in ev.indicators.values()):
                    return UNDECIDED, "one side only, not the louder", None
            word_o = "pseudo-fault" if shows[o] or ev.vf.in_range else "healthy"
            return _named(s, word_o), "one side owns the lines", s
    return _source(ev)


def _lag_reading(lag, criterion) -> LagReading | None:
    """The lag as the verdict reads it: the leading side where it may be used, else None."""
    if lag is None:
        return None
    method = getattr(lag, "method", "correlation")
    lead = None
    if lag.leading in ("a", "b") and (method == "impulses" or lag.peak >= criterion.lag_min_peak):
        lead = "left" if lag.leading == "a" else "right"
    return LagReading(lead, float(lag.lag_s), method, int(getattr(lag, "n_impulses", 0)),
                      float(getattr(lag, "agreement", 1.0)), float(lag.peak))


def _ringing(copies, criterion) -> str | None:
    """The source of one fault and its copy by where the lines ring (step 5): the side whose
    line stands higher in at least ``source_ratio`` times as many bands of the grid as the
    other's, and in at least ``ringing_bands`` (:func:`.pair.band_votes`; a copy is its source
    through a path that passes some bands and stops others); None where no line tells or the
    lines disagree."""
    named = set()
    for e in copies:
        v = e.votes
        if not v:
            continue
        hi, lo = sorted(SIDES, key=v.get, reverse=True)
        if v[hi] >= criterion.source_ratio * max(v[lo], 1) and v[hi] >= criterion.ringing_bands:
            named.add(hi)
    return named.pop() if len(named) == 1 else None


def _source(ev: Evidence) -> tuple[tuple[str, str], str, str | None]:
    """Step 5: one fault and its copy, the source named by where the lines ring, else by the
    paper's criterion and the lag."""
    crit, lag = ev.criterion, ev.lag
    if crit.source == "ringing":
        lead = lag.leading if lag is not None and lag.method == "impulses" and \
            crit.lag == "decide" else None
        ring = ev.ringing
        if lead is not None and ring is not None and lead != ring:
            return UNDECIDED, "lag and ringing disagree", None
        if lead is not None or ring is not None:
            return _named(lead or ring, "pseudo-fault"), "lag" if lead is not None else "ringing", \
                lead or ring
    if ev.vf.m < ev.vf.range[0]:
        return UNDECIDED, "VF below the range", None
    if ev.vf.m > ev.vf.range[1]:
        return UNDECIDED, "VF above the range", None
    split = len(set(ev.larger.values())) > 1
    by_indicators = None if split else next(iter(ev.larger.values()))
    lead = None if lag is None else lag.leading
    sure = lag is not None and lag.method == "impulses"
    seen = {s: any(e.seen[s] for e in ev.copies) for s in SIDES}
    if lead is not None and crit.lag != "off" and seen[lead] and (
            (sure and crit.lag == "decide") or split):
        real, rule = lead, "lag"
    elif split:
        return UNDECIDED, "indicators disagree", None
    else:
        real, rule = by_indicators, "RMS and SPM"
        if lead is not None and lead != real and crit.lag != "off":
            return UNDECIDED, "lag contradicts", None
    if not seen[real]:
        return UNDECIDED, "no line on the source", real
    return _named(real, "pseudo-fault"), rule, real
