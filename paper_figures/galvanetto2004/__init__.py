"""Figures of Galvanetto (2004), J. Sound Vib. 276:121-139, regenerated from the toolkit.

``landau figures galvanetto2004 [--only fig12]``.  Phase portraits (Figs 7-10, 16) come
from the hybrid engine, the maps (11, 13, 14) and bifurcation diagrams (12, 15) from the
event maps of :mod:`landau.verify.galvanetto.maps`; bifurcation points are the located values of
:mod:`landau.verify.galvanetto.bifurcations`.
"""

from __future__ import annotations

from collections import OrderedDict
from dataclasses import replace
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

from landau.analyses.sweep_points import map_points  # noqa: E402
from landau.paper_figures import workers  # noqa: E402
from landau.support.io import atomic_savefig  # noqa: E402
from landau.verify.galvanetto import bifurcations as B  # noqa: E402
from landau.verify.galvanetto.analysis import FIG_STEPPER, beta_diagram, gsp_orbit_trajectory, map_curve, trajectory  # noqa: E402
from landau.verify.galvanetto.maps import iterate, model_for, one_block_cycle  # noqa: E402
from landau.verify.galvanetto.model import one_block, two_blocks  # noqa: E402
from landau.verify.hybrid import EngineOptions, Guard, HybridModel, Status, simulate  # noqa: E402


def _save(fig, out_dir: Path, name: str) -> list[Path]:
    path = atomic_savefig(fig, Path(out_dir) / f"{name}.png", dpi=110, bbox_inches="tight")
    plt.close(fig)
    return [path]


def _one_block_cycle_xy(p):
    """Stick–slip cycle of one block: slip from the stick end, then the stick segment."""
    sol = one_block_cycle(p, FIG_STEPPER, options=EngineOptions(record=True, samples=8))
    y = sol.y
    x_end = 1.0 - p.c * p.V
    if sol.status is Status.STOPPED:
        y = np.column_stack([y, [[x_end], [p.V]]])
    return y


def fig7(out_dir: Path) -> list[Path]:
    fig, axs = plt.subplots(1, 3, figsize=(12, 3.6))
    for ax, V, lab in zip(axs, (1.0, 3.0, 10.801), ("(a) below type II", "(b) between", "(c) type I"), strict=True):
        p = one_block(V, 3.0, 0.2, 0.0)
        y = _one_block_cycle_xy(p)
        ax.plot(y[0], y[1], "k-", lw=1)
        ax.plot([-1, 1], [V, V], "r-", lw=3, alpha=0.4, label="stick interval (3a)")
        ax.set_title(f"{lab}: V = {V:g}")
        ax.set_xlabel("X")
    axs[0].set_ylabel("dX/dt")
    axs[0].legend(fontsize=7)
    fig.suptitle("Fig. 7: one block, γ=3, δ=0.2 (the printed δ=0 is a misprint here), c=0: type II at V=1.2409, type I "
                 "at V=10.8011")
    return _save(fig, out_dir, "fig7")


def _two_block_portrait(axs, p, d0, period, label):
    d = iterate(p, d0, 60, FIG_STEPPER)[-1]
    y = gsp_orbit_trajectory(p, d, period)
    axs[0].plot(y[0], y[2], "k-", lw=0.8)
    axs[1].plot(y[1], y[3], "k-", lw=0.8)
    for ax, i in zip(axs, (1, 2), strict=True):
        ax.axhline(p.V, color="r", lw=0.5)
        ax.set_xlabel(f"X{i}")
        ax.set_ylabel(f"dX{i}/dt")
        ax.set_title(f"{label}, block {i}")


def fig8(out_dir: Path) -> list[Path]:
    fig, axs = plt.subplots(2, 2, figsize=(9, 7))
    for row, V in zip(axs, (0.18, 0.19), strict=True):
        _two_block_portrait(row, two_blocks(V, 1.2, 1.3, 3.0, 0.0), 0.0, 2, f"V={V}")
    fig.suptitle("Fig. 8: two blocks α=1.2, β=1.3, γ=3, δ=0 — type II sliding at V=0.18285 (located)")
    fig.tight_layout()
    return _save(fig, out_dir, "fig8")


