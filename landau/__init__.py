"""landau — weakly nonlinear analysis of friction-driven oscillators.

Data flows one way: a friction law (:mod:`laws`) → a mechanical system
(:class:`SpringBlock`, or any :class:`DynamicalSystem`) → a derivation (:func:`derive`,
:func:`hopf_normal_form`) → numbers, LaTeX and compiled code.
"""

from importlib.metadata import PackageNotFoundError as _PackageNotFoundError
from importlib.metadata import version as _version

try:
    __version__: str = _version("landau-friction")
except _PackageNotFoundError:  # running from a source tree that was never installed
    __version__ = "0+unknown"

from landau.errors import InputError, IntegratorError, LandauError, NoHopfError, SingularPointError
from landau.checking import CheckResult, Verdict, check
from landau.general import HopfNormalForm, hopf_normal_form
from landau.hopf import Convention, Criticality, HopfResult
from landau.linear import HopfLine, HopfPoint, critical_stiffness
from landau.multiscale import CONVENTION, Coefficient, Derivation, LandauPoint, derive
from landau.system import DynamicalSystem, SpringBlock

__all__ = [
    "__version__",
    "CONVENTION", "CheckResult", "Coefficient", "Convention", "Criticality", "Derivation", "DynamicalSystem",
    "HopfLine", "HopfNormalForm", "HopfPoint", "HopfResult", "InputError", "IntegratorError", "LandauError",
    "LandauPoint", "NoHopfError", "SingularPointError", "SpringBlock", "Verdict", "check", "critical_stiffness",
    "derive", "hopf_normal_form",
]
