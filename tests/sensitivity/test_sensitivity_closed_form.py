"""∂k_c/∂p and ∂ω_c/∂p against their closed forms, derived by hand, for the Dieterich and Ruina laws.

At one state variable both laws have the same first derivatives at steady sliding, so the same
Hopf line (Putelat, Dawes & Willis 2010, eqs 7–8 with Table 1):
k_c = σ(b − a)/L · (1 + M V²/(σ a L)) = σ(b − a)/L + M V²(b − a)/(a L²),
ω_c = (V/L) sqrt((b − a)/a).  Their derivatives, term by term:
∂k_c/∂a = −σ/L − M V² b/(a² L²),     ∂k_c/∂b = σ/L + M V²/(a L²),
∂k_c/∂L = −σ(b − a)/L² − 2 M V²(b − a)/(a L³),  ∂k_c/∂σ = (b − a)/L,
∂k_c/∂M = V²(b − a)/(a L²),  ∂k_c/∂V = 2 M V (b − a)/(a L²),  ∂k_c/∂a_v = ∂k_c/∂V_s = 0;
∂ω_c/∂V = ω_c/V, ∂ω_c/∂L = −ω_c/L, ∂ω_c/∂b = ω_c/(2(b − a)), ∂ω_c/∂a = −ω_c b/(2a(b − a)).
The compiled sensitivities agree to 1e-12 relative (float64 rounding of a few operations), the
symbolic closed forms exactly.
"""

import numpy as np
import pytest
import sympy as sp

import landau

P = {"a_v": 0.369, "a": 0.0349, "b": 0.0489, "L": 9e-7, "V_s": 1e-6, "M": 1.2, "sigma": 11.772}


def hand_kc(p, V):
    a, b, L, M, s = p["a"], p["b"], p["L"], p["M"], p["sigma"]
    return {"a": -s / L - M * V ** 2 * b / (a ** 2 * L ** 2), "b": s / L + M * V ** 2 / (a * L ** 2),
            "L": -s * (b - a) / L ** 2 - 2 * M * V ** 2 * (b - a) / (a * L ** 3), "sigma": (b - a) / L,
            "M": V ** 2 * (b - a) / (a * L ** 2), "V": 2 * M * V * (b - a) / (a * L ** 2), "a_v": 0.0, "V_s": 0.0}


def hand_omega(p, V):
    a, b, L = p["a"], p["b"], p["L"]
    om = V / L * np.sqrt((b - a) / a)
    return {"V": om / V, "L": -om / L, "b": om / (2 * (b - a)), "a": -om * b / (2 * a * (b - a)),
            "M": 0.0, "sigma": 0.0, "a_v": 0.0, "V_s": 0.0}


@pytest.mark.parametrize("law", ["dieterich", "ruina"])
@pytest.mark.parametrize("V", [1e-5, 3e-4])
def test_kc_and_omega_sensitivities_against_hand_closed_forms(law, V):
    d = landau.derive(law, ["k_c"])
    res = d.sensitivities(V, P, ["k_c", "omega_c"])
    for q, hand in (("k_c", hand_kc(P, V)), ("omega_c", hand_omega(P, V))):
        for p, want in hand.items():
            got = float(np.ravel(res[q][p])[0])
            # an exact zero comes out as a zero or as rounding of the chain rule's terms, 1e-15 of q/p
            scale = abs(float(np.ravel(res["value"][q])[0])) / (V if p == "V" else P[p])
            assert got == pytest.approx(want, rel=1e-12, abs=1e-14 * scale), (q, p)


@pytest.mark.parametrize("law", ["dieterich", "ruina"])
def test_kc_sensitivity_closed_form_is_the_hand_derivative(law):
    d = landau.derive(law, ["k_c"])
    a, b, L, M, s, V = sp.symbols("a b L M sigma V", positive=True)
    kc = s * (b - a) / L + M * V ** 2 * (b - a) / (a * L ** 2)
    syms = {x.name: x for x in d.coefficient("k_c").closed_form().free_symbols}
    for name, x in (("a", a), ("b", b), ("L", L), ("M", M), ("sigma", s), ("V", V)):
        got = d.sensitivity("k_c", name).closed_form()
        want = sp.diff(kc, x).xreplace({y: syms[y.name] for y in (a, b, L, M, s, V) if y.name in syms})
        assert sp.cancel(got - want) == 0, name


def test_sensitivity_latex_and_units():
    d = landau.derive("dieterich", ["k_c"])
    s = d.sensitivity("k_c", "b")
    tex = s.latex()
    assert tex.startswith("\\begin{align*}") and "\\frac{\\partial k_c}{\\partial b}" in tex
    assert s.units == "N/m" and d.sensitivity("k_c", "L").units == "(N/m)/(m)"
    assert s.name == "d(k_c)/d(b)"


def test_a_quantity_derived_lazily_brings_its_atoms():
    # derive(law, ["k_c"]) builds only k_c: Λ's formula (and the third-derivative atoms it adds) is
    # derived by the sensitivity itself, before the atoms are evaluated
    lazy = landau.derive("ruina", ["k_c"]).sensitivity("Lambda", "a")(1e-4)
    full = landau.derive("ruina").sensitivity("Lambda", "a")(1e-4)
    assert float(lazy) == pytest.approx(float(full), rel=1e-14)
