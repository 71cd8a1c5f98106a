"""Compiled vector-field kernels generated from a symbolic declaration.

A model declares its field as sympy expressions f(t, y; p); :func:`generate_kernel` prints
them (with common-subexpression elimination) as Python source for

    fun(t, y, p, out)      out[i] = f_i(t, y; p)
    jac(t, y, p, out)      out[i, j] = ∂f_i/∂y_j        (exact, differentiated by sympy)

checks that source against a whitelist of syntax (assignments of arithmetic on names and
subscripts, ``math.<function>`` calls and a few builtins), executes it in a namespace that
holds nothing else, and compiles both functions with numba (:func:`compile_source`, through
the cross-process code cache of :mod:`landau.verify.jitcache`).  The result (:class:`Kernel`)
is what the compiled stepper of :mod:`landau.verify.hybrid.dop853` takes: the
simulation layer itself never imports sympy — kernels are made here, on the derivation
side, and handed over as numba callables.

A field whose parameters enter through functions of the parameters alone (``log(L)``,
``V/(M*L**2)``) can first go through :func:`hoist_parameters`: those subexpressions become
derived parameters, appended to the parameter vector once per parameter set by
:class:`DerivedParameters`, and the kernel then does only state-dependent work at each call
(the spring–block model of :mod:`landau.verify.springblock.model` does this).

Only expressions built by sympy (from a law parsed by :mod:`landau.laws.parse` or written
in code) reach this module; user strings never reach ``exec``.
"""

from __future__ import annotations

import ast
import math
from dataclasses import dataclass
from dataclasses import field as _field
from typing import Callable, Mapping, Sequence

import numpy as np
import sympy as sp
from numba import types
from sympy.printing.pycode import PythonCodePrinter

from landau.errors import InputError
from landau.support.cx import as_expr
from landau.verify.hybrid.kernel import Kernel
from landau.verify.jitcache import load_generated, njit_cached

#: numba signatures of the generated functions (the ones the compiled steppers call)
FUN_SIG = types.void(types.float64, types.float64[::1], types.float64[::1], types.float64[::1])
JAC_SIG = types.void(types.float64, types.float64[::1], types.float64[::1], types.float64[:, ::1])

_ALLOWED_NODES = (ast.Module, ast.FunctionDef, ast.arguments, ast.arg, ast.Assign, ast.Name, ast.Load,
                  ast.Store, ast.Subscript, ast.Slice, ast.Tuple, ast.Constant, ast.BinOp, ast.UnaryOp,
                  ast.Call, ast.Attribute, ast.operator, ast.unaryop, ast.IfExp, ast.Compare, ast.cmpop,
                  ast.BoolOp, ast.boolop)
ALLOWED_BUILTINS = ("abs", "min", "max", "float")  # the only builtins generated code may call


class _Printer(PythonCodePrinter):
    def _print_Symbol(self, expr):
        return expr.name


def check_source(src: str) -> None:
    """Refuse generated source that is anything but arithmetic on names and subscripts,
    ``math.<function>`` calls and the builtins ``abs``, ``min``, ``max``, ``float``.

    Raises
    ------
    InputError
        Naming the first node outside the whitelist.
    """
    for node in ast.walk(ast.parse(src)):
        if not isinstance(node, _ALLOWED_NODES):
            raise InputError(f"generated code contains a {type(node).__name__} node: refusing to compile it")
        if isinstance(node, ast.Attribute) and not (isinstance(node.value, ast.Name) and node.value.id == "math"
                                                    and not node.attr.startswith("_")):
            raise InputError(f"generated code accesses attribute {ast.unparse(node)!r}: refusing to compile it")
        if isinstance(node, ast.Call) and not (isinstance(node.func, ast.Attribute)
                                               or (isinstance(node.func, ast.Name)
                                                   and node.func.id in ALLOWED_BUILTINS)):
            raise InputError(f"generated code calls {ast.unparse(node.func)!r}: refusing to compile it")
        if isinstance(node, ast.Name) and node.id.startswith("__"):
            raise InputError(f"generated code uses the name {node.id!r}: refusing to compile it")


