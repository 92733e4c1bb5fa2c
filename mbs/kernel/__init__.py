"""The multibody solver's numba kernels: plain arrays in and out, every slot read by name.

:mod:`.body` one body in the floating frame, :mod:`.markers` markers, :mod:`.elements` force
elements, :mod:`.wheels` the wheels on their rails, :mod:`.bearings` the axle-box bearings,
:mod:`.speed` the speed profile, :mod:`.system` the system's right-hand side,
:mod:`.integrate` the integrators' runs and :mod:`.exchange` the bodies' exchange with the
bearings.
"""
