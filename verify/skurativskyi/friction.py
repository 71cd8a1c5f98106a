"""The friction term F_R(ẋ) of eq. (1) compiled from a velocity-only friction law.

The forced oscillator of Skurativskyi, Kudra, Witkowski & Awrejcewicz (2019) takes its
friction from a :class:`~landau.laws.velocity.VelocityFriction` (default: the regularised
Coulomb law c ẋ + T ẋ/sqrt(ẋ² + ε²) of their eq. (1), :func:`~landau.laws.velocity.regularised_coulomb`).
:func:`compile_friction` prints the law's two branches F(v > 0), F(v < 0) and their
derivatives (by sympy) as Python source, each branch a function of its own,
checks that source with the whitelist of :func:`landau.codegen.kernels.check_source`, and compiles

    friction(v, p)             -> F(v)
    friction_slope(v, p)       -> (F(v), dF/dv)
    friction_derivative(v, p)  -> dF/dv
    subtract_friction(a, v, p) -> a − F(v), the additive terms of F subtracted one by one

with numba.  Their parameters are read from the model's packed vector ``p`` (from index
``first``: the law's parameters in declaration order, then F(0) and F'(0), so that v = 0
exactly never evaluates a branch at its edge).  The source is kept in the per-user kernel
cache of :mod:`landau.verify.jitcache` (named by its hash), so a second process loads the
machine code from disk.  ``friction``, ``friction_derivative`` and ``subtract_friction`` are
also compiled as C callbacks (``numba.cfunc``, reading ``p`` through its data pointer): the
compiled field, SDIRK4 and event-driven loop (:mod:`landau.verify.skurativskyi.field`,
:mod:`~landau.verify.skurativskyi.sdirk`, :mod:`~landau.verify.skurativskyi.rk`) take them as
first-class functions and are compiled once for all laws; a new law compiles only these.

Under ``NUMBA_DISABLE_JIT=1`` (to step through the loop in a debugger) nothing is compiled: the
generated Python functions themselves are the callbacks, the field and loop run as plain
Python with the same floating-point operations, and :func:`warn_plain_python` says so once.

Half-integer powers, frequent in regularised laws, are printed as square roots
(s^{−3/2} → 1/(s·sqrt(s))) and small integer powers as products (v² → v*v): a power routine
costs several times a multiplication or a square root in the inner loop.
"""

from __future__ import annotations

import contextlib
import functools
import math
import warnings
import weakref
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np
import sympy as sp
from sympy.printing.precedence import PRECEDENCE
from sympy.printing.pycode import PythonCodePrinter

from landau.codegen.kernels import ALLOWED_BUILTINS, check_source
from landau.errors import DomainError, InputError
from landau.laws.velocity import V_SLIP, VelocityFriction


class _Printer(PythonCodePrinter):
    """Python printer with bare symbol names, small integer powers as products and half-integer
    powers as square roots."""

    def _print_Symbol(self, expr):
        return expr.name

    def _print_Mul(self, expr):
        # a numerator factor x**k (k = 2…4) is printed as k factors of the product, left to
        # right (T*eps*eps/…, as typed by hand), not as a parenthesised sub-product
        c, nc = expr.args_cnc()
        small = lambda f: f.is_Pow and f.exp.is_Integer and 2 <= int(f.exp) <= 4
        if nc or not any(small(f) for f in c) or any(f.is_Number and f.is_negative for f in c):
            return super()._print_Mul(expr)
        num = [f for f in c if not (f.is_Pow and f.exp.is_negative)]
        den = [f.base ** (-f.exp) for f in c if f.is_Pow and f.exp.is_negative]
        prec = PRECEDENCE["Mul"]
        parts = []
        for f in num:
            if small(f):
                parts += [self.parenthesize(f.base, prec, strict=True)] * int(f.exp)
            else:
                parts.append(self.parenthesize(f, prec, strict=False))
        text = "*".join(parts)
        if den:
            text += "/" + self.parenthesize(sp.Mul(*den), prec, strict=True)
        return text

    def _print_Pow(self, expr, rational=False):
        b, e = expr.base, expr.exp
        if e.is_Integer and 2 <= int(e) <= 4:               # x*x*…: no power routine
            base = self.parenthesize(b, PRECEDENCE["Mul"], strict=True)
            return "(" + "*".join([base] * int(e)) + ")"
        if e.is_Rational and e.q == 2 and abs(e.p) <= 7:
            k = (abs(e.p) - 1) // 2                       # |e| = k + 1/2
            base = self.parenthesize(b, 1000)
            root = f"math.sqrt({self._print(b)})"
            mag = root if k == 0 else f"({base}**{k}*{root})" if k > 1 else f"({base}*{root})"
            return f"(1.0/{mag})" if e.p < 0 else mag
        return super()._print_Pow(expr, rational)


