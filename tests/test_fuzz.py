"""Property-based fuzzing (hypothesis) of the entry points that read user input (issue 21, item 2):
the vehicle and rig configs, the diagnose readers (CSV, HDF5, MATLAB v5), diagnose's, sweep's
(with the ``[sweep]`` table) and dataset's options, damaged axlebox result files, and ``bodies
export`` on good and damaged reduced bodies.

Every generated case either runs or is refused with :class:`ParameterError` (the CLI: exit 2)
in one line; nothing else escapes (no traceback), and every case ends (hypothesis' deadline off,
a per-case time limit instead).  ``AXLEBOX_FULL=1``: 500 cases per entry point; CI: 30.
``benchmarks/fuzz.py`` runs the full size and prints the distinct messages seen.
"""
import json
import os
import re
import signal
import tempfile
from collections import Counter
from contextlib import contextmanager
from pathlib import Path
from unittest.mock import patch

import h5py
import numpy as np
import pytest
from hypothesis import HealthCheck, given, note, settings
from hypothesis import strategies as st

from axlebox._params import ParameterError

from conftest import full_size, write_pair_result

N = 500 if full_size() else 30
SETTINGS = settings(max_examples=N, deadline=None, database=None, derandomize=True,
                    suppress_health_check=list(HealthCheck))
SEEN: dict[str, Counter] = {}

# what a TOML file can hold, wrong or right
scalars = st.one_of(st.integers(-2**63, 2**63 - 1), st.floats(allow_nan=True, allow_infinity=True),
                    st.text(max_size=12), st.booleans())
values = st.one_of(scalars, st.lists(scalars, max_size=4),
                   st.dictionaries(st.text(max_size=6), scalars, max_size=3))


@contextmanager
def time_limit(s: float):
    """A hang fails the case (SIGALRM)."""
    def boom(*_):
        raise TimeoutError(f"no answer in {s} s")
    old = signal.signal(signal.SIGALRM, boom)
    signal.setitimer(signal.ITIMER_REAL, s)
    try:
        yield
    finally:
        signal.setitimer(signal.ITIMER_REAL, 0)
        signal.signal(signal.SIGALRM, old)


def kind_of(msg: str) -> str:
    """A message with its file paths and numbers taken out: what kind of refusal it is."""
    msg = re.sub(r"'[^']*/[^']*'", "FILE", msg)
    msg = re.sub(r"'[^']*'|\[[^\]]*\]|-?\d[\d.e+-]*|nan|inf", "_", msg)
    return msg[:90]


def refused_or_ran(entry: str, fn, *args, names=()):
    """Runs ``fn``; a ParameterError must be one line (naming one of ``names`` when given)."""
    with time_limit(30.0):
        try:
            fn(*args)
        except (ParameterError, FileNotFoundError) as err:
            msg = str(err)
            assert msg and "\n" not in msg, msg
            if names:
                assert any(n in msg for n in names), (names, msg)
            SEEN.setdefault(entry, Counter())[kind_of(msg)] += 1
            return
    SEEN.setdefault(entry, Counter())["(ran)"] += 1


def mutate(base: dict, data, sections: dict) -> tuple[dict, tuple[str, ...]]:
    """``base`` with one of: a field set to any value, a field removed, an unknown field or
    section, a section replaced by a scalar; returns it and the names a refusal must quote."""
    d = {k: dict(v) if isinstance(v, dict) else v for k, v in base.items()}
    op = data.draw(st.sampled_from(["value", "value", "value", "drop", "unknown", "nesting", "section"]))
    sec = data.draw(st.sampled_from(sorted(sections)))
    field = data.draw(st.sampled_from(sorted(sections[sec])))
    if op == "value":
        d.setdefault(sec, {})[field] = data.draw(values)
        return d, (field,)
    if op == "drop":
        d.get(sec, {}).pop(field, None)
        return d, ()
    if op == "unknown":
        d.setdefault(sec, {})["zz_" + data.draw(st.text("abc", min_size=1, max_size=4))] = 1.0
        return d, ("zz_",)
    if op == "nesting":
        d[sec] = data.draw(scalars)
        return d, (sec,)
    d["zz_section"] = {"x": 1}
    return d, ("zz_section",)


# ---------------------------------------------------------------------------- vehicle config


