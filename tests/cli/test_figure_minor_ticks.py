"""Unlabelled minor ticks of the paper figures drawn as one line of markers per axis side
(paper_figures.putelat2010._common): the same picture, far fewer artists."""

import io

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import matplotlib.ticker as mticker  # noqa: E402
import numpy as np  # noqa: E402
from PIL import Image  # noqa: E402

from landau.paper_figures.putelat2010 import _common  # noqa: E402


def _figure(y_hi: float):
    fig, ax = plt.subplots(1, 2, figsize=(6, 3))
    V = np.logspace(-6, -2, 50)        # four decades: eight unlabelled minor ticks in each
    ax[0].loglog(V, 1e3 * V ** 0.5)
    ax[1].plot(V, np.linspace(2.0, y_hi, 50))
    ax[1].set_xscale("log")
    ax[1].set_yscale("log")
    return fig


def _png(fig, merge: bool) -> np.ndarray:
    if merge:
        _common._merge_minor_ticks(fig)
        assert isinstance(fig.axes[0].xaxis.get_minor_locator(), mticker.NullLocator)     # replaced
    fig.tight_layout()
    buf = io.BytesIO()
    fig.savefig(buf, format="png", dpi=100)
    plt.close(fig)
    return np.asarray(Image.open(io.BytesIO(buf.getvalue())).convert("RGBA")).astype(int)


def test_merged_minor_ticks_draw_the_same_pixels():
    before, after = _png(_figure(9.0), False), _png(_figure(9.0), True)
    assert before.shape == after.shape
    diff = np.abs(before - after).max(axis=2)
    # the marks are the same markers at the same places; their positions go through numpy's
    # log10 once per array instead of once per tick, which may differ in the last bit and move
    # an antialiased edge by at most one grey level on a handful of pixels
    assert diff.max() <= 1
    assert np.count_nonzero(diff) <= 20


def test_only_unlabelled_log_minor_ticks_are_replaced():
    fig = _figure(9.0)       # second panel's y axis spans less than a decade: its minor ticks are labelled
    ax0, ax1 = fig.axes
    _common._merge_minor_ticks(fig)
    assert isinstance(ax0.xaxis.get_minor_locator(), mticker.NullLocator)
    assert isinstance(ax0.yaxis.get_minor_locator(), mticker.NullLocator)
    assert isinstance(ax1.yaxis.get_minor_locator(), mticker.LogLocator)          # kept as ticks
    marks = [a for a in ax0.lines if not a.get_in_layout()]        # bottom and left sides
    for mark, lim, along in ((marks[0], ax0.get_xlim(), "x"), (marks[1], ax0.get_ylim(), "y")):
        # the minor ticks inside the view, counted independently: m 10^k, m = 2..9
        want = sorted(m * 10.0 ** k for k in range(-12, 6) for m in range(2, 10) if lim[0] <= m * 10.0 ** k <= lim[1])
        got = mark.get_xdata() if along == "x" else mark.get_ydata()
        np.testing.assert_allclose(sorted(got), want, rtol=1e-12)
    plt.close(fig)
