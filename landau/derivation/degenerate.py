"""One verdict at degenerate Hopf points: Λ with its round-off bound, and the next order where Λ vanishes.

The general engine (:func:`landau.derivation.general.hopf_normal_form`) computes Λ at ``dps``
digits.  At a point where Λ vanishes identically (the quasi-static aging-law spring–block at
K_cr, a centre: Ranjith & Rice 1999), the number it gets is round-off, ~10^(−dps) times the terms
that cancel, and its sign means nothing.  As :func:`landau.derivation.precision.evaluate_mp_checked`
does for ``derive``, the coefficient is evaluated at successive precisions (:data:`LADDER`): a
genuine value is the same at two of them (to :data:`REL_AGREE`), and the difference of the two
bounds its round-off; round-off of a vanishing quantity keeps shrinking with the precision and
never settles.  Such a Λ is reported as 0 with its bound, the criticality as ``degenerate``, and
the next order decides: the second Lyapunov coefficient l₂ = Re c₂ and Λ₅
(:func:`landau.derivation.lyapunov.lyapunov_coefficients`), settled the same way.

A differential-algebraic system (a zero mass entry: the quasi-static spring–block M = 0) is
turned into an ODE with the same dynamics on its constraint manifold (:func:`ode_on_constraint`):
the algebraic rows are differentiated along the flow, with a decay −κ·f_A that makes the
manifold f_A = 0 attracting, so that its centre manifold — where the normal form lives — is the
DAE's.

References
----------
Kuznetsov, Yu. A. (1999). Numerical normalization techniques for all codim 2 bifurcations of
equilibria in ODE's. SIAM J. Numer. Anal. 36, 1104–1124, §7.
Ranjith, K. & Rice, J. R. (1999). Stability of quasi-static slip in a single degree of freedom
elastic system with rate and state dependent friction. J. Mech. Phys. Solids 47, 1207–1218.
Baumgarte, J. (1972). Stabilization of constraints and integrals of motion in dynamical systems.
Comput. Methods Appl. Mech. Eng. 1, 1–16.
"""

from __future__ import annotations

import math
from dataclasses import replace
from typing import Any, Callable, Mapping, Sequence

import mpmath
import sympy as sp

from landau.errors import InputError
from landau.systems.system import DynamicalSystem

#: precisions (digits) of the successive evaluations (those of ``derive``, up to 200)
LADDER = (50, 80, 120, 200)
#: two evaluations agreeing to this (relative) settle a value (float64 results of ≥ 50-digit work)
REL_AGREE = 1e-12
#: float64 unit round-off ×2 (the reported values are float64)
EPS64 = 2.0 ** -52


def settle(compute: Callable[[int], float], dps: int, first: float | None = None,
           ladder: Sequence[int] = LADDER) -> tuple[float, float, bool]:
    """A coefficient evaluated at increasing precision until two evaluations agree.

    Parameters
    ----------
    compute : callable
        ``compute(dps) -> float``, the coefficient computed at ``dps`` digits.
    dps : int
        The first precision.
    first : float, optional
        The value already computed at ``dps``.
    ladder : sequence of int
        Higher precisions to try, in order (those above ``dps`` are used, at least one).

    Returns
    -------
    (value, bound, settled)
        ``settled``: two successive values agree to :data:`REL_AGREE`; ``value`` the first of the
        two and ``bound`` their difference (its round-off, over-estimated) plus the rounding of
        the value to float64.  Otherwise the value
        is round-off of a vanishing quantity: ``value`` 0 and ``bound`` the largest |value| of the
        last two precisions.
    """
    levels = [dps, *[d for d in ladder if d > dps]]
    if len(levels) == 1:
        levels.append(dps + 30)
    prev = compute(levels[0]) if first is None else first
    cur = prev
    for d in levels[1:]:
        cur = compute(d)
        if math.isfinite(cur) and math.isfinite(prev) and abs(cur - prev) <= REL_AGREE * abs(cur):
            return prev, abs(cur - prev) + 0.5 * EPS64 * abs(prev), True
        prev = cur
    return 0.0, max(abs(prev), abs(cur)), False


def algebraic_rows(system: DynamicalSystem, params: Mapping[str, float], p: float) -> list[int]:
    """Indices of the zero diagonal mass entries at these parameter values (empty for an ODE)."""
    if not system.mass_is_diagonal:
        return []
    subs = {s: sp.Float(float(params[s.name])) for s in system.parameters if s.name in params}
    subs[system.parameter] = sp.Float(float(p))
    out = []
    for i, e in enumerate(system.mass):
        val = sp.sympify(e, strict=True).xreplace(subs)
        if val.is_number and float(val) == 0.0:
            out.append(i)
    return out


