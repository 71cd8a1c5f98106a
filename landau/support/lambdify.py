"""Numeric functions of expressions whose symbols carry users' names, built without name clashes.

:func:`sympy.lambdify` prints an expression with the names of its symbols and executes the
text in a namespace where the printed functions (``cos``, ``exp``, ``array``, ``select``…) are
global names — and where it also binds every symbol of the expression by its name.  A symbol
named ``cos`` therefore replaces the function ``cos`` in the generated code (a law parameter
``cos`` gives "'Symbol' object is not callable", or a wrong number where the name is also a
value).  :func:`lambdify_positional` renames every argument, all at once (``xreplace``), to an
internal name no user symbol can take (a leading underscore, which the law, velocity-law and
system constructors refuse), and lambdifies the renamed expression: the generated code then
contains no name a user chose.

:func:`numeric_modules` is the module set every numeric function of the toolkit is printed
against: numpy or mpmath, plus the distributions a non-smooth law's derivatives produce
(|v − v₀| → sign → DiracDelta), zero away from the kink and infinite on it.

This module sits below the friction laws (which compile their own numeric functions) and the
code generators, which all import it from here.
"""

from __future__ import annotations

from typing import Any, Callable

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


def numeric_modules(modules: Any) -> Any:
    """lambdify modules with the distributions a non-smooth law's derivatives produce
    (|v − v₀| → sign → DiracDelta): zero away from the kink, infinite on it."""
    if modules == "numpy":
        return [{"DiracDelta": _dirac_np, "Heaviside": _heaviside_np}, "numpy"]
    if modules == "mpmath":
        return [{"DiracDelta": _dirac_mp, "Heaviside": _heaviside_mp}, "mpmath"]
    return modules


def _rename(args: Any, table: dict[sp.Symbol, sp.Symbol]) -> Any:
    """``args`` (a symbol or a nested list/tuple of symbols) with each symbol renamed to ``_a<i>``."""
    if isinstance(args, (list, tuple)):
        return type(args)(_rename(a, table) for a in args)
    if isinstance(args, sp.Symbol):
        if args not in table:
            table[args] = sp.Symbol(f"_a{len(table)}", **args.assumptions0)
        return table[args]
    return args


def lambdify_positional(args: Any, expr: Any, modules: Any = None, **kwargs: Any) -> Callable:
    """:func:`sympy.lambdify` of ``expr`` over ``args`` after renaming the arguments to internal names.

    Parameters
    ----------
    args : sympy Symbol or (nested) list/tuple of them
        The arguments, as :func:`sympy.lambdify` takes them.
    expr : sympy expression, or a list/tuple/Matrix of them
        What to compute.
    modules : optional
        The numeric library, as for :func:`sympy.lambdify`.
    **kwargs
        Other keyword arguments of :func:`sympy.lambdify` (e.g. ``cse=True``).

    Returns
    -------
    callable
        The same function of the same positional arguments as ``sympy.lambdify(args, expr, …)``.

    Examples
    --------
    >>> import sympy as sp
    >>> x, c = sp.symbols("x cos", real=True)
    >>> lambdify_positional([x, c], sp.cos(x) / c, "math")(0.0, 2.0)
    0.5
    """
    table: dict[sp.Symbol, sp.Symbol] = {}
    new_args = _rename(args, table)

    def rename(e: Any) -> Any:
        if isinstance(e, (list, tuple)):
            return type(e)(rename(x) for x in e)
        if isinstance(e, sp.Basic) or isinstance(e, sp.MatrixBase):
            return e.xreplace(table)
        return e

    return sp.lambdify(new_args, rename(expr), modules=modules, **kwargs)