@SETTINGS
@given(st.data())
def test_vehicle_config(data):
    import dataclasses

    from axlebox.bearing.models.params import BearingParams
    from axlebox.mbs.vehicle.config import SECTIONS, validate
    base = {"defects": {"wheelset": 2, "side": "R", "W": 2e-3}, "joint": {"model": "dtrb"},
            "integrator": {"method": "imex", "dt": 5e-6}}
    validate({**base, "defects": [base["defects"]]})             # the base runs
    sections = {**{k: {f.name: 0 for f in dataclasses.fields(cls)} for k, cls in SECTIONS.items()},
                "bearing": {f.name: 0 for f in dataclasses.fields(BearingParams)},
                "defects": {"W": 0, "L": 0, "H": 0, "row": 0, "side": 0, "wheelset": 0,
                            "kind": 0, "roller": 0, "angle_deg": 0}}
    d, names = mutate(base, data, sections)
    if "defects" in d and isinstance(d["defects"], dict):        # the defect table's entries
        d["defects"] = [d["defects"]]
    refused_or_ran("vehicle config", validate, d, names=names)


def _every_section():
    from axlebox.mbs.vehicle.config import SECTIONS
    return sorted(SECTIONS) + ["bearing", "defects"]


@pytest.mark.parametrize("sec", _every_section())
def test_vehicle_config_unknown_key_in_every_section(sec):
    """An unknown key in any section (``[bearing] model = 3`` once ended in a TypeError) is one
    line naming ``section.key`` and the fields allowed."""
    from axlebox.mbs.vehicle.config import validate
    base = {"joint": {"model": "dtrb"}, "integrator": {"method": "imex", "dt": 5e-6},
            "defects": [{"wheelset": 2, "side": "R", "W": 2e-3}]}
    d = {k: ([dict(v[0])] if isinstance(v, list) else dict(v)) for k, v in base.items()}
    if sec == "defects":
        d["defects"][0]["model"] = 3
        where = "defects[0].model"
    else:
        d.setdefault(sec, {})["model_zz"] = 3
        where = f"{sec}.model_zz"
    with pytest.raises(ParameterError) as err:
        validate(d)
    msg = str(err.value)
    assert where in msg and "expected one of" in msg and "\n" not in msg, msg


@pytest.mark.parametrize("sec", ["rig", "bearing", "defects"])
def test_rig_config_unknown_key_in_every_section(sec):
    from axlebox.bearing.rig import config_from_dict
    d = {"rig": {"duration": 0.01}, "bearing": {}, "defects": [{"W": 1e-3}]}
    (d["defects"][0] if sec == "defects" else d[sec])["model_zz"] = 3
    with pytest.raises(ParameterError) as err:
        config_from_dict(d)
    msg = str(err.value)
    assert f"{sec}.model_zz" in msg and "expected one of" in msg and "\n" not in msg, msg


# -------------------------------------------------------------------------------- rig config


@SETTINGS
@given(st.data())
def test_rig_config(data):
    import dataclasses

    from axlebox.bearing.models.params import BearingParams
    from axlebox.bearing.rig import RigConfig, config_from_dict
    rig = {f.name: 0 for f in dataclasses.fields(RigConfig) if f.name not in ("defects", "bearing")}
    sections = {"rig": rig, "bearing": {f.name: 0 for f in dataclasses.fields(BearingParams)},
                "defects": {"W": 0, "L": 0, "H": 0, "row": 0, "angle": 0, "kind": 0, "roller": 0}}
    base = {"rig": {"duration": 0.01}, "defects": {"W": 1e-3}}
    config_from_dict({**base, "defects": [base["defects"]]})     # the base runs
    d, names = mutate(base, data, sections)
    if isinstance(d.get("defects"), dict):
        d["defects"] = [d["defects"]]
    refused_or_ran("rig config", config_from_dict, d, names=names)


# ----------------------------------------------------------------------------------- readers


def _read(path, left=None, right=None, fs=None):
    from axlebox.pipelines.readers import read
    read(path, left, right, fs)


csv_rows = st.lists(st.lists(st.one_of(st.floats(allow_nan=True, allow_infinity=True).map(repr),
                                       st.text(",; \t0123456789.eE-xa", max_size=6), st.just("")),
                             min_size=0, max_size=4), max_size=30)


@SETTINGS
@given(csv_rows, st.sampled_from([",", ";", "\t", " "]), st.one_of(st.none(), st.floats()))
def test_csv_reader(rows, sep, fs):
    with tempfile.TemporaryDirectory() as tmp:
        p = Path(tmp) / "x.csv"
        p.write_text("\n".join(sep.join(r) for r in rows))
        refused_or_ran("CSV reader", _read, p, None, None, fs)