def kernel_source(states: Sequence[sp.Symbol], field: Sequence[sp.Expr], params: Sequence[sp.Symbol],
                  time: sp.Symbol | None = None, jacobian: bool = True, square: bool = True) -> str:
    """Python source of ``fun(t, y, p, out)`` (and ``jac(t, y, p, out)``) for ``field``.

    Parameters
    ----------
    states : sequence of sympy Symbol
        y_0 … y_{n-1}, in order.
    field : sequence of sympy expressions
        f_i(t, y; p), one per state.
    params : sequence of sympy Symbol
        The entries of the parameter vector ``p``, in order.
    time : sympy Symbol, optional
        The time symbol of a non-autonomous field.
    jacobian : bool
        Also emit ``jac`` (∂f/∂y by sympy).
    square : bool
        True: one component per state (a vector field).  False: any number of components (a
        vector function of the state, such as a mode's guards; no ``jac`` then).

    Returns
    -------
    str
        The source, already checked by :func:`check_source`.  It is kept in the disk cache of
        derivations (:mod:`landau.support.cache`, switched off by ``LANDAU_CACHE=off``), so a later
        process asking for the same field skips the differentiation and the elimination.
    """
    n = len(states)
    if square and len(field) != n:
        raise InputError(f"field has {len(field)} components for {n} states")
    if not square:
        if jacobian:
            raise InputError("a Jacobian is emitted for a vector field only (square=True)")
        if not len(field):
            raise InputError("a vector function needs at least one component")
    names = [s.name for s in states] + [s.name for s in params] + ([time.name] if time is not None else [])
    if len(set(names)) != len(names):
        raise InputError(f"state, parameter and time symbols must be distinct (got {names})")
    known = set(states) | set(params) | ({time} if time is not None else set())
    exprs = [as_expr(e) for e in field]
    free = set().union(*(e.free_symbols for e in exprs)) - known
    if free:
        raise InputError(f"field uses undeclared symbol(s) {sorted(s.name for s in free)}")
    # the generated code names its variables itself (s_i states, q_i parameters, t, c_k
    # subexpressions): a user's symbol names never reach the source
    ren = {s: sp.Symbol(f"s{i}", **s.assumptions0) for i, s in enumerate(states)}
    ren.update({s: sp.Symbol(f"q{i}", **s.assumptions0) for i, s in enumerate(params)})
    if time is not None:
        ren[time] = sp.Symbol("t", **time.assumptions0)
    exprs = [e.xreplace(ren) for e in exprs]
    svars = [ren[s] for s in states]
    # what sympy derives here (the Jacobian, the common subexpressions) depends only on the
    # renamed field: the source is kept in the disk cache of derivations (landau.support.cache) under
    # that field's canonical text, this generator's own code and the sympy version
    from landau.support import cache

    key = cache.make_key("kernel-source", _generator_fingerprint(), sp.__version__, jacobian, len(params),
                         sp.srepr((tuple(svars), tuple(exprs))))
    src = cache.get("kernel-source", key)
    if isinstance(src, str):
        try:
            check_source(src)                   # the cached text passes the same whitelist,
            return src
        except (InputError, SyntaxError):       # or it is rebuilt
            pass
    src = _emit(exprs, svars, len(params), jacobian)
    cache.put("kernel-source", key, src)
    return src


_FINGERPRINT: str | None = None


def _generator_fingerprint() -> str:
    """SHA-256 of this module's source: a changed generator never reads an older entry."""
    global _FINGERPRINT
    if _FINGERPRINT is None:
        import hashlib
        from pathlib import Path

        try:
            _FINGERPRINT = hashlib.sha256(Path(__file__).read_bytes()).hexdigest()[:16]
        except OSError:
            _FINGERPRINT = "unknown"
    return _FINGERPRINT


