"""The direct routes of the derivation, for comparison in ``run.py --baseline-derive``.

Pivot sizes by converting each entry to a complex number (sympy evaluates a symbolic entry
numerically before failing), and the characteristic and Hopf polynomials by expanding the
Berkowitz determinant and the products of its real and imaginary parts as expressions.  The
results are identical; only the cost differs.
"""

from __future__ import annotations

from functools import cached_property

import sympy as sp


def _magnitude(z):
    from landau.support.cx import cx_is_zero

    try:
        return float(abs(complex(z.re, z.im)))
    except (TypeError, ValueError):
        return 0.0 if cx_is_zero(z) else 1.0


def _char(self):
    from landau.derivation.linear import lam
    from landau.errors import InputError

    J = sp.Matrix(self.jets.jacobian())
    E = sp.diag(*self.system.mass)
    char = sp.expand((lam * E - J).det(method="berkowitz"))
    p = self.system.parameter
    if sp.diff(char, p, 2) != 0:
        raise InputError("the Hopf parameter enters the characteristic polynomial nonlinearly")
    return sp.Poly(char.subs(p, 0), lam), sp.Poly(sp.diff(char, p), lam)


def _split(poly):
    from landau.derivation.linear import w

    re, im = sp.Integer(0), sp.Integer(0)
    for (m,), c in poly.terms():
        unit = (1, 0) if m % 4 == 0 else (0, 1) if m % 4 == 1 else (-1, 0) if m % 4 == 2 else (0, -1)
        re += unit[0] * c * w ** m
        im += unit[1] * c * w ** m
    return re, im


def _hopf_polys(self):
    from landau.derivation.linear import W, w

    P, Q = self._char
    Pr, Pi = _split(P)
    Qr, Qi = _split(Q)
    im = sp.expand((Pi * Qr - Pr * Qi) / w)
    re = sp.expand(Pr * Qr + Pi * Qi)
    q2 = sp.expand(Qr ** 2 + Qi ** 2)
    to_W = lambda e: sp.expand(e).subs(w, sp.sqrt(W))
    return sp.Poly(to_W(im), W), to_W(re), to_W(q2)


def install() -> None:
    """Put the direct routes in place of the fast ones (for this process)."""
    import landau.support.cx as cx
    from landau.derivation.linear import HopfLine

    cx.magnitude = _magnitude
    for name, fn in (("_char", _char), ("_hopf_polys", _hopf_polys)):
        prop = cached_property(fn)
        prop.__set_name__(HopfLine, name)
        setattr(HopfLine, name, prop)
