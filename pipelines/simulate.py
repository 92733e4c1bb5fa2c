"""``axlebox simulate CONFIG.toml``: the metro car on tangent track or on a line's curves
(``[[track.layout]]``), from config to result file.

Steps: validate the config; read (or build at the coarse mesh, cached) the reduced bodies the
config makes flexible; wheel-rail tables; track irregularity; the vehicle; static equilibrium on
the track as it lies under the wheels at t = 0 (no settling transient); the run; the result file
(``format = "axlebox-result"``, :mod:`axlebox.bearing.resultfile`), written through a temporary
name.  A run that diverges still writes what it computed, with ``status`` and ``message``
attributes, and the command exits with status 1.  The outputs stream to ``<out>.stream.d`` while
the run goes (:mod:`.stream`: memory flat in the run's length; a segment file per checkpoint
interval, renamed whole, so no kill tears what a checkpoint counts on); every ``checkpoint_every``
simulated seconds the run's state goes to ``<out>.partial.h5`` (through a temporary name); the same
command run again resumes from the two, to the same bits as a run never stopped.
"""
from __future__ import annotations

import math
import time
import tomllib
import dataclasses
from dataclasses import dataclass
from pathlib import Path

import h5py
import numpy as np

from axlebox import configs
from axlebox._cache import cache_dir
from axlebox._files import tmp_path
from axlebox._progress import Progress
from axlebox._params import ParameterError
from axlebox.bearing import resultfile
from axlebox.fem import bodyfile
from axlebox.mbs.post import comfort, safety
from axlebox.mbs.vehicle import config as vconfig
from axlebox.mbs.vehicle import bearings as car_bearings
from axlebox.mbs.solver import integrate
from axlebox.mbs.track import roughness, irregularity as track
from axlebox.mbs.vehicle import statics, car as vehicle, wheel_defects
from axlebox.mbs.kernel import bearings as kb
from axlebox.mbs.wheelrail import element_kernel as ek
from axlebox.mbs.wheelrail.element import build_tables
from axlebox.mbs.wheelrail.profile import read_profile
from axlebox.mbs.wheelrail.standard import chn60, s1002, uic60

from . import stream
from .ahead import NoAhead, compile_statics, start as start_ahead

def reduced_bodies(cfg: vconfig.CarConfig, log=print) -> dict:
    """The reduced bodies the config needs, each kind from its own file (``bodies.<kind>``, a
    user's body), else from ``bodies.dir``, else built (coarse mesh, by its ``bodies.method_<kind>``)
    into the cache; none when every body is rigid and no file or folder is given.  A file must
    have the interfaces the car attaches to its kind (pipelines/bodies.car_interfaces)."""
    from .bodies import car_interfaces
    b = cfg.bodies
    own = {kind: getattr(b, kind) for kind in vconfig.BODY_KINDS if getattr(b, kind)}
    if not b.dir and not b.flexible and not own:
        return {}
    out = {}
    for kind in vconfig.BODY_KINDS:
        field = f"bodies.{kind}" if kind in own else "bodies.dir"
        if kind in own:
            p = Path(own[kind])
        elif b.dir:
            p = Path(b.dir) / f"{kind}.h5"
        else:
            continue
        if not p.is_file():
            why = "no such file" if kind in own else \
                f"it has no {kind}.h5 (axlebox bodies build --body all --out DIR)"
            raise ParameterError(f"{field} = {str(p if kind in own else b.dir)!r} is not allowed: {why}")
        try:
            out[kind] = bodyfile.read(p, fields=False)
        except bodyfile.BodyFileError as err:
            raise ParameterError(f"{field}: {err}") from None
        lacks = [n for n in car_interfaces(kind) if n not in out[kind].nodes]
        if lacks:
            raise ParameterError(f"{field} = {str(p)!r} is not allowed: the car attaches a {kind} at "
                                 f"{', '.join(lacks)}, which it lacks (it has "
                                 f"{', '.join(out[kind].nodes) or 'no interfaces'})")
        method = getattr(b, f"method_{kind}")
        if out[kind].method != method:
            raise ParameterError(f"bodies.method_{kind} = {method!r} is not allowed with {field}: its "
                                 f"{p.name} is {out[kind].method!r}")
    if len(out) == len(vconfig.BODY_KINDS):
        return out
    from .bodies import BODIES, build_body
    for kind in vconfig.BODY_KINDS:
        if kind in out:
            continue
        method = getattr(b, f"method_{kind}")
        where = cache_dir("bodies", f"coarse-{b.modes}" if method == "craig-bampton" else "coarse-guyan")
        rb, _ = build_body(kind, method=method, mesh_size=BODIES[kind].coarse_mesh_size,
                           n_modes=b.modes if method == "craig-bampton" else None,
                           n_reference=0, out_dir=where, log=log)
        out[kind] = rb
    return out


