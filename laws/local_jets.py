"""The local jets of a rate-and-state law: the derivatives of μ and of every state rate, compiled once.

A system built from many copies of one law (a chain of blocks, a multi-degree-of-freedom brake
model) is nonlinear only through each copy's own slip rate and states.  Its multilinear forms
B, C, … at a steady state are therefore assembled from the derivatives of the law's
g(w) = (μ(v, φ₁…φₘ), dφ₁/dt, …, dφₘ/dt) in w = (v, φ₁…φₘ) at that state, one small tensor per
order whatever the number of copies.  :func:`law_jets` gives them: ``D[m]`` of shape
(m + 1 outputs) × (m + 1)^order, ``D[m][o, a, b, …]`` = ∂ᵐg_o/∂w_a∂w_b… (full derivatives, no
factorials; symmetric in the last indices).  Each law is differentiated once by sympy, for every
sorted multi-index up to the order asked, and compiled once into one numpy function
(:func:`_compiled`, cached per law and order), so evaluating the jets costs the same for one block
or a hundred.

References
----------
Kuznetsov, Yu. A. (2004). Elements of Applied Bifurcation Theory, 3rd ed., Springer, §3.5 and
§8.7 (the multilinear forms B, C of a vector field at an equilibrium).
Putelat, T., Dawes, J. H. P., Willis, J. R. (2010). Regimes of frictional sliding of a spring–block
system. J. Mech. Phys. Solids 58, 27–53, eq. (4) (μ and the state rate of one block).
"""

from __future__ import annotations

import itertools
from functools import lru_cache
from typing import TYPE_CHECKING, Callable, Mapping, Sequence

import numpy as np

from landau.support.lambdify import lambdify_positional

if TYPE_CHECKING:
    from landau.laws.law import FrictionLaw


@lru_cache(maxsize=32)
def _compiled(law: FrictionLaw, order: int) -> tuple[list[tuple[int, int, tuple[int, ...]]], Callable]:
    """(entries, fn): every (order m, output o, sorted multi-index) of g's derivatives up to ``order``
    and one numpy function of (v, φ₁…φₘ, law parameters…) returning their values in that order."""
    import sympy as sp

    from landau.laws.law import v

    w = [v, *law.states]
    outputs = [law.mu, *law.rates]
    entries: list[tuple[int, int, tuple[int, ...]]] = []
    exprs = []
    for o, g in enumerate(outputs):
        cache: dict[tuple[int, ...], sp.Expr] = {(): g}
        for m in range(1, order + 1):
            for idx in itertools.combinations_with_replacement(range(len(w)), m):
                # ∂ᵐg/∂w_idx from the derivative one order lower (one sympy diff per entry)
                d = sp.diff(cache[idx[:-1]], w[idx[-1]])
                cache[idx] = d
                if d != 0:
                    entries.append((m, o, idx))
                    exprs.append(d)
    args = [*w, *(p.symbol for p in law.parameters)]
    fn = lambdify_positional(args, exprs, "numpy", cse=True) if exprs else (lambda *a: [])
    return entries, fn


def law_jets(law: FrictionLaw, v_value: float, phis: Sequence[float] | np.ndarray, params: Mapping[str, float],
             order: int = 3) -> dict[int, np.ndarray]:
    """The derivatives of g = (μ, dφ₁/dt, …) in w = (v, φ₁…φₘ) at (v_value, phis), orders 1…``order``.

    Parameters
    ----------
    law : FrictionLaw
    v_value : float
        The slip rate (m/s) of the point, e.g. the driving velocity V at steady sliding.
    phis : sequence of float or ndarray
        The states at the point (e.g. the steady state φ_ss(V)).
    params : mapping
        The law's parameter values by name.
    order : int
        The highest order (3 for Λ, 5 for the fifth-order coefficient).

    Returns
    -------
    dict of int to ndarray
        ``D[m]`` of shape (m + 1,) + (m + 1,)·m: ∂ᵐg_o/∂w_a…, symmetric in its last m indices.
    """
    entries, fn = _compiled(law, int(order))
    nw = 1 + len(law.states)
    vals = fn(float(v_value), *(float(x) for x in phis), *(float(params[p.name]) for p in law.parameters))
    D = {m: np.zeros((nw,) + (nw,) * m) for m in range(1, order + 1)}
    for (m, o, idx), val in zip(entries, vals, strict=True):
        val = float(val)
        for perm in set(itertools.permutations(idx)):
            D[m][(o,) + perm] = val
    return D


__all__ = ["law_jets"]
