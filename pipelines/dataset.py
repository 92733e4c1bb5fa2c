"""``axlebox dataset SWEEP_DIR --out DATA``: a vehicle sweep's results as a labelled dataset of
windows of the two axle-box signals, for training and testing diagnosis methods.

Each result ``SWEEP_DIR/*.h5`` (``axlebox sweep`` or ``axlebox simulate`` of a vehicle) gives
the vertical acceleration (column 2) of the two axle boxes of its defect's wheelset (the first
``[[defects]]`` entry's, else wheelset 2), after the track's fade-in, cut into windows of
``window_s`` every ``hop_s``.  Each window carries its case's labels: speed, each side's defect
(kind, W, L, H, row; "none" without one), which side is real ("left", "right", "both" or
"none"), and the verdict the criterion gives on the whole record (:func:`.diagnose.analyse_file`):
each side's word and reason, the rule that decided and the evidence it read
(:meth:`axlebox.bearing.diagnostics.verdict.Verdict.row`, columns ``verdict_*``) and each side's
defect size as read (:func:`axlebox.bearing.diagnostics.size.size_columns`, ``left_size``,
``left_width_mm`` ...), with where it came from (file, first sample's index in the file's arrays).

Format: one NetCDF-4 file (HDF5 underneath, written by xarray through h5netcdf), because the
windows are a dense (window x sample) array per side and the labels are per-window coordinates:
``xarray.open_dataset(DATA / "dataset.nc")`` loads signals and labels together, and
``.drop_dims("sample").to_dataframe()`` gives the label table as pandas; float64 samples stay
bit-identical (Parquet would store each window as a list cell, and pandas would hold it as
objects).  Written to a temporary name and renamed when complete, with a dataset card
(``DATA/README.md``) that states how it was made.
"""
from __future__ import annotations

import datetime
import json
import math
import os
import platform
from pathlib import Path

import numpy as np

from axlebox._files import h5_bound, h5_reserved, write_text
from axlebox._params import ParameterError
from axlebox._progress import Progress
from axlebox.bearing import resultfile

from .readers import TRACK_FADE_IN_S

COLUMN = 2                        # vertical acceleration
DEFECT_FIELDS = ("kind", "W", "L", "H", "row")
SIDES = {"left": "L", "right": "R"}


def _positive(value, option: str) -> float:
    if isinstance(value, bool) or not isinstance(value, (int, float)) or not math.isfinite(value) \
            or not value > 0:
        raise ParameterError(f"{option} = {value!r} is not allowed: expected a time > 0 s")
    return float(value)


def results(folder) -> list[Path]:
    """The finished result files of a sweep folder (checkpoints and temporary files left out)."""
    folder = Path(folder)
    if not folder.is_dir():
        raise ParameterError(f"SWEEP_DIR {str(folder)!r} is not a folder: expected the --out folder "
                             "of axlebox sweep")
    files = sorted(p for p in folder.glob("*.h5")
                   if not p.name.endswith((".partial.h5", ".stream.h5")))
    if not files:
        raise ParameterError(f"SWEEP_DIR {str(folder)!r} holds no result file (*.h5): expected the "
                             "--out folder of a vehicle sweep")
    return files


