"""The config reference (pipelines/config_reference.py): every field of every config documented,
nothing stale, the page's defaults and ranges the code's own, its tables well formed and a Sphinx build
of it clean with warnings as errors."""
import dataclasses
import re
import subprocess
import sys
import tomllib

import pytest

from axlebox._params import ParameterError
from axlebox.bearing.defects import Defect
from axlebox.bearing.dcrb import DcrbParams
from axlebox.bearing.params import BearingParams
from axlebox.bearing.rig import RIG_SECTIONS, RigConfig
from axlebox.mbs import config
from axlebox.pipelines import config_reference
from axlebox.mbs.config import DEFECT_PLACE, SCHEMA, WHEEL_DEFECT
from axlebox.pipelines.config_reference import FIELDS, HEADER, SECTION_NOTES, reference_markdown
from axlebox.pipelines.sweep import SWEEP_FIELDS

# every unit the reference may give: a typo or a unit written another way fails here
UNITS = {"", "-", "s", "m", "m/s", "km/h", "Hz", "kg", "kg/m", "kg m^2", "N", "N/m", "N s/m",
         "N m^2", "N m/rad", "Pa", "rad", "deg", "µm", "mm"}
NUMERIC = (config.F, config.I, config.N)
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


def test_every_schema_field_has_a_unit_and_a_meaning_and_none_is_stale():
    assert list(FIELDS) == list(SCHEMA)
    assert set(SECTION_NOTES) == set(SCHEMA) and all(SECTION_NOTES.values())
    for sec, fields in SCHEMA.items():
        assert list(FIELDS[sec]) == list(fields), f"[{sec}]: documented fields differ from SCHEMA's"
        for key, spec in fields.items():
            unit, meaning = FIELDS[sec][key]
            assert unit in UNITS, f"{sec}.{key}: unit {unit!r}"
            assert meaning.strip(), f"{sec}.{key}: no meaning"
            numbers = spec[0] in NUMERIC or (spec[0] == config.L and len(spec[2]) == 2
                                            and not isinstance(spec[2][0], str))
            assert (unit != "") == numbers, f"{sec}.{key}: unit {unit!r} for a {spec[0]}"


def test_speed_kmh_says_it_is_in_kmh():
    unit, meaning = FIELDS["run"]["speed_kmh"]
    assert unit == "km/h" and "km/h" in meaning


@pytest.mark.parametrize("rows, expected", [
    (config_reference.bearing_rows, ["type"] + [f.name for f in dataclasses.fields(BearingParams)]),
    (lambda: config_reference.bearing_rows("dcrb"),
     ["type"] + [f.name for f in dataclasses.fields(DcrbParams)]),
    (config_reference.defect_rows, list(DEFECT_PLACE) + [f.name for f in dataclasses.fields(Defect)]
     + ["angle_deg"]),
    (config_reference.wheel_defect_rows, list(WHEEL_DEFECT)),
    (config_reference.rig_rows, [f.name for f in dataclasses.fields(RigConfig)
                              if f.name not in RIG_SECTIONS]),
    (config_reference.sweep_rows, list(SWEEP_FIELDS)),
], ids=["bearing", "bearing_dcrb", "defects", "wheel_defects", "rig", "sweep"])
def test_free_form_tables_document_every_field_the_code_takes(rows, expected):
    got = rows()
    assert [r[0] for r in got] == expected
    for name, typ, default, unit, allowed, meaning in got:
        assert typ and default and allowed and meaning.strip(), name
        assert unit in UNITS, f"{name}: unit {unit!r}"
        if typ in ("float", "int") or typ.startswith("list of float"):
            assert unit, f"{name}: a number without a unit"


def test_free_form_defaults_and_ranges_are_the_dataclasses(page):
    for heading, cls in (("[bearing]", BearingParams), ('[bearing] type = "dcrb"', DcrbParams),
                         ("[rig]", RigConfig)):
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
    """angle_deg's range is derived from Defect.angle's; config._defects checks its own literal:
    the two must agree."""
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
    assert "generated from `axlebox.mbs.config.SCHEMA`" in md
    expected = [f"[{s}]" for s in SCHEMA] + ["[bearing]", '[bearing] type = "dcrb"', "[[defects]]",
                                             "[[wheel_defects]]",
                                             "[rig]", "[sweep]"]
    assert list(page) == expected


def test_page_defaults_and_ranges_are_the_schemas(page):
    for sec, fields in SCHEMA.items():
        assert list(page[f"[{sec}]"]) == list(fields)
        for key, (kind, default, *rng) in fields.items():
            row = page[f"[{sec}]"][key]
            assert toml_value(row[2]) == default, f"{sec}.{key}: default {row[2]}"
            if kind in (config.F, config.I):
                lo, hi = (tomllib.loads(f"x = {v}")["x"] for v in row[4].split(" … "))
                assert (lo, hi) == tuple(rng), f"{sec}.{key}: range {row[4]}"
            elif kind == config.S and rng[0] is not None:
                assert re.findall(r'`"([^"]*)"`', row[4]) == list(rng[0]), f"{sec}.{key}"
    # spot checks, as written in configs/vehicle.toml
    assert page["[run]"]["duration"][2] == "`5.0`"
    assert page["[track]"]["pad_k"][2] == "`6.5e7`"
    assert page["[track]"]["pad_k"][3] == "N/m"
    assert page["[run]"]["speed_kmh"][3] == "km/h"
    assert "Zhai et al. 2004" in page["[track]"]["pad_k"][5]


def test_a_bar_in_a_cell_is_escaped(monkeypatch):
    monkeypatch.setitem(FIELDS["run"], "duration", ("s", "a | b"))
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


def test_the_schemas_choices_are_the_codes():
    """Choice lists the schema spells out itself must be the ones the code acts on."""
    from axlebox.mbs import exchange, roughness
    from axlebox.mbs.config import SCHEMA
    from axlebox.mbs.wheelrail import element
    assert set(SCHEMA["coupling"]["hold"][2]) == set(exchange.HOLDS)
    assert set(SCHEMA["wheelrail"]["law"][2]) == set(element.LAWS)
    assert set(SCHEMA["wheelrail"]["fastsim_update"][2]) == set(element.UPDATES)
    assert set(SCHEMA["track"]["rail_roughness"][2]) == {"none", *roughness.RAIL_DB}
    assert set(SCHEMA["track"]["wheel_roughness"][2]) == {"none", *roughness.WHEEL_DB}


@pytest.mark.parametrize("name,words", [("carbody", "has no FE body"), ("gb2", "has no FE body"),
                                        ("ws9", "is not a body")])
def test_only_bodies_with_an_fe_body_can_be_flexible(name, words):
    """The carbody and gearboxes are always rigid: naming them flexible was silently ignored."""
    from axlebox._params import ParameterError
    from axlebox.mbs.config import validate
    with pytest.raises(ParameterError, match=rf"bodies.flexible = \['{name}'\] is not allowed: "
                                             rf"'{name}' {words}"):
        validate({"bodies": {"flexible": [name]}})
    assert validate({"bodies": {"flexible": ["frame2", "ws4", "ab3L"]}})["bodies"]["flexible"] == \
        ["frame2", "ws4", "ab3L"]
