"""Plots of the toolkit's results (matplotlib, imported only when a plot is asked for).

Every function returns the matplotlib object it drew on — a Figure for multi-panel plots,
an Axes otherwise — so that a script can restyle or save it
(:func:`landau.support.io.atomic_savefig`).  Nothing here computes more than it plots.

* :func:`plot_coefficients` — k_c, Λ, C, … against the driving velocity V, with the
  supercritical (Λ < 0) and subcritical (Λ > 0) ranges shaded;
* :func:`plot_regime_diagram` — the Hopf line in the (V, k) plane split by criticality, the
  codimension-two points and the inertial boundary (Putelat et al. 2010, Figs 5b, 14a);
* :func:`plot_check` — simulated against predicted cycle amplitude over ε², with the
  fitted exponent of the relative error.

**The convention every plotting function and method of the toolkit follows** (this module's,
``Derivation.plot``, ``CoefficientTable.plot``, ``RegimeDiagram.plot``, ``Simulation.plot``, the
command line's): a figure is shown *exactly once* wherever it is drawn, so

1. A function that makes its own figure makes it with :func:`landau.support.figures.new_figure`
   (importable from every layer, the simulation engine's included; never with
   ``matplotlib.figure.Figure(...)`` or ``plt.figure(...)`` directly).  The figure is managed by
   pyplot — a script shows it with ``plt.show()``, a notebook's inline backend at the end of the
   cell, whether the call is the cell's last line or assigned (``fig = d.plot()``) — and it does
   not show a second time as the cell's value; evaluated again in a
   later cell (pyplot has let it go by then) it shows once more, as a returned value should.
   Importing pyplot first also switches a notebook's figure display on, so the first figure of
   a session is an image, not ``<Figure …>`` text.
2. A function that is given ``fig=`` or ``ax=`` draws there and returns that object untouched.
3. No plotting function calls ``plt.show()``, ``plt.close()`` or ``savefig``: the caller
   decides.  A caller that only saves (the command line) draws into a figure of its own given as
   ``fig=`` (a ``matplotlib.figure.Figure``, which pyplot never shows), or closes the one it got
   with ``plt.close(fig)`` after :func:`landau.support.io.atomic_savefig`.
4. The function returns the Figure (several panels) or the Axes (one panel) it drew on.
"""

from __future__ import annotations

import math
from typing import Any, Mapping, Sequence

import numpy as np

from landau.errors import InputError
from landau.support.figures import new_figure

#: colours of the criticality bands
BAND_COLOURS = {"supercritical": "tab:blue", "subcritical": "tab:red", "no Hopf point": "0.6"}

#: axis labels of the spring–block quantities (mathtext)
LABELS = {
    "V": r"$V$ [m/s]",
    "kc": r"$k_c$ [N/m]",
    "omega_c": r"$\omega_c$ [rad/s]",
    "Gamma_bar": r"$\bar\Gamma$ [1/(N s)]",
    "Omega_bar": r"$\bar\Omega$ [1/(N s)]",
    "Lambda": r"$\Lambda$ [1/(m$^2$ s)]",
    "chi": r"$\chi$ [1/(m$^2$ s)]",
    "C": r"$C$ [m/$\sqrt{\mathrm{N/m}}$]",
}


def _new_figure(fig, nrows: int, ncols: int = 1, **kw):
    """Axes on ``fig`` (cleared) or on a new figure (:func:`landau.support.figures.new_figure`)."""
    if fig is None:
        fig = new_figure(figsize=kw.pop("figsize", (6.4, 2.2 * nrows + 0.8)))
    else:
        fig.clf()
    axes = fig.subplots(nrows, ncols, squeeze=False, **kw)
    return fig, axes


