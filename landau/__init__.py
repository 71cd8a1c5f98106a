"""landau — weakly nonlinear analysis of friction-driven oscillators.

Data flows one way: a friction law (:mod:`laws`) → a mechanical system
(:class:`SpringBlock`, or any :class:`DynamicalSystem`) → a derivation (:func:`derive`,
:func:`hopf_normal_form`) → numbers, LaTeX and compiled code.
"""

from typing import TYPE_CHECKING

from landau.derivation.hopf import Convention, Criticality, HopfResult
from landau.errors import InputError, IntegratorError, LandauError, NoHopfError, SingularPointError

if TYPE_CHECKING:  # the same names as _LAZY, for type checkers and the API documentation
    __version__: str
    from landau.analyses.checking import CheckResult, Verdict, check
    from landau.analyses.cycles import cycles
    from landau.analyses.sweep import sweep
    from landau.derivation.general import hopf_normal_form
    from landau.derivation.linear import HopfLine, HopfPoint, critical_stiffness
    from landau.derivation.multiscale import CONVENTION, Coefficient, Derivation, derive
    from landau.simulation import simulate
    from landau.systems.system import DynamicalSystem, SpringBlock

# The derivation engine (sympy) loads on first use of one of its names, so that importing a
# subpackage (``landau.laws``, ``landau.verify.hybrid``) does not import it.
_LAZY = {
    "hopf_normal_form": "landau.derivation.general",
    "HopfLine": "landau.derivation.linear", "HopfPoint": "landau.derivation.linear",
    "critical_stiffness": "landau.derivation.linear",
    "CONVENTION": "landau.derivation.multiscale", "Coefficient": "landau.derivation.multiscale",
    "Derivation": "landau.derivation.multiscale",
    "derive": "landau.derivation.multiscale",
    "DynamicalSystem": "landau.systems.system", "SpringBlock": "landau.systems.system",
    "CheckResult": "landau.analyses.checking", "Verdict": "landau.analyses.checking",
    "check": "landau.analyses.checking",
    "sweep": "landau.analyses.sweep",
    "simulate": "landau.simulation",
    "cycles": "landau.analyses.cycles",
}


def _package_version() -> str:
    """The installed distribution's version (importlib.metadata reads it on first request)."""
    from importlib.metadata import PackageNotFoundError, version

    try:
        return version("landau-friction")
    except PackageNotFoundError:  # running from a source tree that was never installed
        return "0+unknown"


def __getattr__(name: str):
    if name == "__version__":
        value = globals()["__version__"] = _package_version()
        return value
    if name == "plotting":  # ``import landau; landau.plotting.plot_check(...)``
        import landau.plotting

        return landau.plotting
    if name in _LAZY:
        import importlib
        value = getattr(importlib.import_module(_LAZY[name]), name)
        globals()[name] = value
        return value
    raise AttributeError(f"module 'landau' has no attribute {name!r}")


def __dir__():
    return sorted(set(globals()) | set(_LAZY) | {"__version__", "plotting"})


__all__ = [
    "__version__",
    "CONVENTION", "CheckResult", "Coefficient", "Convention", "Criticality", "Derivation", "DynamicalSystem",
    "HopfLine", "HopfPoint", "HopfResult", "InputError", "IntegratorError", "LandauError",
    "NoHopfError", "SingularPointError", "SpringBlock", "Verdict", "check", "critical_stiffness",
    "derive", "hopf_normal_form", "simulate", "sweep",
    "cycles",
]
