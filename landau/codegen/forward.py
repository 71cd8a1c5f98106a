"""Forward-mode differentiation of a compiled straight-line program (:class:`~landau.codegen.formula.Tape`).

A tape evaluates each distinct subexpression of a formula once; :func:`forward` runs the same
program on pairs (value, tangent), the tangent carrying the derivatives along several input
directions at once (Griewank & Walther 2008, ch. 3, the tangent mode).  The derivatives are
those of the formula itself — exact up to the rounding of the arithmetic, never a finite
difference — and the cost is a small multiple of one evaluation whatever the size of the tree:
the amplitude-equation coefficients are DAGs whose tree form is huge (Ruina's Λ: 12 600
operations, whose symbolic gradient by ``sympy.diff`` has 5.8e5 and takes 18 s), while the
tape has a few hundred distinct nodes.

Values are numpy arrays (any float dtype, broadcast together) or mpmath numbers; a tangent is
an array whose first axis runs over the directions (an object array of mpmath numbers in
mpmath mode), ``None`` for a tangent that is identically zero.  The step function and the
delta are differentiated away from their jump (derivative 0).

References
----------
Griewank, A. & Walther, A. (2008), *Evaluating Derivatives*, 2nd ed., SIAM, ch. 3.
"""

from __future__ import annotations

from typing import Any, Callable, Sequence

import numpy as np

from landau.codegen.formula import _MP_FUNCS, _NP_FUNCS, Tape, _mp_constant


def _np_derivatives() -> dict[str, Callable]:
    """function name -> its derivative f′(x) for numpy values."""
    return {"log": lambda x, y: 1 / x, "exp": lambda x, y: y, "sqrt": lambda x, y: 0.5 / y,
            "Abs": lambda x, y: np.sign(x), "sign": lambda x, y: 0 * x, "sin": lambda x, y: np.cos(x),
            "cos": lambda x, y: -np.sin(x), "tanh": lambda x, y: 1 - y * y, "sinh": lambda x, y: np.cosh(x),
            "cosh": lambda x, y: np.sinh(x), "atan": lambda x, y: 1 / (1 + x * x),
            "DiracDelta": lambda x, y: 0 * x, "Heaviside": lambda x, y: 0 * x}


def _mp_derivatives() -> dict[str, Callable]:
    """function name -> its derivative f′(x) for mpmath values."""
    import mpmath

    return {"log": lambda x, y: 1 / x, "exp": lambda x, y: y, "sqrt": lambda x, y: 1 / (2 * y),
            "Abs": lambda x, y: mpmath.sign(x), "sign": lambda x, y: mpmath.mpf(0), "sin": lambda x, y: mpmath.cos(x),
            "cos": lambda x, y: -mpmath.sin(x), "tanh": lambda x, y: 1 - y * y, "sinh": lambda x, y: mpmath.cosh(x),
            "cosh": lambda x, y: mpmath.sinh(x), "atan": lambda x, y: 1 / (1 + x * x),
            "DiracDelta": lambda x, y: mpmath.mpf(0), "Heaviside": lambda x, y: mpmath.mpf(0)}


def _power(b, e):
    """bᵉ as the tape computes it (a negative integer power as a reciprocal)."""
    if e == -1:
        return 1 / b
    if isinstance(e, int) and e < 0:
        return 1 / b ** (-e)
    return b ** e


def _add(a, b):
    if a is None:
        return b
    if b is None:
        return a
    return a + b


def _scale(t, s):
    return None if t is None else t * s


def forward(tape: Tape, values: Sequence[Any], tangents: Sequence[Any], modules: str = "numpy") -> tuple[list, list]:
    """Values and tangents of a tape's outputs.

    Parameters
    ----------
    tape : Tape
        The program (its inputs in the order it was built with).
    values : sequence
        One value per input (numpy arrays broadcasting together, or mpmath numbers).
    tangents : sequence
        One tangent per input: an array of shape ``(n, *shape)`` (n directions) or ``None`` (zero).
    modules : {"numpy", "mpmath"}
        The arithmetic.

    Returns
    -------
    values, tangents : list, list
        One entry per output of the tape (``None`` tangent: the output does not depend on the
        directions).
    """
    if modules == "mpmath":
        import mpmath

        funcs: dict[str, Callable] = {k: getattr(mpmath, v) for k, v in _MP_FUNCS.items()}
        from landau.support.lambdify import _dirac_mp, _heaviside_mp

        funcs["DiracDelta"], funcs["Heaviside"] = _dirac_mp, _heaviside_mp
        derivs = _mp_derivatives()
        consts: list = [None if k != "const" else _mp_constant(v) for k, v, _ in tape.ops]
        log = mpmath.log
    else:
        funcs, derivs = _NP_FUNCS, _np_derivatives()
        consts = tape._constants("float")
        log = np.log
    reg = list(values)
    treg = list(tangents)
    with np.errstate(all="ignore"):
        for (kind, val, args), c in zip(tape.ops, consts, strict=True):
            t = None
            if kind == "const":
                x = c
            elif kind == "add":
                x = reg[args[0]]
                t = treg[args[0]]
                for j in args[1:]:
                    x = x + reg[j]
                    t = _add(t, treg[j])
            elif kind == "mul":
                x = reg[args[0]]
                t = treg[args[0]]
                for j in args[1:]:
                    # d(xy) = y dx + x dy
                    t = _add(_scale(t, reg[j]), _scale(treg[j], x))
                    x = x * reg[j]
            elif kind == "pow":
                b = reg[args[0]]
                e = val if isinstance(val, int) else (
                    float(val) if modules != "mpmath" else mpmath.mpf(int(val.p)) / int(val.q))
                x = _power(b, e)
                if treg[args[0]] is not None:
                    # d(bᵉ) = e bᵉ⁻¹ db
                    t = treg[args[0]] * (e * _power(b, e - 1) if e != 1 else 1)
            elif kind == "powx":
                b, e = reg[args[0]], reg[args[1]]
                x = b ** e
                # d(bᵉ) = bᵉ (ln b de + e db / b)
                t = _add(_scale(treg[args[1]], x * log(b)) if treg[args[1]] is not None else None,
                         _scale(treg[args[0]], x * e / b))
            else:
                xs = [reg[j] for j in args]
                x = funcs[val](*xs)
                if treg[args[0]] is not None:
                    t = treg[args[0]] * derivs[val](xs[0], x)
            reg.append(x)
            treg.append(t)
    return [reg[i] for i in tape.outs], [treg[i] for i in tape.outs]


__all__ = ["forward"]
