"""Scripts that regenerate the source papers' figures from the toolkit.

Each sub-package (one per paper) exposes ``FIGURES``: an ordered mapping from a figure
name (``"fig8"``) to a function ``make(out_dir: Path) -> list[Path]`` that computes only
what that figure plots and writes its PNG(s) atomically.

Parameter loops of independent points (a figure's β or μ values, the scans of
:mod:`landau.analyses.transition`) run on the sweep engine
(:func:`landau.analyses.sweep_points.map_points`, :func:`landau.verify.skurativskyi.sweep.run_sweep`)
with :func:`workers` local processes: ``landau figures PAPER --workers N`` sets it (default one per
CPU); the numbers do not depend on it.
"""

from __future__ import annotations

import os
from contextlib import contextmanager
from typing import Iterator

_WORKERS: list[int | None] = [None]


def workers() -> int:
    """The local processes a figure's parameter loops run on (default: one per CPU)."""
    return int(_WORKERS[0] or os.cpu_count() or 1)


@contextmanager
def using_workers(n: int | None) -> Iterator[None]:
    """Run the figures made inside on ``n`` local processes (None: one per CPU)."""
    if n is not None and int(n) < 1:
        from landau.errors import InputError

        raise InputError(f"--workers must be >= 1, got {n}")
    old = _WORKERS[0]
    _WORKERS[0] = None if n is None else int(n)
    try:
        yield
    finally:
        _WORKERS[0] = old
