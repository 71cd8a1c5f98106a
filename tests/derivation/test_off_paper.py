"""Scenes away from the papers' parameter sets, each against an independent computation.

A locator's search interval must come from the model, not from the published number: these
parameter sets move the answers well outside the published windows.
"""

import mpmath
import numpy as np
import pytest
import sympy as sp
from scipy.integrate import solve_ivp
from scipy.optimize import brentq, newton

from landau.scenes import run_scene

# --- Skurativskyi et al. (2019) -------------------------------------------------------------------

@pytest.mark.parametrize("xI", [-0.003, -0.0015])
def test_skurativskyi_linear_grazing_off_paper(xI):
    """Sec. 5 linearised estimate at another obstacle position: the linearised oscillator
    m ẍ + c ẋ + k_lin (x − X₀) = m₀e ω² sin ωt (k_lin = k + n₁ k_I (X₀ − x_I)^{n₁−1}), integrated with
    scipy, at the returned ω: the trough of its periodic state must touch x_I (to 1e-6 of X₀ − x_I).

    The periodic state is the fixed point of the period map y ↦ Φy + b, which is affine for a linear
    oscillator: b and Φ from scipy's DOP853 over one period from 0, e₁ and e₂, then (I − Φ)y* = b and
    one more period from y* for the trough (instead of damping the transient out over 40 decay times,
    ~300 periods in Python steps, for the same state)."""
    doc = run_scene("skurativskyi2019/grazing-linear", {"xI": xI})
    om, X0 = doc["value"], doc["X0"]
    p = doc["params"]
    k_lin = p["k"] + p["n1"] * p["kI"] * (X0 - xI) ** (p["n1"] - 1)
    m, c, F = p["m"], p["c"], p["m0e"] * om ** 2
    T = 2 * np.pi / om

    def period(y0, dense=False):
        return solve_ivp(lambda t, y: [y[1], (F * np.sin(om * t) - c * y[1] - k_lin * y[0]) / m],
                         (0, T), y0, method="DOP853", rtol=1e-12, atol=1e-16, dense_output=dense)

    b = period([0.0, 0.0]).y[:, -1]
    Phi = np.column_stack([period(e).y[:, -1] - b for e in ([1.0, 0.0], [0.0, 1.0])])
    # (I − Φ) y* = b: the one initial state that a period maps to itself
    y_star = np.linalg.solve(np.eye(2) - Phi, b)
    sol = period(y_star, dense=True)
    trough = X0 + sol.sol(np.linspace(0, T, 20001))[0].min()
    assert trough == pytest.approx(xI, abs=1e-6 * (X0 - xI))


def test_skurativskyi_static_equilibrium_stiff_contact():
    """X₀ for a much softer and a much stiffer contact (k_I = 1e7 and 1e9 N/m^1.5) against a 50-digit
    mpmath root of k X + k_I (X − x_I)^{n₁} = 0."""
    for kI in (1e7, 1e9):
        doc = run_scene("skurativskyi2019/static-equilibrium", {"kI": kI})
        p = doc["params"]
        with mpmath.workdps(50):
            f = lambda X, p=p, kI=kI: p["k"] * X + mpmath.mpf(kI) * (X - p["xI"]) ** mpmath.mpf(p["n1"])  # noqa: E731
            ref = mpmath.findroot(f, (mpmath.mpf(p["xI"]) * (1 - mpmath.mpf(10) ** -12), mpmath.mpf(0)),
                                  solver="anderson")
        assert doc["value"] == pytest.approx(float(ref), rel=1e-12)


# --- Lancioni, Lenci & Galvanetto -------------------------------------------------------------------

