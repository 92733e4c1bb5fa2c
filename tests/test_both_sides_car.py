"""Beyond the paper (issues 20, 31): faults on both sides of a wheelset in the coupled car, one
fault and its copy, and the car's sweep as a dataset.

The sweep's cases of the validation case (configs/validation_48kmh.toml: 50.4 x 2 x 2 mm
outer-ring defects in row 2, at the top) with sides swept (``axlebox sweep --sides``): the defect on both
sides of wheelset 2 and on the gearbox side only, and no defect, at 80 km/h; and the study's
unequal pair (configs/study_unequal.toml: 1 mm 20 degrees on beside 2 mm) at 80 km/h.  The
criterion in its relative form, as the demo.  1.2 s each (0.7 s after the fade-in: 51 BPFO
periods); AXLEBOX_FULL=1 runs 2 s.  Two faults are told from one and its copy by their timing
(bearing/diagnostics/coherence.py): the two bearings' cages wander against each other, a copy
keeps its source's timing.
"""
import pytest
import xarray as xr

from axlebox import configs
from axlebox.bearing.diagnostics.criterion import Criterion
from axlebox.pipelines import cli
from axlebox.pipelines.diagnose import analyse_file
from axlebox.pipelines.sweep import load_config, matrix, run_cases

from conftest import assert_windows_are_the_source, full_size

REL = Criterion(mode="relative")
C_INDEPENDENT = REL.c_independent       # the criterion's default, 0.2


@pytest.fixture(scope="module")
def runs(tmp_path_factory):
    """The four cases in one batch on two single-threaded workers (two sweeps, of three cases and
    of one, kept a core idle for a case's length)."""
    out = tmp_path_factory.mktemp("both_sides")
    T = 2.0 if full_size() else 1.2
    cases = (matrix(*load_config(configs.path("validation_48kmh")), [80.0], [0.0, 2.0], T, None, ["LR", "R"])
             + matrix(*load_config(configs.path("study_unequal")), [80.0], None, T))
    assert run_cases(cases, out, workers=2, log=lambda *_: None) == []
    (out / "v80_w2.h5").rename(out / "v80_unequal.h5")
    names = {"v80_w2_LR", "v80_w2_R", "v80_w0", "v80_unequal"}
    assert {p.stem for p in out.glob("*.h5")} == names
    assert not list(out.rglob("*.toml"))          # the cases ran from memory (simulate.Config)
    return out


def _pair(runs, name, criterion=REL):
    _, _, pair = analyse_file(runs / f"{name}.h5", criterion=criterion)
    print(name, pair.verdict.words, pair.verdict.rule,
          [(e.key, e.timing and e.timing.decision, e.timing and e.timing.c_min, e.votes)
           for e in pair.evidence if any(e.seen.values())])
    return pair


@pytest.mark.slow
@pytest.mark.parametrize("name", ["v80_w2_LR", "v80_unequal"])
def test_defects_on_both_sides_are_faults_on_both_sides(runs, name):
    """Each axle box's BPFO is its own bearing's train: in the two sides' own bands the line's
    coherent fraction falls under 0.2 (benchmarks/README.md "Copy or source"), and each stands
    clear of a healthy bearing's lines; in the relative and the paper's absolute form."""
    for crit in (REL, Criterion()):
        pair = _pair(runs, name, crit)
        assert pair.verdict.words == {"left": "faults on both sides", "right": "faults on both sides"}
        assert pair.verdict.rule == "each side owns a line"
        assert {s: k.kind for s, k in pair.verdict.kinds.items()} == {"left": "outer ring",
                                                                      "right": "outer ring"}
    ev = next(e for e in pair.evidence if e.line == "BPFO")
    assert ev.timing.decision == "independent" and ev.timing.c_min <= C_INDEPENDENT
    assert min(ev.best_snr_db.values()) >= REL.second_db


@pytest.mark.slow
def test_a_defect_on_one_side_keeps_real_and_pseudo(runs):
    """The copy keeps the defect side's timing (coherent fraction over 0.2 in every pair of the
    two sides' own bands); the impulses' lag and where the line rings name the defect side."""
    pair = _pair(runs, "v80_w2_R")
    assert (pair.verdict.words["right"], pair.verdict.words["left"]) == ("real fault", "pseudo-fault")
    ev = next(e for e in pair.evidence if e.line == "BPFO")
    assert ev.timing.decision != "independent"
    assert pair.verdict.real == "right" and pair.verdict.rule in ("lag", "ringing")
    assert pair.verdict.kinds["right"].kind == "outer ring" and pair.verdict.kinds["left"] is None
    assert ev.votes["right"] > ev.votes["left"]


@pytest.mark.slow
def test_no_defect_is_healthy(runs):
    pair = _pair(runs, "v80_w0")
    assert pair.verdict.words["left"] == pair.verdict.words["right"] == "healthy"
    # the car without a defect shows a narrow line at a whole order in its spectrum at some
    # speeds (README, "Wheel flats and polygons"): named as the wheel's, no bearing line
    assert pair.verdict.rule in ("no fault line", "wheel lines only")
    bearing = {"BPFO", "BPFI", "2BSF"}
    assert not bearing & set(pair.left.detected) and not bearing & set(pair.right.detected)


@pytest.mark.slow
def test_the_sweep_as_a_dataset(runs, tmp_path):
    """``axlebox dataset`` on the car's 4-case sweep: every label, the windows bit for bit, the
    verdicts those of diagnose, a card."""
    data = tmp_path / "data"
    assert cli.main(["dataset", str(runs), "--out", str(data), "--window", "0.3", "--hop", "0.2"]) == 0
    ds = xr.load_dataset(data / "dataset.nc")
    labels = ds.drop_dims("sample").to_dataframe()
    real = {"v80_unequal": "both", "v80_w2_LR": "both", "v80_w2_R": "right", "v80_w0": "none"}
    assert set(labels.case) == set(real)
    for name, side in real.items():
        rows = labels[labels.case == name]
        assert set(rows.real_side) == {side}
        pair = analyse_file(runs / f"{name}.h5", criterion=REL)[2]
        assert set(rows.left_verdict) == {pair.verdict.words["left"]}
        assert set(rows.right_verdict) == {pair.verdict.words["right"]}
        assert set(rows.speed_kmh) == {float(name[1:3])}
        assert set(rows.right_kind) == {"none" if side == "none" else "outer"}
    assert_windows_are_the_source(ds, runs)
    card = (data / "README.md").read_text()
    assert all(f"| {name} |" in card for name in real)
