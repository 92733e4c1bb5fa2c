"""The verdicts on the synthetic families with known answers (bearing/diagnostics/families.py),
the floors of the criterion's design: a transmitted copy (transmission 0.05-1, delay 0-5 ms,
path resonance 300-3000 Hz, signal to noise 0-20 dB, 10 s records) is never called "faults on
both sides" and its side is a pseudo-fault or healthy; two independent faults (each its own
slip 0.5-2 % and jitter, size ratio 0.3-3) are faults on both sides in at least 95 %.

CI runs 20 cases of each; AXLEBOX_FULL=1 runs 200 (benchmarks/families.py prints the tables).
"""
import pytest

from axlebox.bearing.catalogue import lookup
from axlebox.bearing.diagnostics.criterion import Criterion
from axlebox.bearing.diagnostics.families import copy_case, two_source_case
from axlebox.bearing.diagnostics.pair import analyse_pair

from conftest import full_size

N = 200 if full_size() else 20
B = lookup("6205")


def verdicts(case):
    res = analyse_pair(case.a, case.b, case.fs, case.params["f_fault"] / B.orders.BPFO, B.orders,
                       B.bore, Criterion(mode="relative"))
    return res.verdict


@pytest.mark.slow
def test_a_copy_is_never_a_second_fault():
    """The copy's side (a healthy bearing) is never called a fault, real or both: 100 %.  It is
    called a pseudo-fault or healthy in at least 95 % (200 cases: 198, benchmarks/README.md; the
    two left are undecided: a copy arriving more than half a fault period late through a
    ringing path, where the lag and where the line rings name different sources, and a copy
    too weak to see beside a source at 1.5 dB signal to noise, whose side's spectrum is like
    the other's)."""
    words = [verdicts(copy_case(seed)).words for seed in range(N)]
    fault = [i for i, w in enumerate(words) if w["right"] in ("real fault", "faults on both sides")]
    assert fault == []
    bad = [i for i, w in enumerate(words) if w["right"] not in ("pseudo-fault", "healthy")]
    print(f"copy side pseudo or healthy in {N - len(bad)} of {N}; not: {bad}")
    assert len(bad) <= 0.05 * N


@pytest.mark.slow
def test_two_faults_are_called_both():
    words = [verdicts(two_source_case(seed)).words for seed in range(N)]
    hit = sum(w == {"left": "faults on both sides", "right": "faults on both sides"} for w in words)
    print(f"faults on both sides in {hit} of {N}")
    assert hit >= 0.95 * N
