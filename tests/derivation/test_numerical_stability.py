"""Compiled (float64, vectorised) coefficients vs the same formulas at 50 digits.

Numerical stability: every compiled coefficient (k_c, ω_c, Γ̄, Ω̄,
Λ, χ, C via ``Derivation.evaluate``) agrees with ``Derivation.evaluate_mp`` (mpmath, 50
digits) to ≤ 1e-9 relative on 200 log-spaced V in each law's velocity-weakening range,
in the quasi-static limit (M = 1e-12 and M = 0), and within 1e-6 (relative) of the
ends V_M, V_m of the range, where k_c, Γ and Λ → 0.  There the engine must return the
limit or flag the point (NaN), never a wrong finite number.

Reference value.  The 50-digit value is trusted where it is converged: if it differs from
the compiled value, it is recomputed at 70 digits; when the two mpmath values disagree
by more than 1e-9 the quantity is below the rounding noise of the formula, i.e. its true
value is its limit (0 for Λ, ∞ for C), and the compiled value must be that limit or NaN.
1e-9 is the required tolerance: float64 evaluation of a well-conditioned formula is good
to ~1e-13 here, so 1e-9 only fails where cancellation destroys ≥ 7 digits.
"""

from __future__ import annotations

import math

import mpmath
import numpy as np
import pytest
import sympy as sp
from vw_ranges import LAWS, vw_range

from landau.derivation.multiscale import derive
from landau.laws import get_law
from landau.systems.system import M, SpringBlock

NAMES = ["kc", "omega_c", "Gamma_bar", "Omega_bar", "Lambda", "chi", "C"]
REL = 1e-9
N_POINTS = 200
#: the limit of a quantity whose true value is below the formula's rounding noise
LIMIT = {"Lambda": 0.0, "chi": 0.0, "Gamma_bar": 0.0, "Omega_bar": 0.0, "kc": 0.0, "omega_c": 0.0, "C": math.inf}

#: what a point flagged "degenerate" (Λ → 0) may return instead of the 50-digit value
DEGENERATE_LIMIT = {"Lambda": 0.0, "chi": 0.0, "C": math.inf}

_derivations: dict[str, object] = {}


def _derivation(name: str):
    if name not in _derivations:
        _derivations[name] = derive(SpringBlock(get_law(name)), NAMES)
    return _derivations[name]


def _mismatches(name: str, Vs, params, method: str = "auto") -> list[str]:
    """Every (V, quantity) where the compiled value is neither the 50-digit value nor the limit."""
    d = _derivation(name)
    comp = d.evaluate(np.asarray(Vs, dtype=float), params, NAMES, method=method)
    flagged = np.asarray(comp.get("degenerate", np.zeros(len(Vs), dtype=bool)))
    bad: list[str] = []
    for i, V0 in enumerate(Vs):
        V0 = float(V0)
        # a point the engine flags as degenerate may return the limits Λ, χ → 0, C → ∞ (a
        # degenerate point may return the limit instead of a value); everything else must still agree
        limits_ok = set(DEGENERATE_LIMIT) if flagged[i] else set()
        try:
            ref = d.evaluate_mp(V0, params, NAMES, dps=50)
        except Exception as exc:  # noqa: BLE001 - any exception here is a finding to report
            bad.append(f"{name} V={V0!r} {params}: evaluate_mp raised {exc!r}")
            continue
        hi = None
        for q in NAMES:
            c, m = float(comp[q][i]), ref[q]
            if math.isfinite(c) and mpmath.isfinite(m) and abs(mpmath.mpf(c) - m) <= REL * abs(m):
                continue
            if q in limits_ok and (math.isnan(c) or c == DEGENERATE_LIMIT[q]):
                continue
            if hi is None:
                hi = d.evaluate_mp(V0, params, NAMES, dps=70)
            m2 = hi[q]
            converged = mpmath.isfinite(m) and mpmath.isfinite(m2) and abs(m - m2) <= REL * abs(m2)
            if converged:
                bad.append(f"{name} V={V0!r} {params}: {q} compiled={c!r} mp50={mpmath.nstr(m, 17)}")
            elif not (math.isnan(c) or c == LIMIT[q]):
                bad.append(f"{name} V={V0!r} {params}: {q} compiled={c!r}, but its true value is the limit "
                           f"{LIMIT[q]} (mp50={mpmath.nstr(m, 5)}, mp70={mpmath.nstr(m2, 5)})")
    return bad


def _grid(name: str) -> np.ndarray:
    lo, hi, ends = vw_range(name)
    # the ends of a true range are zeros of μ_ss' (no Hopf point there): stay 1e-6 inside
    lo = lo * (1 + 1e-6) if lo in ends else lo
    hi = hi * (1 - 1e-6) if hi in ends else hi
    return np.logspace(math.log10(lo), math.log10(hi), N_POINTS)


def _report(bad: list[str]) -> str:
    return f"{len(bad)} mismatches, e.g.\n" + "\n".join(bad[:12])


