"""Complex numbers as (real, imaginary) pairs over any real field.

The engine works with sympy expressions (closed forms), mpmath numbers (50-digit
checks) and floats alike.  Keeping the real and imaginary parts apart lets the
symbolic route take real parts exactly — Λ = 2 Re(β/δ) — without asking sympy to
reason about complex conjugates of symbolic expressions.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any, Callable, Sequence


@dataclass(frozen=True)
class Cx:
    re: Any
    im: Any

    def __add__(self, o: "Cx | Any") -> "Cx":
        o = as_cx(o)
        return Cx(self.re + o.re, self.im + o.im)

    __radd__ = __add__

    def __sub__(self, o: "Cx | Any") -> "Cx":
        o = as_cx(o)
        return Cx(self.re - o.re, self.im - o.im)

    def __rsub__(self, o: Any) -> "Cx":
        return as_cx(o) - self

    def __neg__(self) -> "Cx":
        return Cx(-self.re, -self.im)

    def __mul__(self, o: "Cx | Any") -> "Cx":
        if not isinstance(o, Cx):
            return Cx(self.re * o, self.im * o)
        return Cx(self.re * o.re - self.im * o.im, self.re * o.im + self.im * o.re)

    __rmul__ = __mul__

    def __truediv__(self, o: "Cx | Any") -> "Cx":
        if not isinstance(o, Cx):
            return Cx(self.re / o, self.im / o)
        d = o.re * o.re + o.im * o.im
        return Cx((self.re * o.re + self.im * o.im) / d, (self.im * o.re - self.re * o.im) / d)

    def conj(self) -> "Cx":
        return Cx(self.re, -self.im)

    def abs2(self) -> Any:
        return self.re * self.re + self.im * self.im

    def map(self, fn: Callable[[Any], Any]) -> "Cx":
        return Cx(fn(self.re), fn(self.im))


def as_expr(x: Any):
    """A sympy object for an internal number or expression (never a string: no parsing)."""
    import sympy as sp

    if isinstance(x, sp.Basic):
        return x
    if isinstance(x, int):
        return sp.Integer(x)
    if isinstance(x, float):
        return sp.Float(x)
    raise TypeError(f"expected a sympy expression or a number, got {type(x).__name__}")


def as_cx(x: Any) -> Cx:
    return x if isinstance(x, Cx) else Cx(x, 0 * x if hasattr(x, "__mul__") else 0)


def is_zero(x: Any) -> bool:
    """Structural zero for sympy, exact zero for numbers."""
    try:
        return bool(x == 0)
    except TypeError:
        return False


def cx_is_zero(z: Cx) -> bool:
    return is_zero(z.re) and is_zero(z.im)


def _is_symbolic(x: Any) -> bool:
    """True for a sympy expression with free symbols, which no float conversion can turn into a
    number.  ``is_number`` stops at the first symbol it meets, unlike ``free_symbols``, which
    walks the whole tree."""
    return getattr(x, "is_number", True) is False


def magnitude(z: Cx) -> float:
    """A float size for pivoting; symbolic entries count as 1 when not structurally zero.

    Expressions with free symbols are recognised before any numeric conversion is tried:
    ``complex()`` of such an expression makes sympy evaluate the whole expression tree
    numerically before failing, which dominated the derivation cost for laws with several
    state variables.
    """
    if _is_symbolic(z.re) or _is_symbolic(z.im):
        return 0.0 if cx_is_zero(z) else 1.0
    try:
        return float(abs(complex(z.re, z.im)))
    except (TypeError, ValueError):
        return 0.0 if cx_is_zero(z) else 1.0


def solve(A: Sequence[Sequence[Cx]], b: Sequence[Cx]) -> list[Cx]:
    """Solve A x = b by Gaussian elimination with partial pivoting (largest modulus for
    numbers; first structurally non-zero entry for symbols)."""
    n = len(b)
    M = [[as_cx(A[i][j]) for j in range(n)] + [as_cx(b[i])] for i in range(n)]
    for col in range(n):
        piv = max(range(col, n), key=lambda r: magnitude(M[r][col]))
        if cx_is_zero(M[piv][col]):
            raise ZeroDivisionError("singular linear system in the multiple-scales engine")
        M[col], M[piv] = M[piv], M[col]
        pv = M[col][col]
        for r in range(col + 1, n):
            if cx_is_zero(M[r][col]):
                continue
            f = M[r][col] / pv
            for c in range(col, n + 1):
                if not cx_is_zero(M[col][c]):
                    M[r][c] = M[r][c] - f * M[col][c]
    x: list[Cx] = [Cx(0, 0)] * n
    for i in reversed(range(n)):
        s = M[i][n]
        for j in range(i + 1, n):
            if not cx_is_zero(M[i][j]):
                s = s - M[i][j] * x[j]
        x[i] = s / M[i][i]
    return x


def dot(p: Sequence[Cx], x: Sequence[Cx]) -> Cx:
    """⟨p, x⟩ = Σ conj(pᵢ) xᵢ."""
    out = Cx(0, 0)
    for pi, xi in zip(p, x, strict=True):
        if cx_is_zero(pi) or cx_is_zero(xi):
            continue
        out = out + pi.conj() * xi
    return out
