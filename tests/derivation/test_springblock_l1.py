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


def test_numerically_solved_steady_state_closed_form_norm() -> None:
    """A law whose steady state has no closed form, dφ/dt = G = 1 − vφ/L − c·atan(V_sφ/L): ‖q‖² from the
    one-state formula φ₁ = iω_c G_v/(iω_c − G_φ) at the Newton-solved φ₀, ‖q‖² = 1 + ω_c² + |φ₁|²."""
    import math

    from scipy.optimize import brentq

    import landau
    from landau.laws import FrictionLaw

    p = {"a_v": 0.369, "a": 0.0349, "b": 0.0489, "L": 9e-7, "V_s": 1e-6, "c": 0.1}
    law = FrictionLaw.from_strings("atan-state", "a_v + a*log(v/V_s) + b*log(V_s*phi/L)",
                                   {"phi": "1 - v*phi/L - c*atan(V_s*phi/L)"}, p)
    V = 1e-4
    r = predict(law, V)
    L, Vs, c = p["L"], p["V_s"], p["c"]
    phi0 = brentq(lambda f: 1 - V * f / L - c * math.atan(Vs * f / L), 1e-12, L / V, xtol=1e-30, rtol=1e-15)
    G_v, G_phi = -phi0 / L, -V / L - c * (Vs / L) / (1 + (Vs * phi0 / L) ** 2)
    iw = 1j * r.omega_c
    phi1 = iw * G_v / (iw - G_phi)
    norm2 = 1 + r.omega_c ** 2 + abs(phi1) ** 2
    c1 = complex(r.Lambda, r.chi) / (2 * norm2)
    assert r.c1.real == pytest.approx(c1.real, rel=1e-9)
    assert r.c1.imag == pytest.approx(c1.imag, rel=1e-9)
    assert r.l1 == pytest.approx(c1.real / r.omega_c, rel=1e-9)
    pt = landau.derive(SpringBlock(law)).points([V])[0]
    assert pt.l1 == pytest.approx(r.l1, rel=1e-9)
