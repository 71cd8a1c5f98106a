"""Load-point histories with the optional spring–block terms: radiation damping η and a normal load
that follows the spring (γ_LD, with the Linker–Dieterich state response α_LD).

* a velocity step V₁ → V₂ with η and γ_LD: friction settles at μ_ss(V₂) (Dieterich's law:
  μ_ss = a_v + (a − b) ln(V/V_*)) and the steady force balance holds,
  F = σμ_ss + ηV with σ = σ₀ + γ_LD F, i.e. F = (σ₀μ_ss + ηV)/(1 − γ_LD μ_ss);
* the transient after the step against an independent route: the compiled spring–block
  (:mod:`landau.verify.springblock.model`, the terms built into its generated kernel) driven at V₂
  from steady sliding at V₁, in its own variables X = x − x₀(t);
* no steady sliding for γ_LD μ_ss ≥ 1: a named error (exit 2 on the command line).
"""

from __future__ import annotations

import csv
import math

import pytest
from history_support import assert_transient_matches

from landau.cli import main
from landau.errors import NoSteadySlidingError
from landau.laws import get_law
from landau.verify.springblock.history import simulate_history

LAW = get_law("dieterich")
P = LAW.defaults()
SIGMA0 = 1.2 * 9.81
K = 4e5
TERMS = {"eta": 100.0, "gamma_ld": 0.2}


def _mu_ss(V):
    return P["a_v"] + (P["a"] - P["b"]) * math.log(V / P["V_s"])


def _force_ss(V, eta=TERMS["eta"], gam=TERMS["gamma_ld"]):
    return (SIGMA0 * _mu_ss(V) + eta * V) / (1 - gam * _mu_ss(V))


def test_velocity_step_with_damping_and_normal_load_settles_at_the_steady_force_balance():
    V1, V2 = 1e-5, 1e-4
    sim = simulate_history(LAW, f"{V1}@0,{V2}@10", K, TERMS, t_end=30.0, rtol=1e-10)
    names = list(sim.state_names)
    assert names == ["V", "v", "mu", "phi", "F", "sigma", "x_lp", "slip"]
    start, end = sim.y[:, 0], sim.y_final
    col = {n: i for i, n in enumerate(names)}
    assert start[col["mu"]] == pytest.approx(_mu_ss(V1), rel=1e-12)
    assert start[col["F"]] == pytest.approx(_force_ss(V1), rel=1e-12)
    assert end[col["v"]] == pytest.approx(V2, rel=1e-6)
    assert end[col["mu"]] == pytest.approx(_mu_ss(V2), rel=1e-7)
    assert end[col["mu"]] - start[col["mu"]] == pytest.approx((P["a"] - P["b"]) * math.log(V2 / V1), rel=1e-5)
    # the steady force balance with the damping force and the normal load that follows the spring
    assert end[col["F"]] == pytest.approx(end[col["sigma"]] * end[col["mu"]] + TERMS["eta"] * V2, rel=1e-7)
    assert end[col["F"]] == pytest.approx(_force_ss(V2), rel=1e-7)
    assert end[col["sigma"]] == pytest.approx(SIGMA0 + TERMS["gamma_ld"] * _force_ss(V2), rel=1e-7)
    # the damping force is felt: without it the steady spring force is smaller by eta V / (1 - gamma mu_ss)
    assert _force_ss(V2) - _force_ss(V2, eta=0.0) == pytest.approx(
        TERMS["eta"] * V2 / (1 - TERMS["gamma_ld"] * _mu_ss(V2)), rel=1e-12)


@pytest.mark.parametrize("terms", [{"eta": 100.0}, {"eta": 100.0, "gamma_ld": 0.2, "alpha_ld": 0.3}])
def test_transient_after_the_step_against_the_compiled_model(terms):
    from landau.verify.springblock.model import SpringBlockModel
    from landau.verify.springblock.simulate import integrate

    V1, V2, dt = 1e-5, 1e-4, 0.02
    sim = simulate_history(LAW, f"{V1}@0,{V2}@1", K, terms, t_end=1.0 + dt, rtol=1e-11)
    model = SpringBlockModel.build(LAW, V2, K, terms)
    eta, gam = terms.get("eta", 0.0), terms.get("gamma_ld", 0.0)
    # X = x - x0(t) with x0 = x_lp - F_ss(V2)/k: the spring stretch F/k = F_ss(V2)/k - X
    X0 = (_force_ss(V2, eta, gam) - _force_ss(V1, eta, gam)) / K
    z0 = model.from_physical(X0, V1, [P["L"] / V1])
    run = integrate(model, z0, (0.0, dt), rtol=1e-11)
    assert_transient_matches(sim, model, run, _force_ss(V2, eta, gam), K, V1, f_rel=1e-7)


def test_alpha_ld_moves_the_transient_not_the_steady_state():
    base = {"eta": 100.0, "gamma_ld": 0.2}
    a = simulate_history(LAW, "1e-5@0,1e-4@1", K, base, t_end=1.02, rtol=1e-10)
    b = simulate_history(LAW, "1e-5@0,1e-4@1", K, {**base, "alpha_ld": 0.3}, t_end=1.02, rtol=1e-10)
    assert abs(b.y_final[3] / a.y_final[3] - 1) > 1e-3     # the state responds to the changing normal load
    c = simulate_history(LAW, "1e-5@0,1e-4@1", K, {**base, "alpha_ld": 0.3}, t_end=20.0, rtol=1e-10)
    assert c.y_final[2] == pytest.approx(_mu_ss(1e-4), rel=1e-7)


def test_no_steady_sliding_is_a_named_error(capsys):
    # gamma_ld mu_ss >= 1 at the second velocity (mu_ss(1e-4) = 0.3045): gamma = 3.4
    with pytest.raises(NoSteadySlidingError, match="gamma_ld"):
        simulate_history(LAW, "1e-5@0,1e-4@1", K, {"gamma_ld": 3.4})
    assert main(["simulate", "spring-block", "dieterich", "--V-history", "1e-5@0,1e-4@1", "--k", "4e5",
                 "--param", "gamma_ld=3.4"]) == 2
    assert "gamma_ld" in capsys.readouterr().err


def test_cli_history_with_damping_writes_force_and_normal_load(tmp_path):
    out = tmp_path / "h.csv"
    assert main(["simulate", "spring-block", "dieterich", "--V-history", "1e-5@0,1e-4@5", "--t-end", "10",
                 "--param", "eta=100", "--param", "gamma_ld=0.2", "--out", str(out)]) == 0
    with open(out) as fh:
        head = next(csv.reader(fh))
    assert head == ["t [s]", "V [m/s]", "v [m/s]", "mu [1]", "phi [s]", "F [N]", "sigma [N]", "x_lp [m]", "slip [m]"]
