"""``axlebox report FILE_OR_DIR --out DIR``: the paper's result figures for one run or a sweep,
a summary table (JSON and CSV) and one HTML page, which also shows mode-shape pictures when
there are any.

A *case* is one ``axlebox-result`` file; its speed and defect width come from the config stored in
it (``run.speed_kmh`` for the vehicle, ``rig.speed_kmh`` for the rig; the widest ``W`` among the
top-level ``defects``, 0 without).  A folder is searched for result files one level deep (a
sweep writes one file per case).  Each case is diagnosed exactly as ``axlebox diagnose`` does
(:func:`axlebox.pipelines.diagnose.analyse_file`), so the report and the command never disagree.

The page opens on what a maintainer acts on: each case's two sides, their verdicts in words and
as coloured badges, the fault's kind and size with its interval, who leads and by how much, the
reasons in a ``<details>`` (a phone has no hover); then the indicator, comfort, curving and
conclusions tables (each scrolled in its own box on a narrow screen), the captioned figures and
the mode shapes.

Figures (paper numbering): 9 time signals and 10 envelope spectra, one figure per speed with a
row per width; 11 RMS and SPM, 13 lag and 14 VF against speed; 12 time and frequency comparison
per speed at the widest defect.  Mode shapes: ``*_modeNN.png`` from ``axlebox bodies report``,
found under ``--modes DIR`` or beside the input, copied into ``DIR/modes``.
"""
from __future__ import annotations

import csv
import html
import json
import re
import shutil
from dataclasses import dataclass, field
from pathlib import Path

import h5py
import numpy as np

from axlebox._files import replaced, write_text
from axlebox._params import ParameterError
from axlebox._progress import Progress
from axlebox.bearing import resultfile
from axlebox.bearing.diagnostics.channel import jsonable
from axlebox.bearing.diagnostics.pair import PairResult
from axlebox.bearing.diagnostics.verdict import SIDES
from axlebox.mbs.post.comfort import RideComfort, floor_comfort, nmv_words, sperling_words

from . import conclusions, curving
from . import report_figures as figs
from axlebox.bearing.diagnostics.size import size_columns

from .diagnose import analyse_file
from .readers import TRACK_FADE_IN_S

SUMMARY_FIELDS = ("rms", "peak", "kurtosis", "crest", "spm_db", "spm_class", "FC", "VF")


@dataclass
class Case:
    """One result file: where it is, its case parameters and its diagnosis."""

    path: Path
    speed_kmh: float
    width_mm: float
    pair: PairResult | None             # None: the axle-box signals could not be diagnosed
    defect_side: str | None = None      # "left"/"right": the defective bearing's channel
    ride: list[RideComfort] = field(default_factory=list)   # carbody floor sensors (vehicle runs)
    speed_range: tuple | None = None    # (lowest, highest) km/h read, a run along a speed profile

    @property
    def label(self) -> str:
        w = "no defect" if self.width_mm == 0 else f"{self.width_mm:g} mm"
        v = (f"{self.speed_range[0]:.0f}-{self.speed_range[1]:.0f} km/h" if self.speed_range
             else f"{self.speed_kmh:g} km/h")
        return f"{v}, {w}"

    def row(self) -> dict:
        """The summary table's row: case, both sides' indicators, lag, VF difference, verdicts,
        the rule that decided and the evidence it read (columns ``verdict_*``,
        :meth:`axlebox.bearing.diagnostics.verdict.Verdict.row`)."""
        r = {"file": self.path.name, "speed_kmh": self.speed_kmh, "width_mm": self.width_mm}
        p = self.pair
        if p is not None:
            r.update(left=p.names[0], right=p.names[1])
            for side in ("left", "right"):
                c = getattr(p, side)
                r.update({f"{side}_{k}": getattr(c, k) for k in SUMMARY_FIELDS})
                r[f"{side}_lines"] = " ".join(c.detected)
                r[f"{side}_verdict"] = p.verdict.words[side]
                r.update(size_columns(p.sizes.get(side), f"{side}_"))
            lead = {"a": "left", "b": "right"}.get(p.lag.leading, "neither")
            r.update(lag_s=p.lag.lag_s, leading=lead, lag_correlation=p.lag.peak, vf_diff=p.vf_diff,
                     criterion_m=p.m, **p.verdict.row("verdict_"))
        for rc in self.ride:
            r.update({f"{rc.sensor}_{k}": getattr(rc, k) for k in ("W_z", "W_y", "N_MV")})
        return r