def _valid_files(folder: Path) -> dict[str, Path]:
    from scipy.io import savemat
    rng = np.random.default_rng(0)
    a, b = rng.standard_normal((2, 2000))
    h5 = folder / "ok.h5"
    with h5py.File(h5, "w") as f:
        f["a"] = a
        f["b"] = b
        f["a"].attrs["fs_hz"] = 1e4
    mat = folder / "ok.mat"
    savemat(mat, {"a": a[:, None], "b": b[:, None], "fs": 1e4})
    return {"hdf5": h5, "mat5": mat}


def damaged(raw: bytes, data, anywhere: bool) -> bytes:
    """``raw`` cut short, or with 1-8 bytes overwritten, or 1-8 4-byte fields set to 2^31-1 (a
    huge declared size): in the first 4 KiB (the header, where sizes are declared), or
    ``anywhere`` in the file as well."""
    raw = bytearray(raw)
    op = data.draw(st.sampled_from(["cut", "flip", "huge"]))
    if op == "cut":
        return bytes(raw[:data.draw(st.integers(0, len(raw) - 1))])
    for _ in range(data.draw(st.integers(1, 8))):
        where = st.one_of(st.integers(0, 4096), st.integers(0, len(raw) - 4)) if anywhere else \
            st.integers(0, min(len(raw) - 4, 4096))
        i = min(data.draw(where), len(raw) - 4)
        val = b"\xff\xff\xff\x7f" if op == "huge" else bytes([data.draw(st.integers(0, 255))])
        raw[i:i + len(val)] = val
    return bytes(raw)


@pytest.mark.parametrize("kind", ["hdf5", "mat5"])
@SETTINGS
@given(data=st.data())
def test_truncated_or_corrupted_files(kind, data):
    """A valid file cut short, bytes overwritten (also in the header, where sizes are
    declared), or a size field set huge."""
    with tempfile.TemporaryDirectory() as tmp:
        src = _valid_files(Path(tmp))[kind]
        p = Path(tmp) / f"bad.{'h5' if kind == 'hdf5' else 'mat'}"
        p.write_bytes(damaged(src.read_bytes(), data, anywhere=False))
        refused_or_ran(f"{kind} reader", _read, p, "a", "b", None)


# --------------------------------------------------------------------------- diagnose options


@pytest.fixture(scope="module")
def record(tmp_path_factory):
    from axlebox.bearing.diagnostics.synthetic import coaxial_pair
    from axlebox.bearing.frequencies import orders, shaft_hz
    from axlebox.bearing.models.params import BearingParams
    a, b = coaxial_pair(1.0, 1e4, orders(BearingParams()).BPFO * shaft_hz(48.0),
                        np.random.default_rng(0))
    p = tmp_path_factory.mktemp("rec") / "rec.csv"
    p.write_text("a,b\n" + "\n".join(f"{x:.17g},{y:.17g}" for x, y in zip(a, b)))
    return p


OPTIONS = {"--fs": st.one_of(st.floats().map(repr), st.text(max_size=5)),
           "--rpm": st.one_of(st.floats().map(repr), st.text(max_size=5)),
           "--speed-kmh": st.floats().map(repr), "--band": st.text(",0123456789.-e", max_size=10),
           "--orders": st.text("BPFOIT=,.0123456789", max_size=20), "--bore": st.floats().map(repr),
           "--scale": st.floats().map(repr), "--vf-range": st.text(",0123456789.-e", max_size=10),
           "--left": st.sampled_from(["a", "b", "c", ""]), "--lag": st.text("decidvto", max_size=6),
           "--column": st.integers(-3, 5).map(str), "--nperseg": st.integers(-5, 10**6).map(str),
           "--bearing": st.sampled_from(["dtrb", "6205", "6203", "DTRB", "6206", "", " "]),
           "--bearing-left": st.sampled_from(["6205", "6203", "x", ""]),
           "--bearing-right": st.text("620513", max_size=5),
           "--orders-left": st.text("BPFOIT=,.0123456789", max_size=20),
           "--orders-right": st.sampled_from(["BPFO=3.05,BPFI=4.95,FTF=0.38,BSF=1.99", "BPFO=0"]),
           "--bore-left": st.floats().map(repr), "--bore-right": st.floats().map(repr)}


@SETTINGS
@given(st.dictionaries(st.sampled_from(sorted(OPTIONS)), st.just(None), min_size=1, max_size=3),
       st.data())
