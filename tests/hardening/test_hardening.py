"""No silently wrong answer, no hang, no traceback: every attack on an input path ends in a
correct result or in a named error (CLI: exit 2 and one line on stderr)."""

from __future__ import annotations

import json
import math
import os
import stat
import subprocess
import sys
import time

import numpy as np
import pytest
import sympy as sp

from landau import DynamicalSystem, SpringBlock, derive
from landau.cli import main
from landau.derivation.linear import HopfLine
from landau.errors import BudgetError, DomainError, InputError, OutputError, ParseError
from landau.laws import FrictionLaw, get_law
from landau.laws.law import TABLE1, v
from landau.laws.parse import parse_expression

DIETERICH_MU = "a_v + a*log(v/V_s) + b*log(V_s*phi/L)"
DIETERICH_RATE = "1 - v*phi/L"


def run(capsys, *argv):
    code = main(list(argv))
    out, err = capsys.readouterr()
    return code, out, err


def assert_refused(capsys, *argv, needle: str = "") -> str:
    code, out, err = run(capsys, *argv)
    assert code == 2, (code, out, err)
    assert err.count("\n") == 1 and err.startswith("landau: error:"), err
    assert "Traceback" not in err
    assert needle in err, err
    return err


# --- 1. names that collide with the system's symbols -------------------------------------
@pytest.mark.parametrize("state", ["V", "sigma", "u", "k", "M", "X", "omega"])
def test_state_named_like_a_system_symbol_is_refused(capsys, state):
    # before: a state V gave k_c = 1.929e8 (merged with the driving velocity), u "no Hopf point"
    mu = DIETERICH_MU.replace("phi", state)
    assert_refused(capsys, "linear", "x", "--mu", mu, "--state", f"{state}=1 - v*{state}/L", "--V", "1e-4",
                   needle="reserved")


@pytest.mark.parametrize("name", ["M", "g", "sigma", "V", "k", "omega", "d1_u_phi", "dp_u", "log", "phi_0"])
def test_parameter_named_like_a_system_symbol_is_refused(name):
    # before: M, g, sigma as law parameters ended in a SyntaxError traceback from generated code
    with pytest.raises(InputError, match="reserved"):
        FrictionLaw.from_strings("x", mu=DIETERICH_MU + f" + 0.001*{name}", state={"phi": DIETERICH_RATE},
                                 params={name: 1.0})


@pytest.mark.parametrize("state", ["x0", "lam", "state"])
def test_result_does_not_depend_on_the_names_chosen(state):
    # the same law under another state name: identical coefficients (names never reach the numbers)
    ref = derive(get_law("dieterich"), ["kc", "Lambda"]).evaluate([1e-4, 1e-3], None, ["kc", "Lambda"])
    law = FrictionLaw.from_strings("x", mu=DIETERICH_MU.replace("phi", state),
                                   state={state: DIETERICH_RATE.replace("phi", state)})
    got = derive(law, ["kc", "Lambda"]).evaluate([1e-4, 1e-3], None, ["kc", "Lambda"])
    for key in ("kc", "Lambda"):
        np.testing.assert_allclose(got[key], ref[key], rtol=1e-12)


def test_cli_param_V_and_k_are_explained(capsys):
    assert_refused(capsys, "linear", "dieterich", "--V", "1e-4", "--param", "V=1e-3", needle="give it with --V")
    assert_refused(capsys, "linear", "dieterich", "--V", "1e-4", "--param", "k=1", needle="bifurcation parameter")


# --- 2. complex-valued laws -------------------------------------------------------------
@pytest.mark.parametrize("extra", ["sqrt(-v)", "log(-1)", "log(-v)", "(-v)**0.5", "(-1)**(1/3)"])
def test_law_complex_for_positive_slip_rate_is_refused(capsys, extra):
    # before: sqrt(-v) parsed, the compiled code dropped the imaginary part, Dieterich became "supercritical"
    assert_refused(capsys, "derive", "x", "--mu", f"{DIETERICH_MU} + 0.001*{extra}", "--state",
                   f"phi={DIETERICH_RATE}", "--V", "1e-4", needle="not real")


