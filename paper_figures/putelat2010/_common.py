"""Shared helpers of the Putelat et al. (2010) figures: cached derivations, velocity grids, saving.

The figures of one run share their work: one :class:`Derivation` per law (derived and
compiled once), one evaluation per (law, velocity grid, parameters) however many panels and
figures plot from it (:class:`SharedDerivation`), and one mathtext parser for every figure's
labels (:func:`save`)."""

from __future__ import annotations

import math
from pathlib import Path
from typing import Mapping, Sequence

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import matplotlib.ticker as mticker  # noqa: E402
import numpy as np  # noqa: E402
from matplotlib.lines import Line2D  # noqa: E402
from matplotlib.mathtext import MathTextParser  # noqa: E402

from landau.analyses.transition import velocity_weakening_ranges  # noqa: E402
from landau.derivation.multiscale import CoefficientTable, Derivation  # noqa: E402
from landau.laws import get_law  # noqa: E402
from landau.support.io import atomic_savefig  # noqa: E402
from landau.systems.system import SpringBlock  # noqa: E402

#: the paper's Table 1 values used in labels
L = 0.9e-6
V_S = 1e-6


class SharedDerivation(Derivation):
    """A :class:`Derivation` that evaluates each (velocity grid, parameters) once.

    The figures plot several quantities of one law on one grid, through helpers that each
    ask :meth:`Derivation.evaluate` for a few names (:mod:`landau.analyses.amplitude`); the points
    near an extremum of μ_ss go to a 50-digit fallback on every such call.  Here a call
    whose names were already evaluated on the same grid and parameters gets the stored
    arrays (copies), and a call with new names evaluates only those and adds them.  Calls
    with ``sign_only``, another ``method`` or array-valued parameters are passed through.

    A figure that plots several quantities asks for all of them in its first call
    (:data:`AMPLITUDE_NAMES`), so that the fallback runs once per point for all of them.
    """

    def __init__(self, *args, **kwargs):
        super().__init__(*args, **kwargs)
        self._tables: dict[tuple, dict[str, np.ndarray]] = {}

    def evaluate(self, Vs, params: Mapping[str, float] | None = None,
                 names: Sequence[str] = ("kc", "omega_c", "Gamma_bar", "Lambda"),
                 method: str = "auto", sign_only: bool = False, **overrides) -> CoefficientTable:
        if isinstance(names, str):
            names = [names]
        if overrides:   # parameters as keywords, as Derivation.evaluate takes them
            from landau.derivation.multiscale import _merged

            params = _merged(params, overrides)
        V = np.asarray(Vs, dtype=float)
        if sign_only or method != "auto" or any(np.ndim(v) for v in (params or {}).values()) or V.size < 2:
            return super().evaluate(Vs, params, names, method, sign_only)
        p = self.block.resolve(params)
        key = (V.shape, V.tobytes(), tuple(sorted(p.items())))
        table = self._tables.get(key)
        missing = [n for n in names if table is None or n not in table]
        if missing:
            new = super().evaluate(V, p, missing)
            if table is None:
                table = dict(new)
            else:   # quantities evaluated before keep their values; a degenerate point stays flagged
                table = {**new, **table, "degenerate": table["degenerate"] | new["degenerate"]}
            self._tables[key] = table
        return CoefficientTable({k: v.copy() for k, v in (table or {}).items()}, law=self.block.law.name, params=p)


#: what the amplitude, growth-rate and apparent-stiffness panels use (:mod:`landau.analyses.amplitude`)
AMPLITUDE_NAMES = ("kc", "omega_c", "Gamma_bar", "Omega_bar", "Lambda", "chi")

_DERIVATIONS: dict[str, SharedDerivation] = {}


def derivation(law: str) -> SharedDerivation:
    """One lazily-derived :class:`SharedDerivation` per law, shared by the figures of a run."""
    if law not in _DERIVATIONS:
        _DERIVATIONS[law] = SharedDerivation(SpringBlock(get_law(law)))
    return _DERIVATIONS[law]


def fresh(law: str) -> SharedDerivation:
    """A new :class:`SharedDerivation` of ``law`` (nothing derived or evaluated yet)."""
    return SharedDerivation(SpringBlock(get_law(law)))


def vw_grid(d: Derivation, params: dict, n: int = 300, lo: float = 1e-9, hi: float = 1e-1) -> np.ndarray:
    """Log grid over the velocity-weakening range (clipped to [lo, hi]), clustered towards
    extrema of μ_ss where Γ and Λ go to zero."""
    rs = velocity_weakening_ranges(d, params, 1e-12, 1e2)
    a, b = max(rs[0].lo, lo), min(rs[-1].hi, hi)
    body = np.logspace(math.log10(a), math.log10(b), n)
    ends = []
    eta = 10.0 ** -np.linspace(2, 7, 20)
    if rs[0].lo_extremum and rs[0].lo >= lo:
        ends.append(rs[0].lo * (1 + eta))
    if rs[-1].hi_extremum and rs[-1].hi <= hi:
        ends.append(rs[-1].hi * (1 - eta))
    g = np.unique(np.concatenate([body, *ends]))
    return g[(g > a * (1 + 1e-9)) & (g < b * (1 - 1e-9))] if ends else g