def test_diagnose_options(record, chosen, data):
    """``axlebox diagnose REC.csv --fs 1e4 --rpm 303 [options]``: exit 0 or 2, one line on stderr."""
    argv = ["diagnose", str(record), "--fs", "10000", "--speed-kmh", "48"]
    for k in chosen:
        argv += [k, data.draw(OPTIONS[k])]
    cli_exits_0_or_2("diagnose options", argv)


def cli_exits_0_or_2(entry: str, argv: list[str], limit_s: float = 60.0) -> int:
    """``axlebox ARGV`` in this process: exit 0, or 2 with one line on stderr and no traceback."""
    import contextlib
    import io

    from axlebox.pipelines.cli import main
    err = io.StringIO()
    with time_limit(limit_s), contextlib.redirect_stderr(err), contextlib.redirect_stdout(io.StringIO()):
        try:
            rc = main(argv)
        except SystemExit as e:          # argparse
            rc = e.code
    text = err.getvalue().strip()
    if rc == 1 and "Accepted" in text:   # the options passed; the run itself was replaced (Accepted)
        rc = 0
    assert rc in (0, 2), (argv, rc, text)
    if rc == 2:
        assert len(text.splitlines()) == 1 and "Traceback" not in text, (argv, text)
    SEEN.setdefault(entry, Counter())[kind_of(text) if rc else "(ran)"] += 1
    return rc


# ------------------------------------------------------------------ sweep options and [sweep] table

RIG_SWEEP = "[rig]\nduration = 0.1\n\n[[defects]]\nW = 0.001\n"
numbers = st.one_of(st.floats().map(repr), st.integers(-5, 500).map(str),
                    st.text("0123456789.-e", max_size=5))
SWEEP_OPTIONS = {"--speeds": st.lists(numbers, max_size=3), "--widths": st.lists(numbers, max_size=3),
                 "--kinds": st.lists(st.sampled_from(["outer", "inner", "roller", "x", ""]), max_size=3),
                 "--sides": st.lists(st.sampled_from(["L", "R", "LR", "l", ""]), max_size=3),
                 "--duration": numbers.map(lambda x: [x]), "--workers": numbers.map(lambda x: [x])}


@SETTINGS
@given(st.sampled_from(["rig", "vehicle"]),
       st.dictionaries(st.sampled_from(sorted(SWEEP_OPTIONS)), st.just(None), max_size=3),
       st.dictionaries(st.sampled_from(["speeds_kmh", "widths_mm", "kinds", "sides", "zz"]), values,
                       max_size=2), st.data())
def test_sweep_options_and_table(kind, chosen, table, data):
    """``axlebox sweep CONFIG --out DIR [options]`` with a ``[sweep]`` table of any values: exit 0
    or 2 in one line.  The cases are validated (every case's config) but not run: ``run_cases``
    is replaced by one that records them."""
    import tomli_w

    from axlebox.pipelines import sweep
    from axlebox.pipelines.simulate import load_config
    with tempfile.TemporaryDirectory() as tmp:
        if kind == "rig":
            base = RIG_SWEEP
        else:                               # the shipped vehicle config with one defect
            text = load_config("vehicle").to_toml()
            base = text + '\n[[defects]]\nW = 0.002\n' if "[[defects]]" not in text else text
        cfg = Path(tmp) / "c.toml"
        cfg.write_text(base + ("\n" + tomli_w.dumps({"sweep": table}) if table else ""))
        argv = ["sweep", str(cfg), "--out", str(Path(tmp) / "out")]
        for k in chosen:
            argv += [k, *data.draw(SWEEP_OPTIONS[k])]
        with patch.object(sweep, "run_cases", lambda todo, *a, **k: []):
            cli_exits_0_or_2("sweep options and [sweep]", argv)


# ------------------------------------------------- the rig's and the car's simulate options


class Accepted(Exception):
    """Raised in place of the run once a command's input is accepted."""


def _accepted(*a, **k):
    raise Accepted