@dataclass(frozen=True)
class CompiledFriction:
    """The friction term of one law, compiled (see the module docstring).

    Attributes
    ----------
    law_name : str
        The law's name.
    param_names : tuple of str
        The law's parameters, in the order they are packed from index ``first``.
    first : int
        Index in the packed vector of the first law parameter.
    source : str
        The generated source.
    friction, friction_slope, friction_derivative, subtract_friction : numba dispatcher
        ``friction(v, p) -> F``, ``friction_slope(v, p) -> (F, dF/dv)``,
        ``friction_derivative(v, p) -> dF/dv``, ``subtract_friction(a, v, p) -> a - F(v)``
        (F's additive terms subtracted one by one), compiled on first use from Python.
    pointers : tuple
        ``(friction, friction_derivative, subtract_friction)`` as C callbacks (``numba.cfunc``)
        taking the packed vector's data pointer, whether the law is the built-in one and
        :func:`data_pointer` (:func:`pointer_types`, :func:`is_built_in`): what the compiled
        field, SDIRK4 and loop of this package receive as ``fr``.
    """

    law_name: str
    param_names: tuple[str, ...]
    first: int
    source: str = field(repr=False)
    friction: object = field(repr=False)
    friction_slope: object = field(repr=False)
    friction_derivative: object = field(repr=False)
    subtract_friction: object = field(repr=False)
    pointers: tuple = field(repr=False, default=())

    @property
    def size(self) -> int:
        """Entries of the packed vector used from ``first`` on (parameters, F(0), F'(0))."""
        return len(self.param_names) + 2


_CACHE: dict[tuple, CompiledFriction] = {}
_KEYS: "weakref.WeakKeyDictionary[VelocityFriction, tuple]" = weakref.WeakKeyDictionary()


def law_key(law: VelocityFriction) -> tuple:
    """What identifies the compiled code of a law (its expressions and parameter order, not values)."""
    key = _KEYS.get(law)
    if key is None:
        key = (sp.srepr(law.branch(1)), sp.srepr(law.branch(-1)), tuple(p.name for p in law.parameters))
        _KEYS[law] = key
    return key


def _value_key(law: VelocityFriction) -> tuple:
    """The law's expressions and parameter values."""
    return law_key(law), tuple(p.default for p in law.parameters)


def _branch_source(name: str, value, slope, params, first: int) -> str:
    """``def name(v, p)`` computing F into r0 (printed as declared: for the paper's law the same
    floating-point operations as eq. (1) written by hand) and, if ``slope`` is given, dF/dv into
    r1 (repeated subexpressions are shared by the compiler); no return (added by the caller)."""
    ren = {V_SLIP: sp.Symbol("v", real=True)}
    ren.update({p.symbol: sp.Symbol(f"q{i}", real=True) for i, p in enumerate(params)})
    pr = _Printer({"fully_qualified_modules": True})
    lines = [f"def {name}(v, p):"]
    lines += [f"    q{i} = p[{first + i}]" for i in range(len(params))]
    if value is not None:
        lines.append(f"    r0 = {pr.doprint(value.xreplace(ren))}")
    if slope is not None:
        lines.append(f"    r1 = {pr.doprint(slope.xreplace(ren))}")
    return "\n".join(lines) + "\n"


