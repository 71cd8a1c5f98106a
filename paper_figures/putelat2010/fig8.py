"""Fig. 8: spinodal law (37)–(38), c = 1e-3 — μ_ss, k_c and k̂ (Δx = 5.7 µm), Γ, Λ, amplitudes.

Γ and amplitudes at k_c − k = 0.001 k_c; solid M = 1.2 kg, dashed M = 0.  The Hopf
bifurcation is supercritical (Λ ≤ 0) on the whole velocity-weakening range (V_M, V_m).
"""

from __future__ import annotations

from pathlib import Path

import matplotlib.pyplot as plt
import numpy as np

from landau.analyses.amplitude import apparent_stiffness, growth_rate, slip_amplitude, slip_rate_amplitude
from landau.paper_figures.putelat2010._common import (
    AMPLITUDE_NAMES,
    derivation,
    mu_ss,
    panel_title,
    save,
    symlog_y,
    vlabel,
    vw_grid,
)

C = 1e-3
DX = 5.7e-6


def data() -> dict:
    d = derivation("spinodal")
    P, P0 = {"c": C}, {"c": C, "M": 0.0}
    V = vw_grid(d, P, 260)
    for prm in (P, P0):    # every quantity of the panels below in one evaluation per parameter set
        d.evaluate(V, prm, AMPLITUDE_NAMES)
    Vmu = np.logspace(-9, -1, 300)
    return {"V": V, "V_mu": Vmu, "mu_ss": mu_ss(d, Vmu, P),
            "kc": d.evaluate(V, P, ["kc"])["kc"], "kc_M0": d.evaluate(V, P0, ["kc"])["kc"],
            "khat": apparent_stiffness(d, V, DX, P), "khat_M0": apparent_stiffness(d, V, DX, P0),
            "Gamma": growth_rate(d, V, P), "Gamma_M0": growth_rate(d, V, P0),
            "Lambda": d.evaluate(V, P, ["Lambda"])["Lambda"], "Lambda_M0": d.evaluate(V, P0, ["Lambda"])["Lambda"],
            "slip": slip_amplitude(d, V, P), "slip_M0": slip_amplitude(d, V, P0),
            "slip_rate": slip_rate_amplitude(d, V, P), "slip_rate_M0": slip_rate_amplitude(d, V, P0)}


def make(out_dir: Path) -> list[Path]:
    d = data()
    V = d["V"]
    fig, ax = plt.subplots(2, 3, figsize=(13, 7))
    ax = ax.ravel()
    ax[0].plot(d["V_mu"], d["mu_ss"], "k-")
    ax[0].set_ylabel(r"$\mu_{ss}$")
    panel_title(ax[0], "(a) steady-state friction")
    ax[1].plot(V, d["kc"], "k-", label="$k_c$")
    ax[1].plot(V, d["khat"], "k-.", label=rf"$\hat k$, $\Delta x$ = {DX * 1e6:g} µm")
    ax[1].plot(V, d["khat_M0"], "k:", lw=0.8, label=r"$\hat k$, M = 0")
    ax[1].set_yscale("log")
    ax[1].set_ylim(1e2, 1e6)
    ax[1].set_ylabel("k (N m$^{-1}$)")
    ax[1].legend(fontsize=7)
    panel_title(ax[1], r"(b) critical and apparent stiffness")
    for i, (key, lab, scale) in enumerate([("Gamma", r"$\Gamma$ (s$^{-1}$)", "log"),
                                            ("Lambda", r"$\Lambda$ (m$^{-2}$ s$^{-1}$)", "symlog"),
                                            ("slip", r"max$|x-x_0|$ (m)", "log"),
                                            ("slip_rate", r"max$|\dot x-V|$ (m s$^{-1}$)", "log")]):
        a = ax[2 + i]
        a.plot(V, d[key], "k-", label="M = 1.2 kg")
        a.plot(V, d[key + "_M0"], "k--", label="M = 0")
        if scale == "symlog":
            symlog_y(a, np.r_[d[key], d[key + "_M0"]])
        else:
            a.set_yscale("log")
        a.set_ylabel(lab)
        a.legend(fontsize=7)
    panel_title(ax[2], r"(c) growth rate at $k_c-k=10^{-3}k_c$")
    panel_title(ax[3], r"(d) Landau coefficient ($\Lambda\leq0$)")
    panel_title(ax[4], "(e) slip amplitude")
    panel_title(ax[5], "(f) slip-rate amplitude")
    for a in ax:
        vlabel(a)
    fig.suptitle("Putelat et al. (2010) Fig. 8 — spinodal law, c = 1e-3", fontsize=10)
    return save(fig, out_dir, "fig8")
