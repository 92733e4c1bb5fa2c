"""The track under the car: its irregularities, the rails' and wheels' roughness, its bed.

:mod:`.irregularity` the FRA spectra's irregularities, :mod:`.roughness` the rails' and wheels'
roughness (both sampled from their spectra by :mod:`.sampling`), :mod:`.bed` the track bed under
each wheel.  The line's design geometry (curves, transitions, cant) belongs here too.
"""
