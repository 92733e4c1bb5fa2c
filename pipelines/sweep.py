"""``axlebox sweep CONFIG.toml --out DIR``: speeds x defect widths (x defect kinds x sides) of the
bearing rig (a config with ``[rig]``) or the vehicle (``[run]`` ..., as ``configs/vehicle.toml``),
one case per dask.distributed task on a local cluster (``--workers`` processes, never more than
the cases or the cores, the cores shared out as their numba threads) or the scheduler at
``--scheduler`` (its workers must see DIR).

Lists from the options, else ``[sweep] speeds_kmh``/``widths_mm``/``kinds``/``sides``/
``wheel_defects``, else the config's own speed and defects; width 0 removes the ``[[defects]]``
(one case per speed, whatever the kinds and sides), > 0 sets their ``W`` (m); a kind (``outer``,
``inner``, ``roller``) sets every defect's ``kind``; a side (vehicle only) puts every defect on
``L`` or ``R``, or ``LR`` on both (each entry once per side: faults on both sides of its
wheelset); a wheel defect name (vehicle only) keeps the ``[[wheel_defects]]`` entries of that
``name``, ``none`` none of them (configs/confounders.toml).  Each case writes
``DIR/v48_w2.h5`` (``.`` -> ``p``; ``DIR/v48_w2_inner_LR.h5`` when kinds and sides are swept)
with its own config inside, through a temporary name; a rerun
skips files that open as a result of the same config and removes ``*.tmp`` left by a killed run
(the checkpoints ``*.partial.h5`` and streamed outputs ``*.stream.d`` are kept: a killed case
resumes from its last checkpoint).

What survives what: the sweep holds ``DIR/.sweep.lock`` (a second sweep on DIR is refused, naming
the first); each case's runner holds ``DIR/.<case>.lock`` while it computes, so a case dask reruns
after losing its worker (a kill, a lost connection) is never written by two runners at once; a
worker's death reruns its case elsewhere (dask gives up after 3 deaths: the case is reported
failed); a full disk fails the case before it writes anything (``DiskFullError``), the others
go on.  The summary per case and side goes to ``DIR/summary.csv``: two-sensor (vehicle) results
through :mod:`axlebox.pipelines.report`, the rig's one sensor through
:func:`axlebox.bearing.diagnostics.channel.analyse`.
"""
from __future__ import annotations

import contextlib
import dataclasses
import io
import logging
import math
import os
import signal
import socket
import threading
import time
import tomllib
from dataclasses import dataclass
from pathlib import Path


from axlebox import configs
from axlebox._files import is_locked, locked
from axlebox._params import ParameterError
from axlebox._progress import Progress
from axlebox.bearing import resultfile
from axlebox.bearing.defects import Defect

SWEEP_FIELDS = ("speeds_kmh", "widths_mm", "kinds", "sides", "wheel_defects")
SIDES = ("L", "R", "LR")                             # LR: the defect on both sides of its wheelset
LOCK = ".sweep.lock"                                 # held by the sweep that owns the folder


@dataclass(frozen=True)
class Case:
    """One point of the matrix: ``config`` (a :class:`~axlebox.bearing.rig.RigConfig` or
    :class:`~axlebox.mbs.vehicle.config.CarConfig`) and ``toml``, its file: what its runner gets and
    stores in the result."""

    name: str
    kind: str
    speed_kmh: float
    width_mm: float
    config: object
    defect_kind: str | None = None      # swept kind, None: the config's own
    sides: str | None = None            # swept side(s), None: the config's own
    wheel: str | None = None            # swept wheel defect name, None: the config's own

    @property
    def toml(self) -> str:
        return self.config.to_toml()

    def path(self, out) -> Path:
        return Path(out) / f"{self.name}.h5"


