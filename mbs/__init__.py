"""Floating-frame multibody solver, wheel-rail contact, track and vehicle.

- :mod:`axlebox.mbs.body`, :mod:`axlebox.mbs.system`, :mod:`axlebox.mbs.integrate` rigid and
  flexible bodies (the reduced-body files of :mod:`axlebox.fem`), the assembled system and its
  integrators; the numba kernels in the ``kernel_*`` modules
- :mod:`axlebox.mbs.wheelrail` wheel-rail contact: profiles, contact geometry, Hertz, Kalker, FASTSIM
- :mod:`axlebox.mbs.track` track irregularities (FRA spectra, rail roughness)
- :mod:`axlebox.mbs.vehicle` the B-type metro car; :mod:`axlebox.mbs.bearings` its axle-box bearings
"""
from axlebox import _numba  # noqa: F401  (before any kernel compiles or loads)
