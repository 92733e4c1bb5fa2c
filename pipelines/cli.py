"""The ``axlebox`` command line.

Exit status: 0 success, 2 bad input (one line on stderr naming it), 1 a failure
of the computation.
"""
from __future__ import annotations

import argparse
import dataclasses
import math
import sys
from pathlib import Path

from axlebox._params import ParameterError, number
from axlebox._progress import Progress
from axlebox.bearing.resultfile import ResultFileError
from axlebox.fem.bodyfile import BodyFileError


class _Parser(argparse.ArgumentParser):
    def error(self, message):  # one line, status 2, no usage dump
        self.exit(2, f"axlebox: error: {message}\n")


def _params(text: list[str]) -> dict[str, str]:
    out = {}
    for item in text or []:
        if "=" not in item:
            raise ParameterError(f"--param {item!r} is not allowed: expected NAME=VALUE")
        k, v = item.split("=", 1)
        out[k.strip()] = v.strip()
    return out


def _cmd_bodies_build(a) -> None:
    from axlebox.fem import bodyfile

    from .bodies import BODIES, build_body, build_user_body, make_params
    if a.geometry or a.mesh or a.spec:
        _user_body(a, build_user_body, bodyfile)
        return
    if a.body is None:
        raise ParameterError("--body is required: expected wheelset, axlebox, frame or all (or a body of "
                             "your own: --geometry FILE or --mesh FILE with --spec SPEC.toml)")
    names = list(BODIES) if a.body == "all" else [a.body]
    overrides = _params(a.param)
    if a.body == "all" and overrides:
        raise ParameterError("--param needs a single --body (parameters differ between bodies)")
    if a.modes is not None and a.modes < 1:
        raise ParameterError(f"--modes = {a.modes} is not allowed: expected an integer >= 1")
    if a.fmax is not None and not 0 < a.fmax < math.inf:
        raise ParameterError(f"--fmax = {a.fmax} is not allowed: expected a frequency > 0 Hz")
    if a.mesh_size is not None and not 0 < a.mesh_size < math.inf:
        raise ParameterError(f"--mesh-size = {a.mesh_size} is not allowed: expected a length > 0 m")
    if not 0 <= a.zeta < 1:
        raise ParameterError(f"--zeta = {a.zeta} is not allowed: expected 0 <= zeta < 1")
    params = {n: make_params(n, overrides) for n in names}
    pace = Progress("bodies", len(names), "body", units="bodies")
    for k, n in enumerate(names, 1):
        if k > 1:
            print(f"bodies: [{k}/{len(names)}] {n} next, {pace.left(k - 1)}", flush=True)
        rb, path = build_body(n, method=a.method, n_modes=None if a.fmax else a.modes or 20,
                              fmax_hz=a.fmax, mesh_size=a.mesh_size, params=params[n],
                              coupling=None if a.coupling == "default" else a.coupling,
                              damping=("modal", a.zeta), n_reference=0 if a.no_reference else 30,
                              out_dir=a.out, force=a.force)
        if a.vtu:
            print(f"{n}: wrote {bodyfile.export_vtu(rb, Path(a.out) / f'{n}.vtu')}")


def _user_body(a, build_user_body, bodyfile) -> None:
    """``bodies build --geometry|--mesh FILE --spec SPEC``: a user's part, everything but the
    output's handling from its spec (pipelines/bodyspec.py)."""
    if not a.spec or not (a.geometry or a.mesh):
        raise ParameterError("--spec goes with --geometry FILE or --mesh FILE: expected both (a body "
                             "of your own), or neither (a built-in --body)")
    given = [f"--{k.replace('_', '-')}" for k, v in (("body", a.body), ("modes", a.modes), ("fmax", a.fmax),
                                                      ("mesh_size", a.mesh_size), ("param", a.param))
             if v is not None]
    given += ["--method"] * (a.method != "craig-bampton") + ["--coupling"] * (a.coupling != "default")
    given += ["--zeta"] * (a.zeta != 0.01) + ["--no-reference"] * a.no_reference
    if given:
        raise ParameterError(f"{', '.join(given)} is not allowed with --spec: the spec's [body], [mesh], "
                             "[reduction] and [interfaces] say it")
    rb, path = build_user_body(a.spec, geometry=a.geometry, mesh_file=a.mesh, out_dir=a.out, force=a.force)
    if a.vtu:
        print(f"{rb.name}: wrote {bodyfile.export_vtu(rb, path.with_suffix('.vtu'))}")


def _cmd_bodies_export(a) -> None:
    from .export import export
    print(f"wrote {export(a.body_file, a.format, a.out)}")


def _cmd_bodies_template(a) -> None:
    from .bodies import write_template
    for path in write_template(a.body, a.out, mesh_size=a.mesh_size):
        print(f"wrote {path}")


def _cmd_bodies_report(a) -> None:
    from .render import report
    report(a.dir, a.out, max_modes=a.max_modes)


