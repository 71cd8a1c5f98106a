"""Variable normal stress (Linker & Dieterich 1992): σ = σ₀ + γ_LD k(Vt − x), state response α_LD.

Independent routes: the closed form k_c(γ) = k_c⁰(σ_ss)/(1 − γμ_ss) with σ_ss = (σ₀ + γηV)/(1 − γμ_ss)
(k enters the Jacobian as −k(1 − γμ_ss); every other entry sees σ_ss), and the eigenvalues of the
Jacobian of the equations written by hand here (finite differences).
"""

from __future__ import annotations

import numpy as np
import pytest

from landau.errors import NoSteadySlidingError
from landau.laws import get_law
from landau.verify.springblock.checks import predict

LAW = get_law("dieterich")
OFF = dict(a=0.02, b=0.031, L=2e-5, sigma=30.0, V_s=1e-6, a_v=0.5, M=2.0)


def mu_ss(p, V):
    return p["a_v"] + (p["a"] - p["b"]) * np.log(V / p["V_s"])


@pytest.mark.parametrize("a,b", [(0.02, 0.031), (0.04, 0.031)])   # velocity weakening and strengthening
def test_no_steady_sliding_when_gamma_mu_reaches_one(a, b):
    """Dieterich & Linker (1992): no steady sliding for γ_LD μ_ss ≥ 1, whatever the sign of b − a."""
    V = 1e-4
    p = {**OFF, "a": a, "b": b}
    g = 1.0 / mu_ss(p, V)
    for gamma in (g * 1.0000001, 2 * g):
        with pytest.raises(NoSteadySlidingError, match="gamma_ld"):
            predict(LAW, V, {**p, "gamma_ld": gamma})
    if b > a:
        predict(LAW, V, {**p, "gamma_ld": 0.99 * g})   # just below: a Hopf point


def test_no_steady_sliding_exit_code_2():
    import contextlib
    import io

    from landau.cli.app import main

    err = io.StringIO()
    with contextlib.redirect_stderr(err), contextlib.redirect_stdout(io.StringIO()):
        rc = main(["hopf", "spring-block", "dieterich", "--V", "1e-4", "--param", "gamma_ld=5"])
    assert rc == 2
    assert "no steady sliding" in err.getvalue()


@pytest.mark.parametrize("gamma,eta", [(0.8, 0.0), (-1.5, 0.0), (0.8, 30.0)])
def test_kc_with_gamma_closed_form(gamma, eta):
    V = 2e-4
    p = {**OFF, "gamma_ld": gamma, "eta": eta}
    res = predict(LAW, V, p)
    m0 = mu_ss(p, V)
    s = (p["sigma"] + gamma * eta * V) / (1 - gamma * m0)
    a, b, L, M = p["a"], p["b"], p["L"], p["M"]
    kc0 = (s * (b - a) - eta * V) / L * (1 + M * V ** 2 / (L * (s * a + eta * V)))
    assert res.kc == pytest.approx(kc0 / (1 - gamma * m0), rel=1e-12)
    assert res["gamma_ld"] == gamma


def _hand_jacobian(p, V, k):
    """Jacobian (finite differences) of M u̇ = k(Vt−x) − σμ − ηv, σ = σ₀ + γk(Vt−x),
    θ̇ = 1 − vθ/L − αθσ̇/(bσ), in (X, u, θ), written here."""
    a, b, L, s0, M, g, al, Vs, av = (p[n] for n in ("a", "b", "L", "sigma", "M", "gamma_ld", "alpha_ld",
                                                     "V_s", "a_v"))
    th0 = L / V
    m0 = mu_ss(p, V)
    F0 = s0 * m0 / (1 - g * m0)              # spring force at steady sliding (η = 0)

    def f(y):
        X, u, th = y
        v = V + u
        F = F0 - k * X
        sig = s0 + g * F
        mu = av + a * np.log(v / Vs) + b * np.log(Vs * th / L)
        sdot = -g * k * u
        return np.array([u, (F - sig * mu) / M, 1 - v * th / L - al * th * sdot / (b * sig)])

    y0 = np.array([0.0, 0.0, th0])
    h = np.array([1e-9, 1e-9 * V, 1e-9 * th0])
    return np.column_stack([(f(y0 + h[j] * e) - f(y0 - h[j] * e)) / (2 * h[j]) for j, e in enumerate(np.eye(3))])


