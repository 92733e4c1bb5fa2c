"""One declaration per config field (mbs/vehicle/config.py, axlebox/_params.py) and the reference generated
from it (pipelines/config_reference.py): the page lists exactly the fields the loader accepts, with
the defaults the code uses (one default per field: the config's and the classes the run is built
from agree), every field documented, its tables well formed and a Sphinx build of it clean with
warnings as errors."""
import dataclasses
import re
import subprocess
import sys
import tomllib

import pytest

from axlebox._params import ParameterError
from axlebox.bearing import models
from axlebox.bearing.defects import Defect
from axlebox.bearing.rig import RIG_SECTIONS, RigConfig
from axlebox.mbs.vehicle import config
from axlebox.pipelines import config_reference
from axlebox.mbs.track.line import Segment
from axlebox.mbs.vehicle.config import SECTIONS, CarConfig, WheelDefect
from axlebox.pipelines.config_reference import HEADER, reference_markdown
from axlebox.pipelines.sweep import SWEEP_FIELDS

# every unit the reference may give: a typo or a unit written another way fails here
UNITS = {"", "-", "s", "m", "m/s", "km/h", "Hz", "kg", "kg/m", "kg m^2", "N", "N/m", "N s/m",
         "N m^2", "N m/rad", "Pa", "rad", "deg", "µm", "mm"}
CELL = re.compile(r"(?<!\\)\|")


def cells(line: str) -> list[str]:
    """A table row's cells (``|`` escaped as ``\\|`` stays inside a cell)."""
    assert line.startswith("|") and line.endswith("|"), line
    return [c.strip() for c in CELL.split(line[1:-1])]


def tables(md: str) -> dict[str, dict[str, list[str]]]:
    """``heading -> field -> cells`` of the page; every row checked to have the header's cells."""
    out, heading = {}, None
    for line in md.splitlines():
        if line.startswith("## "):
            heading = line[3:]
            assert heading not in out, f"heading {heading!r} twice"
            out[heading] = {}
        elif line.startswith("|") and heading is not None:
            row = cells(line)
            assert len(row) == len(HEADER), f"{heading}: {line!r} has {len(row)} cells"
            if row == list(HEADER) or set(line) <= set("|-"):
                continue
            name = row[0].strip("`")
            assert name not in out[heading], f"{heading}: {name} twice"
            out[heading][name] = row
    return out


def bearing_heading(name: str) -> str:
    """The reference's heading of model ``name``'s ``[bearing]`` table."""
    return "[bearing]" if name == models.DEFAULT else f'[bearing] type = "{name}"'


def toml_value(cell: str):
    """The value a cell's first code span holds, read as TOML."""
    m = re.match(r"`([^`]*)`", cell)
    assert m, cell
    return tomllib.loads(f"x = {m.group(1)}")["x"]


@pytest.fixture(scope="module")
def md():
    return reference_markdown()


@pytest.fixture(scope="module")
def page(md):
    return tables(md)


def _accepted(section: str) -> list[str]:
    """The fields the loader accepts in ``[section]``, as its refusal of an unknown one lists
    them (the loader's own word, not the declaration's)."""
    with pytest.raises(ParameterError, match="expected one of") as err:
        config.validate({section: {"no_such_field": 1}})
    return err.value.args[0].split("expected one of ")[1].split(", ")


def test_every_section_field_has_a_unit_and_a_meaning():
    for sec, cls in SECTIONS.items():
        assert cls.__doc__.strip(), sec
        for f in dataclasses.fields(cls):
            numeric = "range" in f.metadata
            # a number declared without a unit is dimensionless ("-" on the page)
            unit = f.metadata.get("unit", "") or ("-" if numeric else "")
            assert f.metadata.get("doc", "").strip(), f"{sec}.{f.name}: no meaning"
            assert unit in UNITS, f"{sec}.{f.name}: unit {unit!r}"
            assert (unit != "") == numeric, f"{sec}.{f.name}: unit {unit!r}"


def test_the_reference_lists_exactly_the_fields_the_loader_takes_with_the_codes_defaults(page):
    """The generated page against the loader and the code that runs: each section's rows are
    the fields ``validate`` accepts, in order; each default is the value a config that leaves the
    field out runs with (``CarConfig()``, the TOML ``to_toml`` writes), and that value is
    accepted and round-trips through the file."""
    defaults = CarConfig()
    stored = tomllib.loads(defaults.to_toml())
    assert list(page)[:len(SECTIONS)] == [f"[{s}]" for s in SECTIONS]
    for sec in SECTIONS:
        rows = page[f"[{sec}]"]
        assert list(rows) == _accepted(sec), sec
        for key, row in rows.items():
            used = getattr(getattr(defaults, sec), key)
            shown = toml_value(row[2])
            assert shown == (list(used) if isinstance(used, tuple) else used), f"{sec}.{key}"
            assert stored[sec][key] == shown, f"{sec}.{key}"
    assert config.loads(defaults.to_toml()) == defaults