def _cmd_configs(a) -> None:
    import textwrap

    from axlebox import configs
    if a.action == "show":
        if not a.name:
            raise ParameterError("configs show needs a NAME: one of " + ", ".join(configs.names()))
        print(configs.path(a.name).read_text(), end="")
        return
    if a.name:
        raise ParameterError(f"configs {a.action} {a.name!r} is not allowed: a NAME goes with 'show'")
    width = max(map(len, configs.names()))
    for n in configs.names():
        lines = textwrap.wrap(configs.summary(n), 100 - width - 2) or [""]
        print(f"{n:<{width}}  {lines[0]}")
        for more in lines[1:]:
            print(" " * (width + 2) + more)
    print(f"\n(in {configs.folder()}; axlebox configs show NAME > my.toml to copy and edit; "
          "simulate and sweep take a NAME or a path)")


def _cmd_demo(a) -> None:
    from .demo import CONFIG, DURATION, demo
    demo(a.out, duration=DURATION if a.duration is None else a.duration,
         config=CONFIG if a.config is None else a.config)


def _bearing_params(kind: str, a):
    """The parameters of the bearing model ``kind`` (``--type``) from ``--damping``, ``--cage``
    and ``--param NAME=VALUE``; a name that is not a field of that model is refused naming
    ``--type`` and, where it is another model's field, that model."""
    from axlebox.bearing import models
    cls = models.MODELS[kind].Params
    fields = {f.name: f for f in dataclasses.fields(cls)}
    given = _params(a.param)
    for k in given:
        if k not in fields:
            others = [n for n, m in models.MODELS.items()
                      if n != kind and k in {f.name for f in dataclasses.fields(m.Params)}]
            whose = f" (a field of {' and '.join(others)})" if others else ""
            raise ParameterError(f"--param {k} is not allowed with --type {kind}{whose}: expected one "
                                 f"of {', '.join(fields)}")
    overrides = {}
    for k, v in given.items():
        if fields[k].type in ("str", str):           # a named choice (damping, cage, model)
            overrides[k] = v
            continue
        x = number(f"--param {k}", v)
        overrides[k] = int(x) if fields[k].type in ("int", int) and x.is_integer() else x
    return cls(**{"damping": a.damping, "cage": a.cage, **overrides})


def _cmd_bearing_simulate(a) -> None:
    from math import radians

    from axlebox.bearing.defects import Defect
    from axlebox.bearing.rig import RigConfig, simulate
    if a.defect_width < 0:
        raise ParameterError(f"--defect-width = {a.defect_width} is not allowed: expected a width >= 0 mm "
                             "(0: healthy)")
    bearing = _bearing_params(a.type, a)
    defects = ()
    if a.defect_width > 0:
        defects = (Defect(W=a.defect_width * 1e-3, L=a.defect_length * 1e-3, H=a.defect_depth * 1e-3,
                          row=bearing.rows if a.defect_row is None else a.defect_row,
                          angle=radians(a.defect_angle), kind=a.defect_kind,
                          roller=a.defect_roller),)
    cfg = RigConfig(speed_kmh=a.speed_kmh, F_r=a.radial_load, F_a=a.axial_load, duration=a.duration,
                    dt=a.dt, method=a.method, seed=a.seed, bearing=bearing, defects=defects)
    out = Path(a.out)
    if not out.parent.is_dir():
        raise FileNotFoundError(f"--out: folder {str(out.parent)!r} does not exist")

    progress = Progress("simulating", a.duration)
    try:
        res = simulate(cfg, out=out, progress=lambda x: progress(x * a.duration))
    finally:
        progress.close()
    print(f"wrote {out}: {a.type.upper()}, cage {res.cage_hz(min(0.05, a.duration / 2)):.4f} Hz, "
          f"outer-ring a_z rms "
          f"{res.acceleration[:, 2].std():.3g} m/s^2")
    if a.plot:
        res.plot(out.with_suffix(".png"))
        print(f"wrote {out.with_suffix('.png')}")


def _cmd_contact_geometry(a) -> None:
    from axlebox.mbs.wheelrail.geometry import TrackLayout

    from .contact import run
    lay = TrackLayout(r0=a.r0, gauge=a.gauge * 1e-3, back_to_back=a.back_to_back * 1e-3,
                      cant=0.0 if a.cant == 0 else 1.0 / a.cant)
    res = run(a.wheel, a.rail, a.out, layout=lay, y_max=a.y_max * 1e-3, amplitudes_mm=a.amplitude)
    print(f"{' on '.join(res['table'].names)}: equivalent conicity (harmonic / Klingel)")
    for A, h, k in zip(res["amplitude"], res["harmonic"], res["klingel"]):
        print(f"  {A * 1e3:5.2f} mm: {h:.4f} / {k:.4f}")
    print(f"wrote {Path(a.out) / 'contact_table.csv'}, conicity.csv, contact_table.png")


