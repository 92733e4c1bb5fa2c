"""The car's run configuration: each section declared once, the whole config, its checks, its file.

Each ``[section]`` of the TOML file is a frozen dataclass here (:func:`axlebox._params.section`):
every field's type, default, allowed range or choices, unit and one-line meaning are declared
once, in the field.  Where the code below the config takes the same quantity (the integrator's
:class:`~axlebox.mbs.solver.integrate.Settings`, the track's
:class:`~axlebox.mbs.track.irregularity.IrregularityParams`, the track bed's
:class:`~axlebox.mbs.track.bed.Seats`, the wheel-rail
:class:`~axlebox.mbs.wheelrail.geometry.TrackLayout` and
:class:`~axlebox.mbs.wheelrail.element.WheelRailParams`), the section's field is that class's
field again (:func:`~axlebox._params.like`), so a default cannot differ between the two.  The
config reference (docs) is generated from these declarations
(:mod:`axlebox.pipelines.config_reference`).

:class:`CarConfig` is the whole config: the sections, the bearing model's parameters and the
defects; its cross-field checks run once, on construction, and build the classes the run uses
(their own checks included).  :meth:`CarConfig.to_toml` writes it with every default filled in
(what a result file stores); :func:`loads` / :func:`load` read a file through
:func:`validate`.  An unknown section or field, a value of the wrong type or out of range is
refused with :class:`~axlebox._params.ParameterError` naming ``section.field``, the value and
what is allowed (the CLI turns it into one line and exit status 2).
"""
from __future__ import annotations

import dataclasses
import math
import tomllib
from dataclasses import dataclass, field
from pathlib import Path

import tomli_w

from axlebox._params import (ParameterError, choice, flag, from_table, like, members, numbers, param,
                             rows, section, text, vector, kinded_from_table)
from axlebox._params import check_ranges as _check_fields
from axlebox.bearing import models
from axlebox.bearing.defects import Defect
from axlebox.mbs.solver.integrate import Settings
from axlebox.mbs.vehicle.speed import SpeedProfile
from axlebox.mbs.track.irregularity import IrregularityParams
from axlebox.mbs.track.bed import MODELS as TRACK_MODELS
from axlebox.mbs.track.bed import Seats
from axlebox.mbs.track.line import G, Line, Segment, cant_deficiency
from axlebox.mbs.wheelrail.element import WheelRailParams
from axlebox.mbs.wheelrail.geometry import TrackLayout

BODY_NAMES = (["carbody", "frame1", "frame2"] + [f"ws{i}" for i in range(1, 5)]
              + [f"ab{i}{s}" for i in range(1, 5) for s in "LR"] + [f"gb{i}" for i in range(1, 5)])
# the bodies that have a reduced (FE) body to be flexible with: frames, wheelsets, axle-boxes
FLEXIBLE_NAMES = tuple(n for n in BODY_NAMES if not n.startswith(("carbody", "gb")))
BODY_KINDS = ("wheelset", "axlebox", "frame")
SIDES = ("L", "R")
@section("run")
class Run:
    """What is run: how long and how fast."""

    duration: float = param(5.0, 1e-4, 10000.0, "s", "simulated time; the track must be long enough "
                            "(track.length)")
    speed_kmh: float = param(48.0, 1.0, 200.0, "km/h", "vehicle speed, in km/h by name (the run's speeds "
                             "are the fields not in SI); with a profile its speed at t = 0")
    profile: tuple = rows((), (("time", 0.0, 10000.0, "s"), ("speed", 1.0, 200.0, "km/h")),
                          "speed profile: points (time, speed), the first at 0 s and speed_kmh, times "
                          "increasing; constant acceleration between points, the last speed held "
                          "(mbs/vehicle/speed.py); traction and braking torques at the wheelsets drive the "
                          "car along it (mbs/vehicle/car.py); empty: the constant speed_kmh")
    seed: int = like(IrregularityParams, "seed", doc="seed of the track irregularity's random phases and "
                     "the wheels' roughness")


@section("integrator")
class Integrator:
    """The car's time integrator (mbs/solver/integrate.py)."""

    method: str = like(Settings, "method", doc="'leapfrog' (explicit central differences), 'imex' / "
                       "'imex2' (the leapfrog with the bearings' contact damping / stiffness implicit), "
                       "'rk4' or 'galpha' (generalized-alpha); with bearings (joint.model) one their "
                       "model accepts (bearing/models/__init__.py methods; the config reference lists them)")
    dt: float = like(Settings, "dt", doc="fixed step, dividing 1/output_rate_hz; with bearings and a "
                     "leapfrog method their sub-step; with bearings (joint.model) at most their model's "
                     "step for the method (s, as under method)")
    output_rate_hz: float = like(Settings, "output_rate_hz", doc="sensor output rate (the field system's 10 "
                                 "kHz); with sensors.model = 'accelerometer' a whole multiple >= 2 of "
                                 "sensors.fs_hz")
    state_rate_hz: float = like(Settings, "state_rate_hz", doc="rate of whole-state snapshots")
    rho_inf: float = like(Settings, "rho_inf", doc="generalized-alpha spectral radius at infinity (method "
                          "'galpha' only)")


