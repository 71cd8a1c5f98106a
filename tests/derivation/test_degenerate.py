"""One verdict at degenerate Hopf points: Λ carries a round-off bound, a vanishing Λ is
``degenerate`` (never a round-off sign), and the next order (l₂, Λ₅) decides — also for a DAE."""

from __future__ import annotations

import pytest

from landau.derivation.general import hopf_normal_form, second_lyapunov
from landau.systems.system import DynamicalSystem, SpringBlock

# Putelat et al. (2010) Table 1 and the quasi-static limit M = 0: the aging law's K_cr = σ(b − a)/L
QS = {"M": 0.0}


def aging_quasi_static(V=1e-4, **over):
    b = SpringBlock("dieterich")
    p = b.resolve({**QS, **over})
    p["V"] = V
    kcr = p["sigma"] * (p["b"] - p["a"]) / p["L"]
    return b, p, kcr


@pytest.mark.parametrize("V, over", [(1e-4, {}), (3e-6, {"a": 0.011, "b": 0.016, "L": 2e-5, "sigma": 50.0})])
def test_quasi_static_aging_law_is_degenerate_at_every_order(V, over):
    # a centre (Ranjith & Rice 1999): every Lyapunov coefficient vanishes
    b, p, kcr = aging_quasi_static(V, **over)
    r = hopf_normal_form(b.system, p, (0.8 * kcr, 1.2 * kcr))
    assert r.p_c == pytest.approx(kcr, rel=1e-13)
    assert r.criticality == "degenerate"
    assert r.Lambda == 0.0 and r.l1 == 0.0
    assert r.extra["Lambda_bound"] < 1e-30
    assert r.l2 == 0.0 and r.Lambda5 == 0.0
    assert r.extra["degenerate_at_every_order_computed"] is True
    assert r.extra["criticality_next_order"] == "degenerate"
    assert r.as_dict()["degenerate_at_every_order_computed"] is True


def test_genuine_lambda_carries_a_small_bound():
    b = SpringBlock("dieterich")
    p = b.resolve({})
    p["V"] = 1e-4
    r = hopf_normal_form(b.system, p, (1.5e5, 2.2e5))
    assert r.criticality == "subcritical"
    assert 0 < r.extra["Lambda_bound"] <= 1.2e-16 * abs(r.Lambda)  # float64 rounding of a 50-digit value
    assert "degenerate_at_every_order_computed" not in r.extra


@pytest.mark.parametrize("s2", [-0.3, 0.7])
def test_bautin_normal_form_is_decided_at_fifth_order(s2):
    # z' = (p + i) z + s2 z|z|^4 in z = x + iy: Lambda = 0 exactly; with <q,q> = 1 (z = sqrt2 z'),
    # Re c2 = 4 s2; with the x-component of the mode 1 (z = 2A), Lambda5 = 2 Re(16 s2) = 32 s2
    r2 = "(x^2 + y^2)^2"
    s = DynamicalSystem.from_strings({"x": f"p*x - y + s2*x*{r2}", "y": f"x + p*y + s2*y*{r2}"}, "p",
                                     {"s2": s2}, guess={"x": 0.0, "y": 0.0})
    r = hopf_normal_form(s, s.defaults, (-0.5, 0.5))
    assert r.criticality == "degenerate"
    assert r.l2 == pytest.approx(4 * s2, rel=1e-12)
    assert r.Lambda5 == pytest.approx(32 * s2, rel=1e-12)
    assert r.extra["criticality_next_order"] == ("supercritical" if s2 < 0 else "subcritical")
    assert r.extra["degenerate_at_every_order_computed"] is False


def test_next_order_of_a_dae_matches_the_explicit_reduction():
    # modified-dieterich law, M = 0 (Λ ≠ 0 there, unlike the aging and slip laws): the u-row
    # a ln((V+u)/V) + b ln((c + V_s phi/L)/(c + V_s/V)) = -kX/sigma solves for u explicitly, so the
    # DAE is the 2-state ODE below (written independently, no algebraic row)
    from landau.derivation.degenerate import next_order

    b = SpringBlock("modified-dieterich")
    p = b.resolve(QS)
    p["V"] = 1e-4
    br = (0.5 * p["sigma"] * (p["b"] - p["a"]) / p["L"], 1.2 * p["sigma"] * (p["b"] - p["a"]) / p["L"])
    dae = hopf_normal_form(b.system, p, br, l2=True)
    u = "V*exp(-(k*X/sigma + b*log((c + V_s*phi/L)/(c + V_s/V)))/a) - V"
    ode = DynamicalSystem.from_strings({"X": u, "phi": f"1 - phi*(V + {u})/L"}, "k",
                                       {n: p[n] for n in ("V", "a", "b", "L", "sigma", "c", "V_s")},
                                       equilibrium={"X": "0", "phi": "L/V"})
    ref = hopf_normal_form(ode, ode.defaults, br, l2=True)
    assert dae.p_c == pytest.approx(ref.p_c, rel=1e-13)
    assert dae.Lambda == pytest.approx(ref.Lambda, rel=1e-10) and dae.Lambda < 0
    nd, nr = next_order(b.system, p, dae, 50), next_order(ode, ode.defaults, ref, 50)
    assert nd["Lambda5"] == pytest.approx(nr["Lambda5"], rel=1e-9)      # both normalised on X = 1
    # Kuznetsov's <q, q> = 1 spans (X, u, phi) in the DAE and (X, phi) in the ODE: l2 = Re c2 scales
    # with the square of the factor by which l1 = Re c1/omega does
    assert nd["l2"] / nr["l2"] == pytest.approx((dae.l1 / ref.l1) ** 2, rel=1e-9)
    assert second_lyapunov(b.system, p, dae) == pytest.approx(dae.l2, rel=1e-12)


def test_identical_quasi_static_chain_is_degenerate_in_phase():
    # two identical quasi-static aging-law blocks: the in-phase mode is the single block's centre
    from landau.analyses.chain import chain_hopf
    from landau.systems.chain import SpringBlockChain

    r = chain_hopf(SpringBlockChain("dieterich", 2), {"M_1": 0.0, "M_2": 0.0, "k_coupling": 2e4})
    assert r.p_c == pytest.approx(11.772 * (0.0489 - 0.0349) / 9e-7, rel=1e-12)
    assert r.criticality == "degenerate" and r.extra["mode"] == "in-phase"
    assert r.extra["degenerate_at_every_order_computed"] is True
