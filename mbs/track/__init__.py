"""The track under the car: the line's geometry, its irregularities and roughness, its bed.

:mod:`.line` the line's design geometry (tangents, transitions, curves with cant) and its track
frame, :mod:`.irregularity` the FRA spectra's irregularities, :mod:`.roughness` the rails' and
wheels' roughness (both sampled from their spectra by :mod:`.sampling`), :mod:`.bed` the track bed
under each wheel.
"""
