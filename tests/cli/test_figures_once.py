"""The figures of the toolkit show once (the convention of :mod:`landau.report.plotting`).

Without a notebook kernel: the display hook of :func:`landau.support.figures.new_figure`'s
figures, with IPython's ``display`` recorded (the kernel itself is exercised in
``test_notebook_display.py``).
"""

from __future__ import annotations

import pickle

import matplotlib

matplotlib.use("Agg")

import matplotlib.pyplot as plt  # noqa: E402
import pytest  # noqa: E402

from landau.support.figures import new_figure  # noqa: E402

pytest.importorskip("IPython")


@pytest.fixture
def shown(monkeypatch):
    import IPython.display

    calls = []
    monkeypatch.setattr(IPython.display, "display", lambda obj, raw=False: calls.append(obj))
    return calls


def test_inline_backend_shows_it_once_and_lets_pyplot_go(monkeypatch, shown):
    fig = new_figure()
    fig.subplots().plot([0, 1])
    monkeypatch.setattr(matplotlib, "get_backend", lambda: "module://matplotlib_inline.backend_inline")
    fig._ipython_display_()                      # the cell's value
    assert len(shown) == 1 and shown[0]["image/png"].startswith(b"\x89PNG")
    assert fig.canvas.manager is None          # pyplot let it go: the backend will not show it again
    fig._ipython_display_()                      # asked for again, in a later cell
    assert len(shown) == 2


def test_a_window_backend_is_left_to_show_it(shown):
    fig = new_figure()
    fig._ipython_display_()                      # Agg stands for a window backend here: pyplot's job
    assert shown == []
    plt.close(fig)
    fig._ipython_display_()                      # closed: nobody else will show it
    assert len(shown) == 1


def test_the_figure_is_a_pyplot_figure_and_pickles():
    fig = new_figure(figsize=(3, 2))
    assert isinstance(fig, matplotlib.figure.Figure) and plt.fignum_exists(fig.number)
    fig.subplots().plot([0, 1])
    back = pickle.loads(pickle.dumps(fig))
    assert type(back) is type(fig) and len(back.axes) == 1
    plt.close("all")


def test_plotting_functions_use_it():
    from landau.plotting import plot_check

    fig = plot_check([1e-3, 4e-4], [1.0, 0.632], [0.981, 0.6244])
    assert type(fig).__module__ == "landau.support.figures"
    plt.close("all")
