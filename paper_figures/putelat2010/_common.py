"""Shared helpers of the Putelat et al. (2010) figures: cached derivations, velocity grids, saving."""

from __future__ import annotations

import math
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import matplotlib.ticker as mticker  # noqa: E402
import numpy as np  # noqa: E402

from landau.io import atomic_savefig  # noqa: E402
from landau.multiscale import Derivation  # noqa: E402
from landau.system import SpringBlock  # noqa: E402
from landau.transition import velocity_weakening_ranges  # noqa: E402
from landau.laws import get_law  # noqa: E402

#: the paper's Table 1 values used in labels
L = 0.9e-6
V_S = 1e-6
_DERIVATIONS: dict[str, Derivation] = {}


def derivation(law: str) -> Derivation:
    """One lazily-derived :class:`Derivation` per law, shared by the figures of a run."""
    if law not in _DERIVATIONS:
        _DERIVATIONS[law] = Derivation(SpringBlock(get_law(law)))
    return _DERIVATIONS[law]


def fresh(law: str) -> Derivation:
    return Derivation(SpringBlock(get_law(law)))


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


def save(fig, out_dir: Path, name: str) -> list[Path]:
    fig.tight_layout()
    path = atomic_savefig(fig, Path(out_dir) / f"{name}.png", dpi=100)
    plt.close(fig)
    return [path]


def panel_title(ax, text: str) -> None:
    ax.set_title(text, fontsize=9, loc="left")