def _profile(name: str, kind: str):
    builtin = {"wheel": {"S1002": s1002}, "rail": {"UIC60": uic60, "60E1": uic60, "CHN60": chn60}}[kind]
    if name in builtin:
        return builtin[name]()
    if Path(name).is_file():
        return read_profile(name, kind=kind)
    raise ParameterError(f"wheelrail.{kind} = {name!r} is not allowed: expected "
                         f"{' or '.join(builtin)} or a profile file")


def tables(cfg: vconfig.CarConfig):
    w = cfg.wheelrail
    return build_tables(_profile(w.wheel, "wheel"), _profile(w.rail, "rail"), cfg.layout(),
                        cfg.wheelrail_params())


def _contact_load(cfg: vconfig.CarConfig):
    """The contact filter's load: the static wheel load, when ``track.contact_filter``."""
    return vehicle.static_wheel_load(cfg) if cfg.track.contact_filter else None


def track_record(cfg: vconfig.CarConfig):
    p = cfg.irregularity(_contact_load(cfg) or 0.0)
    return None if p is None else track.generate(p)


def wheel_records(cfg: vconfig.CarConfig, names) -> dict:
    """Each wheel's radius deviation record ``(values, slopes, ds)`` around its rolling circle:
    its roughness (mbs/track/roughness.py; independent random phases per wheel from the run's seed)
    plus its ``[[wheel_defects]]`` (mbs/vehicle/wheel_defects.py), on one grid (a roughness grid, or
    0.25 mm); only the wheels that have either."""
    t, r0 = cfg.track, cfg.wheelset.r0
    rough = t.wheel_roughness != "none"
    mine = {name: [d for d in cfg.wheel_defects if f"ws{d.wheelset}_{d.side}" == name]
            for name in names}
    if not rough and not any(mine.values()):
        return {}
    C = 2 * math.pi * r0
    n = roughness.wheel_grid(r0, t.roughness_lambda_min) if rough else 2 * math.ceil(C / 0.25e-3 / 2)
    s = np.arange(n) * (C / n)
    load = _contact_load(cfg)
    seeds = np.random.SeedSequence([int(cfg.run.seed), 1]).spawn(len(names))
    out = {}
    for name, sq in zip(names, seeds):
        if not rough and not mine[name]:
            continue
        v, d = np.zeros(n), np.zeros(n)
        if rough:
            v, d, _ = roughness.wheel_record(t.wheel_roughness, r0, t.roughness_lambda_min,
                                             load, np.random.default_rng(sq), n=n)
        for e in mine[name]:
            if e.kind == "flat":
                dv, dd = wheel_defects.flat(s, e.length, r0, r0 * math.radians(e.angle_deg), e.shape)
            else:
                dv, dd = wheel_defects.polygon(s, r0, list(e.orders), 1e-6 * np.asarray(e.amplitudes_um),
                                               np.radians(e.phases_deg) if e.phases_deg else None)
            v, d = v + dv, d + dd
        out[name] = (v, d, C / n)
    return out


def _car(cfg, tabs, trk, red, bearings=None):
    """The car's system with its wheels' roughness, assembled."""
    s = vehicle.build(cfg, tabs, trk, red, bearings=bearings)
    s.wheel_records = wheel_records(cfg, [w[0] for w in s.wheels])
    return s.assemble()