def _cmd_simulate(a) -> None:
    from .simulate import run
    res = run(a.config, a.out, duration=a.duration, checkpoint_every=a.checkpoint_every,
              restart=a.restart, ahead=True)
    if not res.ok:
        raise RuntimeError(f"{res.message}; what was computed is in {a.out}")


def _vf_band(a):
    from .diagnose import parse_pair
    return parse_pair(a.vf_band, "--vf-band") if a.vf_band else None


def _thresholds(a) -> dict:
    """The criterion's thresholds given on the command line (``--second-db`` ...), as keyword
    arguments of :class:`axlebox.bearing.diagnostics.criterion.Criterion`; Criterion checks
    each and names its option."""
    from axlebox.bearing.diagnostics.criterion import OPTIONS
    return {name: getattr(a, name) for name in OPTIONS if getattr(a, name) is not None}


def _analysis_options(a) -> dict:
    """The options ``diagnose`` and ``report`` share, as keyword arguments of
    :func:`axlebox.pipelines.diagnose.analyse_file`."""
    from axlebox.bearing.diagnostics.criterion import Criterion

    from .diagnose import parse_pair
    crit = Criterion(mode="relative" if a.relative else "absolute",
                     **({"vf_range": parse_pair(a.vf_range, "--vf-range")} if a.vf_range else {}),
                     **({"rel_range": parse_pair(a.rel_range, "--rel-range")} if a.rel_range else {}),
                     lag="off" if a.no_lag else a.lag, vf_band=_vf_band(a), **_thresholds(a))
    return dict(left=a.left, right=a.right, fs=a.fs, column=a.column, scale=a.scale,
                shaft=a.shaft_hz, speed_kmh=a.speed_kmh, wheel_radius=a.wheel_radius, rpm=a.rpm,
                orders_text=a.orders, bore=a.bore, bearing=a.bearing, orders_left=a.orders_left,
                orders_right=a.orders_right, bearing_left=a.bearing_left,
                bearing_right=a.bearing_right, bore_left=a.bore_left, bore_right=a.bore_right,
                band=parse_pair(a.band, "--band") if a.band else None, criterion=crit,
                nperseg=a.nperseg, guided=not a.no_guide)


def _speed_options(a) -> dict:
    """The speed over time ``diagnose``, ``report`` and ``dataset`` take
    (:mod:`axlebox.pipelines.speed`)."""
    return dict(speed_channel=a.speed_channel, speed_unit=a.speed_unit, tacho=a.tacho,
                tacho_threshold=a.tacho_threshold, speed_csv=a.speed_csv,
                order_tracking=a.order_tracking)


def _cmd_diagnose(a) -> None:
    options = {**_analysis_options(a), **_speed_options(a)}
    if a.window_turns is None:
        from .diagnose import run
        for opt in ("windows_out",):
            if getattr(a, opt) is not None:
                raise ParameterError("--windows-out needs --window-turns: the windows' length in shaft turns")
        run(a.file, json_out=a.json, figures=a.figures, **options)
        return
    from .windows import run_windows
    run_windows(a.file, a.window_turns, a.window_overlap, out=a.windows_out, figures=a.figures, **options)


def _cmd_report(a) -> None:
    from .report import report
    report(a.source, a.out, modes_dir=a.modes, **_analysis_options(a), **_speed_options(a))


def _cmd_sweep(a) -> None:
    from .sweep import sweep
    res = sweep(a.config, a.out, speeds=a.speeds, widths=a.widths, duration=a.duration,
                scheduler=a.scheduler, workers=a.workers, kinds=a.kinds, sides=a.sides,
                vf_band=_vf_band(a), wheels=a.wheel_defects)
    if res["failed"]:
        raise RuntimeError(f"{len(res['failed'])} case(s) failed ({', '.join(res['failed'])}); the "
                           f"finished ones are in {a.out}, a rerun retries the rest")


def _cmd_dataset(a) -> None:
    from axlebox.bearing.diagnostics.criterion import Criterion

    from .dataset import write
    write(a.sweep_dir, a.out, window_s=a.window, hop_s=a.hop,
          criterion=Criterion(mode=a.criterion, **_thresholds(a)), **_speed_options(a))


def _add_speed_options(p):
    """The speed sources and order tracking ``diagnose``, ``report`` and ``dataset`` share
    (:mod:`axlebox.pipelines.speed`); returns their group."""
    sp = p.add_argument_group("speed over the record (a result file of a run along a speed profile "
                               "gives its own: the stored shaft angle)")
    sp.add_argument("--speed-channel", metavar="NAME", help="a channel of the same file holding the "
                    "speed, one sample a sample, in --speed-unit")
    sp.add_argument("--speed-unit", default="km/h", metavar="UNIT",
                    help="km/h (with --wheel-radius), rpm or Hz (default: km/h)")
    sp.add_argument("--tacho", metavar="NAME", help="a once-per-revolution pulse channel of the same "
                    "file (the record is cut to its pulses' span)")
    sp.add_argument("--tacho-threshold", type=float, metavar="LEVEL", help="the level a pulse rises "
                    "through (default: midway between the channel's 1st and 99th percentiles)")
    sp.add_argument("--speed-csv", metavar="FILE", help="a speed profile: CSV of time s (from the "
                    "record's first sample) and speed in --speed-unit, covering the record")
    sp.add_argument("--order-tracking", default="auto", metavar="MODE", help="auto (order-track where "
                    "the speed's range exceeds 0.5 %% of its mean; without a source of the speed, "
                    "the speed read from the record itself), on or off (read at the given speed, "
                    "the record's own speed not read; default: auto)")
    return sp


