"""The compiled simulation of a user's DynamicalSystem (landau.analyses.system_simulation).

Every trajectory is compared with scipy's ``solve_ivp`` (DOP853 at rtol = atol = 1e-13, an
independent integrator, field written by hand here) on E⁻¹·f.  The compiled Radau IIA runs at
rtol 1e-10; the global error of a tolerance-controlled integration over a few dozen periods of a
limit cycle is a modest multiple of the tolerance (the phase error grows linearly), so the final
states must agree to 1e-7 (10³·rtol), and the Hermite samples of ``t_eval`` (error O(h⁴) per step
at the steps rtol 1e-10 takes) to 1e-7 as well.
"""

import math

import numpy as np
import pytest
import scipy.integrate
import sympy as sp

from landau import DynamicalSystem
from landau.analyses import system_simulation
from landau.analyses.system_simulation import simulate_system
from landau.errors import InputError
from landau.verify.hybrid.result import Simulation, Status

A, B = 1.5, 3.3          # b slightly above b_c = 1 + a² = 3.25: the stable cycle of the Brusselator


def _brusselator():
    return DynamicalSystem.from_strings({"x": "a - (b + 1)*x + x^2*y", "y": "b*x - x^2*y"}, "b", {"a": A},
                                        equilibrium={"x": "a", "y": "b/a"}, name="brusselator")


def _brusselator_rhs(t, y):
    x, w = y
    return [A - (B + 1) * x + x * x * w, B * x - x * x * w]


def _reference(rhs, y0, t_end, t_eval=None):
    sol = scipy.integrate.solve_ivp(rhs, (0.0, t_end), y0, method="DOP853", rtol=1e-13, atol=1e-13,
                                    t_eval=t_eval)
    assert sol.status == 0
    return sol


def test_brusselator_from_strings_agrees_with_solve_ivp():
    run = simulate_system(_brusselator(), {"b": B}, 60.0, [1.0, 2.0], rtol=1e-10)
    assert isinstance(run, Simulation) and run.status is Status.FINISHED and run.success
    assert run.state_names == ("x", "y") and run.t_final == 60.0
    ref = _reference(_brusselator_rhs, [1.0, 2.0], 60.0)
    assert np.max(np.abs(run.y_final - ref.y[:, -1])) < 1e-7
    assert run.t[0] == 0.0 and run.t[-1] == 60.0 and np.all(np.diff(run.t) > 0)
    assert np.array_equal(run.y[:, -1], run.y_final)
    # the recorded slopes are the field at the recorded states
    k = len(run.t) // 2
    assert np.allclose(run.f[:, k], _brusselator_rhs(0.0, run.y[:, k]), rtol=1e-14, atol=1e-14)


def test_a_run_taken_in_several_compiled_calls_is_the_same_trajectory(monkeypatch):
    """A long run is taken in compiled calls of at most CHUNK_STEPS attempts, each continuing from the
    previous one's state and step size: with calls of 50 attempts the record is still increasing in time,
    without repeated points, and the final state agrees with solve_ivp as tightly as one call's."""
    monkeypatch.setattr(system_simulation, "CHUNK_STEPS", 50)
    run = simulate_system(_brusselator(), {"b": B}, 60.0, [1.0, 2.0], rtol=1e-10)
    assert run.nsteps > 20 * 50 and len(run.t) == run.nsteps + 1 and np.all(np.diff(run.t) > 0)
    ref = _reference(_brusselator_rhs, [1.0, 2.0], 60.0)
    assert np.max(np.abs(run.y_final - ref.y[:, -1])) < 1e-7
    short = simulate_system(_brusselator(), {"b": B}, 60.0, [1.0, 2.0], max_steps=120)
    assert short.status is Status.MAX_STEPS and short.nsteps <= 120


def test_t_eval_samples_agree_with_solve_ivp():
    te = np.linspace(0.0, 30.0, 301)
    run = simulate_system(_brusselator(), {"b": B}, 30.0, {"x": 1.0, "y": 2.0}, rtol=1e-10, t_eval=te)
    ref = _reference(_brusselator_rhs, [1.0, 2.0], 30.0, te)
    assert np.array_equal(run.t, te) and run.y.shape == (2, 301)
    assert np.max(np.abs(run.y - ref.y)) < 1e-7


