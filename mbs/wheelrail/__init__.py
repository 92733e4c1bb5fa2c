"""Wheel-rail contact: profiles, contact geometry, Hertz normal contact, tangential contact.

Modules, one idea each:

- ``profile``        the :class:`Profile` curve (side-local y outward, z up, metres) and the reader
                     for measured profiles (two-column text, SIMPACK .prw/.prr)
- ``standard``       LM / CHN 60 and S1002 / UIC60 built from their published definitions
- ``geometry``       contact geometry of a wheelset on track: tables against lateral displacement
- ``conicity``       equivalent conicity against amplitude
- ``hertz``          Hertz ellipse (m, n from elliptic integrals), force-penetration law
- ``kalker``         Kalker's creep coefficients and their interpolation; linear creep law
- ``fastsim_kernel`` FASTSIM in numba over plain arrays; ``tangential`` the Python side of it,
                     Shen-Hedrick-Elkins, and creepages from wheelset kinematics
"""
