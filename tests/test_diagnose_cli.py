"""``axlebox diagnose``: a real two-sensor recording, the file readers, and bad input.

The recording is CWRU record 130 (../shared/reference/cwru/README.md): drive-end 6205 bearing
with a 0.007 in outer-race fault, fan-end 6203 bearing healthy, one shaft at 1796 rpm, 12 kHz.
The drive end must come out as the real fault and the fan end as the pseudo-fault.  Every shared
record is scored in tests/test_real_records.py.
"""
import json
import subprocess
import sys

import h5py
import numpy as np
import pytest
import scipy.io

from axlebox.bearing import resultfile
from axlebox.bearing.diagnostics.channel import jsonable
from axlebox.bearing.diagnostics.criterion import VF_METRO, VF_RANGE_PAPER, Criterion
from axlebox.bearing.diagnostics.pair import analyse_pair
from axlebox.bearing.frequencies import FaultOrders, orders, shaft_hz
from axlebox.bearing.models.params import BearingParams
from axlebox.pipelines import diagnose, readers
from axlebox.pipelines.cli import main

from conftest import reference_dir

CWRU = reference_dir() / "cwru" / "cwru_130_OR007_6_0_DE12k.mat"
# CWRU's published fault orders of the drive-end 6205 (README there); BSF = rolling element / 2
CWRU_ORDERS = "BPFO=3.5848,BPFI=5.4152,FTF=0.39828,BSF=2.35675"
CWRU_CH = ["--left", "X130_DE_time", "--right", "X130_FE_time", "--fs", "12000", "--rpm", "1796",
           "--scale", "9.80665"]
CWRU_ARGS = [*CWRU_CH, "--bearing-left", "6205", "--bearing-right", "6203"]
# Absolute thresholds for that rig: VF grows with the square of the frequency scale, so the
# paper's range is carried over by the ratio of the VF of a flat spectrum over the band where
# each machine's signal lies: the CWRU accelerometers fill 0-6 kHz (VF = 6000^2/12 = 3e6 Hz^2),
# the metro's healthy side 0-200 and 300-800 Hz (VF_METRO = 5.72e4 Hz^2): factor 52.4.
CWRU_SCALE = 6000.0 ** 2 / 12 / VF_METRO
CWRU_RANGE = f"{VF_RANGE_PAPER[0] * CWRU_SCALE:.4g},{VF_RANGE_PAPER[1] * CWRU_SCALE:.4g}"
needs_cwru = pytest.mark.skipif(not CWRU.is_file(), reason=f"reference recording {CWRU} is absent "
                                "(set AXLEBOX_REFERENCE to the folder holding cwru/)")


@needs_cwru
@pytest.mark.parametrize("setting", [["--vf-range", CWRU_RANGE], ["--relative"]],
                         ids=["absolute-rig-range", "relative"])
def test_cwru_drive_end_is_real_and_fan_end_pseudo(setting, tmp_path, capsys):
    """Each end with its own bearing: the drive end's BPFO (its 6205's order, 3.5848 x 1796/60 =
    107.3 Hz) is its own; on the fan end the same line is the other bearing's, carried."""
    out = tmp_path / "cwru.json"
    rc = main(["diagnose", str(CWRU), *CWRU_ARGS, *setting, "--json", str(out),
               "--figures", str(tmp_path / "fig")])
    assert rc == 0, capsys.readouterr().err
    d = json.loads(out.read_text())
    assert d["verdicts"]["left"]["verdict"] == "real fault", d["verdicts"]
    assert d["verdicts"]["right"]["verdict"] == "pseudo-fault", d["verdicts"]
    v = d["verdict"]
    assert v["rule"] == "one side owns the lines" and v["real"] == "left"
    bpfo = [ln for ln in v["evidence"]["lines"] if ln["key"] == "BPFO (left bearing)"]
    assert bpfo and bpfo[0]["how"] == "bearing order" and bpfo[0]["seen"] == {"left": True, "right": True}
    # CWRU's outer-race records show the line within 1 % of the published order
    assert d["left"]["lines"]["BPFO"]["f_found"] == pytest.approx(3.5848 * 1796 / 60, rel=0.01)
    assert d["right"]["carried"]["BPFO"]["detected"]
    assert d["right"]["carried"]["BPFO"]["f_found"] == pytest.approx(3.5848 * 1796 / 60, rel=0.01)
    assert not d["right"]["lines"]["BPFO"]["detected"]            # the 6203's BPFO, 91.4 Hz
    assert d["input"]["bearings"]["left"]["name"] == "6205"
    assert d["input"]["bearings"]["right"]["orders"]["BPFO"] == 3.0530
    # the faulty drive end leads the fan end (its impulses start there)
    assert d["lag"]["leading"] == "a"
    assert d["input"]["fs_hz"] == 12000 and d["input"]["n_samples"] == 121991
    assert (tmp_path / "fig" / f"{CWRU.stem}_diagnose.png").stat().st_size > 10_000
    printed = capsys.readouterr().out
    assert "real fault" in printed
    # a machine's record (speed given as --rpm): its shaft's harmonics are the shaft's
    assert d["input"]["rotor"] == d["rotor"] == v["evidence"]["rotor"] == "shaft"
    assert any(o["envelope"] or o["spectrum"] for o in v["evidence"]["shaft_orders"].values())
    assert "shaft: " in v["sentences"]["left"] + v["sentences"]["right"]
    assert "wheel" not in " ".join(v["sentences"].values()) + printed