def test_law_complex_at_steady_state_is_refused_numerically():
    # sqrt(c - v) is real only for v < c: sympy cannot decide, the steady-state check must
    law = FrictionLaw.from_strings("x", mu=DIETERICH_MU + " + 0.001*sqrt(c - v)", state={"phi": DIETERICH_RATE},
                                   params={"c": 1e-5})
    hl = HopfLine(SpringBlock(law))
    assert hl.point(1e-6).status == "ok"          # real there: an answer
    with pytest.raises(DomainError, match="real"):
        hl.point(1e-4)
    with pytest.raises(DomainError):
        derive(law, ["Lambda"]).evaluate([1e-4], None, ["Lambda"])


# --- 3. steady state without a closed form ------------------------------------------------
def _without_closed_form(law: FrictionLaw) -> FrictionLaw:
    """The same law with its closed-form steady state withheld: the numeric route must be used."""
    bare = FrictionLaw(law.name, law.mu, law.states, law.rates, law.parameters, law.source)
    bare.__dict__["steady_state_closed_form"] = None      # as when sympy finds none in its budget
    return bare


@pytest.mark.parametrize("name", ["dieterich", "two-state-dieterich"])
def test_numeric_steady_state_route_matches_the_closed_form(name):
    # an independent route: φ_ss by root finding + the n-state Hopf polynomial, against the closed
    # forms; φ_ss is found to ~1e-15, and k_c, Λ inherit it through well-conditioned formulas
    # (the 1e-8 tolerance leaves room for the Hopf-polynomial roots and longdouble screening)
    law = get_law(name)
    Vs = [1e-5, 1e-4, 3e-4]
    names = ["kc", "omega_c", "Gamma_bar", "Lambda"]
    ref = derive(law, names).evaluate(Vs, None, names)
    got = derive(_without_closed_form(law), names).evaluate(Vs, None, names)
    for key in names:
        np.testing.assert_allclose(got[key], ref[key], rtol=1e-8, equal_nan=True)


def test_law_without_closed_form_runs_on_the_cli(capsys):
    # before: NameError: name 'phi_0' is not defined (exit 1) in linear, derive and verify
    code, out, err = run(capsys, "derive", "x", "--mu", DIETERICH_MU, "--state",
                         "phi=1 - v*phi/L - 0.01*tanh(phi)", "--V", "1e-4", "--json")
    assert code == 0, err
    pt = json.loads(out)["points"][0]
    law = FrictionLaw.from_strings("x", mu=DIETERICH_MU, state={"phi": "1 - v*phi/L - 0.01*tanh(phi)"})
    p = SpringBlock(law).resolve()
    phi = law.steady_state_values(np.array(1e-4), p)[0]
    # the steady state zeroes the rate (to round-off) ...
    assert abs(1 - 1e-4 * phi / p["L"] - 0.01 * math.tanh(phi)) < 1e-14
    # ... and at k = k_c the linearised block, X' = u, M u' = -kX - σ(F_v u + F_φ φ'),
    # φ' = G_v u + G_φ φ' (G: derivatives of dφ/dt), has the pair ±iω_c: an independent eigenvalue check
    sig, a, b, L, V, M = p["sigma"], p["a"], p["b"], p["L"], 1e-4, p["M"]
    F_v, F_phi = a / V, b / phi
    G_v, G_phi = -phi / L, -V / L - 0.01 / math.cosh(phi) ** 2
    assert pt["status"] == "ok" and pt["kc"] > 0 and np.isfinite(pt["Lambda"])
    k = pt["kc"]
    J = np.array([[0, 1, 0], [-k / M, -sig * F_v / M, -sig * F_phi / M], [0, G_v, G_phi]])
    ev = np.linalg.eigvals(J)
    crit = ev[np.argmin(abs(ev.real))]
    assert abs(crit.real) < 1e-8 * abs(crit) and abs(abs(crit.imag) - pt["omega_c"]) < 1e-8 * pt["omega_c"]


