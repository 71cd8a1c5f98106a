"""Talk-ready plots of a :class:`~landau.verify.hybrid.result.Simulation`.

:func:`plot_simulation` draws the overview (one time-series panel per state beside the phase
portrait) or the Poincaré section of a run:

* every axis carries its quantity and unit (``units``: state name → unit);
* a positive quantity that spans more than two decades (the slip rate of a rate-and-state
  block, whose stick phases are invisible on a linear axis) gets a logarithmic axis;
* the run's regimes (``Simulation.regimes``: stick, slip, flight, contact intervals) shade the
  time series and colour the phase portrait, each named in the legend;
* ``discard`` drops the transient t < ``discard`` (the section keeps only the attractor).

The figure follows the toolkit's plotting convention (:mod:`landau.report.plotting`): a new
figure is made by ``landau.support.figures.new_figure`` (a pyplot-managed figure that a notebook
shows exactly once); given ``fig=``, the plot is drawn there and that figure is returned.
"""

from __future__ import annotations

from typing import Mapping, Sequence

import numpy as np

#: shading colour of each regime (unlisted regimes: grey); "slip" is the unshaded background
REGIME_COLOURS = {"stick": "tab:blue", "flight": "tab:green", "contact": "tab:purple",
                  "partial stick": "tab:cyan", "hold": "tab:orange", "slip": None, "free": None,
                  "slide": None}
#: a positive quantity spanning more than this ratio is drawn on a logarithmic axis
LOG_SPAN = 100.0
#: a phase portrait of more points than this is drawn as dots
DOTS_ABOVE = 20_000
#: a longer record is drawn through the extrema of each of this many bins (same picture, bounded memory)
DRAWN_BINS = 5_000


def display_indices(y: np.ndarray, bins: int = DRAWN_BINS) -> np.ndarray:
    """Indices of the points to draw: all of them for a short record, else the first, last, minimum
    and maximum of every state in each of ``bins`` consecutive bins (the envelope a screen shows).

    Parameters
    ----------
    y : ndarray, shape (n, m)
        The recorded states.
    bins : int, optional
        Number of bins.

    Returns
    -------
    ndarray of int
        Increasing indices into the record.
    """
    m = y.shape[1]
    if m <= 8 * bins:
        return np.arange(m)
    edges = np.linspace(0, m, bins + 1).astype(int)
    keep = [edges[:-1], edges[1:] - 1]
    for row in y:
        for red in (np.minimum, np.maximum):
            ext = red.reduceat(row, edges[:-1])
            # the first index in each bin where the extremum is reached
            hit = np.nonzero(row == np.repeat(ext, np.diff(edges)))[0]
            bin_of = np.searchsorted(edges, hit, side="right") - 1
            first = np.unique(bin_of, return_index=True)[1]
            keep.append(hit[first])
    return np.unique(np.concatenate(keep))


def _new_figure(**kw):
    """A figure by the toolkit's convention: ``landau.support.figures.new_figure`` (a notebook shows
    it exactly once)."""
    from landau.support.figures import new_figure

    return new_figure(**kw)


def merged_intervals(regimes: Sequence[tuple[float, float, str]], gap: float = 0.0) -> dict[str, list]:
    """The regime intervals grouped by name, neighbours closer than ``gap`` merged.

    Parameters
    ----------
    regimes : sequence of (t0, t1, name)
        Intervals in time order.
    gap : float, optional
        Intervals of one name separated by less than this are drawn as one.

    Returns
    -------
    dict
        name → list of (t0, width).
    """
    out: dict[str, list[list[float]]] = {}
    for t0, t1, name in regimes:
        lst = out.setdefault(name, [])
        if lst and t0 - lst[-1][1] <= gap:
            lst[-1][1] = max(lst[-1][1], t1)
        else:
            lst.append([float(t0), float(t1)])
    return {k: [(a, b - a) for a, b in v] for k, v in out.items()}


def regimes_from_mask(t: np.ndarray, mask: np.ndarray, inside: str, outside: str) -> tuple:
    """Regime intervals of a sampled run: ``inside`` where ``mask`` holds, ``outside`` elsewhere
    (a change is placed halfway between the two samples on either side of it)."""
    t = np.asarray(t, float)
    mask = np.asarray(mask, bool)
    if len(t) == 0:
        return ()
    cut = np.nonzero(mask[1:] != mask[:-1])[0]
    edges = np.concatenate([[t[0]], 0.5 * (t[cut] + t[cut + 1]), [t[-1]]])
    starts = np.concatenate([[0], cut + 1])
    return tuple((float(edges[i]), float(edges[i + 1]), inside if mask[s] else outside)
                 for i, s in enumerate(starts))