def test_default_start_is_the_displaced_equilibrium():
    """y0 = None: the equilibrium (a, b/a) with x displaced by 1e-3·max(1, a); a supercritical Hopf
    above b_c: the run leaves the unstable equilibrium towards the cycle."""
    run = simulate_system(_brusselator(), {"b": B}, 1.0, rtol=1e-10)
    assert run.y[:, 0] == pytest.approx([A + 1e-3 * A, B / A], rel=1e-15)
    ref = _reference(_brusselator_rhs, run.y[:, 0], 1.0)
    assert np.max(np.abs(run.y_final - ref.y[:, -1])) < 1e-9


def _rate_state():
    """A spring–block with the aging law, slip rate v = V·exp(u) (u = ln(v/V)) so that the state stays
    positive: M·dX/dt… written as E·ẏ = f with E = diag(1, M, 1)."""
    rhs = {"X": "V*(exp(u) - 1)",
           "u": "(k*(-X) - sigma*(a*u + b*log(V*theta/L)))/(V*exp(u))",
           "theta": "1 - V*exp(u)*theta/L"}
    return DynamicalSystem.from_strings(rhs, "k", {"V": 1.0, "sigma": 1.0, "a": 0.01, "b": 0.015, "L": 1.0,
                                                   "M": 0.5},
                                        guess={"X": 0.0, "u": 0.0, "theta": 1.0}, mass={"u": "M"},
                                        name="rate-state")


def test_a_diagonal_mass_is_divided_out():
    """E = diag(1, M, 1): the compiled field is E⁻¹·f; against solve_ivp on the hand-written E⁻¹·f."""
    p = dict(V=1.0, sigma=1.0, a=0.01, b=0.015, L=1.0, M=0.5, k=0.004)

    def rhs(t, y):
        X, u, th = y
        v = p["V"] * math.exp(u)
        return [p["V"] * (math.exp(u) - 1),
                (-p["k"] * X - p["sigma"] * (p["a"] * u + p["b"] * math.log(p["V"] * th / p["L"]))) / v / p["M"],
                1 - v * th / p["L"]]

    y0 = [0.1, 0.0, 1.0]
    run = simulate_system(_rate_state(), {"k": 0.004, "M": 0.5}, 40.0, y0, rtol=1e-10)
    ref = _reference(rhs, y0, 40.0)
    assert run.success
    assert np.max(np.abs(run.y_final - ref.y[:, -1]) / (1 + np.abs(ref.y[:, -1]))) < 1e-7


def test_a_full_mass_matrix_is_inverted():
    """E = [[2, 1], [1, 1]] mixing the rows of a linear oscillator: ẏ = E⁻¹·f, against solve_ivp."""
    x, y, mu = sp.symbols("x y mu", real=True)
    Em = sp.Matrix([[2, 1], [1, 1]])
    f = (mu * x - y - x ** 3, x + mu * y)
    s = DynamicalSystem("mixed", (x, y), f, Em, mu, (0, 0))
    Einv = np.linalg.inv(np.array([[2.0, 1.0], [1.0, 1.0]]))

    def rhs(t, z):
        return Einv @ np.array([0.1 * z[0] - z[1] - z[0] ** 3, z[0] + 0.1 * z[1]])

    run = simulate_system(s, {"mu": 0.1}, 20.0, [0.3, -0.2], rtol=1e-10)
    ref = _reference(rhs, [0.3, -0.2], 20.0)
    assert np.max(np.abs(run.y_final - ref.y[:, -1])) < 1e-8


def test_a_stiff_system_is_integrated_in_few_steps():
    """Robertson's chemical kinetics (Hairer & Wanner 1996, Sec. IV.1; stiffness ratio ~1e11): the
    Radau IIA reaches t = 40 in a few hundred steps; y at t = 40 against solve_ivp's Radau at 1e-12
    (DOP853 cannot do it in reasonable time)."""
    s = DynamicalSystem.from_strings({"a": "-0.04*a + 1e4*b*c", "b": "0.04*a - 1e4*b*c - 3e7*b^2",
                                      "c": "3e7*b^2"}, "p", {}, guess={"a": 1.0})
    run = simulate_system(s, {"p": 0.0}, 40.0, [1.0, 0.0, 0.0], rtol=1e-8, atol=[1e-10, 1e-14, 1e-10])

    def rhs(t, y):
        a, b, c = y
        return [-0.04 * a + 1e4 * b * c, 0.04 * a - 1e4 * b * c - 3e7 * b * b, 3e7 * b * b]

    ref = scipy.integrate.solve_ivp(rhs, (0, 40.0), [1.0, 0.0, 0.0], method="Radau", rtol=1e-12,
                                    atol=[1e-14, 1e-18, 1e-14])
    assert run.success and run.nsteps < 500
    assert run.y_final == pytest.approx(ref.y[:, -1], rel=1e-6, abs=1e-12)


