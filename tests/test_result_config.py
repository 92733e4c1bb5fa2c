"""The whole validated config in every result (issue 50): a car run stores its config with every
default filled in and the package version; every reader (``axlebox diagnose``, ``report``,
``dataset``) loads it through the loader ``axlebox simulate`` uses, so a shipped config with any
one optional field left out still gives a result that is read without a flag; older files whose
config text names only what differed still read, and one this version cannot run is refused in
one line naming the field."""
import dataclasses
import json
import re
import tomllib

import h5py
import numpy as np
import pytest
import tomli_w

from axlebox import configs
from axlebox.bearing import models, resultfile
from axlebox.bearing.diagnostics.synthetic import coaxial_pair
from axlebox.bearing.frequencies import shaft_hz
from axlebox.bearing.rig import RigConfig, config_from_dict
from axlebox.mbs.vehicle import config as vconfig
from axlebox.pipelines import cli, readers
from axlebox.pipelines import simulate as psim

FS = 10_000.0


def _variants():
    """``(config name, field removed, its full TOML as the run stores it)`` for every field each
    shipped config sets whose removal the loader accepts (the rest are required by another field
    the config sets, and refused in one line: asserted here too); variants that store the same
    config are one (the readers see the same file)."""
    out, seen, required = [], set(), []
    for path in sorted(configs.folder().glob("*.toml")):
        raw = tomllib.loads(path.read_text())
        raw.pop("sweep", None)
        rig = "rig" in raw
        load = config_from_dict if rig else vconfig.validate
        for sec, table in raw.items():
            for key in (list(table) if isinstance(table, dict) else []):
                d = {s: (dict(v) if isinstance(v, dict) else v) for s, v in raw.items()}
                del d[sec][key]
                try:
                    text = load(d).to_toml()
                except Exception as err:       # noqa: BLE001 - what it is is asserted below
                    required.append((path.stem, f"{sec}.{key}", err))
                    continue
                if text not in seen:
                    seen.add(text)
                    out.append((path.stem, f"{sec}.{key}", rig, text))
    return out, required


VARIANTS, REQUIRED = _variants()


def _write(path, text: str, rig: bool, seed: int = 0, long: bool = True) -> None:
    """A result file as a run of config ``text`` writes it (resultfile.write, the config stored
    whole), with a synthetic outer-ring defect at its bearing's BPFO on one side: as long as the
    diagnosis needs (``long``: the fade-in, then two cage periods) or 0.2 s (to be read only)."""
    cfg = config_from_dict(tomllib.loads(text)) if rig else vconfig.loads(text)
    f_s = shaft_hz(*((cfg.speed_kmh, cfg.r_wheel) if rig else (cfg.run.speed_kmh, cfg.wheelset.r0)))
    o = models.orders(cfg.bearing)
    T = 0.5 + 2.1 / (o.FTF * f_s) if long else 0.2
    a, b = coaxial_pair(T, FS, o.BPFO * f_s, np.random.default_rng(seed))
    z = np.zeros_like(a)
    names = {"outer_ring": a} if rig else {"ws2_R": a, "ws2_L": b}
    signals = {n: {"acceleration": np.c_[z, z, x]} for n, x in names.items()}
    resultfile.write(path, config_toml=text, seed=0, time=np.arange(a.size) / FS, fs_hz=FS,
                     signals=signals, attrs={"status": "done"})


RIG_CHANNELS = ["--left", "outer_ring", "--right", "outer_ring"]    # the rig's one sensor


def test_every_optional_field_removal_is_accepted_or_refused_in_one_line():
    """What a config cannot leave out (a field another one it sets depends on) is refused before
    a run, in one line naming a field."""
    assert len(VARIANTS) > 50 and REQUIRED
    for name, field, err in REQUIRED:
        assert isinstance(err, vconfig.ParameterError) and "\n" not in str(err), (name, field, err)
        assert re.search(r"\w+\.\w+ = ", str(err)), (name, field, err)       # names a field


@pytest.fixture(scope="module")
def no_speed_run(tmp_path_factory):
    """The shipped car (rigid bodies, bushings: quick) without ``[run] speed_kmh``, 0.05 s:
    ``(config text, result file)``."""
    raw = tomllib.loads(configs.path("vehicle").read_text())
    del raw["run"]["speed_kmh"]
    raw["run"]["duration"] = 0.05
    raw["bodies"]["flexible"] = []
    text = tomli_w.dumps(raw)
    out = tmp_path_factory.mktemp("no_speed") / "run.h5"
    psim.run(psim.Config(text, "no_speed"), out, log=lambda *_: None, checkpoint_every=0)
    return text, out