_NUMBER = re.compile(r"[-+]?(\d+\.?\d*|\.\d+)([eE][-+]?\d+)?")


def carbody_comfort(path) -> list[RideComfort]:
    """The comfort indices of a vehicle result's carbody floor sensors (``signals/carbody*``),
    from the irregularity's fade-in on, as ``axlebox simulate`` computes them; none for a rig's
    result or a run too short for them."""
    with resultfile.reading(path) as f:
        names = [n for n in f.get("signals", {}) if n.startswith("carbody")]
        if not names or "time" not in f:
            return []
        t = f["time"][()]
        acc = {n: f[f"signals/{n}/acceleration"][()] for n in names}
    return floor_comfort(t, acc, TRACK_FADE_IN_S)


def diagnosed_case(path, speed_kmh: float, width_mm: float, side: str | None, log=print, /,
                   **analyse_kw) -> Case:
    """The case of result file ``path``: its diagnosis as ``axlebox diagnose`` makes it
    (:func:`analyse_file` with ``analyse_kw``) and its carbody's ride comfort.  A record that
    cannot be diagnosed but has floor sensors (a comfort run's 1 kHz) is a case of its comfort
    alone (``pair`` None); one with neither raises the diagnosis' ParameterError.  The case's
    own arguments are positional only: ``analyse_kw`` may hold the diagnosis' ``speed_kmh``."""
    ride = carbody_comfort(path)
    try:
        _, _, pair = analyse_file(path, **analyse_kw)
    except ParameterError as err:
        if not ride:
            raise
        pair = None
        log(f"{Path(path).name}: axle-box signals not diagnosed ({err}); ride comfort only")
    return Case(Path(path), speed_kmh, width_mm, pair, side, ride)


#: windows of a run along a speed profile in the report: 5.5 shaft turns (two cage turns, the
#: shortest record the cage's line is resolved in, and a margin), three quarters overlapping
REPORT_TURNS, REPORT_OVERLAP = 5.5, 0.75


def _windows_figures(path, out: Path, log, **options) -> list[tuple[str, Path]]:
    """For a car run along a speed profile: its windows (:mod:`.windows`) as JSON Lines and the
    figure of the verdicts and the speed over time; nothing for other results."""
    from axlebox.mbs.vehicle.config import CarConfig

    from .readers import result_config
    from .windows import analyse_windows
    cfg = result_config(path)
    if not isinstance(cfg, CarConfig) or not cfg.speed_profile().accelerates:
        return []
    try:
        w = analyse_windows(path, REPORT_TURNS, REPORT_OVERLAP, **options)
    except ParameterError as err:
        log(f"report: {Path(path).name}: not read in windows ({err})")
        return []
    w.write(out / f"windows_{Path(path).stem}.jsonl")
    png = out / f"fig_windows_{Path(path).stem}.png"
    w.plot(png)
    s = w.summary
    agree = (f", left {s['words']['left']}, right {s['words']['right']} in {s['share']:.0%}"
             if s["words"] else "")
    log(f"report: {Path(path).name}: {s['read']} windows of {REPORT_TURNS:g} turns read{agree}")
    return [(f"Verdicts and speed over time, {Path(path).name}", png)]


def _speed_range(path) -> tuple[float, float] | None:
    """The lowest and highest speed (km/h) over the part read (from the track's fade-in) of a
    car run along a speed profile; None for a constant speed."""
    from axlebox.mbs.vehicle.config import CarConfig

    from .readers import result_config
    cfg = result_config(path)
    if not isinstance(cfg, CarConfig) or not cfg.speed_profile().accelerates:
        return None
    v = cfg.speed_profile().speed(np.linspace(TRACK_FADE_IN_S, cfg.run.duration, 200)) * 3.6
    return float(v.min()), float(v.max())


