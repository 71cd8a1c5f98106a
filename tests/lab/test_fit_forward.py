"""The forward model of landau fit against an independent integration (scipy's solve_ivp at rtol 1e-12).

Independent: the equations written out by hand for the Dieterich law (Dieterich 1979; v in
closed form), and for the micron-scale law of Putelat et al. (2010, eq. 50), whose μ is not linear
in ln v, with v found by Brent's method from μ at every evaluation — landau integrates (ln v, φ)
there instead.  The sensitivities are checked against centred differences of the independent
solution.
"""

import math

import numpy as np
from fit_support import UM, protocol
from scipy.integrate import solve_ivp
from scipy.optimize import brentq

from landau.lab.forward import ForwardModel, linear_in_log_v
from landau.laws import get_law

DIETERICH = dict(a_v=0.6, a=0.005, b=0.01, L=10 * UM, V_s=1 * UM)
K = 1e3      # 1e-3 per micron


def _independent(rhs, y0, t, V):
    """solve_ivp over each interval of constant load-point velocity, rtol 1e-12."""
    out = np.empty((t.size, len(y0)))
    out[0] = y0
    y = np.array(y0, float)
    edges = [0] + [j for j in range(1, t.size - 1) if V[j] != V[j - 1]] + [t.size - 1]
    for s, e in zip(edges[:-1], edges[1:], strict=True):
        sol = solve_ivp(rhs, (t[s], t[e]), y, method="DOP853", t_eval=t[s:e + 1], rtol=1e-12, atol=1e-15,
                        args=(V[s],))
        assert sol.success
        out[s:e + 1] = sol.y.T
        y = sol.y[:, -1]
    return out


def _dieterich_mu(p, t, V):
    def rhs(_t, y, Vlp):
        mu, th = y
        v = p["V_s"] * math.exp((mu - p["a_v"] - p["b"] * math.log(p["V_s"] * th / p["L"])) / p["a"])
        return [K * (Vlp - v), 1 - v * th / p["L"]]

    th0 = p["L"] / V[0]
    mu0 = p["a_v"] + p["a"] * math.log(V[0] / p["V_s"]) + p["b"] * math.log(p["V_s"] * th0 / p["L"])
    return _independent(rhs, [mu0, th0], t, V)[:, 0]


def test_dieterich_forward_matches_solve_ivp_and_its_differences():
    t, V = protocol([(0.0, 1.0), (10.0, 10.0), (25.0, 1.0)], 40.0, 0.02)
    names = ["a_v", "a", "b", "L"]
    fm = ForwardModel(get_law("dieterich"), names)
    assert fm.closed_form
    run = fm.run(t, V, DIETERICH, K, rtol=1e-12)
    ref = _dieterich_mu(DIETERICH, t, V)
    # both at rtol 1e-12 over ~10^3 steps: agreement to 1e-10 in mu ~ 0.6
    assert np.max(np.abs(run.mu - ref)) < 1e-10
    # 15 D_c after the step to 10 um/s, steady sliding: mu_ss = mu_0 + (a - b) ln 10 (closed form)
    i = np.searchsorted(t, 25.0) - 1
    assert abs(run.mu[i] - (0.6 + (0.005 - 0.01) * math.log(10))) < 1e-4
    for j, n in enumerate(names):
        h = 1e-5
        up, dn = dict(DIETERICH), dict(DIETERICH)
        up[n] *= 1 + h
        dn[n] *= 1 - h
        fd = (_dieterich_mu(up, t, V) - _dieterich_mu(dn, t, V)) / (2 * h * DIETERICH[n])
        # centred difference: truncation ~h^2 = 1e-10, round-off ~1e-12/h = 1e-7 relative
        assert np.max(np.abs(run.dmu[:, j] - fd)) < 1e-5 * np.max(np.abs(fd)), n


def test_stiffness_sensitivity_matches_difference():
    t, V = protocol([(0.0, 1.0), (10.0, 10.0)], 30.0, 0.05)
    fm = ForwardModel(get_law("dieterich"), ["k"])
    run = fm.run(t, V, DIETERICH, K, rtol=1e-12)
    h = 1e-5
    fd = (fm.run(t, V, DIETERICH, K * (1 + h), rtol=1e-12).mu - fm.run(t, V, DIETERICH, K * (1 - h), rtol=1e-12).mu)
    fd /= 2 * h * K
    assert np.max(np.abs(run.dmu[:, 0] - fd)) < 1e-5 * np.max(np.abs(fd))


MICRON = dict(a_v=0.6, a=0.005, b=0.01, L=10 * UM, V_s=1 * UM, c=0.014)


def _micron_mu(p, t, V):
    law = get_law("micron-scale")
    g0 = 2 * math.exp(-p["a_v"] / p["a"]) * p["V_s"]

    def friction(v, phi):
        return p["a"] * (1 + p["b"] / p["a_v"] * math.log(p["c"] + p["V_s"] * phi / p["L"])) * math.asinh(v / g0)

    def rhs(_t, y, Vlp):
        mu, phi = y
        lv = brentq(lambda lv: friction(math.exp(lv), phi) - mu, -60.0, 10.0, xtol=1e-15, rtol=1e-15)
        v = math.exp(lv)
        return [K * (Vlp - v), 1 - v * phi / p["L"]]

    phi0 = float(law.steady_state_values(np.float64(V[0]), p).ravel()[0])
    return _independent(rhs, [friction(V[0], phi0), phi0], t, V)[:, 0]


def test_a_law_not_linear_in_log_v_is_integrated_in_log_v_and_matches_newton():
    law = get_law("micron-scale")
    assert linear_in_log_v(law.mu, law.v) is None
    t, V = protocol([(0.0, 1.0), (5.0, 10.0)], 15.0, 0.05)
    fm = ForwardModel(law, ["b", "L"])
    assert not fm.closed_form
    run = fm.run(t, V, MICRON, K, rtol=1e-12)
    ref = _micron_mu(MICRON, t, V)
    assert np.max(np.abs(run.mu - ref)) < 1e-10
    h = 1e-5
    for j, n in enumerate(["b", "L"]):
        up, dn = dict(MICRON), dict(MICRON)
        up[n] *= 1 + h
        dn[n] *= 1 - h
        fd = (_micron_mu(up, t, V) - _micron_mu(dn, t, V)) / (2 * h * MICRON[n])
        assert np.max(np.abs(run.dmu[:, j] - fd)) < 1e-5 * np.max(np.abs(fd)), n


def test_dieterich_is_linear_in_log_v_with_the_direct_effect_as_slope():
    law = get_law("dieterich")
    A, _ = linear_in_log_v(law.mu, law.v)
    assert A == law.parameter("a").symbol