@section("coupling")
class Coupling:
    """The bodies' step and their exchange with the DTRB bearings (mbs/kernel/exchange.py)."""

    exchange_dt: float = like(Settings, "exchange_dt", doc="the bodies' step and their exchange with the "
                              "DTRBs, a whole multiple of integrator.dt (then the bearings' sub-step); 0: "
                              "integrator.dt; other than integrator.dt with the leapfrog methods only")
    body_substeps: int = like(Settings, "body_substeps", doc="the bodies' steps per exchange, the bearings' "
                              "loads held between (the paper's co-simulation arrangement); 1: one; > 1 "
                              "needs exchange_dt > 0")
    hold: str = like(Settings, "hold", doc="how the loads are held between exchanges: 'zoh' (constant), "
                     "'linear' (extrapolated) or 'jacobian' (plus the bearings' tangent stiffness times the "
                     "rings' displacement, Kuebler and Schiehlen 2000)")


@section("track")
class Track:
    """Track irregularity (FRA spectra, mbs/track/irregularity.py), roughness
    (mbs/track/roughness.py) and the track under each wheel (mbs/track/bed.py; the ballasted seats
    per rail seat, assumed: Zhai, Wang and Lin, J. Sound Vib. 270 (2004) 673-683, 60 kg/m rail, as
    tabulated by the open TTB-2D model)."""

    fra_class: int = like(IrregularityParams, "grade", doc="American (FRA) track class of the irregularity, "
                          "1 (worst) to 6 (best)")
    lambda_min: float = like(IrregularityParams, "lambda_min", doc="shortest irregularity wavelength; below "
                             "lambda_max")
    lambda_max: float = like(IrregularityParams, "lambda_max", doc="longest irregularity wavelength")
    length: float = like(IrregularityParams, "length", doc="periodic irregularity record; with irregularity "
                         "at least the distance run plus the car (geometry.bogie_distance + 5 m)")
    irregularity: bool = flag(True, "false: smooth track (then rail_roughness must be 'none')")
    rail_roughness: str = choice("none", ["none", "iso3095", "network"], "short-wave rail roughness: "
                                 "'iso3095' (the ISO 3095:2013 limit) or 'network' (CNOSSOS-EU's average "
                                 "network); 'none': none")
    wheel_roughness: str = choice("none", ["none", "cast-iron", "composite", "disc"],
                                  "each wheel's roughness by brake: 'cast-iron' or 'composite' brake "
                                  "blocks, or 'disc'; 'none': none")
    contact_filter: bool = flag(True, "the CNOSSOS-EU contact filter of the roughness at the static wheel "
                                "load")
    roughness_lambda_min: float = like(IrregularityParams, "roughness_lambda_min", doc=
                                       "shortest roughness wavelength (3 mm: 4.4 kHz at 48 km/h)")
    model: str = choice("rigid", TRACK_MODELS, "the track under each wheel: 'rigid' rails (the "
                        "paper's car, its calibration and field cases) or 'ballasted' (rail, sleeper and "
                        "ballast lumped under each wheel)")
    rail_mass: float = like(Seats, "rail_mass")
    rail_EI: float = like(Seats, "rail_EI")
    sleeper_spacing: float = like(Seats, "sleeper_spacing")
    pad_k: float = like(Seats, "pad_k")
    pad_c: float = like(Seats, "pad_c")
    start: float = param(0.0, 0.0, 1e6, "m", "with [[track.layout]]: where on the line (chainage "
                         "from its start) the front bogie's centre starts; the rear bogie's wheels "
                         "must be on the line too")
    sleeper_mass: float = like(Seats, "sleeper_mass")
    ballast_mass: float = like(Seats, "ballast_mass")
    ballast_k: float = like(Seats, "ballast_k")
    ballast_c: float = like(Seats, "ballast_c")
    subgrade_k: float = like(Seats, "subgrade_k")
    subgrade_c: float = like(Seats, "subgrade_c")


@section("wheelrail")
class WheelRail:
    """Wheel and rail profiles, their layout and the contact (mbs/wheelrail)."""

    wheel: str = text("S1002", "wheel profile: 'S1002' (built in, a stand-in for the LM profile) or a "
                      "profile file")
    rail: str = text("UIC60", "rail profile: 'UIC60' (60E1), '60E1' or 'CHN60' (built in) or a profile file")
    gauge: float = like(TrackLayout, "gauge", doc="track gauge")
    back_to_back: float = like(TrackLayout, "back_to_back", doc="distance between the wheels' back faces "
                               "(the S1002/60E1 standard pair; the LM wheelset's is 1.353 m)")
    cant: float = like(TrackLayout, "cant", doc="rail inclination, the tan of the cant angle (0.025: 1:40)")
    mu: float = like(WheelRailParams, "mu", doc="wheel-rail friction coefficient")
    law: str = like(WheelRailParams, "law", doc="creep force law: 'fastsim' (Kalker's FASTSIM), 'kalker' "
                    "(linear) or 'she' (Shen-Hedrick-Elkins)")
    fastsim_grid: int = like(WheelRailParams, "nx", doc="FASTSIM elements per semi-axis of the contact patch")
    fastsim_update: str = like(WheelRailParams, "update", doc="FASTSIM slip step: 'cutback' (Kalker's, "
                               "continuous in the creepages, as the implicit Newton needs) or 'rotate' "
                               "(second order, jumps at stick-slip changes)")
    smooth_y: float = like(WheelRailParams, "smooth_y", doc="lateral displacement the contact tables are "
                           "smoothed over (the tread contact jump of S1002 on 60E1 1:40); 0: exact tables")
    split_angle: float = like(WheelRailParams, "split_angle", doc="contact-angle jump of the single-point "
                              "contact that parts two contact regions of a wheel (tread, flange root, "
                              "flange: multi-point contact); one larger than the profiles' jumps gives "
                              "one region, the single-point contact")
    y_field: float = like(WheelRailParams, "y_field", doc="reach of each wheel's contact table beyond "
                          "the rigid wheelset's lateral range on its own field side (a gauge opening "
                          "under a wheelset held against a curve's outer rail)")