def case_parameters(path) -> tuple[float, float, str | None]:
    """``(speed_kmh, width_mm, defect_side)`` from the config stored in an axlebox-result file;
    the side is that ("left"/"right", from ``defects[].side`` L/R) of the widest defect when it
    is on wheelset 2, whose axle-boxes the default channels ws2_L / ws2_R read; None otherwise."""
    from axlebox.bearing.rig import RigConfig

    from .readers import result_config
    cfg = result_config(path)
    if cfg is None:
        raise ParameterError(f"{str(path)!r}: its config is neither a car's ([run] ...) nor a rig's "
                             "([rig]): expected the speed of the case")
    if isinstance(cfg, RigConfig):
        defects = sorted(cfg.defects, key=lambda d: d.W)
        return cfg.speed_kmh, 1e3 * defects[-1].W if defects else 0.0, None
    defects = sorted(cfg.defects, key=lambda d: d.defect.W)
    side = None
    if defects and defects[-1].wheelset == 2:     # the wheelset ws2_L / ws2_R sit on
        side = {"L": "left", "R": "right"}[defects[-1].side]
    return cfg.run.speed_kmh, 1e3 * defects[-1].defect.W if defects else 0.0, side


def _is_result(path: Path) -> bool:
    try:
        with h5py.File(path, "r") as f:
            return f.attrs.get("format") == resultfile.FORMAT
    except OSError:
        return False


def find_results(source) -> list[Path]:
    """The result files of ``source``: the file itself, or a folder's ``*.h5`` one level deep."""
    source = Path(source)
    if not source.exists():
        raise ParameterError(f"report input {str(source)!r} does not exist: expected a result "
                             "file or a folder of them")
    if source.is_file():
        return [source]
    files = sorted(p for p in (*source.glob("*.h5"), *source.glob("*/*.h5")) if _is_result(p))
    if not files:
        raise ParameterError(f"report input {str(source)!r} holds no axlebox-result files "
                             "(*.h5, one level deep)")
    return files


def mode_pictures(source, modes_dir=None) -> list[Path]:
    """Mode-shape PNGs (``*_modeNN.png``) under ``modes_dir``, else beside ``source``."""
    roots = [Path(modes_dir)] if modes_dir else [Path(source) if Path(source).is_dir()
                                                 else Path(source).parent]
    if modes_dir and not roots[0].is_dir():
        raise ParameterError(f"--modes {str(modes_dir)!r} is not a folder: expected the output of "
                             "axlebox bodies report")
    found = []
    for r in roots:
        for pattern in ("*_mode[0-9][0-9].png", "*/*_mode[0-9][0-9].png", "*/*/*_mode[0-9][0-9].png"):
            found += r.glob(pattern)
    return sorted(set(found))


def write_csv(path: Path, rows: list[dict]) -> Path:
    """``rows`` as CSV through a temporary name, a column for every key of any row (rig cases
    have no comfort columns); None and a missing key are written empty."""
    keys = list(dict.fromkeys(k for r in rows for k in r))
    with replaced(path) as tmp, tmp.open("w", newline="") as fh:
        w = csv.DictWriter(fh, fieldnames=keys)
        w.writeheader()
        w.writerows(rows)
    return path


def write_tables(cases: list[Case], out: Path) -> tuple[Path, Path]:
    rows = [jsonable(c.row()) for c in cases]
    j = write_text(out / "summary.json", json.dumps(
        {"cases": rows, "diagnoses": [jsonable(c.pair.to_dict()) for c in cases if c.pair]}, indent=1))
    return j, write_csv(out / "summary.csv", rows)


