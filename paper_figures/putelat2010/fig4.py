"""Fig. 4: Dieterich–Ruina laws — μ_ss, k_c and k̂(Δx), growth rate, Λ, slip and slip-rate amplitudes.

Amplitudes and Γ at k_c − k = 0.001 k_c (as in the paper).  M = 1.2 kg solid, M = 0 dashed.
The toolkit finds Λ ≡ 0 for M = 0 with both laws (degenerate at third order), so no M = 0
amplitude is drawn (the paper's M = 0 Ruina curve rests on its closed form (35); see
docs/verdicts.md).
"""

from __future__ import annotations

from pathlib import Path
from typing import Any

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
)

V = np.logspace(-7, -2, 240)
DX_UM = (0.1, 1.0, 10.0)


def data() -> dict:
    R, Dl = derivation("ruina"), derivation("dieterich")
    # every quantity of the panels below in one evaluation per law and parameter set (M = 0:
    # only k_c and Γ are drawn; Λ vanishes identically there)
    R.evaluate(V, {}, AMPLITUDE_NAMES)
    R.evaluate(V, {"M": 0.0}, ["kc", "Gamma_bar"])
    Dl.evaluate(V, {}, ["Gamma_bar", "Lambda"])
    out: dict[str, Any] = {"V": V, "mu_ss": mu_ss(R, V, {})}
    out["kc"] = R.evaluate(V, {}, ["kc"])["kc"]
    out["kc_M0"] = R.evaluate(V, {"M": 0.0}, ["kc"])["kc"]
    out["khat"] = {dx: apparent_stiffness(R, V, dx * 1e-6) for dx in DX_UM}
    out["Gamma"] = growth_rate(R, V)
    out["Gamma_M0"] = growth_rate(R, V, {"M": 0.0})
    out["Lambda_R"] = R.evaluate(V, {}, ["Lambda"])["Lambda"]
    out["Lambda_D"] = Dl.evaluate(V, {}, ["Lambda"])["Lambda"]
    out["slip_R"] = slip_amplitude(R, V)
    out["slip_D"] = slip_amplitude(Dl, V)
    out["slip_rate_R"] = slip_rate_amplitude(R, V)
    return out


def make(out_dir: Path) -> list[Path]:
    d = data()
    fig, ax = plt.subplots(2, 3, figsize=(13, 7))
    ax = ax.ravel()
    ax[0].plot(V, d["mu_ss"], "k-")
    ax[0].set_ylabel(r"$\mu_{ss}$")
    panel_title(ax[0], "(a) steady-state friction (eq. 27)")
    ax[1].plot(V, d["kc"], "k-", label=r"$k_c$, M = 1.2 kg")
    ax[1].plot(V, d["kc_M0"], "k--", label=r"$k_c$, M = 0")
    for dx, ls in zip(DX_UM, (":", "-.", (0, (5, 1, 1, 1))), strict=True):
        ax[1].plot(V, d["khat"][dx], color="tab:blue", ls=ls, label=rf"$\hat k$, $\Delta x$ = {dx:g} µm")
    ax[1].set_yscale("log")
    ax[1].set_ylim(1e4, 1e7)
    ax[1].set_ylabel("k (N m$^{-1}$)")
    ax[1].legend(fontsize=7)
    panel_title(ax[1], r"(b) $k_c$ (eq. 30) and $\hat k$ (eq. 25), Ruina")
    ax[2].plot(V, d["Gamma"], "k-", label="M = 1.2 kg")
    ax[2].plot(V, d["Gamma_M0"], "k--", label="M = 0")
    ax[2].set_yscale("log")
    ax[2].set_ylabel(r"$\Gamma$ (s$^{-1}$) at $k_c-k=10^{-3}k_c$")
    ax[2].legend(fontsize=7)
    panel_title(ax[2], "(c) growth rate (eq. 32), both laws")
    ax[3].plot(V, d["Lambda_R"], "k-", label="RL")
    ax[3].plot(V, d["Lambda_D"], "k--", label="DL")
    symlog_y(ax[3], np.r_[d["Lambda_R"], d["Lambda_D"]])
    ax[3].set_ylabel(r"$\Lambda$ (m$^{-2}$ s$^{-1}$)")
    ax[3].legend(fontsize=7)
    panel_title(ax[3], r"(d) Landau coefficient $\Lambda$")
    ax[4].plot(V, d["slip_R"], "k-", label="RL")
    ax[4].plot(V, d["slip_D"], "k--", label="DL (where $\\Lambda<0$)")
    ax[4].set_yscale("log")
    ax[4].set_ylabel(r"max$|x-x_0|$ (m)")
    ax[4].legend(fontsize=7)
    ax[4].text(0.02, 0.03, "M = 0: $\\Lambda\\equiv 0$ (degenerate), no curve", transform=ax[4].transAxes, fontsize=7)
    panel_title(ax[4], "(e) slip amplitude (eq. 23)")
    ax[5].plot(V, d["slip_rate_R"], "k-")
    ax[5].set_yscale("log")
    ax[5].set_ylabel(r"max$|\dot x-V|$ (m s$^{-1}$)")
    panel_title(ax[5], "(f) slip-rate amplitude (eq. 24), Ruina")
    for a in ax:
        vlabel(a)
    fig.suptitle("Putelat et al. (2010) Fig. 4 — Dieterich–Ruina laws, Table 1, M = 1.2 kg", fontsize=10)
    return save(fig, out_dir, "fig4")
