"""The floating-frame multibody solver: bodies, force elements, the system, its integrators.

:mod:`.body` rigid and flexible bodies (the reduced-body files of :mod:`axlebox.fem`; its numpy
twin :mod:`.ffrf_numpy`), :mod:`.elements` force elements, :mod:`.system` the assembled system
and :mod:`.integrate` its integrators; they run on :mod:`axlebox.mbs.kernel`.
"""