@needs_cwru
@pytest.mark.parametrize("swap", [False, True], ids=["DE-left", "DE-right"])
def test_cwru_one_faulty_end_is_not_faults_on_both_sides(swap, tmp_path):
    """Whichever channel is given first, with its own bearing: the drive end real, the fan end
    a pseudo-fault."""
    args = ["--left", "X130_FE_time", "--right", "X130_DE_time", *CWRU_CH[4:],
            "--bearing-left", "6203", "--bearing-right", "6205"] if swap else CWRU_ARGS
    out = tmp_path / "c.json"
    assert main(["diagnose", str(CWRU), *args, "--relative", "--json", str(out)]) == 0
    d = json.loads(out.read_text())
    de, fe = ("right", "left") if swap else ("left", "right")
    assert (d["verdicts"][de]["verdict"], d["verdicts"][fe]["verdict"]) == ("real fault", "pseudo-fault")
    assert d["verdict"]["real"] == de


@needs_cwru
def test_cwru_read_with_one_bearing_for_both_ends(tmp_path):
    """Read as if both ends had the drive end's 6205 (one ``--orders`` for both: the case the
    per-side bearings are for): the fan end's BPFO is then a line of its own bearing type, and
    the copy-or-source test finds it the drive end's train (coherent), so the fan end is still
    not a second fault."""
    out = tmp_path / "c.json"
    assert main(["diagnose", str(CWRU), *CWRU_CH, "--orders", CWRU_ORDERS, "--bore", "0.025",
                 "--relative", "--json", str(out)]) == 0
    d = json.loads(out.read_text())
    assert d["verdicts"]["right"]["verdict"] in ("pseudo-fault", "healthy"), d["verdicts"]
    ln = [x for x in d["verdict"]["evidence"]["lines"] if x["key"] == "BPFO"][0]
    assert ln["timing"]["decision"] == "coherent" and ln["how"] == "coherent"


@needs_cwru
def test_cwru_with_the_paper_metro_range_is_undecided(tmp_path, capsys):
    """The paper's Hz^2 range belongs to the metro car: on the 12 kHz rig the VF difference
    (8.4e5 Hz^2) is above it, and the paper's criterion alone says so instead of guessing."""
    out = tmp_path / "c.json"
    assert main(["diagnose", str(CWRU), *CWRU_CH, "--orders", CWRU_ORDERS, "--bore", "0.025",
                 "--json", str(out)]) == 0
    d = json.loads(out.read_text())
    assert d["vf_diff_hz2"] > VF_RANGE_PAPER[1]
    from axlebox.pipelines.diagnose import analyse_file
    _, _, pair = analyse_file(CWRU, left="X130_DE_time", right="X130_FE_time", fs=12000, rpm=1796,
                              scale=9.80665, orders_text=CWRU_ORDERS, bore=0.025)
    v = pair.redecide(Criterion(source="paper"))
    assert v.words["left"] == "undecided" and v.rule == "VF above the range"


# ------------------------------------------------------------------------------ the readers

FS = 10_000.0
SHAFT = 20.0


def two_channels(n=int(1.0 * FS)):
    """Impulses at the DTRB's BPFO ringing 2.5 kHz on the left, a weaker copy on the right."""
    rng = np.random.default_rng(11)
    t = np.arange(n) / FS
    bpfo = orders(BearingParams()).BPFO * SHAFT
    phase = (t * bpfo) % 1.0
    ring = np.exp(-phase / bpfo * 600.0) * np.sin(2 * np.pi * 2500.0 * phase / bpfo)
    return ring + 0.3 * rng.standard_normal(n), 0.3 * np.roll(ring, 10) + 0.3 * rng.standard_normal(n)


