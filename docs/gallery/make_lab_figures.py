"""Regenerate the figures of docs/lab-data.md: ``python docs/gallery/make_lab_figures.py``.

rsfmodel's README velocity step (μ₀ = 0.6, a = 0.005, b = 0.01, D_c = 10 µm, k′ = 1e-3/µm,
1 → 10 → 1 µm/s; Leeman et al., rsfmodel) made by landau's forward model with noise 2e-4, fitted
with its emcee posterior, and the verdict on a rig of 1 kg on 10 MPa whose stiffness lies 0.7 standard
deviations of k_c below k_c.
"""

from pathlib import Path

import numpy as np

from landau.lab.data import LabData
from landau.lab.figure import plot_fit, plot_posterior, plot_verdict
from landau.lab.fit import fit
from landau.lab.forward import ForwardModel
from landau.laws import get_law
from landau.support.io import atomic_savefig

UM = 1e-6
HERE = Path(__file__).resolve().parent

law = get_law("dieterich")
true = {"a_v": 0.6, "a": 0.005, "b": 0.01, "L": 10 * UM, "V_s": 1 * UM}
k = 1e3
t = np.round(np.arange(0.0, 80.0 + 0.1, 0.2), 12)
V = np.where((t >= 10.0) & (t < 40.0), 10 * UM, 1 * UM)
mu = ForwardModel(law, []).run(t, V, true, k, rtol=1e-12).mu
mu = mu + 2e-4 * np.random.default_rng(3).standard_normal(mu.size)
data = LabData(t, V, mu, np.concatenate([[0.0], np.cumsum(V[:-1] * np.diff(t))]), "velocity step")
res = fit(data, law, k=k, free=["a", "b", "L"], mcmc=400, walkers=32, burn=100, seed=11,
          params={"V_s": true["V_s"], "a_v": true["a_v"], "a": 0.006, "b": 0.009, "L": 12 * UM})
rig = {"M": 1.0, "sigma": 1e7}
first = res.verdict({**rig, "k": 1.0}, 1e-5)
kc, sd = first.values["k_c"], first.sd_first_order["k_c"]
verdict = res.verdict({**rig, "k": kc - 0.7 * sd}, 1e-5)
print(f"k_c = {kc:.6g} N/m, sd {sd:.3g}; P(unstable) = {verdict.p_unstable:.3f}, P(subcritical) = "
      f"{verdict.p_subcritical:.3f} ({verdict.probabilities_from})")
for name, fig in (("lab_fit", plot_fit(res, data, title="velocity step 1 -> 10 -> 1 um/s, fitted")),
                  ("lab_posterior", plot_posterior(res)), ("lab_verdict", plot_verdict(verdict))):
    atomic_savefig(fig, HERE / f"{name}.png", dpi=110)
    print(HERE / f"{name}.png")