def load_config(path) -> tuple[str, dict]:
    """``(kind, parsed TOML)`` of a sweep's base config (a file, or the name of a shipped config),
    kind ``"rig"`` or ``"vehicle"``."""
    from axlebox.mbs.vehicle.config import SECTIONS
    path = configs.resolve(path)
    try:
        cfg = tomllib.loads(path.read_text())
    except (tomllib.TOMLDecodeError, UnicodeDecodeError) as err:
        raise ParameterError(f"config {str(path)!r} is not valid TOML: {err}") from None
    secs = set(cfg) - {"sweep", "defects"}
    rig, vehicle = "rig" in secs, bool(secs & set(SECTIONS))
    if rig == vehicle:
        raise ParameterError(f"config {str(path)!r} is of an unknown kind (sections: "
                             f"{', '.join(sorted(cfg)) or 'none'}): expected a bearing rig config "
                             "([rig], [bearing], [[defects]]) or a vehicle config ([run], [track] ...)")
    return ("rig" if rig else "vehicle"), cfg


def _numbers(values, name: str, what: str, zero_ok: bool) -> list[float]:
    """A non-empty list of finite numbers > 0 (>= 0 with ``zero_ok``), duplicates dropped."""
    if not isinstance(values, (list, tuple)) or not values:
        raise ParameterError(f"{name} = {values!r} is not allowed: expected a list of {what}")
    for v in values:
        if isinstance(v, bool) or not isinstance(v, (int, float)) or not math.isfinite(v) \
                or not (v >= 0 if zero_ok else v > 0):
            raise ParameterError(f"{name} {v!r} is not allowed: expected {what} "
                                 f"{'>= 0' if zero_ok else '> 0'}")
    return list(dict.fromkeys(float(v) for v in values))


def typed(kind: str, d: dict):
    """The config object of a parsed rig or vehicle TOML (its ``[sweep]`` left out)."""
    d = {k: v for k, v in d.items() if k != "sweep"}
    if kind == "rig":
        from axlebox.bearing.rig import config_from_dict
        return config_from_dict(d)
    from axlebox.mbs.vehicle.config import validate
    return validate(d)


def _names(values, name: str, allowed: tuple[str, ...]) -> list[str]:
    """A non-empty list of names among ``allowed``, duplicates dropped."""
    if not isinstance(values, (list, tuple)) or not values:
        raise ParameterError(f"{name} = {values!r} is not allowed: expected a list of "
                             + ", ".join(allowed))
    for v in values:
        if v not in allowed:
            raise ParameterError(f"{name} {v!r} is not allowed: expected one of " + ", ".join(allowed))
    return list(dict.fromkeys(values))


def _place(defects: tuple, w, kind, sides) -> list:
    """The case's defects (the rig's :class:`~axlebox.bearing.defects.Defect` or the car's
    :class:`~axlebox.mbs.vehicle.config.BearingDefect` entries): width ``w`` mm (0: none, None: as they
    are), ``kind`` and ``sides`` (None: as they are) set on every entry; ``LR`` gives each
    entry once per side."""
    if w == 0:
        return []
    out = []
    for e in defects:
        change = {**({"W": w * 1e-3} if w is not None else {}), **({"kind": kind} if kind else {})}
        if isinstance(e, Defect):
            out.append(dataclasses.replace(e, **change))
            continue
        e = dataclasses.replace(e, shape=dataclasses.replace(e.shape, **change))
        out += [dataclasses.replace(e, side=s) for s in sides] if sides is not None else [e]
    return out


def _width(e) -> float:
    return (e if isinstance(e, Defect) else e.shape).W


