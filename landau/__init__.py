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

from typing import TYPE_CHECKING

from landau.errors import InputError, IntegratorError, LandauError, NoHopfError, SingularPointError
from landau.hopf import Convention, Criticality, HopfResult

if TYPE_CHECKING:  # the same names as _LAZY, for type checkers and the API documentation
    from landau.checking import CheckResult, Verdict, check
    from landau.general import hopf_normal_form
    from landau.linear import HopfLine, HopfPoint, critical_stiffness
    from landau.multiscale import CONVENTION, Coefficient, Derivation, derive
    from landau.system import DynamicalSystem, SpringBlock

# The derivation engine (sympy) loads on first use of one of its names, so that importing a
# subpackage (``landau.laws``, ``landau.verify.hybrid``) does not import it.
_LAZY = {
    "hopf_normal_form": "landau.general",
    "HopfLine": "landau.linear", "HopfPoint": "landau.linear", "critical_stiffness": "landau.linear",
    "CONVENTION": "landau.multiscale", "Coefficient": "landau.multiscale", "Derivation": "landau.multiscale",
    "derive": "landau.multiscale",
    "DynamicalSystem": "landau.system", "SpringBlock": "landau.system",
    "CheckResult": "landau.checking", "Verdict": "landau.checking", "check": "landau.checking",
}


def __getattr__(name: str):
    if name in _LAZY:
        import importlib
        value = getattr(importlib.import_module(_LAZY[name]), name)
        globals()[name] = value
        return value
    raise AttributeError(f"module 'landau' has no attribute {name!r}")


def __dir__():
    return sorted(set(globals()) | set(_LAZY))


__all__ = [
    "__version__",
    "CONVENTION", "CheckResult", "Coefficient", "Convention", "Criticality", "Derivation", "DynamicalSystem",
    "HopfLine", "HopfPoint", "HopfResult", "InputError", "IntegratorError", "LandauError",
    "NoHopfError", "SingularPointError", "SpringBlock", "Verdict", "check", "critical_stiffness",
    "derive", "hopf_normal_form",
]