def ode_on_constraint(system: DynamicalSystem, params: Mapping[str, float], p: float,
                      kappa: float) -> DynamicalSystem:
    """An ODE ẏ = g(y) whose flow on the constraint manifold f_A = 0 is that of the DAE E·ẏ = f.

    With D the differential rows (E_ii ≠ 0 at these parameters) and A the algebraic ones,
    ẏ_D = f_D/E_D and ẏ_A = −(∂f_A/∂y_A)⁻¹ (∂f_A/∂y_D · ẏ_D + κ f_A): along the flow
    df_A/dt = −κ f_A, so f_A = 0 is invariant and attracting (eigenvalue −κ transversally), and
    the Hopf point, its critical mode and its Lyapunov coefficients are the DAE's (index 1:
    ∂f_A/∂y_A invertible).

    Parameters
    ----------
    system : DynamicalSystem
        With a diagonal mass; returned unchanged if no entry vanishes.
    params : mapping
        The other parameters' values (which mass entries vanish).
    p : float
        The Hopf parameter's value (where the mass entries are tested).
    kappa : float
        The decay rate κ > 0 towards the manifold (any positive value; take ω_c for scale): the
        power of 2 nearest to it is used.

    Returns
    -------
    DynamicalSystem

    Raises
    ------
    InputError
        A non-diagonal singular mass, or an algebraic part that is not index 1.
    """
    alg = algebraic_rows(system, params, p)
    if not alg:
        return system
    n = len(system.states)
    diff = [i for i in range(n) if i not in alg]
    if not diff:
        raise InputError(f"{system.name}: every row is algebraic; there is no dynamics")
    ys = system.states
    f = [sp.sympify(e, strict=True) for e in system.rhs]   # expressions, never strings
    fA = sp.Matrix([f[i] for i in alg])
    FA = fA.jacobian([ys[i] for i in alg])
    FD = fA.jacobian([ys[i] for i in diff])
    gD = sp.Matrix([f[i] / system.mass[i] for i in diff])
    if FA.shape[0] == 1:
        inv = sp.Matrix([[1 / FA[0, 0]]])
    else:
        try:
            inv = FA.inv()
        except ValueError:
            raise InputError(f"{system.name}: the algebraic rows are not index 1 (their Jacobian in the "
                             "algebraic states is singular)") from None
    # κ as a power of 2 near the given rate: exact in the symbolic derivatives (a 15-digit sympy
    # Float times the integers of the derivatives would round, and break the cancellations that
    # make a Lyapunov coefficient vanish at ~1e-16 of its terms)
    if not (math.isfinite(kappa) and kappa > 0):
        raise InputError(f"kappa must be a positive rate, got {kappa!r}")
    kap = sp.Integer(2) ** int(round(math.log2(kappa)))
    gA = -inv * (FD * gD + kap * fA)
    rhs = [None] * n
    for j, i in enumerate(diff):
        rhs[i] = gD[j]
    for j, i in enumerate(alg):
        rhs[i] = gA[j]
    return replace(system, rhs=tuple(rhs), mass=tuple(sp.Integer(1) for _ in range(n)),
                   name=f"{system.name}")


def next_order(system: DynamicalSystem, params: Mapping[str, float] | None, result, dps: int) -> dict[str, Any]:
    """Λ₅ and l₂ at a located Hopf point, each settled over :data:`LADDER` (DAEs through
    :func:`ode_on_constraint`).

    Returns
    -------
    dict
        ``Lambda5``, ``l2`` (0 where they vanish to round-off), ``l2_bound`` and ``l2_settled``.
    """
    from landau.derivation.general import _frozen_equilibrium
    from landau.derivation.lyapunov import lyapunov_coefficients

    ode = ode_on_constraint(system, dict(params or {}), result.p_c, max(abs(result.omega_c), 1e-300))
    cache: dict[int, Any] = {}

    def at(d: int):
        if d not in cache:
            with mpmath.workdps(d):
                probe, values, pc = _frozen_equilibrium(ode, params, result)
                cache[d] = lyapunov_coefficients(probe, values, pc, dps=d, omega_c=result.omega_c, relocate=False)
        return cache[d]

    start = max(dps, 40)
    l2, bound, ok = settle(lambda d: float(at(d).l2), start)
    lam5 = 0.0
    if ok:
        used = next(d for d in sorted(cache) if float(cache[d].l2) == l2)
        lam5 = float(cache[used].Lambda5)
    return {"Lambda5": lam5, "l2": l2, "l2_bound": bound, "l2_settled": ok}


def with_verdict(system: DynamicalSystem, params: Mapping[str, float] | None, res, dps: int,
                 recompute: Callable[[int], Any]):
    """``res`` with Λ's round-off bound, and — where Λ vanishes — Λ = 0 and the next order.

    Parameters
    ----------
    system : DynamicalSystem
    params : mapping or None
    res : HopfResult
        The engine's result at ``dps`` digits.
    dps : int
    recompute : callable
        ``recompute(d) -> HopfResult``: the same point located and expanded at ``d`` digits.

    Returns
    -------
    HopfResult
        ``extra`` gains ``Lambda_bound``; at a degenerate point Λ = l₁ = Re c₁ = 0 (criticality
        ``degenerate``), ``Lambda5``/``l2`` are set, ``extra`` holds ``l2_bound``,
        ``criticality_next_order`` (from the sign of l₂, or ``degenerate``) and
        ``degenerate_at_every_order_computed`` (True when l₂ vanishes too).
    """
    lam, bound, ok = settle(lambda d: float(recompute(d).Lambda), dps, first=res.Lambda)
    extra = dict(res.extra)
    extra["Lambda_bound"] = bound
    if ok and lam != 0.0:
        return replace(res, extra=extra)
    c1 = None if res.c1 is None else complex(0.0, res.c1.imag)
    res = replace(res, Lambda=0.0, l1=0.0 if res.l1 is not None else None, c1=c1)
    nxt = next_order(system, params, res, dps)
    from landau.derivation.hopf import Criticality

    extra["l2_bound"] = nxt["l2_bound"]
    extra["criticality_next_order"] = Criticality.from_sign(nxt["l2"]).value if nxt["l2_settled"] else "degenerate"
    extra["degenerate_at_every_order_computed"] = not (nxt["l2_settled"] and nxt["l2"] != 0.0)
    return replace(res, Lambda5=nxt["Lambda5"], l2=nxt["l2"], extra=extra)
