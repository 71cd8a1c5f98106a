"""The SEAS BP1 cell with pore pressure, analysed at the plate rate V_p = 1e-9 m/s.

SEAS BP1 (Erickson et al. 2020, Seismol. Res. Lett. 91(2A), 874–890): ρ = 2670 kg/m³, c_s = 3.464 km/s,
σ̄ = 50 MPa, a = 0.010, b = 0.015, L = 8 mm, f₀ = 0.6 at V₀ = 1e-6 m/s, the aging law and radiation damping
η = ρc_s/2 (quasi-dynamic: M = 0), per unit area.  Here the total normal stress is σ = 80 MPa with the
ambient pore pressure p_∞ = 30 MPa (σ̄ = 50 MPa, BP1's), and dilatancy (Segall & Rice 1995) with
ε = 2e-4, β = 1e-9 /Pa, t_f = 1e6 s (L/V_p = 8e6 s: neither drained nor undrained).

Independent computation: eliminating u from the algebraic force balance, the linearised cell in
(X, s = δθ/θ_ss, P = p − p_∞) is, with D = σ̄a/V + η,

    u = (−kX − σ̄ b s + μ_ss P)/D,   Ẋ = u,   ṡ = −(V/L)s − u/L,   Ṗ = −P/t_f + (ε/β) ṡ,

whose eigenvalues give k_c by bisection; the limits t_f → 0 and ∞ are the quasi-dynamic closed forms
k_c = [σ̄(b − a) − ηV]/L and [σ̄(b − a) − μ_ss ε/β − ηV]/L.  Λ against the general engine's route
(:func:`landau.derivation.springblock_routes.hopf_point`, numeric jets and Fredholm solves) at an inertia
M = 1e3 kg/m² whose effect on k_c is MV²/(L D) ≈ 5e-20.  The quasi-dynamic cell of ``landau simulate`` (M = 0)
carries the pore pressure: its linear crossing at k_c, and (slow) a simulation confirming the amplitude.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from landau.derivation.springblock_routes import hopf_point
from landau.laws import get_law
from landau.systems.system import SpringBlock
from landau.verify.springblock.checks import predict

RHO, CS = 2670.0, 3464.0
V = 1e-9
A_, B_, L_, F0, V0 = 0.010, 0.015, 8e-3, 0.6, 1e-6
SIG_EFF = 50e6
ETA = RHO * CS / 2
CELL = dict(a=A_, b=B_, L=L_, a_v=F0, V_s=V0, sigma=80e6, p_inf=30e6, M=0.0, eta=ETA,
            eps_dil=2e-4, beta=1e-9, t_drain=1e6)
MU_SS = F0 + (A_ - B_) * math.log(V / V0)


def _jacobian(k, tf):
    D = SIG_EFF * A_ / V + ETA
    ux = np.array([-k, -SIG_EFF * B_, MU_SS]) / D
    s_row = -(V / L_) * np.array([0.0, 1.0, 0.0]) - ux / L_
    p_row = -np.array([0.0, 0.0, 1.0]) / tf + CELL["eps_dil"] / CELL["beta"] * s_row
    return np.array([ux, s_row, p_row])


def _kc_bisected(tf):
    def growth(k):
        return np.max(np.linalg.eigvals(_jacobian(k, tf)).real)

    lo, hi = 1.0, 1e12
    assert growth(lo) > 0 > growth(hi)
    for _ in range(100):
        mid = math.sqrt(lo * hi)
        lo, hi = (mid, hi) if growth(mid) > 0 else (lo, mid)
    lam = np.linalg.eigvals(_jacobian(lo, tf))
    return lo, float(np.max(np.abs(lam.imag)))


def test_bp1_cell_with_pore_pressure_at_the_plate_rate():
    r = predict(get_law("dieterich"), V, CELL)
    kc, w = _kc_bisected(CELL["t_drain"])
    assert r.p_c == pytest.approx(kc, rel=1e-9)
    assert r.omega_c == pytest.approx(w, rel=1e-7)
    drained = (SIG_EFF * (B_ - A_) - ETA * V) / L_
    undrained = (SIG_EFF * (B_ - A_) - MU_SS * CELL["eps_dil"] / CELL["beta"] - ETA * V) / L_
    assert undrained < r.p_c < drained
    # the limits of the same cell
    assert predict(get_law("dieterich"), V, {**CELL, "t_drain": 1e-3}).p_c == pytest.approx(drained, rel=1e-9)
    assert predict(get_law("dieterich"), V, {**CELL, "t_drain": 1e17}).p_c == pytest.approx(undrained, rel=1e-8)
    # Λ and the criticality by the general engine (negligible inertia)
    heavy = {**CELL, "M": 1e3}
    block = SpringBlock.for_params("dieterich", heavy)
    g = hopf_point(block, V, block.resolve(heavy))
    assert g.p_c == pytest.approx(r.p_c, rel=1e-9)
    assert r.Lambda == pytest.approx(g.Lambda, rel=1e-6)
    assert r.criticality == g.criticality == "supercritical"


def test_the_quasidynamic_cell_carries_the_pore_pressure():
    """The simulated cell (M = 0, landau simulate) loses stability at the analysed k_c with frequency ω_c:
    the largest eigenvalue of its reduced Jacobian crosses the imaginary axis there."""
    from landau.verify.springblock.quasidynamic import QuasiDynamicCell

    kc, w = _kc_bisected(CELL["t_drain"])
    growth = []
    for f in (0.99, 1.0, 1.01):
        cell = QuasiDynamicCell.build(get_law("dieterich"), V, kc * f, CELL)
        lam, _ = cell.critical_mode()
        growth.append(lam.real)
        if f == 1.0:
            assert cell.n == 3                                   # ξ, ψ, the pore pressure
            assert lam.imag / cell.time_unit == pytest.approx(w, rel=1e-9)
    assert growth[0] > 1e-4 and abs(growth[1]) < 1e-12 and growth[2] < -1e-4


@pytest.mark.slow
def test_the_bp1_cell_with_pore_pressure_confirmed_by_simulation():
    """The quasi-dynamic cell's simulated cycle confirms the supercritical onset and its amplitude at two ε²
    (the check's contract; the fast sibling above checks the cell's linear crossing at the same k_c)."""
    import landau

    r = landau.check(get_law("dieterich"), V, 1e-3, CELL).as_dict()
    assert r["criticality_predicted"] == "supercritical"
    assert r["verdict"] == "agrees", r
    assert r["eps2_measured"] == [1e-3, 2.5e-4]
    assert abs(r["rel_error"]) < 1e-2          # the contract's extrapolation bound (measured -0.54 %)