def build_model(cfg: vconfig.CarConfig, log=print, ahead=None):
    """Vehicle model in static equilibrium: (model, y0).  With ``joint.model = "bearing"`` the
    equilibrium is found with row bushings first, then the bearings are put in their own
    (mbs/vehicle/bearings.py).  ``ahead``: a process compiling the kernels ahead
    (:mod:`.ahead`), waited for before each step that needs its work."""
    ahead = ahead or NoAhead()
    red = reduced_bodies(cfg, log)
    tabs, trk = tables(cfg), track_record(cfg)
    model = _car(cfg, tabs, trk, red)
    log(f"vehicle: {len(model.bodies)} bodies, {model.n_states} states, flexible: "
        + ", ".join(f"{b.name} ({b.n_modes} modes)" for b in model.bodies if b.n_modes))
    if ahead.take("statics"):
        compile_statics(model)
    else:
        ahead.wait("statics")
    ahead.go()                  # the statics' kernels are in the cache: the run's may compile
    y0 = statics.equilibrium(model, log=log)
    if not cfg.has_bearings:
        return model, y0
    ahead.wait("bearings")
    ws = model.body_state(model.system.index("ws1"), y0)
    loads = {key: F for key, F in car_bearings.joint_loads(model, y0).items()
             if key[0] in cfg.joint.wheelsets}        # the rest stay on row bushings
    starts = car_bearings.start(cfg, loads, float(ws["omega"][1]), log)
    model = _car(cfg, tabs, trk, red, bearings={k: (v.tag, v.P, v.D, v.y0) for k, v in starts.items()})
    y0 = car_bearings.place_axleboxes(model, y0, starts)
    if cfg.coupling.hold == "jacobian":
        model.bearing_stiffness = car_bearings.stiffness(cfg, loads, model.bearing_names)
    log(f"coupled: {model.n_states} states ({model.n_states - model.n_body_states} in "
        f"{len(model.bearing_names)} bearings)")
    return model, y0


def shafts(run: integrate.Run, model, block: int = 4096) -> dict:
    """``ws<k>/angle`` (rad, 0 at the first output, increasing as the car runs forwards) and
    ``ws<k>/speed`` (rad/s) of each wheelset at the output instants: the cubic Hermite through
    the state snapshots' spin angle and spin rate (exact for a spin angle cubic in time between
    snapshots, so for a constant acceleration), read a block of snapshots at a time."""
    from scipy.interpolate import CubicHermiteSpline

    from axlebox.mbs.kernel.body import BI_POS, BI_VEL, SPIN_ANGLE, SPIN_RATE
    ks = [k for k, b in enumerate(model.bodies) if b.spin]          # the wheelsets
    if not ks or run.time.size == 0 or len(run.state_time) < 2:
        return {}
    bi = model.S.bi
    cols = [c for k in ks for c in (int(bi[k, BI_POS]) + SPIN_ANGLE, int(bi[k, BI_VEL]) + SPIN_RATE)]
    n = len(run.state_time)
    read = run.states.rows if hasattr(run.states, "rows") else (lambda r0, r1: run.states[r0:r1])
    Y = np.concatenate([np.asarray(read(r0, min(r0 + block, n)))[:, cols] for r0 in range(0, n, block)])
    out = {}
    for j, k in enumerate(ks):
        beta, w = Y[:, 2 * j], Y[:, 2 * j + 1]
        sign = -1.0 if np.mean(w) < 0 else 1.0          # the spin's sign as the wheels roll forwards
        h = CubicHermiteSpline(np.asarray(run.state_time), sign * beta, sign * w)
        name = model.bodies[k].name
        out[f"{name}/angle"] = (h(run.time) - h(run.time[0]),
                                {"unit": "rad", "from": "the state snapshots' spin (cubic Hermite)"})
        out[f"{name}/speed"] = (h(run.time, 1), {"unit": "rad/s"})
    return out


def drives(run: integrate.Run, model) -> dict:
    """``<drive>/torque`` (N m, about the axle, on the wheelset; its reaction on the gearbox or
    the bogie frame) and ``<drive>/force`` (N, the tractive force the profile asks of the
    wheelset's share of the car) of each wheelset's drive at the output instants, a run along a
    speed profile's (:class:`axlebox.mbs.solver.elements.Drive`; none at a constant speed)."""
    from axlebox.mbs.solver.elements import Drive
    out = {}
    for i, e in enumerate(model.system.elements):
        if isinstance(e, Drive) and e.radius > 0 and run.elements is not None:
            on = model.bodies[model.system.markers[e.m1][0]].name
            out[f"{e.name}/torque"] = (run.elements[:, i, 0], {"unit": "N m", "on": on,
                                                               "about": "the axle"})
            out[f"{e.name}/force"] = (run.elements[:, i, 1], {"unit": "N"})
    return out