def criticality_bands(V: np.ndarray, kc: np.ndarray, Lambda: np.ndarray) -> list[tuple[float, float, str]]:
    """Contiguous velocity ranges of one kind: "supercritical" (Λ < 0), "subcritical" (Λ > 0)
    or "no Hopf point" (k_c not finite or ≤ 0).

    Parameters
    ----------
    V, kc, Lambda : array_like
        The sampled velocities (any order) and the values there.

    Returns
    -------
    list of (lo, hi, kind)
        Ranges in increasing V; a boundary lies at the geometric mean of the two samples on
        either side of it (the sampling resolves it no better).
    """
    V = np.ravel(np.asarray(V, dtype=float))
    order = np.argsort(V)
    V = V[order]
    kc = np.ravel(np.broadcast_to(np.asarray(kc, dtype=float), np.shape(order)))[order]
    lam = np.ravel(np.broadcast_to(np.asarray(Lambda, dtype=float), np.shape(order)))[order]
    kinds = np.where(~np.isfinite(kc) | (kc <= 0), "no Hopf point",
                     np.where(lam < 0, "supercritical", np.where(lam > 0, "subcritical", "degenerate")))
    out: list[tuple[float, float, str]] = []
    i = 0
    while i < len(V):
        j = i
        while j + 1 < len(V) and kinds[j + 1] == kinds[i]:
            j += 1
        lo = V[i] if i == 0 else math.sqrt(V[i - 1] * V[i])
        hi = V[j] if j == len(V) - 1 else math.sqrt(V[j] * V[j + 1])
        out.append((float(lo), float(hi), str(kinds[i])))
        i = j + 1
    return out


def plot_coefficients(table: Mapping[str, Any], names: Sequence[str] | None = None, *, fig=None):
    """Amplitude-equation coefficients against the driving velocity, one panel each.

    Parameters
    ----------
    table : mapping
        Quantity -> array over V, e.g. a :class:`landau.derivation.multiscale.CoefficientTable` from
        :meth:`Derivation.evaluate` (must hold ``"V"``; the bands need ``"kc"`` and ``"Lambda"``).
    names : sequence of str, optional
        Quantities to plot (default: those of k_c, Λ, C present in the table).
    fig : matplotlib.figure.Figure, optional
        Draw into this figure (cleared first).

    Returns
    -------
    matplotlib.figure.Figure
        Panels share the logarithmic V axis; Λ is drawn on a symmetric-log scale (it changes
        sign); the supercritical / subcritical / no-Hopf ranges are shaded on every panel.
    """
    if "V" not in table:
        raise InputError("plot_coefficients needs the velocities 'V' in the table")
    if names is None:
        names = [n for n in ("kc", "Lambda", "C") if n in table] or [
            n for n in table if n not in ("V", "degenerate")]
    missing = [n for n in names if n not in table]
    if missing:
        raise InputError(f"quantity {missing[0]!r} is not in the table (has: {', '.join(table)})")
    V = np.ravel(np.asarray(table["V"], dtype=float))
    order = np.argsort(V)
    fig, axes = _new_figure(fig, len(names), sharex=True)
    bands = []
    if "kc" in table and "Lambda" in table:
        bands = criticality_bands(V, table["kc"], table["Lambda"])
    for ax, name in zip(axes[:, 0], names, strict=True):
        y = np.ravel(np.broadcast_to(np.asarray(table[name], dtype=float), V.shape))[order]
        finite = y[np.isfinite(y)]
        label = LABELS.get(name, name)
        if finite.size and np.all(finite > 0):
            ax.plot(V[order], y, color="k", lw=1.2)
            ax.set_yscale("log")
        elif finite.size and np.any(finite != 0):
            # a quantity that changes sign over decades (Λ): |value| on a log scale, the sign
            # by the line style
            ax.plot(V[order], np.where(y < 0, -y, np.nan), color="k", lw=1.2, label=f"{name} < 0")
            ax.plot(V[order], np.where(y > 0, y, np.nan), color="k", lw=1.2, ls="--", label=f"{name} > 0")
            ax.set_yscale("log")
            label = "|" + label.split(" [")[0] + "|" + (" [" + label.split(" [")[1] if " [" in label else "")
            ax.legend(loc="lower right", fontsize="small")
        else:
            ax.plot(V[order], y, color="k", lw=1.2)
        ax.set_xscale("log")
        ax.set_ylabel(label)
        seen = set()
        for lo, hi, kind in bands:
            if kind in BAND_COLOURS:
                ax.axvspan(lo, hi, color=BAND_COLOURS[kind], alpha=0.12, lw=0,
                           label=None if kind in seen else kind)
                seen.add(kind)
        ax.grid(True, which="major", alpha=0.3)
    axes[-1, 0].set_xlabel(LABELS["V"])
    if bands:
        axes[0, 0].legend(handles=[h for h in axes[0, 0].get_legend_handles_labels()[0]
                                   if h.get_label() in BAND_COLOURS], loc="best", fontsize="small")
    law = getattr(table, "law", "")
    if law:
        fig.suptitle(f"Amplitude equation, law {law}")
    fig.tight_layout()
    return fig


