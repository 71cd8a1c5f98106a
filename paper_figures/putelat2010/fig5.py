"""Fig. 5(a): Landau coefficients of the Ruina (solid) and Dieterich (dashed) laws, with the
Dieterich codimension-two point (Λ_D = 0, eq. 34; k_c ≈ 2.08e5 N/m of Fig. 5b)."""

from __future__ import annotations

from pathlib import Path

import matplotlib.pyplot as plt
import numpy as np

from landau.analyses.transition import codim2_points
from landau.paper_figures.putelat2010._common import derivation, panel_title, save, symlog_y, vlabel

V = np.logspace(-7, -2, 300)


def data() -> dict:
    R, Dl = derivation("ruina"), derivation("dieterich")
    return {"V": V, "Lambda_R": R.evaluate(V, {}, ["Lambda"])["Lambda"],
            "Lambda_D": Dl.evaluate(V, {}, ["Lambda"])["Lambda"],
            "codim2": codim2_points(Dl, float(V[0]), float(V[-1]))}


def make(out_dir: Path) -> list[Path]:
    d = data()
    fig, ax = plt.subplots(figsize=(6, 4.2))
    ax.plot(V, d["Lambda_R"], "k-", label="Ruina law")
    ax.plot(V, d["Lambda_D"], "k--", label="Dieterich law")
    for p in d["codim2"]:
        ax.plot([p.V], [0.0], "ko")
        ax.annotate(f"V* = {p.V:.4g} m/s\n$k_c$ = {p.kc:.4g} N/m", (p.V, 0.0), xytext=(8, 18),
                    textcoords="offset points", fontsize=8)
    symlog_y(ax, np.r_[d["Lambda_R"], d["Lambda_D"]])
    vlabel(ax)
    ax.set_ylabel(r"$\Lambda$ (m$^{-2}$ s$^{-1}$)")
    ax.legend(fontsize=8)
    panel_title(ax, "Putelat et al. (2010) Fig. 5(a): Landau coefficients, M = 1.2 kg")
    return save(fig, out_dir, "fig5")
