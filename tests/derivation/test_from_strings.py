"""``DynamicalSystem.from_strings``: systems written as strings, against closed forms and an
independent computation of the first Lyapunov coefficient."""

from __future__ import annotations

import numpy as np
import pytest
import sympy as sp

from landau.derivation.general import hopf_normal_form
from landau.errors import InputError, ParseError
from landau.systems.system import DynamicalSystem

BRUSSELATOR = {"x": "a - (b + 1)*x + x^2*y", "y": "b*x - x^2*y"}


def brusselator_c1(a: float) -> complex:
    """Kuznetsov's c₁ of the Brusselator at b = 1 + a² (eq. 3.20), written out in numpy.

    About (a, b/a): the quadratic part of ±x²y is (b/a)ξ² + 2aξη, the cubic ξ²η, in the
    direction (1, −1)."""
    b = 1 + a * a
    A = np.array([[b - 1, a * a], [-b, -a * a]])
    w = a
    lam, vr = np.linalg.eig(A)
    i = int(np.argmax(lam.imag))
    q = vr[:, i] / np.linalg.norm(vr[:, i])
    lam_l, vl = np.linalg.eig(A.T)
    j = int(np.argmin(np.abs(lam_l + 1j * w)))
    p = vl[:, j] / np.vdot(vl[:, j], q).conj()          # <p, q> = conj(p).q = 1
    d = np.array([1.0, -1.0])
    B = lambda u, v: d * (2 * (b / a) * u[0] * v[0] + 2 * a * (u[0] * v[1] + u[1] * v[0]))
    C = lambda u, v, z: d * 2 * (u[0] * v[0] * z[1] + u[0] * v[1] * z[0] + u[1] * v[0] * z[0])
    qb = q.conj()
    h11 = np.linalg.solve(A, B(q, qb))                   # A⁻¹B(q, q̄)
    h20 = np.linalg.solve(2j * w * np.eye(2) - A, B(q, q))
    g = C(q, q, qb) - 2 * B(q, h11) + B(qb, h20)
    return 0.5 * np.vdot(p, g)


@pytest.mark.parametrize("a", [0.7, 1.5, 3.0])
def test_brusselator_hopf_point_and_l1(a):
    s = DynamicalSystem.from_strings(BRUSSELATOR, "b", {"a": a}, equilibrium={"x": "a", "y": "b/a"},
                                     name="brusselator")
    r = hopf_normal_form(s, s.defaults, (1 + a * a - 0.5, 1 + a * a + 0.7))
    assert r.p_c == pytest.approx(1 + a * a, rel=1e-13)        # closed form b_c = 1 + a²
    assert r.omega_c == pytest.approx(a, rel=1e-13)            # ω_c = a
    c1 = brusselator_c1(a)
    assert r.l1 == pytest.approx(c1.real / a, rel=1e-9)         # float64 numpy vs 50 digits
    assert r.criticality == "supercritical"
    assert r.extra["Lambda_bound"] <= 1.2e-16 * abs(r.Lambda)


def test_rayleigh_closed_form():
    # x'' - (p - x'^2) x' + x = 0: dr/dt = p r/2 - 3 r^3/8 (averaging), so with x = A e^{it} + c.c.
    # a = 1/2, Lambda = 2 Re b = -3, and Kuznetsov's l1 = -3/4 (<q,q> = 1, omega = 1)
    s = DynamicalSystem.from_strings({"x": "y", "y": "-x + p*y - y^3"}, "p", guess={"x": 0.1, "y": -0.1})
    r = hopf_normal_form(s, None, (-1.0, 1.0))
    assert r.p_c == pytest.approx(0.0, abs=1e-14)
    assert r.omega_c == pytest.approx(1.0, rel=1e-14)
    assert r.dlambda_dp == pytest.approx(0.5, rel=1e-13)
    assert r.Lambda == pytest.approx(-3.0, rel=1e-13)
    assert r.l1 == pytest.approx(-0.75, rel=1e-13)


def test_same_result_as_a_hand_built_system():
    x, y, a, b = sp.symbols("x y a b", real=True)
    hand = DynamicalSystem("brusselator", (x, y), (a - (b + 1) * x + x ** 2 * y, b * x - x ** 2 * y), (1, 1), b,
                           (a, b / a), defaults={"a": 1.5})
    s = DynamicalSystem.from_strings(BRUSSELATOR, "b", {"a": 1.5}, equilibrium={"x": "a", "y": "b/a"})
    r1, r2 = hopf_normal_form(hand, {"a": 1.5}, (2, 4)), hopf_normal_form(s, s.defaults, (2, 4))
    assert (r1.p_c, r1.omega_c, r1.Lambda, r1.chi, r1.l1) == (r2.p_c, r2.omega_c, r2.Lambda, r2.chi, r2.l1)


def test_mass_entries_and_guess():
    # 2 x' = ... halves the growth rate and the frequency: p_c unchanged, omega_c = 1/2
    s = DynamicalSystem.from_strings({"x": "y", "y": "-x + p*y - y^3"}, "p", {"m": 2.0}, guess={},
                                     mass={"x": "m", "y": "m"})
    r = hopf_normal_form(s, s.defaults, (-1.0, 1.0))
    assert r.omega_c == pytest.approx(0.5, rel=1e-13)
    assert r.dlambda_dp == pytest.approx(0.25, rel=1e-12)


@pytest.mark.parametrize("kwargs, message", [
    (dict(rhs={"x": "__import__('os').system('true')"}), "only plain function calls"),
    (dict(rhs={"x": "__import__('os')"}), "unknown function '__import__'"),
    (dict(rhs={"x": "x.real"}), "attribute access"),
    (dict(rhs={"x": "q*x"}), "unknown symbol 'q'"),
    (dict(rhs={"exp": "p"}), "reserved"),
    (dict(rhs={"x__eq": "p"}), "reserved"),
    (dict(rhs={"x": "p*x"}, parameter="x"), "is a state"),
    (dict(rhs={"x": "p*x"}, params={"p": 1.0}), "Hopf parameter"),
    (dict(rhs={"x": "p*x"}, params={"c": float("nan")}), "finite"),
    (dict(rhs={"x": "p*x"}, guess=None), "either the equilibrium"),
    (dict(rhs={"x": "p*x"}, guess=None, equilibrium={"x": "x"}), "is a state"),
    (dict(rhs={"x": "p*x"}, guess={"z": 1.0}), "not a state"),
    (dict(rhs={"x": "p*x"}, mass={"x": "0"}), "every row is algebraic"),
    (dict(rhs={}), "at least one state"),
])
def test_bad_input_is_a_named_error(kwargs, message):
    args = dict(rhs={"x": "p*x"}, parameter="p", params=None, guess={})
    args.update(kwargs)
    with pytest.raises(InputError, match=message):
        DynamicalSystem.from_strings(args.pop("rhs"), args.pop("parameter"), args.pop("params"), **args)


def test_parse_errors_are_input_errors():
    with pytest.raises(ParseError):
        DynamicalSystem.from_strings({"x": "p*x +"}, "p", guess={})