def test_a_car_run_stores_its_whole_config_and_the_package_version(no_speed_run):
    """The issue's case: ``[run] speed_kmh`` left out runs at the default 48 km/h, and the result
    says so: its stored config is the whole validated one (what ``load_config`` gives), so the
    reader finds the shaft speed without a flag."""
    text, out = no_speed_run
    with h5py.File(out, "r") as f:
        stored, version = str(f.attrs["config"]), str(f.attrs["package_version"])
    assert stored == psim.load_config(psim.Config(text, "no_speed")).to_toml()
    assert tomllib.loads(stored)["run"]["speed_kmh"] == 48.0
    from importlib.metadata import version as installed
    assert version == installed("axlebox")
    rec = readers.read(out)
    assert rec.shaft_hz == pytest.approx(shaft_hz(48.0, 0.42), rel=1e-12)


def test_every_variant_is_read_as_its_run_had_it(tmp_path):
    """What each command reads of a result (diagnose: the record's shaft speed and bearing;
    report: the case's speed, defect width and side; dataset: the case's labels) is the stored
    config's, read through the run's loader, for every variant, without a flag."""
    from axlebox.pipelines import dataset, report
    for i, (name, field, rig, text) in enumerate(VARIANTS):
        path = tmp_path / f"v{i:03d}.h5"
        _write(path, text, rig, seed=i, long=False)
        cfg = config_from_dict(tomllib.loads(text)) if rig else vconfig.loads(text)
        speed, r = (cfg.speed_kmh, cfg.r_wheel) if rig else (cfg.run.speed_kmh, cfg.wheelset.r0)
        rec = readers.read(path, *(("outer_ring", "outer_ring") if rig else ()))
        assert rec.shaft_hz == shaft_hz(speed, r), (name, field)
        assert rec.orders == models.orders(cfg.bearing), (name, field)
        assert report.case_parameters(path)[0] == speed, (name, field)
        if not rig:
            labels, _ = dataset.case_labels(path)
            assert labels["speed_kmh"] == speed, (name, field)
            assert labels["real_side"] == {0: "none", 1: "right" if cfg.defects and
                                           cfg.defects[0].side == "R" else "left"}.get(
                len({d.side for d in cfg.defects if d.wheelset == labels["wheelset"]}), "both"), \
                (name, field)


#: the end-to-end commands on one variant of these configs (each command on every variant takes
#: ten minutes; what they read is the test above): a DTRB car with a defect, a DCRB car, wheel
#: defects on bushings, the shipped car (bushings, no defect), the rig
END_TO_END = ("validation_48kmh", "dcrb_48kmh", "confounders", "vehicle", "study_rig")


def test_diagnose_report_and_dataset_run_on_results_of_shipped_configs_without_a_flag(tmp_path,
                                                                                      capsys):
    picked = {}
    for name, field, rig, text in VARIANTS:
        if name in END_TO_END and name not in picked:
            picked[name] = (field, rig, text)
    assert set(picked) == set(END_TO_END)
    car = tmp_path / "car"
    car.mkdir()
    for i, (name, (field, rig, text)) in enumerate(picked.items()):
        path = (tmp_path if rig else car) / f"{name}.h5"
        _write(path, text, rig, seed=i)
        rc = cli.main(["diagnose", str(path), *(RIG_CHANNELS if rig else []),
                       "--json", str(tmp_path / "d.json")])
        assert rc == 0, (name, field, capsys.readouterr().err)
        assert json.loads((tmp_path / "d.json").read_text()), (name, field)
    rc = cli.main(["report", str(car), "--out", str(tmp_path / "report")])
    assert rc == 0, capsys.readouterr().err
    assert (tmp_path / "report" / "index.html").is_file()
    rc = cli.main(["dataset", str(car), "--out", str(tmp_path / "ds")])
    assert rc == 0, capsys.readouterr().err
    import xarray as xr
    with xr.open_dataset(tmp_path / "ds" / "dataset.nc") as ds:
        assert ds.attrs["n_cases"] == len(END_TO_END) - 1