RIG_OPTIONS = {"--speed-kmh": numbers, "--defect-width": numbers, "--defect-length": numbers,
               "--defect-depth": numbers, "--defect-row": numbers, "--defect-roller": numbers,
               "--defect-angle": numbers, "--defect-kind": st.sampled_from(["outer", "inner", "roller", "x"]),
               "--radial-load": numbers, "--axial-load": numbers, "--duration": numbers, "--dt": numbers,
               "--method": st.sampled_from(["rk4", "leapfrog", "imex", "x"]),
               "--damping": st.sampled_from(["ratio", "paper", "stiffness", "x"]),
               "--cage": st.sampled_from(["dynamic", "kinematic", "x"]), "--seed": numbers,
               "--param": st.tuples(st.sampled_from(["Z", "beta", "zeta", "c_r", "x", "D_m", "", "u_a",
                                                     "L_we", "n_slices", "model"]),
                                    numbers).map(lambda t: f"{t[0]}={t[1]}"),
               "--type": st.sampled_from(["dtrb", "dcrb", "x"])}


@SETTINGS
@given(st.dictionaries(st.sampled_from(sorted(RIG_OPTIONS)), st.just(None), min_size=1, max_size=4),
       st.data())
def test_bearing_simulate_options(chosen, data):
    """``axlebox bearing simulate [options] --out F``, the defect given by options: exit 2 in one
    line, or accepted (the rig's run replaced)."""
    from axlebox.bearing import rig
    with tempfile.TemporaryDirectory() as tmp:
        argv = ["bearing", "simulate", "--out", str(Path(tmp) / "r.h5")]
        for k in chosen:
            argv += [k, data.draw(RIG_OPTIONS[k])]
        with patch.object(rig, "simulate", _accepted):
            cli_exits_0_or_2("bearing simulate options", argv)


SIM_OPTIONS = {"--duration": numbers, "--checkpoint-every": numbers, "--restart": st.just(None),
               "--out": st.sampled_from(["r.h5", "nowhere/r.h5", ""])}


@SETTINGS
@given(st.dictionaries(st.sampled_from(sorted(SIM_OPTIONS)), st.just(None), min_size=1, max_size=3),
       st.sampled_from(["vehicle", "validation_48kmh", "no_such_config", "c.toml"]), st.data())
def test_simulate_options(chosen, config, data):
    """``axlebox simulate CONFIG [options]``: exit 2 in one line, or accepted (the model's build,
    the first costly step, replaced)."""
    from axlebox.pipelines import simulate
    with tempfile.TemporaryDirectory() as tmp:
        if config == "c.toml":
            config = str(Path(tmp) / "c.toml")
            Path(config).write_text(data.draw(st.sampled_from(["", "[run]\nduration = 0.1\n", "x = 1",
                                                               "[run\n", "\x00"])))
        argv = ["simulate", config]
        for k in chosen:
            v = data.draw(SIM_OPTIONS[k])
            argv += [k] if v is None else [k, str(Path(tmp) / v) if k == "--out" and v else v]
        if "--out" not in chosen:
            argv += ["--out", str(Path(tmp) / "r.h5")]
        with patch.object(simulate, "build_model", _accepted):
            cli_exits_0_or_2("simulate options", argv)


BODY_OPTIONS = {"--body": st.sampled_from(["wheelset", "axlebox", "frame", "all", "x"]),
                "--method": st.sampled_from(["guyan", "craig-bampton", "x"]), "--modes": numbers,
                "--fmax": numbers, "--mesh-size": numbers, "--zeta": numbers,
                "--coupling": st.sampled_from(["rbe2", "rbe3", "default", "x"]),
                "--param": st.tuples(st.sampled_from(["r_wheel", "axle_length", "x", "thickness", ""]),
                                     numbers).map(lambda t: f"{t[0]}={t[1]}")}


@SETTINGS
@given(st.dictionaries(st.sampled_from(sorted(BODY_OPTIONS)), st.just(None), min_size=1, max_size=4),
       st.data())
def test_bodies_build_options(chosen, data):
    """``axlebox bodies build [options] --out DIR``: exit 2 in one line, or accepted (meshing and
    the FE solve replaced)."""
    from axlebox.pipelines import bodies
    with tempfile.TemporaryDirectory() as tmp:
        argv = ["bodies", "build", "--out", tmp]
        if "--body" not in chosen:
            argv += ["--body", "wheelset"]
        for k in chosen:
            argv += [k, data.draw(BODY_OPTIONS[k])]
        with patch.object(bodies, "build_body", _accepted):
            cli_exits_0_or_2("bodies build options", argv)


# ---------------------------------------------------- damaged result files, dataset options