def test_one_default_per_field_the_config_and_the_run_classes_agree():
    """The issue-50 table, now empty: the config's default of each field the integrator, the
    track and the wheel-rail element also take is theirs (``like``), so building them from a
    config that leaves every field out gives their own defaults."""
    from axlebox.mbs.solver.integrate import Settings
    from axlebox.mbs.track.irregularity import IrregularityParams
    from axlebox.mbs.wheelrail.element import WheelRailParams
    from axlebox.mbs.wheelrail.geometry import TrackLayout
    c = CarConfig()
    assert c.settings() == Settings()
    assert c.layout() == TrackLayout()
    assert c.wheelrail_params() == WheelRailParams()
    assert c.irregularity() == IrregularityParams()
    # the rows of the table in the issue, by name
    assert (c.integrator.method, c.integrator.dt, c.integrator.state_rate_hz) == ("leapfrog", 5e-5, 500.0)
    assert (c.wheelrail.back_to_back, c.wheelrail.fastsim_grid, c.wheelrail.smooth_y) == (1.360, 8, 1e-3)
    assert (c.track.length, c.track.roughness_lambda_min) == (400.0, 0.003)


def test_the_shipped_vehicle_config_writes_out_the_defaults():
    """configs/vehicle.toml spells out every default with its source: it must stay the defaults."""
    from axlebox import configs
    assert config.load(configs.path("vehicle")) == CarConfig()


def test_every_range_and_choice_the_page_shows_is_what_the_loader_does(page):
    """Each number's ends are accepted and a step past them refused; each choice accepted."""
    base = CarConfig()
    for sec, cls in SECTIONS.items():
        for f in dataclasses.fields(cls):
            row = page[f"[{sec}]"][f.name]
            if "range" in f.metadata and "length" not in f.metadata and "numbers" not in f.metadata:
                lo, hi = (tomllib.loads(f"x = {v}")["x"]
                          for v in row[4].split(";")[0].split(" (")[0].split(" … "))
                assert (lo, hi) == f.metadata["range"], f"{sec}.{f.name}"
                step = 1 if f.type == "int" else max(abs(hi), 1.0) * 1e-6
                with pytest.raises(ParameterError, match=rf"{sec}\.{f.name} = "):
                    config.validate({sec: {f.name: hi + step}})
            elif "choices" in f.metadata:
                assert re.findall(r'`"([^"]*)"`', row[4].split(";")[0]) == list(f.metadata["choices"])
                with pytest.raises(ParameterError, match=rf"{sec}\.{f.name} = 'zz' is not allowed"):
                    config.validate({sec: {f.name: "zz"}})
    assert base.run.speed_kmh == 48.0


@pytest.mark.parametrize("rows, expected", [
    *[(lambda name=name: config_reference.bearing_rows(name),
       ["type"] + [f.name for f in dataclasses.fields(m.Params)]) for name, m in models.MODELS.items()],
    (config_reference.defect_rows, ["wheelset", "side"] + [f.name for f in dataclasses.fields(Defect)]
     + ["angle_deg"]),
    (config_reference.wheel_defect_rows, [f.name for f in dataclasses.fields(WheelDefect)]),
    (config_reference.track_layout_rows, [f.name for f in dataclasses.fields(Segment)]),
    (config_reference.rig_rows, [f.name for f in dataclasses.fields(RigConfig)
                              if f.name not in RIG_SECTIONS]),
    (config_reference.sweep_rows, list(SWEEP_FIELDS)),
], ids=[f"bearing_{name}" for name in models.MODELS] + ["defects", "wheel_defects", "track_layout",
                                                       "rig", "sweep"])
def test_free_form_tables_document_every_field_the_code_takes(rows, expected):
    got = rows()
    assert [r[0] for r in got] == expected
    for name, typ, default, unit, allowed, meaning in got:
        assert typ and default and allowed and meaning.strip(), name
        assert unit in UNITS, f"{name}: unit {unit!r}"
        if typ in ("float", "int") or typ.startswith("list of float"):
            assert unit, f"{name}: a number without a unit"


def test_free_form_defaults_and_ranges_are_the_dataclasses(page):
    for heading, cls in [(bearing_heading(name), m.Params) for name, m in models.MODELS.items()] \
            + [("[rig]", RigConfig)]:
        for f in dataclasses.fields(cls):
            if f.name in RIG_SECTIONS:
                continue
            row = page[heading][f.name]
            assert toml_value(row[2]) == f.default, f"{heading} {f.name}"
            if "range" in f.metadata:
                lo, hi = (tomllib.loads(f"x = {v}")["x"]
                          for v in row[4].split(";")[0].split(" (")[0].split(" … "))
                assert (lo, hi) == f.metadata["range"], f"{heading} {f.name}"


