"""The cheap routes taken for speed give the same symbolic results as the direct ones:
pivot sizes in the complex Gaussian elimination (landau.support.cx) and the characteristic / Hopf
polynomials of the Hopf line (landau.derivation.linear)."""

import mpmath
import sympy as sp

import landau.support.cx as cx
from landau.derivation.linear import HopfLine, W, lam, w
from landau.derivation.multiscale import derive
from landau.laws import get_law
from landau.support.cx import Cx
from landau.systems.system import SpringBlock


def _magnitude_by_conversion(z):
    """The direct route: convert to a complex number, count a symbolic entry as 1."""
    try:
        return float(abs(complex(z.re, z.im)))
    except (TypeError, ValueError):
        return 0.0 if cx.cx_is_zero(z) else 1.0


def test_magnitude_matches_the_conversion_route():
    x, y = sp.symbols("x y", real=True)
    cases = [Cx(3.0, 4.0), Cx(mpmath.mpf(3), mpmath.mpf(-4)), Cx(sp.Float(3), sp.Integer(4)),
             Cx(sp.sqrt(2), 0), Cx(x, 0), Cx(0, x * y + 1), Cx(sp.Integer(0), sp.Integer(0)), Cx(0, 0)]
    for z in cases:
        assert cx.magnitude(z) == _magnitude_by_conversion(z), z


def test_two_state_lambda_identical_to_the_conversion_route(monkeypatch):
    # the same derivation with the pivot size computed by the direct route: the pivots, hence
    # the symbolic Λ, must be identical (structurally, not only numerically)
    law = get_law("two-state-dieterich")
    fast = derive(SpringBlock(law), ["Lambda", "chi"])
    lam_fast, chi_fast = fast.formula("Lambda"), fast.formula("chi")
    monkeypatch.setattr(cx, "magnitude", _magnitude_by_conversion)
    slow = derive(SpringBlock(law), ["Lambda", "chi"])
    assert slow.formula("Lambda") == lam_fast
    assert slow.formula("chi") == chi_fast


def test_hopf_polynomials_match_the_berkowitz_route():
    # the characteristic polynomial det(λE − J) by sympy's Berkowitz algorithm on expressions,
    # then Im(P Q̄)/ω, Re(P Q̄), |Q|² expanded in ω and relabelled ω² → W: identical expressions
    for name in ("dieterich", "two-state-dieterich", "nanoscale"):
        line = HopfLine(SpringBlock(get_law(name)))
        J = sp.Matrix(line.jets.jacobian())
        E = sp.diag(*line.system.mass)
        char = sp.expand((lam * E - J).det(method="berkowitz"))
        p = line.system.parameter
        P, Q = sp.Poly(char.subs(p, 0), lam), sp.Poly(sp.diff(char, p), lam)

        def split(poly):
            re = sum((c * w ** m * (1 if m % 4 == 0 else -1) for (m,), c in poly.terms() if m % 2 == 0), sp.S.Zero)
            im = sum((c * w ** m * (1 if m % 4 == 1 else -1) for (m,), c in poly.terms() if m % 2 == 1), sp.S.Zero)
            return re, im

        Pr, Pi = split(P)
        Qr, Qi = split(Q)
        to_W = lambda e: sp.expand(e).subs(w, sp.sqrt(W))
        H, re, q2 = line._hopf_polys
        assert H == sp.Poly(to_W(sp.expand((Pi * Qr - Pr * Qi) / w)), W), name
        assert H.all_coeffs() == sp.Poly(to_W(sp.expand((Pi * Qr - Pr * Qi) / w)), W).all_coeffs(), name
        assert re == to_W(Pr * Qr + Pi * Qi), name
        assert q2 == to_W(Qr ** 2 + Qi ** 2), name
        assert [P.as_expr(), Q.as_expr()] == [c.as_expr() for c in line._char], name