def _pair_results(folder: Path, n: int = 2) -> list[Path]:
    from axlebox.bearing.diagnostics.synthetic import coaxial_pair
    rng = np.random.default_rng(0)
    out = []
    for k in range(n):
        a, b = coaxial_pair(1.5, 1e4, 80.0, rng, amplitude=float(k))
        cfg = "[run]\nspeed_kmh = 48.0\n" + ('[[defects]]\nside = "L"\nW = 0.002\n' if k else "")
        out.append(write_pair_result(folder / f"c{k}.h5", a, b, cfg, 1e4, k))
    return out


@SETTINGS
@given(data=st.data())
def test_damaged_result_files(data):
    """An axlebox result cut short, overwritten or given a huge size field: the sweep's
    ``is_finished`` answers False (never raises), ``axlebox diagnose`` and ``axlebox dataset`` on
    it exit 0 or 2 in one line."""
    from axlebox.pipelines.sweep import is_finished
    with tempfile.TemporaryDirectory() as tmp:
        good, _ = _pair_results(Path(tmp))
        good.write_bytes(damaged(good.read_bytes(), data, anywhere=True))
        with time_limit(30.0):
            assert is_finished(good, "") in (True, False)
        cli_exits_0_or_2("result file: diagnose", ["diagnose", str(good)])
        cli_exits_0_or_2("result file: dataset", ["dataset", tmp, "--out", str(Path(tmp) / "data"),
                                                  "--window", "0.2", "--hop", "0.2"])


@pytest.fixture(scope="module")
def pair_folder(tmp_path_factory):
    d = tmp_path_factory.mktemp("pairs")
    _pair_results(d)
    return d


DATASET_OPTIONS = {"--window": numbers, "--hop": numbers,
                   "--criterion": st.sampled_from(["relative", "absolute", "x", ""])}


@SETTINGS
@given(st.dictionaries(st.sampled_from(sorted(DATASET_OPTIONS)), st.just(None), min_size=1, max_size=3),
       st.data())
def test_dataset_options(pair_folder, chosen, data):
    """``axlebox dataset DIR --out OUT [options]``: exit 0 or 2 in one line."""
    with tempfile.TemporaryDirectory() as tmp:
        argv = ["dataset", str(pair_folder), "--out", str(Path(tmp) / "data")]
        for k in chosen:
            argv += [k, data.draw(DATASET_OPTIONS[k])]
        cli_exits_0_or_2("dataset options", argv)


# ----------------------------------------------------------- bodies export (issue 22, items 2-3)


@pytest.fixture(scope="module")
def tiny_body_bytes(tmp_path_factory) -> bytes:
    from axlebox.fem import bodyfile

    from test_export import tiny_body
    return bodyfile.write(tiny_body(), tmp_path_factory.mktemp("tiny") / "tet.h5").read_bytes()


EXPORT_OUT = ["(folder)", "x.fem", "x.hdf5", "x.h5", "nowhere/x.fem", "tet.h5"]


@SETTINGS
@given(st.sampled_from(["exudyn", "mbdyn", "adams", ""]), st.sampled_from(EXPORT_OUT), st.booleans(),
       st.data())
def test_bodies_export(tiny_body_bytes, fmt, out, damage, data):
    """``axlebox bodies export BODY.h5 --format F --out PATH`` on a valid one-element body, or on
    that body cut short, overwritten or given a huge size field: exit 0 or 2 in one line."""
    with tempfile.TemporaryDirectory() as tmp:
        src = Path(tmp) / "tet.h5"
        src.write_bytes(damaged(tiny_body_bytes, data, anywhere=True) if damage else tiny_body_bytes)
        cli_exits_0_or_2("bodies export", ["bodies", "export", str(src), "--format", fmt, "--out",
                                           tmp if out == "(folder)" else str(Path(tmp) / out)])


# ------------------------------------------ spoiled records: what a real acquisition does (issue 57)
# Each class of spoiling drawn over its parameters, on a healthy wheelset and on an outer-ring
# defect and its copy (bearing/diagnostics/synthetic.py, 1 s at 10 kHz, 48 km/h, the DTRB),
# through ``axlebox diagnose`` on a CSV and through analyse_pair on the arrays: each is read
# (exit 0) or refused in one line (exit 2 / ParameterError), never exit 1; and no spoiling turns
# a healthy side faulty (real fault, faults on both sides), the worst error.  The outcomes
# (read and right, read, refused, crashed) go to SEEN for benchmarks/fuzz.py's figure.

N_SPOIL = 40 if full_size() else 3
SPOIL_SETTINGS = settings(max_examples=N_SPOIL, deadline=None, database=None, derandomize=True,
                          suppress_health_check=list(HealthCheck))
