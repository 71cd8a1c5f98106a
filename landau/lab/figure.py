"""Friction against load-point displacement: the laboratory's plot of a protocol (Marone 1998, fig. 2).

A velocity step or a slide-hold-slide test is read as μ against the load-point displacement x_lp:
the direct effect and the evolution over the memory length are displacements, and a hold is a
vertical drop (relaxation) at a fixed x_lp followed by the peak on reloading.  :func:`plot_friction`
draws it from a run's series (the columns ``x_lp`` and ``mu``; the slip rate below on a
logarithmic axis when the series has ``v``), the hold pieces marked.  It is the default figure of
``landau simulate spring-block --V-history ... --out run.png``.

A fit's figures: :func:`plot_fit` (the record and the fitted model against the load-point
displacement, the residual below), :func:`plot_posterior` (the corner plot of an emcee posterior:
each parameter's histogram, each pair's density, the least-squares point) and :func:`plot_verdict`
(k_c of the rig with its uncertainty against the rig's stiffness: P(unstable) is the area beyond it).

References
----------
Marone, C. (1998), Annu. Rev. Earth Planet. Sci. 26, 643–696.
"""

from __future__ import annotations

import numpy as np

from landau.errors import InputError


def plot_friction(sim, *, fig=None, title: str | None = None):
    """μ against the load-point displacement (and v below, when the run has it) of a protocol's run.

    Parameters
    ----------
    sim : Simulation
        A load-point history's series with the columns ``x_lp`` and ``mu`` (its ``units`` label the axes).
    fig : matplotlib Figure, optional
        Draw into this figure (default a new one, shown once in a notebook).
    title : str, optional
        The figure's title.

    Returns
    -------
    matplotlib.figure.Figure
        Axes 0: μ against x_lp; axes 1 (with ``v``): v against x_lp, logarithmic.
    """
    names = list(sim.state_names)
    if "x_lp" not in names or "mu" not in names:
        raise InputError("friction against load-point displacement needs the columns x_lp and mu "
                         "(a load-point history's run)")
    if fig is None:
        from landau.support.figures import new_figure

        fig = new_figure(figsize=(7.5, 5.5), layout="constrained")
    x, mu = sim.y[names.index("x_lp")], sim.y[names.index("mu")]
    units = dict(getattr(sim, "units", {}) or {})
    xu = units.get("x_lp", "m")
    has_v = "v" in names and np.all(sim.y[names.index("v")] > 0)
    axes = fig.subplots(2, 1, sharex=True, height_ratios=(2, 1)) if has_v else [fig.subplots(1, 1)]
    ax = axes[0]
    ax.plot(x, mu, color="C0", lw=1.2)
    for a, b, label in getattr(sim, "regimes", ()) or ():
        if label == "hold":
            at = x[(sim.t >= a) & (sim.t <= b)]
            if len(at):
                ax.axvline(float(at[0]), color="0.6", lw=0.8, ls=":")
    ax.set_ylabel("friction coefficient mu")
    if has_v:
        axv = axes[1]
        axv.semilogy(x, sim.y[names.index("v")], color="C1", lw=1.0)
        axv.set_ylabel(f"slip rate v [{units.get('v', 'm/s')}]")
        axv.set_xlabel(f"load-point displacement x_lp [{xu}]")
    else:
        ax.set_xlabel(f"load-point displacement x_lp [{xu}]")
    if title:
        fig.suptitle(title, fontsize=10)
    return fig


def _figure(fig, size):
    if fig is None:
        from landau.support.figures import new_figure

        fig = new_figure(figsize=size, layout="constrained")
    return fig


