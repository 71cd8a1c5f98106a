"""Compiled, vectorised evaluation of symbolic results (lambdify with CSE).

Results are formulas in *atoms* (derivatives of the law at the steady state, see
:mod:`landau.derivation.jets`) and parameters.  :class:`CompiledFormula` lambdifies the atom
definitions it needs and the formula separately, each with common-subexpression
elimination, and composes them: vectorised over numpy arrays in any argument.

Every lambdified function goes through :func:`lambdify`, whose generated source is cached
across processes (:mod:`landau.verify.jitcache`), keyed by the formula's structure, the
arguments, the module set and the library versions: a second process executes the stored
source instead of running sympy's common-subexpression elimination and printer again.
"""

from __future__ import annotations

import dis
import hashlib
import linecache
import logging
from typing import Any, Callable, Mapping, Sequence

import numpy as np
import sympy as sp

from landau.support.lambdify import _dirac_mp, _dirac_np, _heaviside_mp, _heaviside_np
from landau.support.lambdify import numeric_modules as _modules

logger = logging.getLogger(__name__)

#: changes whenever the generated code for the same inputs would change (a new cache key)
_LAMBDIFY_FORMAT = "landau-lambdify/1"
_LAMBDIFY_TAG = "lambdify"
_NAMESPACES: dict[str, dict] = {}


def _versions() -> str:
    import numpy

    try:
        import mpmath
        mp_version = mpmath.__version__
    except ImportError:          # pragma: no cover - mpmath is a dependency of sympy
        mp_version = "-"
    return f"{_LAMBDIFY_FORMAT} sympy {sp.__version__} numpy {numpy.__version__} mpmath {mp_version}"


def structure_text(exprs) -> str:
    """A canonical text of ``exprs`` (an expression or nested lists/tuples of them) that visits
    each distinct subexpression once: the key of generated code.

    Two inputs get the same text exactly when they have the same tree: the class of every
    node, in sympy's argument order, and the ``srepr`` of every atom (symbols with their
    assumptions, numbers with their precision).  Nodes are compared by that structure, never
    by sympy's ``==`` (which may equate ``2`` and ``2.0``); a repeated subexpression is written
    once and referred to by number, so the cost is linear in the DAG, not in the (possibly
    exponentially larger) tree.

    Parameters
    ----------
    exprs : sympy expression or (nested) list or tuple of them

    Returns
    -------
    str
    """
    number: dict[tuple, int] = {}          # structural description -> line number
    memo: dict[int, int] = {}              # id(object) -> line number (objects stay alive meanwhile)
    lines: list[str] = []
    keep = []                              # numbers sympified here, kept alive while their id is used

    def emit(desc: tuple, text: str) -> int:
        if desc not in number:
            number[desc] = len(lines)
            lines.append(text)
        return number[desc]

    stack = [(exprs, False)]
    while stack:
        node, done = stack.pop()
        if id(node) in memo:
            continue
        if isinstance(node, (list, tuple)):
            children = list(node)
        elif isinstance(node, sp.Basic):
            children = list(node.args)
        else:
            # a plain number a caller put in a list; strict: a string is refused, never parsed
            sym = sp.sympify(node, strict=True)
            keep.append(sym)
            memo[id(node)] = memo.setdefault(id(sym), emit(("atom", sp.srepr(sym)), sp.srepr(sym)))
            continue
        if not children:
            text = sp.srepr(node) if isinstance(node, sp.Basic) else "[]"
            memo[id(node)] = emit(("atom", text), text)
            continue
        if not done:
            stack.append((node, True))
            stack.extend((a, False) for a in reversed(children) if id(a) not in memo)
            continue
        refs = tuple(memo[id(a)] for a in children)
        head = "[seq]" if isinstance(node, (list, tuple)) else type(node).__name__
        memo[id(node)] = emit((head, refs), f"{head}({','.join(map(str, refs))})")
    return "\n".join(lines)


