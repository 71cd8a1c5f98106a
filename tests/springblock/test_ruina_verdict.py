"""The Ruina-law Landau coefficient: printed eq. (35) of Putelat et al. (2010) vs the engine.

Verdict (docs/verdicts.md): the printed (35) is wrong; the correct form is

    Λ_R = − σ M b (b − a)² V³ (Lσa + MV²)(Lσa + 9MV²) / (L² D₁ D₂),
    D₁ = M²bV⁴ + 2LσMa²V² + L²σ²a³,   D₂ = M²(4b − 3a)V⁴ + 2LσMa²V² + L²σ²a³

(same denominators as the printed (33) and (35)).  Evidence here: the engine's closed form
equals it at random rational points (50 digits), Kuznetsov's projection formula
(landau.derivation.lyapunov) reproduces its C, and the quasi-static (M = 0) system — written
independently in log-variables — has l₁ = 0, as the correct form says and (35) denies.
"""

from __future__ import annotations

import functools
import math
import random

import mpmath
import pytest
import sympy as sp

from landau.derivation.lyapunov import first_lyapunov, spring_block_lyapunov
from landau.derivation.multiscale import derive
from landau.laws import get_law
from landau.systems.system import DynamicalSystem, SpringBlock

a, b, L, V, s, M = sp.symbols("a b L V sigma M", positive=True)
D1 = M ** 2 * b * V ** 4 + 2 * L * s * a ** 2 * M * V ** 2 + L ** 2 * s ** 2 * a ** 3
D2 = M ** 2 * (4 * b - 3 * a) * V ** 4 + 2 * L * s * a ** 2 * M * V ** 2 + L ** 2 * s ** 2 * a ** 3
#: Putelat et al. 2010, eq. (35) as printed (OCR checked against the text that follows it:
#: its V → 0 limit −(b−a)V/(2aL³), V → ∞ limit and the quartic's discriminant all follow from it)
PRINTED = (s * (b - a) * V * (L * s * a + M * V ** 2)
           * (M ** 2 * (14 * a * b + 3 * a ** 2 - 18 * b ** 2) * V ** 4
              - 2 * M * a * L * s * (b ** 2 - a * b + a ** 2) * V ** 2 - a ** 4 * s ** 2 * L ** 2)
           / (2 * L ** 2 * D1 * D2))
#: the correct form (the engine's closed form, cancelled)
CORRECT = (-s * M * b * (b - a) ** 2 * V ** 3 * (L * s * a + M * V ** 2) * (L * s * a + 9 * M * V ** 2)
           / (L ** 2 * D1 * D2))
#: Γ̄ of eq. (32): Γ_DR = −2Γ̄ k₂
GAMMA_BAR = sp.Rational(1, 2) * (s * a / V) / ((s * a / V) ** 2 + M * (M * (b / a) * (V / L) ** 2 + 2 * s * a / L))


@pytest.fixture(scope="module")
def ruina():
    return derive(SpringBlock(get_law("ruina")), ["Gamma_bar", "Lambda", "C"])


@functools.lru_cache(maxsize=None)
def _mp_function(expr, args):
    return sp.lambdify(list(args), expr, "mpmath")


def _at(expr, values):
    """``expr`` at ``values`` (symbol -> mpf), with mpmath; lambdified once per expression."""
    return _mp_function(expr, tuple(values))(*values.values())


def test_engine_closed_form_is_the_correct_form_not_the_printed_one(ruina):
    # the engine's unsimplified expression (its formula in the law's derivatives, ω = sqrt(ω_c²))
    engine = ruina.coefficient("Lambda").expr
    order = sorted(engine.free_symbols, key=lambda x: x.name)
    # once, with common subexpressions shared: the unsimplified form is a tree of the formula DAG
    # (0.1 s per 50-digit evaluation without cse, 1 ms with it; the same digits)
    f_engine = sp.lambdify(order, engine, "mpmath", cse=True)
    rng = random.Random(35)
    with mpmath.workdps(50):
        for _ in range(20):
            # random rational points with b > a > 0 (velocity weakening: a Hopf point exists)
            av = sp.Rational(rng.randint(1, 60), 1000)
            pt = {"a": av, "b": av + sp.Rational(rng.randint(1, 60), 1000), "L": sp.Rational(rng.randint(1, 20), 7),
                  "V": sp.Rational(rng.randint(1, 50), 11), "sigma": sp.Rational(rng.randint(1, 30), 3),
                  "M": sp.Rational(rng.randint(1, 40), 9)}
            e = f_engine(*[mpmath.mpf(pt[x.name].p) / pt[x.name].q for x in order])
            vals = {x: mpmath.mpf(pt[x.name].p) / pt[x.name].q for x in (a, b, L, V, s, M)}
            c, p = _at(CORRECT, vals), _at(PRINTED, vals)
            # 50-digit evaluation of a formula with ~30 levels of nesting: 1e-30 is rounding
            assert abs(e - c) <= mpmath.mpf("1e-30") * abs(c), (pt, e, c)
            # the printed form is off by O(1), not by rounding
            assert abs(e - p) > mpmath.mpf("0.01") * abs(c), (pt, e, p)