def fig9(out_dir: Path) -> list[Path]:
    fig, axs = plt.subplots(2, 2, figsize=(9, 7))
    _two_block_portrait(axs[0], two_blocks(0.725, 1.2, 1.3, 3.0, 0.0), 0.0, 1, "V=0.725")
    p = two_blocks(0.740, 1.2, 1.3, 3.0, 0.0)   # no global stick phase: plain long run
    t, y, _ = trajectory(p, "ss", [0.5, 0.3, p.V, p.V], 300.0, t_keep=200.0)
    for ax, i in zip(axs[1], (0, 1), strict=True):
        ax.plot(y[i], y[2 + i], "k-", lw=0.6)
        ax.axhline(p.V, color="r", lw=0.5)
        ax.set_title(f"V=0.740, block {i + 1}")
        ax.set_xlabel(f"X{i + 1}")
    fig.suptitle("Fig. 9: two blocks, type I sliding at V=0.73501 (located)")
    fig.tight_layout()
    return _save(fig, out_dir, "fig9")


def _slip_field_backward(p, x0, v0, t_end):
    """Backward-time orbit of the smooth r<0 slip field (the unstable cycle attracts)."""
    from scipy.integrate import solve_ivp
    law, c, V = p.law, p.c, p.V
    s = solve_ivp(lambda t, y: [-y[1], (y[0] + c * y[1]) - law.neg(y[1] - V)], (0, t_end), [x0, v0],
                  rtol=1e-10, atol=1e-12, dense_output=True)
    tt = np.linspace(0.8 * t_end, t_end, 4000)
    return s.sol(tt)


def fig10(out_dir: Path) -> list[Path]:
    V = 0.5
    c1 = B.hopf_c1(V)
    c2 = B.nonsmooth_fold_c2(V).value
    cases = [(0.40, "(a) c < c1"), (0.60, "(b) c1 < c < c2"), (c2, "(c) c = c2"), (0.70, "(d) c > c2")]
    fig, axs = plt.subplots(1, 4, figsize=(15, 3.8))
    for ax, (c, lab) in zip(axs, cases, strict=True):
        p = one_block(V, 3.0, 0.0, c)
        x_eq = p.law.neg(-V)
        if c < c2 + 1e-12:
            y = _one_block_cycle_xy(p)
            ax.plot(y[0], y[1], "k-", lw=1.2, label="stick–slip attractor")
        if c > c1:
            u = _slip_field_backward(p, 1 - c * V - 1e-6 if c <= c2 else x_eq + 0.05, V if c <= c2 else 0.0, 400.0)
            ax.plot(u[0], u[1], "b--", lw=1, label="unstable cycle")
        t, y, _ = trajectory(p, "n", [x_eq + (0.01 if c < c1 else 1 - c * V - x_eq), 0.0 if c < c1 else V - 1e-3],
                             200.0 if c < c1 else 60.0)
        ax.plot(y[0], y[1], color="0.6", lw=0.5)
        ax.plot([x_eq], [0], "ko" if c > c1 else "wo", mec="k")
        ax.plot([-1 - c * V, 1 - c * V], [V, V], "r-", lw=3, alpha=0.4)
        ax.set_title(f"{lab}: c={c:.4f}")
        ax.set_xlabel("X")
    axs[0].set_ylabel("dX/dt")
    axs[1].legend(fontsize=7)
    fig.suptitle(f"Fig. 10: damped one block, V=0.5, γ=3, δ=0: subcritical Hopf c1={c1:.4f}, "
                 f"non-smooth fold c2={c2:.6f}")
    return _save(fig, out_dir, "fig10")