def running_safety(run: integrate.Run, model, cfg: vconfig.CarConfig) -> dict:
    """``<wheel>/YQ`` (columns Y, Q, Y/Q and its 2 m sliding mean, with Nadal's limit at the wheel
    profile's flange angle and ``wheelrail.mu``) and ``ws<k>/sum_Y`` (the wheelset's net lateral
    force on the track and its 2 m sliding mean, with Prud'homme's limit at the static wheel
    load) at the output instants (:mod:`axlebox.mbs.post.safety`).  The distance each is
    averaged over is its contact point's x, the distance its wheel has run."""
    from axlebox.mbs.kernel.wheels import WH_SIDE
    if run.time.size == 0 or run.wheels is None:
        return {}
    delta = safety.flange_angle(_profile(cfg.wheelrail.wheel, "wheel"))
    nadal = float(safety.nadal(delta, cfg.wheelrail.mu))
    Q0 = vehicle.static_wheel_load(cfg)
    # the columns needed, in one pass over a streamed run's outputs (not a pass a wheel)
    cols = np.asarray(run.wheels[:, :, [ek.OUT_F, ek.OUT_F + 1, ek.OUT_F + 2, ek.OUT_P]])
    out, of_wheel = {}, []
    for i, name in enumerate(model.wheel_names):
        F = cols[:, i, :3]
        dist = np.maximum.accumulate(cols[:, i, 3])               # never back: a record's distance
        of_wheel.append((F, dist))
        w = safety.wheel_forces(F, 1 if model.S.wh_i[i, WH_SIDE] == 0 else -1, dist)
        out[f"{name}/YQ"] = (np.stack(w, axis=1), {
            "unit": "N, N, 1, 1", "columns": "Y, Q, Y/Q, Y/Q 2 m sliding mean",
            "nadal_limit": nadal, "flange_angle_rad": delta, "mu": cfg.wheelrail.mu,
            "about": "Y on the rail towards its field side, Q on the rail downwards (Nadal; EN 14363)"})
    for b, (iL, iR) in _wheelsets(model).items():
        (FL, sL), (FR, sR) = of_wheel[iL], of_wheel[iR]
        sY = safety.sum_Y(FL, FR)
        both = np.stack([sY, safety.sliding_mean(sY, 0.5 * (sL + sR))], axis=1)
        out[f"{model.bodies[b].name}/sum_Y"] = (both, {
            "unit": "N", "columns": "sum Y, its 2 m sliding mean",
            "prudhomme_limit_N": float(safety.prudhomme(Q0)), "static_wheel_load_N": Q0,
            "about": "the wheelset's lateral force on the track, track y (Prud'homme; EN 14363)"})
    return out


def _wheelsets(model) -> dict:
    """The bodies with a left and a right wheel (the wheelsets): body index -> (left wheel's
    index, right wheel's)."""
    from axlebox.mbs.kernel.wheels import WH_BODY, WH_SIDE
    by_body: dict = {}
    for i in range(len(model.wheel_names)):
        by_body.setdefault(int(model.S.wh_i[i, WH_BODY]), {})[int(model.S.wh_i[i, WH_SIDE])] = i
    return {b: (w[0], w[1]) for b, w in by_body.items() if len(w) == 2}


def wheelset_attitude(run: integrate.Run, model) -> dict:
    """``ws<k>/attitude`` of each wheelset at the output instants: its lateral displacement on
    the track (m, track y: the mean of its two wheel centres' places in their track frames, so
    0 centred between the rails) and its angle of attack (rad, the axle's yaw against the track
    frame about z, the mean of its two wheels'; positive turns the axle's left end back: in a
    left-hand curve a leading wheelset whose flange runs into the outer rail yaws negative), from
    the wheels' outputs (:mod:`axlebox.mbs.kernel.wheels` ``WO_YC``, ``WO_YAW``)."""
    from axlebox.mbs.kernel.wheels import WO_YAW, WO_YC
    if run.time.size == 0 or run.wheels is None:
        return {}
    cols = np.asarray(run.wheels[:, :, [WO_YC, WO_YAW]])
    return {f"{model.bodies[b].name}/attitude": (cols[:, list(pair)].mean(1), {
                "unit": "m, rad", "columns": "lateral displacement, angle of attack",
                "about": "on the track frame at the contacts: y to the left, yaw about z"})
            for b, pair in _wheelsets(model).items()}


