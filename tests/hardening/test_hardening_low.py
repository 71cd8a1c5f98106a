"""Bad input to the hybrid engine, the impact oscillator and the figures command is refused
with a named error; a tiny but genuine Landau coefficient is returned, not flagged degenerate."""

from __future__ import annotations

import json
import math
import threading

import numpy as np
import pytest

from landau.cli import main
from landau.errors import InputError, IntegratorError
from landau.verify.hybrid import Guard, HybridModel, Mode, Status, simulate

# ---------------------------------------------------------------- hybrid engine input

def _oscillator(rhs=None) -> HybridModel:
    """A harmonic oscillator with one section (x = 0 going down)."""
    rhs = rhs or (lambda t, y: np.array([y[1], -y[0]]))
    return HybridModel.from_modes(Mode("free", rhs, (Guard("x=0", lambda t, y: y[0]),)), name="osc")


def _bounded(call, seconds: float = 20.0):
    """Run ``call`` in a thread; fail (instead of hanging the suite) if it does not end."""
    box = {}

    def target():
        try:
            box["value"] = call()
        except BaseException as exc:  # noqa: BLE001 - handed back to the test
            box["error"] = exc

    th = threading.Thread(target=target, daemon=True)
    th.start()
    th.join(seconds)
    assert not th.is_alive(), f"did not end within {seconds} s"
    if "error" in box:
        raise box["error"]
    return box["value"]


def test_hybrid_nan_vector_field_at_start_is_named():
    model = _oscillator(lambda t, y: np.array([np.nan, -y[0]]))
    with pytest.raises(IntegratorError, match="not finite at the initial state"):
        _bounded(lambda: simulate(model, "free", [1.0, 0.0], (0.0, 1.0)))


def test_hybrid_inf_vector_field_at_start_is_named():
    model = _oscillator(lambda t, y: np.array([y[1], -np.inf]))
    with pytest.raises(IntegratorError, match="not finite at the initial state"):
        _bounded(lambda: simulate(model, "free", [1.0, 0.0], (0.0, 1.0)))


@pytest.mark.parametrize("y0", [[np.nan, 0.0], [1.0, np.inf], [1.0, -np.inf]])
def test_hybrid_non_finite_initial_state_is_refused(y0):
    with pytest.raises(InputError, match="initial state"):
        _bounded(lambda: simulate(_oscillator(), "free", y0, (0.0, 1.0)))


def test_hybrid_unknown_mode_names_the_known_modes():
    with pytest.raises(InputError, match=r"no mode 'flying'.*free"):
        simulate(_oscillator(), "flying", [1.0, 0.0], (0.0, 1.0))


@pytest.mark.parametrize("span", [(1.0, 0.0), (1.0, 1.0), (0.0, np.nan), (np.inf, 1.0), (0.0, np.inf)])
def test_hybrid_reversed_empty_or_non_finite_time_span_is_refused(span):
    with pytest.raises(InputError, match="time span"):
        _bounded(lambda: simulate(_oscillator(), "free", [1.0, 0.0], span))


def test_hybrid_valid_run_still_matches_closed_form():
    # x = cos t: the section x = 0 (going down) is first reached at t = π/2; the engine's
    # root tolerance is 1e-14 and the DOP853 tolerances 1e-10/1e-12, so 1e-8 is safe
    sol = simulate(_oscillator(), "free", [1.0, 0.0], (0.0, 2.0))
    assert sol.status is Status.FINISHED
    assert abs(sol.events[0].t - math.pi / 2) < 1e-8
    assert abs(sol.y_final[0] - math.cos(2.0)) < 1e-8


# ---------------------------------------------------------------- impact oscillator parameters

@pytest.mark.parametrize("kw, name", [({"mu": float("nan")}, "mu"), ({"mu": -0.1}, "mu"),
                                      ({"mu": float("inf")}, "mu"),
                                      ({"mu": 0.3, "eN": 1.5}, "eN"), ({"mu": 0.3, "eN": -0.2}, "eN"),
                                      ({"mu": 0.3, "eN": float("nan")}, "eN")])
def test_lancioni_build_refuses_parameters_out_of_domain(kw, name):
    from landau.verify.lancioni.model import build

    with pytest.raises(InputError, match=rf"\b{name}\b.*(>= 0|\[0, 1\])"):
        build(**kw)