@section("bodies")
class Bodies:
    """The reduced (flexible) bodies: where they come from and what they keep."""

    dir: str = text("", "folder of reduced-body files (axlebox bodies build); empty: built at the coarse "
                    "mesh into the cache")
    wheelset: str = text("", "a reduced-body file for the wheelsets, your own (axlebox bodies build "
                         "--geometry|--mesh FILE --spec SPEC; its interfaces named as the built-in "
                         "wheelset's: journal_L_row1 ... tread_R, gear); empty: from dir or built")
    axlebox: str = text("", "a reduced-body file for the axle boxes, your own (its interfaces bore_row1, "
                        "bore_row2, spring_front, spring_rear, sensor_pad); empty: from dir or built")
    frame: str = text("", "a reduced-body file for the bogie frames, your own (its interfaces "
                      "primary_1_L ... primary_2_R, secondary_L, secondary_R, traction_centre); empty: "
                      "from dir or built")
    modes: int = param(12, 1, 100, "-", "Craig-Bampton fixed-interface modes when the bodies are built here "
                       "(not with dir)")
    fmax_wheelset_hz: float = param(1500.0, 1.0, 1e5, "Hz", "a flexible wheelset keeps its free-free modes "
                                    "below this (up past its second bending pair and the 300-800 Hz band); "
                                    "the stiffest kept mode sets the explicit step")
    fmax_axlebox_hz: float = param(2500.0, 1.0, 1e5, "Hz", "a flexible axle-box keeps its free-free modes "
                                   "below this (its lowest modes); the stiffest kept mode sets the explicit "
                                   "step")
    fmax_frame_hz: float = param(600.0, 1.0, 1e5, "Hz", "a flexible frame keeps its free-free modes below "
                                 "this (the frame's own modes); the stiffest kept mode sets the explicit "
                                 "step")
    method_wheelset: str = choice("craig-bampton", ["craig-bampton", "guyan"], "reduction of the wheelset "
                                  "body: Craig-Bampton or Guyan; must match the file in dir")
    method_axlebox: str = choice("craig-bampton", ["craig-bampton", "guyan"], "reduction of the axle-box "
                                 "body: Craig-Bampton or Guyan; must match the file in dir")
    method_frame: str = choice("craig-bampton", ["craig-bampton", "guyan"], "reduction of the frame body: "
                               "Craig-Bampton or Guyan; must match the file in dir")
    zeta_wheelset: float = param(0.01, 0.0, 0.5, "-", "modal damping ratio of a flexible wheelset's modes "
                                 "(replaces the file's)")
    zeta_axlebox: float = param(0.01, 0.0, 0.5, "-", "modal damping ratio of a flexible axle-box's modes "
                                "(replaces the file's)")
    zeta_frame: float = param(0.01, 0.0, 0.5, "-", "modal damping ratio of a flexible frame's modes "
                              "(replaces the file's)")
    flexible: tuple = members(["frame1", "ws1", "ws2", "ab1L", "ab1R", "ab2L", "ab2R"], FLEXIBLE_NAMES,
                              "the bodies made flexible (default: the front bogie); the others are rigid "
                              "with the same FE mass properties; frames, wheelsets and axle-boxes only (the "
                              "carbody and gearboxes have no FE body)", at_least=0)

    def __post_init__(self):
        for v in self.flexible if isinstance(self.flexible, tuple) else ():
            if v not in FLEXIBLE_NAMES:
                what = "has no FE body to be flexible with" if v in BODY_NAMES else "is not a body"
                raise ParameterError(f"bodies.flexible = {list(self.flexible)!r} is not allowed: {v!r} "
                                     f"{what} (expected names from: {', '.join(FLEXIBLE_NAMES)})")
        _check_fields(self)


@section("carbody")
class Carbody:
    """The carbody, rigid (Hangzhou Metro Line 1 B-type motor car, Math. Probl. Eng. 2020, 1584624, Table
    6)."""

    mass: float = param(37400.0, 1.0, 1e6, "kg", "carbody mass, rated load")
    inertia: tuple = vector((35300.0, 1.447e6, 1.435e6), 0.001, 1e9, "kg m^2", "principal moments: roll, "
                            "pitch, yaw (about x, y, z)")
    cg_height: float = param(1.45, 0.3, 5.0, "m", "centre of mass above rail (assumed)")


@section("frame")
class Frame:
    """The bogie frames (two)."""

    mass: float = param(3420.0, 1.0, 1e5, "kg", "frame mass; a flexible frame gets the difference to its FE "
                        "mass as point masses")
    inertia: tuple = vector((1430.0, 1850.0, 2950.0), 0.001, 1e7, "kg m^2", "principal moments about x, y, "
                            "z, used when no reduced body is given")
    cg_height: float = param(0.6, 0.2, 2.0, "m", "centre of mass above rail (assumed)")


