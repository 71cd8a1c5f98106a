"""The posterior of landau.fit by emcee: its spread against the linearised standard errors, the chains saved.

For a record whose model is close to linear in its parameters over their uncertainty (noise
2e-4 on a velocity step: standard errors ~1e-3 relative), the posterior of a flat prior and the
Gaussian likelihood is the Gaussian of the linearisation (Bates & Watts 1988, Sec. 2.3), so the
standard deviation of the draws equals the standard error up to the sampling error of the
chain.  With W walkers, N kept steps and an autocorrelation time τ of some tens of steps there
are ~W N/τ independent draws and the relative error of a standard deviation is ~(2 W N/τ)^-1/2:
~10 % for the short chain of the default suite (16 × 60 kept, asserted within 35 %), ~4 % for
the long one (32 × 150 kept, asserted within 15 %).
"""

import numpy as np
import pytest
from fit_support import record

from landau.lab.fit import fit


def _fit(mcmc, walkers, burn, seed=7, chains=None):
    law, data, true, k = record("aging", noise=2e-4, seed=3, dt=0.2)
    start = {"V_s": true["V_s"], "a_v": true["a_v"], "a": 0.006, "b": 0.009, "L": 12e-6}
    return fit(data, law, k=k, free=["a", "b", "L"], params=start, mcmc=mcmc, walkers=walkers, burn=burn,
               seed=seed, chains=chains)


def _check_spread(res, tol):
    spread = res.samples.std(axis=0, ddof=1)
    for i, n in enumerate(res.names):
        assert abs(spread[i] / res.standard_errors[n] - 1) < tol, (n, spread[i], res.standard_errors[n])
        assert abs(res.samples[:, i].mean() - res.params[n]) < 0.5 * res.standard_errors[n]


def test_posterior_spread_matches_standard_errors_and_chains_are_saved(tmp_path):
    path = tmp_path / "chains.npz"
    res = _fit(100, 16, 40, chains=path)
    assert res.samples is not None and res.samples.shape == (60 * 16, 3)
    _check_spread(res, 0.35)
    with np.load(path) as z:
        assert z["chain"].shape == (100, 16, 3)
        assert list(z["names"]) == ["a", "b", "L"]
        assert int(z["burn"]) == 40
        np.testing.assert_array_equal(z["chain"][40:].reshape(-1, 3), res.samples)
    assert res.to_dict()["mcmc"]["chains"] == str(path)


def test_same_seed_same_chain():
    a, b = _fit(6, 16, 2), _fit(6, 16, 2)
    np.testing.assert_array_equal(a.samples, b.samples)


def test_posterior_with_a_trend_term():
    law, data, true, k = record("aging", noise=2e-4, seed=3, dt=0.2)
    res = fit(data, law, k=k, trend=True, free=["a", "b", "L"], mcmc=6, walkers=16, burn=2,
              params={"V_s": true["V_s"], "a_v": true["a_v"], "a": 0.006, "b": 0.009, "L": 12e-6})
    assert res.names == ("a", "b", "L", "trend") and res.samples.shape == (4 * 16, 4)
    assert np.all(np.isfinite(res.samples))


@pytest.mark.slow
def test_long_chain_spread_matches_standard_errors():
    _check_spread(_fit(300, 32, 150), 0.15)


def test_verdict_hands_on_the_law_parameters_only(monkeypatch):
    """FitResult.verdict calls landau.lab.verdict.rig_verdict with the law's parameters and their rows of
    the covariance and columns of the samples (the lab's stiffness k' is not the rig's k)."""
    import sys
    import types

    from fit_support import record

    seen = {}
    stub = types.ModuleType("landau.lab.verdict")
    stub.rig_verdict = lambda law, fitted, rig, **kw: seen.update(law=law, fitted=fitted, rig=rig, **kw) or "ok"
    monkeypatch.setitem(sys.modules, "landau.lab.verdict", stub)
    law, data, true, k = record("aging", noise=2e-4, seed=3, dt=0.2)
    res = fit(data, law, k=k, fit_k=True, free=["a", "b", "L"], mcmc=4, walkers=16, burn=2,
              params={"V_s": true["V_s"], "a_v": true["a_v"], "a": 0.006, "b": 0.009, "L": 12e-6})
    assert res.names == ("a", "b", "L", "k")
    assert res.verdict({"k": 1e7, "M": 1.0, "sigma": 1e6, "eta": 0.0}, V=1e-6) == "ok"
    assert seen["names"] == ["a", "b", "L"] and seen["V"] == 1e-6
    assert set(seen["fitted"]) == {p.name for p in law.parameters}
    np.testing.assert_array_equal(seen["covariance"], res.covariance[:3, :3])
    np.testing.assert_array_equal(seen["samples"], res.samples[:, :3])