@pytest.mark.parametrize("params", [{"k_phi": 50.0}, {"m1": 0.2, "c_y": 5.0}])
def test_lancioni_hopf_off_paper(params):
    """Hopf point of the slip mode for other parameter sets: no μ window is given, the scene finds it.
    Independent: the slip field (φ̇ = ω, ω̇ = F) from sympy, its Jacobian by central finite differences
    at the numerically solved equilibrium, and Brent's method on the largest real part (≤ 1e-7)."""
    from landau.verify.lancioni.slip import PARAM_NAMES, resolve, slip_accelerations

    doc = run_scene("lancioni/hopf", params)
    p = resolve(params)
    F, _ = slip_accelerations(1)
    phi, om, mu = sp.Symbol("phi", real=True), sp.Symbol("omega", real=True), sp.Symbol("mu", real=True)
    names = [sp.Symbol(n, real=True) for n in PARAM_NAMES]
    f = sp.lambdify([phi, om, mu, *names], F)
    vals = [p[n] for n in PARAM_NAMES]

    def growth(m_):
        pe = newton(lambda x: f(x, 0.0, m_, *vals), p["phi0"], tol=1e-14, maxiter=100)
        h = 1e-6
        J = np.array([[0.0, 1.0],
                      [(f(pe + h, 0, m_, *vals) - f(pe - h, 0, m_, *vals)) / (2 * h),
                       (f(pe, h, m_, *vals) - f(pe, -h, m_, *vals)) / (2 * h)]])
        return float(np.max(np.linalg.eigvals(J).real))

    mu_c = doc["value"]
    ref = brentq(growth, mu_c - 0.02, mu_c + 0.02, xtol=1e-12)
    assert mu_c == pytest.approx(ref, abs=1e-7)
    assert doc["criticality"] in ("supercritical", "subcritical")


# --- Galvanetto (2004) -----------------------------------------------------------------------------

@pytest.mark.parametrize("V,gamma,delta", [(0.3, 2.0, 0.1), (1.0, 5.0, 0.0)])
def test_galvanetto_damped_block_hopf_off_paper(V, gamma, delta):
    """Hopf point c₁ of the damped one-block at other (V, γ, δ): the general engine on the smooth slip
    field against the closed form c₁ = F_k'(−V) = γ(1 − δ)/(1 + γV)² (to 1e-10)."""
    doc = run_scene("galvanetto2004/one-block-c1", {"V": V, "gamma": gamma, "delta": delta})
    assert doc["value"] == pytest.approx(gamma * (1 - delta) / (1 + gamma * V) ** 2, rel=1e-10)


# --- Putelat, Dawes & Willis (2010) ----------------------------------------------------------------

@pytest.mark.parametrize("c", [5e-4, 2e-3])
def test_putelat_modified_dieterich_vm_off_paper(c):
    """Minimum of μ_ss of law (39) at other c, located numerically, against the closed form eq. (41)
    V_m = (b/a − 1)V_*/c (to 1e-8)."""
    doc = run_scene("putelat2010/modified-dieterich-V_m", {"c": c})
    p = doc["params"]
    assert doc["value"] == pytest.approx((p["b"] / p["a"] - 1) * p["V_s"] / c, rel=1e-8)


@pytest.mark.parametrize("scene,sign", [("putelat2010/spinodal-V_m", 1), ("putelat2010/spinodal-V_M", -1)])
@pytest.mark.parametrize("c", [3e-4, 2e-3])
def test_putelat_spinodal_vm_off_paper(c, scene, sign):
    """Local minimum V_m (and maximum V_M) of μ_ss of the spinodal law (37)–(38) at other c against a
    40-digit root of dμ_ss/dV (mpmath differentiation of μ_ss(V) = a asinh(V (c + φ_ss(1 + V_* t_ss/L))^{b/a}
    e^{a_v/a}/(2V_*)), φ_ss = 1/(1 + V t_ss/L)), to 1e-8; the second derivative's sign tells which."""
    doc = run_scene(scene, {"c": c})
    p = {k: mpmath.mpf(v) for k, v in doc["params"].items()}
    with mpmath.workdps(40):
        def mu_ss(V):
            phi = 1 / (1 + V * p["t_ss"] / p["L"])
            return p["a"] * mpmath.asinh(V * (p["c"] + phi * (1 + p["V_s"] * p["t_ss"] / p["L"])) ** (p["b"] / p["a"])
                                         * mpmath.exp(p["a_v"] / p["a"]) / (2 * p["V_s"]))
        ref = mpmath.findroot(lambda lv: mpmath.diff(lambda x: mu_ss(mpmath.exp(x)), lv), mpmath.log(doc["value"]))
        curvature = mpmath.diff(lambda x: mu_ss(mpmath.exp(x)), ref, 2)
    assert doc["value"] == pytest.approx(float(mpmath.exp(ref)), rel=1e-8)
    assert sign * curvature > 0
