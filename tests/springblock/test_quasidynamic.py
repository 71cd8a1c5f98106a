"""The quasi-dynamic spring–block (M = 0, η > 0): the force balance solved for the slip rate.

A BP1-like cell (a = 0.010, b = 0.015, σ = 50 MPa, L = 8 mm, η = ρc_s/2 = 4.624e6 Pa·s/m, per unit
area; aging law).  Independent routes:

* the linearised quasi-dynamic cell in units L, L/V, σ (written here): with a' = a + ηV/σ and
  κ = kL/σ, ξ' = −(κξ + bψ)/a', ψ' = (κξ + bψ)/a' − ψ, so λ² − tr λ + κ/a' = 0 with
  tr = (b − κ)/a' − 1 — the decay rate and period of a small perturbation above k_c;
* the amplitude equation of the multiple-scales engine (C·sqrt(k_c − k), ω_c): the half
  peak-to-peak slip of the cycle, found by a root search on the first return to v = V, falls
  short of it by O(ε²) (the error quarters when ε² does);
* the compiled M > 0 integrator at a mass with M V²/(σL) ≈ 1e-20 over one period.
"""

from __future__ import annotations

import csv
import math

import numpy as np
import pytest
from scipy.optimize import brentq

from landau.cli import main
from landau.errors import InputError
from landau.laws import get_law
from landau.verify.springblock.checks import predict
from landau.verify.springblock.quasidynamic import QuasiDynamicCell, simulate_quasidynamic
from landau.verify.springblock.quasidynamic_orbits import return_map

BP1 = dict(a=0.010, b=0.015, L=8e-3, sigma=50e6, eta=4.624e6, V_s=1e-6, a_v=0.6, M=0.0)
LAW = get_law("dieterich")


def _linear_eigenvalue(V: float, k: float) -> complex:
    """λ [1/s] of the linearised quasi-dynamic aging-law cell (module docstring), upper half-plane."""
    a, b, L, s, eta = BP1["a"], BP1["b"], BP1["L"], BP1["sigma"], BP1["eta"]
    ap, kap = a + eta * V / s, k * L / s
    tr, det = (b - kap) / ap - 1.0, kap / ap
    lam = 0.5 * tr + 1j * math.sqrt(det - 0.25 * tr * tr)
    return lam * V / L


def _peaks(t, x):
    i = np.flatnonzero((x[1:-1] > x[:-2]) & (x[1:-1] >= x[2:])) + 1
    return t[i], x[i]


def test_plate_rate_perturbation_above_kc_decays_at_the_linear_rate():
    """V = 1e-9 m/s, k = 1.1 k_c: a perturbation of 1e-3 L decays at Re λ and turns at Im λ."""
    V = 1e-9
    kc = predict(LAW, V, BP1).kc
    k = 1.1 * kc
    lam = _linear_eigenvalue(V, k)
    assert lam.real < 0
    T = 2 * math.pi / lam.imag
    cell = QuasiDynamicCell.build(LAW, V, k, BP1)
    sim = simulate_quasidynamic(LAW, V, k, BP1, 8 * T, cell.perturbed(1e-3 * BP1["L"]), rtol=1e-11)
    assert sim.status.value == "finished"
    tp, xp = _peaks(sim.t, sim.y[0])
    assert len(tp) >= 6
    rate = math.log(xp[-1] / xp[1]) / (tp[-1] - tp[1])
    period = (tp[-1] - tp[1]) / (len(tp) - 2)
    # peaks of the recorded steps: the step size (~T/100) bounds the timing error
    assert rate == pytest.approx(lam.real, rel=2e-2)
    assert period == pytest.approx(T, rel=2e-3)
    assert np.all(np.diff(xp) < 0) and xp[-1] < 0.3 * xp[0]
    # the force balance holds along the run: k(Vt - x) = sigma mu + eta v, i.e. -kX = sigma (mu - mu0) + eta (v - V)
    mu0 = cell.mu0
    resid = -k * sim.y[0] - BP1["sigma"] * (sim.y[2] - mu0) - BP1["eta"] * (sim.y[1] - V)
    assert np.max(np.abs(resid)) < 1e-9 * BP1["sigma"] * mu0


def _cycle(V: float, eps2: float):
    """(half peak-to-peak slip [m], period [s]) of the cycle at k = k_c(1 − ε²), and the prediction."""
    pr = predict(LAW, V, BP1)
    k = pr.kc * (1 - eps2)
    A = pr.amplitude(k)
    cell = QuasiDynamicCell.build(LAW, V, k, BP1)
    xs = A / cell.ell
    x = brentq(lambda z: return_map(cell, z)[0] - z, 0.8 * xs, 1.2 * xs, xtol=1e-12)
    _, T, xmin = return_map(cell, x)
    return 0.5 * (x - xmin) * cell.ell, T, A, 2 * math.pi / pr.frequency(k)