@section("wheelset")
class Wheelset:
    """The wheelsets (four)."""

    mass: float = param(1539.0, 1.0, 1e5, "kg", "wheelset mass, used when no reduced body is given (and in "
                        "the static wheel load)")
    inertia: tuple = vector((801.0, 104.0, 814.0), 0.001, 1e6, "kg m^2", "principal moments about x, y (the "
                            "axle), z, used when no reduced body is given")
    r0: float = like(TrackLayout, "r0", doc="nominal wheel rolling radius")


@section("axlebox")
class Axlebox:
    """The axle-boxes (eight) and the assembly parts their housing mesh lacks."""

    mass: float = param(78.7, 0.1, 10000.0, "kg", "housing mass (the FE housing's), used when no reduced "
                        "body is given")
    inertia: tuple = vector((0.75, 2.36, 2.08), 1e-5, 10000.0, "kg m^2", "principal moments about x, y, z, "
                            "used when no reduced body is given")
    cup_mass: float = param(0.0, 0.0, 1000.0, "kg", "bearing cup: point masses on the housing's two bore "
                            "spiders")
    cover_mass: float = param(0.0, 0.0, 1000.0, "kg", "end cover: a point mass on the outboard (row 2) bore "
                              "spider")
    adapter_mass: float = param(0.0, 0.0, 1000.0, "kg", "adapter: point masses on the two spring seats")


@section("gearbox")
class Gearbox:
    """The gearboxes (four), hung between the axle and the frame; mass 0: none."""

    mass: float = param(450.0, 0.0, 10000.0, "kg", "gearbox mass (assumed); 0: no gearbox")
    inertia: tuple = vector((20.0, 30.0, 20.0), 1e-4, 1e5, "kg m^2", "principal moments about x, y, z "
                            "(assumed)")
    arm: float = param(0.35, 0.0, 1.5, "m", "from the axle to the gearbox centre of mass, towards the bogie "
                       "centre; below hanger_arm")
    hanger_arm: float = param(0.6, 0.05, 2.0, "m", "from the axle to the hanger on the frame")
    hanger_k: float = param(5e6, 1.0, 1e10, "N/m", "hanger link stiffness (assumed)")
    hanger_c: float = param(20000.0, 0.0, 1e8, "N s/m", "hanger link damping (assumed)")
    side: str = choice("R", ["L", "R"], "the side the gear sits on (as the wheelset geometry's default: 'R')")


@section("geometry")
class Geometry:
    """Where the bodies and suspension points sit (track frame: x forward, y left, z up)."""

    bogie_distance: float = param(12.6, 3.0, 30.0, "m", "distance between the bogie centres")
    wheelbase: float = param(2.2, 1.0, 4.0, "m", "bogie wheelbase")
    journal_y: float = param(1.0, 0.6, 1.5, "m", "lateral position of the journal centres")
    air_spring_y: float = param(1.0, 0.3, 1.5, "m", "lateral position of the air springs (assumed)")
    air_spring_height: float = param(0.85, 0.3, 2.0, "m", "air spring height above rail (assumed)")


@section("primary")
class Primary:
    """Primary suspension, per axle box: two coil springs, each half of these."""

    kx: float = param(1.06e7, 0.0, 1e10, "N/m", "longitudinal stiffness per axle box")
    ky: float = param(7.8e6, 0.0, 1e10, "N/m", "lateral stiffness per axle box")
    kz: float = param(1.7e6, 1.0, 1e10, "N/m", "vertical stiffness per axle box")
    cz: float = param(10000.0, 0.0, 1e8, "N s/m", "vertical damping per axle box (assumed)")


@section("secondary")
class Secondary:
    """Secondary suspension: per air spring (two per bogie) and per bogie."""

    kx: float = param(2.1e5, 0.0, 1e9, "N/m", "longitudinal stiffness per air spring")
    ky: float = param(2e5, 0.0, 1e9, "N/m", "lateral stiffness per air spring (assumed)")
    kz: float = param(3.5e5, 1.0, 1e9, "N/m", "vertical stiffness per air spring (assumed)")
    cz: float = param(30000.0, 0.0, 1e8, "N s/m", "vertical damper alongside each air spring (assumed)")
    cy: float = param(40000.0, 0.0, 1e8, "N s/m", "lateral damper, per bogie (assumed)")
    anti_roll: float = param(1e6, 0.0, 1e9, "N m/rad", "anti-roll bar, per bogie (assumed)")
    traction_k: float = param(5e6, 0.0, 1e10, "N/m", "traction rod (longitudinal link), per bogie (assumed)")
    bumpstop_clearance: float = param(0.03, 0.0, 0.2, "m", "lateral bump stop clearance (assumed)")
    bumpstop_k: float = param(2e6, 0.0, 1e10, "N/m", "lateral bump stop stiffness (assumed)")


@section("joint")
class Joint:
    """The wheelset-axle-box joint: row bushings or the DTRB bearings."""

    model: str = choice("bushing", ["bushing", "bearing", "dtrb"], "'bushing': one bushing per bearing row, "
                        "spin free; 'dtrb': the DTRB model ([bearing]), which [[defects]] need")
    wheelsets: tuple = members((1, 2, 3, 4), (1, 2, 3, 4), "with model = 'dtrb': the wheelsets whose "
                               "axle-boxes sit on DTRBs (the rest keep the bushings)")
    k_radial: float = param(1e9, 1000.0, 1e12, "N/m", "row bushing radial stiffness (order of a DTRB row's)")
    k_axial: float = param(5e8, 1000.0, 1e12, "N/m", "row bushing axial stiffness")
    c: float = param(20000.0, 0.0, 1e8, "N s/m", "row bushing damping, each translation")

    def __post_init__(self):
        _check_fields(self)
        object.__setattr__(self, "wheelsets", tuple(sorted(self.wheelsets)))


