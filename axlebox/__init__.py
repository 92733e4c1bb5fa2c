"""axlebox: railway vehicle dynamics with flexible bodies and axle-box bearing faults.

The subpackages are the architecture, and data flows one way through them::

    geometry -> fem -> (reduced-body files) -> mbs <- bearing;  pipelines on top

* :mod:`axlebox.geometry` parametric gmsh models of the wheelset, axle-box and bogie frame
* :mod:`axlebox.fem` scikit-fem assembly, free-free modes, Guyan / Craig-Bampton, body files
* :mod:`axlebox.mbs` the floating-frame multibody solver, wheel-rail contact, track, vehicle
* :mod:`axlebox.bearing` the double-row tapered roller bearing (the paper's Eqs. 1-16), diagnostics
* :mod:`axlebox.pipelines` what users run, and the ``axlebox`` command line
* :mod:`axlebox.configs` the shipped configs

"The paper" in the docstrings is the publication whose model this package reproduces and
extends: W. Zhao, J. Ding, X. Liao, W. Liu, "Investigation on coaxial pseudo-fault
characteristics induced by the outer ring defect in the single-sided axle-box bearing of
wheelset in urban rail vehicles", Scientific Reports (2025), doi:10.1038/s41598-025-93857-x
(short form: Zhao et al., Sci. Rep. 2025).

In the repository each subpackage is a top-level folder; ``pyproject.toml`` maps them under this
package when it is installed (from a checkout: ``python3 -m pip install -e .``, which maps the
same folders and nothing else: the checkout's tests, benchmarks or build folders never import as
``axlebox.*``).
"""
from ._params import ParameterError

__version__ = "0.1.0"
__all__ = ["ParameterError", "__version__"]