def mu_ss(d: Derivation, Vs, params: dict) -> np.ndarray:
    fmu, _ = d.hopf._compiled_mu
    p = d.block.resolve(params)
    return np.asarray(fmu(*d.block.argvals(np.asarray(Vs, dtype=float), p)), dtype=float)


def symlog_y(ax, values) -> None:
    """Symmetric log scale for a coefficient that changes sign over decades (Λ)."""
    v = np.abs(np.asarray(values, dtype=float))
    v = v[np.isfinite(v) & (v > 0)]
    if v.size:
        lt = float(np.percentile(v, 5))
        ax.set_yscale("symlog", linthresh=lt)
        # one labelled tick every other decade keeps the axis readable over ~15 decades
        ax.yaxis.set_major_locator(mticker.SymmetricalLogLocator(base=100.0, linthresh=lt))
        ax.yaxis.set_minor_locator(mticker.NullLocator())
        base_fmt = mticker.LogFormatterSciNotation(base=10.0, linthresh=lt)

        def fmt(y, pos, lt=lt, base_fmt=base_fmt):
            # the ±linthresh ticks crowd the zero line: label only 0 and the decades beyond
            if y != 0 and abs(y) <= lt * 1.0001:
                return ""
            return "0" if y == 0 else base_fmt(y, pos)

        ax.yaxis.set_major_formatter(mticker.FuncFormatter(fmt))
    ax.axhline(0.0, color="0.6", lw=0.6)


def vlabel(ax) -> None:
    ax.set_xscale("log")
    ax.set_xlabel("V (m s$^{-1}$)")


#: one mathtext parser for every figure: matplotlib keeps parsed labels per parser (each new
#: figure's renderer would otherwise parse the same tick labels, "$10^{-5}$", again)
_MATHTEXT = MathTextParser("path")


def _contains_close(interval, val, rtol: float = 1e-10):
    """Whether ``val`` lies in the closed ``interval`` widened by ``rtol`` of its length (the test
    matplotlib's axis applies to its own ticks)."""
    a, b = sorted(interval)
    slack = (b - a) * rtol
    return a - slack <= val <= b + slack


def _unlabelled_minor_ticks(axis) -> list[Line2D]:
    """The marks of ``axis``'s minor ticks as one line per side, when none of them has a label.

    A log axis over many decades carries ~50 minor ticks, each a matplotlib ``Tick`` of five
    artists, created, positioned and laid out at every draw — most of the time of a figure.
    The same marks (positions, marker, size, width, colour and transform copied from the
    axis's own minor tick) drawn as one line of markers per side give the same pixels.
    Returns [] when the ticks carry labels or grid lines (nothing is replaced then)."""
    if not isinstance(axis.get_minor_locator(), mticker.LogLocator):
        return []
    locs = np.asarray(axis.get_minorticklocs(), dtype=float)      # those on a major tick removed
    lo, hi = sorted(axis.get_view_interval())
    tr = axis.get_transform()
    inside = tr.transform([lo, hi])
    locs = np.array([x for x in locs if _contains_close(inside, tr.transform(x))])
    if locs.size == 0 or any(axis.get_minor_formatter().format_ticks(locs)):
        return []
    tick = axis.get_minor_ticks(1)[0]
    if not tick.get_visible() or tick.gridline.get_visible():
        return []
    lines = []
    for mark, side in ((tick.tick1line, 0.0), (tick.tick2line, 1.0)):
        if not mark.get_visible():
            continue
        other = np.full(locs.shape, side)
        line = Line2D(*((locs, other) if axis.axis_name == "x" else (other, locs)))
        line.update_from(mark)                 # marker, size, width, colours, transform, no clip path
        line.set_zorder(axis.get_zorder())     # drawn where the axis draws its ticks
        line.set_in_layout(False)              # tick marks never counted in the tight layout
        lines.append(line)
    return lines


def _merge_minor_ticks(fig) -> None:
    """Every unlabelled minor-tick set of ``fig`` drawn as single lines (:func:`_unlabelled_minor_ticks`).

    All replacements are found before any locator is switched off: axes sharing an axis share
    its locator."""
    found = [(ax, axis, _unlabelled_minor_ticks(axis)) for ax in fig.axes for axis in (ax.xaxis, ax.yaxis)]
    for ax, axis, lines in found:
        if not lines:
            continue
        for line in lines:
            ax.add_artist(line)
            line.set_clip_on(False)            # outside the axes, like the tick marks
        axis.set_minor_locator(mticker.NullLocator())


def save(fig, out_dir: Path, name: str) -> list[Path]:
    """Lay out ``fig`` (tight layout, computed once), write ``name``.png atomically, close it."""
    fig.canvas.get_renderer().mathtext_parser = _MATHTEXT
    _merge_minor_ticks(fig)
    fig.tight_layout()
    # tight_layout() leaves a placeholder layout engine, which makes savefig draw the whole
    # figure once more before drawing it for the file; the layout is final: drop the engine
    fig.set_layout_engine(None)
    path = atomic_savefig(fig, Path(out_dir) / f"{name}.png", dpi=100)
    plt.close(fig)
    return [path]


def panel_title(ax, text: str) -> None:
    ax.set_title(text, fontsize=9, loc="left")
