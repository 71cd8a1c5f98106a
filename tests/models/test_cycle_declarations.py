"""The ``cycles`` declarations: each model's CycleProblem against its own equations and Hopf result.

Independent computations written for the test: the Jacobian by central differences of ``rhs``;
the critical eigenpair checked as J(y₀; p_c) q = iω_c q; the spring–block's right-hand side
against eq. (4) of Putelat, Dawes & Willis (2010) written out here for the Dieterich law with
radiation damping η (Rice 1993).
"""

from __future__ import annotations

import numpy as np
import pytest

from landau.errors import InputError
from landau.laws import get_law
from landau.models import Setup, get


def _fd_jac(rhs, y, p, scales):
    n = y.size
    J = np.empty((n, n))
    for j in range(n):
        h = 1e-6 * scales[j]
        e = np.zeros(n)
        e[j] = h
        J[:, j] = (rhs(y + e, p) - rhs(y - e, p)) / (2 * h)
    return J


def _checks(pr, rng):
    h = pr.hopf
    y0 = h.equilibrium
    # the equilibrium is one: |f(y0; p_c)| at round-off relative to the field's scale along the mode
    Jc = pr.jac(y0, h.p_c)
    size = np.abs(Jc).max() * np.abs(pr.scales).max()
    assert np.abs(pr.rhs(y0, h.p_c)).max() <= 1e-9 * size
    # the critical eigenpair, normalised on the measured state
    assert h.eigenvector[pr.measure] == pytest.approx(1.0)
    resid = np.abs(Jc @ h.eigenvector - 1j * h.omega * h.eigenvector).max()
    assert resid <= 1e-9 * h.omega * np.abs(h.eigenvector).max()
    # vectorised calls agree with column-by-column calls, and the Jacobian with central differences
    Y = y0[:, None] + 0.02 * pr.scales[:, None] * rng.standard_normal((pr.n, 4))
    F, JJ = pr.rhs(Y, h.p_c), pr.jac(Y, h.p_c)
    assert F.shape == (pr.n, 4) and JJ.shape == (pr.n, pr.n, 4)
    for j in range(4):
        assert np.allclose(F[:, j], pr.rhs(Y[:, j], h.p_c), rtol=1e-14, atol=0)
        Jfd = _fd_jac(pr.rhs, Y[:, j], h.p_c, pr.scales)
        assert np.allclose(JJ[:, :, j], Jfd, rtol=1e-5, atol=1e-6 * np.abs(Jfd).max())


def test_spring_block_dieterich_with_radiation_damping_is_eq4():
    """rhs = Putelat et al. (2010) eq. (4) with the Dieterich law and −η u (Rice 1993), written out here."""
    law = get_law("dieterich")
    pr = get("spring-block").cycles(Setup(law, {"eta": 50.0}))
    assert pr.states == ("X", "u", "phi") and pr.parameter == "k" and pr.parameter_range[0] == 0.0
    d = {p.name: float(p.default) for p in law.parameters if p.default is not None}
    a, b, L, Vs = d["a"], d["b"], d["L"], d["V_s"]
    V, M, sigma, eta = 1e-4, 1.2, 1.2 * 9.81, 50.0
    phi0 = L / V
    mu = lambda v, phi: a * np.log(v / Vs) + b * np.log(Vs * phi / L)   # noqa: E731  (the law's μ up to μ₀)
    rng = np.random.default_rng(3)
    k = 1.1 * pr.hopf.p_c
    for _ in range(3):
        X, u, phi = 1e-6 * rng.standard_normal(), 1e-5 * rng.standard_normal(), phi0 * (1 + 0.1 * rng.random())
        want = np.array([u, (-k * X - sigma * (mu(V + u, phi) - mu(V, phi0)) - eta * u) / M,
                         1 - (V + u) * phi / L])
        got = pr.rhs(np.array([X, u, phi]), k)
        assert np.allclose(got, want, rtol=1e-10, atol=1e-12 * np.abs(want).max())
    _checks(pr, rng)


def test_spring_block_law_with_two_states():
    """Any number of states: the two-state Dieterich law; the HopfStart's C is the Hopf result's."""
    law = get_law("two-state-dieterich")
    setup = Setup(law, {})
    pr = get("spring-block").cycles(setup)
    res = get("spring-block").hopf(setup)
    assert pr.n == 2 + len(law.states)
    assert pr.hopf.p_c == res.p_c and pr.hopf.amplitude == pytest.approx(res.C, rel=1e-15)
    _checks(pr, np.random.default_rng(4))


@pytest.mark.parametrize("model, setup", [
    ("spring-block-chain", Setup(get_law("ruina"), {"k_coupling": 3e4}, {"blocks": 2})),
    ("system", Setup(None, {"a": 2.0}, {"rhs": {"x": "mu*x - y - a*x*(x**2 + y**2)",
                                                 "y": "x + mu*y - a*y*(x**2 + y**2)"},
                                         "parameter": "mu", "equilibrium": {"x": "0", "y": "0"},
                                         "bracket": (-1, 1)})),
    ("mode-coupling", Setup(None, {})),
    ("impact-oscillator", Setup(None, {})),
    ("galvanetto-one-block", Setup(None, {"V": 0.3})),
])
def test_declarations_of_the_other_models(model, setup):
    pr = get(model).cycles(setup)
    _checks(pr, np.random.default_rng(5))


def test_system_amplitude_is_the_closed_form():
    """ẋ = μx − y − a x r², ẏ = x + μy − a y r²: the cycle r = sqrt(μ/a), so C = 1/sqrt(a) on μ > 0."""
    pr = get("system").cycles(Setup(None, {"a": 4.0}, {"rhs": {"x": "mu*x - y - a*x*(x**2 + y**2)",
                                                               "y": "x + mu*y - a*y*(x**2 + y**2)"},
                                                       "parameter": "mu", "equilibrium": {"x": "0", "y": "0"},
                                                       "bracket": (-1, 1)}))
    assert pr.hopf.amplitude == pytest.approx(0.5, rel=1e-9) and pr.hopf.side == 1
    assert pr.hopf.omega == pytest.approx(1.0, rel=1e-12)


def test_system_bracket_as_the_command_line_writes_it_or_a_bad_one_named():
    opts = {"rhs": {"x": "mu*x - y - x*(x**2 + y**2)", "y": "x + mu*y - y*(x**2 + y**2)"}, "parameter": "mu",
            "equilibrium": {"x": "0", "y": "0"}}
    pr = get("system").cycles(Setup(None, {}, {**opts, "bracket": "-1:1"}))
    assert pr.hopf.p_c == pytest.approx(0.0, abs=1e-12)
    with pytest.raises(InputError, match=r"bracket must be two numbers, \(lo, hi\) or 'LO:HI', got '1:2:3'"):
        get("system").cycles(Setup(None, {}, {**opts, "bracket": "1:2:3"}))


def test_models_without_a_smooth_cycle_problem_declare_none():
    """The two-block stick–slip model has no smooth Hopf point (its blocks stick), the forced oscillator
    is forced (its cycles are not born at a Hopf point of an autonomous field)."""
    assert get("galvanetto-two-blocks").cycles is None and get("forced-oscillator").cycles is None


def test_quasi_static_block_is_refused():
    with pytest.raises(InputError, match="invertible mass matrix"):
        get("spring-block").cycles(Setup(get_law("dieterich"), {"M": 0.0, "eta": 1e3}))
