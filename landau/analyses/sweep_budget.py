"""The memory budget of a sweep: its estimate, the machine's memory, the refusal.

A sweep without a file holds its whole grid in memory (:class:`landau.analyses.sweep_engine.Table`:
every point's status, message and variables), so a grid too large for the machine does not fail
at once: it grows for minutes or hours, then swaps or is killed by the kernel.  A sweep written to
a file holds one flag a point (what is still to compute; a shard's, two) and the chunks it is
working on (:class:`landau.analyses.sweep_store.FileTable`: the results go to the file as they
come, the file is assembled block by block): :data:`STORED_BYTES_PER_POINT` a point and
:data:`STORED_OVERHEAD`, whatever the task's variables.  :func:`check_memory` refuses such a grid before
anything is allocated, comparing :func:`memory_estimate` (:data:`BYTES_PER_POINT` a point,
measured) with a budget: an explicit ``max_memory``, or :data:`MEMORY_FRACTION` of the machine's
memory (:func:`machine_memory`: ``os.sysconf``, or the cgroup's limit where it is smaller, since a
container's process is killed at its limit, not at the host's).  The estimate does not know a
task's variables before it runs: a task that stores per-point lists (``simulate``'s Poincaré
points) needs more per point; such sweeps are one-dimensional continuations of thousands of
points, far below any budget.
"""

from __future__ import annotations

import math
import os
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np

from landau.errors import InputError

if TYPE_CHECKING:
    from landau.analyses.sweep_engine import Grid

#: the memory a sweep holds per grid point, in bytes: the ``hopf`` task's peak resident memory
#: grows by 350 bytes a point (its 11 numbers and one string, the statuses and messages, the chunks,
#: the periodic write), 380 with a 77-character message at every other point (peak RSS of a V × a
#: sweep with a file, from 300 × 300 to 900 × 900 points); rounded up to 512 for a margin.  A
#: point whose message is its own string (not shared) adds about its length plus 50 bytes
BYTES_PER_POINT = 512
#: the memory a sweep written to a file holds per grid point: the flag of the points still to compute
#: and a shard's flag of its own points (one byte each)
STORED_BYTES_PER_POINT = 2
#: the memory a sweep written to a file holds whatever its grid: the blocks of the file being assembled
#: (65536 points of every variable), the chunks in flight and the buffered results, the pool's queues
#: (measured: a 10⁷-point hopf sweep peaks 150 MB above the interpreter with its modules; rounded up)
STORED_OVERHEAD = 256 << 20
#: the share of this machine's memory a sweep may use by default
MEMORY_FRACTION = 0.5


def machine_memory() -> int | None:
    """This machine's memory in bytes (``os.sysconf``), or the cgroup's limit if smaller; None if unknown."""
    total = None
    try:
        total = int(os.sysconf("SC_PHYS_PAGES")) * int(os.sysconf("SC_PAGE_SIZE"))
    except (AttributeError, ValueError, OSError):
        pass
    for limit in ("/sys/fs/cgroup/memory.max", "/sys/fs/cgroup/memory/memory.limit_in_bytes"):
        try:
            text = Path(limit).read_text().strip()
        except OSError:
            continue
        if text.isdigit() and (total is None or int(text) < total):
            total = int(text)
    return total if total and total > 0 else None


_SIZE_UNITS = {"": 1, "B": 1, "K": 1 << 10, "M": 1 << 20, "G": 1 << 30, "T": 1 << 40}


def parse_memory(value: Any) -> int | None:
    """Bytes from an integer or a size such as ``"8G"``, ``"500M"``, ``"2.5GB"`` (powers of 1024); None for None."""
    if value is None:
        return None
    if isinstance(value, (int, np.integer)) and not isinstance(value, bool):
        n = int(value)
    else:
        text = str(value).strip().upper().removesuffix("IB").removesuffix("B")
        unit = text[-1:] if text[-1:] in _SIZE_UNITS else ""
        try:
            x = float(text[:len(text) - len(unit)])
        except ValueError:
            raise InputError(f"--max-memory {value!r}: expected a size such as 8G, 500M or a number of bytes") from None
        if not math.isfinite(x):
            raise InputError(f"--max-memory {value!r}: must be finite")
        n = int(x * _SIZE_UNITS[unit])
    if n <= 0:
        raise InputError(f"--max-memory {value!r}: must be positive")
    return n


def memory_estimate(grid: Grid, stored: bool = False) -> int:
    """The bytes a sweep of ``grid`` holds in memory: without a file (``stored`` False),
    :data:`BYTES_PER_POINT` a point and 8 more per axis; written to a file,
    :data:`STORED_BYTES_PER_POINT` a point and :data:`STORED_OVERHEAD`."""
    if stored:
        return grid.size * STORED_BYTES_PER_POINT + STORED_OVERHEAD
    return grid.size * (BYTES_PER_POINT + 8 * len(grid.axes))


def _gib(n: float) -> str:
    return f"{n / (1 << 30):.3g} GiB"


def check_memory(grid: Grid, max_memory: Any = None, stored: bool = False) -> None:
    """Refuse (InputError) a grid whose :func:`memory_estimate` (``stored``: the sweep is written to a
    file) exceeds ``max_memory`` (bytes or a size such as ``"8G"``), by default :data:`MEMORY_FRACTION`
    of :func:`machine_memory` (no limit when that is unknown).  Nothing is allocated."""
    budget = parse_memory(max_memory)
    what = "--max-memory"
    if budget is None:
        total = machine_memory()
        if total is None:
            return
        budget, what = int(MEMORY_FRACTION * total), f"{MEMORY_FRACTION:g} of this machine's {_gib(total)}"
    need = memory_estimate(grid, stored)
    if need > budget:
        raise InputError(f"the grid has {grid.size} points, about {_gib(need)} in memory, more than the budget of "
                         f"{_gib(budget)} ({what}); sweep fewer points{'' if stored else ', write it to a file'}, "
                         "or raise --max-memory")