def write(path, run: integrate.Run, model, cfg: vconfig.CarConfig,
          ride: list[comfort.RideComfort] = ()) -> Path:
    """The result file, its config stored whole (every default filled in); ``ride``: the
    carbody's comfort indices, group ``comfort`` (one (6,) dataset a floor sensor, columns
    :attr:`comfort.RideComfort.COLUMNS`)."""
    fs = 1.0 / np.median(np.diff(run.time)) if run.time.size > 1 else 0.0
    signals = {name: {"acceleration": acc} for name, acc in run.sensors.items()}
    wr = {}
    for i, name in enumerate(model.wheel_names):
        o = run.wheels[:, i]
        wr[f"{name}/force"] = (o[:, ek.OUT_F:ek.OUT_F + 3], {"unit": "N", "frame": "track, on the wheel"})
        wr[f"{name}/normal"] = (o[:, ek.OUT_N], {"unit": "N", "note": "the most loaded contact's"})
        wr[f"{name}/region_normal"] = (o[:, ek.OUT_NPT:ek.OUT_NPT + ek.NPT],
                                       {"unit": "N", "columns": "tread, flange root, flange"})
        wr[f"{name}/region_angle"] = (o[:, ek.OUT_DPT:ek.OUT_DPT + ek.NPT],
                                      {"unit": "rad", "columns": "tread, flange root, flange"})
        wr[f"{name}/creepage"] = (o[:, [ek.OUT_XI, ek.OUT_ETA, ek.OUT_SPIN]],
                                  {"unit": "1, 1, 1/m", "columns": "xi, eta, spin"})
        wr[f"{name}/contact_point"] = (o[:, ek.OUT_P:ek.OUT_P + 3], {"unit": "m"})
    wr.update(running_safety(run, model, cfg))
    wr.update(wheelset_attitude(run, model))
    br = {}
    for i, name in enumerate(model.bearing_names):
        o = run.bearings[:, i]                      # mbs/kernel/bearings.py BR_ROWS
        rows = f"row 1, row {model.bearing_rows}"
        br[f"{name}/ring_loads"] = (o[:, [kb.BR_INNER, kb.BR_OUTER]],
                                    {"unit": "N, N m", "frame": "track", "rows": "inner ring, outer ring",
                                     "columns": "Fx Fy Fz Mx My Mz"})
        br[f"{name}/roller1_cup_force"] = (o[:, kb.BR_MORE, [kb.BR_Q1, kb.BR_QN]],
                                           {"unit": "N", "columns": rows})
        br[f"{name}/cage"] = (o[:, kb.BR_MORE, kb.BR_ANGLE:kb.BR_RATE + 2],
                              {"unit": "rad, rad, rad/s, rad/s", "columns": f"angle {rows}; rate {rows}"})
        br[f"{name}/row_loads"] = (o[:, kb.BR_ROW], {
            "unit": "N, N, N, N, rad, rad",
            "columns": f"axial {rows}; radial {rows}; load zone centre {rows}",
            "about": "each row's rollers' load on the outer ring, track frame: axial along y (to "
                     "the left), radial in x-z, the load zone's centre atan2(F_x, F_z) from the top "
                     "towards the front; at the exchange's last evaluation",
            "wheelset": model.bodies[int(model.B.idx[i, kb.BR_BODY])].name})
    dr = drives(run, model)
    ride_attrs = {"columns": ", ".join(comfort.RideComfort.COLUMNS), "unit": "1, 1, 1, m/s^2, m/s^2, "
                  "m/s^2", "standards": "Sperling (W_z, W_y); EN 12299:2009 6.7.2 (N_MV: W_d on x, y, "
                  "W_b on z; 95th percentile of 5 s r.m.s.)"}
    cm = {rc.sensor: (rc.values(), {**ride_attrs, "record_s": rc.duration_s, "windows": rc.windows})
          for rc in ride}
    groups = {"wheelrail": wr,
              **({"bearings": br} if br else {}),
              **({"comfort": cm} if cm else {}),
              **({"shafts": sh} if (sh := shafts(run, model)) else {}),
              **({"drives": dr} if dr else {}),
              "states": {"time": run.state_time, "y": run.states,
                         "y_end": (run.y_end, {"t": float(run.time[-1]) if run.time.size else 0.0})}}
    return resultfile.write(path, config_toml=cfg.to_toml(), seed=cfg.run.seed, time=run.time, fs_hz=fs,
                            signals=signals, groups=groups,
                            attrs={"status": run.status, "message": run.message, "wall_s": run.wall_s,
                                   "bodies": ",".join(b.name for b in model.bodies)})


