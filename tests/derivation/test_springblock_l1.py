"""l₁ and c₁ on the spring–block's main routes (``predict``, ``Derivation.points``).

The slip-normalised Fredholm route gives Λ and χ (Putelat et al. 2010); Kuznetsov's c₁ rescales
(Λ + iχ)/2 by 1/‖q‖², q the critical eigenvector in the state coordinates (X, u = Ẋ, φ…).  The
independent computation is the general engine's own Kuznetsov projection
(``landau.derivation.general.hopf_normal_form``) on ``SpringBlock(law).system``, which locates the
Hopf point and derives c₁ without the slip-normalised coefficients.
"""

from __future__ import annotations

import pytest

from landau.derivation.general import hopf_normal_form
from landau.laws import get_law
from landau.systems.system import SpringBlock
from landau.verify.springblock.checks import predict

CASES = [("dieterich", 1e-4), ("dieterich", 1e-3), ("ruina", 1e-4), ("ruina", 1e-3)]


def _general(law, V: float, r):
    params = {**{k: v for k, v in r.params.items() if k != "V"}, "V": V}
    return hopf_normal_form(SpringBlock(law).system, params, (0.9 * r.p_c, 1.1 * r.p_c))


@pytest.mark.parametrize(("name", "V"), CASES)
def test_predict_l1_c1_match_general_engine(name: str, V: float) -> None:
    law = get_law(name)
    r = predict(law, V)
    g = _general(law, V, r)
    assert r.l1 == pytest.approx(g.l1, rel=1e-8)
    assert r.c1.real == pytest.approx(g.c1.real, rel=1e-8)
    assert r.c1.imag == pytest.approx(g.c1.imag, rel=1e-8)
    # l1 = Re c1/omega_c, and the JSON carries both
    assert r.l1 == pytest.approx(r.c1.real / r.omega_c, rel=1e-14)
    d = r.as_dict()
    assert d["l1"] == r.l1 and d["c1"] == [r.c1.real, r.c1.imag]
    assert "l1 = " in repr(r)


def test_dieterich_published_point_norm() -> None:
    """Dieterich at V = 1e-4 (Table 1): c₁ = (Λ + iχ)/(2‖q‖²) with ‖q‖² = 1 + ω_c² + |φ₁|² ≈ 2.864e7."""
    r = predict(get_law("dieterich"), 1e-4)
    norm2 = r.Lambda / (2 * r.c1.real)
    assert norm2 == pytest.approx(r.chi / (2 * r.c1.imag), rel=1e-12)
    assert norm2 == pytest.approx(2.864e7, rel=1e-3)
    assert norm2 > 1 + r.omega_c ** 2          # the state component adds |φ₁|² > 0


@pytest.mark.parametrize("name", ["dieterich", "ruina"])
def test_points_carry_the_same_l1_c1(name: str) -> None:
    import landau

    law = get_law(name)
    pts = landau.derive(SpringBlock(law)).points([1e-4, 1e-3])
    for p, V in zip(pts, (1e-4, 1e-3), strict=True):
        r = predict(law, V)
        assert p.l1 == pytest.approx(r.l1, rel=1e-9)
        assert p.c1.real == pytest.approx(r.c1.real, rel=1e-9)
        assert p.c1.imag == pytest.approx(r.c1.imag, rel=1e-9)