def _colour(regime: str):
    """The shading colour of a regime name (its words before a parenthesis: ``"stick (v < V/100)"``
    is shaded as ``"stick"``); None for the unshaded background."""
    return REGIME_COLOURS.get(regime.split(" (")[0], "0.5")


def _label(name: str, units: Mapping[str, str]) -> str:
    u = units.get(name)
    return f"{name} [{u}]" if u else name


def _centred(values: np.ndarray, name: str, units: Mapping[str, str], log: bool) -> tuple[np.ndarray, str]:
    """Section coordinates that sit within 1e-6 of their mean (a periodic orbit's few points)
    are drawn as the deviation from the mean, which the axis label states (no unreadable offset)."""
    v = np.asarray(values, float)
    if log or len(v) == 0:
        return v, _label(name, units)
    mean = float(np.mean(v))
    if mean != 0 and 0 < np.ptp(v) < 1e-6 * abs(mean):
        u = units.get(name)
        return v - mean, f"{name} − {mean:.10g}" + (f" [{u}]" if u else "")
    return v, _label(name, units)


def _is_log(values: np.ndarray) -> bool:
    v = np.asarray(values, float)
    v = v[np.isfinite(v)]
    return bool(len(v) and v.min() > 0 and v.max() / v.min() > LOG_SPAN)


def _regime_legend(ax_handles: list, regimes, span):
    """Legend patches of the regimes that occur (slip as the unshaded background)."""
    from matplotlib.patches import Patch

    names = []
    for _, _, nm in regimes:
        if nm not in names:
            names.append(nm)
    for nm in names:
        col = _colour(nm)
        ax_handles.append(Patch(facecolor=col if col else "white", edgecolor="0.6", alpha=0.25 if col else 1.0,
                                label=f"{nm}" + ("" if col else " (unshaded)")))
    return names