def case_labels(path: Path) -> tuple[dict, object]:
    """``(labels, config)`` of one vehicle result: speed, wheelset, each side's defect, the real
    side, from its stored config read as the run read it (:func:`.readers.result_config`)."""
    from axlebox.bearing.rig import RigConfig

    from .readers import result_config
    try:
        with resultfile.reading(path) as f:
            status = f.attrs.get("status", "done")
        cfg = result_config(path)
    except (OSError, ValueError) as err:
        if isinstance(err, ParameterError):
            raise
        raise ParameterError(f"{path.name} is not an axlebox result file: {err}") from None
    if isinstance(cfg, RigConfig):
        raise ParameterError(f"{path.name} is a bearing-rig result (one sensor): a dataset needs the "
                             "two axle boxes of a vehicle sweep")
    if cfg is None:
        raise ParameterError(f"{path.name} holds no vehicle config: a dataset needs the results of "
                             "a vehicle sweep")
    if status != "done":
        raise ParameterError(f"{path.name} is an unfinished run (status {status!r}): finish the sweep "
                             "first (a rerun of axlebox sweep resumes it)")
    defects = cfg.defects
    ws = defects[0].wheelset if defects else 2
    lab = {"speed_kmh": cfg.run.speed_kmh, "wheelset": ws}
    for s, letter in SIDES.items():
        here = [d for d in defects if d.wheelset == ws and d.side == letter]
        d = here[0].defect if here else None
        lab[f"{s}_kind"] = d.kind if d else "none"
        lab[f"{s}_n_defects"] = len(here)
        for k in ("W", "L", "H"):
            lab[f"{s}_{k}"] = float(getattr(d, k)) if d else 0.0
        lab[f"{s}_row"] = int(d.row) if d else 0
    real = [s for s in SIDES if lab[f"{s}_kind"] != "none"]
    lab["real_side"] = {0: "none", 1: real[0] if real else "none", 2: "both"}[len(real)]
    return lab, cfg


def windows(path: Path, sensors: tuple[str, str], window_s: float, hop_s: float):
    """``(fs, starts, left, right)``: window starts (index into the file's arrays) and the
    (window x sample) arrays, taken from the vertical column after the track's fade-in."""
    with resultfile.reading(path) as f:
        x = []
        for n in sensors:
            if f"signals/{n}/acceleration" not in f:
                raise ParameterError(f"{path.name} has no sensor {n!r}: expected signals/{n}/acceleration")
            x.append(np.asarray(f[f"signals/{n}/acceleration"][:, COLUMN], dtype=float))
        fs = float(f[f"signals/{sensors[0]}/acceleration"].attrs["fs_hz"])
    n = int(round(window_s * fs))
    hop = max(1, int(round(hop_s * fs)))
    i0 = int(round(TRACK_FADE_IN_S * fs))
    if i0 + n > x[0].size:
        raise ParameterError(f"--window {window_s:g} s is not allowed: {path.name} holds "
                             f"{(x[0].size - i0) / fs:.4g} s after the fade-in")
    starts = np.arange(i0, x[0].size - n + 1, hop, dtype=np.int64)
    idx = starts[:, None] + np.arange(n)
    return fs, starts, x[0][idx], x[1][idx]


def build(sweep_dir, *, window_s: float = 0.5, hop_s: float = 0.25, criterion=None, log=print,
          **speed_kw):
    """The dataset as an ``xarray.Dataset`` (module docstring); ``speed_kw``: the speed's source
    and order tracking, as ``axlebox diagnose`` takes them (:func:`.diagnose.analyse_file`;
    default: each result's stored shaft angle)."""
    import xarray as xr

    from axlebox.bearing.diagnostics.criterion import Criterion
    from axlebox.bearing.diagnostics.size import size_columns

    from .diagnose import analyse_file
    window_s, hop_s = _positive(window_s, "--window"), _positive(hop_s, "--hop")
    criterion = Criterion(mode="relative") if criterion is None else criterion
    files = results(sweep_dir)
    rows, left, right, fs_all = [], [], [], set()
    pace = Progress("dataset", len(files), "record")
    for k, path in enumerate(files, 1):
        lab, _ = case_labels(path)
        sensors = (f"ws{lab['wheelset']}_L", f"ws{lab['wheelset']}_R")
        fs, starts, xl, xr_ = windows(path, sensors, window_s, hop_s)
        fs_all.add(fs)
        _, info, pair = analyse_file(path, left=sensors[0], right=sensors[1], criterion=criterion,
                                     **{k: v for k, v in speed_kw.items() if v is not None})
        v = pair.verdict
        lab = {**lab, "case": path.stem, "file": path.name,
               "left_verdict": v.words["left"], "right_verdict": v.words["right"],
               "left_reason": v.sentence("left"), "right_reason": v.sentence("right"),
               "speed_from": (info["speed"] or {}).get("from", "config"),
               "order_tracked": bool((info["speed"] or {}).get("order_tracked", False)),
               **v.row("verdict_"),
               **{k: val for s in SIDES for k, val in size_columns(pair.sizes.get(s), f"{s}_").items()}}
        for i in starts:
            rows.append({**lab, "start_index": int(i), "t_start": float(i / fs)})
        left.append(xl)
        right.append(xr_)
        log(f"dataset: [{k}/{len(files)}] {path.name}: {starts.size} windows, real side "
            f"{lab['real_side']}, verdicts {lab['left_verdict']} / {lab['right_verdict']}{pace.aside(k)}")
    if len(fs_all) > 1:
        raise ParameterError(f"SWEEP_DIR holds results sampled at {sorted(fs_all)} Hz: expected one "
                             "sampling rate (windows of one length)")
    fs = fs_all.pop()
    left, right = np.concatenate(left), np.concatenate(right)
    n = left.shape[1]
    coords = {"window": np.arange(left.shape[0]), "t": ("sample", np.arange(n) / fs)}
    for k in rows[0]:
        coords[k] = ("window", np.array([r[k] for r in rows]))
    ds = xr.Dataset({"left": (("window", "sample"), left), "right": (("window", "sample"), right)},
                    coords=coords)
    ds["left"].attrs.update(units="m s-2", long_name="vertical acceleration, left axle box")
    ds["right"].attrs.update(units="m s-2", long_name="vertical acceleration, right axle box")
    ds["t"].attrs["units"] = "s"
    ds["t_start"].attrs["units"] = "s"
    for s in SIDES:
        for k in ("W", "L", "H"):
            ds[f"{s}_{k}"].attrs["units"] = "m"
    ds.attrs.update(fs_hz=fs, window_s=n / fs, hop_s=hop_s, column=COLUMN,
                    fade_in_s=TRACK_FADE_IN_S, criterion=json.dumps(criterion.to_dict()),
                    source=str(Path(sweep_dir).resolve()), n_cases=len(files),
                    made_by="axlebox dataset", conventions="CF-1.8")
    return ds