def _emit(exprs, svars, nparams: int, jacobian: bool) -> str:
    """The source of fun (and jac) for the renamed field ``exprs`` over ``svars`` (s_i, q_i, t names)."""
    n = len(svars)
    jm = sp.Matrix(exprs).jacobian(sp.Matrix(svars)) if jacobian else sp.zeros(0, 0)
    reps, red = sp.cse(exprs + list(jm), symbols=sp.numbered_symbols("c"), optimizations="basic")
    pr = _Printer({"fully_qualified_modules": True})
    m = len(exprs)

    def prologue(outputs):
        # only the states, parameters and subexpressions these outputs use: an unused line costs
        # numba its typing and lowering at every first build
        need = set().union(*(e.free_symbols for e in outputs))
        kept = []
        for sym, e in reversed(reps):
            if sym in need:
                kept.append((sym, e))
                need |= e.free_symbols
        names = {s.name for s in need}
        head = [f"    s{i} = y[{i}]" for i in range(n) if f"s{i}" in names]
        head += [f"    q{i} = p[{i}]" for i in range(nparams) if f"q{i}" in names]
        return head + [f"    {s} = {pr.doprint(e)}" for s, e in reversed(kept)]

    lines = ["def fun(t, y, p, out):", *prologue(red[:m])]
    lines += [f"    out[{i}] = {pr.doprint(red[i])}" for i in range(m)]
    src = "\n".join(lines) + "\n"
    if jacobian:
        entries = [(i, j, red[m + i * n + j]) for i in range(m) for j in range(n) if red[m + i * n + j] != 0]
        lj = ["def jac(t, y, p, out):", "    out[:, :] = 0.0", *prologue([e for _, _, e in entries])]
        lj += [f"    out[{i}, {j}] = {pr.doprint(e)}" for i, j, e in entries]
        src += "\n" + "\n".join(lj) + "\n"
    check_source(src)
    return src


def generate_kernel(states: Sequence[sp.Symbol], field: Sequence[sp.Expr], params: Sequence[sp.Symbol] = (),
                    values: Mapping[sp.Symbol, float] | Sequence[float] | None = None,
                    time: sp.Symbol | None = None, jacobian: bool = True, name: str = "kernel") -> Kernel:
    """Compile the field f(t, y; p) declared by sympy expressions into a :class:`Kernel`.

    Parameters
    ----------
    states, field, params, time, jacobian
        As in :func:`kernel_source`.
    values : mapping or sequence of float, optional
        Parameter values (by symbol, or in the order of ``params``); required when
        ``params`` is not empty.
    name : str
        A label for error messages and the kernel's repr.

    Returns
    -------
    Kernel
        ``fun`` and ``jac`` compiled by numba (signature ``(float64, float64[::1],
        float64[::1], out)``) and the packed parameter vector.

    Examples
    --------
    >>> import sympy as sp
    >>> y, lam = sp.symbols("y lam")
    >>> k = generate_kernel([y], [-lam * y], [lam], [2.0])
    >>> k(0.0, [1.0])
    array([-2.])
    """
    src = kernel_source(states, field, params, time, jacobian)
    if params:
        if values is None:
            raise InputError(f"kernel {name!r}: values for the parameters {[s.name for s in params]} are needed")
        if isinstance(values, Mapping):
            missing = [s.name for s in params if s not in values]
            if missing:
                raise InputError(f"kernel {name!r}: no value for parameter(s) {missing}")
            pv = [float(values[s]) for s in params]
        else:
            pv = [float(v) for v in values]
            if len(pv) != len(params):
                raise InputError(f"kernel {name!r}: {len(pv)} values for {len(params)} parameters")
    else:
        pv = [0.0]  # numba needs a non-empty float64[::1]
    compiled = compile_source(src, name)
    return Kernel(compiled.fun, np.asarray(pv, float), compiled.jac, name=name, n=len(states), source=src)


