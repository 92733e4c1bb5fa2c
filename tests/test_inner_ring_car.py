"""Beyond the paper (issue 20): the validation case with its defect on the inner ring
(configs/inner_48kmh.toml: the 50.4 x 2 x 2 mm defect on the cone of row 2 of wheelset 2's
gearbox-side bearing, turning with the axle).  Does it show on the healthy side of the wheelset as
the outer ring's defect does (tests/test_validation.py)?  The defect side's envelope spectrum
carries BPFI; the healthy side the same line, over its floor and weaker; its impulses come later.

One run of the demo's 1.6 s (2.0 s with AXLEBOX_FULL=1; README "Inner-ring defect" quotes 2 s).
"""
import pytest

from axlebox import configs
from axlebox.bearing.diagnostics.envelope import envelope_spectrum
from axlebox.bearing.diagnostics.faultlines import detect
from axlebox.bearing.diagnostics.lag import impulse_lag
from axlebox.bearing.frequencies import orders, shaft_hz
from axlebox.bearing.models.params import BearingParams
from axlebox.pipelines import readers
from axlebox.pipelines import simulate as psim
from axlebox.pipelines.demo import DURATION

from conftest import assert_sized, full_size

BAND = (500.0, 4500.0)            # broadband: the axle carries the low band across (README)


@pytest.fixture(scope="module")
def run(tmp_path_factory):
    out = tmp_path_factory.mktemp("inner") / "inner.h5"
    psim.run(configs.path("inner_48kmh"), out, duration=2.0 if full_size() else DURATION,
             log=lambda *_: None)
    rec = readers.read(out)                  # ws2_L, ws2_R; the track's fade-in left out
    sides = {"ws2_R": rec.right, "ws2_L": rec.left}
    return sides, rec.fs, orders(BearingParams()).BPFI * shaft_hz(48.0, 0.42), out


@pytest.mark.slow
def test_inner_ring_defect_shows_on_the_healthy_side_weaker_and_later(run):
    """Both sides' BPFI fundamental passes the false-alarm threshold (p_fa 1e-3 per window,
    bearing/diagnostics/faultlines.py) on the defect side with its harmonics (detected), on the
    healthy side at least its fundamental; the healthy side's line under the defect side's; and
    the defect side leads the impulses by a positive lag under 10 ms, with most impulses agreeing
    (the outer ring's case: 1.5-5.6 ms)."""
    sides, fs, bpfi, _ = run
    res = {}
    for name, x in sides.items():
        f, A = envelope_spectrum(x, fs, band=BAND)
        res[name] = detect(f, A, {"BPFI": bpfi})["BPFI"]
    R, L = res["ws2_R"], res["ws2_L"]
    amp = {n: r.searched[0][2] for n, r in res.items()}
    print(f"BPFI {bpfi:.2f} Hz: defect side {amp['ws2_R']:.3f} m/s^2, {R.searched[0][3]:.1f} dB "
          f"over its floor (threshold {R.searched[0][4]:.1f}), detected {R.detected}; healthy side "
          f"{amp['ws2_L']:.3f}, {L.searched[0][3]:.1f} dB")
    assert R.detected
    assert L.f_found is not None
    assert amp["ws2_L"] < amp["ws2_R"]
    lag = impulse_lag(sides["ws2_R"], sides["ws2_L"], fs, 1.0 / bpfi)
    print(f"lag {lag.lag_s * 1e3:.2f} ms, leading {lag.leading}, {lag.n_impulses} impulses, "
          f"{100 * lag.agreement:.0f} % agree")
    assert lag.leading == "a" and 0.0 < lag.lag_s < 0.01
    assert lag.agreement >= 0.7


@pytest.mark.slow
def test_the_diagnosis_names_the_inner_ring_and_its_size(run):
    """The diagnosis of the two axle boxes (issue 57): the defect side a real fault of the inner
    ring (its BPFI, not the outer ring's BPFO or a roller's 2BSF), the healthy side not called
    faulty; the defect's width, 2 mm, read from the rollers' entry and exit on the turning cone
    (the run's rolling speed of the inner raceway) within 25 % with its interval holding it."""
    from axlebox.pipelines.diagnose import analyse_file
    _, _, pair = analyse_file(run[3])
    assert (pair.verdict.words["right"], pair.verdict.words["left"]) == ("real fault", "pseudo-fault")
    assert pair.verdict.kinds["right"].kind == "inner ring"
    assert_sized(pair.sizes["right"], 2e-3)
