"""Faults on both sides of a wheelset (bearing/diagnostics/own.py, criterion step 1b), on
synthetic pairs with known answers (bearing/diagnostics/synthetic.py): each side's own hits ring
its housing (3 kHz), the other side's arrive 1.2 ms later through the wheelset's bending
(546 Hz) at 0.3 of their RMS, both in wheel-rail noise.  The coupled car's cases are in
tests/test_both_sides_car.py, the real record's in tests/test_diagnose_cli.py."""
import json

import numpy as np
import pytest

from axlebox._params import ParameterError
from axlebox.bearing.diagnostics.criterion import Criterion, verdict
from axlebox.bearing.diagnostics.own import owned
from axlebox.bearing.diagnostics.pair import analyse_pair
from axlebox.bearing.diagnostics.synthetic import both_sides_pair, coaxial_pair
from axlebox.bearing.frequencies import orders, shaft_hz
from axlebox.bearing.params import BearingParams

FS = 10_000.0
SHAFT = shaft_hz(48.0)
ORDERS = orders(BearingParams())
BPFO = ORDERS.BPFO * SHAFT
BORE = 0.130
T = 3.0
REL = Criterion(mode="relative")
HOUSING = dict(f_res=3000.0, zeta=0.03)      # a local defect rings its own housing


@pytest.mark.parametrize("offset_periods", [0.0, 0.1, 0.5])
@pytest.mark.parametrize("amplitude", [(1.0, 1.0), (1.0, 0.7)])
def test_a_fault_on_each_side_is_faults_on_both_sides(offset_periods, amplitude):
    """Whether the two trains coincide (0), follow within a transmission lag (0.1 period,
    2.3 ms: what timing alone would read as a pseudo-fault) or interleave (0.5): each side's
    line stands in the other's band at 0.67-1.5 of it (the copy of one fault alone: 0.08, the
    next test), over the threshold 0.25.  The impulse lag names a leading side (0.7-8.6 ms) in
    every one of these: timing alone would call a pseudo-fault."""
    rng = np.random.default_rng(11)
    left, right = both_sides_pair(T, FS, BPFO, rng, amplitude=amplitude,
                                  offset_s=offset_periods / BPFO, noise=0.3, **HOUSING)
    res = analyse_pair(left, right, FS, SHAFT, ORDERS, BORE, REL)
    assert res.verdicts["left"][0] == res.verdicts["right"][0] == "faults on both sides", res.verdicts
    sh = res.shares["BPFO"]
    assert sh.seen == {"left": True, "right": True}
    assert min(sh.share.values()) >= REL.own_share
    assert "each side carries its own fault line" in res.verdicts["left"][1]
    assert "BPFO is" in res.verdicts["left"][1] and "band" in res.verdicts["left"][1]
    json.dumps(res.to_dict(), allow_nan=False)


@pytest.mark.parametrize("swap", [False, True])
def test_one_fault_and_its_copy_stay_real_and_pseudo(swap):
    """The same housing ring on one side only: the copy's line, seen in the defect side's band,
    is far under half of it, so the paper's criterion decides (real on the defect side)."""
    rng = np.random.default_rng(12)
    a, b = coaxial_pair(T, FS, BPFO, rng, noise=0.3, **HOUSING)
    x = (b, a) if swap else (a, b)
    res = analyse_pair(*x, FS, SHAFT, ORDERS, BORE, REL)
    real, pseudo = ("right", "left") if swap else ("left", "right")
    assert res.verdicts[real][0] == "real fault" and res.verdicts[pseudo][0] == "pseudo-fault", res.verdicts
    own = owned(res.left, res.right, res.shares, REL.lines, REL.own_share)
    assert own[real] == ["BPFO"] and own[pseudo] == []
    if "BPFO" in res.shares:
        sh = res.shares["BPFO"]
        assert not sh.seen[pseudo] or sh.share[pseudo] < REL.own_share


def test_own_share_threshold_moves_the_call():
    """The threshold is the rule: at 2 (neither line reaches twice the other's in its band)
    the same two faults go back to the paper's criterion."""
    rng = np.random.default_rng(11)
    left, right = both_sides_pair(T, FS, BPFO, rng, noise=0.3, **HOUSING)
    strict = analyse_pair(left, right, FS, SHAFT, ORDERS, BORE, Criterion(mode="relative", own_share=2.0))
    assert "faults on both sides" not in {v for v, _ in strict.verdicts.values()}
    with pytest.raises(ParameterError, match="own_share"):
        Criterion(own_share=0.0)


def side(lines: dict, band=(1000.0, 2000.0)):
    """A stand-in ChannelResult: ``lines`` name -> detected."""
    from types import SimpleNamespace
    return SimpleNamespace(VF=1e5, rms=1.0, spm_db=10.0, band=band,
                           lines={n: SimpleNamespace(detected=d) for n, d in lines.items()})


def test_different_lines_on_the_two_sides_are_each_sides_own():
    """An inner-ring fault on the left (BPFI found there only), an outer-ring one on the right
    (BPFO there only): each side owns a line, whatever the VF difference."""
    left, right = side({"BPFO": False, "BPFI": True}), side({"BPFO": True, "BPFI": False})
    v = verdict(left, right, None, REL, shares={})
    assert v["left"][0] == v["right"][0] == "faults on both sides"
    assert "left's BPFI is found on left only" in v["left"][1]
    # without the shares (a caller of the paper's criterion alone) step 1b is left out
    assert verdict(left, right, None, REL)["left"][0] == "undecided"