# --- refusals -----------------------------------------------------------------------------------

def test_an_algebraic_row_is_refused_naming_the_alternative():
    s = DynamicalSystem.from_strings({"x": "-x + z", "z": "x - 2*z + p"}, "p", {}, guess={},
                                     mass={"z": "0"})
    with pytest.raises(InputError, match=r"state 'z' has mass E_ii = 0 .*eliminate the algebraic state"):
        simulate_system(s, {"p": 1.0}, 1.0, [0.0, 0.5])


def test_a_mass_that_vanishes_at_the_parameters_is_refused():
    s = DynamicalSystem.from_strings({"x": "-x + z", "z": "x - 2*z + p"}, "p", {"m": 1.0}, guess={},
                                     mass={"z": "m"})
    assert simulate_system(s, {"p": 1.0}, 1.0, [0.0, 0.5]).success
    with pytest.raises(InputError, match=r"state 'z' has mass E_ii = 0"):
        simulate_system(s, {"p": 1.0, "m": 0.0}, 1.0, [0.0, 0.5])


def test_a_singular_full_mass_matrix_is_refused():
    x, y, mu = sp.symbols("x y mu", real=True)
    s = DynamicalSystem("singular", (x, y), (-x, -y + mu), sp.Matrix([[1, 1], [1, 1]]), mu, (0, mu))
    with pytest.raises(InputError, match="singular"):
        simulate_system(s, {"mu": 1.0}, 1.0, [0.0, 0.0])


@pytest.mark.parametrize("params, kwargs, match", [
    ({}, {}, r"give the Hopf parameter 'b' a value"),
    ({"b": 3.3, "q": 1.0}, {}, r"unknown parameter 'q'"),
    ({"b": float("nan")}, {}, r"parameter 'b' must be finite"),
    ({"b": "three"}, {}, r"parameter 'b' must be a number"),
    ({"b": 3.3}, {"y0": [1.0]}, r"y0 must have 2 values"),
    ({"b": 3.3}, {"y0": {"x": 1.0, "w": 2.0}}, r"'w' is not a state"),
    ({"b": 3.3}, {"y0": [1.0, float("inf")]}, r"y0 must be finite"),
    ({"b": 3.3}, {"t_end": 0.0}, r"t_end must be after t0"),
    ({"b": 3.3}, {"rtol": 0.0}, r"rtol must be in"),
    ({"b": 3.3}, {"atol": -1.0}, r"atol must be positive"),
    ({"b": 3.3}, {"t_eval": [0.0, 20.0]}, r"t_eval must be increasing finite times inside"),
    ({"b": 3.3}, {"max_steps": 0}, r"max_steps must be a positive integer"),
])
def test_bad_input_is_refused_by_name(params, kwargs, match):
    kw = {"t_end": 10.0, "y0": [1.0, 2.0], **kwargs}
    with pytest.raises(InputError, match=match):
        simulate_system(_brusselator(), params, kw.pop("t_end"), kw.pop("y0"), **kw)


def test_a_parameter_without_a_default_must_be_given():
    x, u, p, k = sp.symbols("x u p k", real=True)
    s = DynamicalSystem("rayleigh", (x, u), (u, -k * x + p * u - u ** 3), (1, 1), p, (0, 0))
    with pytest.raises(InputError, match=r"no value for parameter\(s\) k"):
        simulate_system(s, {"p": 0.1}, 1.0, [0.1, 0.0])
    assert simulate_system(s, {"p": 0.1, "k": 9.0}, 1.0, [0.1, 0.0]).success


def test_one_compiled_kernel_serves_every_parameter_value_and_mass():
    """The parameter values and E⁻¹ are entries of the parameter vector, not of the generated code: two
    systems with the same field (other defaults, another mass value) share one source and one compiled
    function, and the runs differ as their parameters say."""
    s1, s2 = _rate_state(), _rate_state()
    c1, c2 = system_simulation.compile_system(s1), system_simulation.compile_system(s2)
    assert c1 is system_simulation.compile_system(s1) and c1 is not c2
    assert c1.source == c2.source and c1.fun is c2.fun and c1.jac is c2.jac
    v = c1.vector({"k": 0.004, "M": 0.25})
    assert v[-1] == 4.0 and v[0] == 0.004          # (k, L, M, V, a, b, sigma, 1/M)
    assert [a.name for a in c1.arguments[:7]] == ["k", "L", "M", "V", "a", "b", "sigma"]


