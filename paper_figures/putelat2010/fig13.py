"""Fig. 13: modified Dieterich law (39) — (a) Λ at c = 3e-4 (M = 1.2 kg solid, M = 0 dashed)
with the transition velocity V*; (b) V*(c) and V_m(c) (eq. 41), V*(3e-4) (•) and c* (○)."""

from __future__ import annotations

from pathlib import Path

import matplotlib.pyplot as plt
import numpy as np

from landau.analyses.transition import codim2_points, transition_curve
from landau.errors import NoHopfError
from landau.paper_figures import workers
from landau.paper_figures.putelat2010._common import V_S, derivation, panel_title, save, symlog_y, vlabel, vw_grid

C = 3e-4
A, B = 0.0349, 0.0489


def panel_a() -> dict:
    d = derivation("modified-dieterich")
    V = vw_grid(d, {"c": C}, 300, lo=1e-7)
    return {"V": V, "Lambda": d.evaluate(V, {"c": C}, ["Lambda"])["Lambda"],
            "Lambda_M0": d.evaluate(V, {"c": C, "M": 0.0}, ["Lambda"])["Lambda"],
            "codim2": codim2_points(d, float(V[0]), float(V[-1]), {"c": C})}


def panel_b() -> dict:
    d = derivation("modified-dieterich")
    curve = transition_curve(d, "c", 1e-5, 2e-3, n=22, workers=workers())
    # the branch that ends on V_m: the largest V* at each c
    top: dict[float, float] = {}
    for r in curve.rows:
        top[r.value] = max(top.get(r.value, 0.0), r.V_star)
    cs = np.array(sorted(top))
    c_star = curve.critical_value
    if c_star is None:
        raise NoHopfError("Fig. 13(b): the transition curve has no critical c* in c = 1e-5 ... 2e-3")
    return {"c": cs, "V_star": np.array([top[c] for c in cs]), "curve": curve,
            "c_grid": np.logspace(-5, np.log10(2e-3), 100), "c_star": c_star,
            "V_m_c_star": (B / A - 1) * V_S / c_star}


def make(out_dir: Path) -> list[Path]:
    a, b = panel_a(), panel_b()
    fig, ax = plt.subplots(1, 2, figsize=(11, 4.2))
    ax[0].plot(a["V"], a["Lambda"], "k-", label="M = 1.2 kg")
    ax[0].plot(a["V"], a["Lambda_M0"], "k--", label="M = 0")
    for p in a["codim2"]:
        ax[0].plot([p.V], [0.0], "ko")
        ax[0].annotate(f"V* = {p.V:.4g} m/s", (p.V, 0.0), xytext=(-90, 15), textcoords="offset points", fontsize=8)
    symlog_y(ax[0], np.r_[a["Lambda"], a["Lambda_M0"]])
    ax[0].set_ylabel(r"$\Lambda$ (m$^{-2}$ s$^{-1}$)")
    vlabel(ax[0])
    ax[0].legend(fontsize=7)
    panel_title(ax[0], "(a) Landau coefficient (45), c = 3e-4")
    cg = b["c_grid"]
    ax[1].plot(b["c"], b["V_star"], "k-", label="V*(c)")
    ax[1].plot(cg, (B / A - 1) * V_S / cg, "k--", label="$V_m(c)$ (41)")
    vs3 = max(p.V for p in a["codim2"])
    ax[1].plot([C], [vs3], "ko")
    ax[1].plot([b["c_star"]], [b["V_m_c_star"]], "o", mfc="white", mec="k")
    ax[1].annotate(f"c* = {b['c_star']:.4g}", (b["c_star"], b["V_m_c_star"]), xytext=(-70, -25),
                   textcoords="offset points", fontsize=8)
    ax[1].set_xscale("log")
    ax[1].set_yscale("log")
    ax[1].set_xlabel("c")
    ax[1].set_ylabel("V (m s$^{-1}$)")
    ax[1].legend(fontsize=7)
    panel_title(ax[1], "(b) transition velocity V*(c)")
    fig.suptitle("Putelat et al. (2010) Fig. 13 — modified Dieterich law (39)", fontsize=10)
    return save(fig, out_dir, "fig13")
