"""Double-row tapered roller bearing (DTRB) of the axle-box (the paper's Eqs. 1-16: W. Zhao,
J. Ding, X. Liao, W. Liu, "Investigation on coaxial pseudo-fault characteristics induced by the
outer ring defect in the single-sided axle-box bearing of wheelset in urban rail vehicles",
Scientific Reports (2025), doi:10.1038/s41598-025-93857-x).

* :mod:`.params` parameters; :mod:`.stiffness` contact stiffnesses (Eqs. 5-11);
  :mod:`.frequencies` fault frequencies; :mod:`.loaddist` Harris load integrals;
  :mod:`.quasistatic` series-spring ring equilibrium.
* :mod:`.layout` the plain arrays; :mod:`.kernel` the numba right-hand side of rollers and cages
  (Eqs. 1-13, 15, 16) and :mod:`.kernel_numpy` its plain-numpy twin; :mod:`.defects` Eq. (14).
* :mod:`.equilibrium` the quasi-static start of the dynamic model; :mod:`.integrate` and
  :mod:`.rig` the standalone rig; :mod:`.resultfile` the ``axlebox-result`` file;
  :mod:`.spectra` the envelope spectrum.
"""
from axlebox import _numba  # noqa: F401  (before any kernel compiles or loads)