@dataclass(frozen=True)
class Config:
    """A car's config as TOML text in memory, as :func:`run` takes it instead of a file:
    ``text`` and ``name`` (what a refusal calls it)."""
    text: str
    name: str = "config text"


def load_config(config_path, duration: float | None = None,
                overrides: dict | None = None) -> vconfig.CarConfig:
    """The config that will run: ``config_path`` (a TOML file, the name of a shipped config
    (:mod:`axlebox.configs`), a :class:`Config` or a :class:`~axlebox.mbs.vehicle.config.CarConfig`)
    with ``overrides`` (section -> {field: value}, or a list of entries for ``defects`` /
    ``wheel_defects``) and ``duration`` replacing its fields."""
    if isinstance(config_path, vconfig.CarConfig):
        cfg = config_path
    elif isinstance(config_path, Config):
        cfg = vconfig.loads(config_path.text, config_path.name)
    else:
        cfg = vconfig.load(configs.resolve(config_path))
    changes = dict(overrides or {})
    if duration is not None:
        changes["run"] = {**changes.get("run", {}), "duration": duration}
    return cfg.replace(**changes) if changes else cfg


def _changed(old_text: str, new_text: str) -> list[str]:
    """``section.field: old -> new`` for every field two configs' TOML texts set differently."""
    def flat(d, pre=""):
        out = {}
        for k, v in d.items():
            if isinstance(v, dict):
                out.update(flat(v, f"{pre}{k}."))
            else:
                out[f"{pre}{k}"] = v
        return out
    try:
        a, b = flat(tomllib.loads(old_text)), flat(tomllib.loads(new_text))
    except tomllib.TOMLDecodeError:
        return ["the checkpoint's config (unreadable)"]
    return [f"{k}: {a.get(k, '(unset)')!r} -> {b.get(k, '(unset)')!r}"
            for k in sorted(set(a) | set(b)) if a.get(k) != b.get(k)] or ["the config's text"]


def partial_path(out) -> Path:
    """The checkpoint of a run writing ``out``: ``<out>.partial.h5``."""
    return Path(str(out) + ".partial.h5")


def read_checkpoint(path: Path, text: str) -> dict:
    """The snapshot in ``path`` (:func:`axlebox.mbs.solver.integrate.simulate`'s ``resume``), or a
    ParameterError naming what changed when it was made by another config."""
    try:
        with h5py.File(path, "r") as f:
            old = str(f.attrs.get("config", ""))
            if old != text:
                changed = _changed(old, text)
                raise ParameterError(
                    f"checkpoint {str(path)!r} was made by another config ({'; '.join(changed[:3])}"
                    f"{' ...' if len(changed) > 3 else ''}): run the same config to resume, or "
                    "--restart to start over")
            return {"k": int(f.attrs["k"]), "wall_s": float(f.attrs["wall_s"]), "y": f["y"][()],
                    "exchange": f["exchange"][()]}
    except (OSError, KeyError) as err:
        raise ParameterError(f"checkpoint {str(path)!r} is not readable ({err}): --restart to "
                             "start over") from None


def write_checkpoint(path: Path, text: str, snap: dict) -> None:
    """The snapshot to ``path``, through a temporary name (a kill leaves the last one whole): the
    config, the outputs done, the state and the bearings' ring motion at the last exchange
    (mbs/kernel/exchange.py); the outputs themselves are in the stream (:mod:`.stream`)."""
    resultfile.write_checkpoint(path, {"config": text, "k": snap["k"], "wall_s": snap["wall_s"]},
                                {"y": snap["y"], "exchange": snap["exchange"]})


