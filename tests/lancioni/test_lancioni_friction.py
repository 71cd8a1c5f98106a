"""The impact oscillator of Lancioni, Lenci & Galvanetto with a user's velocity-dependent friction.

Off-paper case: a Stribeck-type coefficient F(v) = μ (1 + α e^{−v/v₀}) (μ = 0.3, α = 0.2,
v₀ = 0.5 m/s; the paper has plain Coulomb friction), belt v = −1 m/s, parameter set 1.  Each
number of the toolkit (symbolic slip mode → landau engine, hybrid contact simulation) is checked
against an independent computation: eq. (1) of the paper written here directly in numpy (the two
rows solved for (φ̈, λ_N) by np.linalg.solve at every call, no sympy), its Jacobian by central
differences, scipy's brentq and solve_ivp.
"""

import json

import numpy as np
import pytest
from scipy.integrate import solve_ivp
from scipy.optimize import brentq

from landau.cli import main
from landau.errors import InputError
from landau.laws.velocity import VelocityFriction, coulomb
from landau.verify.hybrid.contact import contact_problem, poisson_impact
from landau.verify.lancioni import analysis as A
from landau.verify.lancioni import slip as S
from landau.verify.lancioni.flight_onset import first_lift_off
from landau.verify.lancioni.model import Lancioni, build, slip_state

LAW_TEXT = "mu*(1 + alpha*exp(-v/v0))"
LAW_PARAMS = {"mu": 0.3, "alpha": 0.2, "v0": 0.5}
BELT = -1.0


def _stribeck(v, mu, alpha, v0):
    return mu * (1 + alpha * np.exp(-v / v0))


def _field(phi, w, mu, p=S.SET1, v=BELT):
    """(φ̈, λ_N) of eq. (1) on the belt (g_N = 0, y = l cos φ) with λ_T = −F(g_T) λ_N, g_T = lφ̇ cos φ − v."""
    m1, m2, l, ky, kp, cy, cp, p0, y0, g = (p[k] for k in S.PARAM_NAMES)
    sn, cs = np.sin(phi), np.cos(phi)
    y, yd = l * cs, -l * w * sn
    F = _stribeck(l * w * cs - v, mu, LAW_PARAMS["alpha"], LAW_PARAMS["v0"])
    h1 = cp * w + kp * (phi - p0) + m1 * g * l * sn
    h2 = cy * yd + ky * (y - y0) + m1 * l * w * w * cs + (m1 + m2) * g
    # rows of M q̈ = W λ − h with ÿ = −lφ̇² cos φ − lφ̈ sin φ, unknowns (φ̈, λ_N)
    A = np.array([[m1 * l * l * cs * cs, -l * sn + l * cs * F], [-m2 * l * sn, -1.0]])
    r = np.array([-h1 + m1 * l * l * sn * cs * w * w, -h2 + (m1 + m2) * l * w * w * cs])
    return np.linalg.solve(A, r)


def _equilibrium(mu):
    return brentq(lambda x: _field(x, 0.0, mu)[0], 0.0, 1.0, xtol=1e-15)


def _critical_eigenvalue(mu, h=1e-6):
    pe = _equilibrium(mu)
    J = np.array([[0.0, 1.0],
                  [(_field(pe + h, 0.0, mu)[0] - _field(pe - h, 0.0, mu)[0]) / (2 * h),
                   (_field(pe, h, mu)[0] - _field(pe, -h, mu)[0]) / (2 * h)]])
    lam = np.linalg.eigvals(J)
    return lam[np.argmax(lam.real)]


@pytest.fixture(scope="module")
def law():
    return VelocityFriction.from_strings("stribeck-type", LAW_TEXT, params=LAW_PARAMS)


@pytest.fixture(scope="module")
def hopf(law):
    return S.slip_hopf(friction=law)


def test_slip_hopf_point_with_a_user_law_matches_a_numpy_jacobian(hopf):
    # independent: brentq on the largest real part of the finite-difference Jacobian's eigenvalues
    # (central differences, h = 1e-6: error ~h² f''' ≈ 1e-11 in Re λ; dRe λ/dμ ≈ 21, so μ to ~1e-12)
    assert hopf.parameter == "mu"
    mu_c = brentq(lambda m: _critical_eigenvalue(m).real, hopf.p_c - 0.02, hopf.p_c + 0.02, xtol=1e-14)
    assert hopf.p_c == pytest.approx(mu_c, abs=1e-9)
    assert hopf.omega_c == pytest.approx(abs(_critical_eigenvalue(mu_c).imag), rel=1e-8)
    assert hopf.equilibrium[0] == pytest.approx(_equilibrium(mu_c), abs=1e-10)
    # the velocity weakening (dF/dv < 0) destabilises: below the Coulomb value with the same F(1 m/s)
    assert hopf.p_c * (1 + 0.2 * np.exp(-2)) < S.slip_hopf().p_c


