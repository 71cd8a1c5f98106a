"""The one numeric field builder of a :class:`~landau.systems.system.DynamicalSystem` E(p)·ẏ = f(y; p, q).

Every numeric route that needs a user's system as numbers builds it here, so a system is turned into
code once and in one way:

* :func:`numeric_field` — ``(f, J, E_inverse, vals)``: the right-hand side, its Jacobian in the states
  and the inverse mass matrix as numpy functions of the state and the bifurcation parameter (the
  pieces :func:`landau.check` shoots with);
* :func:`vectorised_field` — ẏ = E(p)⁻¹ f(y; p), ∂ẏ/∂y and ∂ẏ/∂p on many points in one call (a column
  of ``y`` per point), the contract of the cycle engine :class:`landau.periodic.CycleProblem`;
* :func:`multilinear_forms` — the exact second- and third-order forms of ẏ in y,
  B(u, v) = Σ ∂²ẏ/∂y_b∂y_c u_b v_c and C(u, v, w), differentiated symbolically and compiled only when
  first called (the normal forms of cycle bifurcations ask for them at a handful of points; a chain of
  a hundred blocks never pays for its n³ third derivatives unless it asks).

E depends on the parameters and on p, never on the states (:class:`DynamicalSystem` refuses a
state-dependent E), so E⁻¹ multiplies f, J, B and C alike, once per parameter value.
"""

from __future__ import annotations

from typing import Any, Callable, Mapping

import numpy as np

from landau.errors import InputError
from landau.support.lambdify import lambdify_positional
from landau.support.memo import FloatMemo


def numeric_field(system, params: Mapping[str, float], *, entries: bool = False):
    """The system's numeric pieces for a given parameter set: ``(f, J, E_inverse, vals)`` with
    ``f(*y, p, *vals)`` the right-hand side, ``J(*y, p, *vals)`` its Jacobian in the states,
    ``E_inverse(p)`` the inverse mass matrix and ``vals`` the values of ``system.parameters``.
    With ``entries``, ``J`` gives the n² entries row by row as a flat list (each a scalar or an
    array like the states: what the cycle engine evaluates on many points in one call).

    Raises :class:`~landau.errors.InputError` naming a missing parameter, or (from ``E_inverse``)
    a mass matrix that is not invertible (a differential-algebraic system)."""
    import sympy as sp

    missing = [s.name for s in system.parameters if s.name not in params]
    if missing:
        raise InputError(f"{system.name}: missing parameter(s) {', '.join(missing)}")
    vals = [float(params[s.name]) for s in system.parameters]
    args = [*system.states, system.parameter, *system.parameters]
    f = lambdify_positional(args, list(system.rhs), "numpy")
    jac = sp.Matrix(system.rhs).jacobian(system.states)
    J = lambdify_positional(args, list(jac) if entries else jac, "numpy")
    E_of = lambdify_positional([system.parameter, *system.parameters], system.mass_matrix, "numpy")

    def E_inverse(p: float) -> np.ndarray:
        E = np.asarray(E_of(p, *vals), dtype=float)
        if not np.all(np.isfinite(E)) or abs(np.linalg.det(E)) < 1e-300 or np.linalg.cond(E) > 1e14:
            raise InputError(f"{system.name}: direct simulation needs an invertible mass matrix E; a "
                             "differential-algebraic system (singular E) is not supported by the generic check")
        # E⁻¹ once per parameter value: ẏ = E⁻¹ f(y; p) and ∂ẏ/∂y = E⁻¹ J(y; p) (E is small and
        # well conditioned here: cond(E) ≤ 1e14 was checked above)
        return np.linalg.inv(E)

    return f, J, E_inverse, vals


def _stack(values, shape: tuple[int, ...]) -> np.ndarray:
    """The lambdified entries (scalars where an entry is constant) broadcast to ``shape`` and stacked."""
    return np.stack([np.broadcast_to(np.asarray(v, dtype=float), shape) for v in values])


def _inverse_mass(E_inverse: Callable[[float], np.ndarray]) -> FloatMemo[np.ndarray]:
    """E(p)⁻¹ by parameter value, the last 64 values kept (a branch revisits its parameters)."""
    return FloatMemo(E_inverse, 64)