def test_several_positive_roots_the_stable_one_is_chosen():
    # (φ − L/v)(φ − 2L/v) = 0: φ = L/v is stable at fixed v (∂rate/∂φ < 0), 2L/v is not
    law = FrictionLaw.from_strings("two-roots", mu=DIETERICH_MU, state={"phi": "(v/L)**2*(phi - L/v)*(phi - 2*L/v)"})
    p = SpringBlock(law).resolve()
    Vs = np.array([1e-5, 1e-4])
    np.testing.assert_allclose(law.steady_state_values(Vs, p)[0], p["L"] / Vs, rtol=1e-13)
    # and the whole chain equals the same law with that steady state declared
    L = TABLE1["L"].symbol
    declared = FrictionLaw(law.name, law.mu, law.states, law.rates, law.parameters, steady_state=(L / v,))
    got = derive(law, ["kc", "Gamma_bar"]).evaluate(Vs, None, ["kc", "Gamma_bar"])
    ref = derive(declared, ["kc", "Gamma_bar"]).evaluate(Vs, None, ["kc", "Gamma_bar"])
    for key in ("kc", "Gamma_bar"):
        np.testing.assert_allclose(got[key], ref[key], rtol=1e-8)


def test_no_stable_steady_state_is_a_named_error():
    law = FrictionLaw.from_strings("unstable", mu=DIETERICH_MU, state={"phi": "v*phi/L - 1"})
    with pytest.raises(DomainError, match="stable"):
        HopfLine(SpringBlock(law)).point(1e-4)


def test_symbolic_work_is_abandoned_at_its_budget():
    from landau.support.budget import run_bounded

    t0 = time.perf_counter()
    with pytest.raises(BudgetError, match="within 0.5 s"):
        run_bounded(time.sleep, (30,), seconds=0.5, what="a sleep")
    assert time.perf_counter() - t0 < 10
    assert run_bounded(sp.factor, (sp.Symbol("x") ** 2 - 1,), seconds=30, what="a factorisation") == \
        (sp.Symbol("x") - 1) * (sp.Symbol("x") + 1)


# --- 4. parser resource attacks ------------------------------------------------------------
ATTACKS = [
    "10**10**10", "exp(2.0**1e20)", "v**(10**4400)", "+".join(["v"] * 1000), "v" + "+v" * 60_000,
    "**".join(["v"] * 3000), "(" * 1000 + "v" + ")" * 1000, "1e400*v", "0/0 + v", "v/0", "log(0)*v",
    "9" * 5000 + "*v", "exp(exp(exp(exp(10))))*v", "sinh(1e6)*v", "v**1e6", "v**-500", "2**v**2**300",
]


@pytest.mark.parametrize("text", ATTACKS, ids=range(len(ATTACKS)))
def test_parser_attack_is_a_parse_error_in_bounded_time(text):
    t0 = time.perf_counter()
    with pytest.raises(ParseError):
        parse_expression(text, {"v": v}, what="mu")
    assert time.perf_counter() - t0 < 5


@pytest.mark.parametrize("text", [b"\xff\xfev", "v\udcff", "v\x00", b"v+\x80"])
def test_parser_refuses_undecodable_text(text):
    with pytest.raises(ParseError):
        parse_expression(text, {"v": v}, what="mu")


def test_gmp_overflow_attack_does_not_abort_the_interpreter():
    # before: exp(29**(7e12)) aborted Python (gmp overflow, exit 134): run it in a child
    code = ("from landau.laws.parse import parse_expression; from landau.errors import ParseError\n"
            "import sympy as sp\n"
            "try:\n parse_expression('exp(29**(7e12))', {'v': sp.Symbol('v', positive=True)})\n"
            "except ParseError as e:\n print('refused', e)\n")
    res = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=120)
    assert res.returncode == 0 and res.stdout.startswith("refused"), (res.returncode, res.stderr[-500:])


def test_length_is_checked_before_parsing(monkeypatch):
    import ast

    calls = []
    monkeypatch.setattr(ast, "parse", lambda *a, **k: calls.append(a) or (_ for _ in ()).throw(AssertionError))
    with pytest.raises(ParseError, match="too long"):
        FrictionLaw.from_strings("x", mu="v" * 200_000, state={"phi": DIETERICH_RATE})
    assert calls == []


# --- issue §7: errors a user meets ------------------------------------------------------------
def test_negative_eps2_is_read_as_a_value(capsys):
    assert_refused(capsys, "verify", "dieterich", "--V", "1e-4", "--eps2", "-1e-3", needle="--eps2")


def test_verify_refuses_zero_mass(capsys):
    assert_refused(capsys, "verify", "dieterich", "--V", "1e-4", "--param", "M=0", needle="M > 0")


