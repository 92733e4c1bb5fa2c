"""Profile reader, contact geometry and equivalent conicity (issue 4, items 1-2)."""
import math

import numpy as np
import pytest

from axlebox._params import ParameterError
from axlebox.mbs.wheelrail.conicity import equivalent_conicity, klingel_wavelength
from axlebox.mbs.wheelrail.geometry import TrackLayout, contact_table
from axlebox.mbs.wheelrail.profile import Profile, ProfileError, read_profile

from conftest import reference_dir

REF = reference_dir() / "profiles"
S1002 = REF / "MBench_S1002_v3.prw"
UIC60_CANTED = REF / "MBench_UIC60_v3.prr"
UIC60 = REF / "uic60_true.prr"

needs_ref = pytest.mark.skipif(not S1002.is_file(),
                               reason=f"reference profiles not found in {REF} (set AXLEBOX_REFERENCE)")


@pytest.fixture(scope="module")
def mbench():
    """The Manchester benchmark pair: S1002 on UIC60 canted 1:40, gauge 1435, flange backs 1360 mm."""
    w, r = read_profile(S1002), read_profile(UIC60_CANTED)
    return contact_table(w, r, TrackLayout(back_to_back=1.360, cant=0.0), y_max=0.010, n=401)


def _cone(gamma=0.05, half_width=0.07):
    """A pure cone wheel (slope gamma) without a flange: r = r0 - gamma*y (side-local y outward)."""
    y = np.linspace(-half_width, half_width, 701)
    return Profile(y=y, z=gamma * y, kind="wheel", name=f"cone 1:{1 / gamma:.0f}")


def _arc_rail(R=0.04, half_width=0.036):
    y = np.linspace(-half_width, half_width, 721)
    return Profile(y=y, z=-(R - np.sqrt(R * R - y * y)), kind="rail", name=f"R{R * 1e3:.0f} crown")


# ---------------------------------------------------------------------------------------- reader

@needs_ref
def test_simpack_reader_turns_files_into_the_side_local_frame():
    """Kinds from the header, mm -> m, z up, flange and gauge face on the track-centre side."""
    w = read_profile(S1002)
    assert w.kind == "wheel"
    # S1002 flange height 28 mm above the taping line (EN 13715 / UIC 510-2)
    assert -w.z.min() == pytest.approx(0.028, abs=1e-5)
    assert w.y[np.argmin(w.z)] < 0.0
    assert abs(w.height(0.0)) < 1e-6          # taping line at the origin
    r = read_profile(UIC60_CANTED)
    assert r.kind == "rail"
    assert r.z.max() == pytest.approx(0.0, abs=1e-6)
    # the canted UIC60 crown: R300 (EN 13674-1), curvature of the head's top
    assert -1.0 / r.curvature(-0.0075) == pytest.approx(0.300, rel=0.01)


@needs_ref
def test_reader_drops_vertical_flanks_and_uncanted_rail_is_symmetric():
    r = read_profile(UIC60)
    assert np.all(np.diff(r.y) > 0)
    assert r.height(0.02) == pytest.approx(r.height(-0.02), abs=1e-9)


def test_reader_refuses_a_profile_that_goes_back(tmp_path):
    f = tmp_path / "bad.txt"
    f.write_text("# y z mm\n-10 1\n-5 0.2\n0 0\n-2 0.1\n5 0.3\n10 1\n")
    with pytest.raises(ProfileError, match=r"bad.txt is not monotone in y: points 2 and 3"):
        read_profile(f, "rail")
    with pytest.raises(ProfileError, match="kind = None"):
        read_profile(f)
    f.write_text("-10 1\n-5 oops\n")
    with pytest.raises(ProfileError, match="line 2 is not two numbers"):
        read_profile(f, "rail")
    with pytest.raises(ProfileError, match="not monotone"):
        Profile(y=np.array([0.0, 1.0, 0.5, 2.0]), z=np.zeros(4), kind="rail")


def test_two_column_text_matches_the_same_curve(tmp_path):
    y = np.linspace(-30.0, 30.0, 61)
    z_down = 300.0 - np.sqrt(300.0 ** 2 - y ** 2)
    f = tmp_path / "crown.txt"
    np.savetxt(f, np.c_[y, z_down], header="y z (mm, z down)")
    r = read_profile(f, "rail")
    assert r.y[0] == pytest.approx(-0.030)
    assert -1.0 / r.curvature(0.0) == pytest.approx(0.300, rel=1e-3)


# ---------------------------------------------------------------------------------------- geometry