@pytest.fixture(scope="module")
def reference_result():
    left, right = two_channels()
    res = analyse_pair(left, right, FS, SHAFT, orders(BearingParams()), diagnose.DTRB_BORE)
    return left, right, json.loads(json.dumps(jsonable(res.to_dict())))


def write_mat73(path, variables: dict):
    """A MATLAB v7.3 file as MATLAB writes it: a 128-byte text header ("MATLAB 7.3 MAT-file",
    version 0x0200, endian "IM") in a 512-byte HDF5 user block, then HDF5 with each variable
    stored transposed (MATLAB is column-major: an n x 1 column reads as (1, n) in HDF5) and a
    MATLAB_class attribute."""
    with h5py.File(path, "w", userblock_size=512) as f:
        for name, x in variables.items():
            ds = f.create_dataset(name, data=np.asarray(x, float).reshape(-1, 1).T)
            ds.attrs["MATLAB_class"] = np.bytes_("double")
    text = b"MATLAB 7.3 MAT-file, Platform: GLNXA64, Created on: Sat Nov 21 12:00:00 2026 HDF5 schema 1.00 ."
    header = text.ljust(116, b" ") + b"\x00" * 8 + b"\x00\x02" + b"IM"
    with open(path, "r+b") as fh:
        fh.write(header)


def write_inputs(tmp_path, left, right):
    """The same two channels in every format the command reads; -> {name: (path, extra args)}."""
    files = {}
    p = tmp_path / "v5.mat"
    scipy.io.savemat(p, {"DE": left[:, None], "FE": right[:, None], "fs": FS})
    files["mat v5"] = (p, ["--left", "DE", "--right", "FE"])          # fs from the variable
    p = tmp_path / "v73.mat"
    write_mat73(p, {"DE": left, "FE": right})
    files["mat v7.3"] = (p, ["--left", "DE", "--right", "FE", "--fs", str(FS)])
    p = tmp_path / "header.csv"
    np.savetxt(p, np.c_[left, right], delimiter=",", fmt="%.17g", header="DE,FE", comments="")
    files["csv with header"] = (p, ["--left", "DE", "--right", "FE", "--fs", str(FS)])
    p = tmp_path / "plain.txt"
    np.savetxt(p, np.c_[right, left], fmt="%.17g")                   # columns swapped, no header
    files["csv columns"] = (p, ["--left", "1", "--right", "0", "--fs", str(FS)])
    p = tmp_path / "generic.h5"
    with h5py.File(p, "w") as f:
        f.create_dataset("run/left_box", data=left).attrs["fs_hz"] = FS
        f.create_dataset("run/right_box", data=right)
    files["hdf5"] = (p, ["--left", "run/left_box", "--right", "run/right_box"])
    p = tmp_path / "result.h5"
    acc_l, acc_r = np.zeros((left.size, 3)), np.zeros((left.size, 3))
    acc_l[:, 2], acc_r[:, 2] = left, right
    speed = SHAFT * 3.6 * 2 * np.pi * 0.42                           # km/h giving SHAFT on 0.42 m
    resultfile.write(p, config_toml=f"[run]\nspeed_kmh = {speed!r}\n[wheelset]\nr0 = 0.42\n", seed=0,
                     time=np.arange(left.size) / FS, fs_hz=FS,
                     signals={"ws2_L": {"acceleration": acc_l}, "ws2_R": {"acceleration": acc_r}})
    files["axlebox-result"] = (p, [])                                # defaults: ws2_L/ws2_R, fs, speed
    return files


FORMATS = ["mat v5", "mat v7.3", "csv with header", "csv columns", "hdf5", "axlebox-result"]
KEYS = ("rms", "peak", "kurtosis", "crest", "FC", "VF", "MSF", "SV", "spm_db")