def _xmax_model(p):
    """One-block model with an extra section at the maxima of X (velocity 0 from above)."""
    base = model_for(p)
    g = Guard("xmax", lambda t, y: y[1])
    return HybridModel({k: replace(m, guards=m.guards + (g,)) for k, m in base.modes.items()}, name="xmax")


_XMAX_MODELS: dict[float, tuple] = {}


def _xmax_next(c: float, j: float) -> dict[str, float]:
    """Fig. 11, one point: the next maximum of X after the ``j``-th start X_max,n of the panel ``c``."""
    V = 0.5
    if c not in _XMAX_MODELS:   # one model per panel and process
        p = one_block(V, 3.0, 0.0, c)
        _XMAX_MODELS[c] = (p, _xmax_model(p))
    p, m = _XMAX_MODELS[c]
    x_eq = p.law.neg(-V)
    x = np.linspace(x_eq + 0.01, 2.2, 60)[int(j)]
    sol = simulate(m, "n", [x, 0.0], (0.0, 100.0), FIG_STEPPER, EngineOptions(record=False),
                   stop=lambda ev: ev.guard == "xmax" and ev.t > 1e-9)
    return {"x": float(x), "next": float(sol.y_final[0]) if sol.status is Status.STOPPED else np.nan}


def fig11(out_dir: Path) -> list[Path]:
    V = 0.5
    c2 = B.nonsmooth_fold_c2(V).value
    cs = (0.40, 0.60, c2, 0.70)
    # 4 panels x 60 independent starts, on the sweep engine
    pts = map_points(_xmax_next, {"c": cs, "j": np.arange(60)}, workers=workers(), chunk_size=10)
    fig, axs = plt.subplots(1, 4, figsize=(15, 3.8))
    for k, (ax, c) in enumerate(zip(axs, cs, strict=True)):
        xs = np.array([pt["x"] for pt in pts[60 * k:60 * (k + 1)]])
        nxt = [pt["next"] for pt in pts[60 * k:60 * (k + 1)]]
        ax.plot(xs, nxt, "k.-", ms=2, lw=0.8)
        ax.plot(xs, xs, "r:", lw=0.8)
        ax.set_title(f"c={c:.4f}")
        ax.set_xlabel("X_max,n")
    axs[0].set_ylabel("X_max,n+1")
    fig.suptitle("Fig. 11: one-dimensional map of successive maxima of X (damped one block, V=0.5)")
    return _save(fig, out_dir, "fig11")


def _fig12_attractor(b: float) -> dict[str, object]:
    """Fig. 12, one β: the map attractor born at the fold, iterated from just left of the kink."""
    from landau.verify.galvanetto.maps import f_n

    p = B.fig12_params(b)
    dk = B.kink(p, -0.096, FIG_STEPPER)
    d = dk - 1e-5
    pts = []
    for k in range(60):
        d = f_n(p, d, 1, FIG_STEPPER)
        if not -0.105 < d < -0.085:
            break
        if k >= 30:
            pts.append(d)
    return {"n": float(len(pts)), "d": pts}


def _fig12_period1(b: float) -> dict[str, float]:
    """Fig. 12, one β: the period-1 points left (stable until PD) and right (unstable) of the kink."""
    p = B.fig12_params(b)
    dk = B.kink(p, -0.096, FIG_STEPPER)
    out = {}
    for key, side in (("left", (dk - 0.004, dk - 1e-10)), ("right", (dk + 1e-10, dk + 0.004))):
        try:
            out[key] = B.periodic_point(p, 0, 1, FIG_STEPPER, bracket=side).d
            out[key + "_found"] = 1.0
        except Exception:
            out[key], out[key + "_found"] = np.nan, 0.0
    return out