def generate_vector_function(states: Sequence[sp.Symbol], components: Sequence[sp.Expr],
                             params: Sequence[sp.Symbol] = (), values: Sequence[float] | None = None,
                             time: sp.Symbol | None = None, name: str = "vector function") -> Kernel:
    """Compile a vector function g(t, y; p) of the state with any number of components.

    The same route as :func:`generate_kernel` (printing with common-subexpression
    elimination, the whitelist, numba's disk cache) for a function that is not a vector
    field: ``fun(t, y, p, out)`` with ``out[j] = g_j(t, y; p)``, j < ``len(components)``, e.g.
    the guards of a hybrid mode (:attr:`landau.verify.hybrid.model.Mode.guard_kernel`).

    Parameters
    ----------
    states, params, time
        As in :func:`kernel_source`.
    components : sequence of sympy expressions
        g_j(t, y; p).
    values : sequence of float, optional
        Parameter values in the order of ``params`` (required when ``params`` is not empty).
    name : str
        A label for error messages and the kernel's repr.

    Returns
    -------
    Kernel
        ``fun`` compiled on first use; ``n`` is the dimension of the state (not of ``out``).

    Examples
    --------
    >>> import sympy as sp
    >>> x, v, a = sp.symbols("x v a")
    >>> g = generate_vector_function([x, v], [x - a, -v, x * v], [a], [0.5])
    >>> out = np.empty(3)
    >>> g.fun(0.0, np.array([1.0, 2.0]), g.p, out)
    >>> out
    array([ 0.5, -2. ,  2. ])
    """
    src = kernel_source(states, components, params, time, jacobian=False, square=False)
    if params:
        if values is None or len(values) != len(params):
            raise InputError(f"{name!r}: {0 if values is None else len(values)} values for {len(params)} parameters")
        pv = [float(v) for v in values]
    else:
        pv = [0.0]  # numba needs a non-empty float64[::1]
    compiled = compile_source(src, name)
    return Kernel(compiled.fun, np.asarray(pv, float), None, name=name, n=len(states), source=src)


@dataclass(frozen=True)
class CompiledSource:
    """The functions of one generated kernel source, compiled and as plain Python.

    Attributes
    ----------
    source : str
        The source (from :func:`kernel_source`).
    fun, jac : numba dispatcher
        ``fun(t, y, p, out)`` and ``jac(t, y, p, out)`` (``jac`` None when not emitted).
    fun_py, jac_py : function
        The same functions uncompiled (e.g. for a pure-Python baseline).
    """

    source: str = _field(repr=False)
    fun: Callable[..., None]
    jac: Callable[..., None] | None
    fun_py: Callable[..., None] = _field(repr=False)
    jac_py: Callable[..., None] | None = _field(repr=False)


_COMPILED: dict[str, CompiledSource] = {}


def compile_source(src: str, name: str = "kernel") -> CompiledSource:
    """Compile a kernel source of :func:`kernel_source` with numba, through the code cache.

    The source is checked again (:func:`check_source`), kept in the cross-process code cache
    of :mod:`landau.verify.jitcache` (a file named by its SHA-256, executed with the builtins
    ``abs``, ``min``, ``max``, ``float`` and the module ``math`` only) and compiled with
    ``cache=True`` on first use (for the argument types of that call; :data:`FUN_SIG`,
    :data:`JAC_SIG` for the usual C-contiguous float arrays), so a later process loads the
    machine code from disk.  The compiled
    functions are module-level functions of that file's module, so generated code that imports
    them by name is cached on disk as well.  One source is compiled once per process.

    Parameters
    ----------
    src : str
        Source defining ``fun(t, y, p, out)`` and optionally ``jac(t, y, p, out)``.
    name : str
        A label for error messages.

    Returns
    -------
    CompiledSource
    """
    hit = _COMPILED.get(src)
    if hit is not None:
        return hit
    check_source(src)
    ns = load_generated(src, {"math": math}, ALLOWED_BUILTINS)
    if not callable(ns.get("fun")):
        raise InputError(f"kernel {name!r}: the source defines no function fun")
    fun_py, jac_py = ns["fun"], ns.get("jac")
    # compiled on first use (signature None): a field handed to the Radau IIA only as a C callback
    # (landau.verify.hybrid.callbacks) never builds these dispatchers
    fun = njit_cached(fun_py, None)
    jac = njit_cached(jac_py, None) if jac_py is not None else None
    out = CompiledSource(src, fun, jac, fun_py, jac_py)
    _COMPILED[src] = out
    return out