@pytest.mark.parametrize("fmt", FORMATS)
def test_every_format_gives_the_array_path_indicators(fmt, reference_result, tmp_path, capsys):
    """Each reader hands the command the very samples: every indicator equals the array path's
    (CSV is written with 17 significant digits, an exact round trip of a double)."""
    left, right, ref = reference_result
    path, extra = write_inputs(tmp_path, left, right)[fmt]
    shaft = [] if fmt == "axlebox-result" else ["--shaft-hz", str(SHAFT)]
    out = tmp_path / "d.json"
    assert main(["diagnose", str(path), *extra, *shaft, "--json", str(out)]) == 0, capsys.readouterr().err
    d = json.loads(out.read_text())
    assert d["input"]["fs_hz"] == FS and d["input"]["n_samples"] == left.size
    assert d["input"]["shaft_hz"] == pytest.approx(SHAFT, rel=1e-12)
    for s in ("left", "right"):
        for k in KEYS:
            assert d[s][k] == pytest.approx(ref[s][k], rel=1e-9, abs=1e-12), (s, k)
        assert d[s]["detected"] == ref[s]["detected"]
    assert d["lag"]["delay_b_samples"] == pytest.approx(ref["lag"]["delay_b_samples"], abs=1e-6)
    assert {s: v["verdict"] for s, v in d["verdicts"].items()} == \
        {s: v["verdict"] for s, v in ref["verdicts"].items()}


def test_vf_band_option_takes_fc_and_vf_over_the_band(tmp_path, reference_result, capsys):
    """``--vf-band 0,1000``: each side's FC and VF are :func:`fc_vf`'s over 0-1000 Hz of its
    samples, the JSON's criterion and sides say so, and the printed summary names the band."""
    from axlebox.bearing.diagnostics.spectral import fc_vf
    left, right, _ = reference_result
    path, extra = write_inputs(tmp_path, left, right)["csv with header"]
    out = tmp_path / "d.json"
    assert main(["diagnose", str(path), *extra, "--shaft-hz", str(SHAFT), "--vf-band", "0,1000",
                 "--json", str(out)]) == 0, capsys.readouterr().err
    assert "over 0-1000 Hz" in capsys.readouterr().out
    d = json.loads(out.read_text())
    assert d["criterion"]["vf_band"] == [0.0, 1000.0]
    for s, x in (("left", left), ("right", right)):
        FC, VF, _ = fc_vf(x, FS, None, (0.0, 1000.0))
        assert d[s]["vf_band"] == [0.0, 1000.0]
        assert d[s]["FC"] == pytest.approx(FC, rel=1e-12) and d[s]["VF"] == pytest.approx(VF, rel=1e-12)


def test_thresholds_are_options_and_printed_in_the_json(tmp_path, reference_result, capsys):
    """Every threshold that decides a verdict is in the JSON's criterion (the defaults where no
    option moves them); ``--second-db``, ``--clearer-db``, ``--c-independent``, ``--gate-ratio``
    and ``--shaft-p-fa`` set theirs."""
    left, right, ref = reference_result
    for name, value in (("clearer_db", 3.0), ("c_independent", 0.2), ("rho_min_db", 15.0),
                        ("z_min", 5.0), ("ringing_bands", 3), ("gate_ratio", 5.0),
                        ("shaft_p_fa", 1e-3), ("second_db", 15.0), ("source_ratio", 2.0)):
        assert ref["criterion"][name] == value, name
    path, extra = write_inputs(tmp_path, left, right)["csv with header"]
    out = tmp_path / "d.json"
    assert main(["diagnose", str(path), *extra, "--shaft-hz", str(SHAFT), "--second-db", "12",
                 "--clearer-db", "4.5", "--c-independent", "0.1", "--gate-ratio", "inf",
                 "--shaft-p-fa", "1e-4", "--json", str(out)]) == 0, capsys.readouterr().err
    crit = json.loads(out.read_text())["criterion"]
    assert (crit["second_db"], crit["clearer_db"], crit["c_independent"], crit["shaft_p_fa"]) == \
        (12.0, 4.5, 0.1, 1e-4)
    assert crit["gate_ratio"] is None                       # inf: never blank (JSON has no inf)
    with pytest.raises(SystemExit) as e:                    # argparse's refusal: one line too
        main(["diagnose", str(path), *extra, "--shaft-hz", str(SHAFT), "--clearer-db", "loud"])
    err = capsys.readouterr().err
    assert e.value.code == 2 and len(err.strip().splitlines()) == 1
    assert "--clearer-db" in err and "'loud'" in err


def flat_pair(n, f_w):
    """A wheel flat's strikes on both axle boxes (tests/test_diagnostics_wheel.py), in
    wheel-rail noise: whole orders of the wheel's rate, no bearing line."""
    from axlebox.bearing.diagnostics.synthetic import resonance, wheel_rail_noise
    rng = np.random.default_rng(3)
    x = np.zeros(n)
    x[np.round(np.arange(0.01, n / FS, 1.0 / f_w) * FS).astype(int)] = 1.0
    hit = sum(resonance(x, FS, f, 0.02) for f in (300.0, 650.0, 2500.0, 3500.0))
    hit /= hit.std()
    return 6.0 * hit + 0.5 * wheel_rail_noise(n, FS, rng), 10.0 * hit + 0.5 * wheel_rail_noise(n, FS, rng)


