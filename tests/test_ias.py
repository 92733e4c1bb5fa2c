"""The shaft's speed read from the record itself (bearing/diagnostics/ias.py) and the diagnosis on
it (pipelines/speed.py, diagnose.py, windows.py): a source and its copy
(synthetic.angle_coaxial_pair: outer-ring hits at the DTRB's BPFO order, each 1 % of a period off
its place, ringing 600 Hz; the copy through 546 Hz) along known speed profiles, given only the
record's mean speed.

Tolerances: the fault-line search takes a drift of the speed of TRACK_SPREAD (0.5 %: each
harmonic's window is 0.5 % of its fundamental wide, bearing/diagnostics/faultlines.py), so the
speed read must lie within it at 95 % of the samples; and the angle within a sixth of a BPFO
period (1 / (6 x 8.72) = 0.019 turns): the third harmonic, the highest searched, keeps its phase
within half a cycle over the record, so its line stays one line on the clock."""

import json

import numpy as np
import pytest

from axlebox.bearing import models
from axlebox.bearing.diagnostics import ias
from axlebox.bearing.diagnostics.criterion import Criterion
from axlebox.bearing.diagnostics.ordertrack import angle_from_speed
from axlebox.bearing.diagnostics.pair import analyse_pair
from axlebox.bearing.diagnostics.synthetic import angle_coaxial_pair, impulse_train, resonance
from axlebox.bearing.frequencies import shaft_hz
from axlebox.bearing.models.params import BearingParams
from axlebox.pipelines import speed as sp
from axlebox.pipelines.cli import main
from axlebox.pipelines.diagnose import analyse_record
from axlebox.pipelines.readers import Record

FS = 10_000.0
T = 6.0
O = models.orders(BearingParams())
REL = Criterion(mode="relative")
ANGLE_TOL = 1.0 / (6.0 * O.BPFO)
t = np.arange(int(T * FS)) / FS


def _record(f, seed=0, **kw):
    """``(healthy, defect, angle, mean Hz)`` of a source and its copy on the speed ``f`` (Hz at
    each sample of ``t``)."""
    angle = angle_from_speed(t, f)
    defect, healthy = angle_coaxial_pair(angle, FS, O.BPFO, np.random.default_rng(seed), **kw)
    return healthy, defect, angle, float(angle[-1] / t[-1])


RAMP = shaft_hz(30.0) + (shaft_hz(45.0) - shaft_hz(30.0)) * t / T       # 0.69 m/s^2
CONSTANT = np.full(t.size, shaft_hz(40.0))
SPLICE = np.where(t < T / 2, shaft_hz(30.0), shaft_hz(48.0))       # two records end to end


def test_a_linear_ramp_is_read_within_the_line_search_s_drift():
    """30 -> 45 km/h over the record: the BPFO family's ridge, the speed within TRACK_SPREAD at
    95 % of the samples, the angle within a sixth of a BPFO period; the range in the reason."""
    h, d, angle, mean = _record(RAMP)
    e = ias.estimate(h, d, FS, mean, O)
    assert e.status == "changing" and e.family == "BPFO", e.reason
    err = np.gradient(e.angle) * FS / RAMP - 1.0
    assert np.percentile(np.abs(err), 95) <= sp.TRACK_SPREAD
    assert np.max(np.abs(e.angle - angle)) <= ANGLE_TOL
    f = np.gradient(e.angle) * FS
    assert (f.min(), f.max()) == pytest.approx((RAMP.min(), RAMP.max()), rel=sp.TRACK_SPREAD)
    assert f"{f.min():.3g} to {f.max():.3g} Hz" in e.reason
    assert e.source == "estimated from the record (BPFO ridge)"


def test_an_alias_family_is_not_taken_for_the_speed():
    """Given a mean speed 1.152 times the true one (the DTRB's BPFO over its 2 BSF, 8.72 / 7.57),
    the BPFO lines read as a 2BSF family would at the given speed; the families' ridges are told
    apart only by the nominal: here the 2BSF ridge is named, at the given speed's scale."""
    h, d, angle, mean = _record(RAMP)
    ratio = O.BPFO / (2 * O.BSF)
    e = ias.estimate(h, d, FS, mean * ratio, O)
    assert e.family == "2BSF" and e.status == "changing"
    e0 = ias.estimate(h, d, FS, mean, O)
    assert e0.family == "BPFO"


def test_a_constant_speed_is_found_constant_and_read_as_before():
    """40 km/h: 'constant' (within TRACK_SPREAD) and the record read at the given speed, the
    verdict and its evidence the same as without the estimate (analyse_pair at that speed)."""
    h, d, _, mean = _record(CONSTANT)
    e = ias.estimate(h, d, FS, mean, O)
    assert e.status == "constant" and e.spread <= sp.TRACK_SPREAD, e.reason
    info, res = analyse_record(Record(h, d, FS, ("h", "d"), "csv"), None, shaft=mean, criterion=REL)
    ref = analyse_pair(h, d, FS, mean, (O, O), (0.13, 0.13), REL, rotor="shaft")
    assert info["speed"]["from"] == "given" and info["speed"]["estimate"]["status"] == "constant"
    assert not info["speed"]["order_tracked"]
    assert res.verdict.words == ref.verdict.words == {"left": "pseudo-fault", "right": "real fault"}
    assert res.verdict.rule == ref.verdict.rule and res.left.lines.keys() == ref.left.lines.keys()


def test_a_record_of_noise_gives_no_ridge_and_is_read_as_before():
    """No fault (noise only): nothing locked to the shaft stands, the record read at the given
    speed: both sides healthy, as without the estimate."""
    h, d, _, mean = _record(RAMP, amplitude=0.0)
    e = ias.estimate(h, d, FS, mean, O)
    assert e.status == "no ridge" and e.angle is None
    _, res = analyse_record(Record(h, d, FS, ("h", "d"), "csv"), None, shaft=mean, criterion=REL)
    assert res.verdict.words == {"left": "healthy", "right": "healthy"}