def _subtraction_source(name: str, value, params, first: int) -> str:
    """``def name(a, v, p)`` computing a − F(v) into r0 with F's additive terms subtracted one by
    one, left to right, in the printer's order (``a - (t1) - (t2) - …``): for the paper's law
    ``a - c*v - T*v/sqrt(v*v + eps*eps)``, the floating-point operations of eq. (1) written by
    hand (``a - (c*v + T*v/…)`` rounds differently, and the period-doubling cascade of the
    stiff path is sensitive to the last bit)."""
    ren = {V_SLIP: sp.Symbol("v", real=True)}
    ren.update({p.symbol: sp.Symbol(f"q{i}", real=True) for i, p in enumerate(params)})
    pr = _Printer({"fully_qualified_modules": True})
    expr = value.xreplace(ren)
    terms = pr._as_ordered_terms(expr, order=None) if expr.is_Add else [expr]
    lines = [f"def {name}(a, v, p):"]
    lines += [f"    q{i} = p[{first + i}]" for i in range(len(params))]
    lines.append("    r0 = a" + "".join(f" - ({pr.doprint(t)})" for t in terms))
    return "\n".join(lines) + "\n"


def _derivative(f: sp.Expr) -> sp.Expr:
    """dF/dv term by term, each over a common denominator with its numerator expanded when that
    is shorter: for T v/sqrt(v² + ε²) this gives T ε²/(v² + ε²)^{3/2} instead of
    T/sqrt(v² + ε²) − T v²/(v² + ε²)^{3/2}, which cancels for |v| ≫ ε."""
    out = []
    for term in sp.Add.make_args(sp.expand(f, deep=False, mul=True, power_base=False, power_exp=False,
                                           log=False, multinomial=False, basic=False)):
        d = sp.diff(term, V_SLIP)
        num, den = sp.fraction(sp.together(d))
        tidy = sp.expand(num) / den
        out.append(tidy if sp.count_ops(tidy) <= sp.count_ops(d) else d)
    return sp.Add(*out)


# fixed text appended after the whitelist check (it holds nothing derived from the law)
_DISPATCH = """
def friction(v, p):
    if v > 0.0:
        return _value_pos(v, p)
    if v < 0.0:
        return _value_neg(v, p)
    return p[{i0}]


def friction_slope(v, p):
    if v > 0.0:
        return _slope_pos(v, p)
    if v < 0.0:
        return _slope_neg(v, p)
    return p[{i0}], p[{i0} + 1]


def friction_derivative(v, p):
    if v > 0.0:
        return _deriv_pos(v, p)
    if v < 0.0:
        return _deriv_neg(v, p)
    return p[{i0} + 1]


def subtract_friction(a, v, p):
    if v > 0.0:
        return _sub_pos(a, v, p)
    if v < 0.0:
        return _sub_neg(a, v, p)
    return a - p[{i0}]
"""

# the same, when one expression serves both signs and is finite at v = 0 (e.g. the paper's law)
_ONE_EXPRESSION = """
def friction(v, p):
    return _value_pos(v, p)


def friction_slope(v, p):
    return _slope_pos(v, p)


def friction_derivative(v, p):
    return _deriv_pos(v, p)


def subtract_friction(a, v, p):
    return _sub_pos(a, v, p)
"""


@functools.lru_cache(maxsize=256)
def _single_expression_key(key: tuple) -> bool:
    return _smooth_single_expression_uncached(_KEYED[key])


_KEYED: dict = {}


def _smooth_single_expression(law: VelocityFriction) -> bool:
    """:func:`_smooth_single_expression_uncached`, once per law expression."""
    key = law_key(law)
    _KEYED.setdefault(key, law)
    return _single_expression_key(key)


def _smooth_single_expression_uncached(law: VelocityFriction) -> bool:
    """Whether F(v > 0) and F(v < 0) are one expression that, with its derivative, has a value at
    v = 0 for generic parameter values (no division by v, no log v, …); :func:`packed_values`
    checks that value is finite for the parameter values of a run."""
    pos, neg = law.branch(1), law.branch(-1)
    if pos != neg:
        return False
    for e in (pos, _derivative(pos)):
        at0 = e.subs(V_SLIP, 0)
        if at0.has(sp.nan, sp.zoo, sp.oo, -sp.oo) or at0.has(sp.log):
            return False
    return True