def test_derive_and_spring_block_accept_a_law_or_its_name():
    ref = derive(SpringBlock(get_law("dieterich")), ["Gamma_bar"]).evaluate([1e-4], None, ["Gamma_bar"])["Gamma_bar"]
    for arg in (get_law("dieterich"), "dieterich", SpringBlock("dieterich")):
        got = derive(arg, ["Gamma_bar"]).evaluate([1e-4], None, ["Gamma_bar"])["Gamma_bar"]
        np.testing.assert_array_equal(got, ref)


def test_evaluate_takes_one_name_as_a_string():
    d = derive("dieterich", ["Gamma_bar"])
    got = d.evaluate([1e-4, 1e-3], None, "Gamma_bar")
    assert set(got) >= {"Gamma_bar"} and not any(len(k) == 1 and k not in ("V",) for k in got)
    np.testing.assert_array_equal(got["Gamma_bar"], d.evaluate([1e-4, 1e-3], None, ["Gamma_bar"])["Gamma_bar"])


def test_dynamical_system_accepts_plain_numbers():
    from landau import hopf_normal_form

    x, y, p, c = sp.symbols("x y p c", real=True)
    # normal form of the Hopf bifurcation: ẋ = px − y − cx(x²+y²), ẏ = x + py − cy(x²+y²), p_c = 0
    rhs = (p * x - y - c * x * (x ** 2 + y ** 2), x + p * y - c * y * (x ** 2 + y ** 2))
    plain = DynamicalSystem("nf", (x, y), rhs, (1, 1), p, (0, 0))
    exact = DynamicalSystem("nf", (x, y), rhs, (sp.Integer(1), sp.Integer(1)), p, (sp.Integer(0), sp.Integer(0)))
    a = hopf_normal_form(plain, {"c": 1.0}, (-0.5, 0.4))
    b = hopf_normal_form(exact, {"c": 1.0}, (-0.5, 0.4))
    assert a.p_c == pytest.approx(0.0, abs=1e-12) and a.criticality == "supercritical" == b.criticality
    with pytest.raises(InputError):
        DynamicalSystem("nf", (x, y), rhs, ("1", 1), p, (0, 0))


def test_did_you_mean(capsys):
    assert_refused(capsys, "derve", "dieterich", needle="did you mean 'derive'")
    assert_refused(capsys, "linear", "dieterch", "--V", "1e-4", needle="did you mean 'dieterich'")


def test_no_hopf_message_gives_the_weakening_range(capsys):
    code, out, _ = run(capsys, "linear", "spinodal", "--V", "1e-2", "--json")
    text = json.loads(out)["points"][0]["velocity_weakening"]
    # the spinodal law weakens between its extrema V_M ~ 2.7e-8 and V_m ~ 3.9e-4 m/s (Putelat et al. 2010
    # Sec. 4; tests/vw_ranges.py computes them at 50 digits); the grid reads them to within 1/20 decade
    lo, hi = (float(x) for x in text.split("from ")[1].split(" m/s")[0].split(" to "))
    from vw_ranges import vw_range

    V_lo, V_hi, _ = vw_range("spinodal")
    assert abs(math.log10(lo / V_lo)) < 0.1 and abs(math.log10(hi / V_hi)) < 0.1
    code, out, err = run(capsys, "linear", "x", "--mu", "a_v + a*log(v/V_s) - b*log(V_s*phi/L)", "--state",
                         f"phi={DIETERICH_RATE}", "--V", "1e-4")
    assert code == 0 and "velocity strengthening" in out


# --- medium items -------------------------------------------------------------------------------
def test_latex_budget_is_a_named_error_with_a_hint(capsys, monkeypatch, tmp_path):
    import landau.cli.derive as cmd

    monkeypatch.setattr(cmd, "LATEX_SECONDS", 0.05)
    code, out, err = run(capsys, "derive", "modified-dieterich", "--latex", str(tmp_path / "m.tex"))
    assert code == 1 and "BudgetError" in err and "--quantities" in err and err.count("\n") == 1
    assert not any(tmp_path.iterdir())


@pytest.mark.parametrize("target", ["dir", "file-parent", "empty"])
def test_output_errors_are_one_line(capsys, tmp_path, target):
    blocker = tmp_path / "plain"
    blocker.write_text("x")
    path = {"dir": str(tmp_path), "file-parent": str(blocker / "out.tex"), "empty": ""}[target]
    assert_refused(capsys, "linear", "dieterich", "--V", "1e-4", "--latex", path)