def test_a_car_result_stores_each_wheelsets_shaft_angle_and_speed(no_speed_run):
    """Issue 51, item 2: ``shafts/ws<k>/angle`` and ``speed`` at the output rate.  At 48 km/h on
    0.42 m wheels the spin is V / r0 to the creep (under 0.5 %), and the stored angle is the
    integral of the stored speed (trapezoid, to 1e-6 of a turn over 500 outputs)."""
    _, out = no_speed_run
    with h5py.File(out, "r") as f:
        t = f["time"][()]
        for k in range(1, 5):
            angle, speed = f[f"shafts/ws{k}/angle"][()], f[f"shafts/ws{k}/speed"][()]
            assert angle.shape == speed.shape == t.shape
            assert f[f"shafts/ws{k}/angle"].attrs["unit"] == "rad"
            assert np.all(np.abs(speed / (48.0 / 3.6 / 0.42) - 1.0) < 5e-3), k
            integral = np.concatenate([[0.0], np.cumsum(0.5 * (speed[1:] + speed[:-1]) * np.diff(t))])
            assert np.max(np.abs(angle - integral)) < 2 * np.pi * 1e-6, k


def test_a_car_result_stores_each_wheels_Y_Q_and_each_wheelsets_sum_Y(no_speed_run):
    """Issue 69, item 4 (on tangent track): ``wheelrail/<wheel>/YQ`` and ``wheelrail/ws<k>/sum_Y``.
    At the first output the car stands in its statics' equilibrium on smooth track: the eight Q
    carry the car's weight (8 Q0, to the statics' tolerance, 1e-3 of it), each wheelset's two Y
    balance (sum Y zero to 1e-3 of Q0: nothing pushes the car sideways; the gearbox side's Q is
    the larger), each Y the push of its tread's contact angle (Y/Q about 0.008 on S1002 / 60E1
    1:40, under 0.05); the limits are Nadal's at the S1002 flange (70 deg) and Prud'homme's at
    Q0."""
    from axlebox.mbs.post import safety
    from axlebox.mbs.vehicle.car import static_wheel_load
    from axlebox.mbs.wheelrail.standard import s1002
    text, out = no_speed_run
    cfg = vconfig.loads(text)
    Q0 = static_wheel_load(cfg)
    with h5py.File(out, "r") as f:
        t = f["time"][()]
        Q = 0.0
        for k in range(1, 5):
            L, R = f[f"wheelrail/ws{k}_L/YQ"], f[f"wheelrail/ws{k}_R/YQ"]
            assert L.shape == (t.size, 4) and L.attrs["columns"] == "Y, Q, Y/Q, Y/Q 2 m sliding mean"
            assert L.attrs["nadal_limit"] == pytest.approx(
                float(safety.nadal(safety.flange_angle(s1002()), cfg.wheelrail.mu)), rel=1e-12)
            yl, yr = L[0], R[0]
            Q += yl[1] + yr[1]
            assert 0.0 < yl[2] < 0.05 and 0.0 < yr[2] < 0.05
            sY = f[f"wheelrail/ws{k}/sum_Y"]
            assert abs(sY[0, 0]) < 1e-3 * Q0
            assert sY.attrs["prudhomme_limit_N"] == pytest.approx(1e4 + 2 * Q0 / 3, rel=1e-12)
        assert Q == pytest.approx(8 * Q0, rel=1e-3)


def test_older_result_files_read_and_a_config_this_version_refuses_is_one_line(tmp_path):
    """A file from before issue 50 stores the user's text only (defaults left out): read as the
    run read it.  A stored config this version does not run is refused naming the field."""
    old = tmp_path / "old.h5"
    text = "[run]\nduration = 1.0\n[joint]\nmodel = \"bearing\"\n[integrator]\ndt = 1e-5\n"
    _write(old, vconfig.loads(text).to_toml(), rig=False, long=False)
    with h5py.File(old, "r+") as f:              # the file: speed_kmh left out
        f.attrs["config"] = text
        del f.attrs["package_version"]
    rec = readers.read(old)
    assert rec.shaft_hz == pytest.approx(shaft_hz(48.0, 0.42), rel=1e-12)
    bad = tmp_path / "bad.h5"
    _write(bad, vconfig.CarConfig().to_toml(), rig=False)
    with h5py.File(bad, "r+") as f:
        f.attrs["config"] = "[run]\nspeed_kmh = 900.0\n"
    with pytest.raises(vconfig.ParameterError) as err:
        readers.read(bad)
    msg = str(err.value)
    assert "run.speed_kmh" in msg and "bad.h5" in msg and "\n" not in msg


def test_the_rig_stores_its_whole_config_too():
    """A rig config that leaves everything out stores every field (RigConfig.to_toml)."""
    c = config_from_dict({})
    stored = tomllib.loads(c.to_toml())
    assert set(stored["rig"]) == {f.name for f in dataclasses.fields(RigConfig)} - {"bearing", "defects"}
    assert config_from_dict(stored) == c
