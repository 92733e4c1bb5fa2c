"""`axlebox diagnose` with the speed over the record (pipelines/speed.py, windows.py): a source and
its copy (bearing/diagnostics/synthetic.py) swept from 20 to 80 km/h, read with a speed channel, a
tacho and a speed profile; without the speed (read from the record); in windows of shaft turns (JSON Lines); a
constant-speed record read with a constant speed channel as with --rpm (identical verdicts); and
bad speed input, each one line and exit status 2."""

import json

import numpy as np
import pytest

from axlebox.bearing.diagnostics.synthetic import swept_coaxial_pair
from axlebox.bearing.frequencies import shaft_hz
from axlebox.pipelines import diagnose
from axlebox.pipelines.cli import main

from conftest import reference_dir

FS = 10_000.0
R = 0.42
DTRB_BPFO = 8.7246          # the DTRB's outer-ring order (bearing/models/params.py defaults)
T = 20.0


@pytest.fixture(scope="module")
def swept(tmp_path_factory):
    """The sweep as a CSV (healthy, defect, speed in km/h, tacho) and its speed profile (10 Hz)."""
    d = tmp_path_factory.mktemp("swept")
    defect, healthy, angle = swept_coaxial_pair(T, FS, DTRB_BPFO, shaft_hz(20.0, R), shaft_hz(80.0, R),
                                                np.random.default_rng(3))
    f = np.gradient(angle) * FS                              # turns/s
    kmh = f * 2 * np.pi * R * 3.6
    tacho = (np.mod(angle, 1.0) < 0.05).astype(float)        # a pulse each turn
    path = d / "swept.csv"
    np.savetxt(path, np.column_stack([healthy, defect, kmh, tacho]), delimiter=",",
               header="healthy,defect,speed,tacho", comments="")
    t = np.arange(0, T + 0.1, 0.1)
    prof = d / "profile.csv"
    np.savetxt(prof, np.column_stack([t, 20.0 + 60.0 * t / T]), delimiter=",", header="t,kmh",
               comments="")
    return path, prof, d


BASE = ["--left", "healthy", "--right", "defect", "--fs", str(FS), "--relative"]


def _words(path, extra, tmp):
    out = tmp / "d.json"
    assert main(["diagnose", str(path), *BASE, *extra, "--json", str(out)]) == 0
    d = json.loads(out.read_text())
    return d["verdict"]["words"], d["input"]


@pytest.mark.parametrize("how", [["--speed-channel", "speed", "--speed-unit", "km/h"],
                                 ["--tacho", "tacho"], ["PROFILE", "--speed-unit", "km/h"]])
def test_a_swept_source_and_copy_read_with_the_speed(swept, how):
    """20 -> 80 km/h in 20 s: with its speed (a channel, a tacho or a profile) the defect side is
    the real fault and the healthy side its pseudo-fault; read at one mean speed the fault is
    smeared over a band and missed, and the healthy side never called faulty."""
    path, prof, d = swept
    how = [str(prof) if h == "PROFILE" else h for h in how]
    if str(prof) in how:
        how = ["--speed-csv", *how]
    words, info = _words(path, how, d)
    assert info["speed"]["order_tracked"]
    # (a tacho: from its first pulse)
    assert info["speed"]["min_hz"] == pytest.approx(shaft_hz(20.0, R), rel=0.1)
    assert info["speed"]["max_hz"] == pytest.approx(shaft_hz(80.0, R), rel=0.03)
    assert words == {"left": "pseudo-fault", "right": "real fault"}


def test_without_the_speed_it_is_read_from_the_record(swept):
    """Given only the mean speed (50 km/h), the speed over the record is read from the record
    (bearing/diagnostics/ias.py, the BPFO ridge) and the record on that clock: the defect side
    the real fault, the healthy side its pseudo-fault (before: both healthy, the fault smeared)."""
    path, _, d = swept
    words, info = _words(path, ["--speed-kmh", "50"], d)
    assert info["speed"]["from"] == "estimated from the record (BPFO ridge)"
    assert info["speed"]["order_tracked"] and info["speed"]["estimate"]["status"] == "changing"
    assert info["speed"]["min_hz"] == pytest.approx(shaft_hz(20.0, R), rel=0.03)
    assert info["speed"]["max_hz"] == pytest.approx(shaft_hz(80.0, R), rel=0.03)
    assert words == {"left": "pseudo-fault", "right": "real fault"}


def test_windows_of_shaft_turns_as_json_lines(swept, capsys):
    """Windows of 20 turns (half overlapping): each a JSON object with its span, speed, lines and
    verdict; the summary last, with the share of windows that agree."""
    path, _, d = swept
    out = d / "w.jsonl"
    assert main(["diagnose", str(path), *BASE, "--speed-channel", "speed", "--window-turns", "20",
                 "--windows-out", str(out), "--figures", str(d / "figs")]) == 0
    assert (d / "figs" / "swept_windows.png").stat().st_size > 10_000
    rows = [json.loads(line) for line in out.read_text().splitlines()]
    summary = rows.pop()["summary"]
    assert len(rows) == summary["windows"] >= 5
    for r in rows:
        assert r["turns"] == pytest.approx(20.0, rel=0.01)
        assert r["t1_s"] > r["t0_s"] and r["speed_hz"][1] > r["speed_hz"][0]
        assert {"words", "rule", "lines", "rms_left", "spm_db_right", "lag_s"} <= set(r)
        assert r["words"]["left"] not in ("real fault", "faults on both sides")
    assert summary["words"] == {"left": "pseudo-fault", "right": "real fault"}
    assert summary["share"] >= 0.8
    assert "summary: left pseudo-fault, right real fault" in capsys.readouterr().out


