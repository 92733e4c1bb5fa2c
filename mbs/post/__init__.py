"""Post-processing of the car's signals: ride comfort, its frequency weightings, running safety.

:mod:`.comfort` Sperling's ride index and EN 12299's mean comfort N_MV, :mod:`.weighting` the
frequency weightings of ISO 2631 and EN 12299, :mod:`.safety` Y/Q against Nadal's limit and the
wheelsets' sum of Y against Prud'homme's.
"""
