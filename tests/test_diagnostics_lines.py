"""Each side's own bearing and the lines searched on it: the bearing catalogue, the rolling
element's line with its cage sidebands, and what masks a line another cause explains
(bearing/catalogue.py, bearing/diagnostics/faultlines.py, channel.py)."""
import json

import numpy as np
import pytest

from axlebox._params import ParameterError
from axlebox.bearing.catalogue import catalogue, lookup
from axlebox.bearing.diagnostics import faultlines
from axlebox.bearing.diagnostics.channel import analyse, distinct, line_frequencies
from axlebox.bearing.diagnostics.synthetic import resonance, wheel_rail_noise
from axlebox.bearing.frequencies import orders
from axlebox.bearing.models.params import BearingParams


def test_the_catalogue_holds_the_published_orders():
    """CWRU's published orders (Bearing Data Center; Smith and Randall 2015, Table 2): the
    rolling element's defect order is 2 BSF."""
    d, f = lookup("6205"), lookup("6203")
    assert (d.orders.BPFO, d.orders.BPFI, d.orders.FTF) == (3.5848, 5.4152, 0.39828)
    assert d.orders.at(1.0)["2BSF"] == pytest.approx(4.7135, abs=1e-12)
    assert (f.orders.BPFO, f.orders.BPFI, f.orders.FTF) == (3.0530, 4.9469, 0.3817)
    assert f.orders.at(1.0)["2BSF"] == pytest.approx(3.9874, abs=1e-12)
    assert (d.bore, f.bore) == (0.025, 0.017)
    assert lookup(" DTRB ").orders == orders(BearingParams())
    json.dumps({k: b.to_dict() for k, b in catalogue().items()})
    with pytest.raises(ParameterError, match=r"--bearing-left '6206' is not allowed: expected one "
                                             r"of 6203, 6205, crb, dcrb, dtrb"):
        lookup("6206", "--bearing-left")


def test_the_other_bearings_lines_are_searched_where_they_differ():
    """On the CWRU motor the two bearings' BPFO, BPFI and 2 BSF windows (+-3 %) do not overlap,
    so each end searches the other's too (carried); their cages' FTF does (0.398 / 0.382)."""
    d, f = lookup("6205").orders, lookup("6203").orders
    own, carried, side = line_frequencies(30.0, d, ("BPFO", "BPFI", "2BSF", "FTF"), f, 0.03)
    assert set(carried) == {"BPFO", "BPFI", "2BSF"}
    assert carried["BPFO"] == pytest.approx(3.053 * 30.0)
    assert side == {"2BSF": pytest.approx(0.39828 * 30), "~2BSF": pytest.approx(0.3817 * 30)}
    assert not distinct(d.FTF, f.FTF, 0.03) and distinct(d.BPFO, f.BPFO, 0.03)
    # one bearing type on both sides: nothing carried
    assert line_frequencies(30.0, d, ("BPFO",), d, 0.03)[1] == {}


def spectrum(peaks, f0=100.0, df=0.1, seed=0):
    """An envelope amplitude spectrum 0-1000 Hz: Rayleigh noise (median 1) and ``peaks``
    {frequency: amplitude}."""
    rng = np.random.default_rng(seed)
    f = np.arange(0.0, 1000.0, df)
    A = rng.rayleigh(1.0 / np.sqrt(2 * np.log(2)), f.size)
    for fk, a in peaks.items():
        A[int(round(fk / df))] = a
    return f, A


def test_the_rolling_elements_line_counts_its_cage_sidebands():
    """2 BSF at 120 Hz with its cage sidebands at +-10 Hz and no harmonics (the defect carried
    in and out of the load zone once a cage turn): detected when the sidebands are searched
    with it, not without; each sideband is 20 log10(30) = 29.5 dB over the median floor (read
    on a ring of about 40 bins, whose sample median scatters by about 15 %: 1.5 dB)."""
    f, A = spectrum({120.0: 30.0, 110.0: 30.0, 130.0: 30.0})
    with_sb = faultlines.detect(f, A, {"2BSF": 120.0}, sidebands={"2BSF": 10.0})["2BSF"]
    assert with_sb.detected and with_sb.f_found == pytest.approx(120.0)
    assert [round(r[1], 1) for r in with_sb.sidebands] == [110.0, 130.0]
    assert all(r[3] == pytest.approx(29.5, abs=2.0) for r in with_sb.sidebands)
    assert not faultlines.detect(f, A, {"2BSF": 120.0})["2BSF"].detected
    with pytest.raises(ParameterError, match="sidebands"):
        faultlines.detect(f, A, {"2BSF": 120.0}, sidebands={"BPFO": 10.0})


def test_what_another_cause_explains_is_masked():
    """A line at a shaft harmonic (4 x 30 Hz) is the shaft's; a 2 BSF whose sidebands are a
    stronger BPFI's shaft sidebands borrows them and is masked by it."""
    shaft = 30.0
    f, A = spectrum({120.0: 40.0, 240.0: 40.0, 360.0: 40.0})
    r = faultlines.detect(f, A, {"X": 119.6}, shaft_hz=shaft)["X"]
    assert not r.detected and r.masked_by == "shaft"
    # BPFI 162 Hz with harmonics and shaft sidebands 132 / 192 Hz; 2 BSF at 142 Hz with
    # sidebands at 132 and 152: the 132 Hz one is BPFI - f_shaft
    f, A = spectrum({162.0: 60.0, 324.0: 50.0, 486.0: 40.0, 132.0: 30.0, 192.0: 30.0,
                     142.0: 25.0, 152.0: 25.0})
    found = faultlines.detect(f, A, {"BPFI": 162.0, "2BSF": 142.0}, shaft_hz=shaft,
                              sidebands={"2BSF": 10.0}, n_required=2)
    assert found["BPFI"].detected
    assert not found["2BSF"].detected and found["2BSF"].masked_by == "BPFI"


def test_a_roller_defect_is_found_by_its_line():
    """Hits at 2 BSF of the DTRB at 48 km/h, their size modulated once a cage turn, ringing
    3 kHz in wheel-rail noise: the channel finds 2BSF (fundamental and harmonics or sidebands)
    and no BPFO or BPFI."""
    fs, T = 10_000.0, 4.0
    shaft = 5.05
    fo = orders(BearingParams())
    f2, fc = 2 * fo.BSF * shaft, fo.FTF * shaft
    n = int(T * fs)
    t = np.arange(n) / fs
    hits = np.zeros(n)
    k = np.arange(0.01, T, 1.0 / f2)
    hits[(k * fs).astype(int)] = 1.0 + 0.6 * np.cos(2 * np.pi * fc * k)
    rng = np.random.default_rng(3)
    x = resonance(hits, fs, 3000.0, 0.03) + 0.2 * wheel_rail_noise(n, fs, rng) \
        + 0.002 * rng.standard_normal(n)
    ch = analyse(x, fs, shaft, fo, 0.130)
    assert ch.lines["2BSF"].detected and ch.lines["2BSF"].f_found == pytest.approx(f2, rel=0.01)
    assert not ch.lines["BPFO"].detected and not ch.lines["BPFI"].detected
    assert t.size == n