def run(config_path, out, duration: float | None = None, log=print,
        overrides: dict | None = None, checkpoint_every: float | None = None,
        restart: bool = False, ahead=False) -> integrate.Run:
    """The whole command; ``config_path``: a file, a shipped config's name or a :class:`Config`
    (in memory: the sweep's cases).  The outputs stream to ``<out>.stream.d`` while the run
    goes (memory flat in its length; :mod:`.stream`), the result is made from it at the end.
    ``checkpoint_every`` (simulated s, 0: none; None: 1 s): snapshots of the state to
    ``<out>.partial.h5``; a rerun of the same config resumes
    from it and the stream and gives the same file as an uninterrupted run; another config is
    refused (exit 2, naming what changed) unless ``restart``.  Returns the run's status, wall
    time, recorded time and sensors; its wheel-rail, bearing and state outputs are in the file
    only (copied to it from the stream a block at a time).  ``ahead``: compile the kernels in a
    second process meanwhile where numba's cache lacks them (True; :mod:`.ahead`), or that
    process, started by the caller."""
    cfg = load_config(config_path, duration, overrides)
    text = cfg.to_toml()
    out = Path(out)
    if checkpoint_every is None:
        checkpoint_every = 1.0          # a checkpoint is the state alone: cheap at any length
    if not out.parent.is_dir():
        raise FileNotFoundError(f"--out: folder {str(out.parent)!r} does not exist")
    if not (math.isfinite(checkpoint_every) and checkpoint_every >= 0):
        raise ParameterError(f"--checkpoint-every = {checkpoint_every!r} is not allowed: expected "
                             "a simulated time >= 0 s (0: no checkpoints)")
    partial, streamed = partial_path(out), stream.stream_path(out)
    tmp_path(partial).unlink(missing_ok=True)                            # a kill mid-write
    resume = None
    if partial.is_file():
        if restart:
            partial.unlink()
        else:
            resume = read_checkpoint(partial, text)
            if not streamed.is_dir():       # (an earlier version's was one file, <out>.stream.h5)
                raise ParameterError(f"checkpoint {str(partial)!r} has no stream {str(streamed)!r} "
                                     "(made by an earlier version?): --restart to start over")
    s = cfg.settings()
    t0 = time.perf_counter()
    ahead = start_ahead(cfg) if ahead is True else ahead or NoAhead()
    try:
        model, y0 = build_model(cfg, log, ahead)
        ahead.wait("run")
    finally:
        ahead.close()
    log(f"model ready in {time.perf_counter() - t0:.1f} s; running {cfg.run.duration:g} s "
        f"({s.method}, dt {s.dt:g} s)" + (f", resuming at {resume['k'] / s.output_rate_hz:g} s from {partial}"
                                          if resume else ""))

    progress = Progress("simulating", cfg.run.duration)
    sink = stream.Stream(streamed, model, s.state_every, None if resume is None else resume["k"],
                         every=stream.kept_every(s, cfg.sensors))

    def checkpoint(snap):               # the outputs committed first: a checkpoint's are all whole
        sink.commit(snap["k"])
        write_checkpoint(partial, text, snap)
    try:
        res = integrate.simulate(model, cfg.run.duration, s, y0=y0, progress=progress,
                                 checkpoint=checkpoint,
                                 checkpoint_every=checkpoint_every if checkpoint_every > 0 else math.inf,
                                 resume=resume, sink=sink.append)
    finally:
        sink.close()
        progress.close()
    with stream.finished(streamed, res, model, s, cfg.sensors) as rec:   # as the acquisition records it
        ride = comfort.floor_comfort(rec.time, rec.sensors, model.system.track_ramp)   # fade-in left out
        write(out, rec, model, cfg, ride)
        # what the caller gets: the recorded time and sensors; the rest is in the file
        res = dataclasses.replace(rec, wheels=None, elements=None, bearings=None, states=None)
    partial.unlink(missing_ok=True)
    stream.remove(streamed)
    T = res.time[-1] if res.time.size else 0.0
    log(f"wrote {out}: {T:g} s simulated in {res.wall_s:.1f} s wall ({T / max(res.wall_s, 1e-9):.3f} "
        f"simulated s per wall s)")
    for rc in ride:
        log("ride comfort, " + rc.summary())
    if cfg.segments and res.time.size:
        from .curving import summary, table as curving_table
        log(summary(curving_table(out)))
    if cfg.has_bearings:
        from .cageslip import cage_slip, table
        log(table(cage_slip(out)))
    return res
