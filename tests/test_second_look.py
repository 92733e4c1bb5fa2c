"""The second look (pipelines/diagnose.py analyse_record, pipelines/speed.py): an order-tracked
"faults on both sides" stands only where the record read in time says so too.

Why it stays (issue 57): a copy reaches the other side a path's delay later in time, and on the
shaft's clock a fixed delay is a share of a turn that grows with the speed, so while the speed
changes the copy's lines turn against their source's by ``2 pi k BPFO_order (f1 - f0) tau``
(tests/test_diagnostics_coherence.py, the closed form; benchmarks/README.md "The copy under
traction"); on one speed ramp that turn and two trains' drift grow alike, so the copy test cannot
tell them apart.  So does the accelerating car's copy in one window of its 4 s run, its 5th
harmonic turning as the drive's torque leaves the healthy side's wheel (bearing/diagnostics/
coherence.py); its copy's strength changing with the speed no longer needs it."""
import numpy as np

from axlebox.bearing.catalogue import lookup
from axlebox.bearing.diagnostics.criterion import Criterion
from axlebox.bearing.diagnostics.pair import analyse_pair
from axlebox.bearing.diagnostics.synthetic import swept_coaxial_pair
from axlebox.bearing.frequencies import shaft_hz
from axlebox.pipelines.diagnose import BOTH, analyse_record
from axlebox.pipelines.readers import Record
from axlebox.pipelines.speed import Speed

FS = 10_000.0
DTRB = lookup("dtrb")


def test_a_long_path_over_a_wide_sweep_is_kept_from_calling_the_healthy_side_faulty():
    """A source (right) and its copy through a 5 ms path (left) while the shaft speeds up from 20
    to 80 km/h over 5 s: the 5th harmonic turns by ``2 pi 5 x 8.72 x 6.3 Hz x 5 ms``, 8.6 rad, and
    read on the shaft's clock alone the copy's line is its own: both sides faulty.  With the
    second look the healthy side is not called faulty."""
    right, left, angle = swept_coaxial_pair(5.0, FS, DTRB.orders.BPFO, shaft_hz(20.0), shaft_hz(80.0),
                                            np.random.default_rng(0), delay_s=5e-3)
    f_mean = (angle[-1] - angle[0]) * FS / (angle.size - 1)
    clock = analyse_pair(left, right, FS, f_mean, DTRB.orders, DTRB.bore, Criterion(), angle=angle)
    assert clock.verdict.words == {"left": BOTH, "right": BOTH}
    ev = next(e for e in clock.evidence if e.line == "BPFO")
    assert ev.timing.decision == "independent"
    info, res = analyse_record(Record(left, right, FS, ("healthy", "defect"), "csv"),
                               Speed(angle, "the sweep's angle", "shaft"))
    assert info["speed"]["order_tracked"] and info["speed"]["second_look"]
    assert res.verdict.words["left"] not in ("real fault", BOTH)
