"""landau — weakly nonlinear analysis of friction-driven oscillators.

Data flows one way: a friction law (:mod:`laws`) → a mechanical system
(:class:`SpringBlock`, or any :class:`DynamicalSystem`) → a derivation (:func:`derive`,
:func:`hopf_normal_form`) → numbers, LaTeX and compiled code.
"""

from landau.errors import InputError, IntegratorError, LandauError, NoHopfError, SingularPointError
from landau.general import HopfNormalForm, hopf_normal_form
from landau.linear import HopfLine, HopfPoint, critical_stiffness
from landau.multiscale import CONVENTION, Coefficient, Derivation, LandauPoint, derive
from landau.system import DynamicalSystem, SpringBlock

__all__ = [
    "CONVENTION", "Coefficient", "Derivation", "DynamicalSystem", "HopfLine", "HopfNormalForm", "HopfPoint",
    "InputError", "IntegratorError", "LandauError", "LandauPoint", "NoHopfError", "SingularPointError",
    "SpringBlock", "critical_stiffness", "derive", "hopf_normal_form",
]