def fig12(out_dir: Path) -> list[Path]:
    fold, pd, bc = B.discontinuous_fold().value, B.period_doubling().value, B.border_collision().value
    crisis = B.boundary_crisis().value
    fig, ax = plt.subplots(figsize=(9, 5.5))
    # attractor born at the fold: iterate from just left of the kink at every β (the
    # far attractor near d ≈ −0.05 coexists and is not drawn, as in the paper); every β on its
    # own, on the sweep engine
    betas = np.linspace(fold + 1e-6, 1.7290, 50)
    for b, pt in zip(betas, map_points(_fig12_attractor, {"b": betas}, workers=workers()), strict=True):
        pts = list(pt["d"][:int(pt["n"])])
        ax.plot(np.full(len(pts), b), pts, "k.", ms=1.5)
    # period-1 points left (stable until PD) and right (unstable) of the kink
    sb: list[float] = []
    sd: list[float] = []
    ub: list[float] = []
    ud: list[float] = []
    b14 = np.linspace(fold + 1e-6, 1.7290, 14)
    for b, pt in zip(b14, map_points(_fig12_period1, {"b": b14}, workers=workers()), strict=True):
        for key, bb, dd in (("left", sb, sd), ("right", ub, ud)):
            if pt[key + "_found"] == 1.0:
                dd.append(float(pt[key]))
                bb.append(b)
    sba, sda = np.array(sb), np.array(sd)
    ax.plot(sba[sba <= pd], sda[sba <= pd], "k-", lw=2, label="stable period-1")
    ax.plot(sba[sba >= pd], sda[sba >= pd], "g-", lw=0.8, label="unstable period-1 (after PD)")
    ax.plot(ub, ud, "b-", lw=0.8, label="unstable period-1 (fold)")
    for k, (x, lab) in enumerate(((fold, "fold"), (pd, "period doubling"), (bc, "border collision"),
                                  (crisis, "crisis (paper tick 1.7280)"))):
        ax.axvline(x, color="r", lw=0.5)
        ax.annotate(f"{lab} {x:.5f}", (x, -0.0995 + 0.0012 * k), fontsize=7, xytext=(3, 0),
                    textcoords="offset points")
    ax.set_ylim(-0.1010, -0.0915)
    ax.set_xlabel("β")
    ax.set_ylabel("d")
    ax.legend(fontsize=7, loc="upper right")
    ax.set_title("Fig. 12: two blocks α=1.2, γ=3, δ=0, V=0.25 (map attractor born at the fold)")
    return _save(fig, out_dir, "fig12")


def _map_panel(ax, beta, lo, hi, period=1, n=300):
    p = B.fig12_params(beta)
    ds = np.linspace(lo, hi, n)
    ax.plot(ds, map_curve(p, ds, period), "k-", lw=1)
    ax.plot(ds, ds, "r:", lw=0.8)
    ax.set_title(f"β={beta}" + (f", f^{period}" if period > 1 else ""))
    ax.set_xlabel("d_n")
    ax.set_ylabel("d_n+1")


def fig13(out_dir: Path) -> list[Path]:
    fig, ax = plt.subplots(figsize=(5.5, 5))
    beta = 1.7222
    _map_panel(ax, beta, -0.105, -0.088)
    p = B.fig12_params(beta)
    dk = B.kink(p)
    s = B.periodic_point(p, 0, 1, bracket=(dk - 0.004, dk - 1e-10)).d
    u = B.periodic_point(p, 0, 1, bracket=(dk + 1e-10, dk + 0.004)).d
    ax.plot([s], [s], "ko")
    ax.annotate("s", (s, s), textcoords="offset points", xytext=(-10, 5))
    ax.plot([u], [u], "wo", mec="k")
    ax.annotate("u", (u, u), textcoords="offset points", xytext=(5, -12))
    ax.set_title("Fig. 13: map f just past the discontinuous fold (β=1.7222)")
    return _save(fig, out_dir, "fig13")


