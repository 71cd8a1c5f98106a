"""The Hopf polynomial of a characteristic polynomial P(λ) + p Q(λ): exact products in the atoms.

A pair λ = ±iω crosses the imaginary axis where P(iω) + p Q(iω) = 0 with p real, i.e. where
Im(P Q̄)(iω) = 0, and there p = −Re(P Q̄)/|Q|² (Putelat et al. 2010, eqs 7–8, for one state
variable).  With P(iω) = P_r + i P_i, Q(iω) = Q_r + i Q_i (P_r, Q_r even in ω, P_i, Q_i odd):

    H(W) = (P_i Q_r − P_r Q_i)/ω,   Re(P Q̄) = P_r Q_r + P_i Q_i,   |Q|² = Q_r² + Q_i²,

all even in ω, so ω² → W relabels their exponents.  The coefficients of P and Q are polynomials
in the law's derivative atoms (one generator per derivative, 2n + 2 of them for n state
variables) with integer coefficients; their products are formed by FLINT's multivariate
arithmetic (python-flint), exactly: the same polynomials as sympy's ring arithmetic, which cost
about a second for eight state variables against a few hundredths here.
"""

from __future__ import annotations

from typing import Any, Callable

import sympy as sp
from sympy.polys.rings import ring as poly_ring


def split_at_iw(coeffs: list[Any], zero: Any) -> tuple[dict[int, Any], dict[int, Any]]:
    """(Re, Im) of Σ cₘ λᵐ at λ = iω as {power of ω: coefficient} (``coeffs`` lowest power first)."""
    re: dict[int, Any] = {}
    im: dict[int, Any] = {}
    for m, c in enumerate(coeffs):
        if c == zero:
            continue
        (re if m % 2 == 0 else im)[m] = c if m % 4 in (0, 1) else -c
    return re, im


def _mul(a: dict[int, Any], b: dict[int, Any]) -> dict[int, Any]:
    out: dict[int, Any] = {}
    for i, x in a.items():
        for j, y in b.items():
            out[i + j] = out[i + j] + x * y if i + j in out else x * y
    return out


def _sub(a: dict[int, Any], b: dict[int, Any]) -> dict[int, Any]:
    out = dict(a)
    for m, y in b.items():
        out[m] = out[m] - y if m in out else -y
    return out


def _add(a: dict[int, Any], b: dict[int, Any]) -> dict[int, Any]:
    out = dict(a)
    for m, y in b.items():
        out[m] = out[m] + y if m in out else y
    return out


def _flint_codec(ring) -> tuple[Callable[[Any], Any], Callable[[Any], Any]] | None:
    """(to FLINT, back to ``ring``) for a sympy polynomial ring over ℤ; None without python-flint."""
    try:
        import flint
    except ImportError:
        return None
    ctx = flint.fmpz_mpoly_ctx.get(tuple(f"x{i}" for i in range(ring.ngens)), "lex")
    to = lambda e: ctx.from_dict({m: int(c) for m, c in e.items()})
    back = lambda f: ring.from_dict({tuple(int(x) for x in m): int(c) for m, c in f.to_dict().items()})
    return to, back


def hopf_polynomials(P: sp.Poly, Q: sp.Poly, W: sp.Symbol) -> tuple[sp.Poly, sp.Expr, sp.Expr] | None:
    """(H(W), Re(P Q̄), |Q|²) of the module docstring, or None where P and Q are not polynomials in λ
    over one polynomial ring over ℤ (the caller then multiplies the sympy polynomials).

    Parameters
    ----------
    P, Q : sympy.Poly
        The characteristic polynomial's parts, in λ over ℤ[atoms].
    W : sympy.Symbol
        The symbol of ω².

    Returns
    -------
    (sympy.Poly, sympy.Expr, sympy.Expr) or None
        H as a polynomial in W over ℤ[the atoms it uses]; Re(P Q̄) and |Q|² expanded in W and the atoms.
    """
    K = P.domain
    if K != Q.domain or not (K.is_PolynomialRing and K.domain.is_ZZ):
        return None
    R = K.ring
    codec = _flint_codec(R)
    to, back = codec if codec is not None else (lambda e: e, lambda e: e)
    # coefficient lists lowest power first, in the ring of the atoms (sympy's or FLINT's)
    Pr, Pi = split_at_iw([to(c) for c in reversed(P.rep.to_list())], to(R.zero))
    Qr, Qi = split_at_iw([to(c) for c in reversed(Q.rep.to_list())], to(R.zero))
    im = {m: back(c) for m, c in _sub(_mul(Pi, Qr), _mul(Pr, Qi)).items()}
    re = {m: back(c) for m, c in _add(_mul(Pr, Qr), _mul(Pi, Qi)).items()}
    q2 = {m: back(c) for m, c in _add(_mul(Qr, Qr), _mul(Qi, Qi)).items()}
    if any(m % 2 == 0 and c for m, c in im.items()) or any(m % 2 and c for d in (re, q2) for m, c in d.items()):
        raise ArithmeticError("Im(P Q̄)/ω, Re(P Q̄) or |Q|² is not even in ω")
    H = {(m - 1) // 2: c for m, c in im.items() if c}
    # H over the ring of the atoms it uses (the domain sympy finds for its expression)
    used = sorted({i for c in H.values() for mon in c.keys() for i, e in enumerate(mon) if e})
    sub_ring = sp.ZZ[tuple(R.symbols[i] for i in used)] if used else sp.ZZ
    if used:
        Hd = {k: sub_ring.ring.from_dict({tuple(mon[i] for i in used): c for mon, c in v.items()})
              for k, v in H.items()}
    else:
        Hd = {k: sub_ring.convert(int(v.get(R.zero_monom, 0))) for k, v in H.items()}
    Hpoly = sp.Poly.from_dict({(k,): c for k, c in Hd.items()} or {(0,): sub_ring.zero}, W, domain=sub_ring)
    # Re(P Q̄), |Q|² as expanded expressions in (W, atoms)
    RW, *_ = poly_ring([W, *R.symbols], sp.ZZ)

    def expr(d: dict[int, Any]) -> sp.Expr:
        terms = {(m // 2, *mon): c for m, v in d.items() for mon, c in v.items()}
        return RW.from_dict(terms).as_expr() if terms else sp.Integer(0)

    return Hpoly, expr(re), expr(q2)


__all__ = ["hopf_polynomials", "split_at_iw"]
