"""Axle-box roller bearings: the paper's double-row tapered roller bearing (DTRB; Eqs. 1-16:
W. Zhao, J. Ding, X. Liao, W. Liu, "Investigation on coaxial pseudo-fault characteristics induced
by the outer ring defect in the single-sided axle-box bearing of wheelset in urban rail vehicles",
Scientific Reports (2025), doi:10.1038/s41598-025-93857-x) and the models beside it.

* :mod:`.models`: the list of models (the registry) and each model's module, its parameters and
  its rollers' contacts with the rings (:mod:`.models.dtrb`, :mod:`.models.dcrb`; the shared
  fields :mod:`.models.params`).
* :mod:`.kernel`: the numba parts every model shares, plain arrays read by name
  (:mod:`.kernel.layout`): a roller's and a cage's dynamics, the contact laws, the pockets, the
  ring contacts, one bearing's right-hand side, the implicit kick, the dynamic and quasi-dynamic
  sub-steps, the exchange window, and where a kernel picks a model's parts
  (:mod:`.kernel.dispatch`).
* :mod:`.statics`: the quasi-static ring equilibrium, the dynamic model's static start, the
  contact stiffnesses (Eqs. 5-11) and Harris's load-distribution integrals.
* Beside them: :mod:`.defects` the local defects (Eq. 14); :mod:`.frequencies`,
  :mod:`.catalogue` the fault orders; :mod:`.integrate`, :mod:`.rig` and :mod:`.resultfile` the
  standalone rig and its ``axlebox-result`` file; :mod:`.spectra` the envelope spectrum; and
  :mod:`.diagnostics`, the diagnosis of a two-channel record.
"""
from axlebox import _numba  # noqa: F401  (before any kernel compiles or loads)
