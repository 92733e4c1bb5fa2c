"""Axle-box roller bearings: the paper's double-row tapered roller bearing (DTRB; Eqs. 1-16:
W. Zhao, J. Ding, X. Liao, W. Liu, "Investigation on coaxial pseudo-fault characteristics induced
by the outer ring defect in the single-sided axle-box bearing of wheelset in urban rail vehicles",
Scientific Reports (2025), doi:10.1038/s41598-025-93857-x) and the models beside it.

* :mod:`.models` the list of models and the one point where the kernels pick one; :mod:`.dtrb`
  the DTRB (its parameters :mod:`.params`), with :mod:`.stiffness` contact stiffnesses (Eqs.
  5-11), :mod:`.quasistatic` series-spring ring equilibrium.
* The shared parts, plain arrays read by name (:mod:`.layout`): :mod:`.roller` a roller's and a
  cage's kinematics and Newton-Euler equations (Eqs. 2, 12, 13); :mod:`axlebox.bearing.contact`
  the contact laws (Eqs. 4, 9); :mod:`.pocket` the cage pockets (Eqs. 9-11); :mod:`.defects` Eq.
  (14); :mod:`.blocks` the implicit steps' rows; :mod:`.evaluate` one bearing's right-hand side
  (Eqs. 1-16); :mod:`.kernel_numpy` the DTRB's plain-numpy twin.
* Stepping: :mod:`.step` the dynamic bearing's leapfrog and :mod:`.implicit` its implicit kick;
  :mod:`.quasidynamic` the quasi-dynamic bearing; :mod:`.advance` the exchange window.
* :mod:`.equilibrium` the quasi-static start; :mod:`axlebox.bearing.integrate` and :mod:`.rig`
  the standalone rig; :mod:`.frequencies`, :mod:`.catalogue` fault orders; :mod:`.loaddist` Harris load
  integrals; :mod:`.resultfile` the ``axlebox-result`` file; :mod:`.spectra` the envelope
  spectrum."""
from axlebox import _numba  # noqa: F401  (before any kernel compiles or loads)

