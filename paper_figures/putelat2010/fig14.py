"""Fig. 14: (a) regime diagram in (V, k): spinodal Hopf lines for c = 1e-3, 7e-4, 5e-4, 3e-4
(solid supercritical, dashed subcritical), their codimension-two points (•), the transition
line k*(V*(c)) of law (39) (thick), the inertial boundary k = Mω_c² (law 39 at c = 3e-4, thin
dotted; Dieterich–Ruina, thin solid) and the naive crossover M/k = (L/V)² (double dash);
(b) time scales of the spinodal law (c = 1e-3): 1/ω_c, (M/k_c)^{1/2}, L/V."""

from __future__ import annotations

from pathlib import Path

import matplotlib.pyplot as plt
import numpy as np

from landau.analyses.regimes import naive_crossover, regime_diagram
from landau.analyses.transition import transition_curve
from landau.paper_figures import workers
from landau.paper_figures.putelat2010._common import L, derivation, panel_title, save, vlabel, vw_grid

CS = (1e-3, 7e-4, 5e-4, 3e-4)
M = 1.2


def panel_a() -> dict:
    sp = derivation("spinodal")
    diagrams = {c: regime_diagram(sp, vw_grid(sp, {"c": c}, 200, lo=1e-8), {"c": c}) for c in CS}
    md = derivation("modified-dieterich")
    line = transition_curve(md, "c", 1e-4, 2e-3, n=16, workers=workers())  # regimes.transition_line
    rows = sorted((r for r in line.rows if np.isfinite(r.V_ext) or r.kc == 0.0), key=lambda r: r.value)
    top: dict[float, tuple[float, float]] = {}
    for r in rows:
        if r.value not in top or r.V_star > top[r.value][0]:
            top[r.value] = (r.V_star, r.kc)
    Vb = np.logspace(-8, -2.5, 200)
    om39 = md.evaluate(Vb, {"c": 3e-4}, ["omega_c"])["omega_c"]
    omDR = derivation("ruina").evaluate(Vb, {}, ["omega_c"])["omega_c"]
    return {"diagrams": diagrams, "line_V": np.array([v for v, _ in top.values()]),
            "line_k": np.array([k for _, k in top.values()]), "c_star": line.critical_value,
            "V_b": Vb, "inertial_39": M * om39 ** 2, "inertial_DR": M * omDR ** 2,
            "naive": naive_crossover(Vb, M, L)}


def panel_b() -> dict:
    sp = derivation("spinodal")
    V = vw_grid(sp, {"c": 1e-3}, 200)
    r = sp.evaluate(V, {"c": 1e-3}, ["kc", "omega_c"])
    return {"V": V, "inv_omega": 1 / r["omega_c"], "inertial": np.sqrt(M / r["kc"]), "relax": L / V}


def make(out_dir: Path) -> list[Path]:
    a, b = panel_a(), panel_b()
    fig, ax = plt.subplots(1, 2, figsize=(12, 4.6))
    for c, col in zip(CS, ("tab:blue", "tab:green", "tab:orange", "tab:red"), strict=True):
        g = a["diagrams"][c]
        ax[0].plot(g.V, g.supercritical, "-", color=col, lw=1, label=f"Hopf, c = {c:g}")
        ax[0].plot(g.V, g.subcritical, "--", color=col, lw=1.5)
        for p in g.codim2:
            ax[0].plot([p.V], [p.kc], "o", color=col)
    ax[0].plot(a["line_V"], a["line_k"], "k-", lw=2.5, label="transition line $k^*(V^*)$, law (39)")
    ax[0].plot(a["V_b"], a["inertial_39"], "k:", lw=1, label=r"$k = M\omega_c^2$ (43), c = 3e-4")
    ax[0].plot(a["V_b"], a["inertial_DR"], "k-", lw=0.6, label=r"$k = M\omega_c^2$, Dieterich–Ruina")
    ax[0].plot(a["V_b"], a["naive"], color="k", ls=(0, (6, 2, 1, 2, 1, 2)), lw=1, label=r"$M/k = (L/V)^2$")
    ax[0].set_yscale("log")
    ax[0].set_ylim(1e2, 1e7)
    ax[0].set_xlim(1e-8, 3e-3)
    ax[0].set_ylabel("k (N m$^{-1}$)")
    ax[0].legend(fontsize=6, loc="lower left")
    panel_title(ax[0], "(a) regime diagram: supercritical (solid) / subcritical (dashed)")
    ax[1].plot(b["V"], b["inv_omega"], "k-", label=r"$1/\omega_c$")
    ax[1].plot(b["V"], b["inertial"], "k--", label=r"$(M/k_c)^{1/2}$")
    ax[1].plot(b["V"], b["relax"], "k:", label="L/V")
    ax[1].set_yscale("log")
    ax[1].set_ylabel("time (s)")
    ax[1].legend(fontsize=7)
    panel_title(ax[1], "(b) characteristic time scales, spinodal law c = 1e-3")
    for x in ax:
        vlabel(x)
    fig.suptitle("Putelat et al. (2010) Fig. 14, M = 1.2 kg", fontsize=10)
    return save(fig, out_dir, "fig14")
