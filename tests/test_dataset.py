"""``axlebox dataset``: a sweep folder as labelled windows of the two axle-box signals.

A 4-case sweep with known answers, written as the vehicle's result files (bearing/diagnostics/
synthetic.py): no defect, an outer-ring defect on the left, on the right, and on both sides.  The
coupled car's own 4-case sweep goes through the same command in tests/test_both_sides_car.py.
"""
import h5py
import numpy as np
import pandas as pd
import pytest
import xarray as xr

from axlebox.bearing import resultfile
from axlebox.bearing.diagnostics.synthetic import both_sides_pair, coaxial_pair
from axlebox.bearing.frequencies import orders, shaft_hz
from axlebox.bearing.models.params import BearingParams
from axlebox.pipelines import cli
from axlebox.pipelines.diagnose import analyse_file

from conftest import assert_windows_are_the_source, write_pair_result

FS = 10_000.0
T = 3.0
DEFECT = '[[defects]]\nwheelset = 2\nside = "{side}"\nW = 0.002\nrow = 2\nkind = "{kind}"\n'
# the axle-boxes on the DTRB (the defects' bearings) at a step it takes: a config a run accepts
BEARINGS = '[joint]\nmodel = "bearing"\n[integrator]\ndt = 1e-5\n'
CASES = {"none": ((), "none"), "left": (("L",), "left"), "right": (("R",), "right"),
         "both": (("L", "R"), "both")}


def write_case(folder, name, sides, speed=48.0, seed=0, kind="outer"):
    rng = np.random.default_rng(seed)
    bpfo = orders(BearingParams()).BPFO * shaft_hz(speed)
    house = dict(f_res=3000.0, zeta=0.03, noise=0.3)
    if len(sides) == 2:
        left, right = both_sides_pair(T, FS, bpfo, rng, **house)
    else:
        a, b = coaxial_pair(T, FS, bpfo, rng, amplitude=1.0 if sides else 0.0, **house)
        left, right = (a, b) if sides == ("L",) else (b, a)
    cfg = (f"[run]\nspeed_kmh = {speed}\n" + BEARINGS
           + "".join(DEFECT.format(side=s, kind=kind) for s in sides))
    return write_pair_result(folder / f"{name}.h5", left, right, cfg, FS, seed)


@pytest.fixture(scope="module")
def sweep_dir(tmp_path_factory):
    d = tmp_path_factory.mktemp("sweep")
    for i, (name, (sides, _)) in enumerate(CASES.items()):
        write_case(d, name, sides, seed=i)
    return d


@pytest.fixture(scope="module")
def dataset(sweep_dir, tmp_path_factory):
    out = tmp_path_factory.mktemp("data") / "data"
    assert cli.main(["dataset", str(sweep_dir), "--out", str(out), "--window", "0.4",
                     "--hop", "0.3"]) == 0
    return out


def test_loads_in_one_line_with_every_label(dataset):
    ds = xr.open_dataset(dataset / "dataset.nc")
    labels = ds.drop_dims("sample").to_dataframe()
    assert isinstance(labels, pd.DataFrame)
    for col in ("case", "file", "start_index", "t_start", "speed_kmh", "wheelset", "real_side",
                "left_kind", "left_W", "left_L", "left_H", "left_row", "right_kind", "right_W",
                "right_L", "right_H", "right_row", "left_verdict", "right_verdict"):
        assert col in labels.columns, col
    # 2.5 s after the fade-in: windows of 0.4 s every 0.3 s start at 0.5, 0.8, ... 2.6 s
    per_case = labels.groupby("case").size()
    assert dict(per_case) == {c: 8 for c in CASES}
    assert ds.sizes["sample"] == 4000 and ds.attrs["fs_hz"] == FS
    for name, (sides, real) in CASES.items():
        rows = labels[labels.case == name]
        assert set(rows.real_side) == {real}
        for s, letter in (("left", "L"), ("right", "R")):
            kind = "outer" if letter in sides else "none"
            assert set(rows[f"{s}_kind"]) == {kind}
            assert set(rows[f"{s}_W"]) == ({0.002} if kind == "outer" else {0.0})
    ds.close()


def test_windows_reproduce_the_source_arrays_exactly(dataset, sweep_dir):
    ds = xr.load_dataset(dataset / "dataset.nc")
    assert_windows_are_the_source(ds, sweep_dir)
    for k in range(ds.sizes["window"]):
        w = ds.isel(window=k)
        assert float(w.t_start) == pytest.approx(int(w.start_index) / FS)