def plot_regime_diagram(diagram, ax=None):
    """The regime diagram of the spring–block in the (V, k) plane.

    Parameters
    ----------
    diagram : landau.analyses.regimes.RegimeDiagram
        From :func:`landau.analyses.regimes.regime_diagram`.
    ax : matplotlib Axes, optional
        Draw on these axes (default: a new figure).

    Returns
    -------
    matplotlib.axes.Axes
        The Hopf line k_c(V) — solid where supercritical (Λ < 0), dashed where subcritical —
        the codimension-two points (Λ = 0) and the inertial boundary k = Mω_c² (dotted).

    References
    ----------
    Putelat, T., Dawes, J. H. P., Willis, J. R. (2010). Regimes of frictional sliding of a
    spring–block system. J. Mech. Phys. Solids 58, 27–53, Figs 5b and 14a.
    """
    if ax is None:
        ax = new_figure(figsize=(6.4, 4.4)).subplots()
    V = np.asarray(diagram.V, dtype=float)
    ax.loglog(V, diagram.supercritical, color=BAND_COLOURS["supercritical"], lw=1.6,
              label=r"Hopf line, supercritical ($\Lambda<0$)")
    ax.loglog(V, diagram.subcritical, color=BAND_COLOURS["subcritical"], lw=1.6, ls="--",
              label=r"Hopf line, subcritical ($\Lambda>0$)")
    ib = np.asarray(diagram.inertial_boundary, dtype=float)
    if np.any(np.isfinite(ib) & (ib > 0)):
        ax.loglog(V, np.where(ib > 0, ib, np.nan), color="0.4", lw=1.0, ls=":",
                  label=r"inertial boundary $M\omega_c^2$")
    for i, c in enumerate(diagram.codim2):
        ax.plot([c.V], [c.k_c], "o", color="k", ms=5, label="codimension-two point" if i == 0 else None)
        ax.annotate(f"V = {c.V:.4g}", (c.V, c.k_c), textcoords="offset points", xytext=(6, 6), fontsize="small")
    kc = np.asarray(diagram.kc, dtype=float)
    kc = kc[np.isfinite(kc) & (kc > 0)]
    if kc.size:
        ax.set_ylim(kc.min() / 3, kc.max() * 3)    # the Hopf line, not the inertial boundary, sets the scale
    ax.set_xlabel(LABELS["V"])
    ax.set_ylabel(r"$k$ [N/m]")
    ax.grid(True, which="major", alpha=0.3)
    ax.legend(loc="best", fontsize="small")
    ax.set_title("steady sliding is stable above the Hopf line", fontsize="medium")
    return ax