def test_subcritical_by_direct_integration(hopf):
    # the engine's c₁ says subcritical (an unstable cycle of amplitude ≈ C sqrt(μ_c − μ) below μ_c).
    # Independent: integrate the numpy slip ODE at μ_c − 0.005 from 0.7 and 1.4 times that amplitude
    # (released at rest) and follow the successive maxima of φ − φ_e: the smaller start decays, the
    # larger grows (with a supercritical point both would decay) until g_T reaches 0, where the
    # slip phase would end.
    assert hopf.criticality == "subcritical" and hopf.cycle_side == -1
    mu = hopf.p_c - 0.005
    pe, A = _equilibrium(mu), hopf.amplitude(mu)

    def maxima(f):
        def top(t, y):
            return y[1]
        top.direction = -1

        def stop(t, y):
            return S.SET1["l"] * np.cos(y[0]) * y[1] - BELT
        stop.terminal = True
        sol = solve_ivp(lambda t, y: [y[1], _field(y[0], y[1], mu)[0]], (0.0, 4.0), [pe + f * A, 0.0],
                        rtol=1e-10, atol=1e-12, events=(top, stop))
        return sol.y_events[0][:, 0] - pe

    small, large = maxima(0.7), maxima(1.4)
    assert np.all(np.diff(small) < 0) and small[-1] < 0.85 * small[0]
    assert len(large) >= 5 and np.all(np.diff(large) > 0) and large[-1] > 1.2 * large[0]


def test_hopf_point_with_a_user_law_confirmed_by_the_hybrid_simulation(law, hopf):
    # growth rate of a 1e-5 kick in the full hybrid model (the model evaluates the law at each
    # state's g_T; impact, flight and stick guards armed) at μ_c ∓ 0.002: the zero of the line
    # through them is within O(δ² σ''/σ') ~ 1e-5 of the engine's μ_c, its slope within 5 % of
    # the engine's dRe λ/dμ (linear theory)
    mu0, g1, g2 = A.hopf_by_simulation(delta=2e-3, friction=law)
    assert g1.sigma < 0 < g2.sigma and g1.modes == g2.modes == ("slip+",)
    assert abs(mu0 - hopf.p_c) < 5e-5
    assert (g2.sigma - g1.sigma) / 4e-3 == pytest.approx(hopf.dlambda_dp.real, rel=0.05)


def test_lift_off_with_a_user_law_matches_solve_ivp(law):
    # hybrid engine (every mode and guard armed, the law evaluated by the model) against solve_ivp on
    # the numpy slip ODE to its first event λ_N = 0 (both rtol ≤ 1e-10: event times agree to ~1e-9 s)
    mu, kick = 0.375, 0.02
    phi_start = _equilibrium(mu) + kick
    ev = first_lift_off(mu, phi=phi_start, friction=law)
    assert ev.guard == "lift-off" and ev.next_mode == "flight"

    def lam_n(t, y):
        return _field(y[0], y[1], mu)[1]
    lam_n.terminal, lam_n.direction = True, -1

    def stop(t, y):  # g_T = 0 would end the slip phase first
        return S.SET1["l"] * np.cos(y[0]) * y[1] - BELT
    stop.terminal = True
    sol = solve_ivp(lambda t, y: [y[1], _field(y[0], y[1], mu)[0]], (0.0, 5.0), [phi_start, 0.0],
                    method="DOP853", rtol=1e-12, atol=1e-14, events=(lam_n, stop))
    assert sol.t_events[0].size == 1 and sol.t_events[1].size == 0
    assert ev.t == pytest.approx(sol.t_events[0][0], abs=1e-8)
    assert ev.state[0] == pytest.approx(sol.y_events[0][0][0], abs=1e-8)
    assert ev.state[2] == pytest.approx(sol.y_events[0][0][1], abs=1e-7)


def test_coulomb_law_object_is_the_papers_model():
    # the default model and the model given coulomb(mu) as a law are the same: forces bit for bit,
    # and the Hopf point through the law path equals the published-value path (paper: 0.40977)
    a, b = build(0.41), build(friction=coulomb(0.41))
    y = slip_state(a.mech, 0.4, 0.3)
    for mode in ("slip+", "slip-", "stick"):
        assert np.array_equal(a.forces(mode, 0.0, y)[0], b.forces(mode, 0.0, y)[0])
    h_law = S.slip_hopf(friction=coulomb(0.3))
    assert h_law.p_c == pytest.approx(S.slip_hopf().p_c, abs=1e-12)
    assert abs(h_law.p_c - 0.40977) < 1e-5


def test_slip_force_uses_the_law_at_the_current_velocity(law):
    # λ_T/λ_N in slip is −F(g_T) at the state's relative velocity; stick uses the one-sided limits
    cm = build(friction=law)
    y = slip_state(cm.mech, 0.39, 0.2)
    gT = S.SET1["l"] * np.cos(0.39) * 0.2 - BELT
    _, lamN, lamT, _ = cm.forces("slip+", 0.0, y)
    assert lamT / lamN == pytest.approx(-_stribeck(gT, **LAW_PARAMS), rel=1e-14)
    assert cm.mech.static_mu() == pytest.approx((0.3 * 1.2, 0.3 * 1.2), rel=1e-15)