FS_SPOIL, T_SPOIL, KMH = 1e4, 1.0, 48.0
FAULTY = ("real fault", "faults on both sides")
SPOIL_CLASSES = ("quantized (ADC bits)", "quantized (decimals)", "clipped", "offset and drift",
                 "held stretch", "NaN gaps", "one channel all zeros", "channels of different lengths",
                 "shorter than two cage periods")


@pytest.fixture(scope="module")
def bases():
    """(left, right, defect side or None) for seeds 0-1: a healthy wheelset, a defect on the left."""
    from axlebox.bearing.diagnostics.synthetic import coaxial_pair
    from axlebox.bearing.frequencies import orders, shaft_hz
    from axlebox.bearing.models.params import BearingParams
    f = orders(BearingParams()).BPFO * shaft_hz(KMH)
    out = []
    for seed in range(2):
        for amp in (0.0, 1.0):
            a, b = coaxial_pair(T_SPOIL, FS_SPOIL, f, np.random.default_rng(seed), amplitude=amp)
            out.append((a, b, "left" if amp else None))
    return out


def spoiled(kind: str, a, b, data):
    """The pair ``a, b`` spoiled as ``kind`` says, its parameters drawn from ``data``: the two
    channels (NaN where a sample is lost; a shorter channel padded with NaN, an empty cell in
    the CSV) and a short description."""
    from axlebox.bearing.diagnostics import synthetic as sy
    n = a.size
    draw = data.draw
    side = draw(st.sampled_from(["left", "right", "both"]))
    which = {"left": (True, False), "right": (False, True), "both": (True, True)}[side]

    def each(fn):
        return tuple(fn(x) if w else x for x, w in zip((a, b), which))
    if kind == "quantized (ADC bits)":
        bits, k = draw(st.integers(8, 16)), draw(st.floats(3.0, 50.0))
        fsc = k * max(a.std(), b.std())
        return each(lambda x: sy.adc(x, bits, fsc)) + (f"{bits} bits on +-{k:.3g} RMS, {side}",)
    if kind == "quantized (decimals)":
        rms, dec = draw(st.floats(0.005, 2.0)), draw(st.integers(0, 4))
        g = rms / max(a.std(), b.std())
        return tuple(sy.quantize(g * x, 10.0 ** -dec) for x in (a, b)) + (f"RMS {rms:.3g}, {dec} decimals",)
    if kind == "clipped":        # 0.01 % to 70 % of the samples, evenly in the logarithm
        p = 1.0 - 10.0 ** draw(st.floats(-4.0, -0.15))
        return each(lambda x: sy.clip(x, np.quantile(np.abs(x), p))) + (f"at the {p:.4g} quantile, {side}",)
    if kind == "offset and drift":
        o, sl, w = draw(st.floats(-1e3, 1e3)), draw(st.floats(-20.0, 20.0)), draw(st.floats(0.0, 10.0))
        return each(lambda x: sy.drift(x, FS_SPOIL, o, sl, w, draw(st.floats(0.2, 100.0)))) + (
            f"offset {o:.3g}, slope {sl:.3g}/s, wander {w:.3g}, {side}",)
    if kind == "held stretch":
        i0, m = draw(st.integers(0, n - 1)), draw(st.integers(1, n))
        v = draw(st.sampled_from([None, 0.0]))
        return each(lambda x: sy.hold(x, i0, m, v)) + (f"{m} samples from {i0} held at {v}, {side}",)
    if kind == "NaN gaps":
        k, m = draw(st.integers(1, 20)), draw(st.integers(1, 2000))
        starts = draw(st.lists(st.integers(0, n - 1), min_size=k, max_size=k))
        return each(lambda x: sy.gaps(x, starts, m)) + (f"{k} gaps of {m} samples, {side}",)
    if kind == "one channel all zeros":
        z = draw(st.sampled_from(["left", "right"]))
        return (np.zeros(n), b, "left all zeros") if z == "left" else (a, np.zeros(n), "right all zeros")
    if kind == "channels of different lengths":
        m = draw(st.integers(1, n - 1))
        cut = np.r_[np.ones(n - m), np.full(m, np.nan)]
        return each(lambda x: x * cut) + (f"{side} {m} samples shorter",)
    m = draw(st.integers(8, int(0.9 / 2.203 * 2 * FS_SPOIL) - 1))     # two FTF periods at 48 km/h
    return a[:m], b[:m], f"{m} samples"


