"""From a fit to a verdict, end to end: a noisy velocity step fitted with its emcee posterior, carried
to a rig's k_c by :meth:`FitResult.verdict`.  The first-order standard deviation of k_c (exact
sensitivities times the fit's covariance) equals the spread of k_c over the posterior draws within
10 %: over the posterior (relative standard errors ~1e-3) k_c is close to linear in (a, b, L), so the
two agree up to the chain's sampling error of a standard deviation, ~(2 W N/τ)^-1/2 (see
test_fit_mcmc.py: ~5 % for 32 walkers × 150 kept steps)."""

import numpy as np
import pytest
from fit_support import record

from landau.lab.fit import fit

#: a rig: 1 kg on 10 MPa per unit area, at 10 µm/s
RIG = {"M": 1.0, "sigma": 1e7}
V = 1e-5


def _posterior(steps, walkers, burn):
    law, data, true, k = record("aging", noise=2e-4, seed=3, dt=0.2)
    start = {"V_s": true["V_s"], "a_v": true["a_v"], "a": 0.006, "b": 0.009, "L": 12e-6}
    return fit(data, law, k=k, free=["a", "b", "L"], params=start, mcmc=steps, walkers=walkers, burn=burn, seed=11)


def _verdict(res):
    kc = res.verdict({**RIG, "k": 1.0}, V).values["k_c"]
    return res.verdict({**RIG, "k": 0.9 * kc}, V)


def _check(res, tol):
    """The verdict's assertions; returns the verdict (each costs a Λ over every posterior draw)."""
    v = _verdict(res)
    sd1, sds = v.sd_first_order["k_c"], v.sd_samples["k_c"]
    assert v.n_no_hopf == 0 and v.n_samples == res.samples.shape[0]
    assert abs(sds / sd1 - 1) < tol, (sd1, sds)
    # the rig at 0.9 k_c is unstable, by many standard deviations of k_c
    assert v.unstable and v.p_unstable == 1.0
    # the first-order sd is the gradient times the covariance: J Σ Jᵀ
    g = np.array([v.sensitivities["k_c"][n] for n in res.names])
    assert sd1 == pytest.approx(float(np.sqrt(g @ res.covariance @ g)), rel=1e-10)
    return v


def test_propagated_sd_of_kc_equals_the_posterior_spread():
    res = _posterior(120, 32, 40)
    _figures(res, _check(res, 0.10))


def _figures(res, v):
    """The docs page's three figures draw what they say (landau.lab.figure)."""
    from landau.lab.figure import plot_fit, plot_posterior, plot_verdict

    law, data, _, _ = record("aging", noise=2e-4, seed=3, dt=0.2)
    top, bottom = plot_fit(res, data).axes
    x, mu = top.lines[0].get_data()
    np.testing.assert_allclose(x, data.x_lp * 1e6)
    np.testing.assert_array_equal(mu, data.mu)
    np.testing.assert_array_equal(top.lines[1].get_data()[1], res.model)
    np.testing.assert_allclose(bottom.lines[0].get_data()[1], res.model - data.mu)
    corner = plot_posterior(res).axes
    n = len(res.names)
    assert len(corner) == n * n and sum(ax.get_visible() for ax in corner) == n * (n + 1) // 2
    (curve, rig_line) = plot_verdict(v).axes[0].lines
    assert float(rig_line.get_xdata()[0]) == v.rig["k"]
    xs, dens = curve.get_data()
    assert xs[int(np.argmax(dens))] == pytest.approx(v.values["k_c"], rel=2 * (xs[1] - xs[0]) / xs[0])


@pytest.mark.slow
def test_propagated_sd_of_kc_equals_the_posterior_spread_long_chain():
    _check(_posterior(400, 32, 100), 0.05)
