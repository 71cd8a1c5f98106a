"""A :class:`CycleProblem` from a symbolic system E·ẏ = f(y; p, q): E⁻¹f, its Jacobian and forms compiled.

The system is read by its attributes only (``states``, ``rhs``, ``mass_matrix``, ``parameter``,
``defaults``, ``name``, ``normalise``), as :class:`landau.systems.system.DynamicalSystem` has
them — user systems from strings (``DynamicalSystem.from_strings``) included. sympy is imported
only here, when a problem is built. The parameters other than p are substituted; the vector
field ẏ = E(p)⁻¹ f(y; p), ∂/∂y, ∂/∂p and the second- and third-order forms B, C are lambdified
by :func:`landau.support.lambdify.lambdify_positional` and wrapped to the contract's shapes
(a column per point; constant entries broadcast).
"""

from __future__ import annotations

from typing import Any, Callable, Mapping

import numpy as np

from landau.errors import InputError
from landau.periodic.problem import CycleProblem, HopfStart


def _flatten(nested: Any) -> list[Any]:
    if isinstance(nested, (list, tuple)):
        return [x for item in nested for x in _flatten(item)]
    return [nested]


def build(system: Any, params: Mapping[str, float] | None = None, *, hopf: HopfStart | None = None,
          measure: int | None = None, scales: np.ndarray | None = None,
          parameter_range: tuple[float, float] = (-np.inf, np.inf)) -> CycleProblem:
    """The :class:`CycleProblem` of ``system`` at the parameter values ``params`` (over its defaults)."""
    import sympy as sp

    from landau.support.lambdify import lambdify_positional

    values = {**dict(getattr(system, "defaults", {}) or {}), **dict(params or {})}
    p = system.parameter
    states = list(system.states)
    n = len(states)
    free = set().union(*(sp.sympify(e).free_symbols for e in system.rhs)) | set(system.mass_matrix.free_symbols)
    subs = {}
    for s in free - set(states) - {p}:
        if s.name not in values:
            raise InputError(f"system {system.name!r}: no value for parameter {s.name!r}; give it in params")
        subs[s] = float(values[s.name])
    E = sp.Matrix(system.mass_matrix).xreplace(subs)
    if E.det() == 0:
        raise InputError(f"system {system.name!r}: the mass matrix is singular (a DAE); cycles need E invertible")
    f = sp.Matrix([sp.sympify(e).xreplace(subs) for e in system.rhs])
    g = (E.inv() * f) if E != sp.eye(n) else f
    g = sp.Matrix([sp.simplify(e) if e.count_ops() < 200 else e for e in g])
    J = g.jacobian(states)
    u = sp.symbols(f"_u0:{n}", real=True)
    v = sp.symbols(f"_v0:{n}", real=True)
    w = sp.symbols(f"_w0:{n}", real=True)
    Bexpr = [sum(J[a, b].diff(states[c]) * u[b] * v[c] for b in range(n) for c in range(n)) for a in range(n)]
    Cexpr = [sum(J[a, b].diff(states[c]).diff(states[d]) * u[b] * v[c] * w[d]
                 for b in range(n) for c in range(n) for d in range(n)) for a in range(n)]
    args = [list(states), p]
    f_n = lambdify_positional(args, list(g), "numpy")
    J_n = lambdify_positional(args, J.tolist(), "numpy")
    P_n = lambdify_positional(args, list(g.diff(p)), "numpy")
    B_n = lambdify_positional([list(states), p, list(u), list(v)], Bexpr, "numpy")
    C_n = lambdify_positional([list(states), p, list(u), list(v), list(w)], Cexpr, "numpy")

    def shaped(fn: Callable[..., Any], shape: tuple[int, ...]) -> Callable[..., np.ndarray]:
        def call(y: np.ndarray, par: float, *vecs: np.ndarray) -> np.ndarray:
            y = np.asarray(y, dtype=float)
            tail = y.shape[1:]
            out = fn(list(y), float(par), *[list(np.asarray(x, dtype=float)) for x in vecs])
            flat = [np.broadcast_to(np.asarray(x, dtype=float), tail) for x in _flatten(out)]
            return np.array(flat).reshape(shape + tail)
        return call

    j = system.normalise if measure is None else measure
    return CycleProblem(
        name=str(system.name), states=tuple(s.name for s in states), parameter=p.name,
        rhs=shaped(f_n, (n,)), jac=shaped(J_n, (n, n)), params={k: float(x) for k, x in values.items()},
        dfdp=shaped(P_n, (n,)), multilinear=(shaped(B_n, (n,)), shaped(C_n, (n,))), scales=scales,
        measure=int(j), hopf=hopf, parameter_range=parameter_range)
