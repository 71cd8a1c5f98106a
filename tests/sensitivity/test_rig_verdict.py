"""``rig_verdict``: the probabilities against closed forms for a Gaussian in one parameter, the
first-order σ(k_c) against the spread over Gaussian samples, and its refusals.

One parameter, b ~ N(b₀, s²), Dieterich law (Putelat, Dawes & Willis 2010, eq. 30):
k_c = σ(b − a)/L + M V²(b − a)/(a L²) is affine in b with slope g = σ/L + M V²/(a L²), so k_c is
exactly Gaussian, σ_kc = g s, and P(k < k_c) = Φ((k_c(b₀) − k)/(g s)) — for the first-order route
exactly, for samples within the binomial error sqrt(P(1 − P)/N).  Λ is not affine in b; at the
velocity V* where Λ(b*) = 0 (found here by bracketing), P(Λ > 0) = P(b > b*) = Φ((b₀ − b*)/s) for
Λ increasing through b* (no other root within 6 s).
"""

import math

import numpy as np
import pytest
from scipy.optimize import brentq

import landau
from landau.errors import InputError
from landau.lab.verdict import rig_verdict

P = {"a": 0.0349, "b": 0.0489, "L": 9e-7}
RIG = {"M": 1.2, "sigma": 11.772}
N = 20000


def Phi(x):
    return 0.5 * math.erfc(-x / math.sqrt(2))


def test_p_unstable_one_parameter_gaussian_closed_form():
    V, s = 1e-4, 2e-4
    a, b, L, M, sg = P["a"], P["b"], P["L"], RIG["M"], RIG["sigma"]
    kc = sg * (b - a) / L + M * V ** 2 * (b - a) / (a * L ** 2)
    g = sg / L + M * V ** 2 / (a * L ** 2)
    k = kc - 0.6 * g * s                          # the rig a little softer than k_c: P = Φ(0.6)
    rig = {"k": k, **RIG}
    v = rig_verdict("dieterich", P, rig, covariance=[[s ** 2]], names=["b"], V=V)
    assert v.values["k_c"] == pytest.approx(kc, rel=1e-12)
    assert v.sd_first_order["k_c"] == pytest.approx(g * s, rel=1e-12)
    assert v.p_unstable == pytest.approx(Phi(0.6), rel=1e-10) and v.probabilities_from == "first-order Gaussian"
    assert v.unstable and v.sensitivities["k_c"]["b"] == pytest.approx(g, rel=1e-12)
    rng = np.random.default_rng(5)
    samples = rng.normal(b, s, size=(N, 1))
    w = rig_verdict("dieterich", P, rig, covariance=[[s ** 2]], names=["b"], samples=samples, V=V)
    binomial = math.sqrt(Phi(0.6) * (1 - Phi(0.6)) / N)
    assert w.probabilities_from == "samples" and w.n_samples == N and w.n_no_hopf == 0
    assert abs(w.p_unstable - Phi(0.6)) < 4 * binomial
    assert w.p_unstable_gaussian == pytest.approx(Phi(0.6), rel=1e-10)
    # the sample spread of an exactly Gaussian k_c: standard error of a standard deviation 1/sqrt(2N)
    assert w.sd_samples["k_c"] == pytest.approx(g * s, rel=4 / math.sqrt(2 * N))