def matrix(kind: str, cfg: dict, speeds=None, widths=None, duration=None, kinds=None,
           sides=None, wheels=None) -> list[Case]:
    """The cases of ``cfg`` (parsed TOML, its ``[sweep]`` read here): speeds (km/h) x widths
    (mm) x defect kinds x sides x wheel defects (names of ``[[wheel_defects]]`` entries,
    ``none``: without); options over ``[sweep]``."""
    from axlebox.bearing.kernel.layout import KINDS
    sw = cfg.get("sweep", {})
    if not isinstance(sw, dict):
        raise ParameterError(f"sweep = {sw!r} is not allowed: expected a [sweep] table")
    for k in sw:
        if k not in SWEEP_FIELDS:
            raise ParameterError(f"sweep.{k} is not a field of [sweep]: expected one of "
                                 f"{', '.join(SWEEP_FIELDS)}")
    def axis(given, key, option, what, zero_ok, default):
        if given is not None:
            return _numbers(given, option, what, zero_ok)
        return _numbers(sw[key], f"sweep.{key}", what, zero_ok) if key in sw else default

    def names(given, key, option, allowed):
        if given is not None:
            return _names(given, option, allowed)
        return _names(sw[key], f"sweep.{key}", allowed) if key in sw else [None]
    base = typed(kind, cfg)
    speeds = axis(speeds, "speeds_kmh", "--speeds", "speeds in km/h", False,
                  [(base if kind == "rig" else base.run).speed_kmh])
    widths = axis(widths, "widths_mm", "--widths", "defect widths in mm", True,
                  [None])                                # None: the config's defects as they are
    kinds = names(kinds, "kinds", "--kinds", tuple(KINDS))
    sides = names(sides, "sides", "--sides", SIDES)
    named = [e.name for e in getattr(base, "wheel_defects", ())]
    wheels = names(wheels, "wheel_defects", "--wheel-defects",
                   tuple(dict.fromkeys(["none"] + [n for n in named if n])))
    if kind == "rig" and wheels != [None]:
        raise ParameterError(f"wheel defects {wheels!r} are not allowed for the bearing rig: it "
                             "has no wheel; sweep them with a vehicle config")
    if kind == "rig" and sides != [None]:
        raise ParameterError(f"sides {sides!r} are not allowed for the bearing rig: it has one "
                             "bearing; sweep sides with a vehicle config")
    if duration is not None and not (math.isfinite(duration) and duration > 0):
        raise ParameterError(f"--duration = {duration!r} is not allowed: expected a time > 0 s")
    defects = base.defects
    if not defects and (any(widths) or kinds != [None] or sides != [None]):
        what, field = ((f"width {next(w for w in widths if w):g} mm", "W") if any(widths) else
                       (f"kinds {kinds!r}", "kind") if kinds != [None] else (f"sides {sides!r}", "side"))
        raise ParameterError(f"{what} is not allowed: the config has no [[defects]] entry whose "
                             f"defects.{field} to set; add one or sweep width 0 only")
    cases = {}
    for v, w, dk, sd, wd in ((v, w, dk, sd, wd) for v in speeds for w in widths for dk in kinds
                             for sd in sides for wd in wheels):
        if w == 0:                   # no defect: one case, whatever the kind and side
            dk, sd = None, None
        placed = _place(defects, w, dk, None if sd is None else
                        (("L", "R") if sd == "LR" else (sd,)))
        run = {"speed_kmh": float(v), **({"duration": float(duration)} if duration is not None else {})}
        if kind == "rig":
            c = dataclasses.replace(base, **run, defects=tuple(placed))
        else:
            # wd: the wheel defects of that name only; "none": none
            wheel = base.wheel_defects if wd is None else [e for e in base.wheel_defects if e.name == wd]
            c = base.replace(run=run, defects=placed, wheel_defects=wheel)
        mm = w if w is not None else 1e3 * max((_width(e) for e in defects), default=0.0)
        name = f"v{v:g}_w{mm:g}".replace(".", "p") + "".join(
            f"_{x}" for x in (dk, sd, wd) if x is not None)
        if name not in cases:
            cases[name] = Case(name, kind, float(v), mm, c, dk, sd, wd)
    return list(cases.values())


def case_lock(out) -> Path:
    """The lock a case's runner holds while it computes ``out``: ``.<name>.lock`` beside it."""
    out = Path(out)
    return out.with_name(f".{out.name.split('.')[0]}.lock")