@section("sensors")
class Sensors:
    """The axle-box accelerometers and the acquisition (pipelines/sensor.py)."""

    node: str = text("sensor_pad", "the housing node the sensor follows; a box without it: a point 0.175 m "
                     "above its centre")
    model: str = choice("ideal", ["ideal", "accelerometer"], "'ideal': the model's accelerations as they "
                        "are; 'accelerometer': the measurement chain")
    fs_hz: float = param(10000.0, 100.0, 1e6, "Hz", "acquisition rate (the paper's system: 10 kHz); model "
                         "'accelerometer' only")
    resonance_hz: float = param(25000.0, 100.0, 1e7, "Hz", "mounted resonance (an industrial IEPE "
                                "accelerometer, e.g. PCB 603C01: 25 kHz)")
    resonance_q: float = param(30.0, 0.5, 1000.0, "-", "quality factor of the resonance (assumed)")
    highpass_hz: float = param(0.5, 0.0, 1000.0, "Hz", "first-order electrical high-pass (the datasheet's "
                               "-3 dB point); 0: none")
    passband: float = param(0.45, 0.05, 0.49, "-", "anti-alias filter flat to passband x fs_hz, stopping "
                            "from fs_hz / 2 (e.g. TI ADS1278: 0.453)")


# ---- the entries of [[defects]] and [[wheel_defects]] ------------------------------------------

@dataclass(frozen=True)
class BearingDefect:
    """A ``[[defects]]`` entry: where on the car (``wheelset``, ``side``), its centre in degrees
    from the top (the load zone's middle) and the rest of its shape
    (:class:`~axlebox.bearing.defects.Defect`, paper Eqs. 14-15)."""

    SECTION = "defects"
    wheelset: int = param(2, 1, 4, "-", "vehicle only: the wheelset whose bearing has it, one of "
                          "joint.wheelsets")
    side: str = choice("R", SIDES, "vehicle only: its bearing's side (the gearbox side is gearbox.side)")
    angle_deg: float = param(0.0, -360.0, 360.0, "deg", "vehicle only: centre of the defect from the "
                             "top (the load zone's middle), in degrees by name; the rig's is angle, "
                             "in rad")
    shape: Defect = field(default_factory=Defect)

    def __post_init__(self):
        _check_fields(self)

    @property
    def defect(self) -> Defect:
        """The defect as the bearing takes it (its angle in rad)."""
        return dataclasses.replace(self.shape, angle=math.radians(self.angle_deg))

    @classmethod
    def from_table(cls, d, where: str) -> BearingDefect:
        if not isinstance(d, dict):
            raise ParameterError(f"{where} = {d!r} is not allowed: expected a [[defects]] table")
        allowed = ["wheelset", "side"] + [f.name for f in dataclasses.fields(Defect)
                                          if f.name != "angle"] + ["angle_deg"]
        for key in d:
            if key not in allowed:
                raise ParameterError(f"{where}.{key} is not a field of [[defects]]: expected one "
                                     f"of {', '.join(allowed)}")
        place = {k: d[k] for k in ("wheelset", "side", "angle_deg") if k in d}
        shape = {k: v for k, v in d.items() if k not in place}
        try:
            return from_table(cls, place, where, shape=from_table(Defect, shape, where))
        except ParameterError as err:
            if str(err).startswith(("defects.", "Defect.")):
                raise ParameterError(f"{where}: {err}") from None
            raise

    def to_table(self) -> dict:
        shape = {k: v for k, v in dataclasses.asdict(self.shape).items() if k != "angle"}
        return {"wheelset": self.wheelset, "side": self.side, "angle_deg": self.angle_deg, **shape}


#: the fields of each kind of wheel defect (the others do not apply to it)
WHEEL_DEFECT_FIELDS = {"flat": ("wheelset", "side", "kind", "length", "shape", "angle_deg", "name"),
                       "polygon": ("wheelset", "side", "kind", "orders", "amplitudes_um",
                                   "phases_deg", "name")}


@dataclass(frozen=True)
class WheelDefect:
    """A ``[[wheel_defects]]`` entry: a wheel tread defect, a radius deviation turning with its
    wheel (mbs/vehicle/wheel_defects.py); each kind takes its fields of :data:`WHEEL_DEFECT_FIELDS`."""

    SECTION = "wheel_defects"
    wheelset: int = param(1, 1, 4, "-", "the wheelset")
    side: str = choice("R", SIDES, "its wheel")
    kind: str = choice("flat", tuple(WHEEL_DEFECT_FIELDS), "'flat' or 'polygon' "
                       "(mbs/vehicle/wheel_defects.py)")
    length: float = param(0.04, 1e-4, 0.2, "m", "the flat's chord (depth about length^2 / (8 r0)); "
                          "below the wheel radius")
    shape: str = choice("rounded", ("rounded", "fresh"), "'rounded' (a worn flat's haversine) or "
                        "'fresh' (the chord, sharp edges)")
    angle_deg: float = param(0.0, -360.0, 360.0, "deg", "the flat's centre around the rolling circle")
    orders: tuple = numbers((20.0,), 1.0, 200.0, "-", "whole harmonic orders around the "
                            "circumference (times the wheel's rate)")
    amplitudes_um: tuple = numbers((50.0,), 0.0, 5000.0, "µm", "radius amplitude of each order, in "
                                   "micrometres by name")
    phases_deg: tuple = numbers((), -360.0, 360.0, "deg", "phase of each order; empty: all 0")
    name: str = text("", "a label that a sweep's [sweep] wheel_defects picks entries by")

    def __post_init__(self):
        _check_fields(self)
        if self.kind == "polygon":
            n = len(self.orders)
            if (len(self.amplitudes_um) != n or len(self.phases_deg) not in (0, n)
                    or any(o != round(o) for o in self.orders)):
                raise ParameterError(f"wheel_defects.orders = {list(self.orders)!r} is not allowed: "
                                     "expected whole orders, one amplitudes_um (and phases_deg, if "
                                     "given) each")

    @classmethod
    def from_table(cls, d, where: str) -> WheelDefect:
        return kinded_from_table(cls, d, where, WHEEL_DEFECT_FIELDS, "wheel defect")

    def to_table(self) -> dict:
        return {k: (list(v) if isinstance(v, tuple) else v)
                for k, v in dataclasses.asdict(self).items() if k in WHEEL_DEFECT_FIELDS[self.kind]}


