"""Double-row tapered roller bearing (DTRB) of the axle-box (paper Eqs. 1-16).

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