@pytest.mark.parametrize("name", LAWS)
def test_compiled_matches_mp_in_range(name):
    bad = _mismatches(name, _grid(name), {})
    assert not bad, _report(bad)


@pytest.mark.parametrize("mass", [1e-12, 0.0])
@pytest.mark.parametrize("name", LAWS)
def test_compiled_matches_mp_quasi_static(name, mass):
    bad = _mismatches(name, _grid(name), {"M": mass})
    assert not bad, _report(bad)


@pytest.mark.parametrize("name", [n for n in LAWS if vw_range(n)[2]])
def test_compiled_near_range_ends(name):
    # V within 1e-6, 1e-7, 1e-9 (relative) of V_M and V_m, on the velocity-weakening side
    lo, hi, ends = vw_range(name)
    Vs = [e * (1 + s * r) for e in ends for r in (1e-6, 1e-7, 1e-9)
          for s in ((1,) if e == lo else (-1,))]
    bad = []
    for mass in (1.2, 0.0):
        bad += _mismatches(name, Vs, {"M": mass})
    assert not bad, _report(bad)


RATIONAL_LAWS = ["dieterich", "ruina", "modified-dieterich"]


@pytest.mark.parametrize("mass", [1.2, 1e-12, 0.0])
@pytest.mark.parametrize("name", RATIONAL_LAWS)
def test_exactly_cancelled_route_matches_mp(name, mass):
    """The route large batches take (landau.derivation.rational: Horner with error bounds, exact ℚ
    fallback) against 50 digits on the same grid, plus V within 1e-6…1e-9 of the range ends
    and of the codimension-two point, where the bound sends points to the exact fallback."""
    from landau.analyses.transition import codim2_points

    d = _derivation(name)
    lo, hi, ends = vw_range(name)
    extra = [e * (1 + s * r) for e in ends for r in (1e-6, 1e-9) for s in ((1,) if e == lo else (-1,))]
    if mass > 0:
        extra += [c.V * (1 + r) for c in codim2_points(d, lo * 1.001, hi * 0.999, {"M": mass}) for r in (1e-7, -1e-9)]
    bad = _mismatches(name, np.concatenate([_grid(name), extra]), {"M": mass}, method="rational")
    assert not bad, _report(bad)


def _rationalised(expr: sp.Expr) -> sp.Expr:
    """Cancel an expression with square roots of V, a, σ and b − a (Dieterich–Ruina closed forms):
    V = s_V², a = s_a², σ = s_σ², b = a + s_d² make every radical a symbol, so ``cancel`` is exact."""
    sy = {s.name: s for s in expr.free_symbols}
    sV, sa, ss, sd = sp.symbols("s_V s_a s_sigma s_d", positive=True)
    e = expr.subs({sy["b"]: sy["a"] + sd ** 2}).subs({sy["V"]: sV ** 2, sy["a"]: sa ** 2, sy["sigma"]: ss ** 2})
    return sp.cancel(sp.together(e))


def test_dieterich_quasi_static_lambda_vanishes_closed_form():
    # Putelat et al. 2010, text below eq. (33): "neglecting inertia implies A_D(V) = 0"
    coef = _derivation("dieterich").coefficient("Lambda")
    assert _rationalised(coef.expr.subs(M, 0)) == 0          # the engine's formula, cancelled exactly
    closed = coef.closed_form()                              # re-derived in Q(V, a, b, L, σ, M)(ω_c)
    m = next(x for x in closed.free_symbols if x.name == "M")
    assert closed.subs(m, 0) == 0 and sp.cancel(closed / m).subs(m, 0) != 0   # Λ_D = M·(…), exactly
    # and it is not zero for M > 0 (eq. 33 is O(M); subcritical, Λ_D > 0, at V = 1e-5)
    assert _derivation("dieterich").evaluate_mp(1e-5, {"M": 1.2}, ["Lambda"])["Lambda"] > 1e8


def test_dieterich_quasi_static_lambda_vanishes_numerically():
    d = _derivation("dieterich")
    Vs = np.logspace(-8, -1, 50)
    lam = d.evaluate(Vs, {"M": 0.0}, ["Lambda"])["Lambda"]
    # exactly zero (or flagged): any finite non-zero number would be read as a criticality
    assert np.all((lam == 0) | np.isnan(lam)), lam[(lam != 0) & ~np.isnan(lam)][:5]


def test_dieterich_quasi_static_lambda_vanishes_at_50_digits():
    d = _derivation("dieterich")
    for V0 in (1e-7, 1e-5, 1e-3):
        lam = d.evaluate_mp(V0, {"M": 0.0}, ["Lambda"], dps=50)["Lambda"]
        # the terms of Λ are O(1e13) here: 1e-25 is 38 orders below them, i.e. exact zero at 50 digits
        assert abs(lam) < mpmath.mpf(10) ** -25, (V0, lam)