# ---- the whole config --------------------------------------------------------------------------

#: the tables of a car config, by name: each declared section's class
SECTIONS = {cls.SECTION: cls for cls in (Run, Integrator, Coupling, Track, WheelRail, Bodies, Carbody,
                                          Frame, Wheelset, Axlebox, Gearbox, Geometry, Primary,
                                          Secondary, Joint, Sensors)}


def _default_bearing():
    return models.from_table({}, "bearing")


@dataclass(frozen=True)
class CarConfig:
    """The car's whole run configuration: its sections (one attribute each, named as the TOML
    tables), ``bearing`` (the bearing model's parameters, bearing/models/__init__.py), ``defects`` and
    ``wheel_defects``.  Built, it has passed every check; :meth:`replace` makes another one
    (the sweep's cases), :meth:`to_toml` is its file."""

    run: Run = field(default_factory=Run)
    integrator: Integrator = field(default_factory=Integrator)
    coupling: Coupling = field(default_factory=Coupling)
    track: Track = field(default_factory=Track)
    wheelrail: WheelRail = field(default_factory=WheelRail)
    bodies: Bodies = field(default_factory=Bodies)
    carbody: Carbody = field(default_factory=Carbody)
    frame: Frame = field(default_factory=Frame)
    wheelset: Wheelset = field(default_factory=Wheelset)
    axlebox: Axlebox = field(default_factory=Axlebox)
    gearbox: Gearbox = field(default_factory=Gearbox)
    geometry: Geometry = field(default_factory=Geometry)
    primary: Primary = field(default_factory=Primary)
    secondary: Secondary = field(default_factory=Secondary)
    joint: Joint = field(default_factory=Joint)
    sensors: Sensors = field(default_factory=Sensors)
    bearing: object = field(default_factory=_default_bearing)
    defects: tuple[BearingDefect, ...] = ()
    wheel_defects: tuple[WheelDefect, ...] = ()
    #: ``[[track.layout]]``: the line's segments (mbs/track/line.py); none: tangent track, the
    #: bodies described from the inertial frame
    segments: tuple[Segment, ...] = ()

    def __post_init__(self):
        _cross_checks(self)

    # -- what the run takes -----------------------------------------------------------------------
    @property
    def has_bearings(self) -> bool:
        """Whether the axle-boxes sit on rolling bearings (``joint.model`` not ``"bushing"``)."""
        return self.joint.model != "bushing"

    def settings(self) -> Settings:
        """The integrator's settings: ``[integrator]`` and ``[coupling]``."""
        return Settings(**dataclasses.asdict(self.integrator), **dataclasses.asdict(self.coupling))

    def layout(self) -> TrackLayout:
        w = self.wheelrail
        return TrackLayout(r0=self.wheelset.r0, gauge=w.gauge, back_to_back=w.back_to_back, cant=w.cant)

    def wheelrail_params(self) -> WheelRailParams:
        w = self.wheelrail
        return WheelRailParams(mu=w.mu, law=w.law, nx=w.fastsim_grid, ny=w.fastsim_grid,
                               update=w.fastsim_update, smooth_y=w.smooth_y,
                               split_angle=w.split_angle, y_field=w.y_field)

    def irregularity(self, contact_load: float = 0.0) -> IrregularityParams | None:
        """The track irregularity's parameters (None on smooth track); ``contact_load``: the
        static wheel load of the roughness's contact filter."""
        t = self.track
        if not t.irregularity:
            return None
        extra = {}
        if t.rail_roughness != "none":
            extra = dict(roughness=True, roughness_spectrum=t.rail_roughness,
                         roughness_lambda_min=t.roughness_lambda_min, contact_load=contact_load)
        return IrregularityParams(grade=t.fra_class, lambda_min=t.lambda_min, lambda_max=t.lambda_max,
                                  length=t.length, seed=self.run.seed, **extra)

    def speed_profile(self) -> SpeedProfile:
        """The run's speed over time: ``run.profile``, or the constant ``run.speed_kmh``."""
        if self.run.profile:
            return SpeedProfile.from_kmh(self.run.profile)
        return SpeedProfile.constant(self.run.speed_kmh / 3.6)

    def line(self, s0: float = 1.5) -> Line | None:
        """The line of ``[[track.layout]]`` (None without one: tangent track); ``s0`` the
        distance between the rails' contact points its cant is measured over, m."""
        return Line(self.segments, s0=s0) if self.segments else None

    def track_needed(self, duration: float | None = None) -> float:
        """Metres of track the car covers in ``duration`` s (default: the run's): the distance
        run plus its length (the bogie distance and 5 m)."""
        T = self.run.duration if duration is None else duration
        return float(self.speed_profile().distance(T)) + self.geometry.bogie_distance + 5.0

    # -- another one, and the file ----------------------------------------------------------------
    def replace(self, **changes) -> CarConfig:
        """A copy with ``changes``: a section's name -> ``{field: value}`` (those fields
        replaced, checked), ``bearing`` -> a ``[bearing]`` table or parameters, ``defects`` /
        ``wheel_defects`` -> their entries (tables or objects)."""
        new = {}
        for name, value in changes.items():
            if name == "track" and "layout" in value:
                value = dict(value)
                new["segments"] = _segments(value.pop("layout"))
            if name in SECTIONS:
                new[name] = _section(name, {**_table(getattr(self, name)), **value})
            elif name == "bearing":
                new[name] = value if not isinstance(value, dict) else models.from_table(value, "bearing")
            elif name in ("defects", "wheel_defects"):
                new[name] = _entries(name, value)
            else:
                raise ParameterError(f"[{name}] is not a section of the vehicle config: expected one "
                                     f"of {', '.join(_NAMES)}")
        return dataclasses.replace(self, **new)

    def to_dict(self) -> dict:
        """Every table and field, defaults filled in, as plain TOML data."""
        out = {name: _table(getattr(self, name)) for name in SECTIONS}
        if self.segments:
            out["track"]["layout"] = [g.to_table() for g in self.segments]
        out["bearing"] = models.to_table(self.bearing)
        if self.defects:
            out["defects"] = [d.to_table() for d in self.defects]
        if self.wheel_defects:
            out["wheel_defects"] = [d.to_table() for d in self.wheel_defects]
        return out

    def to_toml(self) -> str:
        """The whole config as TOML, every default filled in (:func:`loads` reads it back to an
        equal config)."""
        return tomli_w.dumps(self.to_dict())