def test_not_a_system_is_refused():
    with pytest.raises(InputError, match="takes a DynamicalSystem, got dict"):
        simulate_system({"x": "-x"}, {}, 1.0)


def test_a_run_that_cannot_finish_says_why():
    """ẋ = x² from x = 1 blows up at t = 1: the run stops before t_end with a failing status and the
    time reached (never a silent NaN); a too small step budget stops with MAX_STEPS."""
    s = DynamicalSystem.from_strings({"x": "x^2 + p"}, "p", {}, guess={"x": 0.0})
    run = simulate_system(s, {"p": 0.0}, 2.0, [1.0])
    assert not run.success and run.status in (Status.STEP_SIZE_UNDERFLOW, Status.NON_FINITE)
    assert run.t_final < 1.0 + 1e-6 and "before t_end = 2" in run.message
    short = simulate_system(_brusselator(), {"b": B}, 60.0, [1.0, 2.0], max_steps=10)
    assert short.status is Status.MAX_STEPS and short.t_final < 60.0 and "max_steps" in short.message


# --- the check of a user system uses the compiled integrator ----------------------------------

def test_the_check_shoots_with_the_compiled_flow_and_matches_scipy(monkeypatch):
    """The check of the Brusselator (a = 1.5) integrates with the compiled Radau IIA (every flow built
    is counted); its simulated amplitude and frequency equal those of the former route, scipy's Radau
    (the flow left to ``_shoot``'s default), to 1e-6 (both at rtol 1e-10; the monodromy's central
    differences and hybrd's stopping make the two differ by more than the integrations do)."""
    from landau import check
    from landau.analyses import checking

    s = _brusselator()
    built = []
    real = system_simulation.shooting_flow

    def counted(*args):
        built.append(args[1])
        return real(*args)

    monkeypatch.setattr(system_simulation, "shooting_flow", counted)
    ours = check(s, eps2=1e-3, params={"a": A}, bracket=(2.5, 4.0))
    assert built and all(b["b"] > 3.25 for b in built)
    monkeypatch.setattr(system_simulation, "shooting_flow", lambda *a: None)   # _shoot's scipy default
    theirs = check(s, eps2=1e-3, params={"a": A}, bracket=(2.5, 4.0))
    assert ours.verdict == theirs.verdict == checking.Verdict.AGREES
    assert ours.amplitude_simulated == pytest.approx(theirs.amplitude_simulated, rel=1e-6)
    assert ours.frequency_simulated == pytest.approx(theirs.frequency_simulated, rel=1e-6)
    assert ours.rel_error == pytest.approx(theirs.rel_error, abs=1e-6)


# --- the same code as plain Python ----------------------------------------------------------------

_SHORT_RUN = """
import json, warnings
warnings.simplefilter("always")
from landau import DynamicalSystem
from landau.analyses.system_simulation import simulate_system
s = DynamicalSystem.from_strings({"x": "a - (b + 1)*x + x^2*y", "y": "b*x - x^2*y"}, "b", {"a": 1.5},
                                 equilibrium={"x": "a", "y": "b/a"})
r = simulate_system(s, {"b": 3.3}, 5.0, [1.0, 2.0], rtol=1e-8)
print(json.dumps({"y": r.y_final.tolist(), "steps": r.nsteps, "nfev": r.nfev, "status": r.status.value}))
"""


def test_runs_as_plain_python_under_numba_disable_jit():
    """NUMBA_DISABLE_JIT=1 (CONTRIBUTING, debugging a compiled core): the generated field, the Radau IIA
    loop and the slopes' helper run as plain Python and take the same steps as the compiled run, its
    state equal to 1e-12 (the same operations in the same order; only exp/log/pow may round differently
    in Python's and the compiled code's math library)."""
    import json
    import os
    import subprocess
    import sys

    out = {}
    for jit in (True, False):
        env = dict(os.environ)
        env.pop("NUMBA_DISABLE_JIT", None)
        if not jit:
            env["NUMBA_DISABLE_JIT"] = "1"
        p = subprocess.run([sys.executable, "-c", _SHORT_RUN], capture_output=True, text=True, env=env, timeout=600)
        assert p.returncode == 0, p.stderr
        assert ("runs as plain Python" in p.stderr) is not jit
        out[jit] = json.loads(p.stdout.strip().splitlines()[-1])
    assert out[True]["status"] == out[False]["status"] == "finished"
    assert out[True]["steps"] == out[False]["steps"] and out[True]["nfev"] == out[False]["nfev"]
    assert np.allclose(out[True]["y"], out[False]["y"], rtol=1e-12, atol=0)
