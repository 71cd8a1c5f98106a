"""Exact derivatives of a system's right-hand side at its equilibrium, built lazily.

``Jets(system).order(n)`` builds the n-th derivative tensor of f at y₀ the first time it
is asked for and caches it; :attr:`Jets.built` records which orders were actually built,
so a caller asking only for k_c and ω_c can be shown never to build second or third
derivatives.  Tensors are stored sparsely over sorted index tuples.

Each non-trivial derivative value is replaced by an opaque real *atom* symbol
(``d_u_phi``, …) whose definition is kept in :attr:`Jets.atoms`.  The engine works on
atoms — small rational expressions, exactly the paper's "in terms of F_V, G_φ, …"
formulas (15)–(21) — and the atoms are substituted (for closed forms) or evaluated
first (for compiled code) only at the end.  This is what keeps derivation fast.
"""

from __future__ import annotations

import itertools
from typing import Any, Callable, Sequence

import sympy as sp

from landau.cx import Cx, cx_is_zero
from landau.system import DynamicalSystem


def _is_simple(expr: sp.Expr) -> bool:
    return expr.is_Number or expr.is_Symbol or (expr.is_Mul and len(expr.args) == 2 and expr.args[0].is_Number
                                                and expr.args[1].is_Symbol)


class Jets:
    """Lazy, cached derivative tensors of f at the equilibrium, in atom symbols."""

    def __init__(self, system: DynamicalSystem):
        self.system = system
        self.n = len(system.states)
        self._at = dict(zip(system.states, system.equilibrium))
        self._cache: dict[int, dict[tuple[int, ...], sp.Expr]] = {}
        self._param: tuple | None = None
        self.atoms: dict[sp.Symbol, sp.Expr] = {}
        self.built: list[int] = []

    def _atom(self, name: str, value: sp.Expr) -> sp.Expr:
        if value == 0:
            return sp.Integer(0)
        if _is_simple(value) or self.system.parameter in value.free_symbols:
            return value
        sym = sp.Symbol(name, real=True)
        self.atoms[sym] = value
        return sym

    def order(self, n: int) -> dict[tuple[int, ...], sp.Expr]:
        """{(i, j₁ ≤ … ≤ jₙ): ∂ⁿfᵢ/∂y_{j₁}…∂y_{jₙ} at y₀} (atoms), zero entries omitted."""
        if n in self._cache:
            return self._cache[n]
        ys = self.system.states
        out: dict[tuple[int, ...], sp.Expr] = {}
        for i, f in enumerate(self.system.rhs):
            for idx in itertools.combinations_with_replacement(range(self.n), n):
                if not all(ys[j] in f.free_symbols for j in set(idx)):
                    continue
                val = sp.diff(f, *[ys[j] for j in idx]).subs(self._at)
                name = f"d{n}_{ys[i].name}_" + "_".join(ys[j].name for j in idx)
                atom = self._atom(name, val)
                if atom != 0:
                    out[(i, *idx)] = atom
        self._cache[n] = out
        self.built.append(n)
        return out

    def jacobian(self) -> list[list[sp.Expr]]:
        J = [[sp.Integer(0)] * self.n for _ in range(self.n)]
        for (i, j), val in self.order(1).items():
            J[i][j] = val
        return J

    def parameter_derivatives(self) -> tuple[list[sp.Expr], list[list[sp.Expr]]]:
        """(∂f/∂p, ∂J/∂p) at the equilibrium: the unfolding of the Hopf point."""
        if self._param is None:
            p = self.system.parameter
            ys = self.system.states
            fp = [self._atom(f"dp_{ys[i].name}", sp.diff(f, p).subs(self._at)) for i, f in enumerate(self.system.rhs)]
            Jp = [[self._atom(f"dp_{ys[i].name}_{y.name}", sp.diff(f, p, y).subs(self._at)) for y in ys]
                  for i, f in enumerate(self.system.rhs)]
            self._param = (fp, Jp)
        return self._param

    def expand_atoms(self, expr: sp.Expr) -> sp.Expr:
        """Replace atoms by their definitions."""
        return expr.xreplace(self.atoms)


def multilinear(tensor: dict[tuple[int, ...], Any], vectors: Sequence[Sequence[Cx]], n: int,
                convert: Callable[[Any], Any] = lambda x: x) -> list[Cx]:
    """Σ over all index orderings of D[i, j₁…jₘ] a¹_{j₁}…aᵐ_{jₘ} (symmetric multilinear form)."""
    out = [Cx(0, 0) for _ in range(n)]
    for key, val in tensor.items():
        i, idx = key[0], key[1:]
        val = convert(val)
        for perm in set(itertools.permutations(idx)):
            term: Cx | None = None
            for slot, j in enumerate(perm):
                comp = vectors[slot][j]
                if cx_is_zero(comp):
                    term = None
                    break
                term = comp if term is None else term * comp
            if term is not None:
                out[i] = out[i] + term * val
    return out
