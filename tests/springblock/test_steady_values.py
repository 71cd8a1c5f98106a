"""The spring–block's steady spring force and normal load as numbers (``steady_values``).

Closed form (the force balance F − σ μ_ss − η V = 0 with σ = σ₀ + γ_LD F, radiation damping η and
the variable normal stress of Linker & Dieterich 1992): F_ss = (σ₀ μ_ss + η V)/(1 − γ_LD μ_ss),
σ_ss = (σ₀ + γ_LD η V)/(1 − γ_LD μ_ss).  The values are solved once per set of terms in symbols:
a load history calls this at every run, and solving with the numbers themselves made sympy
rationalise every float by PSLQ (17 ms a call, most of a compiled history's CPU).
"""

from __future__ import annotations

import pytest
import sympy as sp

from landau.errors import InputError
from landau.systems import springblock_terms as T

SIGMA0, MU, V = 11.772, 0.6, 1e-5


@pytest.mark.parametrize("eta, gamma", [(0.0, 0.0), (100.0, 0.0), (100.0, 0.3), (3e3, -0.2)])
def test_steady_values_are_the_closed_form(eta, gamma):
    terms = ("eta", "gamma_ld")
    F, sigma = T.steady_values(terms, SIGMA0, MU, V, {"eta": eta, "gamma_ld": gamma})
    # a few ulps: the closed form and the solved form round differently
    assert F == pytest.approx((SIGMA0 * MU + eta * V) / (1 - gamma * MU), rel=1e-15)
    assert sigma == pytest.approx((SIGMA0 + gamma * eta * V) / (1 - gamma * MU), rel=1e-15)


def test_numbers_are_not_solved_again(monkeypatch):
    terms = ("eta", "gamma_ld")
    T.steady_values(terms, SIGMA0, MU, V, {"eta": 1.0, "gamma_ld": 0.1})   # solved (here or earlier)

    def refuse(*args, **kwargs):
        raise AssertionError("sympy.solve called for numbers")

    monkeypatch.setattr(sp, "solve", refuse)
    F, _ = T.steady_values(terms, 2 * SIGMA0, MU / 2, 3 * V, {"eta": 7.0, "gamma_ld": 0.2})
    assert F == pytest.approx((2 * SIGMA0 * MU / 2 + 7.0 * 3 * V) / (1 - 0.2 * MU / 2), rel=1e-15)


def test_a_term_registered_again_is_solved_again():
    c = sp.Symbol("c_test_load", nonnegative=True)
    for slope in (0.1, 0.4):   # the same name, two declarations: σ = σ₀ + slope·c·F
        T.register_term("c_test_load", T.Term(c, "1", "a test load", "a test", True,
                                              load=lambda b, s=slope: s * b.symbol["c_test_load"] * b.F))
        try:
            _, sigma = T.steady_values(("c_test_load",), SIGMA0, MU, V, {"c_test_load": 1.0})
        finally:
            T.unregister_term("c_test_load")
        assert sigma == pytest.approx(SIGMA0 / (1 - slope * MU), rel=1e-15)


def test_no_steady_sliding_where_the_load_diverges():
    with pytest.raises(InputError, match="no finite spring force"):
        T.steady_values(("gamma_ld",), SIGMA0, MU, V, {"gamma_ld": 1 / MU})
