"""Figures of Skurativskyi et al. (2019), Nonlinear Dyn. 98:1795, regenerated from the toolkit.

``landau figures skurativskyi2019 [--only fig3]``.  Bifurcation diagrams come from the
continuation sweeps of :mod:`landau.verify.skurativskyi.sweep` (the sweep engine, on
``landau figures --workers`` local processes; the numbers do not depend on it), phase portraits
and profiles from :func:`landau.verify.skurativskyi.simulate.run`.  Default resolutions are
modest (ω steps 0.05 rad/s, 30–150 recorded periods, rtol 1e-7) so that every figure runs
in under a minute on two cores; the paper uses steps of 0.005 rad/s.
"""

from __future__ import annotations

from collections import OrderedDict
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

from landau.analyses.sweep_points import map_points  # noqa: E402
from landau.paper_figures import workers  # noqa: E402
from landau.support.io import atomic_savefig  # noqa: E402
from landau.verify.skurativskyi.model import PAPER  # noqa: E402
from landau.verify.skurativskyi.simulate import run  # noqa: E402
from landau.verify.skurativskyi.sweep import SweepSpec, run_sweep  # noqa: E402

RTOL_FIG = 1e-7


def _save(fig, out_dir: Path, name: str) -> list[Path]:
    path = atomic_savefig(fig, Path(out_dir) / f"{name}.png", dpi=110, bbox_inches="tight")
    plt.close(fig)
    return [path]


def _diagram(ax_x, ax_t, res, color, label, ms=2.0):
    w_x = np.concatenate([np.full(len(a.x_section), a.omega) for a in res.values])
    x = np.concatenate([a.x_section for a in res.values]) * 1e3
    ax_x.plot(w_x, x, "o", color=color, ms=ms, mew=0, label=label)
    if ax_t is not None:
        w_t = np.concatenate([np.full(len(a.intervals), a.omega) for a in res.values])
        T = np.concatenate([a.intervals for a in res.values])
        ax_t.plot(w_t, T, "o", color=color, ms=ms, mew=0)


def fig2cd(out_dir: Path) -> list[Path]:
    om = np.round(np.arange(13.8, 25.0 + 1e-9, 0.05), 6)
    # small chunks: below ω ≈ 15.5 the cart sticks on the obstacle for most of the period and
    # the explicit step is bounded by the Hertz-damping slope (those points cost ~10× more)
    res = run_sweep(om, "up", spec=SweepSpec(n_first=60, n_step=30, n_keep=30, rtol=RTOL_FIG), chunk_size=10,
                    progress=False, workers=workers())
    fig, (a, b) = plt.subplots(1, 2, figsize=(12, 4.2))
    _diagram(a, b, res, "k", "increasing ω")
    a.axhline(PAPER.xI * 1e3, color="r", lw=0.6)
    a.set_xlabel("ω [rad/s]")
    a.set_ylabel("x [mm] at t = 2πi/ω")
    a.set_title("(c) Poincaré section")
    b.set_xlabel("ω [rad/s]")
    b.set_ylabel("T_j [s]")
    b.set_ylim(0, 0.42)
    b.set_title("(d) inter-impact intervals")
    fig.suptitle("Fig. 2(c,d): simulated bifurcation diagrams, increasing ω (step 0.05, 30 periods kept)")
    return _save(fig, out_dir, "fig2cd")


def _updown(lo, hi, step, title, name, out_dir):
    om = np.round(np.arange(lo, hi + 1e-9, step), 6)
    spec = SweepSpec(n_first=100, n_step=40, n_keep=40, rtol=RTOL_FIG)
    up = run_sweep(om, "up", spec=spec, progress=False, workers=workers())
    dn = run_sweep(om, "down", spec=spec, progress=False, workers=workers())
    fig, (a, b) = plt.subplots(2, 1, figsize=(9, 7.5), sharex=True)
    _diagram(a, b, up, "r", "increasing ω", ms=3.0)
    _diagram(a, b, dn, "g", "decreasing ω", ms=1.6)
    a.set_ylabel("x [mm] at t = 2πi/ω")
    a.legend(fontsize=8, markerscale=2)
    b.set_ylabel("T_j [s]")
    b.set_xlabel("ω [rad/s]")
    a.set_title(title)
    return _save(fig, out_dir, name)


def fig3(out_dir: Path) -> list[Path]:
    return _updown(20.5, 25.0, 0.05, "Fig. 3: ω ∈ [20.5, 25]: section (a) and T_j (b); red up, green down",
                   "fig3", out_dir)


def fig4(out_dir: Path) -> list[Path]:
    return _updown(17.5, 20.5, 0.05, "Fig. 4: ω ∈ [17.5, 20.5]: section (a) and T_j (b); red up, green down",
                   "fig4", out_dir)


