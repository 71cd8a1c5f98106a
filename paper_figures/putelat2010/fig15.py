"""Fig. 15: nanoscale contact law (48), a₂ = 0.0085 — (a) μ_ss, (b) k_c, (c) Λ with its two
sign changes V_l* ≈ 6.24e-6 and V_h* ≈ 3.41e-4 m/s.  Panel (b) never builds cubic derivatives.
The thin dotted line is the spinodal law (37)–(38), c = 1e-3."""

from __future__ import annotations

from pathlib import Path

import matplotlib.pyplot as plt
import numpy as np

from landau.analyses.transition import codim2_points
from landau.paper_figures.putelat2010._common import derivation, mu_ss, panel_title, save, symlog_y, vlabel, vw_grid

LAW, REF = "nanoscale", ("spinodal", {"c": 1e-3})
PARAMS: dict[str, float] = {}


def kc_panel(d=None, law=LAW, params=PARAMS) -> dict:
    d = d or derivation(law)
    V = vw_grid(d, params, 240)
    return {"V": V, "kc": d.evaluate(V, params, ["kc"])["kc"]}


def lambda_panel(law=LAW, params=PARAMS) -> dict:
    d = derivation(law)
    V = vw_grid(d, params, 300)
    return {"V": V, "Lambda": d.evaluate(V, params, ["Lambda"])["Lambda"],
            "codim2": codim2_points(d, float(V[0]) * 0.999, float(V[-1]) * 1.001, params)}


def make_law_figure(out_dir: Path, name: str, law: str, cases: dict, title: str) -> list[Path]:
    """μ_ss, k_c, Λ for ``cases`` = {label: params} of ``law`` plus the spinodal reference."""
    fig, ax = plt.subplots(1, 3, figsize=(14, 4.2))
    Vmu = np.logspace(-9, -1, 300)
    ref = derivation(REF[0])
    ax[0].plot(Vmu, mu_ss(ref, Vmu, REF[1]), "k:", lw=0.8, label="law (37)-(38), c = 1e-3")
    kref = kc_panel(ref, *REF)
    ax[1].plot(kref["V"], kref["kc"], "k:", lw=0.8, label="law (37)-(38)")
    # one or two cases: the line styles are taken in order
    for (lab, prm), ls in zip(cases.items(), ("-", "--"), strict=False):
        ax[0].plot(Vmu, mu_ss(derivation(law), Vmu, prm), "k", ls=ls, label=lab)
        k = kc_panel(None, law, prm)
        ax[1].plot(k["V"], k["kc"], "k", ls=ls, label=lab)
        lp = lambda_panel(law, prm)
        ax[2].plot(lp["V"], lp["Lambda"], "k", ls=ls, label=lab)
        for j, p in enumerate(lp["codim2"]):
            ax[2].plot([p.V], [0.0], "ko")
            ax[2].annotate(f"{p.V:.4g}", (p.V, 0.0), xytext=(4, 10 if (j + len(ax[2].texts)) % 2 else -16),
                           textcoords="offset points", fontsize=8)
    symlog_y(ax[2], np.concatenate([l.get_ydata() for l in ax[2].get_lines() if len(l.get_ydata()) > 2]))
    ax[0].set_ylabel(r"$\mu_{ss}$")
    ax[1].set_yscale("log")
    ax[1].set_ylim(bottom=1e2)
    ax[1].set_ylabel("$k_c$ (N m$^{-1}$)")
    ax[2].set_ylabel(r"$\Lambda$ (m$^{-2}$ s$^{-1}$)")
    for a, t in zip(ax, ("(a) steady-state friction", "(b) critical stiffness", r"(c) Landau coefficient"),
                    strict=True):
        panel_title(a, t)
        vlabel(a)
        a.legend(fontsize=7)
    fig.suptitle(title, fontsize=10)
    return save(fig, out_dir, name)


def make(out_dir: Path) -> list[Path]:
    return make_law_figure(out_dir, "fig15", LAW, {r"$a_2$ = 0.0085": PARAMS},
                           "Putelat et al. (2010) Fig. 15 — nanoscale contact law (48), Table 1, M = 1.2 kg")