def test_a_window_too_short_is_not_read_with_its_reason(swept):
    from axlebox.pipelines.windows import analyse_windows
    path, _, _ = swept
    w = analyse_windows(path, 3.0, 0.0, left="healthy", right="defect", fs=FS,
                        speed_channel="speed")
    assert w.rows and all("too short" in r["not_read"] for r in w.rows)
    assert w.summary["read"] == 0 and w.summary["words"] is None


def _bad(tmp, columns, header, extra, capsys):
    path = tmp / "bad.csv"
    np.savetxt(path, np.column_stack(columns), delimiter=",", header=header, comments="")
    rc = main(["diagnose", str(path), "--left", "a", "--right", "b", "--fs", str(FS), *extra])
    err = capsys.readouterr().err.strip()
    return rc, err


@pytest.mark.parametrize("case, expect", [
    ("gap", "--speed-channel 'speed'"), ("negative", "--speed-channel 'speed' sample"),
    ("missing pulse", "--tacho 'tacho': tacho pulse"), ("extra pulse", "--tacho 'tacho': tacho pulse"),
    ("profile short", "--speed-csv"), ("two sources", "--speed-channel and --tacho"),
    ("mode", "--order-tracking 'sometimes'"), ("unit", "--speed-unit 'mph'"),
    ("window", "--window-turns = 10000"), ("speed and rpm", "--rpm is not allowed"),
])
def test_bad_speed_input_is_one_line_and_exit_2(tmp_path, capsys, case, expect):
    n = int(4 * FS)
    rng = np.random.default_rng(0)
    a, b = rng.standard_normal(n), rng.standard_normal(n)
    speed = np.full(n, 40.0)
    angle = np.arange(n) / FS * shaft_hz(40.0, R)
    tacho = (np.mod(angle, 1.0) < 0.05).astype(float)
    extra = ["--speed-channel", "speed"]
    if case == "gap":
        speed[1000:1200] = np.nan
    elif case == "negative":
        speed[2000:] = -40.0
    elif case in ("missing pulse", "extra pulse"):
        turn = int(FS / shaft_hz(40.0, R))
        if case == "missing pulse":
            tacho[2 * turn + 50: 2 * turn + int(0.1 * turn)] = 0.0
            tacho[int(2.5 * turn):int(3.5 * turn)] = 0.0
        else:
            tacho[int(2.5 * turn):int(2.5 * turn) + 100] = 1.0
        extra = ["--tacho", "tacho"]
    elif case == "profile short":
        prof = tmp_path / "p.csv"
        prof.write_text("t,kmh\n0,40\n2,40\n")
        extra = ["--speed-csv", str(prof)]
    elif case == "two sources":
        extra += ["--tacho", "tacho"]
    elif case == "mode":
        extra += ["--order-tracking", "sometimes"]
    elif case == "unit":
        extra += ["--speed-unit", "mph"]
    elif case == "window":
        extra += ["--window-turns", "10000"]
    elif case == "speed and rpm":
        extra += ["--rpm", "600"]
    rc, err = _bad(tmp_path, [a, b, speed, tacho], "a,b,speed,tacho", extra, capsys)
    assert rc == 2, err
    assert "\n" not in err and "Traceback" not in err
    assert expect in err, err


CWRU = reference_dir() / "cwru" / "cwru_130_OR007_6_0_DE12k.mat"


@pytest.mark.skipif(not CWRU.is_file(), reason=f"reference recording {CWRU} is absent (a user's "
                    "clone without the team's reference data)")
def test_a_constant_speed_record_reads_the_same_with_its_speed(tmp_path):
    """CWRU record 130 at 1796 rev/min, read with --rpm and with a speed profile of 1796 rev/min
    (--speed-csv): the same verdict and evidence (a constant speed is not order-tracked); and
    with order tracking forced on, still the same words."""
    common = dict(left="X130_DE_time", right="X130_FE_time", fs=12000.0, bearing_left="6205",
                  bearing_right="6203")
    _, _, ref = diagnose.analyse_file(CWRU, rpm=1796.0, **common)
    prof = tmp_path / "rpm.csv"
    prof.write_text("t,rpm\n0,1796\n100,1796\n")
    _, info, same = diagnose.analyse_file(CWRU, speed_csv=str(prof), speed_unit="rpm", **common)
    assert not info["speed"]["order_tracked"]
    assert info["shaft_hz"] == pytest.approx(1796.0 / 60.0, rel=1e-9)
    assert same.verdict.row() == ref.verdict.row() or _same_rows(same.verdict.row(), ref.verdict.row())
    _, info, forced = diagnose.analyse_file(CWRU, speed_csv=str(prof), speed_unit="rpm",
                                            order_tracking="on", **common)
    assert info["speed"]["order_tracked"]
    assert forced.verdict.words == ref.verdict.words


def _same_rows(a, b):
    return a.keys() == b.keys() and all(
        (isinstance(a[k], float) and np.isnan(a[k]) and np.isnan(b[k])) or a[k] == b[k] for k in a)
