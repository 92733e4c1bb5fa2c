"""The defect's size from the rollers' entry and exit events (bearing/diagnostics/size.py):
the kinematics and the conversion against the model's own definitions (bearing/defects.py,
bearing/frequencies.py), the events' separation on synthetic records with known entry and exit
times (bearing/diagnostics/synthetic.py spall_record), the resolution and the refusals.  The
model's known answers on the car (the study's widths) are in benchmarks/size.py and
benchmarks/README.md; tests/test_real_records.py holds the real records' sizes."""
import math

import numpy as np
import pytest

from axlebox._params import ParameterError
from axlebox.bearing import catalogue
from axlebox.bearing.defects import Defect
from axlebox.bearing.diagnostics import size
from axlebox.bearing.diagnostics.synthetic import spall_record
from axlebox.bearing.frequencies import orders as fault_orders
from axlebox.bearing.frequencies import shaft_hz
from axlebox.bearing.models.params import BearingParams

FS = 10_000.0
F_FAULT = 36.7                    # the DTRB's BPFO at 40 km/h
ONE_MODE = ((2300.0, 0.05),)      # a housing mode in the band of a 10 kHz acquisition


def record(dt_samples, seed=0, **kw):
    kw.setdefault("modes", ONE_MODE)
    x, _ = spall_record(2.3, FS, F_FAULT, dt_samples / FS, np.random.default_rng(seed), **kw)
    return x


# --- kinematics and conversion: the model's own definitions ---------------------------------
def test_rolling_speed_is_each_surfaces_speed_in_the_model():
    """``pi f_s D_m (1 - g^2) / 2`` equals the cage's speed over the cup (omega_c D_o / 2), the
    shaft's over the cage on the cone ((omega_s - omega_c) D_i / 2) and the roller's spin over
    its own surface (omega_b D_b / 2), the model's kinematics (bearing/frequencies.py) with
    its raceway diameters (bearing/models/params.py): to rounding."""
    p = BearingParams()
    o = fault_orders(p)
    f_s = shaft_hz(40.0)
    v = size.rolling_speed(o, f_s, p.D_m)
    w_s, w_c, w_b = (2 * math.pi * f_s * k for k in (1.0, o.FTF, o.BSF))
    assert v == pytest.approx(w_c * p.D_o / 2, rel=1e-12)
    assert size.surface_diameter("outer", o, p.D_m, p.D_b) == pytest.approx(p.D_o, rel=1e-12)
    assert v == pytest.approx(w_b * p.D_b / 2, rel=1e-12)
    # the cone: D_i at its own angle (7.5 deg) against g at the cup's (10 deg): 0.1 % apart
    assert v == pytest.approx((w_s - w_c) * p.D_i / 2, rel=2e-3)


@pytest.mark.parametrize("kind", ["outer", "inner", "roller"])
@pytest.mark.parametrize("W", [0.5e-3, 1e-3, 3e-3, 5e-3])
def test_the_whole_width_inverts_the_models_defect_window(kind, W):
    """A roller crosses the model's window ``tau = 2 arcsin(W / D)`` (Defect.tau, Eq. 14) in
    ``tau D / (2 v)``; that time gives W back."""
    p = BearingParams()
    o = fault_orders(p)
    v = size.rolling_speed(o, shaft_hz(60.0), p.D_m)
    D = size.surface_diameter(kind, o, p.D_m, p.D_b)
    tau = Defect(W=W, kind=kind).tau(p) if kind != "inner" else 2 * math.asin(W / D)
    assert size.width_from_lag(tau * D / (2 * v), v, D) == pytest.approx(W, rel=1e-9)


