"""No hidden NaN or infinity: a value beyond float64's range is a named error, a representable
value whose float64 evaluation overflows or underflows is computed in a scaled form (mpmath,
unbounded exponent), and a float32 overflow never lets a float64 value pass unscreened."""

from __future__ import annotations

import json
import subprocess
import sys
import warnings

import mpmath
import numpy as np
import pytest

import landau
from landau.errors import DomainError


@pytest.fixture(scope="module")
def dieterich():
    return landau.derive("dieterich")


def _mp(d, V, params, names, dps=120):
    """An independent evaluation: the same formulas at 120 digits, Λ settled by the precision ladder."""
    p = d.block.resolve(params)
    point = {a.name: float(v) for a, v in zip(d.args[1:], d.block.argvals(V, p)[1:], strict=True)}
    with mpmath.workdps(dps):
        return d._evaluate_mp_checked(V, point, names)[0]


def test_overflow_beyond_float64_is_named(dieterich):
    # k_c = 4.2e321 N/m at b = 1e308: was "status ok" with k_c, Λ = null (exit 0)
    with pytest.raises(DomainError, match=r"kc = 4\.24493e\+321 N/m at V = 1 m/s .* b = 1e\+308"):
        dieterich.evaluate([1.0], {"b": 1e308}, ["kc", "omega_c", "Gamma_bar", "Lambda", "C"])


def test_cli_exit_2_names_the_quantity():
    out = subprocess.run([sys.executable, "-m", "landau", "derive", "dieterich", "--param", "b=1e308", "--V", "1",
                          "--json"], capture_output=True, text=True, timeout=300)
    assert out.returncode == 2, out.stdout
    assert "kc" in out.stderr and "b = 1e+308" in out.stderr and "float64 range" in out.stderr


def test_representable_kc_whose_float64_formula_overflows(dieterich):
    # σ = 1e300: k_c = σ(b − a)/L = 1.5556e304 N/m exists; the float64 closed form gave NaN ("no Hopf point")
    t = dieterich.evaluate([1.0, 1e-3], {"sigma": 1e300}, ["kc", "omega_c", "Gamma_bar", "Lambda", "C"])
    assert t["kc"] == pytest.approx(1e300 * (0.0489 - 0.0349) / 9e-7, rel=1e-12)
    for i, V in enumerate((1.0, 1e-3)):
        ref = _mp(dieterich, V, {"sigma": 1e300}, ["Gamma_bar", "Lambda", "C"])
        for n in ("Gamma_bar", "Lambda", "C"):
            assert t[n][i] == pytest.approx(float(ref[n]), rel=1e-10), (n, V)


def test_C_of_an_underflowed_growth_rate(dieterich):
    # M = 1e200: Γ̄ = 1.2e-413 underflows, C = 2 sqrt(2Γ̄/|Λ|) ≈ 2.2e-112 does not (was printed as 0.0)
    with warnings.catch_warnings():
        warnings.simplefilter("error", RuntimeWarning)   # no overflow warning leaks from the screen
        t = dieterich.evaluate([1.0], {"M": 1e200}, ["kc", "omega_c", "Gamma_bar", "Lambda", "C"])
    ref = _mp(dieterich, 1.0, {"M": 1e200}, ["Gamma_bar", "Lambda", "C"])
    assert float(ref["C"]) == pytest.approx(2.2218599533468551e-112, rel=1e-12)
    assert t["C"][0] == pytest.approx(float(ref["C"]), rel=1e-10)
    assert t["Gamma_bar"][0] == 0.0 and t["Lambda"][0] < 0


def test_float32_overflow_does_not_pass_a_float64_value(dieterich):
    # M = 1e-300: float32 Λ overflows to -inf, float64 Λ = 31 (cancellation); |31 − ∞| ≤ rel·∞ passed it
    t = dieterich.evaluate([1.0, 1e-3], {"M": 1e-300}, ["Lambda"])
    for i, V in enumerate((1.0, 1e-3)):
        ref = float(_mp(dieterich, V, {"M": 1e-300}, ["Lambda"])["Lambda"])
        assert t["Lambda"][i] == pytest.approx(ref, rel=1e-10)


def test_every_value_finite_where_a_hopf_point_exists(dieterich):
    t = dieterich.evaluate(np.logspace(-6, 0, 7), {"M": 1e200}, ["kc", "omega_c", "Gamma_bar", "Lambda", "C"])
    for n in ("kc", "omega_c", "Gamma_bar", "Lambda", "C"):
        assert np.all(np.isfinite(t[n])), n
    assert np.all(t["C"] > 0)      # no representable C underflows to 0 (C ≈ 2e-112 … 2e-109 here)
    assert json.dumps(t.rows(), allow_nan=False)


def test_a_hopf_result_never_carries_nan():
    from landau.derivation.hopf import HopfResult
    from landau.errors import SingularPointError

    with pytest.raises(SingularPointError, match=r"Lambda = nan is not finite at p = 1 \(a = 1e\+308\)"):
        HopfResult("s", "p", 1.0, 1.0, (0.0,), complex(1, 0), float("nan"), 0.0, params={"a": 1e308})
    with pytest.raises(SingularPointError, match="c1 = "):
        HopfResult("s", "p", 1.0, 1.0, (0.0,), complex(1, 0), -1.0, 0.0, c1=complex(float("inf"), 0))
    assert HopfResult("s", "p", 1.0, 1.0, (0.0,), complex(1, 0), -1.0, 0.0).Lambda == -1.0


def test_tiny_mass_settles_beyond_550_digits(dieterich):
    # Λ ∝ M: at M = 1e-308 its terms cancel over ~315 orders, beyond the 550-digit ladder (was: Λ = 0,
    # "degenerate", C = null); the value follows Λ(M = 1e-300)·1e-8 (Λ linear in M as M → 0)
    t = dieterich.evaluate([1.0], {"M": 1e-308}, ["Gamma_bar", "Lambda", "C"])
    ref = dieterich.evaluate([1.0], {"M": 1e-300}, ["Lambda"])["Lambda"][0] * 1e-8
    assert not t["degenerate"][0]
    assert t["Lambda"][0] == pytest.approx(ref, rel=1e-9)
    assert np.isfinite(t["C"][0])


def test_C_beyond_float64_is_named(dieterich):
    # L = 1e300: Λ = 4.7e-1219 underflows, C = 4.6e606 overflows (was: "degenerate", C = null)
    with pytest.raises(DomainError, match=r"C = 4\.55131e\+606 .* L = 1e\+300"):
        dieterich.evaluate([1e-6], {"L": 1e300}, ["Gamma_bar", "Lambda", "C"])
