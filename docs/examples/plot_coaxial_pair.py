"""
A real fault and its coaxial pseudo-fault
=========================================

A defect on one axle box's bearing strikes once per roller passing (BPFO); the wheelset carries
each strike to the other axle box, later and through its bending, so the healthy side shows the
same fault line: the *coaxial pseudo-fault*.  Here a synthetic pair with a known answer (the
bearing-signal model of Antoni and Randall, J. Vib. Acoust. 125 (2003), with a 1.2 ms path delay
and the wheelset's second bending at 546 Hz) is read as ``axlebox diagnose`` reads two
recordings, and the verdict names the source and the copy.
"""

import numpy as np

from axlebox.bearing.catalogue import lookup
from axlebox.bearing.diagnostics.criterion import Criterion
from axlebox.bearing.diagnostics.pair import analyse_pair
from axlebox.bearing.diagnostics.synthetic import coaxial_pair
from axlebox.bearing.frequencies import shaft_hz

fs = 10_000.0                               # Hz, the field system's rate
f_shaft = shaft_hz(48.0)                    # the wheelset's rate at 48 km/h, 0.42 m wheels
dtrb = lookup("dtrb")                       # the axle-box bearing's fault orders and bore
f_bpfo = dtrb.orders.BPFO * f_shaft
print(f"shaft {f_shaft:.3f} Hz, BPFO {f_bpfo:.2f} Hz")

# %%
# Three seconds of both sides: the right side has the defect; the left side receives its
# strikes 1.2 ms later at 0.3 of their strength, each side with its own wheel-rail noise.
rng = np.random.default_rng(1)
right, left = coaxial_pair(3.0, fs, f_bpfo, rng, amplitude=1.0, delay_s=1.2e-3, gain=0.3)

res = analyse_pair(left, right, fs, f_shaft, dtrb.orders, dtrb.bore, Criterion(mode="relative"),
                   names=("left axle box", "right axle box"))
print(res.summary())
for side in ("left", "right"):
    print(f"{side}: {res.verdict.words[side]} ({res.verdict.sentence(side)})")

# %%
# The known answer: the right side is the real fault, the left side its copy.
assert res.verdict.words["right"] == "real fault", res.verdict.words
assert res.verdict.words["left"] == "pseudo-fault", res.verdict.words

# %%
# Both envelope spectra with the fault lines found, and the verdicts.
fig = res.plot()