def test_long_legal_name_is_written(capsys, tmp_path):
    path = tmp_path / ("a" * 251 + ".tex")       # 255 bytes: legal; the temporary must fit too
    code, _, err = run(capsys, "linear", "dieterich", "--V", "1e-4", "--latex", str(path))
    assert code == 0, err and path.read_text().startswith(r"\documentclass")


@pytest.mark.parametrize("rng", ["1e-300:1e300", "1e-9:inf", "nan:1", "1:1", "2:1"])
def test_overflowing_ranges_are_refused(capsys, rng):
    assert_refused(capsys, "derive", "dieterich", "--V", "1e-4", "--codim2", rng, needle="--codim2")


def test_atomic_write_keeps_links_modes_and_leaves_no_temporary(tmp_path):
    from landau.support.io import atomic_write, atomic_write_text

    real = tmp_path / "real.txt"
    real.write_text("old")
    os.chmod(real, 0o600)
    link = tmp_path / "link.txt"
    link.symlink_to(real)
    atomic_write_text(link, "new")
    assert link.is_symlink() and real.read_text() == "new"
    assert stat.S_IMODE(real.stat().st_mode) == 0o600
    def boom(fh):
        fh.write("partial")
        raise RuntimeError("killed while rendering")
    with pytest.raises(RuntimeError):
        atomic_write(tmp_path / "x.txt", boom)
    assert sorted(p.name for p in tmp_path.iterdir()) == ["link.txt", "real.txt"]
    with pytest.raises(OutputError):
        atomic_write_text("/dev/null", "x")


def test_law_name_cannot_inject_latex(capsys, tmp_path):
    path = tmp_path / "x.tex"
    name = r"x}\input{/etc/passwd}"
    code, _, err = run(capsys, "linear", name, "--mu", DIETERICH_MU, "--state", f"phi={DIETERICH_RATE}",
                       "--V", "1e-4", "--latex", str(path))
    assert code == 0, err
    text = path.read_text()
    assert r"\input{" not in text and r"x\}\textbackslash{}input\{/etc/passwd\}" in text


# --- low items -------------------------------------------------------------------------------------
@pytest.mark.parametrize("argv, needle", [
    (["--state", "phi=1-v*phi/L", "--state", "phi=1-v*phi/L"], "twice"),
    (["--state", "phi=1-v*phi/L", "--param", "c=1", "--param", "c=2"], "twice"),
    (["--state", "phi=1-v*phi/L", "--latex", ""], "empty"),
    (["--state", "phi=1-v*phi/L", "--quantities", ""], "no quantity"),
])
def test_silently_accepted_inputs_are_refused(capsys, argv, needle):
    assert_refused(capsys, "derive", "x", "--mu", DIETERICH_MU, "--V", "1e-4", *argv, needle=needle)


@pytest.mark.parametrize("mu", ["0/0*v + a", "1e400*v", "a*log(v) + 0*log(0)"])
def test_non_finite_numbers_are_parse_errors_not_missing_v(mu):
    with pytest.raises(ParseError, match="finite"):
        FrictionLaw.from_strings("x", mu=mu, state={"phi": DIETERICH_RATE})


def test_undefined_function_through_the_python_api_is_refused():
    phi = sp.Symbol("phi", positive=True)
    f = sp.Function("__import__('os').system")
    with pytest.raises(InputError, match="function"):
        FrictionLaw("x", f(v) + sp.log(v), (phi,), (1 - v * phi,))


def test_ctrl_c_is_one_line(capsys, monkeypatch):
    import landau.cli.laws as cmd

    def interrupted(args):
        raise KeyboardInterrupt
    monkeypatch.setattr(cmd, "run", interrupted)
    code, out, err = run(capsys, "laws")
    assert code == 130 and err == "landau: interrupted\n"


@pytest.mark.parametrize("L", ["1e-300", "1e300"])
def test_overflow_at_extreme_parameters_is_not_reported_as_no_hopf(capsys, L):
    # before: k_c = nan (overflow) or omega_c^2 = -0 (underflow) read as "no Hopf bifurcation", exit 0;
    # Dieterich is velocity weakening at every V, so a Hopf point exists in exact arithmetic
    code, out, err = run(capsys, "linear", "dieterich", "--V", "1e-4", "--param", f"L={L}")
    assert code == 2 and "floating-point range" in err and err.count("\n") == 1