def test_a_vehicles_lines_are_the_wheels_and_a_machines_the_shafts(tmp_path, capsys):
    """The same two channels: from a car's result file (its speed stored) or read with
    ``--speed-kmh``, the lines at whole orders of the shaft are the wheel's ("wheel lines
    only", "wheel: 1x, 2x ..."); read with ``--shaft-hz`` (a machine), the shaft's."""
    f_w = shaft_hz(40.0)
    left, right = flat_pair(int(4.5 * FS), f_w)
    p = tmp_path / "car.h5"
    acc_l, acc_r = np.zeros((left.size, 3)), np.zeros((left.size, 3))
    acc_l[:, 2], acc_r[:, 2] = left, right
    resultfile.write(p, config_toml="[run]\nspeed_kmh = 40.0\n[wheelset]\nr0 = 0.42\n", seed=0,
                     time=np.arange(left.size) / FS, fs_hz=FS,
                     signals={"ws2_L": {"acceleration": acc_l}, "ws2_R": {"acceleration": acc_r}})
    csv = tmp_path / "machine.csv"
    np.savetxt(csv, np.c_[left, right], delimiter=",", fmt="%.17g", header="DE,FE", comments="")
    said = {}
    for name, args in (("result", [str(p)]),
                       ("speed", [str(csv), "--fs", str(FS), "--speed-kmh", "40"]),
                       ("shaft", [str(csv), "--fs", str(FS), "--shaft-hz", repr(f_w)])):
        out = tmp_path / f"{name}.json"
        assert main(["diagnose", *args, "--json", str(out)]) == 0, capsys.readouterr().err
        d = json.loads(out.read_text())
        said[name] = (d["input"]["rotor"], d["verdict"]["rule"], d["verdict"]["sentences"]["left"])
        assert d["verdict"]["words"] == {"left": "healthy", "right": "healthy"}, said[name]
    for name in ("result", "speed"):
        rotor, rule, text = said[name]
        assert (rotor, rule) == ("wheel", "wheel lines only") and "wheel: 1x, 2x" in text, said[name]
    rotor, rule, text = said["shaft"]
    assert (rotor, rule) == ("shaft", "shaft lines only") and "shaft: 1x, 2x" in text, text
    assert "wheel" not in text


def test_file_kind_reads_the_content_not_the_name(tmp_path, reference_result):
    left, right, _ = reference_result
    files = write_inputs(tmp_path, left, right)
    kinds = {k: readers.file_kind(p) for k, (p, _) in files.items()}
    assert kinds == {"mat v5": "mat5", "mat v7.3": "mat73", "csv with header": "csv",
                     "csv columns": "csv", "hdf5": "hdf5", "axlebox-result": "axlebox-result"}
    renamed = tmp_path / "looks_like.csv"
    renamed.write_bytes(files["mat v7.3"][0].read_bytes())
    assert readers.file_kind(renamed) == "mat73"


def test_vehicle_results_leave_out_the_track_fade_in(tmp_path):
    """Vehicle runs fade the irregularity in over 0.5 s (mbs/solver/system.py): left out of the record,
    also when the config as run leaves [track] at its defaults (configs/validation_48kmh.toml)."""
    n = int(2 * FS)
    acc = np.random.default_rng(0).standard_normal((n, 3))      # any signal (a constant one is refused)
    p = tmp_path / "veh.h5"
    resultfile.write(p, config_toml="[run]\nspeed_kmh = 48.0\n", seed=0,
                     time=np.arange(n) / FS, fs_hz=FS,
                     signals={"ws2_L": {"acceleration": acc}, "ws2_R": {"acceleration": acc}})
    rec = diagnose.read(p)
    assert rec.left.size == n - int(0.5 * FS) and rec.shaft_hz == pytest.approx(shaft_hz(48.0))