# --------------------------------------------------------------------------------------------
# parameter-only subexpressions, evaluated once per parameter set instead of once per call
@dataclass(frozen=True)
class HoistedField:
    """A field whose parameter-only subexpressions are replaced by derived parameters.

    Attributes
    ----------
    field : list of sympy expressions
        The field, in the original states, parameters and the symbols ``derived``; every
        subexpression left in it depends on a state (or time), apart from single symbols
        and numbers.
    derived : tuple of sympy Symbol
        The derived parameters, to be appended to the parameter vector in this order.
    values : tuple of sympy expressions
        Their definitions in terms of the original parameters.
    """

    field: list
    derived: tuple
    values: tuple


def hoist_parameters(field: Sequence[sp.Expr], params: Sequence[sp.Symbol], prefix: str = "hoisted") -> HoistedField:
    """Replace the parameter-only subexpressions of ``field`` by derived parameters.

    A generated kernel evaluates its whole expression at every call: ``log`` of a parameter,
    a product or quotient of parameters, are recomputed although they never change during an
    integration.  This pass walks each expression once, bottom-up; a subexpression whose free
    symbols are all parameters (and which is not a single symbol or number) becomes a new
    symbol, and in a sum or product the parameter-only terms (factors) are gathered into one
    such symbol, e.g. ``q1*(w + log(q8) - log(q4))`` → ``q1*(w + d0)`` with
    ``d0 = log(q8) - log(q4)``.  The field is otherwise unchanged (no expansion, no
    re-association of state-dependent terms), so its rounding differs from the original only
    in the order in which parameter terms are combined.

    Parameters
    ----------
    field : sequence of sympy expressions
        The field f(t, y; p).
    params : sequence of sympy Symbol
        The parameters (every other free symbol counts as a state or time).
    prefix : str
        Stem of the derived symbols' names (``prefix0``, ``prefix1``, …; lengthened with
        underscores if it clashes with a symbol of the field).

    Returns
    -------
    HoistedField
        Evaluate ``values`` with :func:`derived_parameter_function` and append them to the
        parameter vector of a kernel generated for ``params + derived``.

    Examples
    --------
    >>> import sympy as sp
    >>> x, a, b = sp.symbols("x a b", positive=True)
    >>> h = hoist_parameters([sp.exp(-x) * (sp.log(a) + x) / b], [a, b])
    >>> h.field, h.values
    ([hoisted1*(hoisted0 + x)*exp(-x)], (log(a), 1/b))
    """
    pset = set(params)
    exprs = [as_expr(e) for e in field]
    taken = {s.name for e in exprs for s in e.free_symbols} | {s.name for s in params}
    while any(nm.startswith(prefix) for nm in taken):
        prefix = "_" + prefix if not prefix.startswith("__") else prefix + "_"
        if prefix.startswith("___"):
            raise InputError("no free name for the derived parameters")
    table: dict[sp.Expr, sp.Symbol] = {}
    const_memo: dict[sp.Basic, bool] = {}

    def symbol_for(e):
        s = table.get(e)
        if s is None:
            # real, without asking sympy's assumptions about e (slow): the kernel is real arithmetic
            s = table[e] = sp.Symbol(f"{prefix}{len(table)}", real=True)
        return s

    def constant(e):
        hit = const_memo.get(e)
        if hit is None:
            if not e.args:
                hit = e in pset or not e.free_symbols
            else:
                hit = all([constant(a) for a in e.args])
            const_memo[e] = hit
        return hit

    def walk(e):
        if not e.args or isinstance(e, (sp.Number, sp.NumberSymbol)):
            return e
        if constant(e):
            return symbol_for(e)
        if e.is_Add or e.is_Mul:
            const = [a for a in e.args if constant(a)]
            rest = [walk(a) for a in e.args if not constant(a)]
            if len(const) == 1 and (not const[0].args or const[0].is_Number):
                return e.func(const[0], *rest)
            if const:
                return e.func(symbol_for(e.func(*const)), *rest)
            return e.func(*rest)
        return e.func(*[walk(a) for a in e.args])

    out = [walk(e) for e in exprs]
    derived = tuple(table.values())
    return HoistedField(out, derived, tuple(table))