def run_case(kind: str, toml_text: str, out: str, threads: int = 0) -> dict:
    """Run one case in this process (a dask worker) into ``out``, written through a temporary
    name by the runner.  A plain top-level function of plain arguments, so dask can ship it.
    ``threads`` > 0: numba threads for the case (local workers share the cores between them).
    The case's lock is held while it runs: a second runner of the same case (dask rerunning it
    after losing a worker that is in fact still computing, or another sweep) waits for the
    first and then finds the case finished (``computed`` False) instead of writing it twice."""
    t0 = time.perf_counter()
    out = Path(out)
    with locked(case_lock(out), what=f"pid {os.getpid()} on {socket.gethostname()}"):
        if is_finished(out, toml_text):
            return {"path": str(out), "wall_s": time.perf_counter() - t0, "computed": False}
        if threads > 0:
            import numba
            numba.set_num_threads(min(threads, numba.config.NUMBA_NUM_THREADS))
        if kind == "rig":
            from axlebox.bearing.rig import config_from_dict, simulate
            simulate(config_from_dict(tomllib.loads(toml_text)), out=out)     # through a temporary name
        else:
            from .simulate import Config, run
            with contextlib.redirect_stderr(io.StringIO()):
                res = run(Config(toml_text, out.stem), out, log=lambda *a: None)
            if not res.ok:
                raise RuntimeError(f"{res.message}; what was computed is in {out}")
    return {"path": str(out), "wall_s": time.perf_counter() - t0, "computed": True}


def is_finished(path, toml_text: str) -> bool:
    """``path`` opens as a complete axlebox-result of this very config that did not stop early."""
    try:
        with resultfile.reading(path) as f:
            return (f.attrs.get("config") == toml_text and f.attrs.get("status", "done") == "done"
                    and "time" in f and "signals" in f)
    except (OSError, ValueError):                    # missing, not a result, damaged
        return False


