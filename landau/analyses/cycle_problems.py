"""A model's smooth system as the cycle engine's input: :class:`~landau.periodic.problem.CycleProblem`.

Every model whose motion (or a smooth part of it) is a :class:`~landau.systems.system.DynamicalSystem`
E(p)·ẏ = f(y; p) declares its ``cycles`` through :func:`cycle_problem`: the field and its Jacobian
come from the one numeric builder of the system (:mod:`landau.systems.numeric_field`, the
one :func:`landau.check` shoots with) through :meth:`CycleProblem.from_system`: E⁻¹ applied,
vectorised over the columns of ``y`` as the engine's contract asks, with the exact ∂f/∂p and the
multilinear forms of the normal forms; the Hopf point it starts from is the model's own Hopf result
(:func:`hopf_start`: p_c, ω_c, the critical eigenvector q of J(y₀; p_c) for iω_c with its
normalised component q_n = 1, the amplitude equation's C, its side and Λ, Λ₅).

A cycle's amplitude is the half peak-to-peak swing of the state the amplitude equation is
normalised on (the slip X of a spring–block: Putelat, Dawes & Willis 2010, eq. 26, A = C·sqrt|k − k_c|),
so that the continued branch and C·sqrt|p − p_c| are the same number near onset.

References
----------
Kuznetsov, Y. A. (2004), *Elements of Applied Bifurcation Theory*, 3rd ed., Springer, Sec. 3.5
(the Hopf point and its critical eigenvector) and Ch. 10 (cycles as a boundary-value problem).
Putelat, T., Dawes, J. H. P. & Willis, J. R. (2010), Regimes of frictional sliding of a spring–block
system, J. Mech. Phys. Solids 58, 27–53.
"""

from __future__ import annotations

import math
from dataclasses import replace
from typing import Mapping

import numpy as np

from landau.errors import InputError
from landau.periodic.from_system import without_unknowns
from landau.periodic.problem import CycleProblem, HopfStart


def hopf_start(result, jac, measure: int, y0) -> HopfStart:
    """The :class:`HopfStart` of a model's Hopf result (a :class:`~landau.derivation.hopf.HopfResult`)
    at the equilibrium ``y0``.

    The critical eigenvector q is recomputed from ``jac`` at (y₀, p_c): the eigenvector of the
    eigenvalue nearest iω_c, scaled so that q[measure] = 1 (the normalisation of C and Λ).
    """
    y0 = np.asarray(y0, dtype=float)
    # the eigenproblem J(y₀; p_c) q = λ q, λ ≈ iω_c (Kuznetsov 2004, Sec. 3.5)
    lam, vecs = np.linalg.eig(np.asarray(jac(y0, result.p_c), dtype=float))
    i = int(np.argmin(np.abs(lam - 1j * result.omega_c)))
    q = vecs[:, i]
    if abs(q[measure]) < 1e-300:
        raise InputError(f"{result.system}: the critical mode does not move state {measure}: no amplitude measure")
    q = q / q[measure]
    C = result.C
    L5 = getattr(result, "Lambda5", None)
    return HopfStart(p_c=float(result.p_c), equilibrium=y0, omega=float(result.omega_c), eigenvector=q,
                     amplitude=float(C) if math.isfinite(C) else None, side=int(result.cycle_side),
                     Lambda=float(result.Lambda) if math.isfinite(result.Lambda) else None,
                     Lambda5=None if L5 is None or not math.isfinite(L5) else float(L5))


def state_scales(start: HopfStart, p_range: float) -> np.ndarray:
    """A typical magnitude of each state: the larger of |y₀,i| and the predicted swing |q_i|·C·sqrt(p_range)
    (the swing at a parameter distance ``p_range`` from onset), floored at 1e-12 of the largest."""
    C = start.amplitude if start.amplitude is not None else 1.0
    swing = np.abs(start.eigenvector) * C * math.sqrt(abs(p_range))
    s = np.maximum(np.abs(start.equilibrium), swing)
    top = float(np.max(s)) if np.all(np.isfinite(s)) and np.max(s) > 0 else 1.0
    return np.maximum(np.where(np.isfinite(s), s, top), 1e-12 * top)


def cycle_problem(system, params: Mapping[str, float], result, *, name: str | None = None,
                  unknowns: Mapping[str, float] | None = None,
                  parameter_range: tuple[float, float] = (-np.inf, np.inf)) -> CycleProblem:
    """The :class:`CycleProblem` of ``system`` at ``params`` started from its Hopf ``result``.

    Parameters
    ----------
    system : DynamicalSystem
        E(p)·ẏ = f(y; p) with p = ``system.parameter`` the continuation parameter.
    params : mapping of str to float
        Every other parameter's value (names the system does not use are ignored).
    result : HopfResult or None
        The model's Hopf point (its ``normalise`` names the amplitude's state); None: no start
        (the branch is then started from a simulated cycle or a guess), measured on ``system.normalise``.
    name : str, optional
        The problem's name (default the system's).
    unknowns : mapping, optional
        Values of the system's numeric unknowns (a steady state with no closed form).
    parameter_range : (float, float)
        Where p is meaningful (k > 0 for a spring–block).
    """
    problem = CycleProblem.from_system(system, params, name=name, unknowns=unknowns,
                                       parameter_range=parameter_range)
    if result is None:
        return problem
    measure = problem.states.index(result.normalise) if result.normalise in problem.states else problem.measure
    if len(result.equilibrium):
        y0 = result.equilibrium
    else:
        y0 = equilibrium_values(without_unknowns(system, unknowns or {}), problem.params, result.p_c)
    start = hopf_start(result, problem.jac, measure, y0)
    return replace(problem, measure=measure, hopf=start,
                   scales=state_scales(start, 0.1 * (abs(start.p_c) or 1.0)))


def equilibrium_values(system, params: Mapping[str, float], p: float) -> np.ndarray:
    """The system's closed-form equilibrium y₀ (its ``equilibrium`` expressions) at ``params`` and p."""
    from landau.support.lambdify import lambdify_positional

    args = [system.parameter, *system.parameters]
    y0 = lambdify_positional(args, list(system.equilibrium), "numpy")(float(p), *(params[a.name] for a in args[1:]))
    y0 = np.asarray(y0, dtype=float)
    if not np.all(np.isfinite(y0)):
        raise InputError(f"{system.name}: the equilibrium is not finite at these parameters: {y0.tolist()}")
    return y0


__all__ = ["cycle_problem", "hopf_start", "equilibrium_values", "state_scales"]