def test_a_loaded_rollers_events_and_their_inverse():
    """The bridged width is where Eq. 14's drop A(W) reaches the approach; past it the events'
    angle grows from 0 towards the whole window, and width_from_lag inverts it."""
    r, delta, D = 0.0117, 14e-6, 0.203
    Wb = size.bridged_width(r, delta)
    assert size.drop(Wb, r) == pytest.approx(delta, rel=1e-12)
    assert size.event_angle(Wb, D, r, delta) == pytest.approx(0.0, abs=1e-8)
    assert size.event_angle(0.99 * Wb, D, r, delta) == 0.0
    v = 1.2
    for W in (1.2e-3, 2e-3, 3e-3, 5e-3):
        a = size.event_angle(W, D, r, delta)
        assert 0 < a < 2 * math.asin(W / D)
        assert size.width_from_lag(a * D / (2 * v), v, D, r, delta) == pytest.approx(W, rel=1e-7)


def test_the_catalogues_diameters_agree_with_its_orders():
    """A bearing's pitch and roller diameters give its published cage order back
    (``FTF = (1 - D_b cos(alpha) / D_m) / 2``; the ball bearings at 0 deg, to the published
    digits; the DTRB at its cup angle)."""
    for name in ("6205", "6203"):
        b = catalogue.lookup(name)
        assert 0.5 * (1 - b.roller / b.pitch) == pytest.approx(b.orders.FTF, abs=2e-4)
    b, p = catalogue.lookup("dtrb"), BearingParams()
    assert 0.5 * (1 - b.roller * math.cos(p.alpha_o) / b.pitch) == pytest.approx(b.orders.FTF, rel=1e-12)
    assert size.geometry_of(catalogue.custom(b.orders, 0.1)) is None


# --- the events on synthetic records with known times -----------------------------------------
@pytest.mark.parametrize("dt", [8.0, 12.5, 25.0, 40.0])
def test_the_events_separation_is_read(dt):
    """Entry and exit ``dt`` samples apart, the exit with an impact: read within half a sample,
    its interval (bootstrap over the periods, widened by the timing's half sample) holding the
    truth."""
    ev = size.event_lag(record(dt), FS, 1.01 * F_FAULT)
    assert ev.dt_s is not None and ev.snr >= size.MIN_SNR
    assert abs(ev.dt_s * FS - dt) < 0.5
    lo, hi = ev.interval_s()
    assert lo - 0.5 / FS <= dt / FS <= hi + 0.5 / FS
    assert abs(ev.alpha_hz - F_FAULT) < 0.02 * F_FAULT


def test_rollers_that_slip_two_per_cent():
    ev = size.event_lag(record(25.0, seed=3, jitter=0.02), FS, F_FAULT)
    assert ev.dt_s is not None and abs(ev.dt_s * FS - 25.0) < 0.5


def test_a_bridged_defects_edges_are_its_events():
    """A roller that rides over the defect without unloading (a half-sine dip of its load):
    the dip's edges, Eq. 14's slope breaks, are the pair, the whole width apart."""
    ev = size.event_lag(record(17.0, events="dip"), FS, F_FAULT)
    assert ev.dt_s is not None and abs(ev.dt_s * FS - 17.0) < 0.5


def test_one_impact_a_pass_is_no_pair():
    """One event a pass (no entry): nothing stands at the search's lags as an echo would."""
    for seed in range(3):
        ev = size.event_lag(record(0.0, seed=seed, events="single"), FS, F_FAULT)
        assert ev.dt_s is None, ev.snr


def test_events_closer_than_the_resolution_are_not_a_number():
    """Entry and exit 3 samples apart (below :data:`size.RESOLUTION_SAMPLES`): the outer-ring
    defect at 80 km/h that far apart is below resolution, with the width the limit stands for."""
    p = BearingParams()
    o = fault_orders(p)
    f_s = shaft_hz(80.0)
    g = size.Geometry(p.D_m, p.D_b)
    x = record(3.0)
    r = size.estimate(x, FS, f_s, o, "outer", g, f_line=F_FAULT)
    assert r.status == "below resolution" and r.width_m is None
    v = size.rolling_speed(o, f_s, p.D_m)
    assert r.limit_m == pytest.approx(v * size.RESOLUTION_SAMPLES / FS, rel=1e-3)
    assert r.interval_m == (0.0, r.limit_m)