@pytest.mark.slow
def test_engine_closed_form_is_exactly_the_correct_form(ruina):
    # Coefficient.closed_form() re-derives Λ in ℚ(V, a, b, L, σ, M)(ω_c) (landau.derivation.rational): it must
    # be the correct form identically, not just at sample points (~20 s: multivariate gcds)
    engine = ruina.coefficient("Lambda").closed_form()
    sym = {x.name: x for x in engine.free_symbols}
    correct = CORRECT.xreplace({x: sym[x.name] for x in (a, b, L, V, s, M)})
    assert sp.cancel(engine - correct) == 0
    assert all(p.exp.is_integer for p in engine.atoms(sp.Pow))   # no radicals left: Λ_R is rational


#: Table 1 (L = 0.9e-6 m), M = 1.2 kg, σ = 11.772 N
TABLE1 = {"a": 0.0349, "b": 0.0489, "L": 0.9e-6, "sigma": 11.772, "M": 1.2}
#: (V, Λ correct, Λ printed) at Table 1 — the numbers of docs/verdicts.md, recomputed below
VELOCITIES = (1e-6, 1e-5, 1e-4, 5.6e-4, 1e-3, 1e-2)


@pytest.mark.parametrize("V0", VELOCITIES)
def test_numbers_engine_kuznetsov_and_correct_form_agree(ruina, V0):
    vals = {x: mpmath.mpf(TABLE1[x.name]) for x in (a, b, L, s, M)}
    vals[V] = mpmath.mpf(V0)
    with mpmath.workdps(50):
        lam_c, lam_p, gbar = _at(CORRECT, vals), _at(PRINTED, vals), _at(GAMMA_BAR, vals)
    eng = ruina.evaluate_mp(V0, {}, ["Gamma_bar", "Lambda", "C"])
    assert abs(eng["Gamma_bar"] - gbar) <= 1e-14 * gbar          # eq. (32) (inputs are floats: 1e-14)
    assert abs(eng["Lambda"] - lam_c) <= 1e-14 * abs(lam_c)
    k = spring_block_lyapunov(ruina.block, V0, jets=ruina.jets)
    C_correct = float(2 * mpmath.sqrt(2 * gbar / abs(lam_c)))
    C_printed = float(2 * mpmath.sqrt(2 * gbar / abs(lam_p)))
    assert k.sign == -1                                            # supercritical, as the paper says
    assert math.isclose(k.C, C_correct, rel_tol=1e-10)             # the independent route
    assert not math.isclose(k.C, C_printed, rel_tol=0.05)          # ≥ 12 % off at every V listed
    # Λ implied by Kuznetsov with Γ̄ of eq. (32): Λ_K = 2Γ̄ Re c₁ / (|q_X|² |μ'|)
    lam_k = 2 * float(gbar) * k.c1.real / (k.q_norm ** 2 * abs(k.dmu_dp))
    assert math.isclose(lam_k, float(lam_c), rel_tol=1e-10)


def test_quasi_static_limit():
    # printed: Λ_R(M = 0) = −(b − a)V/(2aL³) ≠ 0 (text after eq. 35); correct: Λ_R(M = 0) = 0
    assert sp.simplify(PRINTED.subs(M, 0) + (b - a) * V / (2 * a * L ** 3)) == 0
    assert CORRECT.subs(M, 0) == 0
    # hence eq. (25), k̂ − k_c = Λ(Δx)²/(8Γ̄) (|δ|²/(16ω_c²F_V) = 1/(8Γ̄)), gives
    dx = sp.Symbol("Delta_x", positive=True)
    khat_printed = sp.simplify((PRINTED * dx ** 2 / (8 * GAMMA_BAR)).subs(M, 0))
    assert sp.simplify(khat_printed + s * (b - a) * dx ** 2 / (8 * L ** 3)) == 0   # the paper's, with (Δx)²
    assert (CORRECT * dx ** 2 / (8 * GAMMA_BAR)).subs(M, 0) == 0                   # correct: no shift at O(Δx²)
    small_m = sp.limit(CORRECT * dx ** 2 / (8 * GAMMA_BAR) / M, M, 0)
    assert sp.simplify(small_m + b * (b - a) ** 2 * V ** 2 * dx ** 2 / (4 * L ** 4 * a ** 3)) == 0


