"""Floating-frame multibody solver, wheel-rail contact, track and vehicle.

- :mod:`mbs.wheelrail` wheel-rail contact: profiles, contact geometry, Hertz, Kalker, FASTSIM
- :mod:`mbs.track` track irregularities (FRA spectra, rail roughness)

The multibody solver and the vehicle come next; they read the reduced-body files of :mod:`fem`.
"""
from bearing import _jitcache  # noqa: F401  (before any kernel compiles or loads)