@pytest.mark.parametrize("n", [2000, pytest.param(N, marks=pytest.mark.slow)])
def test_p_subcritical_one_parameter_at_the_codimension_two_point(n):
    # every sample sits near Λ = 0, where each value is settled with mpmath (~10 ms): 2000 samples in
    # the default suite (binomial error 0.011), 20000 in the slow one (0.0035)
    d = landau.derive("dieterich", ["Lambda"])

    def lam(V, b=P["b"]):
        return float(d.evaluate(np.array([V]), {**P, **RIG, "b": b}, ["Lambda"])["Lambda"][0])
    Vstar = brentq(lam, 1e-4, 3e-4, xtol=1e-18, rtol=1e-15)   # Λ(b = 0.0489) = 0 here (a sign change)
    s = 1e-5
    slope = (lam(Vstar, P["b"] + s) - lam(Vstar, P["b"] - s)) / (2 * s)
    b0 = P["b"] + 0.8 * s
    fitted = {**P, "b": b0}
    want = Phi(0.8 if slope > 0 else -0.8)
    assert all(np.sign(lam(Vstar, P["b"] + t * s)) == np.sign(slope * t) for t in (-6, -3, 3, 6))
    rng = np.random.default_rng(8)
    v = rig_verdict("dieterich", fitted, {"k": 1e5, **RIG}, covariance=[[s ** 2]], names=["b"],
                    samples=rng.normal(b0, s, size=(n, 1)), V=Vstar)
    assert abs(v.p_subcritical - want) < 4 * math.sqrt(want * (1 - want) / n)
    # first order: Φ(Λ(b₀)/(|Λ′| s)); Λ(b₀)/Λ′ differs from b₀ − b* by the curvature, here < 1e-3 of it
    assert v.p_subcritical_gaussian == pytest.approx(want, abs=1e-3)


def test_first_order_sigma_kc_against_the_spread_over_gaussian_samples():
    # three correlated parameters, relative standard deviations 1e-3: the first-order σ(k_c) is the
    # spread of k_c over the samples within their sampling error (1/sqrt(2N) = 0.5 %, asserted at 3 %)
    V = 1e-4
    names = ["a", "b", "L"]
    mean = np.array([P[x] for x in names])
    sd = 1e-3 * mean
    corr = np.array([[1.0, 0.6, -0.3], [0.6, 1.0, 0.2], [-0.3, 0.2, 1.0]])
    cov = corr * np.outer(sd, sd)
    rng = np.random.default_rng(20261202)
    samples = rng.multivariate_normal(mean, cov, size=N)
    v = rig_verdict("dieterich", P, {"k": 1.8e5, **RIG}, covariance=cov, names=names, samples=samples, V=V)
    assert v.sd_samples["k_c"] == pytest.approx(v.sd_first_order["k_c"], rel=0.03)
    assert v.sd_samples["Lambda"] == pytest.approx(v.sd_first_order["Lambda"], rel=0.03)
    # and the first-order σ(k_c) is J Σ Jᵀ with the hand gradient of eq. (30)
    a, b, L, M, sg = P["a"], P["b"], P["L"], RIG["M"], RIG["sigma"]
    J = np.array([-sg / L - M * V ** 2 * b / (a ** 2 * L ** 2), sg / L + M * V ** 2 / (a * L ** 2),
                  -sg * (b - a) / L ** 2 - 2 * M * V ** 2 * (b - a) / (a * L ** 3)])
    assert v.sd_first_order["k_c"] == pytest.approx(math.sqrt(J @ cov @ J), rel=1e-10)


@pytest.mark.parametrize("kwargs, needle", [
    ({"rig": {"k": 1e5, "mass": 1.0}}, "unknown rig entry 'mass'"),
    ({"rig": {"M": 1.0}}, "needs its stiffness k"),
    ({"rig": {"k": -1.0}}, "must be > 0"),
    ({"covariance": [[1.0, 0.0]]}, "covariance must be 3 x 3"),
    ({"covariance": -np.eye(3)}, "positive semi-definite"),
    ({"samples": np.ones((5, 2))}, "samples must have shape (n_samples, 3)"),
    ({"samples": np.full((5, 3), -1.0)}, "must be > 0"),
    ({"names": ["a", "b", "D_c"]}, "'D_c' has no fitted value"),
    ({"V": 0.0}, "V"),
])
def test_bad_input_is_a_named_input_error(kwargs, needle):
    args = {"rig": {"k": 1e5}, "V": 1e-4, **kwargs}
    with pytest.raises(InputError, match=None) as err:
        rig_verdict("dieterich", P, **args)
    assert needle in str(err.value)


def test_a_fitted_name_outside_the_rig_quantities_is_inert_and_listed():
    v = rig_verdict("dieterich", {**P, "trend": 1e-3}, {"k": 1e5}, covariance=np.eye(4) * 1e-12,
                    names=["a", "b", "L", "trend"], V=1e-4)
    assert v.inert == ("trend",) and v.sensitivities["k_c"]["trend"] == 0.0
