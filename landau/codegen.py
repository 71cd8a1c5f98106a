"""Compiled, vectorised evaluation of symbolic results (lambdify with CSE).

Results are formulas in *atoms* (derivatives of the law at the steady state, see
:mod:`landau.jets`) and parameters.  :class:`CompiledFormula` lambdifies the atom
definitions it needs and the formula separately, each with common-subexpression
elimination, and composes them: vectorised over numpy arrays in any argument.
"""

from __future__ import annotations

from typing import Callable, Mapping, Sequence

import numpy as np
import sympy as sp


def _dirac_np(x, *_):
    return np.where(np.asarray(x) == 0, np.inf, 0.0)


def _heaviside_np(x, h0=0.5):
    return np.heaviside(x, h0)


def _dirac_mp(x, *_):
    import mpmath
    return mpmath.inf if x == 0 else mpmath.mpf(0)


def _heaviside_mp(x, h0=0.5):
    import mpmath
    return mpmath.mpf(1) if x > 0 else (mpmath.mpf(0) if x < 0 else mpmath.mpf(h0))


def _modules(modules: str):
    """lambdify modules with the distributions a non-smooth law's derivatives produce
    (|v − v₀| → sign → DiracDelta): zero away from the kink, infinite on it."""
    if modules == "numpy":
        return [{"DiracDelta": _dirac_np, "Heaviside": _heaviside_np}, "numpy"]
    if modules == "mpmath":
        return [{"DiracDelta": _dirac_mp, "Heaviside": _heaviside_mp}, "mpmath"]
    return modules


def compile_expr(expr: sp.Expr, args: Sequence[sp.Symbol], modules: str = "numpy") -> Callable:
    """lambdify ``expr`` over ``args`` with CSE; broadcasts over numpy arrays."""
    fn = sp.lambdify(list(args), expr, modules=_modules(modules), cse=True)
    if modules != "numpy":
        return fn

    def f(*vals):
        with np.errstate(all="ignore"):
            out = fn(*vals)
        shape = np.broadcast(*[np.asarray(x) for x in vals]).shape if vals else ()
        return np.broadcast_to(np.asarray(out, dtype=float), shape) if shape else float(out)

    return f


class CompiledFormula:
    """f(args) = formula(atoms(args), args), compiled once, for numpy or mpmath."""

    def __init__(self, formula: sp.Expr, args: Sequence[sp.Symbol], atoms: Mapping[sp.Symbol, sp.Expr],
                 modules: str = "numpy"):
        self.formula = formula
        self.args = tuple(args)
        # atoms may be defined through other atoms (nested): resolve them in dependency order
        needed: list[sp.Symbol] = []
        stack = [s for s in formula.free_symbols if s in atoms]
        while stack:
            s = stack.pop()
            if s in needed:
                continue
            needed.append(s)
            stack.extend(t for t in atoms[s].free_symbols if t in atoms and t not in needed)
        self.atom_syms = tuple(sorted(needed, key=lambda s: s.name))
        atom_exprs = [atoms[s].xreplace({t: atoms[t] for t in self.atom_syms}) for s in self.atom_syms]
        self.modules = modules
        self._atoms = sp.lambdify(list(self.args), atom_exprs, modules=_modules(modules), cse=True) if atom_exprs else None
        self._f = sp.lambdify([*self.atom_syms, *self.args], formula, modules=_modules(modules), cse=True)

    def call_with_atoms(self, atom_values: Mapping[sp.Symbol, object], *vals):
        """Evaluate with atom values computed elsewhere (shared between formulas)."""
        with np.errstate(all="ignore"):
            return self._f(*(atom_values[s] for s in self.atom_syms), *vals)

    def __call__(self, *vals):
        if self.modules == "numpy":
            with np.errstate(all="ignore"):
                avals = self._atoms(*vals) if self._atoms else []
                out = self._f(*avals, *vals)
            shape = np.broadcast(*[np.asarray(x) for x in vals]).shape if vals else ()
            return np.broadcast_to(np.asarray(out, dtype=float), shape).copy() if shape else float(out)
        avals = self._atoms(*vals) if self._atoms else []
        return self._f(*avals, *vals)


class AtomTable:
    """Evaluates a set of atoms once per call (CSE across all of them), for many formulas."""

    def __init__(self, atoms: Mapping[sp.Symbol, sp.Expr], args: Sequence[sp.Symbol]):
        self.atoms = atoms
        self.args = tuple(args)
        self._fns: dict[frozenset, tuple] = {}

    def evaluate(self, wanted: Sequence[sp.Symbol], *vals) -> dict[sp.Symbol, object]:
        key = frozenset(wanted)
        if key not in self._fns:
            syms = tuple(sorted(key, key=lambda s: s.name))
            exprs = [self.atoms[s] for s in syms]
            self._fns[key] = (syms, sp.lambdify(list(self.args), exprs, modules=_modules("numpy"), cse=True) if syms else None)
        syms, fn = self._fns[key]
        if fn is None:
            return {}
        with np.errstate(all="ignore"):
            return dict(zip(syms, fn(*vals)))