def test_the_vehicle_defect_angle_range_is_what_the_config_accepts(page):
    """angle_deg's range on the page is what the vehicle's [[defects]] accepts."""
    row = page["[[defects]]"]["angle_deg"]
    lo, hi = (float(v) for v in row[4].split(" … "))
    dtrb = {"joint": {"model": "dtrb"}, "integrator": {"dt": 1e-5}}
    for ok in (lo, hi):
        config.validate({**dtrb, "defects": [{"angle_deg": ok}]})
    for bad in (lo - 1e-6, hi + 1e-6):
        with pytest.raises(ParameterError, match="angle_deg"):
            config.validate({**dtrb, "defects": [{"angle_deg": bad}]})
    # and the fields the vehicle's [[defects]] takes are the documented ones less the rig's angle
    with pytest.raises(ParameterError, match="expected one of (.*)") as err:
        config.validate({**dtrb, "defects": [{"nonsense": 1}]})
    taken = err.value.args[0].split("expected one of ")[1].split(", ")
    assert sorted(taken) == sorted(set(page["[[defects]]"]) - {"angle"})


def test_page_title_intro_and_headings(md, page):
    lines = md.splitlines()
    assert lines[0] == "# Config reference"
    assert sum(line.startswith("# ") for line in lines) == 1
    assert not any(line.startswith("###") for line in lines)
    assert "generated from the dataclasses that declare them" in md
    expected = [f"[{s}]" for s in SECTIONS] + [bearing_heading(name) for name in models.MODELS] \
        + ["[[defects]]", "[[wheel_defects]]", "[[track.layout]]", "[rig]", "[sweep]"]
    assert list(page) == expected


def test_page_spot_checks_as_written_in_the_shipped_vehicle_config(page):
    assert page["[run]"]["duration"][2] == "`5.0`"
    assert page["[track]"]["pad_k"][2] == "`6.5e7`"
    assert page["[track]"]["pad_k"][3] == "N/m"
    assert page["[run]"]["speed_kmh"][3] == "km/h"
    assert "Zhai et al. 2004" in page["[track]"]["pad_k"][5]


def test_a_bar_in_a_cell_is_escaped(monkeypatch):
    from axlebox._params import param, section

    @section("run")
    class Run:
        """A section whose field's meaning holds a bar."""
        duration: float = param(5.0, 1e-4, 1e4, "s", "a | b")
    monkeypatch.setitem(SECTIONS, "run", Run)
    row = tables(reference_markdown())["[run]"]["duration"]
    assert row[5] == r"a \| b"


def test_sphinx_builds_the_page_with_warnings_as_errors(tmp_path, md):
    pytest.importorskip("sphinx")
    pytest.importorskip("myst_parser")
    src = tmp_path / "src"
    src.mkdir()
    # the MyST settings of docs/conf.py
    (src / "conf.py").write_text('project = "axlebox"\nextensions = ["myst_parser"]\n'
                                 'myst_enable_extensions = ["dollarmath", "colon_fence"]\n'
                                 "myst_heading_anchors = 3\n")
    (src / "index.md").write_text(md)
    out = subprocess.run([sys.executable, "-m", "sphinx", "-W", "-q", "-b", "html", str(src),
                          str(tmp_path / "html")], capture_output=True, text=True, timeout=300)
    assert out.returncode == 0, out.stdout + out.stderr
    html = (tmp_path / "html" / "index.html").read_text()
    assert html.count("<table") == len(tables(md))


def test_the_declared_choices_are_the_codes():
    """Choice lists a section spells out itself must be the ones the code acts on."""
    from axlebox.mbs.kernel import exchange
    from axlebox.mbs.track import roughness
    from axlebox.mbs.wheelrail import element

    def choices(sec, key):
        f = next(f for f in dataclasses.fields(SECTIONS[sec]) if f.name == key)
        return set(f.metadata["choices"])
    assert choices("coupling", "hold") == set(exchange.HOLDS)
    assert choices("wheelrail", "law") == set(element.LAWS)
    assert choices("wheelrail", "fastsim_update") == set(element.UPDATES)
    assert choices("track", "rail_roughness") == {"none", *roughness.RAIL_DB}
    assert choices("track", "wheel_roughness") == {"none", *roughness.WHEEL_DB}


@pytest.mark.parametrize("name,words", [("carbody", "has no FE body"), ("gb2", "has no FE body"),
                                        ("ws9", "is not a body")])
def test_only_bodies_with_an_fe_body_can_be_flexible(name, words):
    """The carbody and gearboxes are always rigid: naming them flexible was silently ignored."""
    from axlebox._params import ParameterError
    from axlebox.mbs.vehicle.config import validate
    with pytest.raises(ParameterError, match=rf"bodies.flexible = \['{name}'\] is not allowed: "
                                             rf"'{name}' {words}"):
        validate({"bodies": {"flexible": [name]}})
    assert validate({"bodies": {"flexible": ["frame2", "ws4", "ab3L"]}}).bodies.flexible == \
        ("frame2", "ws4", "ab3L")
