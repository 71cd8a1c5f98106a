"""Compiled vector-field kernels generated from a symbolic declaration.

A model declares its field as sympy expressions f(t, y; p); :func:`generate_kernel` prints
them (with common-subexpression elimination) as Python source for

    fun(t, y, p, out)      out[i] = f_i(t, y; p)
    jac(t, y, p, out)      out[i, j] = ∂f_i/∂y_j        (exact, differentiated by sympy)

checks that source against a whitelist of syntax (assignments of arithmetic on names and
subscripts, ``math.<function>`` calls and a few builtins), executes it in a namespace that
holds nothing else, and compiles both functions with numba (:func:`compile_source`, through
the cross-process code cache of :mod:`landau.verify.jitcache`).  The result (:class:`Kernel`)
is what the compiled steppers of :mod:`landau.verify.hybrid.compiled` take: the
simulation layer itself never imports sympy — kernels are made here, on the derivation
side, and handed over as numba callables.

Only expressions built by sympy (from a law parsed by :mod:`landau.laws.parse` or written
in code) reach this module; user strings never reach ``exec``.
"""

from __future__ import annotations

import ast
import math
from dataclasses import dataclass
from dataclasses import field as _field
from typing import Mapping, Sequence

import numpy as np
import sympy as sp
from numba import types
from sympy.printing.pycode import PythonCodePrinter

from landau.cx import as_expr
from landau.errors import InputError
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
                                               or (isinstance(node.func, ast.Name) and node.func.id in ALLOWED_BUILTINS)):
            raise InputError(f"generated code calls {ast.unparse(node.func)!r}: refusing to compile it")
        if isinstance(node, ast.Name) and node.id.startswith("__"):
            raise InputError(f"generated code uses the name {node.id!r}: refusing to compile it")


def kernel_source(states: Sequence[sp.Symbol], field: Sequence[sp.Expr], params: Sequence[sp.Symbol],
                  time: sp.Symbol | None = None, jacobian: bool = True) -> str:
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

    Returns
    -------
    str
        The source, already checked by :func:`check_source`.  It is kept in the disk cache of
        derivations (:mod:`landau.cache`, switched off by ``LANDAU_CACHE=off``), so a later
        process asking for the same field skips the differentiation and the elimination.
    """
    n = len(states)
    if len(field) != n:
        raise InputError(f"field has {len(field)} components for {n} states")
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
    # renamed field: the source is kept in the disk cache of derivations (landau.cache) under
    # that field's canonical text, this generator's own code and the sympy version
    from landau import cache

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
    head = [f"    s{i} = y[{i}]" for i in range(n)]
    head += [f"    q{i} = p[{i}]" for i in range(nparams)]
    body = [f"    {s} = {pr.doprint(e)}" for s, e in reps]
    lines = ["def fun(t, y, p, out):", *head, *body]
    lines += [f"    out[{i}] = {pr.doprint(red[i])}" for i in range(n)]
    src = "\n".join(lines) + "\n"
    if jacobian:
        lj = ["def jac(t, y, p, out):", "    out[:, :] = 0.0", *head, *body]
        for i in range(n):
            for j in range(n):
                e = red[n + i * n + j]
                if e != 0:
                    lj.append(f"    out[{i}, {j}] = {pr.doprint(e)}")
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
    fun: object
    jac: object | None
    fun_py: object = _field(repr=False)
    jac_py: object | None = _field(repr=False)


_COMPILED: dict[str, CompiledSource] = {}


def compile_source(src: str, name: str = "kernel") -> CompiledSource:
    """Compile a kernel source of :func:`kernel_source` with numba, through the code cache.

    The source is checked again (:func:`check_source`), kept in the cross-process code cache
    of :mod:`landau.verify.jitcache` (a file named by its SHA-256, executed with the builtins
    ``abs``, ``min``, ``max``, ``float`` and the module ``math`` only) and compiled with
    ``cache=True``, so a later process loads the machine code from disk.  The compiled
    functions are module-level functions of that file's module, so compiled-method templates
    bound to them are cached on disk as well (:mod:`landau.verify.hybrid.specialise`).  One
    source is compiled once per process.

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
    fun = njit_cached(fun_py, FUN_SIG)
    jac = njit_cached(jac_py, JAC_SIG) if jac_py is not None else None
    out = CompiledSource(src, fun, jac, fun_py, jac_py)
    _COMPILED[src] = out
    return out