def shares(workers: int | None, cases: int, cores: int) -> tuple[int, int]:
    """Local worker processes and numba threads each for ``cases`` cases on ``cores`` cores
    (``workers``: as asked, default one a core): never more workers than cases or cores, the
    cores shared out among them, so workers times threads is at most the cores (a thread more
    waits at every parallel region for one that is not running: benchmarks/README.md, "The car
    beside another process")."""
    n = max(1, min(workers or cores, cases, cores))
    return n, max(1, cores // n)


def run_cases(todo: list[Case], out, scheduler=None, workers=None, log=print) -> list[str]:
    """Run ``todo`` on dask, one line per finished case; returns the names of the failed ones."""
    from dask.distributed import Client, LocalCluster, as_completed

    from axlebox._threads import cores
    n, threads = shares(workers, len(todo), cores())
    t0 = time.perf_counter()
    cluster = None
    if scheduler:
        try:
            client = Client(scheduler, timeout="20s")
        except (OSError, ValueError, TimeoutError) as err:
            raise ParameterError(f"--scheduler {scheduler!r} is not reachable: {err}") from None
    else:      # the workers start with Ctrl-C ignored: it stops this process, which closes them
        main = threading.current_thread() is threading.main_thread()
        old = signal.signal(signal.SIGINT, signal.SIG_IGN) if main else None
        try:
            # dashboard on a free port: two sweeps at once (or two test workers) do not collide
            cluster = LocalCluster(n_workers=n, threads_per_worker=1, processes=True, dashboard_address=":0",
                                   silence_logs=logging.CRITICAL)     # a failed case is one line below
        finally:
            if main:
                signal.signal(signal.SIGINT, old)
        client = Client(cluster)
    failed = []
    try:
        log(f"sweep: {len(todo)} case(s) on {scheduler or f'a local cluster of {n} worker(s)'}"
            + (f" (--workers {workers}: at most one a core, {cores()})"
               if not scheduler and workers and workers > n and n < len(todo) else ""))
        # local workers split the cores; a remote scheduler's workers keep numba's default (and
        # each run fits its threads to the cores the others leave: axlebox/_threads.py)
        threads = 0 if scheduler else threads
        futs = {client.submit(run_case, c.kind, c.toml, str(c.path(out)), threads, pure=False): c
                for c in todo}
        pace = Progress("sweep", len(todo), "case")
        for k, fut in enumerate(as_completed(futs), 1):
            c, head = futs[fut], f"[{k}/{len(todo)}] {futs[fut].name}"
            try:
                r = fut.result()
                log(f"{head}: done in {r['wall_s']:.1f} s (elapsed {time.perf_counter() - t0:.1f} s"
                    f"{pace.aside(k)})" if r["computed"]
                    else f"{head}: finished by another runner meanwhile: not computed again")
            except Exception as err:  # noqa: BLE001 - one case's failure does not stop the others
                failed.append(c.name)
                log(f"{head}: failed: {type(err).__name__}: {err}")
    finally:
        client.close()
        if cluster is not None:
            cluster.close()
    return failed


def _row(c: Case, path: Path, side: str, sensor: str, ch, verdict: str, lag_s=None, vf_diff=None) -> dict:
    from axlebox.bearing.diagnostics.wheel import text
    return dict(file=path.name, speed_kmh=c.speed_kmh, width_mm=c.width_mm, side=side, sensor=sensor,
                rms=ch.rms, spm_db=ch.spm_db, spm_class=ch.spm_class, VF=ch.VF, FC=ch.FC,
                kurtosis=ch.kurtosis, lines=" ".join(ch.detected), verdict=verdict, lag_s=lag_s,
                vf_diff=vf_diff, wheel_lines=text(ch.wheel_env, ch.wheel_spec))


def rig_rows(c: Case, path: Path, criterion) -> list[dict]:
    """The rig's one sensor: one-channel indicators (FC and VF over ``criterion.vf_band``),
    searching the fault lines the record holds two periods of (``channel.analyse`` needs that; a
    0.3 s run at 20 km/h holds BPFO only)."""
    from axlebox.bearing.diagnostics.channel import analyse
    from axlebox.bearing.rig import SENSOR

    from .readers import read
    rec = read(path, SENSOR, SENSOR)
    f = rec.orders.at(rec.shaft_hz)
    lines = tuple(n for n in ("BPFO", "BPFI", "2BSF", "FTF")
                  if rec.left.size / rec.fs >= 2.0 / f[n]) or ("BPFO",)
    ch = analyse(rec.left, rec.fs, rec.shaft_hz, rec.orders, rec.bearing.bore, lines=lines,
                 vf_band=criterion.vf_band)
    verdict = f"lines {' '.join(ch.detected)}" if ch.detected else "no fault line"
    return [_row(c, path, "-", SENSOR, ch, verdict)]


def vehicle_rows(c: Case, path: Path, criterion):
    """Both sides of the defect's wheelset (``wheelset`` of the first defect, else ws2) as
    ``axlebox diagnose`` does under ``criterion``, and the carbody's ride comfort:
    ``(axlebox.pipelines.report.Case, rows)``; a run whose axle-box record cannot be diagnosed
    (a comfort run's 1 kHz) gives its ride comfort alone and no rows."""
    from .report import diagnosed_case
    ws = c.config.defects[0].wheelset if c.config.defects else None
    rc = diagnosed_case(path, c.speed_kmh, c.width_mm, None, lambda *_: None,
                        criterion=criterion,
                        **(dict(left=f"ws{ws}_L", right=f"ws{ws}_R") if ws else {}))
    p = rc.pair
    if p is None:
        return rc, []
    return rc, [
        _row(c, path, s, p.names[i], getattr(p, s), p.verdict.words[s], p.lag.lag_s, p.vf_diff)
        for i, s in enumerate(("left", "right"))]


def table(rows: list[dict]) -> str:
    """The printed summary: one line per case and side."""
    def fmt(v, spec):
        bad = v is None or (isinstance(v, float) and not math.isfinite(v))
        return format("-", f">{spec.split('.')[0]}") if bad else format(v, spec)
    out = [f"{'case':<12} {'km/h':>6} {'mm':>5} {'side':<5} {'sensor':<10} {'RMS m/s2':>9} {'SPM dB':>7} "
           f"{'VF Hz2':>9} {'lag ms':>7} {'dVF Hz2':>9}  verdict"]
    for r in rows:
        lag = None if r["lag_s"] is None else 1e3 * r["lag_s"]
        out.append(f"{Path(r['file']).stem:<12} {r['speed_kmh']:>6g} {r['width_mm']:>5g} {r['side']:<5} "
                   f"{r['sensor']:<10} {fmt(r['rms'], '9.4g')} {fmt(r['spm_db'], '7.1f')} "
                   f"{fmt(r['VF'], '9.4g')} {fmt(lag, '7.2f')} {fmt(r['vf_diff'], '9.3g')}  {r['verdict']}")
    return "\n".join(out)


def summarise(cases: list[Case], out, log=print, criterion=None) -> list[dict]:
    """Diagnose every finished case (under ``criterion``, default the paper's), print the
    table, write ``out/summary.csv``."""
    from axlebox.bearing.diagnostics.criterion import PAPER

    from .report import write_csv, write_tables
    criterion = PAPER if criterion is None else criterion
    rows, report_cases = [], []
    for c in (c for c in cases if is_finished(c.path(out), c.toml)):
        try:
            if c.kind == "rig":
                rows += rig_rows(c, c.path(out), criterion)
            else:
                rc, r = vehicle_rows(c, c.path(out), criterion)
                report_cases.append(rc)
                rows += r
        except ParameterError as err:
            log(f"summary: {c.name}: not analysed: {err}")
    if not rows and not report_cases:
        return rows
    if rows:
        log(table(rows))
    for rc in report_cases:
        for r in rc.ride:
            log(f"{rc.path.stem}: ride comfort, {r.summary()}")
    if report_cases:
        write_tables(report_cases, Path(out))          # summary.csv and summary.json, as axlebox report
    else:
        write_csv(Path(out) / "summary.csv", rows)
    log(f"sweep: wrote {Path(out) / 'summary.csv'}")
    return rows


def sweep(config, out, *, speeds=None, widths=None, duration=None, scheduler=None, workers=None,
          log=print, kinds=None, sides=None, vf_band=None, wheels=None) -> dict:
    """The whole command.  Returns ``{"cases", "skipped", "ran", "failed", "rows"}``;
    ``vf_band``: the summary's band of FC and VF (``Criterion.vf_band``), default the whole."""
    from axlebox.bearing.diagnostics.criterion import Criterion
    criterion = Criterion(vf_band=vf_band)
    if workers is not None and (isinstance(workers, bool) or not isinstance(workers, int) or workers < 1):
        raise ParameterError(f"--workers = {workers!r} is not allowed: expected an integer >= 1")
    if workers is not None and scheduler:
        raise ParameterError(f"--workers {workers} is not allowed with --scheduler: the scheduler's "
                             "cluster has its own workers")
    cases = matrix(*load_config(config), speeds, widths, duration, kinds, sides, wheels)
    out = Path(out)
    out.mkdir(parents=True, exist_ok=True)
    note = (f"pid {os.getpid()} on {socket.gethostname()}, started "
            f"{time.strftime('%Y-%m-%d %H:%M:%S')}")
    with contextlib.ExitStack() as held:
        try:
            held.enter_context(locked(out / LOCK, wait=False, what=note))
        except BlockingIOError as err:         # only the lock's own refusal, not the sweep's
            raise ParameterError(f"--out {str(out)!r} is in use by another sweep ({err.strerror}): "
                                 "wait for it to finish, or give another --out") from None
        return _sweep(cases, out, scheduler, workers, log, criterion)


def _sweep(cases: list[Case], out: Path, scheduler, workers, log, criterion=None) -> dict:
    for p in sorted(out.glob("*.tmp")):
        if is_locked(case_lock(p)):             # a runner of an earlier sweep is still writing it
            log(f"sweep: {p.name}: kept (its case is being computed by another runner)")
            continue
        p.unlink(missing_ok=True)
        log(f"sweep: removed {p.name} (left by an interrupted run)")
    todo = [c for c in cases if not is_finished(c.path(out), c.toml)]
    for c in cases:
        if c not in todo:
            log(f"sweep: {c.name}: skipped (finished)")
        elif c.path(out).exists():
            log(f"sweep: {c.name}: its file is not a finished run of this config: recomputing")
    failed = run_cases(todo, out, scheduler, workers, log) if todo else []
    log(f"sweep: {len(cases)} case(s): {len(cases) - len(todo)} skipped, {len(todo) - len(failed)} run, "
        f"{len(failed)} failed")
    return {"cases": cases, "skipped": [c.name for c in cases if c not in todo],
            "ran": [c.name for c in todo if c.name not in failed], "failed": failed,
            "rows": summarise(cases, out, log, criterion)}
