"""Putelat, Dawes & Willis (2010) scenes away from Table 1, each against an independent computation.

The scenes' search windows come from the law's scales (V̂ = sqrt(aσL/M) of eq. 31, c_crit of Sec. 4.1,
V_m of eq. 41, L/t_ss), so these sets move the answers away from the printed numbers.  The
references are Kuznetsov's first Lyapunov coefficient at 40 digits (projection method on the full
system, not the multiple-scales closed form the scenes evaluate) and closed forms; the extrema of μ_ss
(against mpmath roots) are in test_off_paper.py.
"""

import pytest
from scipy.optimize import brentq

from landau.derivation.lyapunov import spring_block_lyapunov
from landau.laws import get_law
from landau.scenes import run_scene
from landau.systems.system import SpringBlock


def _sigma_params(doc):
    q = {k: v for k, v in doc["params"].items() if k != "g"}
    q["sigma"] = q["M"] * doc["params"]["g"]
    return q


@pytest.mark.parametrize("params", [{"c": 5e-4}, {"c": 2e-4, "b": 0.055}])
def test_modified_dieterich_transition_velocity_against_kuznetsov(params):
    """V* of law (39) (Λ = 0 on the Hopf line) at other c and b against the root of Kuznetsov's
    l₁(V) (landau.derivation.lyapunov, 40 digits, k_c re-located from the eigenvalues) found by brentq between
    V*(1 ∓ 1e-3).  Λ and l₁ have the same sign and a simple zero; l₁ is evaluated to ~1e-30, so the
    roots agree to brentq's xtol (1e-12 relative); 1e-8 leaves room for the relocation of k_c."""
    doc = run_scene("putelat2010/V-star-modified-dieterich", params)
    V = doc["value"]
    q = _sigma_params(doc)
    block = SpringBlock(get_law("modified-dieterich"))
    l1 = lambda v: spring_block_lyapunov(block, v, q).l1  # noqa: E731
    ref = brentq(l1, V * (1 - 1e-3), V * (1 + 1e-3), xtol=1e-12 * V, rtol=1e-12)
    assert V == pytest.approx(ref, rel=1e-8)


@pytest.mark.parametrize("params", [{"b": 0.055}, {"L": 2e-6, "a": 0.03}])
def test_critical_residual_strength_off_paper(params):
    """c* of law (39) for other b, a and L: the transition line ends where V* meets the minimum of μ_ss,
    so the reported V_m(c*) must equal the closed form of eq. (41), (b/a − 1)V_*/c*, at the returned
    c* (to 1e-8: both are double-precision evaluations); and V* exists 1 % below c* (the V* scene
    returns a value) but not 1 % above (a named InputError)."""
    from landau.errors import InputError

    doc = run_scene("putelat2010/c-star", params)
    c, p = doc["value"], doc["params"]
    assert doc["V_m"] == pytest.approx((p["b"] / p["a"] - 1) * p["V_s"] / c, rel=1e-8)
    below = run_scene("putelat2010/V-star-modified-dieterich", {**params, "c": 0.99 * c})
    assert below["value"] > 0
    with pytest.raises(InputError):
        run_scene("putelat2010/V-star-modified-dieterich", {**params, "c": 1.01 * c})


@pytest.mark.parametrize("params", [{"M": 0.3}, {"L": 3e-6, "b": 0.06}])
def test_nanoscale_low_transition_off_paper_is_a_sign_change_of_kuznetsov_l1(params):
    """Low-velocity transition V_l* of the nanoscale law at other M, L, b: Kuznetsov's l₁ (40 digits)
    changes sign across V_l*(1 ∓ 1e-3).  (Near a simple zero |l₁| grows linearly; 1e-3 relative is
    ~1e6 times the scene's root tolerance.)"""
    doc = run_scene("putelat2010/nanoscale-V-star-low", params)
    V, q = doc["value"], _sigma_params(doc)
    block = SpringBlock(get_law("nanoscale"))
    lo, hi = (spring_block_lyapunov(block, V * f, q).l1 for f in (1 - 1e-3, 1 + 1e-3))
    assert lo * hi < 0
