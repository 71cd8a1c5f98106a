"""Friction against load-point displacement: the laboratory's plot of a protocol (Marone 1998, fig. 2).

A velocity step or a slide-hold-slide test is read as μ against the load-point displacement x_lp:
the direct effect and the evolution over the memory length are displacements, and a hold is a
vertical drop (relaxation) at a fixed x_lp followed by the peak on reloading.  :func:`plot_friction`
draws it from a run's series (the columns ``x_lp`` and ``mu``; the slip rate below on a
logarithmic axis when the series has ``v``), the hold pieces marked.  It is the default figure of
``landau simulate spring-block --V-history ... --out run.png``.

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


__all__ = ["plot_friction"]