def _table_html(cases: list[Case]) -> str:
    head = ["case", "side", "sensor", "RMS m/s&sup2;", "peak m/s&sup2;", "kurtosis", "SPM dB",
            "FC Hz", "VF Hz&sup2;", "lines", "verdict", "defect width", "lag ms", "&Delta;VF Hz&sup2;"]
    # id: a stable handle on the verdict table for links and tests/test_report_browser.py
    out = ["<table id='verdicts'><tr>" + "".join(f"<th>{h}</th>" for h in head) + "</tr>"]
    for c in cases:
        p = c.pair
        for i, side in enumerate(("left", "right")):
            s = getattr(p, side)
            verdict, why = p.verdict.words[side], p.verdict.sentence(side)
            cells = [f"{s.rms:.4g}", f"{s.peak:.4g}", f"{s.kurtosis:.3g}",
                     f"{s.spm_db:.1f} ({s.spm_class})", f"{s.FC:.0f}", f"{s.VF:.3g}",
                     html.escape(" ".join(s.detected) or "none"),
                     f"<span title='{html.escape(why)}'>{html.escape(verdict)}</span>",
                     _size_cell(p.sizes.get(side))]
            first = (f"<td rowspan=2>{html.escape(c.label)}</td>" if i == 0 else "")
            tail = (f"<td rowspan=2 class=num>{1e3 * p.lag.lag_s:.2f}</td>"
                    f"<td rowspan=2 class=num>{p.vf_diff:.3g}</td>"
                    if i == 0 else "")
            out.append(f"<tr>{first}<td>{side}</td><td>{html.escape(p.names[i])}</td>"
                       + "".join(_td(v) for v in cells) + tail + "</tr>")
    out.append("</table>")
    return "\n".join(out)


def _size_cell(r) -> str:
    if r is None or r.status == "not read":
        return "&ndash;"
    return f"<span title='{html.escape(r.reason)}'>{html.escape(r.text())}</span>"


def _td(v: str) -> str:
    """A table cell, right-aligned where it holds a number (a trailing "(words)" allowed)."""
    num = _NUMBER.fullmatch(v.split(" (")[0]) is not None
    return f"<td class=num>{v}</td>" if num else f"<td>{v}</td>"


def _comfort_html(cases: list[Case]) -> str:
    head = ["case", "sensor", "W_z", "W_y", "N_MV", "a_XP95, a_YP95, a_ZP95 m/s&sup2;", "record"]
    out = ["<table><tr>" + "".join(f"<th>{h}</th>" for h in head) + "</tr>"]
    for c in cases:
        for r in c.ride:
            cells = [html.escape(c.label), html.escape(r.sensor),
                     f"{r.W_z:.2f} ({sperling_words(r.W_z)})", f"{r.W_y:.2f} ({sperling_words(r.W_y)})",
                     f"{r.N_MV:.2f} ({nmv_words(r.N_MV)})", ", ".join(f"{v:.3g}" for v in r.a_P95),
                     f"{r.duration_s:.3g} s, {r.windows} window(s)"]
            out.append("<tr>" + "".join(_td(v) for v in cells) + "</tr>")
    out.append("</table>")
    return "\n".join(out)


#: what each figure shows, by its file name's start: the caption under it on the page
CAPTIONS = {
    "fig09": "Both axle boxes' accelerations over the record, a row per defect width: the defect "
             "side's impacts and their weaker copy on the healthy side (the paper's Fig. 9).",
    "fig10": "Envelope spectra of both sides with the bearing's fault lines marked; a line on "
             "the healthy side at the defect side's BPFO is the coaxial pseudo-fault (Fig. 10).",
    "fig11": "RMS and SPM shock value of both sides against speed, a line per defect width "
             "(Fig. 11).",
    "fig12": "Time and frequency comparison of the two sides at the widest defect (Fig. 12).",
    "fig13": "How far the healthy side's impulses trail the defect side's, against speed "
             "(Fig. 13).",
    "fig14": "Both sides' VF (the spectra's dispersion) against speed; their difference is the "
             "paper's criterion (Fig. 14).",
    "fig_comfort_spectra": "The carbody floor's weighted acceleration spectra (EN 12299).",
    "fig_comfort_speed": "Sperling's W_z, W_y and EN 12299's N_MV against speed.",
    "fig_windows": "Each window's verdicts beside the speed, along a run whose speed changes.",
    "curving": "Y, Q, Y/Q, the sum of Y, the lateral displacement and the angle of attack along "
               "the line (EN 14363).",
}

