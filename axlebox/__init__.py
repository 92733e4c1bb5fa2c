"""axlebox: railway vehicle dynamics with flexible bodies and axle-box bearing faults.

The subpackages are the architecture, and data flows one way through them::

    geometry -> fem -> (reduced-body files) -> mbs <- bearing;  pipelines on top

* :mod:`axlebox.geometry` parametric gmsh models of the wheelset, axle-box and bogie frame
* :mod:`axlebox.fem` scikit-fem assembly, free-free modes, Guyan / Craig-Bampton, body files
* :mod:`axlebox.mbs` the floating-frame multibody solver, wheel-rail contact, track, vehicle
* :mod:`axlebox.bearing` the double-row tapered roller bearing (paper Eqs. 1-16), diagnostics
* :mod:`axlebox.pipelines` what users run, and the ``axlebox`` command line
* :mod:`axlebox.configs` the shipped configs

In the repository each subpackage is a top-level folder; ``pyproject.toml`` maps them under this
package when it is installed.
"""
from pathlib import Path as _Path

from ._params import ParameterError

__version__ = "0.1.0"
__all__ = ["ParameterError", "__version__"]

# Run from a source checkout that is not installed (``python -m axlebox`` in the checkout), the
# subpackages are the folders beside this one: let the import system find them there too.
_top = _Path(__file__).resolve().parent.parent
if (_top / "pyproject.toml").is_file() and (_top / "pipelines" / "cli.py").is_file():
    __path__.append(str(_top))
del _Path, _top