def test_a_sized_side_and_its_json():
    """25 samples at 40 km/h on the DTRB's cup: the whole width ``v dt`` (load unknown), its
    interval holding it; the result's dict is JSON."""
    import json
    p = BearingParams()
    o = fault_orders(p)
    f_s = shaft_hz(40.0)
    r = size.estimate(record(25.0), FS, f_s, o, "outer", size.Geometry(p.D_m, p.D_b),
                      f_line=o.BPFO * f_s)
    v = size.rolling_speed(o, f_s, p.D_m)
    W = size.width_from_lag(25.0 / FS, v, p.D_o)
    assert r.status == "sized"
    assert r.width_m == pytest.approx(W, rel=0.03)
    assert r.interval_m[0] <= W <= r.interval_m[1]
    assert "mm" in r.text()
    json.dumps(r.to_dict(), allow_nan=False)


def test_refusals_name_the_field():
    p = BearingParams()
    o = fault_orders(p)
    with pytest.raises(ParameterError, match="kind = 'cage'"):
        size.estimate(record(25.0), FS, 4.2, o, "cage", size.Geometry(p.D_m, p.D_b))
    with pytest.raises(ParameterError, match="f_line = -1"):
        size.event_lag(record(25.0), FS, -1.0)
    with pytest.raises(ParameterError, match="too short"):
        size.event_lag(np.random.default_rng(0).standard_normal(300), FS, F_FAULT)
    r = size.estimate(record(25.0), FS, 4.2, o, "outer", None)
    assert r.status == "not read" and "--bearing" in r.reason


def test_a_changing_speed_read_on_the_shafts_clock():
    """The 25-sample record played with the shaft speeding up by a fifth over it: in time the
    fault's rate sweeps and the echo smears; read at equal steps of the shaft's angle, the
    events are those of the mean speed again."""
    p = BearingParams()
    o = fault_orders(p)
    x0 = record(25.0)
    n = x0.size
    f_s = F_FAULT / o.BPFO                           # the shaft rate the record was made at
    u = np.linspace(0.0, 1.0, n)
    warp = (0.9 * u + 0.1 * u * u) / 1.0             # its own time at our samples: 0.9 -> 1.1 speed
    x = np.interp(warp * (n - 1), np.arange(n), x0)
    angle = f_s * warp * (n - 1) / FS                # turns
    g = size.Geometry(p.D_m, p.D_b)
    r = size.estimate(x, FS, f_s, o, "outer", g, angle=angle)
    v = size.rolling_speed(o, f_s, p.D_m)
    assert r.status == "sized"
    assert r.width_m == pytest.approx(size.width_from_lag(25.0 / FS, v, p.D_o), rel=0.05)
    with pytest.raises(ParameterError, match="angle of 3 samples"):
        size.estimate(x, FS, f_s, o, "outer", g, angle=[0.0, 1.0, 2.0])


@pytest.mark.parametrize("case", ["v20_w1", "v40_w3", "v80_w3", "v80_w5"])
def test_the_models_known_widths(case):
    """The car's defect side (tests/data/make_size_excerpts.py: 1 s at 10 kHz of an outer-ring
    defect W wide, read with the file's roller load).  The quasi-dynamic car: 1 mm at 20 km/h,
    ridden over (its edges 17 samples apart), and 3 mm at 40 km/h, the roller unloading (26
    samples).  The full car at 80 km/h (the study's): 3 and 5 mm, 12 and 21 samples, whose pairs
    stand only 11-14 times the floor of |R| (size.MIN_SNR: the lobes fill more of a short
    period's lags).  The width within 5 % and its interval holding it."""
    from pathlib import Path
    d = np.load(Path(__file__).parent / "data" / "size_excerpts.npz")
    fs, f_s, _, W, Q = d[f"{case}_meta"]
    x = d[f"{case}_x"] * float(d["lsb"])
    b = catalogue.lookup("dtrb")
    r = size.estimate(x, fs, f_s, b.orders, "outer", size.geometry_of(b, Q))
    assert r.status == "sized", r.reason
    assert r.width_m == pytest.approx(W, rel=0.05)
    assert r.interval_m[0] <= W <= r.interval_m[1]
