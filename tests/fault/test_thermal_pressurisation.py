"""Thermal pressurisation (and dilatancy) on the spring–block against an independent computation.

The field is written out here by hand in numpy/sympy, independently of the term declarations
(:mod:`landau.systems.fault_terms`): the aging law μ = a_v + a ln(v/V*) + b ln(V*θ/L),
dθ/dt = 1 − vθ/L (Putelat et al. 2010, eqs 26 + 28), the effective normal stress σ̄ = σ − p, the
lumped slip-zone temperature rise and pore pressure (Rice 2006; Segall & Rice 2006, reduced to one
relaxation time each), with y = (X, u, θ, P = p − p_∞, T = T_rise − T_ss)::

    M u̇ = −kX + σ̄_ss μ_ss − (σ̄_ss − P) μ(V + u, θ)
    θ̇  = 1 − (V + u)θ/L
    Ṫ  = (σ̄_ss − P) μ (V + u)/(ρc·2w) − (T + T_ss)/t_th,    T_ss = σ̄_ss μ_ss V t_th/(ρc·2w)
    Ṗ  = −P/t_f + (ε/β) θ̇/θ + Λ Ṫ

k_c: bisection on the sign of the largest real part of the eigenvalues of the assembled Jacobian;
l₁: Kuznetsov (2004, §3.5, eq. 3.20) with the derivatives of this field, in the same coordinates,
⟨q, q⟩ = 1; Λ from it through c₁ = (Λ + iχ)/(2‖q‖²) with q slip-normalised.
"""

from __future__ import annotations

import numpy as np
import pytest
import sympy as sp

from landau.laws import get_law
from landau.verify.springblock.checks import predict

LAW = get_law("dieterich")
V = 1e-6
BASE = dict(sigma=20.0, p_inf=5.0, beta=1e-3, t_drain=0.5, lambda_tp=1e5, rho_c=30.0, w_sz=1e-3, t_th=0.2)
CASES = {"thermal only": {**BASE, "eps_dil": 0.0}, "thermal and dilatancy": {**BASE, "eps_dil": 1e-4}}


def _field(p):
    """The hand-written field g(y; k) = E⁻¹ f (sympy), its state symbols and k."""
    X, u, th, P, T, k = sp.symbols("X u theta P T k", real=True)
    a_v, a, b, L, Vs, M = (sp.Float(p[n]) for n in ("a_v", "a", "b", "L", "V_s", "M"))
    sig = sp.Float(p["sigma"] - p["p_inf"])
    mu_ss = a_v + (a - b) * sp.log(sp.Float(V) / Vs)
    v = V + u
    mu = a_v + a * sp.log(v / Vs) + b * sp.log(Vs * th / L)
    rc2w = sp.Float(p["rho_c"] * 2 * p["w_sz"])
    T_ss = sig * mu_ss * V * p["t_th"] / rc2w
    th_dot = 1 - v * th / L
    T_dot = (sig - P) * mu * v / rc2w - (T + T_ss) / p["t_th"]
    P_dot = -P / p["t_drain"] + p["eps_dil"] / p["beta"] * th_dot / th + p["lambda_tp"] * T_dot
    g = [u, (-k * X + sig * mu_ss - (sig - P) * mu) / M, th_dot, P_dot, T_dot]
    return sp.Matrix(g), (X, u, th, P, T), k


def _independent(p):
    """(k_c, ω_c, l₁, Λ) of the hand-written field."""
    g, y, k = _field(p)
    y0 = {y[0]: 0, y[1]: 0, y[2]: p["L"] / V, y[3]: 0, y[4]: 0}
    Jk = sp.lambdify(k, g.jacobian(y).subs(y0), "numpy")

    def growth(kk):
        return np.max(np.linalg.eigvals(np.array(Jk(kk), dtype=float)).real)

    lo, hi = 1.0, 1e9          # unstable below k_c, stable above (checked)
    assert growth(lo) > 0 > growth(hi)
    for _ in range(80):
        mid = np.sqrt(lo * hi)
        lo, hi = (mid, hi) if growth(mid) > 0 else (lo, mid)
    kc = np.sqrt(lo * hi)
    gk = g.subs(k, kc)
    A = np.array(Jk(kc), dtype=float)
    lam, vec = np.linalg.eig(A)
    i = int(np.argmin(np.abs(lam.real) + 1e3 * (lam.imag <= 0)))
    w = lam[i].imag
    q = vec[:, i] / np.linalg.norm(vec[:, i])
    lamT, vecT = np.linalg.eig(A.T)
    j = int(np.argmin(np.abs(lamT - (-1j * w))))
    pv = vecT[:, j]
    pv = pv / np.conj(np.vdot(pv, q))                # ⟨p, q⟩ = p̄ᵀq = 1
    at = [y0[s] for s in y]
    D2 = sp.derive_by_array(sp.derive_by_array(list(gk), y), y)          # [j, k, i]
    D3 = sp.derive_by_array(D2, y)                                       # [l, j, k, i]
    D2n = np.array(sp.lambdify(y, D2, "numpy")(*at), dtype=float)
    D3n = np.array(sp.lambdify(y, D3, "numpy")(*at), dtype=float)
    Hn = [D2n[:, :, i] for i in range(5)]
    D3n = [D3n[:, :, :, i] for i in range(5)]

    def B(x, z):
        return np.array([x @ h @ z for h in Hn])

    def C(x, z, s):
        return np.array([np.einsum("jkl,j,k,l->", d, x, z, s) for d in D3n])

    # A h₁₁ = B(q, q̄): the (0, 0) harmonic of the quadratic terms
    h11 = np.linalg.solve(A, B(q, np.conj(q)))
    # (2iω − A) h₂₀ = B(q, q): the second harmonic
    h20 = np.linalg.solve(2j * w * np.eye(5) - A, B(q, q))
    c = np.vdot(pv, C(q, q, np.conj(q))) - 2 * np.vdot(pv, B(q, h11)) + np.vdot(pv, B(np.conj(q), h20))
    l1 = c.real / (2 * w)
    q_slip = q / q[0]
    Lambda = 2 * np.vdot(q_slip, q_slip).real * l1 * w   # c₁ = (Λ + iχ)/(2‖q‖²), Re c₁ = ω l₁
    return kc, w, l1, Lambda


@pytest.mark.parametrize("case", list(CASES))
def test_kc_and_lambda_against_the_assembled_jacobian_and_kuznetsov(case):
    params = CASES[case]
    r = predict(LAW, V, params)
    p = {**{q.name: q.default for q in LAW.parameters}, "M": 1.2, **params}
    kc, w, l1, Lam = _independent(p)
    # the bisection resolves k_c to 1e-12 relative; the engine's closed route is exact to rounding
    assert r.p_c == pytest.approx(kc, rel=1e-9)
    assert r.omega_c == pytest.approx(w, rel=1e-7)
    # Kuznetsov's l₁ from derivatives at k_c: the bisected k_c's error (1e-12) and the eigenvectors' rounding
    # (measured 2.5e-13)
    assert r.l1 == pytest.approx(l1, rel=1e-9)
    assert r.Lambda == pytest.approx(Lam, rel=1e-9)
    assert r.criticality == ("supercritical" if Lam < 0 else "subcritical")


def test_thermal_pressurisation_moves_kc():
    """The term acts: Λ_TP = 0 (with the same dilatancy) gives another k_c (the test above is not vacuous)."""
    off = predict(LAW, V, {**CASES["thermal and dilatancy"], "lambda_tp": 0.0}).p_c
    on = predict(LAW, V, CASES["thermal and dilatancy"]).p_c
    assert abs(on / off - 1) > 0.05
