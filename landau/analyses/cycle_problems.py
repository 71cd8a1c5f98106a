"""A model's smooth system as the cycle engine's input: :class:`~landau.periodic.problem.CycleProblem`.

Every model whose motion (or a smooth part of it) is a :class:`~landau.systems.system.DynamicalSystem`
E(p)·ẏ = f(y; p) declares its ``cycles`` through :func:`cycle_problem`: the field and its Jacobian
come from the one numeric builder of the system (:func:`landau.analyses.shooting.numeric_field`, the
one :func:`landau.check` shoots with), E⁻¹ applied, vectorised over the columns of ``y`` as the
engine's contract asks; the Hopf point it starts from is the model's own Hopf result
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
from typing import Mapping

import numpy as np

from landau.errors import InputError
from landau.periodic.problem import CycleProblem, HopfStart


def _stack(values, shape: tuple[int, ...]) -> np.ndarray:
    """The lambdified entries (scalars where an entry is constant) broadcast to ``shape`` and stacked."""
    return np.stack([np.broadcast_to(np.asarray(v, dtype=float), shape) for v in values])


def _without_unknowns(system, values: Mapping[str, float]):
    """``system`` with its numeric unknowns (a steady state with no closed form) replaced by their values."""
    if not system.unknowns:
        return system
    from dataclasses import replace

    missing = [u.name for u in system.unknowns if u.name not in values]
    if missing:
        raise InputError(f"{system.name}: the values of the unknowns {', '.join(missing)} are needed")
    sub = {u: float(values[u.name]) for u in system.unknowns}
    return replace(system, rhs=tuple(e.xreplace(sub) for e in system.rhs),
                   equilibrium=tuple(e.xreplace(sub) for e in system.equilibrium), unknowns=(),
                   unknown_equations=(), unknown_guess=())


def vector_field(system, params: Mapping[str, float]):
    """``(rhs, jac)`` of ẏ = E(p)⁻¹ f(y; p) vectorised as :class:`CycleProblem` asks.

    ``rhs(y, p)``: (n,) → (n,), (n, m) → (n, m); ``jac(y, p)``: (n, n) or (n, n, m).  The
    pieces are :func:`landau.analyses.shooting.numeric_field`'s (E must be invertible: a
    differential-algebraic system is refused there with an InputError).
    """
    from landau.analyses.shooting import numeric_field

    f, J, E_inverse, vals = numeric_field(system, params, entries=True)
    n = len(system.states)
    cache: dict[float, np.ndarray] = {}

    def einv(p: float) -> np.ndarray:
        p = float(p)
        if p not in cache:
            if len(cache) > 64:
                cache.clear()
            cache[p] = E_inverse(p)
        return cache[p]

    def rhs(y, p):
        y = np.asarray(y, dtype=float)
        F = _stack(f(*y, float(p), *vals), y.shape[1:])
        return np.tensordot(einv(p), F, axes=(1, 0))

    def jac(y, p):
        y = np.asarray(y, dtype=float)
        A = _stack(J(*y, float(p), *vals), y.shape[1:]).reshape(n, n, *y.shape[1:])
        return np.tensordot(einv(p), A, axes=(1, 0))

    return rhs, jac


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
    system = _without_unknowns(system, unknowns or {})
    used = {s.name for s in system.parameters}
    fixed = {k: float(v) for k, v in params.items() if k in used}
    rhs, jac = vector_field(system, fixed)
    states = tuple(s.name for s in system.states)
    measure = system.normalise
    start = None
    if result is not None:
        if result.normalise in states:
            measure = states.index(result.normalise)
        y0 = result.equilibrium if len(result.equilibrium) else equilibrium_values(system, fixed, result.p_c)
        start = hopf_start(result, jac, measure, y0)
    scales = None if start is None else state_scales(start, 0.1 * (abs(start.p_c) or 1.0))
    return CycleProblem(name=name or system.name, states=states, parameter=system.parameter.name, rhs=rhs,
                        jac=jac, params=fixed, scales=scales, measure=measure, hopf=start,
                        parameter_range=parameter_range)


def equilibrium_values(system, params: Mapping[str, float], p: float) -> np.ndarray:
    """The system's closed-form equilibrium y₀ (its ``equilibrium`` expressions) at ``params`` and p."""
    from landau.support.lambdify import lambdify_positional

    args = [system.parameter, *system.parameters]
    y0 = lambdify_positional(args, list(system.equilibrium), "numpy")(float(p), *(params[a.name] for a in args[1:]))
    y0 = np.asarray(y0, dtype=float)
    if not np.all(np.isfinite(y0)):
        raise InputError(f"{system.name}: the equilibrium is not finite at these parameters: {y0.tolist()}")
    return y0


__all__ = ["cycle_problem", "hopf_start", "equilibrium_values", "state_scales", "vector_field"]
