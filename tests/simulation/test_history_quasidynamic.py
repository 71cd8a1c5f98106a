"""Load-point histories at M = 0 with radiation damping η > 0: the quasi-dynamic force balance
k u = σ μ(v, φ) + η v (u = x_lp − x the spring's stretch) fixes the slip rate at every instant.

* a velocity step V₁ → V₂: friction settles at μ_ss(V₂) (Dieterich's law: μ_ss = a_v + (a − b) ln(V/V_*),
  so μ_ss(V₂) − μ_ss(V₁) = (a − b) ln(V₂/V₁)) and the steady force balance F = σμ_ss + ηV holds;
* the transient after the step against an independent route: the compiled spring–block with a tiny
  mass M (:mod:`landau.verify.springblock.model`), driven at V₂ from steady sliding at V₁.  With η the
  inertia enters through the fast time M/η; against the slow time L/V its relative effect is
  MV/(ηL) = 1e-11 here, far below the integration tolerance;
* the command line writes the series with the spring force; M = 0 without η is a named error.
"""

from __future__ import annotations

import csv
import math

import pytest
from history_support import assert_transient_matches

from landau.cli import main
from landau.errors import InputError
from landau.laws import get_law
from landau.verify.springblock.history import simulate_history

LAW = get_law("dieterich")
P = LAW.defaults()
SIGMA = 1.2 * 9.81
K = 4e5
QD = {"M": 0.0, "eta": 100.0, "sigma": SIGMA}


def _mu_ss(V):
    return P["a_v"] + (P["a"] - P["b"]) * math.log(V / P["V_s"])


def test_velocity_step_at_m0_settles_at_the_steady_force_balance():
    V1, V2 = 1e-5, 1e-4
    sim = simulate_history(LAW, f"{V1}@0,{V2}@10", K, QD, t_end=30.0, rtol=1e-10)
    names = list(sim.state_names)
    assert names == ["V", "v", "mu", "phi", "F", "x_lp", "slip"]
    col = {n: i for i, n in enumerate(names)}
    start, end = sim.y[:, 0], sim.y_final
    assert start[col["mu"]] == pytest.approx(_mu_ss(V1), rel=1e-12)
    assert end[col["v"]] == pytest.approx(V2, rel=1e-7)
    assert end[col["mu"]] == pytest.approx(_mu_ss(V2), rel=1e-8)
    assert end[col["mu"]] - start[col["mu"]] == pytest.approx((P["a"] - P["b"]) * math.log(V2 / V1), rel=1e-6)
    assert end[col["F"]] == pytest.approx(SIGMA * _mu_ss(V2) + QD["eta"] * V2, rel=1e-8)
    # the force balance holds at every recorded point, in the transient too (the slip rate solves it)
    F, mu, v = sim.y[col["F"]], sim.y[col["mu"]], sim.y[col["v"]]
    assert max(abs(F - SIGMA * mu - QD["eta"] * v)) < 1e-10 * SIGMA
    assert max(v) > 1.5 * V2          # the step overshoots: a transient was integrated


@pytest.mark.parametrize("terms", [{}, {"gamma_ld": 0.2, "alpha_ld": 0.3}])
def test_m0_transient_against_a_tiny_mass_compiled_run(terms):
    from landau.verify.springblock.model import SpringBlockModel
    from landau.verify.springblock.simulate import integrate

    V1, V2, dt = 1e-5, 1e-4, 0.02
    prm = {**QD, **terms}
    sim = simulate_history(LAW, f"{V1}@0,{V2}@1", K, prm, t_end=1.0 + dt, rtol=1e-11)
    model = SpringBlockModel.build(LAW, V2, K, {**prm, "M": 1e-10})
    gam = terms.get("gamma_ld", 0.0)

    def force_ss(V):
        return (SIGMA * _mu_ss(V) + QD["eta"] * V) / (1 - gam * _mu_ss(V))

    # X = x - x0(t) with x0 = x_lp - F_ss(V2)/k: the spring force F = F_ss(V2) - k X
    z0 = model.from_physical((force_ss(V2) - force_ss(V1)) / K, V1, [P["L"] / V1])
    run = integrate(model, z0, (0.0, dt), rtol=1e-11)
    assert_transient_matches(sim, model, run, force_ss(V2), K, V1, f_rel=1e-8)


def test_m0_history_on_the_command_line(tmp_path, capsys):
    out = tmp_path / "step.csv"
    argv = ["simulate", "spring-block", "dieterich", "--V-history", "1e-5@0,0@5,1e-5@15", "--t-end", "25",
            "--param", "M=0", "--param", "eta=100", "--param", f"sigma={SIGMA}", "--out", str(out)]
    assert main(argv) == 0
    with open(out) as fh:
        rows = list(csv.reader(fh))
    assert rows[0] == ["t [s]", "V [m/s]", "v [m/s]", "mu [1]", "phi [s]", "F [N]", "x_lp [m]", "slip [m]"]
    v = [float(r[2]) for r in rows[1:]]
    assert min(v) < 1e-3 * 1e-5           # the hold: the slip rate falls by decades
    assert v[-1] == pytest.approx(1e-5, rel=1e-3)


def test_m0_history_without_damping_needs_a_direct_effect(capsys):
    # M = 0 without eta is the quasi-static run (tests/lab); its force balance fixes v only where
    # mu grows with v, so a law without a direct effect (a < 0) is a named error
    from landau.laws import FrictionLaw

    flat = FrictionLaw.from_strings("negative-direct-effect", "mu0 - c*log(v/V0) + b*log(V0*phi/L)",
                                    {"phi": "1 - v*phi/L"}, {"mu0": 0.6, "c": 0.002, "b": 0.01, "V0": 1e-6, "L": 1e-5})
    with pytest.raises(InputError, match="direct effect"):
        simulate_history(flat, "1e-5@0,1e-4@10", K, {"M": 0.0, "sigma": SIGMA})
    assert main(["simulate", "spring-block", "--mu", "mu0 - c*log(v/V0) + b*log(V0*phi/L)",
                 "--state", "phi=1 - v*phi/L", "--param", "mu0=0.6", "--param", "c=0.002", "--param", "b=0.01",
                 "--param", "V0=1e-6", "--param", "L=1e-5", "--V-history", "1e-5@0,1e-4@10", "--param", "M=0",
                 "--param", f"sigma={SIGMA}", "--k", "1e5"]) == 2
    assert "direct effect" in capsys.readouterr().err
    with pytest.raises(InputError, match="'eta'.*>= 0"):
        simulate_history(LAW, "1e-5@0,1e-4@10", K, {"M": 0.0, "sigma": SIGMA, "eta": -1.0})