def plot_simulation(sim, kind: str = "overview", *, phase: tuple[int, int] = (0, 1), period: float | None = None,
                    units: Mapping[str, str] | None = None, fig=None, discard: float = 0.0,
                    log: Sequence[str] | None = None, section_label: str | None = None, title: str | None = None):
    """Draw a simulation (see the module docstring) and return the Figure.

    Parameters
    ----------
    sim : Simulation
        The run.
    kind : {"overview", "poincare"}
        Time series and phase portrait, or the Poincaré section.
    phase : (int, int)
        State components of the phase portrait / section axes.
    period : float, optional
        Strobe period of a stroboscopic section (default: the logged section events).
    units : mapping, optional
        State name (and ``"t"``) → unit.
    fig : matplotlib Figure, optional
        Draw here instead of a new figure.
    discard : float, optional
        Leave out t < ``discard`` (a transient).
    log : sequence of str, optional
        States drawn on a logarithmic axis (default: the positive ones spanning > 2 decades).
    section_label : str, optional
        What the section events are (legend of the Poincaré plot).
    title : str, optional
        The title's words before the run's status (default the model's name).

    Returns
    -------
    matplotlib.figure.Figure
    """
    from matplotlib.ticker import MaxNLocator

    if kind not in ("overview", "poincare"):
        raise ValueError(f"kind must be 'overview' or 'poincare', got {kind!r}")
    units = dict(units or {})
    names = sim._names()
    n = len(names)
    i0, i1 = (int(phase[0]), int(phase[1])) if n > 1 else (0, 0)
    if not (0 <= i0 < n and 0 <= i1 < n):
        raise ValueError(f"phase components {phase!r} out of range for {n} states")
    full = sim
    if discard:
        sim = sim.after(discard)
    idx = display_indices(sim.y) if len(sim.t) else np.arange(0)
    t_draw, y_draw = sim.t[idx], sim.y[:, idx]
    tu = units.get("t", "s")
    tlabel = f"t [{tu}]" if tu else "t"
    logset = set(log) if log is not None else {nm for i, nm in enumerate(names) if len(sim.t) and _is_log(sim.y[i])}
    title = (title or sim.model) + ("" if sim.success else f" (stopped: {sim.status.value})")
    if discard:
        title += f", t ≥ {discard:g}"
    if kind == "poincare":
        ts, ys = full.section_points(period)   # a strobe keeps the phase of the whole run's start
        if discard:
            ts, ys = ts[ts >= discard], ys[:, ts >= discard]
            if len(ts) == 0:
                raise ValueError(f"no section point at t >= {discard:g}")
        fig = fig if fig is not None else _new_figure(figsize=(6.0, 4.8), layout="constrained")
        ax = fig.add_subplot(1, 1, 1)
        what = section_label or (f"stroboscopic, period {period:.6g} {tu}".rstrip()
                                 if period is not None else "section crossings")
        if log is None:   # the section's own span decides (the whole run's may span decades more)
            logset = {nm for i, nm in enumerate(names) if _is_log(ys[i])}
        xs, xl = _centred(ys[i0], names[i0], units, names[i0] in logset)
        yv, yl = _centred(ys[i1], names[i1], units, names[i1] in logset)
        ax.plot(xs, yv, ".", ms=4, color="tab:red", label=f"{len(ts)} points: {what}")
        ax.set_xlabel(xl)
        ax.set_ylabel(yl)
        for axis, nm, scale in ((ax.xaxis, names[i0], ax.set_xscale), (ax.yaxis, names[i1], ax.set_yscale)):
            if nm in logset:
                scale("log")
            else:
                axis.set_major_locator(MaxNLocator(5))
                axis.get_major_formatter().set_useOffset(False)
        ax.legend(loc="best", fontsize="small")
        ax.set_title(f"Poincaré section — {title}")
        return fig
    fig = fig if fig is not None else _new_figure(figsize=(11, max(4.5, 1.7 * n + 0.8)), layout="constrained")
    gs = fig.add_gridspec(n, 2, width_ratios=(1.35, 1))
    regimes = [r for r in getattr(sim, "regimes", ()) if r[1] > (sim.t[0] if len(sim.t) else -np.inf)]
    span = (sim.t[-1] - sim.t[0]) if len(sim.t) > 1 else 1.0
    shaded = merged_intervals(regimes, gap=span / 4000)
    axes: list = []
    for i in range(n):
        ax = fig.add_subplot(gs[i, 0], sharex=axes[0] if axes else None)
        axes.append(ax)
        for nm, iv in shaded.items():
            col = _colour(nm)
            if col:
                ax.broken_barh(iv, (0, 1), transform=ax.get_xaxis_transform(), facecolor=col, alpha=0.18, lw=0)
        ax.plot(t_draw, y_draw[i], lw=0.8, color="k")
        if names[i] in logset:
            ax.set_yscale("log")
        else:
            ax.yaxis.set_major_locator(MaxNLocator(4))
        ax.set_ylabel(_label(names[i], units))
        if i < n - 1:
            ax.tick_params(labelbottom=False)
    if len(sim.t):
        axes[0].set_xlim(sim.t[0], sim.t[-1])
    axes[-1].set_xlabel(tlabel)
    axes[-1].xaxis.set_major_locator(MaxNLocator(6))
    ax = fig.add_subplot(gs[:, 1])
    handles: list = []
    if n >= 2 and len(sim.t):
        x, y = y_draw[i0], y_draw[i1]
        # a long (decimated) record is drawn as points: lines would join states far apart in time
        style = dict(ls="none", marker=".", ms=1.0) if len(x) > DOTS_ABOVE else dict(lw=0.7)
        if regimes:
            # the trajectory coloured by regime: each point takes the regime of its time
            starts = np.array([r[0] for r in regimes])
            which = np.clip(np.searchsorted(starts, t_draw, side="right") - 1, 0, len(regimes) - 1)
            lab = np.array([regimes[k][2] for k in which])
            kinds = list(dict.fromkeys(lab))
            for nm in kinds:
                col = _colour(nm) or "k"
                on = lab == nm
                on[1:] |= on[:-1]   # each piece runs on to the next point: no gap at a regime change
                xs, ys_ = np.where(on, x, np.nan), np.where(on, y, np.nan)
                ax.plot(xs, ys_, color=col, label=f"trajectory, {nm}" if len(kinds) > 1 else "trajectory", **style)
        else:
            ax.plot(x, y, color="k", label="trajectory", **style)
        ax.plot(x[:1], y[:1], "o", ms=6, mfc="none", color="tab:red", label=f"start, t = {sim.t[0]:.4g}")
        ax.plot(x[-1:], y[-1:], "s", ms=5, color="tab:red", label=f"end, t = {sim.t[-1]:.4g}")
        ax.set_xlabel(_label(names[i0], units))
        ax.set_ylabel(_label(names[i1], units))
        if names[i0] in logset:
            ax.set_xscale("log")
        else:
            ax.xaxis.set_major_locator(MaxNLocator(5))
        if names[i1] in logset:
            ax.set_yscale("log")
        ax.set_title("phase portrait", fontsize="medium")
    if any(_colour(nm) for _, _, nm in regimes):   # a legend of the shading when something is shaded
        _regime_legend(handles, regimes, span)
        fig.legend(handles=handles, loc="outside upper left", ncol=len(handles), fontsize="small", frameon=False,
                   title="regimes (shaded)", title_fontsize="small", alignment="left")
    ax.legend(loc="best", fontsize="small")
    fig.suptitle(title)
    return fig
