"""The stability diagram of friction-induced flutter: complex eigenvalues against a parameter.

What a brake engineer's complex eigenvalue analysis plots: the frequencies Im λ and the growth rates
Re λ of the modes of the sliding motion (:meth:`landau.systems.mode_coupling.ModeCoupling.first_order`)
against the friction coefficient μ (or any parameter of the model).  Two frequencies approach and
merge at the mode-coupling threshold μ_c, where one growth rate turns positive (Hoffmann et al. 2002,
Fig. 2); with damping they stay apart and the growth rate crosses zero at a Hopf point.

Written as a CSV (one row per parameter value; ``re_j``, ``im_j`` in rad/s and ``f_j`` in Hz for each
mode j, ordered by frequency) and a two-panel figure, both atomically.

References
----------
Hoffmann, N., Fischer, M., Allgaier, R. & Gaul, L. (2002), Mech. Res. Commun. 29, 197–205.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from landau.errors import InputError, NoSteadySlidingError
from landau.systems.mode_coupling import ModeCoupling


@dataclass(frozen=True)
class StabilityDiagram:
    """Eigenvalues of the sliding motion against a parameter.

    Parameters
    ----------
    parameter : str
        The parameter varied.
    values : ndarray, shape (m,)
        Its values.
    eigenvalues : ndarray, shape (m, n)
        At each value the n eigenvalues with Im λ ≥ 0 (one of each pair ±, the upper ones), sorted
        by Im λ (to 1e-9 of the largest |λ|) then Re λ; NaN where the contact opens at the steady sliding state.
    """

    parameter: str
    values: np.ndarray
    eigenvalues: np.ndarray

    @property
    def frequencies(self) -> np.ndarray:
        """Im λ (rad/s)."""
        return self.eigenvalues.imag

    @property
    def growth_rates(self) -> np.ndarray:
        """Re λ (1/s)."""
        return self.eigenvalues.real

    def unstable(self) -> np.ndarray:
        """True where some growth rate is positive (beyond round-off of the largest |λ|)."""
        scale = np.nanmax(np.abs(self.eigenvalues), axis=1)
        return np.nanmax(self.growth_rates, axis=1) > 1e-9 * scale

    def csv(self) -> str:
        """The diagram as CSV text."""
        n = self.eigenvalues.shape[1]
        head = [self.parameter] + [f"{w}_{j + 1}" for j in range(n) for w in ("re", "im", "f_hz")]
        lines = [",".join(head)]
        for p, row in zip(self.values, self.eigenvalues, strict=True):
            cells = [repr(float(p))]
            for z in row:
                cells += [repr(float(z.real)), repr(float(z.imag)), repr(float(z.imag) / (2 * math.pi))]
            lines.append(",".join(cells))
        return "\n".join(lines) + "\n"

    def write_csv(self, path: str | Path) -> Path:
        """Write :meth:`csv` to ``path`` atomically."""
        from landau.support.io import atomic_write_text

        return atomic_write_text(path, self.csv())

    def figure(self, threshold: float | None = None):
        """A matplotlib figure: frequencies (Hz) and growth rates (1/s) against the parameter."""
        from matplotlib.figure import Figure

        fig = Figure(figsize=(6.4, 5.6))
        ax_f, ax_g = fig.subplots(2, 1, sharex=True)
        for j in range(self.eigenvalues.shape[1]):
            ax_f.plot(self.values, self.frequencies[:, j] / (2 * math.pi), ".", ms=2)
            ax_g.plot(self.values, self.growth_rates[:, j], ".", ms=2)
        ax_f.set_ylabel("frequency Im λ / 2π [Hz]")
        ax_g.set_ylabel("growth rate Re λ [1/s]")
        ax_g.set_xlabel(self.parameter)
        ax_g.axhline(0.0, color="0.5", lw=0.6)
        if threshold is not None:
            for ax in (ax_f, ax_g):
                ax.axvline(threshold, color="C3", lw=0.8, ls="--")
        ax_f.set_title("stability diagram (complex eigenvalues of the sliding motion)")
        return fig

    def save_figure(self, path: str | Path, threshold: float | None = None) -> Path:
        """Write :meth:`figure` to ``path`` atomically."""
        from landau.support.io import atomic_savefig

        return atomic_savefig(self.figure(threshold), path)


def stability_diagram(mc: ModeCoupling, values, parameter: str = "mu") -> StabilityDiagram:
    """The eigenvalues of the sliding motion of ``mc`` at each of ``values`` of ``parameter``.

    Parameters
    ----------
    mc : ModeCoupling
    values : array_like
        The parameter values (e.g. ``np.linspace(0, 1, 200)`` for μ).
    parameter : str
        Any parameter of :meth:`ModeCoupling.parameter_values` (μ by default).

    Returns
    -------
    StabilityDiagram
    """
    vals = np.asarray(values, dtype=float)
    if vals.ndim != 1 or vals.size == 0 or not np.all(np.isfinite(vals)):
        raise InputError("stability_diagram: the parameter values must be a non-empty list of finite numbers")
    n = mc.n
    out = np.full((vals.size, n), np.nan + 1j * np.nan)
    for i, p in enumerate(vals):
        try:
            lam = np.linalg.eigvals(mc.with_value(parameter, float(p)).first_order())
        except NoSteadySlidingError:
            continue
        upper = lam[np.argsort(-lam.imag, kind="stable")][:n]
        # by frequency, and a merged pair (equal Im λ to round-off) by growth rate
        scale = max(float(np.max(np.abs(upper))), 1e-300)
        out[i] = upper[np.lexsort((upper.real, np.round(upper.imag / scale, 9)))]
    return StabilityDiagram(parameter, vals, out)


__all__ = ["StabilityDiagram", "stability_diagram"]