def test_alpha_hopf_point_against_eigenvalues():
    V = 2e-4
    p = {**OFF, "gamma_ld": 0.6, "alpha_ld": 0.25, "eta": 0.0}
    res = predict(LAW, V, p)
    lam = np.linalg.eigvals(_hand_jacobian(p, V, res.kc))
    i = np.argmax(lam.real)
    assert abs(lam[i].real) < 1e-5 * abs(lam[i].imag)
    assert abs(lam[i].imag) == pytest.approx(res.omega_c, rel=1e-5)
    # just below k_c unstable, just above stable
    assert np.max(np.linalg.eigvals(_hand_jacobian(p, V, 0.99 * res.kc)).real) > 0
    assert np.max(np.linalg.eigvals(_hand_jacobian(p, V, 1.01 * res.kc)).real) < 0


def test_simulation_model_with_every_term_against_hand_written_field():
    """The compiled field of the simulator (scaled variables ξ = X/ℓ, w = ln(v/V), ψ = ln(θ/θ₀),
    τ = tV/ℓ) with η, γ_LD and α_LD against the equations written here; at k = k_c its linearisation
    has the critical pair on the imaginary axis."""
    from landau.verify.springblock.model import SpringBlockModel

    V = 2e-4
    p = {**OFF, "gamma_ld": 0.6, "alpha_ld": 0.25, "eta": 7.0}
    res = predict(LAW, V, p)
    model = SpringBlockModel.build(LAW, V, res.kc, p)
    a, b, L, s0, M, g, al, eta, Vs, av = (p[n] for n in ("a", "b", "L", "sigma", "M", "gamma_ld", "alpha_ld",
                                                          "eta", "V_s", "a_v"))
    k, ell, th0 = res.kc, model.ell, L / V
    m0 = mu_ss(p, V)
    s_ss = (s0 + g * eta * V) / (1 - g * m0)
    F0 = s_ss * m0 + eta * V

    def f_hand(y):
        xi, w, psi = y
        X, v, th = xi * ell, V * np.exp(w), th0 * np.exp(psi)
        F = F0 - k * X
        sig = s0 + g * F
        mu = av + a * np.log(v / Vs) + b * np.log(Vs * th / L)
        udot = (F - sig * mu - eta * v) / M
        thdot = 1 - v * th / L - al * th * (-g * k * (v - V)) / (b * sig)
        return np.array([v / V - 1, ell / V * udot / v, ell / V * thdot / th])

    rng = np.random.default_rng(3)
    for _ in range(3):
        y = rng.normal(scale=0.05, size=3)
        assert model.f(y) == pytest.approx(f_hand(y), rel=1e-9, abs=1e-12)
    lam = np.linalg.eigvals(model.J(np.zeros(3)))
    i = np.argmax(lam.real)
    assert abs(lam[i].real) < 1e-6 * abs(lam[i].imag)
    assert abs(lam[i].imag) * V / ell == pytest.approx(res.omega_c, rel=1e-6)


def test_check_with_every_term():
    """η, γ_LD < 0 (the load decreases with the spring force) and α_LD together: the simulated cycle
    agrees with the general engine's prediction."""
    import landau

    r = landau.check("dieterich", 1e-4, 1e-3, {"eta": 100.0, "gamma_ld": -1.0, "alpha_ld": 0.3})
    assert r.agrees and r.prediction.criticality == "supercritical"


def test_latex_closed_form_with_gamma(tmp_path):
    import contextlib
    import io

    from landau.cli.app import main

    tex = tmp_path / "kc.tex"
    with contextlib.redirect_stdout(io.StringIO()):
        rc = main(["derive", "dieterich", "--V", "1e-4", "--param", "gamma_ld=0.5", "--quantities", "kc",
                   "--latex", str(tex)])
    assert rc == 0
    assert r"\gamma_{\mathrm{ld}}" in tex.read_text()