def fig5(out_dir: Path) -> list[Path]:
    om = np.round(np.arange(17.5, 23.0 + 1e-9, 0.05), 6)
    spec = SweepSpec(n_first=100, n_step=50, n_keep=150, rtol=RTOL_FIG, lyapunov=True)
    fig, ax = plt.subplots(figsize=(9, 4))
    for d, c in (("up", "r"), ("down", "g")):
        res = run_sweep(om, d, spec=spec, progress=False, workers=workers())
        ax.plot(res.params, [a.lyapunov for a in res.values], "-", color=c, lw=1, label=f"{d} sweep")
    ax.axhline(0, color="k", lw=0.5)
    ax.set_xlabel("ω [rad/s]")
    ax.set_ylabel("λ₁ [1/s]")
    ax.set_title("Fig. 5: top Lyapunov exponent (step 0.05, 150 periods, renormalised every period)")
    ax.legend(fontsize=8)
    return _save(fig, out_dir, "fig5")


def _portrait_data(i: float, cases: tuple, n_transient: int = 60, rtol: float = RTOL_FIG) -> dict:
    """One portrait (case ``i`` of ``cases`` = ((ω, periods shown), ...)): a dense trajectory over the
    periods shown after a transient, its section points and impacts (each case on its own)."""
    omega, n_show = cases[int(i)]
    p = PAPER.with_(omega=omega)
    y0 = run(p, n_transient, rtol=rtol, strobe=False).y_final
    # dense trajectory for the plot: short sub-runs of 1/200 period
    P = p.period
    ts, xs, vs = [0.0], [y0[0]], [y0[1]]
    y = y0
    for k in range(200 * n_show):
        r = run(p, 1 / 200, y, t0=k * P / 200, rtol=rtol, strobe=False)
        y = r.y_final
        ts.append(r.t_final)
        xs.append(y[0])
        vs.append(y[1])
    r = run(p, n_show, y0, rtol=rtol)
    return {"t": ts, "x": xs, "v": vs, "strobe_x": r.strobe_y[:, 0], "strobe_v": r.strobe_y[:, 1],
            "n_strobe": float(len(r.strobe_y)), "impact_v": r.impact_v, "n_impacts": float(len(r.impacts))}


def _portraits(axs, cases: tuple, profile: bool = False) -> None:
    """The portraits of ``cases`` = ((ω, periods shown), ...) on ``axs``, computed on the sweep engine."""
    data = map_points(_portrait_data, {"i": np.arange(len(cases))}, fixed={"cases": tuple(cases)},
                      workers=workers())
    for ax, (omega, n_show), d in zip(axs, cases, data, strict=True):
        p = PAPER.with_(omega=omega)
        xs, vs, ts = np.asarray(d["x"]) * 1e3, np.asarray(d["v"]) * 1e3, np.asarray(d["t"])
        n = 200 * n_show + 1
        xs, vs, ts = xs[:n], vs[:n], ts[:n]
        if profile:
            ax.plot(ts, xs, "k-", lw=0.8)
            ax.axhline(p.xI * 1e3, color="r", lw=0.8)
            ax.set_xlabel("t [s]")
            ax.set_ylabel("x [mm]")
        else:
            m, k = int(d["n_strobe"]), int(d["n_impacts"])
            ax.plot(xs, vs, "k-", lw=0.7)
            ax.axvline(p.xI * 1e3, color="r", lw=0.8)
            ax.plot(np.asarray(d["strobe_x"][:m]) * 1e3, np.asarray(d["strobe_v"][:m]) * 1e3, "o", color="r", ms=4)
            ax.plot(np.full(k, p.xI * 1e3), np.asarray(d["impact_v"][:k]) * 1e3, "o", color="b", ms=3)
            ax.set_xlabel("x [mm]")
            ax.set_ylabel("dx/dt [mm/s]")
        ax.set_title(f"ω = {omega:g} rad/s ({int(d['n_impacts']) / n_show:g} impacts/period)", fontsize=9)


def fig8(out_dir: Path) -> list[Path]:
    fig, axs = plt.subplots(2, 4, figsize=(15, 7))
    _portraits(list(axs.flat), tuple(zip((14.0, 14.1, 15.0, 16.0, 17.0, 17.5, 18.0, 19.0), (1, 1, 1, 1, 1, 1, 4, 2),
                                         strict=True)))
    fig.suptitle("Fig. 8: impact adding (red line x = x_I, red dots t = 2πi/ω, blue dots impacts)")
    fig.tight_layout()
    return _save(fig, out_dir, "fig8")


def fig10(out_dir: Path) -> list[Path]:
    fig, axs = plt.subplots(1, 3, figsize=(14, 3.8))
    _portraits(list(axs), tuple(zip((15.0, 16.7, 18.0), (1, 1, 4), strict=True)), profile=True)
    fig.suptitle("Fig. 10: profiles x(t) with micro-impacts near the stop (red line x = x_I)")
    fig.tight_layout()
    return _save(fig, out_dir, "fig10")


FIGURES = OrderedDict([("fig2cd", fig2cd), ("fig3", fig3), ("fig4", fig4), ("fig5", fig5),
                       ("fig8", fig8), ("fig10", fig10)])