def _add_dataset(sub) -> None:
    ds = sub.add_parser("dataset", help="a vehicle sweep as labelled windows of the two axle-box "
                                        "signals (NetCDF-4, xarray) with a dataset card",
                        description="Cuts every result of a vehicle sweep folder into windows of "
                        "the two axle-box signals (vertical, after the track's fade-in) labelled "
                        "with speed, each side's defect, the real side and the criterion's verdict; "
                        "writes OUT/dataset.nc (xarray.open_dataset) and OUT/README.md.")
    ds.add_argument("sweep_dir", help="the --out folder of axlebox sweep (vehicle results)")
    ds.add_argument("--out", required=True, help="output folder (dataset.nc, README.md)")
    ds.add_argument("--window", type=float, default=0.5, metavar="S", help="window length in s "
                                                                            "(default 0.5)")
    ds.add_argument("--hop", type=float, default=0.25, metavar="S", help="step between window "
                                                                          "starts in s (default 0.25)")
    ds.add_argument("--criterion", choices=("relative", "absolute"), default="relative",
                    help="the criterion's VF mode for the verdict labels (default relative, as the "
                         "demo)")
    _add_threshold_options(ds)
    _add_speed_options(ds)
    ds.set_defaults(func=_cmd_dataset)


def _add_sweep(sub) -> None:
    sw = sub.add_parser("sweep", help="a study matrix (speeds x defect widths [x kinds x sides]) of the "
                                      "bearing rig or "
                                      "the vehicle on dask.distributed; resumable; summary table",
                        description="Runs every case (speed x defect width) of a rig config ([rig]) "
                        "or a vehicle config ([run] ...) as a dask.distributed task, on a local "
                        "cluster or the scheduler named; one result file per case (DIR/v<speed>_"
                        "w<width>.h5), written through a temporary name; a rerun skips finished "
                        "cases. Ends with a table of indicators per case and side (DIR/summary.csv).")
    sw.add_argument("config", help="base config: a TOML file or a shipped config's name (axlebox "
                                   "configs): a rig config (study_rig) or a vehicle config (study); "
                                   "an optional [sweep] gives speeds_kmh, widths_mm, kinds, sides, "
                                   "wheel_defects")
    sw.add_argument("--speeds", type=float, nargs="+", metavar="V",
                    help="speeds in km/h (default: sweep.speeds_kmh, else the config's speed)")
    sw.add_argument("--widths", type=float, nargs="+", metavar="MM",
                    help="defect widths in mm, 0: no defect; > 0 sets W of every [[defects]] entry "
                         "(default: sweep.widths_mm, else the config's defects)")
    sw.add_argument("--kinds", nargs="+", metavar="KIND",
                    help="defect kinds (outer, inner, roller) set on every [[defects]] entry "
                         "(default: sweep.kinds, else the config's)")
    sw.add_argument("--sides", nargs="+", metavar="SIDE",
                    help="vehicle: L, R or LR (both sides of the wheelset) for every [[defects]] "
                         "entry (default: sweep.sides, else the config's)")
    sw.add_argument("--wheel-defects", nargs="+", metavar="NAME",
                    help="vehicle: names of [[wheel_defects]] entries, one case each (entries "
                         "sharing a name go together), none: without (default: "
                         "sweep.wheel_defects, else the config's)")
    sw.add_argument("--scheduler", metavar="ADDRESS",
                    help="dask scheduler (e.g. tcp://host:8786; default: a local cluster)")
    sw.add_argument("--workers", type=int, metavar="N",
                    help="local worker processes, at most one a core, the cores shared out as "
                         "their threads (default: the core count)")
    sw.add_argument("--duration", type=float, metavar="S", help="simulated time of every case "
                                                                "(default: the config's)")
    sw.add_argument("--out", required=True, help="output folder (one .h5 per case, summary.csv)")
    sw.add_argument("--vf-band", metavar="LO,HI", help=VF_BAND_HELP)
    sw.set_defaults(func=_cmd_sweep)


VF_BAND_HELP = ("band in Hz over which each side's FC and VF (the paper's Eq. 18) are taken, "
                "e.g. 0,1000 (default: the record's whole band)")


