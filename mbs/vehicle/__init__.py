"""The B-type metro car: its config, bodies and suspension, bearings, statics, speed, wheels.

:mod:`.config` its run configuration, :mod:`.car` its bodies and suspension on the track,
:mod:`.bearings` its axle-box bearings, :mod:`.statics` its steady-running equilibrium,
:mod:`.speed` its speed profile, :mod:`.wheel_defects` its wheels' tread defects.
"""
