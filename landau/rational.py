"""Exact cancellation for laws whose steady-state derivatives are rational in V.

For the Dieterich, Ruina and modified Dieterich laws every derivative at steady sliding is a
rational function of V (the logarithms vanish there).  With the parameters fixed (as exact
decimal rationals) the Fredholm code of :mod:`landau.fredholm` runs in the field ℚ(V, ω), where
every operation is cancelled as it is made; ω² = ω_c²(V) then removes ω.  The result is each
coefficient as P(V) + ω·Q(V) with P, Q single cancelled fractions — e.g. Λ_D ∝ M V³(…)/(…) with
the factor V³ explicit — which float64 evaluates to full precision where the general formula
cancels ten or more digits (low V, M → 0).  A coefficient that vanishes identically (Λ_D at M = 0)
comes out as exactly 0.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Callable, Mapping, Sequence

import numpy as np
import sympy as sp
from sympy import QQ
from sympy.polys.fields import field

from landau.cx import Cx, as_expr
from landau.fredholm import cubic_coefficient, linear_coefficient, null_vectors
from landau.linear import w
from landau.system import V


@dataclass(frozen=True)
class RationalCoefficient:
    """value(V) = P(V) + ω_c(V)·Q(V), P and Q cancelled fractions in V (parameters fixed)."""

    name: str
    P: sp.Expr
    Q: sp.Expr
    fP: Callable
    fQ: Callable

    @property
    def identically_zero(self) -> bool:
        return self.P == 0 and self.Q == 0

    def __call__(self, Vs: np.ndarray, omega: np.ndarray) -> np.ndarray:
        with np.errstate(all="ignore"):
            return np.asarray(self.fP(Vs), dtype=Vs.dtype) + omega * np.asarray(self.fQ(Vs), dtype=Vs.dtype)


def _exact(x: float) -> sp.Rational:
    return sp.Rational(repr(float(x)))


def rational_coefficients(derivation, names: Sequence[str], params: Mapping[str, float]
                          ) -> dict[str, RationalCoefficient] | None:
    """The requested base coefficients in cancelled form at fixed ``params``, or None when some
    derivative at steady state is not rational in V (then the general route is used)."""
    d = derivation
    J, E, r, c = d._structure()
    fp, Jp = d.jets.parameter_derivatives()
    need_cubic = any(n in ("Lambda", "chi") for n in names)
    B2 = d.jets.order(2) if need_cubic or any(f != 0 for f in fp) else {}
    C3 = d.jets.order(3) if need_cubic else {}
    kc, W_c = d.hopf.closed_form
    sub = {s: _exact(params[s.name]) for s in d.args[1:]}
    atoms = {a: e.xreplace(sub) for a, e in d.jets.atoms.items()}
    if not all(e.is_rational_function(V) for e in atoms.values()):
        return None
    K, KV, Kw = field("V,omega", QQ)
    local = {V: sp.Symbol("V"), w: sp.Symbol("omega")}

    def conv(e):
        e = as_expr(e).xreplace({d.k: kc}).xreplace(atoms).xreplace(sub).xreplace(local)
        return K.from_expr(e) if e.free_symbols else K(sp.Rational(e))

    Jk = [[conv(x) for x in row] for row in J]
    Ek = [conv(x) for x in E]
    Wk = conv(W_c)
    vec = null_vectors(Jk, Ek, Kw, d.system.normalise, r, c)
    values: dict[str, Cx] = {}
    if any(n in ("Gamma_bar", "Omega_bar") for n in names):
        a = linear_coefficient(vec, Jk, [[conv(x) for x in row] for row in Jp], [conv(x) for x in fp],
                               {k: conv(v) for k, v in B2.items()})
        values["Gamma_bar"], values["Omega_bar"] = -a.re, a.im
    if need_cubic:
        b = cubic_coefficient(vec, Jk, Ek, Kw, {k: conv(v) for k, v in B2.items()},
                              {k: conv(v) for k, v in C3.items()}, K(1) / 2)
        values["Lambda"], values["chi"] = 2 * b.re, 2 * b.im

    def split(poly):
        """poly(V, ω) = A(V) + ω B(V) modulo ω² = ω_c²(V)."""
        A, B = K(0), K(0)
        for (i, j), coef in poly.terms():
            term = K(coef) * KV ** i * Wk ** (j // 2)
            if j % 2:
                B += term
            else:
                A += term
        return A, B

    out = {}
    Vsym = sp.Symbol("V")
    for n in names:
        q = values[n]
        nA, nB = split(q.numer)
        dA, dB = split(q.denom)
        den = dA * dA - Wk * dB * dB
        P = (nA * dA - Wk * nB * dB) / den
        Q = (nB * dA - nA * dB) / den
        Pe, Qe = P.as_expr(), Q.as_expr()
        out[n] = RationalCoefficient(n, Pe, Qe, sp.lambdify(Vsym, Pe, "numpy"), sp.lambdify(Vsym, Qe, "numpy"))
    return out