def _cached(fn, signature=None, kind="njit"):
    """``numba.njit(cache=True, inline="always")(fn)`` (compiled on first use, for the parameter
    vector's type of that use: an array from Python, a data pointer in the callbacks) or, with
    ``kind="cfunc"``, ``numba.cfunc(signature, cache=True)(fn)``.  The disk cache works as in
    :func:`landau.verify.jitcache.njit_cached`, which this follows (a cache entry that cannot be
    loaded is dropped and the function compiled afresh)."""
    import numba as nb

    from landau.verify import jitcache

    def make(cache):
        if kind == "cfunc":
            return nb.cfunc(signature, cache=cache)(fn)
        return nb.njit(cache=cache, inline="always")(fn)

    if not Path(fn.__code__.co_filename).is_file():
        return make(False)
    try:
        return make(True)
    except Exception:
        jitcache._drop_numba_entries(Path(fn.__code__.co_filename))
        return make(True)


@functools.lru_cache(maxsize=None)
def pointer_types() -> tuple:
    """The numba signatures of the callbacks in :attr:`CompiledFriction.pointers`:
    ``friction(v, p*)``, ``friction_derivative(v, p*)`` and ``subtract_friction(a, v, p*)``
    (``p*`` the data pointer of the packed parameter vector), as ``types.FunctionType``."""
    from numba import types

    ptr = types.CPointer(types.float64)
    one = types.float64(types.float64, ptr)
    sub = types.float64(types.float64, types.float64, ptr)
    return (types.FunctionType(one), types.FunctionType(one), types.FunctionType(sub), types.boolean,
            types.FunctionType(ptr(ptr)))


def _identity(p):
    return p


class Callbacks(tuple):
    """The tuple ``fr`` handed to the compiled field and loop (:attr:`CompiledFriction.pointers`).

    A tuple whose numba type is known without inspecting its items
    (``numba.extending.typeof_impl`` is registered for it): numba's generic typing of a tuple
    of C callbacks costs ~0.1 ms a call, a noticeable part of a short run."""

    __slots__ = ()


@functools.lru_cache(maxsize=None)
def callbacks_type():
    """The numba type of every :class:`Callbacks` (a tuple of :func:`pointer_types`)."""
    from numba import types

    return types.Tuple(pointer_types())


@functools.lru_cache(maxsize=None)
def _register_typeof_once() -> None:
    from numba.extending import typeof_impl

    @typeof_impl.register(Callbacks)
    def _typeof_callbacks(val, c):
        return callbacks_type()


@functools.lru_cache(maxsize=None)
def data_pointer():
    """The C callback ``p* -> p*`` (identity on a float64 pointer), compiled once per machine: the
    compiled loop calls it once with ``p.ctypes`` to hold the data pointer of the packed vector
    as a ``CPointer(float64)`` (numba converts an array's ``ctypes`` to a pointer at a call's
    typed argument).  The field then reads ``p`` through that pointer: no array, so no
    reference counts in the calls of the inner loop (the caller owns ``p`` for the whole run)."""
    from numba import types

    ptr = types.CPointer(types.float64)
    return _cached(_identity, ptr(ptr), "cfunc")


def is_built_in(law: VelocityFriction) -> bool:
    """Whether ``law`` is the paper's regularised Coulomb law c v + T v/sqrt(v² + ε²) (same
    expressions, parameters c, T, eps in that order, any values): the compiled field of
    :mod:`landau.verify.skurativskyi.field` then evaluates it inline instead of through the
    callbacks (the same operations; an indirect call cannot be inlined)."""
    from landau.laws.velocity import regularised_coulomb

    return law_key(law) == law_key(regularised_coulomb())


def _paper_first() -> int:
    from landau.verify.skurativskyi.model import ILAW

    return ILAW


@contextlib.contextmanager
def quiet_first_class():
    """Silence numba's notice that first-class function types are experimental (a documented
    feature; the loops of :mod:`landau.verify.skurativskyi.rk` are typed with it)."""
    from numba.core.errors import NumbaExperimentalFeatureWarning

    with warnings.catch_warnings():
        warnings.simplefilter("ignore", NumbaExperimentalFeatureWarning)
        yield