def score(entry: str, words: dict | None, defect, outcome: str) -> None:
    """Counts ``outcome`` (a refusal's kind, or "crashed") or, for a read, whether its verdict
    is right: the defect side a real fault and the other not faulty, or both healthy; and
    asserts the worst error absent: no healthy side called faulty."""
    if words is not None:
        healthy = [s for s in ("left", "right") if s != defect]
        assert not any(words[s] in FAULTY for s in healthy), (entry, words, defect)
        right = (words[defect] == "real fault") if defect else \
            words == {"left": "healthy", "right": "healthy"}
        outcome = "read, right" if right else f"read, {words}"
    SEEN.setdefault(entry, Counter())[outcome] += 1


def _csv(path: Path, a, b) -> None:
    """Two columns; a NaN is written as an empty cell where the channel has ended (NaN to its
    end), as ``nan`` elsewhere."""
    def cells(x):
        tail = x.size - np.argmax(~np.isnan(x[::-1])) if np.isfinite(x).any() else 0
        return [("" if i >= tail else "nan") if v != v else repr(float(v)) for i, v in enumerate(x)]
    path.write_text("a,b\n" + "\n".join(f"{u},{v}" for u, v in zip(cells(a), cells(b))) + "\n")


@pytest.mark.parametrize("kind", SPOIL_CLASSES)
@SPOIL_SETTINGS
@given(data=st.data())
def test_spoiled_record_through_the_command(bases, kind, data):
    """``axlebox diagnose REC.csv --fs 1e4 --speed-kmh 48`` on a spoiled record: exit 0 or 2 in
    one line; read, no healthy side called faulty."""
    a, b, defect = bases[data.draw(st.integers(0, len(bases) - 1))]
    x_l, x_r, what = spoiled(kind, a, b, data)
    note(what)
    with tempfile.TemporaryDirectory() as tmp:
        p, out = Path(tmp) / "rec.csv", Path(tmp) / "rec.json"
        _csv(p, x_l, x_r)
        try:
            rc = cli_exits_0_or_2(f"spoiled: {kind} (command)",
                                  ["diagnose", str(p), "--fs", str(FS_SPOIL), "--speed-kmh", str(KMH),
                                   "--json", str(out)])
        except AssertionError:
            score(f"spoiled: {kind} (command)", None, defect, "crashed")
            raise
        words = json.loads(out.read_text())["verdict"]["words"] if rc == 0 else None
    score(f"spoiled: {kind}", words, defect, "refused" if rc else "")


@pytest.mark.parametrize("kind", SPOIL_CLASSES)
@SPOIL_SETTINGS
@given(data=st.data())
def test_spoiled_record_through_analyse_pair(bases, kind, data):
    """``analyse_pair`` on the spoiled arrays: a result, or a one-line ParameterError (NaN and
    channels of different lengths are refused there: reading around gaps is the readers' job);
    no healthy side called faulty."""
    from axlebox.bearing.catalogue import lookup
    from axlebox.bearing.diagnostics.pair import analyse_pair
    from axlebox.bearing.frequencies import shaft_hz
    a, b, defect = bases[data.draw(st.integers(0, len(bases) - 1))]
    x_l, x_r, what = spoiled(kind, a, b, data)
    note(what)
    if kind == "channels of different lengths":
        x_l, x_r = x_l[np.isfinite(x_l)], x_r[np.isfinite(x_r)]
    dtrb = lookup("dtrb")
    entry = f"spoiled: {kind} (analyse_pair)"
    with time_limit(60.0):
        try:
            r = analyse_pair(x_l, x_r, FS_SPOIL, shaft_hz(KMH), dtrb.orders, dtrb.bore)
        except ParameterError as err:
            assert str(err) and "\n" not in str(err), str(err)
            SEEN.setdefault(entry, Counter())[kind_of(str(err))] += 1
            return
        except Exception as err:
            score(entry, None, defect, f"crashed: {type(err).__name__}")
            raise
    score(entry, r.verdict.words, defect, "")


def teardown_module():
    if os.environ.get("AXLEBOX_FUZZ_REPORT"):
        with open(os.environ["AXLEBOX_FUZZ_REPORT"], "w") as fh:
            for entry, c in SEEN.items():
                fh.write(f"{entry}\t{sum(c.values())}\t{len(c)}\t" + " | ".join(
                    f"{k} x{v}" for k, v in c.most_common()) + "\n")
