"""The exchange between the car's bodies and its bearings in a leapfrog run: the bodies step at
the exchange step ``H``, each bearing in ``n`` sub-steps of ``h = H / n`` between two exchanges
(:func:`axlebox.bearing.kernel.advance.advance`, :func:`.bearings.bearing_exchange`).

Why: the rollers' contact modes (21-23 kHz) hold the bearings' step near 5e-6 s, while the car
without bearings is accurate at 5e-5 s; stepping everything at the rollers' step spends a third
of the run on the car's own right-hand side (benchmarks/README.md, "Speed by design").

The coupling is explicit, as a co-simulation's (the paper's SIMPACK-Simulink exchange every
1e-4 s): at each exchange a bearing sees its rings move on the straight line through their
motion at this exchange and the last, over a window of one step centred on the exchange, and
the bodies get its ring loads averaged over the window, held for the step.  The mean carries
the window's impulse whole (momentum is exchanged without loss), and for loads linear in the
ring motion it is the load at the exchange: the coupling is then the single-rate leapfrog's,
with no lag to feed energy into the stiff bearing modes (a window of the step just past did:
bearing/kernel/advance.py).  What the exchange step changes is how the impulses of the nonlinear
contacts (the defect) are spread over the step, and the ring motion's curvature within it;
both are measured against the single-rate run (tests/test_coupled.py, benchmarks/README.md
"Multirate").

**Co-simulation** (``m`` > 1, the paper's SIMPACK-Simulink arrangement, where the vehicle
integrates on its own between exchanges): the bodies take ``m`` leapfrog steps of ``H / m`` an
exchange, the exchange's mean ring loads on the markers throughout (``hold`` "zoh", a zero-order
hold, as a co-simulation interface holds its inputs between communication points), or carried
on the line through the last two exchanges' ("linear", first-order extrapolation), or held
with the interface Jacobian ("jacobian": the held loads plus ``-K`` times the outer ring's
displacement from the inner since the exchange, ``K`` each bearing's tangent stiffness at its
static load along x, y, z, :func:`axlebox.mbs.vehicle.bearings.stiffness`; the remedy of Kuebler and
Schiehlen, "Two methods of simulator coupling", Math. Comput. Model. Dyn. Syst. 6 (2000)
93-113: the stiff linear part follows the bodies at their own step, only the rest is held).  The held
loads come from a window centred on the exchange and act over the step after it, so a zero-order
hold lags the bearing stiffness by about ``H / 2``: on a mode of frequency ``w`` a negative
damping ratio near ``w H / 4`` (11 % for the axle box on its bearing, 700 Hz, at the paper's
1e-4 s).  With ``m = 1`` the run is the single-rate-bodies one above, bit for bit.

:class:`Exchange` (a named tuple numba compiles): ``ring`` the ring motion at the last exchange
(n_bearings, 2, 12), ``flags[0]`` 1 before the run's first exchange, ``flags[1]`` 1 once
``held`` (2, n_bearings, 2, 6: this exchange's and the last one's ring loads in the track
frame, inner and outer ring, force and moment) holds an exchange, ``m`` and ``hold`` the
co-simulation's body steps and hold, ``h`` and ``n`` the bearings' sub-step and sub-steps an
exchange, ``mode`` (bearing/kernel/step.py ``MODES``), ``K`` and ``r0`` the "jacobian" hold's
stiffness and outer-ring places.  The bearings' own scratch is theirs
(mbs/kernel/bearings.py ``Bearings``).
"""
from __future__ import annotations

from collections import namedtuple

import numpy as np

from axlebox.bearing.kernel.layout import LOAD, RING, RINGS
from axlebox.bearing.kernel.step import MODES

Exchange = namedtuple("Exchange", ["ring", "flags", "h", "n", "mode", "held", "m", "hold", "K", "r0"])
ZOH, LINEAR, JACOBIAN = 0, 1, 2
HOLDS = {"zoh": ZOH, "linear": LINEAR, "jacobian": JACOBIAN}
FIRST, HELD = 0, 1                # flags: before the run's first exchange; ``held`` holds one
THIS, LAST = 0, 1                 # held: this exchange's loads, the last one's


def exchange(model, method: str, h: float, n: int, ring=None, m: int = 1, hold: str = "zoh",
             K=None) -> Exchange:
    """The exchange of ``model``'s bearings for a leapfrog ``method`` ('leapfrog', 'imex',
    'imex2') with sub-step ``h`` and ``n`` sub-steps an exchange; ``ring``: the last exchange's
    ring motion of a run this one continues (:attr:`axlebox.mbs.solver.integrate.Run.exchange`),
    else the run starts.  ``m`` > 1: the bodies take ``m`` steps an exchange with the ring
    loads held (``hold``, :data:`HOLDS`; module docstring, "Co-simulation"); ``K`` (n_bearings,
    3): the bearings' tangent stiffness the "jacobian" hold needs
    (:func:`axlebox.mbs.vehicle.bearings.stiffness`)."""
    nbr = len(model.bearing_names)
    start = ring is None
    ring = np.zeros((nbr, RINGS, RING)) if start else np.array(ring, float).reshape(nbr, RINGS, RING)
    flags = np.zeros(2, np.int64)
    flags[FIRST] = 1 if start else 0
    return Exchange(ring=ring, flags=flags, h=float(h), n=int(n), mode=int(MODES[method]),
                    held=np.zeros((2, nbr, RINGS, LOAD)), m=int(m), hold=HOLDS[hold],
                    K=np.zeros((nbr, 3)) if K is None else np.array(K, float).reshape(nbr, 3),
                    r0=np.zeros((nbr, 3)))
