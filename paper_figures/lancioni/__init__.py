"""Figures of Lancioni, Lenci & Galvanetto (frictional impact oscillator), from the toolkit.

``landau figures lancioni [--only fig2]``.  Slip branches come from the engine (Hopf point,
:mod:`landau.derivation.general`) and shooting on the slip ODE; detached branches and orbits from the
hybrid engine (:mod:`landau.verify.lancioni`).  The φ̇_max section is φ̈ = 0, φ̇ > 0 (see
:mod:`landau.verify.lancioni.diagrams` for why not the OCR's "φ = 0").  Belt v = −1 m/s (the
direction with the Hopf point); Fig. 6: v = sin(πt/2).
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
from landau.verify.hybrid import simulate  # noqa: E402
from landau.verify.lancioni import analysis as A  # noqa: E402
from landau.verify.lancioni import diagrams as D  # noqa: E402
from landau.verify.lancioni.contact import default_options  # noqa: E402
from landau.verify.lancioni.model import build, slip_state  # noqa: E402
from landau.verify.lancioni.slip import SET1, SET2, equilibrium_phi, slip_hopf  # noqa: E402


def _save(fig, out_dir: Path, name: str) -> list[Path]:
    path = atomic_savefig(fig, Path(out_dir) / f"{name}.png", dpi=110, bbox_inches="tight")
    plt.close(fig)
    return [path]


def _slip_point(params, hopf, mu: float) -> dict[str, float]:
    """One μ of a slip branch: φ̇_max of the slip cycle (shooting; each μ on its own)."""
    return {"phidot_max": A.slip_cycle(mu, params, hopf=hopf).phidot_max}


def _slip_branch(params, mu_end, n=12):
    h = slip_hopf(params)
    mus = h.p_c + (mu_end - h.p_c) * np.linspace(0.02, 1.0, n) ** 2
    cyc = map_points(_slip_point, {"mu": mus}, fixed={"params": params, "hopf": h}, workers=workers())
    return h, mus, np.array([c["phidot_max"] for c in cyc])


def _orbit(mu, eN, params, y0, mode, t_end, t_keep):
    cm = build(mu, eN, params)
    sol = simulate(cm.model, mode or cm.initial_mode(0.0, y0), y0, (0.0, t_end), D.STEPPER,
                   default_options(record=True, samples=8))
    t, y, modes = sol.trajectory()
    k = t >= t_end - t_keep
    return t[k], y[:, k], [m for m, kk in zip(modes, k, strict=True) if kk], sol


def fig2(out_dir: Path) -> list[Path]:
    h, mus_s, w_s = _slip_branch(SET1, A.lift_off_mu(SET1)[0])
    fig, axs = plt.subplots(1, 2, figsize=(12, 4.2))
    det_mus = [0.4099, 0.405, 0.40, 0.395, 0.392, 0.390, 0.3897, 0.3896, 0.38957]
    y = np.array([0.38, 0.929, 0.0, 0.0])
    for ax in axs:
        ax.plot([0.38, h.p_c], [0, 0], "k-", lw=1.5, label="slip equilibrium")
        ax.plot([h.p_c, 0.42], [0, 0], "k:", lw=1)
        ax.plot(mus_s, w_s, "b-", lw=1.5, label="slip cycle (shooting)")
    for eN, c in ((0.0, "r"), (0.2, "g")):
        pts = D.diagram(det_mus if eN == 0 else det_mus[:6], y, None, eN=eN, t_transient=10.0, t_keep=3.0)
        for ax in axs:
            for p in pts:
                ax.plot(np.full(len(p.phidot_max), p.mu), p.phidot_max, c + ".", ms=4)
            ax.plot([], [], c + ".", label=f"detached, e_N={eN:g}")
    axs[0].set_ylim(-0.05, 1.2)
    axs[1].set_xlim(h.p_c - 2e-5, 0.40985)
    axs[1].set_ylim(-0.02, 0.35)
    axs[0].axvline(0.38957, color="gray", lw=0.5)
    for ax in axs:
        ax.set_xlabel("μ")
        ax.set_ylabel("φ̇_max")
    axs[0].legend(fontsize=7)
    axs[0].set_title("(a) set 1, v = −1: equilibrium, slip cycle, detached branches")
    axs[1].set_title(f"(b) Hopf μ_c={h.p_c:.6f} ({h.criticality}) to lift-off 0.409828")
    fig.suptitle("Fig. 2: bifurcation diagram (φ̇ maxima); paper: Hopf 0.40977, lift-off 0.40983, accumulation 0.38957")
    return _save(fig, out_dir, "fig2")


def fig3(out_dir: Path) -> list[Path]:
    fig, ax = plt.subplots(figsize=(6.5, 4.5))
    pe = equilibrium_phi(SET1, 0.3, 1)
    ax.plot([pe], [0], "ko", label="equilibrium μ=0.3")
    c = A.slip_cycle(0.4098, SET1)
    t, y, _, _ = _orbit(0.4098, 0.0, SET1, slip_state(build(0.4098).mech, c.phi_max), "slip+", 3.0, 0.4)
    ax.plot(y[0], y[2], "b-", label="slip cycle μ=0.4098")
    pts = D.diagram([0.4099, 0.400], np.array([0.38, 0.929, 0, 0]), None, eN=0.2, t_transient=10, t_keep=1)
    t, y, _, _ = _orbit(0.400, 0.2, SET1, pts[-1].state, pts[-1].mode, 2.0, 0.4)
    ax.plot(y[0], y[2], "g-", lw=0.8, label="bouncing μ=0.40, e_N=0.2")
    ax.set_xlabel("φ")
    ax.set_ylabel("φ̇")
    ax.legend(fontsize=8)
    ax.set_title("Fig. 3: orbits, set 1")
    return _save(fig, out_dir, "fig3")


def _set2_points():
    h = slip_hopf(SET2)
    mus = [0.362, 0.37, 0.38, 0.40, 0.42, 0.44, 0.45, 0.46, 0.48, 0.50]
    _, cyc = A.stick_onset_mu(SET2)  # start on the slip cycle where stick appears
    y = slip_state(build(0.362, 0.0, SET2).mech, cyc.phi_max)
    return h, D.diagram(mus, y, None, eN=0.0, params=SET2, t_transient=15.0, t_keep=4.0)


def fig4(out_dir: Path) -> list[Path]:
    h, mus_s, w_s = _slip_branch(SET2, A.stick_onset_mu(SET2)[0])
    h, pts = _set2_points()
    fig, ax = plt.subplots(figsize=(7, 4.5))
    ax.plot([0.3, h.p_c], [0, 0], "k-", label="slip equilibrium")
    ax.plot(mus_s, w_s, "b-", label="slip cycle")
    for p in pts:
        col = "m" if "flight" in p.modes else "r"
        ax.plot(np.full(len(p.phidot_max), p.mu), p.phidot_max, col + ".", ms=5)
    ax.plot([], [], "r.", label="stick-slip (sim.)")
    ax.plot([], [], "m.", label="with free flight (sim.)")
    for m in (0.353, 0.360, 0.453):
        ax.axvline(m, color="gray", lw=0.5)
    ax.axvline(0.44986, color="m", lw=0.5, ls="--", label="flight onset found 0.44986")
    ax.set_xlabel("μ")
    ax.set_ylabel("φ̇_max")
    ax.legend(fontsize=8)
    ax.set_title(f"Fig. 4: set 2 (m1=0.4, kφ=25), Hopf {h.p_c:.5f}; paper 0.353 / 0.360 / 0.453")
    return _save(fig, out_dir, "fig4")


def fig5(out_dir: Path) -> list[Path]:
    fig, ax = plt.subplots(figsize=(6.5, 4.5))
    y = slip_state(build(0.36, 0.0, SET2).mech, equilibrium_phi(SET2, 0.36, 1) + 0.05)
    mode = None
    for mu, col in ((0.357, "b"), (0.40, "r"), (0.44, "m"), (0.47, "k")):
        t, yy, _, sol = _orbit(mu, 0.0, SET2, y, mode, 15.0, 1.0)
        ax.plot(yy[0], yy[2], col + "-", lw=0.8, label=f"μ={mu}")
        y, mode = sol.y_final, sol.final_mode
    ax.set_xlabel("φ")
    ax.set_ylabel("φ̇")
    ax.legend(fontsize=8)
    ax.set_title("Fig. 5: set 2 orbits (e_N = 0)")
    return _save(fig, out_dir, "fig5")


def fig6(out_dir: Path) -> list[Path]:
    fig, axs = plt.subplots(2, 1, figsize=(9, 6), sharex=True)
    for ax, mu in zip(axs, (0.5, 0.3), strict=True):
        run = D.sine_belt_run(mu)
        ax.plot(run.t, run.y[2], "k-", lw=0.7, label="φ̇")
        ax.plot(run.t, np.sin(np.pi * run.t / 2), "b--", lw=0.7, label="v = sin(πt/2)")
        gap = run.y[1] - np.cos(run.y[0])
        ax.plot(run.t, 20 * gap, "r-", lw=0.7, label="20·g_N (flight)")
        ax.set_title(f"μ = {mu}: {len(run.flights)} flights, hopping time {run.hop_time:.3g} s")
        ax.legend(fontsize=7, loc="upper right")
    axs[1].set_xlabel("t [s]")
    fig.suptitle("Fig. 6: sinusoidal belt — hopping for μ = 0.5, none for μ = 0.3")
    return _save(fig, out_dir, "fig6")


FIGURES = OrderedDict([("fig2", fig2), ("fig3", fig3), ("fig4", fig4), ("fig5", fig5), ("fig6", fig6)])