def test_cycle_below_kc_against_the_amplitude_equation():
    """V = 1e-6 m/s (ηV/σ ≈ 1e-4; at the plate rate the same scaled cell has ηV/σ ≈ 1e-10 and its cycle's
    Floquet multiplier is within 2e-9 of 1, below what a float64 shooting resolves).  The cubic amplitude
    equation holds for ε² well below ε²_max = V²/(C²ω_c²k_c) ≈ 4.6e-6 (slip rate swing < V)."""
    V = 1e-6
    pr = predict(LAW, V, BP1)
    assert pr.criticality == "supercritical"
    emax = V * V / (pr.C ** 2 * pr.omega_c ** 2 * pr.kc)
    errs = []
    for e in (emax / 10, emax / 40):
        amp, T, A, T_pred = _cycle(V, e)
        errs.append(amp / A - 1)
        assert T == pytest.approx(T_pred, rel=1e-4)
    # O(ε²) remainder: under 1 % at ε²_max/10 and a quarter of it at a quarter of ε²
    assert abs(errs[0]) < 1e-2
    assert errs[0] / errs[1] == pytest.approx(4.0, rel=0.15)


@pytest.mark.parametrize("extra", [{}, {"gamma_ld": 0.2, "alpha_ld": 0.3}])
def test_quasidynamic_agrees_with_tiny_mass_compiled_run(extra):
    """M = 1e-2 kg/m² (M V²/(σL) = 2.5e-20, fast eigenvalue −η/M): one period from the same state, also
    with a normal load that follows the spring (γ_LD) and the Linker–Dieterich state response (α_LD)."""
    from landau.verify.springblock.model import SpringBlockModel
    from landau.verify.springblock.simulate import integrate

    V = 1e-6
    pr = predict(LAW, V, BP1)
    k = 0.99 * pr.kc
    T = 2 * math.pi / pr.omega_c
    prm = {**BP1, **extra}
    cell = QuasiDynamicCell.build(LAW, V, k, prm)
    y0 = cell.perturbed(0.05 * BP1["L"])
    qd = simulate_quasidynamic(LAW, V, k, cell, T, y0, rtol=1e-11)
    assert abs(qd.y[0]).max() > 0.04 * BP1["L"]
    model = SpringBlockModel.build(LAW, V, k, {**prm, "M": 1e-2})
    v0 = V * math.exp(cell.slip_rate(y0))
    z0 = model.from_physical(y0[0] * cell.ell, v0, [cell.phi0[0] * math.exp(y0[1])])
    run = integrate(model, z0, (0.0, T), rtol=1e-11)
    ph = model.to_physical(run.y_final)
    scale = 0.05 * BP1["L"]
    # rtol 1e-11 over ~500 steps; the O(MV²/(σL)) difference is 1e-20
    assert float(ph["X"]) == pytest.approx(qd.y[0, -1], abs=1e-8 * scale)
    assert float(ph["v"]) == pytest.approx(qd.y[1, -1], rel=1e-8)
    assert float(ph["phi"]) == pytest.approx(qd.y[3, -1], rel=1e-8)


def test_cli_writes_the_quasidynamic_series(tmp_path, capsys):
    out = tmp_path / "qd.csv"
    argv = ["simulate", "spring-block", "dieterich", "--V", "1e-6", "--t-end", "2e5", "--out", str(out)]
    argv += [f"--param={n}={v}" for n, v in BP1.items()]
    assert main(argv) == 0
    with open(out) as fh:
        rows = list(csv.reader(fh))
    assert rows[0] == ["t [s]", "X [m]", "v [m/s]", "mu [1]", "phi [s]"]
    assert len(rows) > 20
    assert "quasi-dynamic" in capsys.readouterr().out


def test_m0_without_damping_is_a_named_error(capsys):
    with pytest.raises(InputError, match="eta > 0"):
        QuasiDynamicCell.build(LAW, 1e-6, 1e7, {**BP1, "eta": 0.0})
    assert main(["simulate", "spring-block", "dieterich", "--V", "1e-6", "--param", "M=0"]) == 2
    assert "eta > 0" in capsys.readouterr().err


@pytest.mark.slow
def test_landau_verify_checks_the_quasidynamic_cell(capsys):
    """`landau verify` at M = 0: the cycle's amplitude against the prediction at ε² ≈ ε²_max/10, by the
    return map of the quasi-dynamic cell (about 2 s)."""
    import json

    argv = ["verify", "dieterich", "--V", "1e-6", "--eps2", "4.6e-7", "--json"]
    argv += [f"--param={n}={v}" for n, v in BP1.items()]
    assert main(argv) == 0
    pt = json.loads(capsys.readouterr().out)["points"][0]
    assert pt["verdict"] == "agrees"
    assert abs(pt["rel_error"]) < 1e-2 and pt["cycle_stable"]
    # the measured Floquet multiplier against the predicted gap 2 Re(dλ/dk) (k_c − k) T
    gap = 1 - pt["detail"]["floquet_multipliers"][0]
    assert gap == pytest.approx(pt["detail"]["points"][-1]["multiplier_gap"], rel=0.05)