def _lambdify_key(args: Sequence[sp.Symbol], expr, modules: str) -> str:
    h = hashlib.sha256()
    for part in (_versions(), modules, sp.srepr(tuple(args)), structure_text(expr)):
        h.update(part.encode())
        h.update(b"\0")
    return h.hexdigest()[:32]


def _namespace(modules: str) -> dict:
    """The globals sympy's lambdify gives generated code for ``modules`` (made once per process)."""
    ns = _NAMESPACES.get(modules)
    if ns is None:
        ns = _NAMESPACES[modules] = sp.lambdify([], 0, modules=_modules(modules)).__globals__
    return ns


def _global_names(code) -> set[str]:
    out = {ins.argval for ins in dis.get_instructions(code) if ins.opname in ("LOAD_GLOBAL", "LOAD_NAME")}
    for c in code.co_consts:
        if hasattr(c, "co_code"):
            out |= _global_names(c)
    return out


def _source_of(fn, ns: dict) -> str | None:
    """The source sympy generated for ``fn``, when every global it reads is the same object in
    the shared namespace ``ns`` (else None: such a function is not cached)."""
    entry = linecache.cache.get(fn.__code__.co_filename)
    if not entry or len(entry) < 3:   # absent, or a lazy entry without the lines
        return None
    source = "".join(entry[2])
    import builtins

    for name in _global_names(fn.__code__):
        if name in ns:
            if ns[name] is not fn.__globals__.get(name):
                return None
        elif not hasattr(builtins, name):
            return None
    return source


def _from_source(source: str, ns: dict, filename: str):
    local: dict = {}
    exec(compile(source, filename, "exec"), ns, local)
    (fn,) = local.values()
    return fn


def lambdify(args: Sequence[sp.Symbol], expr, modules: str = "numpy") -> Callable:
    """``sympy.lambdify(args, expr, modules, cse=True)``, its generated source cached on disk.

    The key is a SHA-256 of the structure of ``expr`` (:func:`structure_text`), the
    arguments, the module set and the sympy/numpy/mpmath versions; the source is stored
    atomically in the code folder of :mod:`landau.verify.jitcache` with an HMAC of its text under
    the per-user key of :mod:`landau.support.cachedir`, checked before the text is executed.  A
    stored file that does not verify (edited, planted, truncated) or does not compile is removed
    and rebuilt.  Only code whose every global name
    is the module set's own is stored (so executing it in that namespace is what sympy would
    have done); anything else is lambdified in every process.

    Parameters
    ----------
    args : sequence of sympy.Symbol
        The arguments, in order.
    expr : sympy expression or list of them
        What to compute.
    modules : {"numpy", "mpmath"} or other lambdify module name
        The numeric library (with the distributions of :func:`_modules`).

    Returns
    -------
    callable
    """
    from landau.verify import jitcache

    args = list(args)
    try:
        key = _lambdify_key(args, expr, modules)
    except (TypeError, ValueError, RecursionError):      # something structure_text cannot print
        return sp.lambdify(args, expr, modules=_modules(modules), cse=True)
    ns = _namespace(modules)
    stored = jitcache.load_keyed_source(key, _LAMBDIFY_TAG)
    if stored is not None:
        source, path = stored
        try:
            return _from_source(source, ns, str(path))
        except Exception as exc:                 # corrupt though complete: rebuild below
            logger.warning("ignoring unusable generated code %s (%s)", path, exc)
            jitcache.discard_keyed_source(key, _LAMBDIFY_TAG)
    fn = sp.lambdify(args, expr, modules=_modules(modules), cse=True)
    generated = _source_of(fn, ns)
    if generated is not None:
        jitcache.store_keyed_source(key, _LAMBDIFY_TAG, generated)
    return fn