#: the verdict's colour class: a fault red, a copy amber, healthy green, no word grey
_TONE = {"real fault": "fault", "faults on both sides": "fault", "pseudo-fault": "copy",
         "healthy": "ok", "undecided": "none"}

_STYLE = (
    "body{font-family:system-ui,sans-serif;margin:1.5em auto;max-width:1300px;padding:0 1em;"
    "color:#222;line-height:1.4}h2{margin-top:1.6em;border-bottom:1px solid #ddd}"
    # tables: a tinted header, banded rows, and scrolled in their own box on a narrow screen
    ".scroll{overflow-x:auto;max-width:100%}"
    "table{border-collapse:collapse;font-size:90%;margin:.5em 0}td,th{border:1px solid #d6d6d6;"
    "padding:4px 8px;text-align:left;vertical-align:top}th{background:#eef1f5}"
    "tr:nth-child(even) td{background:#fafbfc}"
    # numbers line up on the right; words and sentences read from the left
    "td.num{text-align:right;white-space:nowrap}"
    ".cards{display:flex;flex-wrap:wrap;gap:1em}.case{border:1px solid #ccc;border-radius:6px;"
    "padding:.6em 1em;flex:1 1 22em;max-width:40em}.case h3{margin:.2em 0 .5em}"
    ".side{margin:.35em 0}.badge{display:inline-block;padding:1px 8px;border-radius:10px;"
    "font-weight:bold;color:#fff;margin-right:.4em}.fault .badge{background:#c62828}"
    ".copy .badge{background:#e08a00}.ok .badge{background:#2e7d32}.none .badge{background:#757575}"
    "details{margin:.4em 0;font-size:90%}details p{margin:.3em 0}"
    "figure{margin:1em 0}figcaption{font-size:90%;color:#444;margin-top:.3em}"
    "img{max-width:100%;height:auto}.modes{display:flex;flex-wrap:wrap;gap:.5em}"
    ".modes img{width:380px}")


def _caption(path: Path) -> str:
    stem = path.stem
    key = max((k for k in CAPTIONS if stem.startswith(k)), key=len, default=None)
    return CAPTIONS.get(key, "")


def _mode_caption(path: Path) -> str:
    """``wheelset_mode07.png`` -> ``wheelset, mode 7`` (the name ``axlebox bodies report`` gives)."""
    m = re.fullmatch(r"(.+)_mode0*(\d+)", path.stem)
    return f"{m[1].replace('_', ' ')}, mode {m[2]}" if m else path.stem.replace("_", " ")


def _side_words(c: Case, side: str) -> str:
    """One side in words: its verdict, the fault's kind and size with its interval."""
    p = c.pair
    esc = html.escape
    word = p.verdict.words[side]
    out = [f"<span class='badge'>{esc(word)}</span><b>{side}</b> ({esc(p.names[SIDES.index(side)])})"]
    kind = p.verdict.kinds.get(side)
    if kind is not None:
        out.append(esc(kind.kind if kind.decided else "kind undecided: " + " or ".join(kind.named)))
    size = p.sizes.get(side)
    if size is not None and size.status != "not read":
        out.append("size: " + esc(size.text()))
    if word == "pseudo-fault":
        out.append("the other side's fault carried through the axle, not this bearing's")
    if c.defect_side == side:
        out.append("<i>the simulated defect's side</i>")
    return f"<div class='side {_TONE.get(word, 'none')}'>" + " &middot; ".join(out) + "</div>"


def _summary_html(cases: list[Case]) -> str:
    """What a maintainer acts on, first: per case each side's verdict with the fault's kind and
    size, and who leads; the reasons one click away (``<details>``: readable on a phone, where
    a hover title is not)."""
    esc = html.escape
    cards = []
    for c in cases:
        p = c.pair
        why = "".join(f"<p><b>{side}</b>: {esc(p.verdict.sentence(side))}</p>"
                      for side in ("left", "right"))
        warn = "".join(f"<p>{esc(w)}</p>" for w in p.warnings)
        cards.append(f"<div class='case'><h3>{esc(c.label)}</h3>"
                     + _side_words(c, "left") + _side_words(c, "right")
                     + f"<p>{esc(p.lag.sentence(p.names))}.</p>{warn}"
                     f"<details><summary>why these verdicts</summary>{why}</details></div>")
    return "<section id='summary'><h2>Verdicts</h2><div class='cards'>" + "".join(cards) + \
        "</div></section>"


