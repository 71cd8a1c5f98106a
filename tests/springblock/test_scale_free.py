"""Scale-free spring–block numerics: a BP1-like quasi-dynamic cell at the plate rate.

The cell of the SEAS benchmark BP1 (a = 0.010, b = 0.015, σ = 50 MPa, L = 8 mm, η = ρc_s/2 =
4.624e6 Pa·s/m, per unit area) at V = 1e-9 m/s: slow pair ω_c ≈ 1e-7 rad/s and, with inertia,
a fast eigenvalue ≈ −η/M.  The independent route is the general Fredholm engine on the same
equations written by hand in dimensionless variables (time by L/V, slip by L, stress by σ), where
every number is O(1) except the mass m = MV²/(σL).
"""

from __future__ import annotations

import pytest
import sympy as sp

from landau.derivation.general import hopf_normal_form
from landau.errors import NoHopfError
from landau.laws import get_law
from landau.systems.system import DynamicalSystem, SpringBlock
from landau.verify.springblock.checks import predict

BP1 = dict(a=0.010, b=0.015, L=8e-3, sigma=50e6, eta=4.624e6, V_s=1e-6, a_v=0.6)
V = 1e-9


def _dimensionless_hopf(m: float, h: float, a: float, b: float):
    """(κ_c, ω̂_c, Λ̂) of the aging-law cell in units L, L/V, σ: X̂' = û, m û' = −κX̂ − [a ln(1+û) + b ln θ̂] − h û,
    θ̂' = 1 − (1 + û)θ̂ (h = ηV/σ)."""
    X, u, th = sp.symbols("X u th", real=True)
    kap = sp.Symbol("kappa", real=True)
    rhs = (u, -kap * X - (a * sp.log(1 + u) + b * sp.log(th)) - h * u, 1 - (1 + u) * th)
    sys_ = DynamicalSystem("bp1-hat", (X, u, th), rhs, (1, sp.Float(m), 1), kap, (0, 0, 1))
    k0 = (b - a - h) * (1 + m / (a + h))
    r = hopf_normal_form(sys_, {}, (0.5 * k0, 2.0 * k0))
    return r.p_c, r.omega_c, r.Lambda


@pytest.mark.parametrize("M", [0.0, 1e-2])
def test_bp1_cell_hopf_point_against_dimensionless_route(M):
    res = predict(get_law("dieterich"), V, {**BP1, "M": M})
    a, b, L, s, eta = BP1["a"], BP1["b"], BP1["L"], BP1["sigma"], BP1["eta"]
    kc = (s * (b - a) - eta * V) / L * (1 + M * V ** 2 / (L * (s * a + eta * V)))
    assert res.kc == pytest.approx(kc, rel=1e-12)
    m, h = M * V ** 2 / (s * L), eta * V / s
    kap, w, lam = _dimensionless_hopf(m, h, a, b)
    # back to SI: k = κσ/L, ω = ω̂V/L, Λ = Λ̂ V/L³ (slip amplitude in units of L, time in L/V)
    assert res.kc == pytest.approx(kap * s / L, rel=1e-9)
    assert res.omega_c == pytest.approx(w * V / L, rel=1e-9)
    assert res.omega_c == pytest.approx(8.84e-8, rel=1e-3)
    assert res.Lambda == pytest.approx(lam * V / L ** 3, rel=1e-6)
    assert res.criticality == "supercritical"
    if M > 0:   # the fast eigenvalue ≈ −η/M is 1e15 times the slow pair
        assert eta / M / res.omega_c > 1e15


@pytest.mark.parametrize("V_", [1e-10, 1.0])
@pytest.mark.parametrize("M", [1e-8, 1e4])
def test_extremes_of_rate_and_mass(V_, M):
    """Plate rate to seismic slip rate, 1e-8 to 1e4 kg (per unit area): k_c from the closed form and Λ
    from the dimensionless route."""
    # at 1 m/s the BP1 damping (ηV = 4.6 MPa > σ(b − a) = 0.25 MPa) stabilises every k: no Hopf point
    with pytest.raises(NoHopfError):
        predict(get_law("dieterich"), 1.0, {**BP1, "M": M})
    eta = BP1["eta"] if V_ < 1e-3 else 1e4
    prm = {**BP1, "M": M, "eta": eta}
    a, b, L, s = BP1["a"], BP1["b"], BP1["L"], BP1["sigma"]
    kc = (s * (b - a) - eta * V_) / L * (1 + M * V_ ** 2 / (L * (s * a + eta * V_)))
    res = predict(get_law("dieterich"), V_, prm)
    assert res.kc == pytest.approx(kc, rel=1e-10)
    m, h = M * V_ ** 2 / (s * L), eta * V_ / s
    # where m is below 1e-20 the quasi-dynamic DAE (m = 0) is the reference: the inertia changes
    # the slow pair by O(m ω̂/(a + h)) relative, far below the tolerance
    kap, w, lam = _dimensionless_hopf(m if m > 1e-20 else 0.0, h, a, b)
    assert res.Lambda == pytest.approx(lam * V_ / L ** 3, rel=1e-6)


def test_block_without_damping_term_rejects_eta():
    from landau.errors import InputError

    with pytest.raises(InputError, match="eta"):
        SpringBlock("dieterich").resolve({"eta": 1.0})


@pytest.mark.parametrize("M", [1e-8, 1.0])
def test_general_engine_on_the_dimensional_bp1_cell(M):
    """The general engine on the cell in SI units, where the fast eigenvalue −η/M (4.6e14 and
    4.6e6 1/s) sits beside the slow pair at 8.8e-8 rad/s: float64 eigenvalues of J/M resolve the
    pair only to about 1e-16·|J/M| ≈ 0.05 1/s, so the scan used to see no crossing
    ("no Hopf crossing of k in [1.5625e+07, 6.25e+07]").  Against the dimensionless route."""
    from landau.systems.system import SpringBlock

    a, b, L, s, eta = BP1["a"], BP1["b"], BP1["L"], BP1["sigma"], BP1["eta"]
    block = SpringBlock.for_params(get_law("dieterich"), {**BP1, "M": M})
    prm = {**block.resolve({**BP1, "M": M}), "V": V}
    kc = (s * (b - a) - eta * V) / L * (1 + M * V ** 2 / (L * (s * a + eta * V)))
    res = hopf_normal_form(block.system, prm, (0.5 * kc, 2.0 * kc))
    kap, w, lam = _dimensionless_hopf(M * V ** 2 / (s * L), eta * V / s, a, b)
    assert res.p_c == pytest.approx(kap * s / L, rel=1e-9)
    assert res.omega_c == pytest.approx(w * V / L, rel=1e-9)
    assert res.Lambda == pytest.approx(lam * V / L ** 3, rel=1e-6)
    assert res.criticality == "supercritical"