def vectorised_field(system, params: Mapping[str, float]):
    """``(rhs, jac, dfdp)`` of ẏ = E(p)⁻¹ f(y; p), each on many points in one call.

    ``rhs(y, p)``: (n,) → (n,), (n, m) → (n, m); ``jac(y, p)``: (n, n) or (n, n, m);
    ``dfdp(y, p)`` like ``rhs``: ∂ẏ/∂p = E⁻¹(∂f/∂p − ∂E/∂p·E⁻¹f). The pieces are
    :func:`numeric_field`'s (E must be invertible: a differential-algebraic system is refused
    with an InputError naming it).
    """
    import sympy as sp

    if system.mass_is_diagonal and any(e == 0 for e in system.mass):
        # a zero row of a diagonal E is an algebraic equation: refused before any compilation (a full
        # E is checked by E_inverse at each parameter value, where it is first inverted)
        raise InputError(f"{system.name}: the mass matrix is singular (an algebraic row, a differential-"
                         "algebraic system); cycles and simulations need E invertible")
    f, J, E_inverse, vals = numeric_field(system, params, entries=True)
    n = len(system.states)
    einv = _inverse_mass(E_inverse)
    args = [*system.states, system.parameter, *system.parameters]
    p = system.parameter
    f_p = lambdify_positional(args, [sp.diff(e, p) for e in system.rhs], "numpy")
    dE = sp.Matrix(system.mass_matrix).diff(p)
    E_p = None if dE.is_zero_matrix else lambdify_positional([p, *system.parameters], dE, "numpy")

    def rhs(y, par):
        y = np.asarray(y, dtype=float)
        F = _stack(f(*y, float(par), *vals), y.shape[1:])
        return np.tensordot(einv(par), F, axes=(1, 0))

    def jac(y, par):
        y = np.asarray(y, dtype=float)
        A = _stack(J(*y, float(par), *vals), y.shape[1:]).reshape(n, n, *y.shape[1:])
        return np.tensordot(einv(par), A, axes=(1, 0))

    def dfdp(y, par):
        y = np.asarray(y, dtype=float)
        G = _stack(f_p(*y, float(par), *vals), y.shape[1:])
        if E_p is not None:
            # ∂(E⁻¹f)/∂p = E⁻¹(∂f/∂p − ∂E/∂p·E⁻¹f): the product rule on E·ẏ = f
            F = np.tensordot(einv(par), _stack(f(*y, float(par), *vals), y.shape[1:]), axes=(1, 0))
            G = G - np.tensordot(np.asarray(E_p(float(par), *vals), dtype=float), F, axes=(1, 0))
        return np.tensordot(einv(par), G, axes=(1, 0))

    return rhs, jac, dfdp


Form = Callable[..., np.ndarray]


def multilinear_forms(system, params: Mapping[str, float]) -> tuple[Form, Form]:
    """``(B, C)``: B(y, p, u, v) = Σ_bc ∂²ẏ/∂y_b∂y_c u_b v_c and C(y, p, u, v, w) = Σ_bcd ∂³ẏ/∂y_b∂y_c∂y_d u_b v_c w_d
    of ẏ = E(p)⁻¹ f(y; p), exact, each compiled on its first call.

    The directional derivatives are taken one direction at a time, D_u f = J·u, then D_v(D_u f),
    then D_w(D_v D_u f): n² first derivatives instead of the n³ entries of the third-derivative
    tensor. Vectors and states may carry a trailing axis of points, as in :func:`vectorised_field`.
    """
    missing = [s.name for s in system.parameters if s.name not in params]
    if missing:
        raise InputError(f"{system.name}: missing parameter(s) {', '.join(missing)}")
    vals = [float(params[s.name]) for s in system.parameters]
    n = len(system.states)
    built: dict[int, Any] = {}
    inverse: list[FloatMemo[np.ndarray]] = []

    def einv(p: float) -> np.ndarray:
        if not inverse:
            inverse.append(_inverse_mass(numeric_field(system, params)[2]))
        return inverse[0](p)

    def compiled(order: int):
        if order not in built:
            import sympy as sp

            y = list(system.states)
            dirs = [sp.symbols(f"_{c}0:{n}", real=True) for c in "uvw"[:order]]
            expr = sp.Matrix(system.rhs)
            for d in dirs:  # D_d expr = Σ_c ∂expr/∂y_c d_c
                expr = expr.jacobian(y) * sp.Matrix(d)
            args = [*y, system.parameter, *system.parameters, *(s for d in dirs for s in d)]
            built[order] = lambdify_positional(args, list(expr), "numpy")
        return built[order]

    def form(order: int) -> Form:
        def call(y, p, *vecs):
            y = np.asarray(y, dtype=float)
            flat = [x for v in vecs for x in np.asarray(v, dtype=float)]
            shape = np.broadcast_shapes(y.shape[1:], *(np.shape(v)[1:] for v in vecs))
            F = _stack(compiled(order)(*y, float(p), *vals, *flat), shape)
            return np.tensordot(einv(p), F, axes=(1, 0))
        return call

    return form(2), form(3)


__all__ = ["multilinear_forms", "numeric_field", "vectorised_field"]
