"""A :class:`CycleProblem` from a symbolic system E(p)·ẏ = f(y; p, q).

The system is read by its attributes only (``states``, ``rhs``, ``mass_matrix``, ``parameter``,
``parameters``, ``defaults``, ``unknowns``, ``name``, ``normalise``), as
:class:`landau.systems.system.DynamicalSystem` has them — user systems from strings
(``DynamicalSystem.from_strings``) and every model's declared system alike. The numbers come from
the one numeric field builder of a system, :mod:`landau.systems.numeric_field`: ẏ = E(p)⁻¹f, ∂ẏ/∂y
and ∂ẏ/∂p vectorised over the points of a mesh, and the exact multilinear forms B, C of the normal
forms, compiled only if a bifurcation of cycles asks for them. sympy is imported only when a
problem is built.
"""

from __future__ import annotations

from dataclasses import replace
from typing import Any, Mapping

import numpy as np

from landau.errors import InputError
from landau.periodic.problem import CycleProblem, HopfStart


def without_unknowns(system: Any, values: Mapping[str, float]) -> Any:
    """``system`` with its numeric unknowns (a steady state with no closed form) replaced by their values."""
    if not system.unknowns:
        return system
    missing = [u.name for u in system.unknowns if u.name not in values]
    if missing:
        raise InputError(f"{system.name}: the values of the unknowns {', '.join(missing)} are needed")
    sub = {u: float(values[u.name]) for u in system.unknowns}
    return replace(system, rhs=tuple(e.xreplace(sub) for e in system.rhs),
                   equilibrium=tuple(e.xreplace(sub) for e in system.equilibrium), unknowns=(),
                   unknown_equations=(), unknown_guess=())


def build(system: Any, params: Mapping[str, float] | None = None, *, hopf: HopfStart | None = None,
          measure: int | None = None, scales: np.ndarray | None = None, name: str | None = None,
          unknowns: Mapping[str, float] | None = None,
          parameter_range: tuple[float, float] = (-np.inf, np.inf)) -> CycleProblem:
    """The :class:`CycleProblem` of ``system`` at the parameter values ``params`` (over its defaults;
    names the system does not use are ignored), with the unknowns' values ``unknowns`` where its
    steady state has no closed form."""
    from landau.systems.numeric_field import multilinear_forms, vectorised_field

    system = without_unknowns(system, unknowns or {})
    values = {**dict(getattr(system, "defaults", {}) or {}), **dict(params or {})}
    used = {s.name for s in system.parameters}
    fixed = {k: float(v) for k, v in values.items() if k in used}
    rhs, jac, dfdp = vectorised_field(system, fixed)
    j = system.normalise if measure is None else measure
    return CycleProblem(
        name=str(name or system.name), states=tuple(s.name for s in system.states),
        parameter=system.parameter.name, rhs=rhs, jac=jac, params=fixed, dfdp=dfdp,
        multilinear=multilinear_forms(system, fixed), scales=scales, measure=int(j), hopf=hopf,
        parameter_range=parameter_range)
