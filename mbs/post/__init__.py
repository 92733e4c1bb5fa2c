"""Post-processing of the car's signals: ride comfort and its frequency weightings.

:mod:`.comfort` Sperling's ride index and EN 12299's mean comfort N_MV, :mod:`.weighting` the
frequency weightings of ISO 2631 and EN 12299.
"""