CARD = """# axlebox dataset

Made by `axlebox dataset {src} --out {out} --window {window:g} --hop {hop:g}` on {date}
({machine}): {n_win} windows of {window:g} s ({n} samples at {fs:g} Hz) every {hop:g} s, from
{n_cases} simulated cases of a vehicle sweep (`axlebox sweep`, the coupled bearing-vehicle-track
model: the B-type metro car with eight double-row tapered roller bearings, 6-DOF rollers and cages).

## Load

```python
import xarray as xr
# signals and labels
ds = xr.open_dataset("{out}/dataset.nc")
# the labels, one row per window, as a pandas DataFrame
labels = ds.drop_dims("sample").to_dataframe()
```

## Content

- `left`, `right` (window, sample): vertical acceleration (m/s^2) of the left and right axle box
  of the defect's wheelset (the first `[[defects]]` entry's, else wheelset 2), through the
  sensor model the case's config names, taken from column {column} of
  `signals/ws<k>_<L|R>/acceleration` in `file`, from sample `start_index` on: each window equals
  the source array's slice exactly (float64, no filtering, no rescaling). The first {fade:g} s of
  every run (the track irregularity fading in) are left out.
- labels per window (coordinates on `window`): `case`, `file`, `start_index`, `t_start` (s),
  `speed_kmh`, `wheelset`; per side (`left_*`, `right_*`): `kind` (outer, inner, roller or none),
  `W`, `L`, `H` (m; 0 without a defect), `row` (1 inboard, 2 outboard; 0 without), `n_defects`;
  `real_side` (left, right, both or none: where the simulation put defects); `left_verdict`,
  `right_verdict` with `*_reason`: what the criterion (`axlebox diagnose`, {mode} mode) says
  on the whole record of the case (real fault, pseudo-fault, healthy, faults on both sides or
  undecided): a baseline to compare a method with, not ground truth; `verdict_rule` (the rule
  that decided), `verdict_real` (the side it named real, or none) and the evidence it read,
  `verdict_*`: the VF difference against the range (`verdict_vf_m`, `_lo`, `_hi`, `_where`),
  each side's compared indicators, the lag (`verdict_lag_leading`, `verdict_lag_s`), each
  fault line seen and how its source was found (`verdict_lines`), the whole orders of the
  wheel's rate on each side (`verdict_orders_left`, `_right`), the blanking of a wheel flat's
  strikes (`verdict_gate_*`, NaN without), the fault's kind named on each side called faulty
  (`verdict_kind_left`, `_right`: outer ring, inner ring, roller, "kind undecided" or none;
  `verdict_kinds_*` every kind that fits); where the speed came from (`speed_from`) and whether
  the record was read on the shaft's clock (`order_tracked`); per side the defect's size the
  diagnosis reads from the rollers' entry and exit events (`left_size`: sized, bridged, below
  resolution or not read; `left_width_mm` with its interval `left_width_lo_mm`,
  `left_width_hi_mm`, NaN where none; `left_events_ms`, the events' separation): an estimate to
  compare with the true `left_W`.  The criterion with every threshold is the file's `criterion`
  attribute (JSON).

## Cases

| case | km/h | left | right | real side | verdicts (left / right) | rule | width read (L / R) | windows |
| --- | --- | --- | --- | --- | --- | --- | --- | --- |
{table}

## How it was made, and what it is not

Every number is a prediction of the model (README of axlebox: which parameters are calibrated,
on what); the contact damping is the one calibrated parameter set. Windows of one case overlap
when the hop is shorter than the window and are not independent samples: split training and
test data by case, not by window. The sweep's own configs are in the result files (`config`
attribute), with the seed of each run.
"""