def test_landau_verify_refuses_m0_without_damping(capsys):
    assert main(["verify", "dieterich", "--V", "1e-4", "--param", "M=0"]) == 2
    assert "eta > 0" in capsys.readouterr().err


#: a two-state law at M = 0 with radiation damping (no length L: the cell's unit is 1 µm); supercritical
TWO_STATE = dict(M=0.0, eta=10.0, sigma=11.772)


@pytest.mark.slow
def test_check_finds_the_cycle_of_a_two_state_law_at_m0():
    """landau.check at M = 0 for `two-state-dieterich` (two states: a section point has two coordinates,
    Newton shooting on the return map to v = V): the half peak-to-peak slip against C·sqrt(k_c − k) at
    ε² = 1e-3 and ε²/4, its error falling like ε² (the check's contract), and the two Floquet
    multipliers: the amplitude mode's gap 1 − |m| against the predicted 2 Re(dλ/dk)(k_c − k)·T, the
    other strongly contracting (about 4 s)."""
    from landau import check
    from landau.analyses import contract

    res = check("two-state-dieterich", 1e-4, 1e-3, TWO_STATE)
    assert res.verdict == "agrees", res.reason
    assert res.cycle_stable
    errs = list(res.scaling.rel_errors)
    assert abs(errs[0]) < 0.03 and errs[0] / errs[1] == pytest.approx(4.0, rel=0.1)
    assert abs(res.extrapolated_error) < 2e-3
    mults = sorted(res.detail["floquet_multipliers"], reverse=True)
    assert len(mults) == 2 and mults[1] < 1e-2
    # the measured gap carries the O(ε²) remainder of the amplitude equation (a few % at ε² = 1e-3)
    for pt in res.detail["points"]:
        assert pt["multiplier_gap"] == pytest.approx(contract.multiplier_gap(res.prediction, pt["eps2"],
                                                                             res.prediction.p_c), rel=0.06)


#: a subcritical quasi-dynamic point: the nanoscale law of Putelat et al. (2010), eq. (48), at V = 1e-7 m/s with
#: weak damping (Λ > 0; the aging and slip laws are supercritical at every η > 0 when M = 0)
SUB = dict(M=0.0, eta=0.01, sigma=11.772)
SUB_V = 1e-7


def test_bistability_probe_at_m0_decays_below_and_grows_beyond_the_unstable_cycle():
    """At k = k_c(1 + 1e-3): from the linear mode at half the predicted amplitude the orbit decays to steady
    sliding, from twice it grows (the return map to v = V moves the maxima of X monotonically away from
    the unstable cycle)."""
    from landau.verify.springblock.quasidynamic_orbits import fate, section_point

    law = get_law("nanoscale")
    pr = predict(law, SUB_V, SUB)
    assert pr.criticality == "subcritical"
    k = pr.kc * (1 + 1e-3)
    A = pr.amplitude(k)
    cell = QuasiDynamicCell.build(law, SUB_V, k, SUB)
    below, z_below = fate(cell, section_point(cell, 0.5 * A), 0.2 * A, 6 * A)
    beyond, z_beyond = fate(cell, section_point(cell, 2.0 * A), 0.2 * A, 6 * A)
    assert (below, beyond) == ("decays", "grows")
    assert z_below[0] * cell.ell < 0.5 * A < 2.0 * A < z_beyond[0] * cell.ell


@pytest.mark.slow
def test_landau_verify_shows_bistability_at_a_subcritical_m0_point(capsys):
    """`landau verify` at a subcritical M = 0 point with the bistability test (no --no-bistability): the
    unstable cycle by the return map, the threshold between decay and growth bracketed by bisection around
    it, and the large stick-slip cycle beyond it stable (about 3 s)."""
    import json

    argv = ["verify", "nanoscale", "--V", str(SUB_V), "--json"] + [f"--param={n}={v}" for n, v in SUB.items()]
    assert main(argv) == 0
    pt = json.loads(capsys.readouterr().out)["points"][0]
    assert pt["verdict"] == "agrees" and pt["bistable"] is True
    d = pt["detail"]
    assert abs(pt["rel_error"]) < 1e-3
    lo, hi = d["bracket_initial_max_slip"]
    assert lo < d["unstable_cycle"]["max_slip"] < hi and hi / lo < 1.05
    big = d["large_cycle"]
    assert big["max_slip"] > 10 * hi and max(big["floquet_multipliers"]) < 1e-3
