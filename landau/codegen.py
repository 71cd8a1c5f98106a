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


#: tree size from which a formula is compiled as a :class:`Tape` instead of by lambdify
_TAPE_FROM = 100_000


class CompiledFormula:
    """f(args) = formula(atoms(args), args), compiled once, for numpy or mpmath."""

    def __init__(self, formula: sp.Expr, args: Sequence[sp.Symbol], atoms: Mapping[sp.Symbol, sp.Expr],
                 modules: str = "numpy"):
        self.formula = formula
        self.args = tuple(args)
        # atoms may be defined through other atoms (nested): resolve them in dependency order
        needed: list[sp.Symbol] = []
        stack = [s for s in dag_free_symbols(formula) if s in atoms]
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
        inputs = [*self.atom_syms, *self.args]
        tape = None
        if tree_size(formula) > _TAPE_FROM:
            try:
                tape = Tape(formula, inputs)
            except ValueError:      # an operation the tape does not know: lambdify handles it
                tape = None
        if tape is not None:
            self._f = lambda *vals: tape(*vals, modules=modules)
        else:
            self._f = sp.lambdify(inputs, formula, modules=_modules(modules), cse=True)

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


_NP_FUNCS = {"log": np.log, "exp": np.exp, "sqrt": np.sqrt, "Abs": np.abs, "sign": np.sign, "sin": np.sin,
             "cos": np.cos, "tanh": np.tanh, "sinh": np.sinh, "cosh": np.cosh, "atan": np.arctan,
             "DiracDelta": _dirac_np, "Heaviside": _heaviside_np}
_MP_FUNCS = {"log": "log", "exp": "exp", "sqrt": "sqrt", "Abs": "fabs", "sign": "sign", "sin": "sin", "cos": "cos",
             "tanh": "tanh", "sinh": "sinh", "cosh": "cosh", "atan": "atan"}


def dag_free_symbols(expr: sp.Basic) -> set[sp.Symbol]:
    """``expr.free_symbols`` visiting each distinct subexpression once (sympy walks the tree)."""
    seen: set[sp.Basic] = set()
    out: set[sp.Symbol] = set()
    stack = [expr]
    while stack:
        node = stack.pop()
        if node in seen:
            continue
        seen.add(node)
        if node.is_Symbol:
            out.add(node)
        stack.extend(a for a in node.args if a not in seen)
    return out


def tree_size(expr: sp.Basic) -> int:
    """Nodes of ``expr`` counted as a tree (what lambdify and cse traverse), computed on the
    DAG in linear time."""
    size: dict[sp.Basic, int] = {}
    stack = [(expr, False)]
    while stack:
        node, done = stack.pop()
        if node in size:
            continue
        if done or not node.args:
            size[node] = 1 + sum(size[a] for a in node.args)
            continue
        stack.append((node, True))
        stack.extend((a, False) for a in node.args if a not in size)
    return size[expr]


class Tape:
    """A straight-line program for ``expr``: each distinct subexpression is evaluated once.

    The engine's formulas come out of Gaussian elimination as DAGs whose tree form is huge
    (two-state Dieterich: Λ has 8.9e5 tree nodes but 225 distinct operations), and lambdify's
    and cse's tree traversals took ~6 s per law;
    the tape is built in one pass over the distinct nodes and interpreted over numpy arrays
    (any float dtype, the per-operation overhead is negligible for vectors) or mpmath numbers.
    """

    def __init__(self, expr: sp.Expr, inputs: Sequence[sp.Symbol]):
        slot: dict[sp.Basic, int] = {s: i for i, s in enumerate(inputs)}
        ops: list[tuple[str, object, tuple[int, ...]]] = []
        stack = [(expr, False)]
        while stack:
            node, done = stack.pop()
            if node in slot:
                continue
            if node.is_Symbol:
                raise ValueError(f"symbol {node} is not an input of the tape")
            if node.is_Number or node in (sp.pi, sp.E):
                slot[node] = len(inputs) + len(ops)
                ops.append(("const", node, ()))
                continue
            if not done:
                stack.append((node, True))
                stack.extend((a, False) for a in node.args if a not in slot)
                continue
            if node.is_Add:
                op = ("add", None, tuple(slot[a] for a in node.args))
            elif node.is_Mul:
                op = ("mul", None, tuple(slot[a] for a in node.args))
            elif node.is_Pow:
                e = node.exp
                if not e.is_Number:
                    op = ("powx", None, (slot[node.base], slot[e]))
                elif e == sp.Rational(1, 2):
                    op = ("func", "sqrt", (slot[node.base],))
                else:
                    op = ("pow", int(e) if e.is_Integer else e, (slot[node.base],))
            elif isinstance(node, sp.Function) and type(node).__name__ in _NP_FUNCS:
                op = ("func", type(node).__name__, tuple(slot[a] for a in node.args))
            else:
                raise ValueError(f"no tape operation for {type(node).__name__}")
            slot[node] = len(inputs) + len(ops)
            ops.append(op)
        self.ops = ops
        self.out = slot[expr]
        self._consts: dict[str, list] = {}

    def _constants(self, mode: str) -> list:
        if mode not in self._consts:
            out = []
            for kind, val, _ in self.ops:
                if kind != "const":
                    out.append(None)
                elif mode == "longdouble" and val.is_Rational:
                    out.append(np.longdouble(int(val.p)) / np.longdouble(int(val.q)))
                else:
                    out.append(float(val))
            self._consts[mode] = out
        return self._consts[mode]

    def __call__(self, *vals, modules: str = "numpy"):
        if modules == "mpmath":
            import mpmath

            consts = [None if k != "const" else (mpmath.mpf(int(v.p)) / int(v.q) if v.is_Rational else mpmath.mpf(str(v)))
                      for k, v, _ in self.ops]
            funcs = {k: getattr(mpmath, v) for k, v in _MP_FUNCS.items()}
            funcs["DiracDelta"], funcs["Heaviside"] = _dirac_mp, _heaviside_mp
        else:
            ld = any(getattr(v, "dtype", None) == np.longdouble for v in vals)
            consts = self._constants("longdouble" if ld else "float")
            funcs = _NP_FUNCS
        reg = list(vals)
        for (kind, val, args), c in zip(self.ops, consts):
            if kind == "const":
                reg.append(c)
            elif kind == "add":
                acc = reg[args[0]]
                for j in args[1:]:
                    acc = acc + reg[j]
                reg.append(acc)
            elif kind == "mul":
                acc = reg[args[0]]
                for j in args[1:]:
                    acc = acc * reg[j]
                reg.append(acc)
            elif kind == "pow":
                x = reg[args[0]]
                if val == -1:
                    reg.append(1 / x)
                elif isinstance(val, int) and val > 0:
                    reg.append(x ** val)
                elif isinstance(val, int):
                    reg.append(1 / x ** (-val))
                else:
                    reg.append(x ** (float(val) if modules != "mpmath" else mpmath.mpf(int(val.p)) / int(val.q)))
            elif kind == "powx":
                reg.append(reg[args[0]] ** reg[args[1]])
            else:
                reg.append(funcs[val](*(reg[j] for j in args)))
        return reg[self.out]