def _scroll(table: str) -> str:
    return f"<div class='scroll'>{table}</div>"


def write_html(cases, figures: list[tuple[str, Path]], modes: list[Path], out: Path,
               claims=(), curves=()) -> Path:
    esc = html.escape
    diagnosed = [c for c in cases if c.pair is not None]
    criterion = ""
    if diagnosed:
        crit = diagnosed[0].pair.criterion
        criterion = (f"Criterion: {esc(crit.mode)}, range [{crit.range[0]:.4g}, {crit.range[1]:.4g}] "
                     f"{esc(crit.unit)}, FC and VF over {esc(crit.band_text)}, "
                     f"compared {esc(', '.join(crit.compare))}. ")
    parts = ["<!doctype html><html lang='en'><head><meta charset='utf-8'>",
             "<meta name='viewport' content='width=device-width, initial-scale=1'>",
             f"<title>axlebox report</title><style>{_STYLE}</style>",
             "</head><body><h1>Coaxial pseudo-fault report</h1>",
             _summary_html(diagnosed) if diagnosed else "",
             "<h2>Indicators and verdicts</h2>",
             f"<p>{len(cases)} case(s), {len(diagnosed)} with axle-box diagnoses. {criterion}"
             "A verdict's reason is under &ldquo;why these verdicts&rdquo; above. "
             "Tables: <a href='summary.csv'>summary.csv</a>, <a href='summary.json'>summary.json"
             "</a>.</p>", _scroll(_table_html(diagnosed)) if diagnosed else ""]
    if any(c.ride for c in cases):
        parts += ["<h2>Ride comfort of the carbody</h2>",
                  "<p>Sperling's ride index (W_z vertical, W_y lateral) and EN 12299's mean comfort "
                  "N_MV (standard method: W_d on x and y, W_b on z, 95th percentile of 5 s r.m.s.) "
                  "of each floor sensor after the irregularity's fade-in. The standard evaluates "
                  "5 min; a shorter record's N_MV is an indication.</p>", _scroll(_comfort_html(cases))]
    if curves:
        parts += ["<h2>Curving</h2>",
                  "<p>Each run on a line: its wheels' Y and Q, Y/Q against Nadal's flange-climb "
                  "limit, each wheelset's sum Y against Prud'homme's, lateral displacement and "
                  "angle of attack, and each bearing's rows (EN 14363; the plot along the line is "
                  "among the figures).</p>"]
        parts += [f"<h3>{esc(name)}</h3>{_scroll(body)}" for name, body in curves]
    if claims:
        parts += ["<h2>The paper's conclusions beside ours</h2>",
                  "<p>Each claim of the paper's conclusions (1)-(3) and of its Fig. 11, checked "
                  "on these cases (<a href='conclusions.csv'>conclusions.csv</a>); &ldquo;no "
                  "case&rdquo; where these cases cannot judge a claim (a trend needs a sweep).</p>",
                  _scroll(conclusions.table_html(claims))]
    if figures:
        parts.append("<h2>Figures</h2>")
    for title, path in figures:
        cap = _caption(path)
        parts.append(f"<figure><img src='{esc(path.name)}' alt='{esc(title)}'><figcaption><b>"
                     f"{esc(title)}.</b> {esc(cap)}</figcaption></figure>")
    if modes:
        parts.append("<h2>Mode shapes</h2><div class='modes'>")
        parts += [f"<figure><img src='modes/{esc(m.name)}' alt='{esc(m.stem)}'><figcaption>"
                  f"{esc(_mode_caption(m))}</figcaption></figure>" for m in modes]
        parts.append("</div>")
    parts.append("</body></html>")
    return write_text(out / "index.html", "\n".join(parts))