def fig14(out_dir: Path) -> list[Path]:
    fig, axs = plt.subplots(2, 2, figsize=(9, 8.5))
    for col, beta in enumerate((1.7234, 1.7238)):
        _map_panel(axs[0, col], beta, -0.105, -0.088, 1)
        _map_panel(axs[1, col], beta, -0.103, -0.090, 2)
    fig.suptitle("Fig. 14: maps f and f² before (β=1.7234) and after (β=1.7238) the border collision")
    fig.tight_layout()
    return _save(fig, out_dir, "fig14")


def fig15(out_dir: Path) -> list[Path]:
    betas = np.linspace(1.7652, 1.7656, 25)
    res = beta_diagram(betas, -0.0858, n_transient=30, n_keep=4)
    bstar = B.grazing_sliding().value
    fig, ax = plt.subplots(figsize=(7, 5))
    for b, v in zip(res.params, res.values, strict=True):
        if v is not None:
            ax.plot(np.full(len(v), b), v, "k.", ms=3)
    ax.axvline(bstar, color="r", lw=0.6)
    ax.set_title(f"Fig. 15: grazing–sliding at β*={bstar:.7f} (block 1's short stick appears for β>β*)", fontsize=9)
    ax.set_xlabel("β")
    ax.set_ylabel("d (period-2 attractor)")
    return _save(fig, out_dir, "fig15")


def fig16(out_dir: Path) -> list[Path]:
    p = two_blocks(0.05, 1.2, 2.0, 10.756, 0.0)
    d = iterate(p, 0.1969494, 40, FIG_STEPPER)[-1]
    y = gsp_orbit_trajectory(p, d, 2)
    fig, axs = plt.subplots(1, 2, figsize=(10, 4.5))
    axs[0].plot(y[1], y[3], "k-", lw=0.8)
    axs[0].axhline(p.V, color="r", lw=0.5)
    axs[0].set_xlabel("X2")
    axs[0].set_ylabel("dX2/dt")
    axs[0].set_title("(a) phase plane of block 2")
    # zoom on the slip phase with r2 > 0 born from the stick phase (point P of the paper)
    up = np.nonzero(y[3] > p.V + 1e-12)[0]
    if len(up):
        ins = axs[0].inset_axes([0.3, 0.08, 0.4, 0.35])
        k0, k1 = max(up[0] - 40, 0), min(up[-1] + 40, y.shape[1])
        ins.plot(y[1, k0:k1], y[3, k0:k1] - p.V, "k.-", ms=1.5, lw=0.6)
        ins.axhline(0, color="r", lw=0.5)
        ins.set_title("zoom: dX2/dt − V near P", fontsize=7)
        ins.tick_params(labelsize=6)
    axs[1].plot(y[0], y[1], "k-", lw=0.8)
    a, b = p.alpha, p.beta
    # parallelogram Γ: |X1 + α(X1 − X2)| ≤ 1, |X2 + α(X2 − X1)| ≤ β
    M = np.array([[1 + a, -a], [-a, 1 + a]])
    corners = [np.linalg.solve(M, [s1, s2 * b]) for s1, s2 in ((1, 1), (1, -1), (-1, -1), (-1, 1), (1, 1))]
    axs[1].plot(*np.array(corners).T, "r-", lw=0.8)
    axs[1].set_xlabel("X1")
    axs[1].set_ylabel("X2")
    axs[1].set_title("(b) displacement plane and g.s.p. region Γ")
    fig.suptitle(f"Fig. 16: multi-sliding, α=1.2, β=2, δ=0, V=0.05, γ=10.756 (located "
                 f"γ*={B.multi_sliding(gamma=10.756, d0=0.1969494).value:.6f})")
    return _save(fig, out_dir, "fig16")


FIGURES = OrderedDict([("fig7", fig7), ("fig8", fig8), ("fig9", fig9), ("fig10", fig10), ("fig11", fig11),
                       ("fig12", fig12), ("fig13", fig13), ("fig14", fig14), ("fig15", fig15),
                       ("fig16", fig16)])
