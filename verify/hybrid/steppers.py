"""Mode integrators ("steppers") the engine drives one step at a time.

Contract (the same members scipy's :class:`scipy.integrate.OdeSolver` has, so every
scipy solver qualifies unchanged): a *stepper factory* is a callable

    factory(fun, t0, y0, t_bound, jac) -> stepper

and the stepper has

* ``step()``: advance one step; returns ``None`` or an error message;
* ``status``: ``"running"``, ``"finished"`` (reached ``t_bound``) or ``"failed"``;
* ``t``, ``y``: the state after the step, ``t_old``: the time before it;
* ``dense_output()``: a callable interpolant valid on ``[t_old, t]`` accepting a scalar
  time (returns shape ``(n,)``) or a 1-D array of times (returns ``(n, m)``);
* ``nfev``: number of right-hand-side evaluations so far.

Steppers that keep ``f`` (the vector field at ``(t, y)``) current after every step — scipy's
explicit Runge–Kutta solvers and Radau, and any stepper that declares ``keeps_f = True`` (the
compiled DOP853) — let the engine screen each step on its cubic Hermite interpolant and skip the
dense output where no guard can cross (:class:`landau.verify.hybrid.locate.HermiteScreen`).

A compiled stepper only has to expose these members to be used by
:func:`landau.verify.hybrid.simulate` without change.  A factory that declares
``takes_kernel = True`` is handed a mode's compiled :class:`~landau.verify.hybrid.kernel.Kernel`
(generated from a symbolic declaration by :mod:`landau.codegen.kernels`) instead of its Python
``rhs``: :mod:`landau.verify.hybrid.dop853` (DOP853, with the guard screen inside its compiled
loop) is such a factory.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any, Callable, Mapping

import numpy as np

from landau.verify.hybrid.dop853 import CompiledDOP853

#: scipy.integrate solver classes by name (scipy is imported on first use)
_METHODS = ("DOP853", "RK45", "RK23", "Radau", "BDF", "LSODA")


@dataclass(frozen=True)
class ScipyStepper:
    """Factory for a scipy ``OdeSolver`` (DOP853 by default; Radau/BDF for stiff modes).

    ``rtol``/``atol`` are passed through; ``max_step`` bounds the step so that the
    guard sampling (a fixed number of dense-output samples per step) resolves the guards.
    """

    method: str = "DOP853"
    rtol: float = 1e-10
    atol: float = 1e-12
    max_step: float = np.inf
    first_step: float | None = None
    options: Mapping[str, Any] = field(default_factory=dict)

    def __call__(self, fun, t0: float, y0: np.ndarray, t_bound: float, jac=None):
        import scipy.integrate

        if self.method not in _METHODS:
            raise KeyError(self.method)
        cls = getattr(scipy.integrate, self.method)
        kw = dict(rtol=self.rtol, atol=self.atol, max_step=self.max_step, **self.options)
        if self.first_step is not None:
            kw["first_step"] = min(self.first_step, abs(t_bound - t0)) or None
        if jac is not None and self.method in ("Radau", "BDF", "LSODA"):
            kw["jac"] = jac
        return cls(fun, t0, y0, t_bound, **kw)

    def __repr__(self) -> str:
        return f"ScipyStepper({self.method}, rtol={self.rtol:g}, atol={self.atol:g})"


def DOP853Stepper(rtol: float = 1e-10, atol: float = 1e-12, **kw) -> ScipyStepper:
    """The default non-stiff stepper (8th order, 7th-order dense output)."""
    return ScipyStepper("DOP853", rtol, atol, **kw)


def RadauStepper(rtol: float = 1e-8, atol: float = 1e-10, **kw) -> ScipyStepper:
    """A stiff stepper (implicit, 5th order, uses ``Mode.jac`` when given)."""
    return ScipyStepper("Radau", rtol, atol, **kw)


StepperFactory = Callable[..., Any]



#: the hybrid engine's default: the compiled DOP853 over each mode's compiled kernel (scipy's DOP853,
#: the same method, for a mode whose field is a plain Python function), so that the quiet steps of a
#: mode run in one compiled call
DEFAULT_STEPPER = CompiledDOP853(rtol=1e-10, atol=1e-12)