def warn_plain_python() -> None:
    """Warn once per process that the forced oscillator runs as plain Python (``NUMBA_DISABLE_JIT=1``)."""
    from landau.verify.hybrid.callbacks import warn_once

    warn_once("skurativskyi-nojit", "landau: NUMBA_DISABLE_JIT is set: the forced oscillator's field and "
                                    "integrator run as plain Python (tens of times slower)")


def compile_friction(law: VelocityFriction, first: int) -> CompiledFriction:
    """Generate and compile F(v) and (F, dF/dv) of ``law`` reading its parameters from ``p[first:]``.

    Parameters
    ----------
    law : VelocityFriction
        A law continuous at v = 0 (a set-valued law has no single force there: the model
        refuses it before compiling).
    first : int
        Index of the law's first parameter in the packed vector.

    Returns
    -------
    CompiledFriction
        One per law expression and ``first`` in a process; under ``NUMBA_DISABLE_JIT=1`` its
        functions and ``pointers`` are the generated Python functions (module docstring).
    """
    from landau.verify.hybrid.callbacks import jit_enabled
    from landau.verify.jitcache import load_generated

    jit = jit_enabled()
    if not jit:
        warn_plain_python()
    key = (law_key(law), int(first), jit)
    if key in _CACHE:
        return _CACHE[key]
    params = law.parameters
    parts = []
    for side, tag in ((1, "pos"), (-1, "neg")):
        f0 = law.branch(side)
        parts.append((_branch_source(f"_value_{tag}", f0, None, params, first), "r0"))
        parts.append((_branch_source(f"_slope_{tag}", f0, _derivative(f0), params, first), "(r0, r1)"))
        parts.append((_branch_source(f"_deriv_{tag}", None, _derivative(f0), params, first), "r1"))
        parts.append((_subtraction_source(f"_sub_{tag}", f0, params, first), "r0"))
    check_source("\n".join(body for body, _ in parts))
    src = "\n\n".join(f"{body}    return {ret}\n" for body, ret in parts) + (
        _ONE_EXPRESSION if _smooth_single_expression(law) else _DISPATCH.format(i0=first + len(params)))
    ns = load_generated(src, {"math": math}, ALLOWED_BUILTINS)
    if not jit:
        # NUMBA_DISABLE_JIT=1: the generated Python functions themselves are the callbacks (the
        # field hands them the packed vector, see field.data; the loop holds the array itself)
        pointers = Callbacks((ns["friction"], ns["friction_derivative"], ns["subtract_friction"],
                              bool(is_built_in(law) and first == _paper_first()), _identity))
        out = CompiledFriction(law.name, tuple(p.name for p in params), int(first), src, ns["friction"],
                               ns["friction_slope"], ns["friction_derivative"], ns["subtract_friction"], pointers)
        _CACHE[key] = out
        return out
    # the dispatchers replace the Python functions in the cached module, so that the functions
    # calling them compile against them (and inline them) and `from <module> import friction`
    # finds them; nothing here compiles until first use, except the three C callbacks
    for nm in ("_value_pos", "_value_neg", "_deriv_pos", "_deriv_neg", "_slope_pos", "_slope_neg",
               "_sub_pos", "_sub_neg", "friction", "friction_slope", "friction_derivative", "subtract_friction"):
        ns[nm] = _cached(ns[nm])
    sigs = [t.signature for t in pointer_types()[:3]]
    pointers = tuple(_cached(ns[nm].py_func, sig, "cfunc")
                     for nm, sig in zip(("friction", "friction_derivative", "subtract_friction"), sigs, strict=True))
    _register_typeof_once()
    pointers = Callbacks(pointers + (bool(is_built_in(law) and first == _paper_first()), data_pointer()))
    out = CompiledFriction(law.name, tuple(p.name for p in params), int(first), src, ns["friction"],
                           ns["friction_slope"], ns["friction_derivative"], ns["subtract_friction"], pointers)
    _CACHE[key] = out
    return out