def _add_threshold_options(dg) -> None:
    """The criterion's thresholds a user may move (bearing/diagnostics/criterion.py, Criterion:
    where each default comes from); the defaults are Criterion's."""
    from axlebox.bearing.diagnostics.criterion import Criterion as C
    dg.add_argument("--second-db", type=float, metavar="DB",
                    help="how far over its floor each side's own fault line must stand for faults "
                         f"on both sides (default {C.second_db:g} dB: a healthy bearing's own lines "
                         "reach 13)")
    dg.add_argument("--clearer-db", type=float, metavar="DB",
                    help="how far one side's own line must stand over the other's for the clearer "
                         f"to be called real when the other is faint (default {C.clearer_db:g} dB)")
    dg.add_argument("--c-independent", type=float, metavar="C",
                    help="coherent fraction in [0, 1) at or under which a line seen on both sides "
                         f"is two impulse trains, a fault on each side (default {C.c_independent:g})")
    dg.add_argument("--gate-ratio", type=float, metavar="R",
                    help="turn-folded envelope peak over its median from which a wheel flat's "
                         f"strikes are blanked, > 1 (default {C.gate_ratio:g}; inf: never)")
    dg.add_argument("--shaft-p-fa", type=float, metavar="P",
                    help="false-alarm probability a record of naming a line at a whole multiple "
                         f"of the shaft's rate, in (0, 1) (default {C.shaft_p_fa:g})")


def _add_analysis_options(dg) -> None:
    dg.add_argument("--left", help="left channel: sensor (result file; default ws2_L), variable "
                                   "(.mat), dataset path (HDF5) or column name (CSV; default first)")
    dg.add_argument("--right", help="right channel, likewise (default ws2_R; CSV: second column)")
    dg.add_argument("--column", type=int, default=2, help="result files: acceleration column "
                                                          "(default 2, vertical)")
    dg.add_argument("--fs", type=float, help="sampling rate in Hz (required for CSV and files without one)")
    dg.add_argument("--scale", type=float, default=1.0,
                    help="multiply the samples (e.g. 9.80665 for data in g; default 1: m/s^2)")
    sp = dg.add_mutually_exclusive_group()
    sp.add_argument("--shaft-hz", type=float, help="shaft (wheelset) rotation frequency, Hz")
    sp.add_argument("--rpm", type=float, help="shaft speed in rev/min")
    sp.add_argument("--speed-kmh", type=float, help="vehicle speed (with --wheel-radius)")
    dg.add_argument("--wheel-radius", type=float, default=0.42, metavar="M", help="default 0.42")
    dg.add_argument("--bearing", metavar="NAME", help="both sides' bearing from the catalogue "
                    "(dtrb, 6205, 6203; default: the file's, else dtrb)")
    dg.add_argument("--bearing-left", metavar="NAME", help="the left side's bearing (e.g. 6205)")
    dg.add_argument("--bearing-right", metavar="NAME", help="the right side's bearing (e.g. 6203)")
    dg.add_argument("--orders", metavar="BPFO=..,BPFI=..,FTF=..,BSF=..",
                    help="both sides' fault orders (multiples of the shaft speed; BSF the roller "
                         "spin, half the rolling element's defect order)")
    dg.add_argument("--orders-left", metavar="BPFO=..,...", help="the left side's fault orders")
    dg.add_argument("--orders-right", metavar="BPFO=..,...", help="the right side's fault orders")
    dg.add_argument("--bore", type=float, metavar="M", help="bearing bore for SPM (default: the "
                    "bearing's, 0.130 for the DTRB; required with --orders)")
    dg.add_argument("--bore-left", type=float, metavar="M", help="the left side's bore")
    dg.add_argument("--bore-right", type=float, metavar="M", help="the right side's bore")
    dg.add_argument("--band", metavar="LO,HI", help="envelope band in Hz (default: spectral kurtosis)")
    dg.add_argument("--no-guide", action="store_true",
                    help="keep each side's spectral-kurtosis band even where the other side shows "
                         "a fault line (default: search that side again in the band where the line "
                         "stands highest)")
    dg.add_argument("--nperseg", type=int, help="Welch segment for FC/VF (default about 1 s)")
    dg.add_argument("--vf-band", metavar="LO,HI", help=VF_BAND_HELP)
    dg.add_argument("--vf-range", metavar="LO,HI", help="VF difference range in Hz^2 meaning a "
                                                        "pseudo-fault (default the paper's 8000,74900)")
    dg.add_argument("--relative", action="store_true", help="compare |VF_L - VF_R| / max(VF) "
                    "instead (machine-independent; default range 0.14,1)")
    dg.add_argument("--rel-range", metavar="LO,HI", help="range of the relative VF difference")
    lg = dg.add_mutually_exclusive_group()
    lg.add_argument("--lag", choices=("decide", "veto", "off"), default="decide",
                    help="how the lag between the sides enters the verdict: decide (default: a "
                         "lag read on the impulses names the real side), veto (a lag that "
                         "contradicts RMS and SPM leaves both undecided; it breaks their ties), "
                         "off (the paper's RMS and SPM alone)")
    lg.add_argument("--no-lag", action="store_true", help="the same as --lag off")
    _add_threshold_options(dg)