def plot_check(eps2s, predicted=None, simulated=None, *, exponent: float | None = None, fig=None,
               title: str | None = None, units: str = "m"):
    """Simulated against predicted cycle amplitude over ε², with the fitted error exponent.

    Parameters
    ----------
    eps2s : array_like, or a sequence of check results
        Distances to threshold ε² = |k − k_c|/k_c (or |p − p_c|/p_c), all > 0.  Or, with
        ``predicted`` and ``simulated`` omitted, the results of :func:`landau.check` at
        several ε² (anything with ``eps2``, ``amplitude_predicted`` and ``amplitude_simulated``).
    predicted, simulated : array_like
        The amplitude predicted by the amplitude equation and the one measured on the
        simulated cycle at each ε² (NaN where no cycle was found).
    exponent : float, optional
        Exponent p of |simulated/predicted − 1| ∝ (ε²)^p; fitted by least squares in
        log–log over the finite points when omitted (p ≈ 1 when the prediction is right to
        leading order and the next correction is O(ε²)).
    fig : matplotlib.figure.Figure, optional
        Draw into this figure (cleared first).
    title : str, optional
        Figure title.
    units : str
        Unit of the amplitudes (axis label).

    Returns
    -------
    matplotlib.figure.Figure
        Left: both amplitudes against ε² (log–log; the prediction scales as ε).  Right: the
        relative error against ε² with the fitted power law.
    """
    if predicted is None and simulated is None:
        results = list(eps2s)
        if not results or not all(hasattr(r, "amplitude_simulated") for r in results):
            raise InputError("plot_check needs (eps2, predicted, simulated) arrays or a list of check results")
        nan = float("nan")
        eps2s = [r.eps2 for r in results]
        predicted = [nan if r.amplitude_predicted is None else r.amplitude_predicted for r in results]
        simulated = [nan if r.amplitude_simulated is None else r.amplitude_simulated for r in results]
        if title is None:
            title = f"{results[0].system}: amplitude equation against simulation"
    e = np.asarray(eps2s, dtype=float)
    pr = np.asarray(predicted, dtype=float)
    sim = np.asarray(simulated, dtype=float)
    if not (e.shape == pr.shape == sim.shape) or e.ndim != 1 or e.size == 0:
        raise InputError("plot_check needs three 1-D arrays of the same length (eps2, predicted, simulated)")
    if np.any(~(e > 0)):
        raise InputError("plot_check: every eps2 must be > 0")
    rel = np.abs(sim / pr - 1.0)
    ok = np.isfinite(rel) & (rel > 0)
    if exponent is None and ok.sum() >= 2:
        exponent = float(np.polyfit(np.log(e[ok]), np.log(rel[ok]), 1)[0])
    fig, axes = _new_figure(fig, 1, 2, figsize=(9.0, 3.6))
    a1, a2 = axes[0]
    order = np.argsort(e)
    a1.loglog(e[order], pr[order], "-", color="tab:blue", label="predicted")
    a1.loglog(e, sim, "o", color="k", ms=5, mfc="none", label="simulated")
    a1.set_xlabel(r"$\varepsilon^2$")
    a1.set_ylabel(f"cycle amplitude [{units}]")
    a1.legend(fontsize="small")
    a1.grid(True, which="major", alpha=0.3)
    a2.loglog(e[ok], rel[ok], "o", color="k", ms=5, mfc="none", label="|simulated/predicted − 1|")
    if exponent is not None and ok.sum() >= 2:
        # the fitted power law through the geometric centre of the points
        x0, y0 = np.exp(np.mean(np.log(e[ok]))), np.exp(np.mean(np.log(rel[ok])))
        xs = np.array([e[ok].min(), e[ok].max()])
        a2.loglog(xs, y0 * (xs / x0) ** exponent, "-", color="tab:red",
                  label=rf"fit $\propto(\varepsilon^2)^{{{exponent:.2f}}}$")
    a2.set_xlabel(r"$\varepsilon^2$")
    a2.set_ylabel("relative error")
    a2.legend(fontsize="small")
    a2.grid(True, which="major", alpha=0.3)
    if title:
        fig.suptitle(title)
    fig.tight_layout()
    return fig
