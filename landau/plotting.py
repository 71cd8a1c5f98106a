"""Plots of the toolkit's results, under a short name: ``landau.plotting.plot_check(...)``.

The functions live in :mod:`landau.report.plotting` (with the convention every plotting
function follows: a figure shows exactly once, in a script with ``plt.show()`` and in a
notebook whether the call ends the cell or is assigned).
"""

from landau.report.plotting import (
    BAND_COLOURS,
    LABELS,
    criticality_bands,
    new_figure,
    plot_check,
    plot_coefficients,
    plot_regime_diagram,
)

__all__ = ["BAND_COLOURS", "LABELS", "criticality_bands", "new_figure", "plot_check", "plot_coefficients",
           "plot_regime_diagram"]