def test_a_quantized_real_style_record_reads(tmp_path, capsys):
    """Issue 57: a record of two healthy bearings on one shaft, 20 kHz, stored to three decimals
    of a unit whose RMS is 0.06 (test_diagnostics_channel.real_style, seed 83): before the SPM's
    extrema were found on runs of equal samples this exited 1 with PyEMD's "`x` must be strictly
    increasing sequence"; now it reads, both sides healthy (no bearing line in it).  The orders
    are the Rexnord ZA-2115's (16 rollers a row, 0.331 in rollers on a 2.815 in pitch circle,
    15.17 deg; Qiu et al., J. Sound Vib. 289 (2006) 1066-1090) at 2000 rpm."""
    from test_diagnostics_channel import real_style
    p = tmp_path / "ims.csv"
    np.savetxt(p, np.c_[tuple(real_style(83))], fmt="%.3f", delimiter=",", header="b1,b2", comments="")
    out = tmp_path / "ims.json"
    rc = main(["diagnose", str(p), "--fs", "20000", "--rpm", "2000", "--orders",
               "BPFO=7.092,BPFI=8.908,FTF=0.4433,BSF=4.198", "--bore", "0.0556", "--json", str(out)])
    assert rc == 0, capsys.readouterr().err
    assert json.loads(out.read_text())["verdict"]["words"] == {"left": "healthy", "right": "healthy"}


def _csv_text(path, a, b, header="a,b"):
    """Two columns as text; NaN as an empty cell (a sample not written)."""
    cell = [["" if v != v else repr(float(v)) for v in x] for x in (a, b)]
    path.write_text(header + "\n" + "\n".join(f"{u},{v}" for u, v in zip(*cell)) + "\n")
    return path


def test_gaps_and_held_stretches_are_read_around(tmp_path):
    """NaN samples (empty cells; a channel that ends first) and a stretch held at one value for
    0.1 s or more (a dropped sensor) are left out by reading the longest stretch where both
    channels are finite and moving, with a note; the samples read are the file's, unchanged."""
    rng = np.random.default_rng(0)
    a, b = rng.standard_normal(12000), rng.standard_normal(12000)
    a[[100, 5000]] = np.nan                        # two lost samples on the left
    b[9000:] = np.nan                              # the right channel ends first
    b[7000:8200] = b[6999]                         # and holds its value 0.12 s at 10 kHz
    rec = diagnose.read(_csv_text(tmp_path / "g.csv", a, b), fs=FS)
    assert (rec.start, rec.left.size) == (101, 4899)            # samples 101-5000, the longest
    assert np.array_equal(rec.left, a[101:5000]) and np.array_equal(rec.right, b[101:5000])
    assert "2 NaN/inf samples in 2 gap(s)" not in rec.notes[0]    # the trailing 3000 are gaps too
    assert "3002 NaN/inf samples in 3 gap(s)" in rec.notes[0] and "1 stretch(es)" in rec.notes[0]
    c = rng.standard_normal(9000)
    c[3000:3998] = c[2999]                          # 999 samples of one value: under HOLD_S, read
    rec = diagnose.read(_csv_text(tmp_path / "h.csv", c, c[::-1]), fs=FS)
    assert rec.left.size == 9000 and not rec.notes


@pytest.mark.parametrize("case", ["all zeros", "held throughout", "lengths (hdf5)", "no stretch"])
def test_a_dropped_sensor_is_refused_in_one_line(case, tmp_path, capsys):
    """A channel constant throughout (all zeros; one value held), two HDF5 datasets of different
    lengths (sampled together or not: unknown), or gaps leaving nothing: exit 2, one line."""
    rng = np.random.default_rng(1)
    a, b = rng.standard_normal(12000), rng.standard_normal(12000)
    if case == "lengths (hdf5)":
        p = tmp_path / "r.h5"
        with h5py.File(p, "w") as f:
            f["a"], f["b"] = a, b[:-7]
        args, words = [str(p), "--left", "a", "--right", "b", "--fs", str(FS)], ["12000 samples", "11993"]
    else:
        if case == "all zeros":
            b[:] = 0.0
        elif case == "held throughout":
            a[:] = 0.25
        else:
            a[::500] = np.nan
            b[250::500] = np.nan
        p = _csv_text(tmp_path / "r.csv", a, b)
        args = [str(p), "--fs", str(FS)]
        words = {"all zeros": ["--right 'b'", "constant (0 in all", "a dropped sensor"],
                 "held throughout": ["--left 'a'", "constant (0.25", "a dropped sensor"],
                 "no stretch": ["too short", "48 NaN/inf samples in 48 gap(s)"]}[case]
    rc = main(["diagnose", *args, "--shaft-hz", str(SHAFT)])
    err = capsys.readouterr().err.strip()
    assert rc == 2 and len(err.splitlines()) == 1, err
    assert all(w in err for w in words), err