def report(source, out_dir, *, left=None, right=None, modes_dir=None, log=print,
           **diagnose_kw) -> Path:
    """Diagnose every case of ``source`` and write figures, tables and ``index.html`` into
    ``out_dir``; ``diagnose_kw`` go to :func:`axlebox.pipelines.diagnose.analyse_file` (shaft speed,
    bearing, criterion, band ...).  Returns the page's path."""
    files = find_results(source)
    out = Path(out_dir)
    out.mkdir(parents=True, exist_ok=True)
    cases = []
    pace = Progress("report", len(files), "case")
    for k, path in enumerate(files, 1):
        speed, width, side = case_parameters(path)
        if left is not None or right is not None:
            side = None                     # other channels than the default ws2_L / ws2_R
        cases.append(diagnosed_case(path, speed, width, side, lambda m: log(f"report: {m}"),
                                    left=left, right=right, **diagnose_kw))
        cases[-1].speed_range = _speed_range(path)
        pair = cases[-1].pair
        if pair is not None:
            log(f"report: [{k}/{len(files)}] {path.name}: {cases[-1].label}: left "
                f"{pair.verdict.words['left']}, right {pair.verdict.words['right']} "
                f"({pair.verdict.rule}{pace.aside(k)})")
    cases.sort(key=lambda c: (c.speed_kmh, c.width_mm))
    all_cases, cases = cases, [c for c in cases if c.pair is not None]
    figures = []
    for v in sorted({c.speed_kmh for c in cases}):
        at = [c for c in cases if c.speed_kmh == v]
        tag = f"{v:g}kmh"
        figures.append((f"Fig. 9 - time signals, {v:g} km/h",
                        figs.time_signals(at, out / f"fig09_time_{tag}.png")))
        figures.append((f"Fig. 10 - envelope spectra, {v:g} km/h",
                        figs.envelope_spectra(at, out / f"fig10_envelope_{tag}.png")))
        figures.append((f"Fig. 12 - time and frequency comparison, {at[-1].label}",
                        figs.comparison(at[-1], out / f"fig12_comparison_{tag}.png")))
    if cases:
        figures.append(("Fig. 11 - RMS and SPM", figs.indicators(cases, out / "fig11_rms_spm.png")))
        if any(c.width_mm > 0 for c in cases):
            figures.append(("Fig. 13 - lag", figs.lags(cases, out / "fig13_lag.png")))
        figures.append(("Fig. 14 - VF", figs.vf(cases, out / "fig14_vf.png")))
    if any(c.ride for c in all_cases):
        figures.append(("Ride comfort - weighted floor spectra",
                        figs.comfort_spectra(all_cases, out / "fig_comfort_spectra.png")))
        figures.append(("Ride comfort - W_z, W_y and N_MV against speed",
                        figs.comfort_indices(all_cases, out / "fig_comfort_speed.png")))
    for path in files:                  # runs along a speed profile: read window by window too
        figures += _windows_figures(path, out, log, left=left, right=right, **diagnose_kw)
    curves = []
    for path in files:                  # runs on a line: the curving table and the plot along it
        rec = curving.read(path)
        if (fig := curving.figure(rec, out / f"curving_{path.stem}.png")) is not None:
            curves.append((path.name, curving.table_html(curving.table(rec))))
            figures.append((f"Curving along the line - {path.name}", fig))
    figures.sort(key=lambda t: t[1].name)
    pictures = mode_pictures(source, modes_dir)
    if pictures:
        (out / "modes").mkdir(exist_ok=True)
        for p in pictures:
            shutil.copy2(p, out / "modes" / p.name)
    write_tables(all_cases, out)
    claims = conclusions.claims(cases) if any(c.defect_side for c in cases) else []
    if claims:
        write_csv(out / "conclusions.csv", conclusions.as_rows(claims))
    page = write_html(all_cases, figures, pictures, out, claims, curves)
    log(f"report: {len(all_cases)} case(s), {len(figures)} figures, {len(pictures)} mode pictures "
        f"-> {page}")
    return page
