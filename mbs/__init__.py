"""Floating-frame multibody solver, wheel-rail contact, track and vehicle.

Empty until the vehicle issues land; it reads the reduced-body files written by :mod:`fem`.
"""