def test_verdict_labels_are_what_diagnose_says(dataset, sweep_dir):
    """The labels' verdicts are the relative criterion's on each whole record; on these known
    answers: healthy without defects, real on the defect side, faults on both sides."""
    from axlebox.bearing.diagnostics.criterion import Criterion
    labels = xr.open_dataset(dataset / "dataset.nc").drop_dims("sample").to_dataframe()
    expect = {"none": ("healthy", "healthy"), "left": ("real fault", "pseudo-fault"),
              "right": ("pseudo-fault", "real fault"),
              "both": ("faults on both sides", "faults on both sides")}
    for name in CASES:
        r = labels[labels.case == name].iloc[0]
        _, _, pair = analyse_file(sweep_dir / f"{name}.h5", criterion=Criterion(mode="relative"))
        assert (r.left_verdict, r.right_verdict) == (pair.verdict.words["left"], pair.verdict.words["right"])
        assert (r.left_verdict, r.right_verdict) == expect[name], name
        # the rule and the evidence's fields, not only the sentence
        v = pair.verdict
        assert (r.verdict_rule, r.verdict_real, r.verdict_rotor) == (v.rule, v.real or "none", "wheel")
        assert r.verdict_vf_m == pytest.approx(v.evidence.vf.m, rel=1e-12)
        assert r.verdict_lag_leading == (v.evidence.lag.leading or "none")
        assert r.left_reason == v.sentence("left")
        # issue 57: the fault's kind on each side called faulty (these hit at BPFO: the outer
        # ring), where the speed came from and whether the record was order-tracked
        for side in ("left", "right"):
            kind = r[f"verdict_kind_{side}"]
            faulty = r[f"{side}_verdict"] in ("real fault", "faults on both sides")
            assert kind == ("outer ring" if faulty else "none"), (name, side, kind)
        assert (r.speed_from, bool(r.order_tracked)) == ("config", False)
        # each side's defect size as the diagnosis reads it (bearing/diagnostics/size.py)
        for s in ("left", "right"):
            got = pair.sizes[s]
            assert r[f"{s}_size"] == got.status
            assert (r[f"{s}_size"] == "not read") == (pair.verdict.words[s] not in
                                                      ("real fault", "faults on both sides"))
            if got.width_m is not None:
                assert r[f"{s}_width_mm"] == pytest.approx(1e3 * got.width_m, rel=1e-12)


def test_card_states_how_it_was_made(dataset):
    card = (dataset / "README.md").read_text()
    assert "xr.open_dataset" in card and "--window 0.4 --hop 0.3" in card
    for name in CASES:
        assert f"| {name} |" in card
    assert "split training and test data by case" in " ".join(card.split())
    assert not list(dataset.glob("*.tmp"))


def _rig_result(folder):
    z = np.zeros((100, 3))
    return resultfile.write(folder / "rig.h5", config_toml="[rig]\nspeed_kmh = 48.0\n", seed=0,
                            time=np.arange(100) / FS, fs_hz=FS, signals={"outer_ring": {"acceleration": z}})


@pytest.mark.parametrize("setup, args, words", [
    (lambda d: None, ["nowhere"], "SWEEP_DIR"),
    (lambda d: (d / "empty").mkdir(), ["empty"], "no result file"),
    (lambda d: (d / "r").mkdir() or _rig_result(d / "r"), ["r"], "bearing-rig result"),
    (lambda d: (d / "x").mkdir() or h5py.File(d / "x" / "plain.h5", "w").close(), ["x"],
     "not an axlebox result"),
    (lambda d: None, ["SWEEP", "--window", "0"], "--window"),
    (lambda d: None, ["SWEEP", "--hop", "-1"], "--hop"),
    (lambda d: None, ["SWEEP", "--window", "5"], "--window 5 s is not allowed"),
    (lambda d: (d / "file").write_text(""), ["SWEEP", "--out", "FILE"], "is a file"),
    (lambda d: None, ["SWEEP", "--criterion", "loose"], "--criterion"),
])
def test_bad_input_exits_2_with_one_line(tmp_path, sweep_dir, capsys, setup, args, words):
    setup(tmp_path)
    argv = [str(sweep_dir) if a == "SWEEP" else str(tmp_path / "file") if a == "FILE"
            else str(tmp_path / a) if a in ("nowhere", "empty", "r", "x") else a for a in args]
    if "--out" not in argv:
        argv += ["--out", str(tmp_path / "out")]
    try:
        rc = cli.main(["dataset", *argv])
    except SystemExit as e:             # argparse's refusals (--criterion choices)
        rc = e.code
    assert rc == 2
    err = capsys.readouterr().err.strip()
    assert len(err.splitlines()) == 1 and words in err and "Traceback" not in err, err


def test_the_speed_options_reach_the_labels(sweep_dir, tmp_path, capsys):
    """Issue 57 item 6: ``dataset`` takes ``--order-tracking`` and the speed sources as
    ``diagnose`` does: "on" without a speed over time (these constant-speed results store none)
    is one line naming what to give, exit 2; "off" labels every window not order-tracked."""
    assert cli.main(["dataset", str(sweep_dir), "--out", str(tmp_path / "on"),
                     "--order-tracking", "on"]) == 2
    err = capsys.readouterr().err.strip()
    assert "--order-tracking on needs the shaft's speed" in err and len(err.splitlines()) == 1
    assert cli.main(["dataset", str(sweep_dir), "--out", str(tmp_path / "csv"),
                     "--speed-csv", str(tmp_path / "v.csv")]) == 2
    err = capsys.readouterr().err.strip()
    assert "--speed-csv" in err and len(err.splitlines()) == 1
    assert cli.main(["dataset", str(sweep_dir), "--out", str(tmp_path / "off"), "--window", "1",
                     "--hop", "1", "--order-tracking", "off"]) == 0
    labels = xr.open_dataset(tmp_path / "off" / "dataset.nc").drop_dims("sample").to_dataframe()
    assert not labels.order_tracked.any() and set(labels.speed_from) == {"config"}