def plot_fit(result, data, *, fig=None, title: str | None = None):
    """The record and the fitted model against the load-point displacement (µm), the residual below.

    Parameters
    ----------
    result : FitResult
        A fit (:func:`landau.lab.fit.fit`): its ``model`` (μ of the fitted law at each sample) and
        ``residual``.
    data : LabData
        The record it was fitted to.

    Returns
    -------
    matplotlib.figure.Figure
        Axes 0: μ of the record (points) and of the fit (line); axes 1: the residual μ_fit − μ.
    """
    if len(result.model) != len(data.mu):
        raise InputError(f"plot_fit: the fit has {len(result.model)} samples, the record {len(data.mu)}")
    fig = _figure(fig, (7.5, 5.5))
    ax, axr = fig.subplots(2, 1, sharex=True, height_ratios=(2, 1))
    x = np.asarray(data.x_lp) * 1e6
    ax.plot(x, data.mu, ".", color="0.55", ms=2.5, label="record")
    ax.plot(x, result.model, color="C0", lw=1.2, label=f"fit ({result.law.name})")
    ax.set_ylabel("friction coefficient mu")
    ax.legend(loc="best", fontsize=8)
    axr.plot(x, result.model - np.asarray(data.mu), color="C3", lw=0.8)
    axr.axhline(0.0, color="0.5", lw=0.6)
    axr.set_ylabel("residual")
    axr.set_xlabel("load-point displacement x_lp [um]")
    if title:
        fig.suptitle(title, fontsize=10)
    return fig


def plot_posterior(result, *, fig=None, bins: int = 30):
    """The corner plot of the fit's posterior draws (``result.samples``): each parameter's histogram on
    the diagonal, each pair's two-dimensional histogram below it, the least-squares values marked."""
    if result.samples is None:
        raise InputError("plot_posterior: the fit has no posterior draws (fit(..., mcmc=STEPS))")
    names, draws = list(result.names), np.asarray(result.samples)
    n = len(names)
    fig = _figure(fig, (2.2 * n + 1, 2.2 * n + 1))
    axes = fig.subplots(n, n, squeeze=False)
    for i in range(n):
        for j in range(n):
            ax = axes[i][j]
            if j > i:
                ax.set_visible(False)
                continue
            if i == j:
                ax.hist(draws[:, i], bins=bins, color="C0", histtype="step")
                ax.axvline(result.params[names[i]], color="C3", lw=0.8)
                ax.set_yticks([])
            else:
                ax.hist2d(draws[:, j], draws[:, i], bins=bins, cmap="Blues")
                ax.plot(result.params[names[j]], result.params[names[i]], "+", color="C3", ms=8)
            if i == n - 1:
                ax.set_xlabel(names[j])
            else:
                ax.set_xticklabels([])
            if j == 0 and i > 0:
                ax.set_ylabel(names[i])
            elif j > 0:
                ax.set_yticklabels([])
    return fig


def plot_verdict(verdict, *, fig=None):
    """k_c of the rig with its first-order uncertainty (a Gaussian) against the rig's stiffness k; the
    area beyond k is P(unstable) (:class:`~landau.lab.verdict.RigVerdict`)."""
    kc = float(verdict.values["k_c"])
    sd = None if verdict.sd_first_order is None else float(verdict.sd_first_order["k_c"])
    if not (np.isfinite(kc) and sd is not None and sd > 0):
        raise InputError("plot_verdict: needs k_c and its first-order standard deviation (a covariance)")
    fig = _figure(fig, (6.5, 3.5))
    ax = fig.subplots(1, 1)
    k = float(verdict.rig["k"])
    lo, hi = min(kc - 5 * sd, k - sd), max(kc + 5 * sd, k + sd)
    grid = np.linspace(lo, hi, 400)
    dens = np.exp(-0.5 * ((grid - kc) / sd) ** 2) / (sd * np.sqrt(2 * np.pi))
    ax.plot(grid, dens, color="C0", lw=1.2, label="k_c (first order)")
    gauss = verdict.p_unstable_gaussian if verdict.p_unstable_gaussian is not None else verdict.p_unstable
    ax.fill_between(grid, dens, where=grid > k, color="C3", alpha=0.3,
                    label=f"P(unstable) = {gauss:.3g} (first order)")
    ax.axvline(k, color="k", lw=1.0, ls="--", label="the rig's k")
    ax.set_xlabel("stiffness [N/m]")
    ax.set_yticks([])
    ax.set_title(f"{verdict.criticality} onset: P(unstable) = {verdict.p_unstable:.3g}, P(subcritical) = "
                 f"{verdict.p_subcritical:.3g} ({verdict.probabilities_from})", fontsize=9)
    ax.legend(loc="best", fontsize=8)
    return fig


__all__ = ["plot_fit", "plot_friction", "plot_posterior", "plot_verdict"]