def compile_expr(expr: sp.Expr, args: Sequence[sp.Symbol], modules: str = "numpy") -> Callable:
    """lambdify ``expr`` over ``args`` with CSE; broadcasts over numpy arrays."""
    fn = lambdify(args, expr, modules)
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
        inputs = [*self.atom_syms, *self.args]
        if modules == "mpmath" and self._mp_tapes(formula, atom_exprs, inputs):
            return
        self._atoms = lambdify(self.args, atom_exprs, modules) if atom_exprs else None
        tape = None
        if tree_size(formula) > _TAPE_FROM:
            try:
                tape = Tape(formula, inputs)
            except ValueError:      # an operation the tape does not know: lambdify handles it
                tape = None
        if tape is not None:
            self._f = lambda *vals: tape(*vals, modules=modules)
        else:
            self._f = lambdify(inputs, formula, modules)

    def _mp_tapes(self, formula, atom_exprs, inputs) -> bool:
        """The mpmath version as straight-line programs (:class:`Tape`): built in one pass over
        the distinct subexpressions, where lambdify's common-subexpression elimination costs
        tenths of a second per formula — paid in every process for the few points that need
        50 digits.  False (nothing set) when an operation has no tape form."""
        try:
            atoms = Tape(list(atom_exprs), list(self.args)) if atom_exprs else None
            tape = Tape(formula, inputs)
        except ValueError:
            return False
        self._atoms = (lambda *vals: atoms(*vals, modules="mpmath")) if atoms is not None else None
        self._f = lambda *vals: tape(*vals, modules="mpmath")
        return True

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
            self._fns[key] = (syms, lambdify(self.args, exprs, "numpy") if syms else None)
        syms, fn = self._fns[key]
        if fn is None:
            return {}
        with np.errstate(all="ignore"):
            return dict(zip(syms, fn(*vals), strict=True))


_NP_FUNCS: dict[str, Callable] = {
    "log": np.log, "exp": np.exp, "sqrt": np.sqrt, "Abs": np.abs, "sign": np.sign, "sin": np.sin,
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

    def __init__(self, expr, inputs: Sequence[sp.Symbol]):
        self._many = isinstance(expr, (list, tuple))       # several outputs sharing one program
        outputs = list(expr) if self._many else [expr]
        slot: dict[sp.Basic, int] = {s: i for i, s in enumerate(inputs)}
        # (kind, value, argument slots): value is None, a function name, an exponent or a constant
        ops: list[tuple[str, Any, tuple[int, ...]]] = []
        stack = [(e, False) for e in reversed(outputs)]
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
            op: tuple[str, Any, tuple[int, ...]]
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
        self.outs = [slot[e] for e in outputs]
        self.out = self.outs[0]
        self._consts: dict[str, list] = {}

    def _constants(self, mode: str) -> list:
        if mode not in self._consts:
            out: list[Any] = []
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

            consts = [None if k != "const" else _mp_constant(v) for k, v, _ in self.ops]
            funcs: dict[str, Callable] = {k: getattr(mpmath, v) for k, v in _MP_FUNCS.items()}
            funcs["DiracDelta"], funcs["Heaviside"] = _dirac_mp, _heaviside_mp
        else:
            ld = any(getattr(v, "dtype", None) == np.longdouble for v in vals)
            consts = self._constants("longdouble" if ld else "float")
            funcs = _NP_FUNCS
        reg = list(vals)
        for (kind, val, args), c in zip(self.ops, consts, strict=True):
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
        return [reg[i] for i in self.outs] if self._many else reg[self.out]


def _mp_constant(v: sp.Basic):
    """A constant of a tape at mpmath's working precision: rationals exactly, a Float with its
    exact binary value (as sympy's mpmath printer writes it), π and e to full precision."""
    import mpmath

    if v.is_Rational:
        return mpmath.mpf(int(v.p)) / int(v.q)
    if v is sp.pi:
        return +mpmath.pi
    if v is sp.E:
        return +mpmath.e
    if isinstance(v, sp.Float):
        return mpmath.mpf(v._mpf_)
    return mpmath.mpf(str(v))
