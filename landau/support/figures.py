"""New matplotlib figures that a notebook shows exactly once (matplotlib imported on first use).

A figure made by ``plt.figure()`` and returned by a function shows twice in a notebook: once
because pyplot's inline backend shows every figure it manages at the end of the cell, once more
as the cell's value.  One made by ``matplotlib.figure.Figure()`` shows at most once, and only
when it is the cell's last value (``<Figure …>`` text in a session where pyplot was never
imported), and ``plt.show()`` never shows it in a script.  :func:`new_figure` gives a
pyplot-managed figure of a subclass that, when a notebook displays it, lets pyplot go of it:
it shows once whether it is the cell's value or assigned (``fig = d.plot()``: the inline
backend shows it at the end of the cell), a script shows it with ``plt.show()``, and displayed
again in a later cell it shows once more.  Every plotting function of the toolkit makes its figures here (the
convention is stated in :mod:`landau.report.plotting`); this module sits in
:mod:`landau.support` so that every layer, the simulation engine included, can use it.
"""

from __future__ import annotations

from typing import Any

_FIGURE_CLASS: Any = None


def figure_class() -> type:
    """The Figure subclass of :func:`new_figure` (defined on first use: importing this module
    does not import matplotlib)."""
    global _FIGURE_CLASS
    if _FIGURE_CLASS is None:
        from matplotlib.figure import Figure as _MplFigure

        class Figure(_MplFigure):
            """A matplotlib Figure that IPython displays exactly once.

            Displayed (as a cell's value, by ``display``, or by the inline backend at the end
            of the cell) it shows its image and, when pyplot's inline backend still manages
            it, hands it back to pyplot (``plt.close``) so that the backend does not show it a
            second time.  Under a window or widget backend it leaves the showing to pyplot.
            """

            def _ipython_display_(self) -> None:
                import matplotlib

                managed = self.canvas.manager is not None
                if managed and "inline" not in matplotlib.get_backend():
                    return  # a window or a widget of pyplot's backend shows it
                import io

                from IPython.display import display

                buf = io.BytesIO()
                self.savefig(buf, format="png", bbox_inches="tight")
                display({"image/png": buf.getvalue(), "text/plain": repr(self)}, raw=True)
                if managed:  # shown: the inline backend need not show it again at the end of the cell
                    import matplotlib.pyplot as plt

                    plt.close(self)

        Figure.__module__ = __name__
        Figure.__qualname__ = "Figure"      # pickled by reference as landau.support.figures.Figure
        _FIGURE_CLASS = Figure
    return _FIGURE_CLASS


def __getattr__(name: str):
    if name == "Figure":
        return figure_class()
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")


def new_figure(**figure_kw: Any):
    """A new figure for a plotting function of the toolkit.

    Parameters
    ----------
    **figure_kw
        Passed to :func:`matplotlib.pyplot.figure` (``figsize``, ``layout``, ``dpi``, …).

    Returns
    -------
    matplotlib.figure.Figure
        A pyplot-managed figure (a script shows it with ``plt.show()``, a notebook at the end of
        the cell) that a notebook does not show a second time as the cell's value.
    """
    import matplotlib.pyplot as plt

    return plt.figure(FigureClass=figure_class(), **figure_kw)