def _cone_on_circle_exact(y, gamma, R, layout, y_cw, y_cr):
    """Independent exact solution for a cone on a circular crown: each wheel line is tangent to its
    rail circle (distance from the circle's centre = R); returns roll and the two rolling radii."""
    from scipy.optimize import fsolve
    r0 = layout.r0

    def lines(phi, z):
        c, s = math.cos(phi), math.sin(phi)
        out = []
        for sg in (1.0, -1.0):
            p = np.array([sg * y_cw, -r0])                # taping-line point, wheelset frame
            d = np.array([sg * 1.0, gamma])              # along the generator, outward
            P = np.array([y + c * p[0] - s * p[1], z + s * p[0] + c * p[1]])
            D = np.array([c * d[0] - s * d[1], s * d[0] + c * d[1]])
            out.append((P, D / np.linalg.norm(D), np.array([sg * y_cr, -R]), np.linalg.norm(d)))
        return out

    def eqs(q):
        res = []
        for P, D, C, _ in lines(*q):
            v = C - P
            res.append(abs(v[0] * D[1] - v[1] * D[0]) - R)
        return res
    phi, z = fsolve(eqs, [0.0, r0], xtol=1e-12)
    r = [r0 - gamma * (np.dot(C - P, D) / nd) for P, D, C, nd in lines(phi, z)]
    return phi, r


def test_cone_on_circular_crown_against_the_exact_tangency_solution():
    """A 1:20 cone on R40 crowns: roll and rolling radii equal the exact line-circle tangency."""
    gamma, R = 0.05, 0.04
    lay = TrackLayout(cant=0.0)
    rail = _arc_rail(R)
    t = contact_table(_cone(gamma), rail, lay, y_max=0.006, n=13)
    y_cw = 0.5 * lay.back_to_back + 0.070
    y_cr = 0.5 * lay.gauge - rail.gauge_point()
    for j in (0, 3, 8, 12):
        phi, r = _cone_on_circle_exact(t.y[j], gamma, R, lay, y_cw, y_cr)
        assert t.roll[j] == pytest.approx(phi, abs=1e-8)
        np.testing.assert_allclose(t.r[j], r, atol=2e-8)


def test_conicity_methods_agree_for_a_linear_radius_difference():
    """For a cone dr is linear in y: both methods return dr/(2y) at every amplitude, and the
    kinematic wavelength is Klingel's L = 2 pi sqrt(e0 r0 / lambda)."""
    t = contact_table(_cone(0.05), _arc_rail(), TrackLayout(cant=0.0), y_max=0.006, n=25)
    lam = 0.5 * np.polyfit(t.y, t.delta_r, 1)[0]
    A = [0.001, 0.003, 0.005]
    np.testing.assert_allclose(equivalent_conicity(t, A), lam, rtol=1e-3)
    np.testing.assert_allclose(equivalent_conicity(t, A, "klingel"), lam, rtol=1e-3)
    L = 2 * math.pi * math.sqrt(t.e0 * t.layout.r0 / lam)
    assert klingel_wavelength(t, 0.004) == pytest.approx(L, rel=1e-3)


@needs_ref
def test_contact_geometry_is_mirror_symmetric(mbench):
    t = mbench
    np.testing.assert_allclose(t.delta_r, -t.delta_r[::-1], atol=1e-9)
    np.testing.assert_allclose(t.roll, -t.roll[::-1], atol=1e-10)
    np.testing.assert_allclose(t.delta[:, 0], t.delta[::-1, 1], atol=1e-7)
    np.testing.assert_allclose(t.y_wheel[:, 0], t.y_wheel[::-1, 1], atol=1e-8)


@needs_ref
def test_tread_contact_of_the_centred_wheelset(mbench):
    """Centred: both contacts on the R300 crown and the wheel's 1:40 tread; r = r0 - z_w; angle ~ cant."""
    c = mbench.at(0.0)
    assert c["kappa_rail_y"][0] == pytest.approx(1 / 0.300, rel=0.01)
    assert c["delta"][0] == pytest.approx(math.atan(1 / 40), abs=0.01)
    r = c["r"][0]
    assert c["kappa_wheel_x"][0] == pytest.approx(math.cos(c["delta_wheel"][0]) / r, rel=1e-12)
    assert c["z"] == pytest.approx(0.0, abs=2e-4)


@needs_ref
def test_flange_contact_is_reached_at_the_flangeway_clearance(mbench):
    """Flange contact once y exceeds the clearance: contact angle above 60 deg, dr over 15 mm."""
    big = mbench.at(0.009)
    assert np.degrees(big["delta"][0]) > 45.0
    assert big["r"][0] - big["r"][1] > 0.015
    assert mbench.at(0.009)["roll"] > 0.0          # left wheel climbs: left side up


def test_bad_inputs_name_the_field():
    with pytest.raises(ParameterError, match="TrackLayout.back_to_back"):
        TrackLayout(back_to_back=1.5)
    with pytest.raises(ParameterError, match="y_max"):
        contact_table(_cone(), _arc_rail(), y_max=-1.0)
    with pytest.raises(ParameterError, match="is a rail profile"):
        contact_table(_arc_rail(), _arc_rail())
    t = contact_table(_cone(), _arc_rail(), TrackLayout(cant=0.0), y_max=0.004, n=9)
    with pytest.raises(ParameterError, match="amplitudes"):
        equivalent_conicity(t, [0.01])
    with pytest.raises(ParameterError, match="method"):
        equivalent_conicity(t, [0.002], method="regression")