@pytest.mark.parametrize("kw, name", [({"mu": float("nan")}, "mu"), ({"mu": -1.0}, "mu"),
                                      ({"eN": 2.0}, "eN"), ({"eN": -0.5}, "eN")])
def test_contact_model_refuses_parameters_out_of_domain(kw, name):
    # any ContactMechanics (here the point mass on a plane) is checked when the model is built
    from landau.verify.hybrid.contact import ContactModel, PointMassOnPlane

    with pytest.raises(InputError, match=rf"\b{name}\b"):
        ContactModel(PointMassOnPlane(**kw))


def test_lancioni_domain_edges_are_accepted():
    from landau.verify.lancioni.model import build

    assert build(0.0, 0.0).mech.mu == 0.0 and build(0.4, 1.0).mech.eN == 1.0


# ---------------------------------------------------------------- figures --only ""

@pytest.mark.parametrize("only", ["", " ", ",", " , "])
def test_figures_empty_only_exits_2(capsys, only, tmp_path):
    code = main(["figures", "lancioni", "--only", only, "--out", str(tmp_path), "--json"])
    out, err = capsys.readouterr()
    assert code == 2 and json.loads(out) == {"error": err.strip().removeprefix("landau: error: "),
                                            "kind": "InputError", "exit_code": 2}
    assert len(err.strip().splitlines()) == 1 and "--only" in err
    assert not any(tmp_path.iterdir())


# ---------------------------------------------------------------- tiny but non-zero Λ

def test_tiny_inertia_lambda_is_returned_not_degenerate():
    """Λ_D is proportional to M (Putelat, Dawes & Willis 2010, eq. 33: Λ_D = M·(…), exactly):
    Λ(M = 1e-50) = 1e-30·Λ(M = 1e-20), a tiny number with a definite sign, not the vanishing
    quasi-static value."""
    from landau.derivation.multiscale import derive
    from landau.laws import get_law
    from landau.systems.system import SpringBlock

    d = derive(SpringBlock(get_law("dieterich")), ["Lambda"])
    Vs = [1e-5, 1e-3]
    ref = d.evaluate(Vs, {"M": 1e-20}, ["Lambda"])  # 1e-20 is already settled in float64 / mpmath
    tiny = d.evaluate(Vs, {"M": 1e-50}, ["Lambda"])
    assert not tiny["degenerate"].any()
    # linearity in M: the independent value 1e-30·Λ(M = 1e-20); both are good to ~1e-10
    np.testing.assert_allclose(tiny["Lambda"], 1e-30 * ref["Lambda"], rtol=1e-9)
    # and a 120-digit evaluation (the terms are O(1e13), so 120 digits leave ~60 exact ones)
    for V0, lam in zip(Vs, tiny["Lambda"], strict=True):
        exact = d.evaluate_mp(V0, {"M": 1e-50}, ["Lambda"], dps=120)["Lambda"]
        assert abs(lam - float(exact)) <= 1e-10 * abs(float(exact))
    rows = tiny.rows()
    assert [r["criticality"] for r in rows] == [r["criticality"] for r in ref.rows()]
    assert all(r["criticality"] != "degenerate" for r in rows)
    # the exactly vanishing quasi-static case stays degenerate
    zero = d.evaluate(Vs, {"M": 0.0}, ["Lambda"])
    assert list(zero["Lambda"]) == [0.0, 0.0] and zero["degenerate"].all()


def test_tiny_inertia_lambda_on_the_cli(capsys):
    # the same through `landau derive`: Λ ∝ M, so Λ(M = 1e-50) = 1e-30·Λ(M = 1e-20) with its sign
    import json

    docs = {}
    for m in ("1e-50", "1e-20"):
        code = main(["derive", "dieterich", "--V", "1e-5", "--param", f"M={m}", "--json"])
        out, err = capsys.readouterr()
        assert code == 0, err
        docs[m] = json.loads(out)["points"][0]
    tiny, ref = docs["1e-50"], docs["1e-20"]
    assert tiny["criticality"] == ref["criticality"] == "subcritical"
    assert abs(tiny["Lambda"] - 1e-30 * ref["Lambda"]) <= 1e-9 * abs(1e-30 * ref["Lambda"])
