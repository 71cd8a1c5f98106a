"""landau.check and landau.testing: one verification entry point for any law or system."""

import pathlib
import runpy

import numpy as np
import pytest
import sympy as sp

from landau import Criticality, DynamicalSystem, Verdict, check
from landau.errors import InputError
from landau.laws import get_law
from landau.testing import assert_prediction
from landau.verify.springblock.checks import predict, subcritical_check, supercritical_check

ROOT = pathlib.Path(__file__).resolve().parents[2]


def _polar_normal_form(a: float, b: float) -> DynamicalSystem:
    """ż = (μ + i)z + a z|z|² + b z|z|⁴ in Cartesian coordinates (Kuznetsov 2004, eq. 8.19 with ω = 1)."""
    x, y, mu, sa, sb = sp.symbols("x y mu a b", real=True)
    r2 = x * x + y * y
    g = sa * r2 + sb * r2 * r2
    return DynamicalSystem("polar-normal-form", (x, y), (mu * x - y + g * x, x + mu * y + g * y),
                           (sp.Integer(1), sp.Integer(1)), mu, (sp.Integer(0), sp.Integer(0)),
                           defaults={"a": a, "b": b})


def test_general_system_supercritical_cycle_is_exact():
    """a = −1, b = 0: the cycle has radius sqrt(μ) exactly, the cubic amplitude equation is exact, so the
    simulated half peak-to-peak x equals C·sqrt(μ) to the shooting tolerance (1e-6 relative)."""
    r = check(_polar_normal_form(-1.0, 0.0), eps2=1e-2, bracket=(-0.5, 0.5))
    assert r.criticality == Criticality.SUPERCRITICAL and r.verdict is Verdict.AGREES
    assert r.amplitude_simulated == pytest.approx(np.sqrt(r.p), rel=1e-6)
    assert r.cycle_stable is True
    assert r.frequency_simulated == pytest.approx(1.0, rel=1e-6)


def test_general_system_subcritical_unstable_cycle():
    """a = +1, b = −1: the unstable cycle at μ < 0 has r² = (1 − sqrt(1 + 4μ))/2 (closed form); the cubic
    prediction sqrt(−μ) is off by O(ε²) (−0.5 % at μ = −0.01); the simulated cycle is unstable."""
    r = check(_polar_normal_form(1.0, -1.0), eps2=1e-2, bracket=(-0.5, 0.5))
    assert r.criticality == Criticality.SUBCRITICAL and r.p < 0
    exact = np.sqrt((1 - np.sqrt(1 + 4 * r.p)) / 2)
    assert r.amplitude_simulated == pytest.approx(exact, rel=1e-6)
    assert r.cycle_stable is False and r.verdict is Verdict.AGREES


def test_outside_validity_gives_largest_valid_eps2():
    """Ruina law, V = 1e-5 m/s, ε² = 1e-3: the predicted slip-rate swing is 2.96 V (measured by direct
    simulation to be full stick–slip), so the check reports the range of validity instead of a
    disagreement; the swing A·ω_c ∝ sqrt(ε²) equals V at ε² = 1e-3/2.96²."""
    r = check("ruina", V=1e-5, eps2=1e-3)
    assert r.verdict is Verdict.OUTSIDE_VALIDITY and not r.agrees
    pr = r.prediction
    swing = pr.amplitude(pr.p_c * (1 - 1e-3)) * pr.omega_c / 1e-5
    assert swing == pytest.approx(2.96, abs=0.01)
    assert r.eps2_max_valid == pytest.approx(1e-3 / swing ** 2, rel=1e-12)
    with pytest.raises(AssertionError, match="largest valid eps2"):
        assert_prediction("ruina", V=1e-5, eps2=1e-3)


def test_each_procedure_refuses_the_other_criticality():
    """Calling the supercritical procedure at a subcritical point is an input error, not agrees=False."""
    law = get_law("dieterich")
    assert predict(law, 1e-5).criticality == Criticality.SUBCRITICAL
    with pytest.raises(InputError, match="subcritical"):
        supercritical_check(law, 1e-5, 1e-3)
    with pytest.raises(InputError, match="supercritical"):
        subcritical_check(get_law("ruina"), 1e-4, 1e-3)