_NAMES = (*SECTIONS, "bearing", "defects", "wheel_defects")


def _table(obj) -> dict:
    def plain(v):
        return [plain(x) for x in v] if isinstance(v, tuple) else v
    return {k: plain(v) for k, v in dataclasses.asdict(obj).items()}


def _section(name: str, fields):
    return from_table(SECTIONS[name], fields, name)


def _segments(items) -> tuple:
    if not isinstance(items, (list, tuple)):
        raise ParameterError(f"track.layout = {items!r} is not allowed: expected [[track.layout]] "
                             "tables")
    return tuple(g if isinstance(g, Segment) else Segment.from_table(g, f"track.layout[{i}]")
                 for i, g in enumerate(items))


def _entries(name: str, items) -> tuple:
    cls = BearingDefect if name == "defects" else WheelDefect
    if not isinstance(items, (list, tuple)):
        raise ParameterError(f"{name} = {items!r} is not allowed: expected [[{name}]] tables")
    return tuple(d if isinstance(d, cls) else cls.from_table(d, f"{name}[{i}]")
                 for i, d in enumerate(items))


#: the config's names of the fields of the classes a run is built from, for their refusals
_THEIR_NAMES = (("IrregularityParams.grade", "track.fra_class"), ("IrregularityParams.seed", "run.seed"),
                ("IrregularityParams.", "track."), ("TrackLayout.r0", "wheelset.r0"),
                ("TrackLayout.", "wheelrail."), ("WheelRailParams.nx", "wheelrail.fastsim_grid"),
                ("WheelRailParams.update", "wheelrail.fastsim_update"),
                ("WheelRailParams.", "wheelrail."), ("Settings.", "integrator."))


def _cross_checks(c: CarConfig) -> None:
    """The checks between fields, each once: those of the classes the run is built from
    (the integrator's steps and rates, the track layout, the irregularity's wavelengths) by
    building them, then the car's own."""
    for build in (c.settings, c.layout, c.wheelrail_params, c.irregularity):
        try:
            build()
        except ParameterError as err:       # named as the config names the field
            msg = str(err)
            for theirs, ours in _THEIR_NAMES:
                msg = msg.replace(theirs, ours)
            raise ParameterError(msg) from None
    r = c.run
    if r.profile:
        c.speed_profile()                   # its own checks: times from 0, increasing
        if r.profile[0][1] != r.speed_kmh:
            raise ParameterError(f"run.speed_kmh = {r.speed_kmh:g} is not allowed with run.profile: "
                                 f"expected its speed at 0 s, {r.profile[0][1]:g} km/h")
    t = c.track
    if not t.irregularity and t.rail_roughness != "none":
        raise ParameterError(f"track.rail_roughness = {t.rail_roughness!r} is not allowed with "
                             "track.irregularity = false: expected 'none' (the rails' roughness "
                             "rides on their irregular record)")
    need = c.track_needed()
    _check_line(c)
    if t.irregularity and t.length < need:
        raise ParameterError(f"track.length = {t.length:g} is not allowed: the car runs "
                             f"{need:.0f} m (distance plus its length); expected at least that")
    if c.has_bearings:
        models.check_step(c.bearing, c.integrator.method, c.integrator.dt, "integrator.method",
                          "integrator.dt")
        for d in c.defects:
            if d.wheelset not in c.joint.wheelsets:
                raise ParameterError(f"defects: wheelset = {d.wheelset} is not allowed: its "
                                     f"axle-boxes sit on row bushings (joint.wheelsets = "
                                     f"{list(c.joint.wheelsets)}); expected one of those")
    elif c.defects:
        raise ParameterError("defects need joint.model = 'bearing': with the bushing joint there is "
                             "no bearing to hold them")
    sn, ig = c.sensors, c.integrator
    if sn.model != "ideal":
        ratio = ig.output_rate_hz / sn.fs_hz
        if ratio < 2 or abs(ratio - round(ratio)) > 1e-9:
            raise ParameterError(f"integrator.output_rate_hz = {ig.output_rate_hz:g} is not allowed "
                                 f"with sensors.model = {sn.model!r}: expected a whole multiple, at "
                                 f"least 2, of sensors.fs_hz = {sn.fs_hz:g} (the acquisition filters "
                                 "and decimates what the run writes)")
    g = c.gearbox
    if g.mass > 0 and g.arm >= g.hanger_arm:
        raise ParameterError(f"gearbox.arm = {g.arm:g} is not allowed: expected less than "
                             f"gearbox.hanger_arm = {g.hanger_arm:g} (the hanger carries the far end)")