def test_a_speed_step_is_followed_away_from_it():
    """40 -> 46 km/h at mid-record (12 s): the step's size read within TRACK_SPREAD, and the
    speed within TRACK_SPREAD at 95 % of the samples more than two final frames (LADDER's last,
    in turns) from the step: the final profile is a least-squares cubic spline with knots a frame
    apart, whose basis functions span four knot intervals, so a step moves it two either side."""
    T2 = 12.0
    t2 = np.arange(int(T2 * FS)) / FS
    step = np.where(t2 < T2 / 2, shaft_hz(40.0), 1.15 * shaft_hz(40.0))
    angle = angle_from_speed(t2, step)
    d, h = angle_coaxial_pair(angle, FS, O.BPFO, np.random.default_rng(0))
    e = ias.estimate(h, d, FS, float(angle[-1] / t2[-1]), O)
    assert e.status == "changing", e.reason
    f = np.gradient(e.angle) * FS
    away = np.abs(t2 - T2 / 2) > 2 * ias.LADDER[-1][0] / step
    err = f[away] / step[away] - 1.0
    assert np.percentile(np.abs(err), 95) <= sp.TRACK_SPREAD
    before, after = (np.median(f[away & (t2 < T2 / 2)]), np.median(f[away & (t2 > T2 / 2)]))
    assert after / before == pytest.approx(1.15, abs=sp.TRACK_SPREAD)


@pytest.fixture(scope="module")
def splice(tmp_path_factory):
    """Two records end to end, 30 and 48 km/h: the ridge jumps (as CSV)."""
    h, d, _, mean = _record(SPLICE)
    path = tmp_path_factory.mktemp("splice") / "splice.csv"
    np.savetxt(path, np.column_stack([h, d]), delimiter=",", header="healthy,defect", comments="")
    return h, d, mean, path


def test_a_ridge_that_jumps_is_not_trusted_and_the_verdict_is_undecided(splice, tmp_path):
    """The speed rises by 60 % from one frame to the next: 'untrusted', the jump named; `axlebox
    diagnose` says 'undecided' on both sides, the reason first: the speed's change and the
    sources to give."""
    h, d, mean, path = splice
    e = ias.estimate(h, d, FS, mean, O)
    assert e.status == "untrusted" and "jumps by" in e.reason and e.angle is None
    out = tmp_path / "d.json"
    rc = main(["diagnose", str(path), "--left", "healthy", "--right", "defect", "--fs", str(FS),
               "--relative", "--shaft-hz", f"{mean:.6f}", "--json", str(out)])
    assert rc == 0
    v = json.loads(out.read_text())
    assert v["verdict"]["words"] == {"left": "undecided", "right": "undecided"}
    assert v["verdict"]["rule"] == "speed not read"
    for s in ("left", "right"):
        reason = v["verdicts"][s]["reason"]
        assert reason.startswith("the speed changes by") and sp.GIVE in reason
    assert v["input"]["speed"]["estimate"]["status"] == "untrusted"


def test_two_families_that_disagree_are_not_trusted():
    """A BPFO train on the ramp and, on both sides, impulses at a constant rate (a source not
    locked to the shaft, a compressor's) where the BPFI line sits at the mean speed, ringing the
    same mode at 0.3 of the fault's RMS: one ridge stands still while another climbs."""
    h, d, _, mean = _record(RAMP)
    rng = np.random.default_rng(7)
    other = resonance(impulse_train(t.size, FS, O.BPFI * mean, rng), FS, 600.0, 0.05)
    other *= 0.3 / other.std()
    e = ias.estimate(h + other, d + other, FS, mean, O)
    assert e.status == "untrusted" and "tells another speed" in e.reason, e.reason


def test_windows_say_which_speed_each_used_and_where_it_came_from(tmp_path, splice):
    """`axlebox diagnose --window-turns`: on a ramp each window's JSON line names the speed's
    source (the estimate's family) and the speed it was read at, rising window to window, the
    defect side never healthy; on the splice every window undecided with the reason."""
    h, d, _, mean = _record(RAMP)
    path = tmp_path / "ramp.csv"
    np.savetxt(path, np.column_stack([h, d]), delimiter=",", header="healthy,defect", comments="")
    out = tmp_path / "w.jsonl"
    base = ["--left", "healthy", "--right", "defect", "--fs", str(FS), "--relative",
            "--window-turns", "10", "--window-overlap", "0"]
    assert main(["diagnose", str(path), *base, "--shaft-hz", f"{mean:.6f}",
                 "--windows-out", str(out)]) == 0
    rows = [json.loads(line) for line in out.read_text().splitlines()][:-1]
    assert len(rows) == 2
    for r in rows:
        assert r["speed_source"] == "estimated from the record (BPFO ridge)"
        assert r["speed_hz"][0] <= r["shaft_hz"] <= r["speed_hz"][1]
        assert r["words"]["right"] != "healthy" and r["words"]["left"] not in ("real fault",
                                                                             "faults on both sides")
    assert rows[1]["shaft_hz"] > 1.1 * rows[0]["shaft_hz"]
    _, _, mean_s, spath = splice
    assert main(["diagnose", str(spath), *base, "--shaft-hz", f"{mean_s:.6f}",
                 "--windows-out", str(out)]) == 0
    rows = [json.loads(line) for line in out.read_text().splitlines()][:-1]
    assert rows and all(r["words"] == {"left": "undecided", "right": "undecided"} for r in rows)
    assert all(r["speed_source"] == "given" and "jumps by" in r["speed_note"] for r in rows)