def _quasi_static_ruina() -> DynamicalSystem:
    """M = 0 spring–block with the Ruina law, written independently of landau.systems.system:
    states X = x − x₀ and θ = ln(Vφ/L); y = ln(ẋ/V) from the force balance
    kX = −σ(a y + b θ); Ẋ = V(eʸ − 1), θ̇ = −(V eʸ/L)(y + θ) (eqs 4, 26, 29 with M = 0)."""
    X, th = sp.symbols("X theta", real=True)
    k, av, bv, Lv, Vv, sv = sp.symbols("k a b L V sigma", positive=True)
    y = (-k * X / sv - bv * th) / av
    return DynamicalSystem("quasi-static-ruina", (X, th), (Vv * (sp.exp(y) - 1), -(Vv * sp.exp(y) / Lv) * (y + th)),
                           (sp.Integer(1), sp.Integer(1)), k, (sp.Integer(0), sp.Integer(0)))


@pytest.mark.parametrize("V0", [1e-6, 1e-5, 1e-4])
def test_quasi_static_ruina_is_degenerate_by_kuznetsov(V0):
    vals = {**{n: TABLE1[n] for n in ("a", "b", "L", "sigma")}, "V": V0}
    kc = vals["sigma"] * (vals["b"] - vals["a"]) / vals["L"]        # eq. (30) with M = 0
    res = first_lyapunov(_quasi_static_ruina(), vals, kc * (1 + 1e-3), dps=50)
    assert math.isclose(res.p_c, kc, rel_tol=1e-12)
    gbar = V0 / (2 * vals["sigma"] * vals["a"])                      # eq. (32) with M = 0
    lam_k = 2 * gbar * res.c1.real / (res.q_norm ** 2 * abs(res.dmu_dp))
    lam_printed = -(vals["b"] - vals["a"]) * V0 / (2 * vals["a"] * vals["L"] ** 3)
    # 50 digits: Λ_K is zero to ≥ 30 orders of magnitude below the printed value
    assert abs(lam_k) < 1e-30 * abs(lam_printed), (lam_k, lam_printed)


def test_small_mass_scaling_by_kuznetsov(ruina):
    # correct form: Λ_R ≈ −M b (b − a)² V³/(σ L⁴ a⁴) as M → 0, so l₁ ∝ M (printed: l₁ → const ≠ 0)
    ratios = [spring_block_lyapunov(ruina.block, 1e-5, {"M": m}, jets=ruina.jets).l1 / m for m in (1e-2, 1e-4, 1e-6)]
    assert all(r < 0 for r in ratios)
    assert math.isclose(ratios[1], ratios[2], rel_tol=1e-5) and math.isclose(ratios[0], ratios[2], rel_tol=1e-2)


def test_paper_general_formulas_give_the_correct_form():
    # the paper's own eqs (7)-(8), (11)-(19), (21), coded directly in F_V, F_φ, G_V, … (no jets, no
    # Fredholm module: benchmarks/bench_engine.py, PaperLambda) — they give the correct form, not (35)
    import sys
    from pathlib import Path

    sys.path.insert(0, str(Path(__file__).resolve().parent.parent.parent / "benchmarks"))
    from bench_engine import PaperLambda

    paper = PaperLambda("ruina")
    for V0 in (1e-6, 1e-4, 1e-2):
        vals = {x: mpmath.mpf(TABLE1[x.name]) for x in (a, b, L, s, M)}
        vals[V] = mpmath.mpf(V0)
        with mpmath.workdps(40):
            got = paper.at(V0, {})
            lam_c, lam_p = _at(CORRECT, vals), _at(PRINTED, vals)
            assert abs(got - lam_c) <= mpmath.mpf("1e-25") * abs(lam_c), (V0, got, lam_c)
            assert abs(got - lam_p) > mpmath.mpf("0.1") * abs(lam_c), (V0, got, lam_p)