def test_a_long_csv_is_read_on_its_middle_in_memory_flat_in_its_length(tmp_path):
    """A record longer than ``max_samples`` is read on its middle, parsed row by row: the peak
    memory of reading 2e5 rows is within 1.5 times that of 2e4 rows (measured 1.14: 1.8 and 2.1
    MB), where reading all of each grows with it (8.4 MB against 0.8)."""
    import tracemalloc
    rng = np.random.default_rng(2)
    peak = {}
    for n in (20000, 200000):
        x = rng.standard_normal((n, 2))
        p = _csv_text(tmp_path / f"r{n}.csv", x[:, 0], x[:, 1])
        for cap in (4096, None):
            tracemalloc.start()
            rec = diagnose.read(p, fs=FS, max_samples=cap)
            peak[n, cap] = tracemalloc.get_traced_memory()[1]
            tracemalloc.stop()
        a = (n - 4096) // 2
        assert rec.left.size == n
        rec = diagnose.read(p, fs=FS, max_samples=4096)
        assert rec.start == a and np.array_equal(rec.left, x[a:a + 4096, 0])
        assert f"the middle 0.4096 s of {n / FS:g} s" in rec.notes[0]
    assert peak[200000, 4096] < 1.5 * peak[20000, 4096], peak
    assert peak[200000, None] > 5 * peak[20000, None], peak


def test_parse_orders_and_shaft_speed():
    assert diagnose.parse_orders(CWRU_ORDERS) == FaultOrders(FTF=0.39828, BPFO=3.5848,
                                                             BPFI=5.4152, BSF=2.35675)
    rec = diagnose.Record(np.zeros(3), np.zeros(3), FS, ("a", "b"), "csv")
    assert diagnose.shaft_speed(rec, rpm=1796) == pytest.approx(1796 / 60)
    # 48 km/h on 0.42 m wheels: 5.0525 Hz (the paper: the wheelset turns at 5.1 Hz)
    assert diagnose.shaft_speed(rec, speed_kmh=48) == pytest.approx(48 / 3.6 / (2 * np.pi * 0.42))


# ------------------------------------------------------------------------------- bad input