def write(sweep_dir, out, *, window_s: float = 0.5, hop_s: float = 0.25, criterion=None,
          log=print, **speed_kw) -> Path:
    """Build the dataset and write ``out/dataset.nc`` and ``out/README.md`` (temporary names,
    renamed when complete; ``speed_kw`` as :func:`build` takes them).  Returns the path of the
    NetCDF file."""
    from axlebox.bearing.diagnostics.criterion import Criterion
    out = Path(out)
    if out.exists() and not out.is_dir():
        raise ParameterError(f"--out {str(out)!r} is a file: expected a folder for the dataset")
    criterion = Criterion(mode="relative") if criterion is None else criterion
    ds = build(sweep_dir, window_s=window_s, hop_s=hop_s, criterion=criterion, log=log, **speed_kw)
    out.mkdir(parents=True, exist_ok=True)
    path = out / "dataset.nc"
    with h5_reserved(path, h5_bound(v.values for v in ds.variables.values())) as fo:
        ds.to_netcdf(fo, engine="h5netcdf")
    lab = ds.drop_dims("sample").to_dataframe()
    table = []
    for case, g in lab.groupby("case", sort=True):
        r = g.iloc[0]
        side = {s: (f"{r[f'{s}_kind']} {1e3 * r[f'{s}_W']:g} mm row {r[f'{s}_row']}"
                    if r[f"{s}_kind"] != "none" else "none") for s in SIDES}
        read = {s: (f"{r[f'{s}_width_mm']:.2f} mm ({r[f'{s}_width_lo_mm']:.2f}-"
                    f"{r[f'{s}_width_hi_mm']:.2f})" if r[f"{s}_size"] == "sized" else r[f"{s}_size"])
                for s in SIDES}
        table.append(f"| {case} | {r['speed_kmh']:g} | {side['left']} | {side['right']} | "
                     f"{r['real_side']} | {r['left_verdict']} / {r['right_verdict']} | "
                     f"{r['verdict_rule']} | {read['left']} / {read['right']} | {len(g)} |")
    card = CARD.format(src=sweep_dir, out=out, window=ds.attrs["window_s"], hop=hop_s,
                       date=datetime.date.today().isoformat(),
                       machine=f"{platform.machine()}, {os.cpu_count()} cores",
                       n_win=ds.sizes["window"], n=ds.sizes["sample"], fs=ds.attrs["fs_hz"],
                       n_cases=ds.attrs["n_cases"], column=COLUMN, fade=TRACK_FADE_IN_S,
                       mode=criterion.mode, table="\n".join(table))
    write_text(out / "README.md", card)
    log(f"dataset: wrote {path} ({ds.sizes['window']} windows of {ds.sizes['sample']} samples) "
        f"and {out / 'README.md'}")
    return path
