"""Fig. 9: spinodal law — effect of the residual strength c on (a) k_c and (b) Λ.

Panel (a) needs only the linear problem: it never builds the cubic-order derivatives."""

from __future__ import annotations

from pathlib import Path

import matplotlib.pyplot as plt
import numpy as np

from landau.paper_figures.putelat2010._common import derivation, panel_title, save, symlog_y, vlabel, vw_grid

CS = (1e-3, 7e-4, 5e-4, 3e-4)
STYLES = ("-", "--", "-.", ":")


def kc_panel(d=None) -> dict:
    d = d or derivation("spinodal")
    out = {}
    for c in CS:
        V = vw_grid(d, {"c": c}, 200)
        out[c] = (V, d.evaluate(V, {"c": c}, ["kc"])["kc"])
    return out


def lambda_panel(d=None) -> dict:
    d = d or derivation("spinodal")
    out = {}
    for c in CS:
        V = vw_grid(d, {"c": c}, 200)
        out[c] = (V, d.evaluate(V, {"c": c}, ["Lambda"])["Lambda"])
    return out


def make(out_dir: Path) -> list[Path]:
    kc, lam = kc_panel(), lambda_panel()
    fig, ax = plt.subplots(1, 2, figsize=(11, 4.2))
    for c, ls in zip(CS, STYLES, strict=True):
        ax[0].plot(*kc[c], "k", ls=ls, label=f"c = {c:g}")
        ax[1].plot(*lam[c], "k", ls=ls, label=f"c = {c:g}")
    ax[0].set_yscale("log")
    ax[0].set_ylim(bottom=1e2)
    ax[0].set_ylabel("$k_c$ (N m$^{-1}$)")
    symlog_y(ax[1], np.concatenate([v[1] for v in lam.values()]))
    ax[1].set_ylabel(r"$\Lambda$ (m$^{-2}$ s$^{-1}$)")
    panel_title(ax[0], "(a) critical stiffness")
    panel_title(ax[1], r"(b) Landau coefficient ($\Lambda>0$ just below $V_m$ for c < c*)")
    for a in ax:
        vlabel(a)
        a.legend(fontsize=7)
    fig.suptitle("Putelat et al. (2010) Fig. 9 — spinodal law, M = 1.2 kg", fontsize=10)
    return save(fig, out_dir, "fig9")