def bad_inputs(tmp_path, left, right):
    files = write_inputs(tmp_path, left, right)
    nan_csv = tmp_path / "nan.csv"
    r = right.copy()
    r[::1000] = np.nan          # a lost sample every 0.1 s: no stretch between long enough to read
    np.savetxt(nan_csv, np.c_[left, r], delimiter=",", fmt="%.17g", header="DE,FE", comments="")
    short = tmp_path / "short.csv"
    np.savetxt(short, np.c_[left[:500], right[:500]], delimiter=",", fmt="%.17g")
    junk = tmp_path / "junk.bin"
    junk.write_bytes(bytes(range(256)) * 8)
    cut = tmp_path / "cut.h5"                       # an HDF5 file cut short (a broken copy)
    cut.write_bytes(files["hdf5"][0].read_bytes()[:1500])
    sh = ["--shaft-hz", str(SHAFT)]
    return {
        "missing variable": ([str(files["mat v5"][0]), "--left", "DE", "--right", "RE", *sh],
                             ["--right 'RE'", "DE, FE, fs"]),
        "missing sensor": ([str(files["axlebox-result"][0]), "--left", "ws1_L"], ["--left 'ws1_L'", "ws2_L"]),
        "missing fs": ([str(files["csv with header"][0]), *sh], ["--fs is missing", "CSV"]),
        "missing fs (mat v7.3)": ([str(files["mat v7.3"][0]), "--left", "DE", "--right", "FE", *sh],
                                  ["--fs is missing"]),
        "NaNs": ([str(nan_csv), "--fs", str(FS), *sh], ["too short", "10 NaN/inf samples in 10 gap"]),
        # 500 samples = 0.05 s; the FTF line (0.436 x 20 Hz = 8.72 Hz) needs two periods, 0.229 s
        "too short for the lines": ([str(short), "--fs", str(FS), *sh], ["too short", "FTF", "two periods"]),
        # a Welch segment longer than the record
        "too short for the Welch segment": ([str(files["csv with header"][0]), "--fs", str(FS), *sh,
                                             "--nperseg", "20000"], ["nperseg", "too short"]),
        "unknown file type": ([str(junk), *sh], ["unknown type"]),
        "unreadable file": ([str(cut), "--left", "a", "--right", "b", *sh], ["cut.h5", "not readable"]),
        "no file": ([str(tmp_path / "none.mat"), *sh], ["does not exist"]),
        "bad orders": ([str(files["csv with header"][0]), "--fs", str(FS), *sh, "--orders", "BPFO=3.5"],
                       ["--orders lacks", "BPFI"]),
        "orders without bore": ([str(files["csv with header"][0]), "--fs", str(FS), *sh, "--orders",
                                 CWRU_ORDERS], ["--bore is missing"]),
        "unknown bearing": ([str(files["csv with header"][0]), "--fs", str(FS), *sh,
                             "--bearing-right", "6206"],
                            ["--bearing-right '6206'", "6203, 6205, crb, dcrb, dtrb"]),
        "two bearings for a side": ([str(files["csv with header"][0]), "--fs", str(FS), *sh,
                                     "--bearing-left", "6205", "--orders-left", CWRU_ORDERS],
                                    ["--orders-left and --bearing-left"]),
        "side orders without bore": ([str(files["csv with header"][0]), "--fs", str(FS), *sh,
                                      "--orders-left", CWRU_ORDERS], ["--bore is missing", "--bore-left"]),
        "bad side bore": ([str(files["csv with header"][0]), "--fs", str(FS), *sh, "--bearing",
                           "6205", "--bore-right", "-1"], ["--bore-right", "-1"]),
        "no shaft speed": ([str(files["csv with header"][0]), "--fs", str(FS)], ["shaft speed is missing"]),
        "vf band above Nyquist": ([str(files["csv with header"][0]), "--fs", str(FS), *sh,
                                   "--vf-band", "0,6000"], ["--vf-band", "Nyquist", "5000 Hz"]),
        "vf band upside down": ([str(files["csv with header"][0]), "--fs", str(FS), *sh,
                                 "--vf-band", "900,100"], ["--vf-band", "0 <= LO < HI"]),
        "bad clearer db": ([str(files["csv with header"][0]), "--fs", str(FS), *sh,
                            "--clearer-db", "-1"], ["--clearer-db", "-1", "expected a level >= 0 dB"]),
        "bad second db": ([str(files["csv with header"][0]), "--fs", str(FS), *sh,
                           "--second-db", "nan"], ["--second-db", "nan", ">= 0 dB"]),
        "bad c independent": ([str(files["csv with header"][0]), "--fs", str(FS), *sh,
                               "--c-independent", "1.5"], ["--c-independent", "1.5", "[0, 1)"]),
        "bad gate ratio": ([str(files["csv with header"][0]), "--fs", str(FS), *sh,
                            "--gate-ratio", "0.5"], ["--gate-ratio", "0.5", "a ratio > 1"]),
        "bad shaft p_fa": ([str(files["csv with header"][0]), "--fs", str(FS), *sh,
                            "--shaft-p-fa", "0"], ["--shaft-p-fa", "0", "(0, 1)"]),
    }


CASES = ["missing variable", "missing sensor", "missing fs", "missing fs (mat v7.3)", "NaNs",
         "too short for the lines", "too short for the Welch segment", "unknown file type",
         "unreadable file", "no file",
         "bad orders", "orders without bore", "unknown bearing", "two bearings for a side",
         "side orders without bore", "bad side bore", "no shaft speed", "vf band above Nyquist",
         "vf band upside down", "bad clearer db", "bad second db", "bad c independent",
         "bad gate ratio", "bad shaft p_fa"]


@pytest.mark.parametrize("case", CASES)
def test_bad_input_exits_2_with_one_line_naming_it(case, tmp_path, reference_result, capsys):
    left, right, _ = reference_result
    args, words = bad_inputs(tmp_path, left, right)[case]
    rc = main(["diagnose", *args])
    err = capsys.readouterr().err
    assert rc == 2, err
    lines = err.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("axlebox: error:"), err
    for w in words:
        assert w in lines[0], lines[0]
    assert "Traceback" not in err


def test_bad_input_through_the_installed_command(tmp_path, reference_result):
    """The real entry point, in a fresh process: status 2, one line, no traceback."""
    left, right, _ = reference_result
    args, words = bad_inputs(tmp_path, left, right)["NaNs"]
    r = subprocess.run([sys.executable, "-m", "axlebox", "diagnose", *args],
                       capture_output=True, text=True, timeout=300)
    assert r.returncode == 2
    assert len(r.stderr.strip().splitlines()) == 1 and "10 NaN" in r.stderr
    assert "Traceback" not in r.stderr + r.stdout
