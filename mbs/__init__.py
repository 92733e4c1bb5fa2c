"""The car and its track in time: a floating-frame multibody solver, its numba kernels, the track,
wheel-rail contact, the B-type metro car and ride comfort, each a folder, importing one way.

* :mod:`.kernel` the solver's numba kernels, plain arrays read by slot name: one body, markers,
  force elements, wheels, bearings, the system's right-hand side, the integrators' runs and the
  exchange with the bearings;
* :mod:`.solver` the Python side of it: bodies (the reduced-body files of :mod:`axlebox.fem`),
  force elements, the assembled system, its integrators;
* :mod:`.track` what the wheels run on: the irregularities, the rails' and wheels' roughness,
  the track bed under each wheel;
* :mod:`.wheelrail` wheel-rail contact: profiles, contact geometry, Hertz, Kalker, FASTSIM;
* :mod:`.vehicle` the B-type metro car: its config, its bodies and suspension, its axle-box
  bearings, its statics, its speed profile, its wheels' defects;
* :mod:`.post` what is read off a run's signals: ride comfort and its frequency weightings.

Imports run one way (tests/test_packaging.py): kernel below solver below vehicle; track,
wheelrail and post below the vehicle and each on its own (the kernels read the wheel-rail
element's kernel).
"""
from axlebox import _numba  # noqa: F401  (before any kernel compiles or loads)