def parser() -> argparse.ArgumentParser:
    from axlebox.bearing import models
    p = _Parser(prog="axlebox", description="Railway vehicle dynamics with flexible bodies and "
                                            "axle-box bearing faults.")
    sub = p.add_subparsers(dest="command", required=True, parser_class=_Parser)

    d = sub.add_parser("demo", help="the main job: modal bodies, the paper's validation case with "
                                    "its DTRBs, diagnosis of both sides and the HTML report")
    d.add_argument("--out", default="axlebox-demo", help="output folder (default: axlebox-demo)")
    d.add_argument("--duration", type=float, default=None, metavar="S",
                   help="simulated time of the validation case (default 1.6, at least 1.41: "
                        "the track's fade-in and two cage periods)")
    d.add_argument("--config", default=None, metavar="NAME",
                   help="the case to run (default validation_48kmh; dcrb_48kmh: the same car on "
                        "double-row cylindrical roller bearings)")
    d.set_defaults(func=_cmd_demo)

    cf = sub.add_parser("configs", help="the shipped configs: list them, or show one to copy and edit",
                        description="Lists the configs installed with axlebox (each takes the place "
                        "of a path in simulate and sweep), or prints one: axlebox configs show "
                        "validation_48kmh > my.toml")
    cf.add_argument("action", nargs="?", default="list", choices=["list", "show"],
                    help="list (default) or show NAME")
    cf.add_argument("name", nargs="?", help="a shipped config's name (with show)")
    cf.set_defaults(func=_cmd_configs)

    b = sub.add_parser("bodies", help="modal bodies from geometry")
    bs = b.add_subparsers(dest="bodies_command", required=True, parser_class=_Parser)
    bb = bs.add_parser("build", help="mesh, assemble and reduce bodies into <out>/<body>.h5: the built-in "
                       "ones (--body) or your own (--geometry or --mesh with --spec)")
    bb.add_argument("--body", choices=["wheelset", "axlebox", "frame", "all"], help="a built-in body")
    bb.add_argument("--geometry", metavar="FILE", help="your own part as CAD: STEP, IGES or BREP")
    bb.add_argument("--mesh", metavar="FILE", help="your own part as a mesh: Abaqus .inp, Nastran .bdf, "
                    "gmsh .msh, Salome .med, .vtu")
    bb.add_argument("--spec", metavar="SPEC.toml", help="what your part is: kind, material, mesh size, "
                    "reduction and interfaces by name (docs: your own bodies)")
    bb.add_argument("--method", default="craig-bampton", choices=["guyan", "craig-bampton"])
    g = bb.add_mutually_exclusive_group()
    g.add_argument("--modes", type=int, default=None,
                   help="fixed-interface modes kept by Craig-Bampton (default 20)")
    g.add_argument("--fmax", type=float, default=None, help="keep fixed-interface modes below HZ")
    bb.add_argument("--mesh-size", type=float, default=None, help="element size in m (default per body)")
    bb.add_argument("--coupling", default="default", choices=["default", "rbe2", "rbe3"],
                    help="interface coupling on every surface (default: per interface)")
    bb.add_argument("--param", action="append", metavar="NAME=VALUE",
                    help="geometry parameter (SI), repeatable, e.g. r_wheel=0.41")
    bb.add_argument("--zeta", type=float, default=0.01, help="modal damping ratio (default 0.01)")
    bb.add_argument("--no-reference", action="store_true",
                    help="skip the full-model free-free modes used to report the reduction error")
    bb.add_argument("--vtu", action="store_true", help="also write <body>.vtu with the mode shapes")
    bb.add_argument("--force", action="store_true",
                    help="rebuild even if <out>/<body>.h5 holds the same request (default: keep it)")
    bb.add_argument("--out", required=True, help="output folder")
    bb.set_defaults(func=_cmd_bodies_build)

    bt = bs.add_parser("template", help="a built-in body as STEP and the spec that builds it again "
                       "(bodies build --geometry --spec): a start for your own")
    bt.add_argument("--body", required=True, choices=["wheelset", "axlebox", "frame"])
    bt.add_argument("--mesh-size", type=float, default=None, help="element size in m (default: the car's)")
    bt.add_argument("--out", required=True, help="output folder: <body>.step and <body>.toml")
    bt.set_defaults(func=_cmd_bodies_template)

    br = bs.add_parser("report", help="render mode shapes off-screen and write index.html")
    br.add_argument("dir", help="folder of reduced-body files (or one .h5 file)")
    br.add_argument("--out", required=True, help="report folder")
    br.add_argument("--max-modes", type=int, default=None, help="render at most N modes a body")
    br.set_defaults(func=_cmd_bodies_report)

    bx = bs.add_parser("export", help="a reduced body for another multibody code: Exudyn "
                                      "(FEMinterface .hdf5) or MBDyn (modal element .fem)",
                       description="Writes the reduced body for Exudyn's ObjectFFRFreducedOrder "
                       "(FEMinterface.LoadFromFile data: mesh, full mass and stiffness reassembled "
                       "from the mesh and material, the body's modes; .hdf5) or as MBDyn's modal "
                       "element database (.fem: the master/output nodes, their mode shapes, modal "
                       "mass, stiffness and damping, rigid-body inertia). SI units.")
    bx.add_argument("body_file", metavar="BODY.h5", help="a reduced-body file (axlebox bodies build)")
    bx.add_argument("--format", required=True, choices=["exudyn", "mbdyn"])
    bx.add_argument("--out", required=True, metavar="PATH",
                    help="file to write (exudyn: ending in .hdf5), or an existing folder "
                         "(<folder>/<body>.hdf5 or .fem)")
    bx.set_defaults(func=_cmd_bodies_export)

    be = sub.add_parser("bearing", help="an axle-box bearing alone (any model: --type)")
    bes = be.add_subparsers(dest="bearing_command", required=True, parser_class=_Parser)
    bsim = bes.add_parser("simulate", help="standalone rig: spinning inner ring, outer ring on a "
                                           "spring-damper, constant load; writes an axlebox-result file")
    bsim.add_argument("--type", choices=list(models.MODELS), default=models.DEFAULT,
                      help="the bearing model, as [bearing] type: " + "; ".join(
                          f"{n} {m.SUMMARY}" for n, m in models.MODELS.items())
                      + f" (default {models.DEFAULT}); --param takes its fields")
    bsim.add_argument("--speed-kmh", type=float, default=48.0, help="vehicle speed (default 48)")
    bsim.add_argument("--defect-width", type=float, default=0.0, metavar="MM",
                      help="defect width in mm (default 0: healthy)")
    bsim.add_argument("--defect-length", type=float, default=50.4, metavar="MM",
                      help="defect length across the raceway in mm (default 50.4)")
    bsim.add_argument("--defect-depth", type=float, default=2.0, metavar="MM",
                      help="defect depth in mm (default 2)")
    bsim.add_argument("--defect-row", type=int, default=None,
                      help="row of the defect, 1 to the bearing's rows (default: its last, a double-row "
                           "bearing's outboard row 2)")
    bsim.add_argument("--defect-kind", default="outer",
                      help="outer (on the outer ring, the DTRB's cup; default), inner (on the "
                           "inner ring, the DTRB's cone, turning with the shaft) or roller (on one "
                           "roller, turning with its spin)")
    bsim.add_argument("--defect-roller", type=int, default=1,
                      help="the roller (1..Z) that carries a roller defect (default 1)")
    bsim.add_argument("--defect-angle", type=float, default=0.0, metavar="DEG",
                      help="defect centre from the top (load zone middle), degrees (default 0); "
                           "a roller defect: the roller's spin angle at which it meets the cup")
    bsim.add_argument("--radial-load", type=float, default=54e3, metavar="N", help="default 54e3")
    bsim.add_argument("--axial-load", type=float, default=0.0, metavar="N", help="default 0")
    bsim.add_argument("--duration", type=float, default=1.0, metavar="S", help="simulated time (default 1)")
    bsim.add_argument("--dt", type=float, default=1e-5, metavar="S", help="integration step (default 1e-5)")
    bsim.add_argument("--method", default="rk4",
                      help="integrator: rk4 (default), leapfrog (one evaluation a step, 5x faster "
                           "at 1e-5 s, about 1 %% off RK4 in the outer ring's RMS), imex or imex2")
    bsim.add_argument("--damping", default="ratio", choices=["ratio", "paper", "stiffness"],
                      help="contact damping law: ratio (zeta of the roller's contact oscillator), "
                           "paper (c_rule x K), stiffness (beta x the tangent stiffness); "
                           "default ratio")
    bsim.add_argument("--cage", default="dynamic", choices=["dynamic", "kinematic"],
                      help="cage rotation: dynamic state or the paper's Eq. 2 (default dynamic)")
    bsim.add_argument("--param", action="append", metavar="NAME=VALUE",
                      help="a field of the --type model's parameters (SI), repeatable, e.g. "
                           "u_r=1e-4 (the fields: axlebox configs' [bearing] reference)")
    bsim.add_argument("--seed", type=int, default=0, help="turns the roller set by a random phase")
    bsim.add_argument("--plot", action="store_true", help="also write <out>.png")
    bsim.add_argument("--out", required=True, help="result file (.h5)")
    bsim.set_defaults(func=_cmd_bearing_simulate)

    sm = sub.add_parser("simulate", help="the metro car on tangent track, or on the line of its "
                                         "[[track.layout]], from a config (e.g. vehicle, "
                                         "validation_48kmh, curve_300m_left_unbalanced); writes an "
                                         "axlebox-result file")
    sm.add_argument("config", help="vehicle config: a TOML file or a shipped config's name (axlebox configs)")
    sm.add_argument("--duration", type=float, default=None, metavar="S",
                    help="simulated time (default: the config's run.duration)")
    sm.add_argument("--out", required=True, help="result file (.h5)")
    sm.add_argument("--checkpoint-every", type=float, default=None, metavar="S",
                    help="simulated seconds between checkpoints of the state to OUT.partial.h5 "
                         "(default: 1; 0: none; the outputs stream to OUT.stream.d meanwhile); the "
                         "same command run again resumes from the last")
    sm.add_argument("--restart", action="store_true",
                    help="start over, dropping a checkpoint of another config")
    sm.set_defaults(func=_cmd_simulate)

    dg = sub.add_parser("diagnose", help="real fault or coaxial pseudo-fault from the two sides' "
                                         "signals (axlebox-result, CSV, .mat v5/v7.3, HDF5)",
                        description="Indicators of both channels (RMS, kurtosis, envelope spectrum "
                        "fault lines, SPM Eq. 17, FC/VF Eq. 18), their time lag, the VF difference "
                        "and the paper's criterion; prints a summary, writes JSON and a figure.")
    dg.add_argument("file", help="axlebox-result .h5, CSV (columns), MATLAB .mat (v5 or v7.3) or HDF5")
    _add_analysis_options(dg)
    dg.add_argument("--json", metavar="OUT", help="write the indicators and verdicts as JSON")
    dg.add_argument("--figures", metavar="DIR", help="write <file>_diagnose.png into DIR")
    sp = _add_speed_options(dg)
    sp.add_argument("--window-turns", type=float, metavar="N", help="read the record in windows of N "
                    "shaft turns (at least about 5: two cage turns), one verdict a window")
    sp.add_argument("--window-overlap", type=float, default=0.5, metavar="SHARE",
                    help="share of a window the next one overlaps (default: 0.5)")
    sp.add_argument("--windows-out", metavar="FILE", help="the windows as JSON Lines, one object a "
                    "window, the summary last")
    dg.set_defaults(func=_cmd_diagnose)

    rp = sub.add_parser("report", help="the paper's result figures (Figs. 9-14), a summary table and "
                                       "an HTML page for a run or a sweep folder",
                        description="Diagnoses every axlebox-result file (the file, or a folder's "
                        "*.h5 one level deep) as diagnose does; writes fig09-fig14 PNGs, summary.csv/"
                        ".json and index.html, with mode-shape pictures when present.")
    rp.add_argument("source", help="a result file or a folder of them (a sweep)")
    rp.add_argument("--out", required=True, help="report folder")
    rp.add_argument("--modes", metavar="DIR", help="mode-shape pictures (axlebox bodies report "
                                                   "output; default: looked for beside the input)")
    _add_analysis_options(rp)
    _add_speed_options(rp)
    rp.set_defaults(func=_cmd_report)

    _add_sweep(sub)
    _add_dataset(sub)

    c = sub.add_parser("contact", help="wheel-rail contact")
    cs = c.add_subparsers(dest="contact_command", required=True, parser_class=_Parser)
    cg = cs.add_parser("geometry", help="contact geometry table of a wheelset on straight track and "
                                        "equivalent conicity; writes CSV and a figure")
    cg.add_argument("--wheel", default="S1002", help="S1002 or a profile file (.prw or 'y z' mm text)")
    cg.add_argument("--rail", default="UIC60", help="UIC60 (60E1), CHN60 or a profile file (.prr, text)")
    cg.add_argument("--gauge", type=float, default=1435.0, metavar="MM", help="track gauge (default 1435)")
    cg.add_argument("--back-to-back", type=float, default=1360.0, metavar="MM",
                    help="distance between the wheels' back faces (default 1360; the paper's metro 1353)")
    cg.add_argument("--cant", type=float, default=40.0, metavar="N",
                    help="rail cant 1:N (default 40; 0 for a file that is already canted)")
    cg.add_argument("--r0", type=float, default=0.42, metavar="M", help="nominal wheel radius (default 0.42)")
    cg.add_argument("--y-max", type=float, default=10.0, metavar="MM",
                    help="lateral displacements -y..y (default 10)")
    cg.add_argument("--amplitude", type=float, nargs="+", default=[1, 2, 3, 4, 5, 6], metavar="MM",
                    help="amplitudes for the equivalent conicity (default 1 2 3 4 5 6)")
    cg.add_argument("--out", required=True, help="output folder")
    cg.set_defaults(func=_cmd_contact_geometry)
    return p


def main(argv: list[str] | None = None) -> int:
    a = parser().parse_args(argv)
    try:
        a.func(a)
    except (ParameterError, BodyFileError, ResultFileError, FileNotFoundError) as err:
        print(f"axlebox: error: {err}", file=sys.stderr)
        return 2
    except KeyboardInterrupt:
        print("axlebox: interrupted", file=sys.stderr)
        return 1
    except Exception as err:  # noqa: BLE001 - a failure of the computation, reported in one line
        print(f"axlebox: failed: {type(err).__name__}: {err}", file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