#: m, the smallest curve radius of a B-type metro car's lines (GB 50157-2013, Code for Design of
#: Metro, Table 6.2.2: depot and yard lines; main lines 300 m, 250 m where difficult)
MIN_RADIUS = 150.0
#: m, the largest cant deficiency EN 13803:2017 admits on plain line (150 mm, about 1 m/s^2
#: unbalanced; metro codes keep to 0.4-0.5 m/s^2, GB 50157-2013 5.3.3)
MAX_CANT_DEFICIENCY = 0.150


def _check_line(c: CarConfig) -> None:
    """The line must hold the whole run: the rear wheelset at the start, the front one at the
    end."""
    line = c.line()
    if line is None:
        if c.track.start != 0.0:
            raise ParameterError(f"track.start = {c.track.start:g} is not allowed without "
                                 "[[track.layout]]: expected 0 (tangent track has no chainage)")
        return
    g = c.geometry
    v_max = max(c.speed_profile().v)
    for i, sg in enumerate(c.segments):
        if sg.kind != "curve":
            continue
        if sg.radius < MIN_RADIUS:
            raise ParameterError(
                f"track.layout[{i}].radius = {sg.radius:g} is not allowed for this car: expected at "
                f"least {MIN_RADIUS:g} m, the smallest radius a B-type metro car's bogies and "
                "couplers are built for (GB 50157-2013, Table 6.2.2: its depot and yard lines)")
        d = cant_deficiency(v_max, sg.radius, sg.superelevation, line.s0)
        if d > MAX_CANT_DEFICIENCY:
            raise ParameterError(
                f"track.layout[{i}] at {v_max * 3.6:g} km/h is not allowed: its cant deficiency "
                f"would be {d * 1e3:.0f} mm ({G * d / line.s0:.2f} m/s^2 unbalanced); expected at "
                f"most {MAX_CANT_DEFICIENCY * 1e3:.0f} mm (EN 13803:2017's largest limit): more "
                "superelevation, a larger radius or a lower speed")
    rear = g.bogie_distance + g.wheelbase / 2
    if c.track.start < rear:
        raise ParameterError(f"track.start = {c.track.start:g} is not allowed: the rear wheelset "
                             f"stands {rear:g} m behind the front bogie's centre; expected at least "
                             f"{rear:g} m (the car on the line)")
    end = c.track.start + float(c.speed_profile().distance(c.run.duration)) + g.wheelbase / 2
    if end > line.length:
        raise ParameterError(f"run.duration = {c.run.duration:g} is not allowed on this line: the "
                             f"front wheelset would reach {end:.1f} m, the line ends at "
                             f"{line.length:g} m; expected a shorter run, a later end of "
                             "[[track.layout]] or an earlier track.start")


def validate(user: dict) -> CarConfig:
    """The config of a parsed TOML dict: defaults overridden by what it names, every value
    checked."""
    if not isinstance(user, dict):
        raise ParameterError(f"config = {user!r} is not allowed: expected TOML tables")
    out = {}
    for name, fields in user.items():
        if name in SECTIONS:
            if not isinstance(fields, dict):
                raise ParameterError(f"{name} = {fields!r} is not allowed: expected a [{name}] table")
            if name == "track" and "layout" in fields:
                fields = dict(fields)
                out["segments"] = _segments(fields.pop("layout"))
            out[name] = _section(name, fields)
        elif name == "bearing":
            out[name] = models.from_table(fields, "bearing")
        elif name in ("defects", "wheel_defects"):
            out[name] = _entries(name, fields)
        else:
            raise ParameterError(f"[{name}] is not a section of the vehicle config: expected one of "
                                 f"{', '.join(_NAMES)}")
    return CarConfig(**out)


def loads(text: str, where: str = "config text") -> CarConfig:
    """The config of TOML ``text`` (``where`` names it in a refusal)."""
    try:
        user = tomllib.loads(text)
    except tomllib.TOMLDecodeError as err:
        raise ParameterError(f"{where} is not valid TOML: {err}") from None
    return validate(user)


def load(path) -> CarConfig:
    """The config of a TOML file."""
    path = Path(path)
    if not path.is_file():
        raise ParameterError(f"config = {str(path)!r} is not allowed: no such file")
    return loads(path.read_text(), f"config {str(path)!r}")