def packed_values(law: VelocityFriction) -> list[float]:
    """The law's entries of the packed vector: its parameter values (defaults), F(0), F'(0).

    Parameters
    ----------
    law : VelocityFriction

    Returns
    -------
    list of float

    Raises
    ------
    InputError
        The law is set-valued at v = 0 or has no finite value or slope there.
    """
    key = _value_key(law)
    if key not in _PACKED:
        check_regularised(law)
        vals = [float(law.defaults()[p.name]) for p in law.parameters]
        f0 = float(law.value(0.0))
        d0 = float(law.slope(0.0))
        if not (math.isfinite(f0) and math.isfinite(d0)):
            raise InputError(f"friction law {law.name!r}: F or dF/dv is not finite at v = 0 (F(0) = {f0!r}, "
                             f"F'(0) = {d0!r}); the forced oscillator needs a law smooth through v = 0")
        if _smooth_single_expression(law):
            # the compiled code evaluates the expression itself at v = 0 (no branch): it must be finite
            with np.errstate(all="ignore"):
                direct = [float(law.numeric(1, k)(0.0, *vals)) for k in (0, 1)]
            if not all(map(math.isfinite, direct)):
                raise InputError(f"friction law {law.name!r}: its expression is not finite at v = 0 for these "
                                 "parameter values")
        _PACKED[key] = vals + [f0, d0]
    return list(_PACKED[key])


_PACKED: dict[tuple, list] = {}
_CHECKED: set = set()


def check_regularised(law: VelocityFriction) -> None:
    """Refuse a law the compiled model cannot integrate: not a velocity law, parameters without a
    value, or set-valued at v = 0 (Coulomb: stick needs a phase of its own, which this model,
    like the paper, replaces by a regularisation).

    Parameters
    ----------
    law : VelocityFriction

    Raises
    ------
    InputError
    """
    if not isinstance(law, VelocityFriction):
        raise InputError(f"the forced oscillator takes a VelocityFriction law (friction F(v) of the sliding "
                         f"velocity), got {type(law).__name__}")
    missing = [p.name for p in law.parameters if p.default is None]
    if missing:
        raise InputError(f"friction law {law.name!r}: parameter(s) {', '.join(missing)} need a value")
    key = _value_key(law)
    if key in _CHECKED:
        return
    try:
        set_valued = law.is_set_valued()
    except DomainError as exc:
        raise InputError(str(exc)) from None
    if set_valued:
        lo, hi = law.limits_at_zero()
        raise InputError(f"friction law {law.name!r} is set-valued at v = 0 (F(0-) = {lo:g}, F(0+) = {hi:g}): "
                         "the forced-oscillator simulator needs a law continuous through v = 0, e.g. the "
                         "regularised Coulomb law of Skurativskyi et al. (2019) with eps > 0")
    _CHECKED.add(key)


_VISCOUS: dict[tuple, float] = {}


def viscous_coefficient(law: VelocityFriction) -> float:
    """The law's viscous coefficient lim F(v)/v as v → +∞ [N s/m], at its parameter defaults.

    The part of the friction that grows linearly with the velocity: c for c v + T v/sqrt(v² + ε²)
    (Skurativskyi et al. 2019, eq. 1) and for c v + T tanh(v/ε).  The linearised solution of
    their Sec. 5 (eq. 4) and the harmonic balance (eqs 5–6) damp with this coefficient only;
    the bounded remainder F(v) − c v (the dry part T sgn v) is treated there as a small
    nonlinear term and dropped.

    Parameters
    ----------
    law : VelocityFriction

    Returns
    -------
    float

    Raises
    ------
    InputError
        F(v)/v has no finite limit (the friction grows faster than linearly).
    """
    vals = law.defaults()
    key = _value_key(law)
    if key not in _VISCOUS:
        e = law.branch(1).subs({p.symbol: vals[p.name] for p in law.parameters})
        try:
            lim = sp.limit(e / V_SLIP, V_SLIP, sp.oo)
            x = float(lim)
        except (TypeError, ValueError, NotImplementedError):
            x = math.nan
        if not math.isfinite(x):
            raise InputError(f"friction law {law.name!r}: F(v)/v has no finite limit as v -> oo, so the law has "
                             "no viscous coefficient for the linearised solution (Sec. 5)")
        _VISCOUS[key] = x
    return _VISCOUS[key]
