"""One default for one thing: a one-block chain is the spring–block, with the same default load.

Before, ``hopf spring-block-chain dieterich --blocks 1 --param M_1=2`` gave k_c = 315104.8 N/m (σ₁
defaulted to M₁ g) and ``hopf spring-block dieterich --param M=2`` 193024.8 (σ stays 1.2 kg × g: a mass
alone changes the inertia only, Putelat et al. 2010 Sec. 3).  The closed form of the aging law,
k_c = σ(b − a)/L · (1 + M V²/(σ a L)) (Putelat et al. 2010, eq. 30), is the independent value.
"""

from __future__ import annotations

import pytest

import landau.models as models
from landau.laws import get_law

V = 1e-4


def _kc(M, sigma):
    p = get_law("dieterich").defaults()
    return sigma * (p["b"] - p["a"]) / p["L"] * (1 + M * V**2 / (sigma * p["a"] * p["L"]))


@pytest.mark.parametrize("over, M, sigma", [({"M": 2.0}, 2.0, 1.2 * 9.81), ({"M": 2.0, "g": 9.0}, 2.0, 18.0),
                                            ({"M": 0.0, "g": 9.0}, 0.0, 1.2 * 9.0)])
def test_a_one_block_chain_is_the_spring_block(over, M, sigma):
    law = get_law("dieterich")
    single = models.get("spring-block").hopf(models.Setup(law, {"V": V, **over}))
    chain_over = {("M_1" if k == "M" else k): v for k, v in over.items()}
    chain = models.get("spring-block-chain").hopf(models.Setup(law, {"V": V, **chain_over}, {"blocks": 1}))
    assert single.p_c == pytest.approx(_kc(M, sigma), rel=1e-12)
    assert chain.p_c == pytest.approx(single.p_c, rel=1e-12)
