"""
Wheel-rail contact geometry and equivalent conicity
===================================================

The wheel-rail element reads tables of the contact geometry of a wheelset on its two rails
against its lateral displacement: contact points, rolling radii, contact angles and the roll of
the wheelset.  Here S1002 wheels (EN 13715) on 60E1 rails (EN 13674-1) inclined 1:40, standard
gauge, 1360 mm between the wheels' back faces, and the equivalent conicity the table gives,
by harmonic linearisation and by Klingel's kinematic wavelength (:mod:`axlebox.mbs.wheelrail.conicity`).
"""

import numpy as np

from axlebox.mbs.wheelrail import conicity, geometry, standard

layout = geometry.TrackLayout(gauge=1.435, back_to_back=1.360, cant=1 / 40)
table = geometry.contact_table(standard.s1002(), standard.uic60(), layout)
fig = table.plot()

# %%
# Equivalent conicity at 2, 3 and 4 mm amplitude: the wheelset's lateral displacement in a
# sinusoid of that amplitude, its rolling radius difference linearised.
A = np.array([2e-3, 3e-3, 4e-3])
harmonic = conicity.equivalent_conicity(table, A)
klingel = conicity.equivalent_conicity(table, A, "klingel")
for a, h, k in zip(A, harmonic, klingel):
    print(f"amplitude {a * 1e3:.0f} mm: harmonic {h:.3f}, Klingel {k:.3f}")

# %%
# The two linearisations agree where the radius difference is smooth (within 2 % here); they
# part where the contact jumps across the tread.
assert np.allclose(harmonic, klingel, rtol=0.02)
