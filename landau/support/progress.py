"""Progress bars that appear only where someone is watching.

:func:`progress` wraps an iterable (or counts steps) with tqdm: a text bar on a terminal, a
notebook widget in Jupyter (``tqdm.auto``, with ipywidgets installed; without it the text bar,
without tqdm's warning that it found no widgets), nothing when stderr is not a terminal (pipes, CI
logs), in ``--json`` mode (:func:`set_quiet`) or with ``LANDAU_PROGRESS=off``.
"""

from __future__ import annotations

import os
import sys
import warnings
from typing import Iterable, TypeVar

T = TypeVar("T")
_quiet = False


def set_quiet(flag: bool) -> None:
    """Silence every progress bar of this process (the CLI does this for ``--json``)."""
    global _quiet
    _quiet = bool(flag)


def _in_notebook() -> bool:
    ipython = sys.modules.get("IPython")   # a notebook kernel has imported it already
    if ipython is None:
        return False
    try:
        shell = ipython.get_ipython()
    except Exception:
        return False
    return shell is not None and type(shell).__name__ == "ZMQInteractiveShell"


def _bar_class():
    """tqdm's bar class for here: the notebook widget in a Jupyter kernel (``tqdm.auto``), else the
    text bar.  Without ipywidgets (or with one too old) ``tqdm.auto`` falls back to the text bar
    after a ``TqdmWarning`` "IProgress not found" printed above the bar: that warning, and only it,
    is silenced, the text bar being the right bar then (``pip install ipywidgets`` for the widget)."""
    if not _in_notebook():
        from tqdm import tqdm

        return tqdm
    from tqdm import TqdmWarning

    with warnings.catch_warnings():
        warnings.filterwarnings("ignore", message="IProgress not found", category=TqdmWarning)
        from tqdm.auto import tqdm as auto

    return auto


def shown() -> bool:
    """Whether a bar would be shown now."""
    if _quiet or os.environ.get("LANDAU_PROGRESS", "on").strip().lower() in ("0", "off", "false", "no"):
        return False
    if _in_notebook():
        return True
    return bool(getattr(sys.stderr, "isatty", lambda: False)())


def progress(iterable: Iterable[T] | None = None, *, total: int | None = None, desc: str = "",
             unit: str = "it", leave: bool = False):
    """A tqdm bar over ``iterable`` (or a manual one with ``total``), disabled where nobody watches.

    Parameters
    ----------
    iterable : the items to iterate over, or None for a bar advanced with ``.update()``.
    total : number of steps (default: ``len(iterable)`` where defined).
    desc : the label.
    unit : what one step is.
    leave : keep the finished bar on screen.

    Returns
    -------
    tqdm.tqdm
        Iterate over it, or call ``update()``/``set_description()``; a context manager.
    """
    return _bar_class()(iterable, total=total, desc=desc, unit=unit, leave=leave, disable=not shown(),
                dynamic_ncols=True)