def derived_parameter_source(params: Sequence[sp.Symbol], values: Sequence[sp.Expr]) -> str:
    """Python source of ``derived(p, out)``: ``out[j] = values[j](p)`` (parameters renamed q_i).

    Checked by :func:`check_source`, and kept in the disk cache of derivations like the
    kernel sources (printing it would otherwise be most of the cost of a warm start).
    """
    ren = {s: sp.Symbol(f"q{i}", **s.assumptions0) for i, s in enumerate(params)}
    # expressions of hoist_parameters; strict: a string is refused, never parsed
    vals = [sp.sympify(v, strict=True).xreplace(ren) for v in values]
    from landau.support import cache

    key = cache.make_key("derived-parameters", _generator_fingerprint(), sp.__version__, len(params),
                         sp.srepr(tuple(vals)))
    src = cache.get("derived-parameters", key)
    if isinstance(src, str):
        try:
            check_source(src)
            return src
        except (InputError, SyntaxError):
            pass
    pr = _Printer({"fully_qualified_modules": True})
    lines = ["def derived(p, out):", *(f"    q{i} = p[{i}]" for i in range(len(params)))]
    lines += [f"    out[{j}] = {pr.doprint(v)}" for j, v in enumerate(vals)]
    if not vals:
        lines.append("    out[:] = 0.0")
    src = "\n".join(lines) + "\n"
    check_source(src)
    cache.put("derived-parameters", key, src)
    return src


class DerivedParameters:
    """``full = dp(base)``: a parameter vector extended by the derived parameters of a
    :class:`HoistedField`, evaluated once (plain Python, ``math`` functions).

    The source (``def derived(p, out)``) passes the whitelist of :func:`check_source` and is
    executed like a kernel source (:mod:`landau.verify.jitcache`), not compiled: it runs once
    per parameter set.

    Parameters
    ----------
    params : sequence of sympy Symbol
        The base parameters, in the order of the vector ``base``.
    values : sequence of sympy expressions
        The derived parameters in terms of ``params`` (:attr:`HoistedField.values`).
    """

    def __init__(self, params: Sequence[sp.Symbol], values: Sequence[sp.Expr]):
        self.nbase = len(params)
        self.nderived = len(values)
        self.source = derived_parameter_source(params, values)
        self._fn = load_generated(self.source, {"math": math}, ALLOWED_BUILTINS)["derived"]
        self._values = tuple(values)

    def __call__(self, base) -> np.ndarray:
        base = [float(b) for b in base]
        if len(base) != self.nbase:
            raise InputError(f"{len(base)} parameter values for {self.nbase} parameters")
        out = [0.0] * self.nderived
        try:
            self._fn(base, out)
        except (ValueError, ZeroDivisionError, OverflowError) as exc:
            raise InputError(f"a parameter combination of the field cannot be evaluated ({exc}): "
                             f"check the parameter values {base}") from None
        bad = [str(v) for v, x in zip(self._values, out, strict=True) if not math.isfinite(x)]
        if bad:
            raise InputError(f"parameter combination(s) {bad} of the field are not finite at {base}")
        return np.ascontiguousarray(base + out, dtype=float)
