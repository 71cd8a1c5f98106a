"""Fig. 10: spinodal law, c = 3e-4 — (a) μ_ss, (b) k_c, (c) Γ at k_c − k = 0.001 k_c, (d) Λ.

Solid M = 1.2 kg, dashed M = 0: inertia makes Λ > 0 in a narrow band below V_m; Λ ≤ 0
everywhere without inertia.  Panel (b) never builds cubic-order derivatives."""

from __future__ import annotations

from pathlib import Path

import matplotlib.pyplot as plt
import numpy as np

from landau.analyses.amplitude import growth_rate
from landau.analyses.transition import codim2_points
from landau.paper_figures.putelat2010._common import derivation, mu_ss, panel_title, save, symlog_y, vlabel, vw_grid

C = 3e-4


def kc_panel(d=None) -> dict:
    d = d or derivation("spinodal")
    V = vw_grid(d, {"c": C}, 260)
    return {"V": V, "kc": d.evaluate(V, {"c": C}, ["kc"])["kc"],
            "kc_M0": d.evaluate(V, {"c": C, "M": 0.0}, ["kc"])["kc"]}


def data() -> dict:
    d = derivation("spinodal")
    P, P0 = {"c": C}, {"c": C, "M": 0.0}
    out = kc_panel(d)
    V = out["V"]
    for prm in (P, P0):    # Γ and Λ of the panels below in one evaluation per parameter set
        d.evaluate(V, prm, ["Gamma_bar", "Lambda"])
    Vmu = np.logspace(-9, -1, 300)
    out.update(V_mu=Vmu, mu_ss=mu_ss(d, Vmu, P), Gamma=growth_rate(d, V, P), Gamma_M0=growth_rate(d, V, P0),
               Lambda=d.evaluate(V, P, ["Lambda"])["Lambda"], Lambda_M0=d.evaluate(V, P0, ["Lambda"])["Lambda"],
               codim2=codim2_points(d, float(V[0]), float(V[-1]), P))
    return out


def make(out_dir: Path) -> list[Path]:
    d = data()
    V = d["V"]
    fig, ax = plt.subplots(2, 2, figsize=(10, 7))
    ax = ax.ravel()
    ax[0].plot(d["V_mu"], d["mu_ss"], "k-")
    ax[0].set_ylabel(r"$\mu_{ss}$")
    ax[1].plot(V, d["kc"], "k-", label="M = 1.2 kg")
    ax[1].plot(V, d["kc_M0"], "k--", label="M = 0")
    ax[1].set_yscale("log")
    ax[1].set_ylim(bottom=1e2)
    ax[1].set_ylabel("$k_c$ (N m$^{-1}$)")
    ax[2].plot(V, d["Gamma"], "k-", label="M = 1.2 kg")
    ax[2].plot(V, d["Gamma_M0"], "k--", label="M = 0")
    ax[2].set_yscale("log")
    ax[2].set_ylabel(r"$\Gamma$ (s$^{-1}$)")
    ax[3].plot(V, d["Lambda"], "k-", label="M = 1.2 kg")
    ax[3].plot(V, d["Lambda_M0"], "k--", label="M = 0")
    for p in d["codim2"]:
        ax[3].plot([p.V], [0.0], "ko")
        ax[3].annotate(f"V* = {p.V:.4g}", (p.V, 0.0), xytext=(-60, 15), textcoords="offset points", fontsize=8)
    symlog_y(ax[3], np.r_[d["Lambda"], d["Lambda_M0"]])
    ax[3].set_ylabel(r"$\Lambda$ (m$^{-2}$ s$^{-1}$)")
    for a, t in zip(ax, ("(a) steady-state friction", "(b) critical stiffness",
                         r"(c) growth rate at $k_c-k=10^{-3}k_c$", r"(d) Landau coefficient"), strict=True):
        panel_title(a, t)
        vlabel(a)
    for a in ax[1:]:
        a.legend(fontsize=7)
    fig.suptitle("Putelat et al. (2010) Fig. 10 — spinodal law, c = 3e-4", fontsize=10)
    return save(fig, out_dir, "fig10")