@pytest.mark.parametrize("kwargs,match", [
    (dict(target="ruina", V=1e-4, eps2=-1e-3), "eps2"),
    (dict(target="ruina", V=None), "needs the driving velocity"),
    (dict(target=3.0, V=1e-4), "FrictionLaw"),
])
def test_bad_arguments_are_named(kwargs, match):
    with pytest.raises(InputError, match=match):
        check(**kwargs)


def test_prediction_is_the_unified_hopf_result():
    """The verifier's prediction is a HopfResult in the spring–block convention: a = −Γ̄ + iΩ̄, so C and
    the frequency shift are the engine's eq. (23) numbers."""
    pr = predict(get_law("ruina"), 1e-4)
    assert pr.convention.name == "putelat2010" and pr.parameter == "k"
    assert pr.C == pytest.approx(2 * np.sqrt(2 * pr.Gamma_bar / abs(pr.Lambda)), rel=1e-15)
    k = pr.kc * (1 - 1e-3)
    assert pr.frequency(k) == pytest.approx(
        pr.omega_c - (pr.Omega_bar + pr.chi * pr.Gamma_bar / pr.Lambda) * (pr.kc - k), rel=1e-14)


def test_ci_example_file_runs_and_agrees():
    """The CI test file shown in the README for a user's own law runs and passes."""
    ns = runpy.run_path(str(ROOT / "examples" / "ci" / "test_my_law.py"))
    ns["test_my_law_amplitude_equation_holds"]()


def test_readme_shows_the_ci_example_file_verbatim():
    """The README's CI example is the very file the suite runs, so the two cannot drift apart."""
    example = (ROOT / "examples" / "ci" / "test_my_law.py").read_text(encoding="utf-8")
    readme = (ROOT / "README.md").read_text(encoding="utf-8")
    assert "```python\n" + example in readme


@pytest.mark.slow
def test_subcritical_point_within_one_percent_agrees():
    """Dieterich law, V = 1e-5 m/s, ε² = 1.6e-5 (subcritical, below V_D* ≈ 2.07e-4 m/s): the shot
    unstable cycle is within ~1 % of C·sqrt(k − k_c) (the O(ε²) remainder, cf. the fitted exponent 1 in
    tests/springblock/test_springblock_slow.py); bistability is shown and the bisection bracket, in the same measure
    (half peak-to-peak: the cycle's mean shift removed), contains the prediction — so the check agrees."""
    r = check("dieterich", V=1e-5, eps2=1.6e-5)
    assert r.criticality == Criticality.SUBCRITICAL
    assert abs(r.rel_error) <= 0.015
    assert r.bistable is True and r.detail["bracket_contains_prediction"] is True
    assert r.verdict is Verdict.AGREES


@pytest.mark.slow
def test_subcritical_bracket_uses_half_peak_to_peak():
    """Law (39), c = 3e-4, V = 1.2e-3 m/s: with the mean shift removed the bracket's midpoint is within
    1 % of the prediction (measured −0.30 %; the shot cycle +0.08 %)."""
    r = check("modified-dieterich", V=1.2e-3, eps2=1e-3, params={"c": 3e-4})
    assert r.verdict is Verdict.AGREES
    assert abs(r.detail["bracket_rel_error"]) <= 0.01 and abs(r.rel_error) <= 0.01


def test_general_system_with_a_full_mass_matrix():
    """E·ẏ = E·f with a full invertible E is the same flow as ẏ = f: the check simulates it through E⁻¹
    and finds the same exact cycle (radius sqrt(μ)) as without E."""
    base = _polar_normal_form(-1.0, 0.0)
    Em = sp.Matrix([[2, sp.Rational(1, 3)], [sp.Rational(-1, 2), 1]])
    mixed = DynamicalSystem("polar-normal-form-E", base.states, tuple(Em * sp.Matrix(base.rhs)), Em,
                            base.parameter, base.equilibrium, defaults=base.defaults)
    r = check(mixed, eps2=1e-2, bracket=(-0.5, 0.5))
    assert r.verdict is Verdict.AGREES
    assert r.amplitude_simulated == pytest.approx(np.sqrt(r.p), rel=1e-6)
