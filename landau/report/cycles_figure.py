"""The bifurcation diagram of a branch of cycles: amplitude and period against the continuation parameter.

:func:`plot_cycle_branch` draws, from a :class:`~landau.analyses.cycles.BranchTable` (the branch's
columns and special points, :func:`landau.analyses.cycles.branch_table`):

* left, the amplitude (half peak-to-peak of the measured state) against the parameter: the cycles
  stable where every nontrivial Floquet multiplier lies inside the unit circle (solid) and unstable
  elsewhere (dashed); the equilibrium branch (amplitude 0: solid where stable, dashed where
  unstable) and the Hopf point (a square);
* right, the period, with the Hopf point at 2π/ω_c;
* on both, the special points: folds of cycles LPC (circle), period doublings PD (triangle),
  Neimark–Sacker points NS (diamond), each labelled.

It follows the plotting convention of :mod:`landau.report.plotting` (given ``fig=`` it draws there;
else a new figure from :func:`landau.support.figures.new_figure`; it never shows or saves) and
returns a summary of what it drew (the command line's JSON).

References
----------
Kuznetsov, Y. A. (2004), *Elements of Applied Bifurcation Theory*, 3rd ed., Springer, Ch. 10 (the
diagrams of cycles and their bifurcations); Putelat, Dawes & Willis (2010), Fig. 6 (the style:
stable solid, unstable dotted, the Hopf point and the saddle-node of cycles marked).
"""

from __future__ import annotations

from typing import Any

import numpy as np

#: the marker of each kind of special point
MARKERS = {"LPC": "o", "PD": "^", "NS": "D", "BP": "s"}
#: the line style of stable and unstable solutions
STYLES = {True: "-", False: "--"}


def runs(stable: np.ndarray) -> list[tuple[int, int, bool]]:
    """The maximal runs of equal stability: (first, last + 1, stable) with neighbouring runs sharing
    their end point (so that the drawn line is continuous)."""
    stable = np.asarray(stable, dtype=bool)
    out: list[tuple[int, int, bool]] = []
    start = 0
    for i in range(1, stable.size + 1):
        if i == stable.size or stable[i] != stable[start]:
            out.append((start, min(i + 1, stable.size), bool(stable[start])))
            start = i
    return out


def _draw(ax, x, y, stable, colour) -> int:
    n = 0
    for a, b, st in runs(stable):
        ax.plot(x[a:b], y[a:b], STYLES[st], color=colour, lw=1.6)
        n += 1
    return n


def plot_cycle_branch(table, *, fig=None, colour: str = "C0") -> dict[str, Any]:
    """Draw the branch ``table`` (a :class:`~landau.analyses.cycles.BranchTable`) on ``fig`` (module docstring).

    Returns
    -------
    dict
        ``axes`` (the two Axes), ``lines`` (runs of stable and unstable cycles drawn), ``special``
        (kind → number of markers), ``hopf`` (whether the Hopf point was drawn).
    """
    if fig is None:
        from landau.support.figures import new_figure

        fig = new_figure(figsize=(9.0, 3.8))
    ax_a, ax_t = fig.subplots(1, 2)
    p, stable = np.asarray(table.p, dtype=float), np.asarray(table.stable, dtype=bool)
    n_lines = _draw(ax_a, p, np.asarray(table.amplitude, dtype=float), stable, colour)
    _draw(ax_t, p, np.asarray(table.period, dtype=float), stable, colour)
    hopf = table.hopf
    drawn_hopf = False
    if hopf is not None:
        lo, hi = float(np.nanmin(np.append(p, hopf.p_c))), float(np.nanmax(np.append(p, hopf.p_c)))
        pad = 0.05 * (hi - lo or abs(hopf.p_c) or 1.0)
        # the equilibrium branch: stable on one side of p_c, unstable on the other
        for a, b, st in ((lo - pad, hopf.p_c, hopf.equilibrium_stable_below), (hopf.p_c, hi + pad,
                                                                               not hopf.equilibrium_stable_below)):
            ax_a.plot([a, b], [0.0, 0.0], STYLES[bool(st)], color="0.3", lw=1.2)
        ax_a.plot([hopf.p_c], [0.0], "s", color="k", ms=6, label="Hopf")
        ax_t.plot([hopf.p_c], [2 * np.pi / hopf.omega], "s", color="k", ms=6)
        drawn_hopf = True
    special: dict[str, int] = {}
    for sp in table.special:
        m = MARKERS.get(sp.kind, "x")
        first = sp.kind not in special
        ax_a.plot([sp.p], [sp.amplitude], m, color="C3", ms=7, mfc="none", mew=1.6,
                  label=sp.kind if first else None)
        ax_t.plot([sp.p], [sp.period], m, color="C3", ms=7, mfc="none", mew=1.6)
        ax_a.annotate(sp.kind, (sp.p, sp.amplitude), textcoords="offset points", xytext=(4, 4), fontsize=8)
        special[sp.kind] = special.get(sp.kind, 0) + 1
    unit = f" [{table.unit}]" if table.unit else ""
    ax_a.set_xlabel(table.parameter)
    ax_a.set_ylabel(f"amplitude of {table.measure}{unit}")
    ax_t.set_xlabel(table.parameter)
    ax_t.set_ylabel("period")
    ax_t.ticklabel_format(axis="y", useOffset=False)
    for ax in (ax_a, ax_t):
        ax.tick_params(axis="x", labelrotation=25)
    ax_a.set_title(table.name, fontsize=9)
    if special or drawn_hopf:
        ax_a.legend(fontsize=8, loc="best")
    return {"axes": [ax_a, ax_t], "lines": n_lines, "special": special, "hopf": drawn_hopf}


__all__ = ["MARKERS", "STYLES", "plot_cycle_branch", "runs"]