def test_asymmetric_stick_cone_closed_form():
    # unit Delassus matrix, b = (−g, a): stick forces λ = (g, −a); stick iff −μ₊g ≤ −a ≤ μ₋g,
    # otherwise slip in the direction of a with λ_T = ∓μ±λ_N (closed form)
    G, g = np.eye(2), 10.0
    assert contact_problem(G, np.array([-g, -3.0]), (0.2, 0.5), 0.0).mode == "stick"       # λ_T = 3 ≤ 5
    sol = contact_problem(G, np.array([-g, 3.0]), (0.2, 0.5), 0.0)                        # λ_T = −3 < −2
    assert sol.mode == "slip+" and sol.lamT == pytest.approx(-2.0)
    sol = contact_problem(G, np.array([-g, -6.0]), (0.2, 0.5), 0.0)                       # λ_T = 6 > 5
    assert sol.mode == "slip-" and sol.lamT == pytest.approx(5.0)


def test_poisson_impact_uses_the_one_sided_limit_of_the_sliding_direction():
    # point mass (G = I): plastic impact with γ⁻ = (−1, γ_T⁻).  Sticking needs the impulse
    # Λ_T = −γ_T⁻ inside [−μ₊Λ_N, μ₋Λ_N] with Λ_N = 1; otherwise the tangential velocity keeps its
    # sign and drops by μ_σ (closed form γ_T⁺ = γ_T⁻ − σ μ_σ).
    G = np.eye(2)
    assert poisson_impact(G, [-1.0, -0.4], (0.2, 0.5), 0.0).compression == "stick"
    r = poisson_impact(G, [-1.0, 0.4], (0.2, 0.5), 0.0)
    assert r.compression == "slip+" and r.gamma_plus[1] == pytest.approx(0.4 - 0.2)
    r = poisson_impact(G, [-1.0, -0.9], (0.2, 0.5), 0.0)
    assert r.compression == "slip-" and r.gamma_plus[1] == pytest.approx(-0.9 + 0.5)


def test_bad_laws_are_refused(law):
    with pytest.raises(InputError, match="coefficient"):
        build(friction=VelocityFriction.from_strings("f", "T + c*v", params={"T": 0.6, "c": 6.0}, quantity="force"))
    with pytest.raises(InputError, match="k_y"):
        S.slip_hopf(friction=VelocityFriction.from_strings("f", "k_y*0.1", params={"k_y": 3.0}))
    with pytest.raises(InputError, match="either as mu or as a law"):
        Lancioni(mu=0.5, friction=law)
    with pytest.raises(InputError, match="nosuch"):
        S.slip_hopf(friction=law, parameter="nosuch")


# ---------------------------------------------------------------------------------------- CLI
CLI_LAW = ["--friction", LAW_TEXT, "--param", "mu=0.3", "--param", "alpha=0.2", "--param", "v0=0.5"]


def test_cli_hopf_with_a_user_law(capsys, hopf):
    assert main(["hopf", "impact-oscillator", *CLI_LAW, "--json"]) == 0
    doc = json.loads(capsys.readouterr().out)
    assert doc["model"] == "impact-oscillator" and doc["parameter"] == "mu"
    assert doc["p_c"] == pytest.approx(hopf.p_c, rel=1e-12)   # the same computation as the Python call
    assert doc["criticality"] == "subcritical" and len(doc["c1"]) == 2


def test_cli_hopf_coulomb_default(capsys):
    assert main(["hopf", "impact-oscillator", "--json"]) == 0
    doc = json.loads(capsys.readouterr().out)
    assert abs(doc["p_c"] - 0.40977) < 1e-5 and doc["criticality"] == "supercritical"  # paper, Sec. 3


def test_cli_simulate_with_a_user_law(tmp_path, capsys):
    out = tmp_path / "run.csv"
    assert main(["simulate", "impact-oscillator", *CLI_LAW, "--t-end", "1", "--out", str(out), "--json"]) == 0
    doc = json.loads(capsys.readouterr().out)
    assert doc["exit_code"] == 0 and doc["parameters"]["alpha"] == 0.2 and out.exists()
    rows = np.loadtxt(out, delimiter=",", skiprows=1)
    # μ = 0.3 is below μ_c ≈ 0.382 and the start (1e-3 rad off) inside the unstable cycle: stays on the belt
    assert np.abs(rows[:, 2] - np.cos(rows[:, 1])).max() < 1e-8


@pytest.mark.parametrize("argv, word", [
    (["hopf", "impact-oscillator", "--friction", "mu*(1 + beta*v)", "--param", "mu=0.3"], "beta"),
    (["hopf", "impact-oscillator", *CLI_LAW, "--parameter", "gamma"], "gamma"),
    (["hopf", "impact-oscillator", "--param", "v_belt=1"], "v_belt"),
    (["simulate", "impact-oscillator", "--friction", "mu*exp(-v/w0)", "--param", "mu=0.3"], "w0"),
    (["simulate", "impact-oscillator", *CLI_LAW, "--param", "zeta=1"], "zeta"),
])
def test_cli_bad_input_exit_2(argv, word, capsys):
    assert main(argv) == 2
    err = capsys.readouterr().err
    assert len(err.strip().splitlines()) == 1 and word in err
