"""The sweep mechanism: a parameter grid cut into fixed chunks, run on any executor, stored as it goes.

A sweep evaluates one *task* (:mod:`landau.analyses.sweep_tasks`) at every point of a grid, the
Cartesian product of named 1-D axes.  What it guarantees, and why:

* **The same numbers whatever runs them.**  The grid is cut into chunks whose composition
  depends only on the grid and the task (never on the executor or the number of workers), and
  every point is computed by deterministic code from its own parameters (and, for a
  continuation, from the chunk's own warm-up points), so the numbers are the same, bit for bit,
  whichever executor runs them.
* **A bad point fails alone.**  A task returns per point ``ok`` or the reason it has no result
  (``no-hopf``, ``degenerate``, ``outside-validity``, ``failed``) with a one-line message.  When
  ``task.run`` raises for a chunk of several points (a vectorised task meets one point it cannot
  take: an overflow, a parameter the law refuses), the chunk is run again in halves, each
  halved again if it raises, down to the failing points (:func:`run_chunk`): the valid points
  get their values, each failing point status ``failed`` and its own exception's first line.
  The split is itself deterministic (it depends only on which points raise), so the first
  guarantee holds; and a point's value does not depend on it for the tasks that allow it: the
  point-by-point tasks compute each point alone anyway, and the spring–block ``hopf`` task
  evaluates every chunk of a grid by one route, chosen once per grid
  (``SpringBlockHopf.for_grid``), elementwise, so a point in a smaller piece gets the value it
  has in its chunk, to the last bit (tested).  A continuation chunk is not split (its points depend on the
  points before them, so a point run alone would be another computation): all its points are
  ``failed`` with the exception's first line.  A task says otherwise with ``splittable``.
* **Bounded in flight.**  Any :class:`concurrent.futures.Executor` (``submit`` returning a
  future) runs the chunks: local processes by default, the calling process for one worker,
  ``distributed.Client(...).get_executor()`` for a dask cluster.  At most ``2 × workers`` chunks
  (:data:`IN_FLIGHT` on an executor of unknown size) are in flight, so a grid of a million points
  does not queue a million tasks.
* **No orphans.**  The local processes end with the sweep's process, even when it is killed
  with SIGKILL (:func:`landau.support.lifetime.die_with_parent`); when the run is interrupted or
  fails, they are ended at once (the chunks they run would be thrown away).
* **Stored as it goes, O(chunk) a write, never lost to a signal or a SIGKILL.**  With a file,
  finished chunks go to a journal beside it, a small file each batch, written atomically
  (:mod:`landau.analyses.sweep_store`: why a journal and not netCDF appended in place), so a
  write costs O(chunk) whatever was written before; the netCDF file (the same labelled Dataset)
  is assembled block by block at the end, also when the run is interrupted: Ctrl-C, and
  SIGTERM, which raises :class:`~landau.support.lifetime.Terminated` (a KeyboardInterrupt) in
  the main thread so that the same ``finally`` runs.  A run killed with SIGKILL leaves its
  journal, taken up by the next run (none of its points lost or computed twice).  Temporaries
  are removed whatever ends a write; one left by a killed run is removed by the next run on the
  same host once its writer's pid is gone
  (:func:`~landau.analyses.sweep_files.remove_stale_temporaries`).
* **A finished file is checked, not trusted.**  Before a file's points are reused, its statuses,
  variables, finiteness at ``ok`` points, landau version and the checksum of its results are
  checked (:func:`~landau.analyses.sweep_store.distrust`); a file that fails is recomputed and
  the reason said.
* **Resumable.**  A re-run with the same file reuses every finished point (of the file, if it is
  trusted, and of the journal) and computes the rest: the ``pending`` ones (not computed yet) and
  the ``failed`` ones (a worker lost, a run that failed), tried again.
* **Shards: the same numbers on independent machines.**  ``shard=(I, N)`` computes only the
  chunks whose number is I − 1 modulo N (:func:`shard_of`): the chunks are those of the unsharded
  run (their composition depends on the grid and the task, never on N), so every point a shard
  computes is, bit for bit, the point of the unsharded run, and the N shards cover the grid
  exactly once.  Chunks are dealt round-robin rather than in N consecutive blocks because a
  sweep's cost is not uniform over its grid (a regime map is slow near the Hopf line): dealt
  round-robin, each shard gets a share of every region.  Each shard's file holds the whole grid,
  its points finished and the others ``pending`` (on disk; in memory a shard holds what any run
  holds); :func:`~landau.analyses.sweep_files.merge_files`
  joins them.
* **Memory bounded by the chunking, or refused up front.**  A sweep with a file holds one flag a
  point (what is left to compute; a shard two) and the chunks in flight
  (:data:`~landau.analyses.sweep_budget.STORED_BYTES_PER_POINT`,
  :data:`~landau.analyses.sweep_budget.STORED_OVERHEAD`); the chunks of consecutive points are
  made one at a time (:class:`ChunkList`), never the grid's parameters at once: a 10⁷-point
  sweep runs in a few hundred MB.  A sweep without a file returns its whole grid in memory
  (:data:`~landau.analyses.sweep_budget.BYTES_PER_POINT` bytes a point for the ``hopf`` task).
  A grid whose estimate exceeds the memory budget — ``max_memory`` bytes, by default half of this
  machine's memory (its physical memory or its cgroup limit, whichever is smaller;
  :func:`~landau.analyses.sweep_budget.check_memory`) — is refused with an InputError before
  anything is allocated or computed.
* **Write errors named.**  A file that cannot be written is an
  :class:`~landau.errors.OutputError` naming the file and the cause: a full disk as "no space left
  on device" (whatever the netCDF backend raised,
  :func:`~landau.analyses.sweep_files.write_error`), any other error by its errno's own message.

xarray and a netCDF backend (h5netcdf, netCDF4 or scipy) are needed only to store a sweep
(:mod:`landau.analyses.sweep_files`), imported on first use (``pip install landau-friction[sweep]``).
"""

from __future__ import annotations

import math
import os
from concurrent.futures import FIRST_COMPLETED, Executor, ProcessPoolExecutor, wait
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, Iterator, Sequence

import numpy as np

from landau.analyses.sweep_budget import check_memory
from landau.analyses.sweep_files import (  # noqa: F401 - _engine, xarray: re-exported for the commands
    _engine,
    _first_line,
    xarray,
)
from landau.analyses.sweep_store import FileTable
from landau.errors import InputError

#: chunks kept in flight on an executor of unknown size (a dask cluster): twice its workers otherwise
IN_FLIGHT = 1024
#: the status of a point not computed yet
PENDING = "pending"
#: the statuses a task may give a point
STATUSES = ("ok", "no-hopf", "degenerate", "outside-validity", "failed")


# ---------------------------------------------------------------------------------------------
# grid
# ---------------------------------------------------------------------------------------------
@dataclass(frozen=True)
class Axis:
    """One swept parameter: its name, values (in sweep order) and SI unit."""

    name: str
    values: tuple[float, ...]
    units: str = ""

    def __post_init__(self):
        if not self.name.isidentifier():
            raise InputError(f"--grid: {self.name!r} is not a parameter name")
        if not self.values:
            raise InputError(f"--grid {self.name}: no values")
        if not all(math.isfinite(v) for v in self.values):
            raise InputError(f"--grid {self.name}: every value must be finite")
        if len(set(self.values)) != len(self.values):
            raise InputError(f"--grid {self.name}: a value is given twice")


#: the largest number of values of one axis and of the whole grid
MAX_AXIS, MAX_POINTS = 10_000_000, 100_000_000


def parse_axis(text: str) -> Axis:
    """An axis from ``NAME=LO:HI:N[:log]`` (N values from LO to HI, evenly or log-spaced) or
    ``NAME=v1,v2,...``.

    Parameters
    ----------
    text : str
        The ``--grid`` argument.

    Returns
    -------
    Axis

    Raises
    ------
    InputError
        Not of either form, N < 1, a value that is not a finite number, log-spacing of a range
        that is not positive.
    """
    if "=" not in text:
        raise InputError(f"--grid {text!r}: expected NAME=LO:HI:N[:log] or NAME=v1,v2,...")
    name, spec = (s.strip() for s in text.split("=", 1))

    def num(tok: str) -> float:
        try:
            x = float(tok)
        except ValueError:
            raise InputError(f"--grid {name}: {tok!r} is not a number") from None
        if not math.isfinite(x):
            raise InputError(f"--grid {name}: {tok!r} is not finite")
        return x

    if ":" in spec:
        parts = spec.split(":")
        if len(parts) not in (3, 4) or (len(parts) == 4 and parts[3].strip() not in ("log", "lin")):
            raise InputError(f"--grid {name}={spec}: expected LO:HI:N or LO:HI:N:log")
        lo, hi = num(parts[0]), num(parts[1])
        try:
            n = int(parts[2])
        except ValueError:
            raise InputError(f"--grid {name}: the number of values {parts[2]!r} is not an integer") from None
        if not 1 <= n <= MAX_AXIS:
            raise InputError(f"--grid {name}: the number of values must be between 1 and {MAX_AXIS}, got {n}")
        if n > 1 and lo == hi:
            raise InputError(f"--grid {name}: LO = HI with {n} values")
        if len(parts) == 4 and parts[3].strip() == "log":
            if not (lo > 0 and hi > 0):
                raise InputError(f"--grid {name}: a log-spaced range needs LO > 0 and HI > 0")
            vals = np.logspace(math.log10(lo), math.log10(hi), n)
        else:
            vals = np.linspace(lo, hi, n)
        return Axis(name, tuple(float(v) for v in vals))
    toks = [t for t in (t.strip() for t in spec.split(",")) if t]
    if not toks:
        raise InputError(f"--grid {name}: no values")
    return Axis(name, tuple(num(t) for t in toks))


@dataclass(frozen=True)
class Grid:
    """The Cartesian product of axes; points are numbered in C order (the last axis fastest)."""

    axes: tuple[Axis, ...]

    def __post_init__(self):
        if not self.axes:
            raise InputError("a sweep needs at least one --grid axis")
        names = [a.name for a in self.axes]
        dup = sorted({n for n in names if names.count(n) > 1})
        if dup:
            raise InputError(f"--grid {dup[0]} is given twice")
        if self.size > MAX_POINTS:
            raise InputError(f"the grid has {self.size} points; at most {MAX_POINTS} are accepted")

    @property
    def names(self) -> tuple[str, ...]:
        return tuple(a.name for a in self.axes)

    @property
    def shape(self) -> tuple[int, ...]:
        return tuple(len(a.values) for a in self.axes)

    @property
    def size(self) -> int:
        return int(np.prod(self.shape, dtype=np.int64))

    def columns(self, flat: np.ndarray) -> dict[str, np.ndarray]:
        """The parameter values at flat indices ``flat``, one array per axis."""
        idx = np.unravel_index(np.asarray(flat, dtype=np.int64), self.shape)
        return {a.name: np.asarray(a.values, dtype=float)[i] for a, i in zip(self.axes, idx, strict=True)}


def make_grid(grid: Any, units: dict[str, str] | None = None) -> Grid:
    """A :class:`Grid` from a Grid, a mapping ``name -> values`` (or ``name -> "LO:HI:N[:log]"``) or a
    sequence of ``"NAME=..."`` strings; ``units`` names each parameter's unit."""
    units = units or {}
    if isinstance(grid, Grid):
        axes = list(grid.axes)
    elif isinstance(grid, dict):
        axes = []
        for name, vals in grid.items():
            if isinstance(vals, str):
                axes.append(parse_axis(f"{name}={vals}"))
            else:
                arr = np.atleast_1d(np.asarray(vals, dtype=float))
                if arr.ndim != 1:
                    raise InputError(f"grid {name}: values must be a 1-D list")
                axes.append(Axis(str(name), tuple(float(v) for v in arr)))
    elif isinstance(grid, (list, tuple)) and all(isinstance(g, str) for g in grid):
        axes = [parse_axis(g) for g in grid]
    else:
        raise InputError("grid: expected a mapping NAME -> values or a list of 'NAME=LO:HI:N[:log]' strings")
    return Grid(tuple(Axis(a.name, a.values, units.get(a.name, a.units)) for a in axes))


# ---------------------------------------------------------------------------------------------
# shards
# ---------------------------------------------------------------------------------------------
def parse_shard(shard: Any) -> tuple[int, int] | None:
    """``(I, N)`` from ``"I/N"`` or a pair of integers (1 <= I <= N); None for None.

    Raises
    ------
    InputError
        Not of that form, N < 1 or I outside 1..N.
    """
    if shard is None:
        return None
    if isinstance(shard, str):
        parts = shard.split("/")
        try:
            i, n = (int(t) for t in parts) if len(parts) == 2 else (None, None)
        except ValueError:
            i = n = None
    elif isinstance(shard, (tuple, list)) and len(shard) == 2 and all(
            isinstance(v, (int, np.integer)) and not isinstance(v, bool) for v in shard):
        i, n = int(shard[0]), int(shard[1])
    else:
        i = n = None
    if i is None or n is None:
        raise InputError(f"--shard {shard!r}: expected I/N, the I-th of N shards (e.g. 3/8)")
    if n < 1 or not 1 <= i <= n:
        raise InputError(f"--shard {i}/{n}: I must be between 1 and N (N >= 1)")
    return i, n


def shard_of(chunk_number: int, n: int) -> int:
    """The shard (1..n) that computes chunk ``chunk_number``: the chunks dealt round-robin."""
    return chunk_number % n + 1


# ---------------------------------------------------------------------------------------------
# chunks
# ---------------------------------------------------------------------------------------------
@dataclass
class Chunk:
    """Points computed together: their flat indices and parameters, and for a continuation the
    warm-up parameter values run (not recorded) before the first point."""

    number: int
    index: np.ndarray
    points: dict[str, np.ndarray]
    warm: list[dict[str, float]] = field(default_factory=list)
    done: dict[int, dict[str, Any]] = field(default_factory=dict)  # position -> stored record (resume)


class ChunkList(Sequence[Chunk]):
    """The chunks of consecutive flat indices of a grid, each made when asked for: the list of a
    grid of 10⁸ points is not 10⁸ parameters in memory."""

    def __init__(self, grid: Grid, size: int):
        self.grid, self.size = grid, int(size)

    def __len__(self) -> int:
        return -(-self.grid.size // self.size)

    def span(self, number: int) -> slice:
        """The flat indices of chunk ``number`` as a slice."""
        return slice(number * self.size, min(self.grid.size, (number + 1) * self.size))

    def __getitem__(self, number):
        if isinstance(number, slice):
            return [self[i] for i in range(*number.indices(len(self)))]
        if not -len(self) <= number < len(self):
            raise IndexError(number)
        number %= len(self)
        sp = self.span(number)
        idx = np.arange(sp.start, sp.stop, dtype=np.int64)
        return Chunk(number, idx, self.grid.columns(idx))

    def with_todo(self, todo: np.ndarray) -> np.ndarray:
        """The numbers of the chunks with a point flagged in ``todo`` (vectorised, in blocks)."""
        out = []
        step = max(1, (1 << 22) // self.size) * self.size
        for s in range(0, self.grid.size, step):
            part = todo[s:s + step]
            pad = (-len(part)) % self.size
            if pad:
                part = np.concatenate([part, np.zeros(pad, dtype=bool)])
            out.append(np.flatnonzero(part.reshape(-1, self.size).any(axis=1)) + s // self.size)
        return np.concatenate(out) if out else np.zeros(0, dtype=np.int64)


def chunks(grid: Grid, size: int, along: str | None = None, overlap: int = 0,
           descending: bool = False) -> Sequence[Chunk]:
    """The grid cut into chunks of at most ``size`` points.

    Without ``along`` the chunks are runs of consecutive flat indices.  With ``along`` (a
    continuation, e.g. in the forcing frequency) each line of the grid along that axis is run in
    increasing (or, ``descending``, decreasing) order and cut into pieces of ``size`` points, each
    preceded by the ``overlap`` points before it as warm-up.  The cut depends only on the grid.
    """
    if size < 1:
        raise InputError(f"chunk size must be >= 1, got {size}")
    if along is None:
        return ChunkList(grid, size)
    out: list[Chunk] = []
    if along not in grid.names:
        raise InputError(f"the continuation parameter {along} is not swept (give --grid {along}=...)")
    ax = grid.names.index(along)
    flat = np.arange(grid.size, dtype=np.int64).reshape(grid.shape)
    lines = np.moveaxis(flat, ax, -1).reshape(-1, grid.shape[ax])
    order = np.argsort(np.asarray(grid.axes[ax].values))
    if descending:
        order = order[::-1]
    for line in lines:
        seq = line[order]
        for s in range(0, len(seq), size):
            idx = seq[s:s + size]
            warm_idx = seq[max(0, s - overlap):s]
            cols = grid.columns(warm_idx)
            warm = [{k: float(v[j]) for k, v in cols.items()} for j in range(len(warm_idx))]
            out.append(Chunk(len(out), idx, grid.columns(idx), warm))
    return out


@dataclass
class ChunkResult:
    """What a chunk returns: per point its status, message and the task's variables (columns)."""

    index: np.ndarray
    status: list[str]
    message: list[str]
    values: dict[str, np.ndarray]            # name -> array (n,) or (n, m) for a per-point list
    strings: dict[str, list[str]] = field(default_factory=dict)
    error: BaseException | None = None       # the exception that failed the chunk (``strict`` runs)


def _only(res: ChunkResult, mask: np.ndarray) -> ChunkResult:
    """The points of ``res`` whose flat index is set in ``mask``."""
    keep = np.flatnonzero(mask[np.asarray(res.index, dtype=np.int64)])
    if len(keep) == len(res.index):
        return res
    return ChunkResult(np.asarray(res.index)[keep], [res.status[j] for j in keep], [res.message[j] for j in keep],
                       {k: np.asarray(v)[keep] for k, v in res.values.items()},
                       {k: [v[j] for j in keep] for k, v in res.strings.items()}, res.error)


def splittable(task) -> bool:
    """Whether a failing chunk of ``task`` may be re-run point by point: a task says so with its
    attribute ``splittable``; by default every task but a continuation (whose points depend on the
    points before them in the chunk, so that a point run alone is not the point of the chunk)."""
    return bool(getattr(task, "splittable", not getattr(task, "continuation", False)))


def _part(chunk: Chunk, start: int, stop: int) -> Chunk:
    """Points ``start:stop`` of ``chunk`` as a chunk of their own (parameters still arrays)."""
    return Chunk(chunk.number, np.asarray(chunk.index)[start:stop],
                 {k: np.asarray(v)[start:stop] for k, v in chunk.points.items()})


def _joined(parts: list[ChunkResult]) -> ChunkResult:
    """The results ``parts`` of consecutive pieces of a chunk as one: a variable a piece lacks (a
    failed point returns none) is NaN there, a string "", a list padded with NaN to the longest."""
    sizes = [len(r.index) for r in parts]
    n = sum(sizes)
    starts = np.concatenate([[0], np.cumsum(sizes)]).astype(int)
    values: dict[str, np.ndarray] = {}
    for name in dict.fromkeys(k for r in parts for k in r.values):
        rows = [np.asarray(r.values[name], dtype=float) if name in r.values else None for r in parts]
        widths = [row.shape[1] for row in rows if row is not None and row.ndim == 2]
        col = np.full((n, max(widths)) if widths else (n,), np.nan)
        for a, b, row in zip(starts[:-1], starts[1:], rows, strict=True):
            if row is None:
                continue
            if col.ndim == 1:
                col[a:b] = row.reshape(-1)
            else:
                row = row.reshape(b - a, -1)
                col[a:b, :row.shape[1]] = row
        values[name] = col
    strings = {name: [x for r, m in zip(parts, sizes, strict=True) for x in r.strings.get(name, [""] * m)]
               for name in dict.fromkeys(k for r in parts for k in r.strings)}
    return ChunkResult(np.concatenate([np.asarray(r.index) for r in parts]),
                       [s for r in parts for s in r.status], [m for r in parts for m in r.message], values, strings,
                       next((r.error for r in parts if r.error is not None), None))


def run_chunk(task, chunk: Chunk, split: bool = True) -> ChunkResult:
    """Run ``task`` on one chunk (in a worker).

    A chunk of several points that raises is run again in two halves (with ``split``, for a
    :func:`splittable` task), each split again if it raises, down to single points: the valid
    points get their values, each failing point status ``failed`` and its own exception's first
    line, in O(k log n) runs for k failing points among n (n runs, one per point, would make a
    chunk of 4096 points with one bad point 700 times slower than the chunk).  Otherwise the
    exception marks every point of the chunk ``failed`` with its first line.  The result's
    ``error`` is the exception (the first failing point's after a split).
    """
    try:
        res = task.run(chunk)
    except (KeyboardInterrupt, SystemExit):
        raise
    except Exception as exc:  # noqa: BLE001 - one failing chunk must not end the sweep
        n = len(chunk.index)
        if split and n > 1 and splittable(task):
            half = n // 2
            return _joined([run_chunk(task, _part(chunk, 0, half)), run_chunk(task, _part(chunk, half, n))])
        return ChunkResult(chunk.index, ["failed"] * n, [_first_line(exc)] * n, {}, error=exc)
    return res


# ---------------------------------------------------------------------------------------------
# the in-memory table (its file: landau.analyses.sweep_files)
# ---------------------------------------------------------------------------------------------
class Table:
    """Every point's status, message and variables, stored flat (grid.size rows)."""

    def __init__(self, grid: Grid, units: dict[str, str]):
        self.grid = grid
        self.units = dict(units)
        self.status = np.full(grid.size, PENDING, dtype=object)
        self.message = np.full(grid.size, "", dtype=object)
        self.values: dict[str, np.ndarray] = {}
        self.strings: dict[str, np.ndarray] = {}
        self.shard: tuple[int, int] | None = None   # (I, N) of a shard's run
        self.shard_points = grid.size                # the points this run computes

    def _column(self, name: str, width: int | None) -> np.ndarray:
        col = self.values.get(name)
        shape = (self.grid.size,) if width is None else (self.grid.size, width)
        if col is None:
            col = self.values[name] = np.full(shape, np.nan)
        elif width is not None and col.shape[1] < width:  # a longer list: widen, padded with NaN
            wide = np.full(shape, np.nan)
            wide[:, :col.shape[1]] = col
            col = self.values[name] = wide
        return col

    def put(self, res: ChunkResult) -> None:
        idx = np.asarray(res.index, dtype=np.int64)
        for name, arr in res.values.items():
            arr = np.asarray(arr, dtype=float)
            col = self._column(name, None if arr.ndim == 1 else arr.shape[1])
            if arr.ndim == 1:
                col[idx] = arr
            else:
                col[idx] = np.nan
                col[idx, :arr.shape[1]] = arr
        for name, vals in res.strings.items():
            col = self.strings.setdefault(name, np.full(self.grid.size, "", dtype=object))
            col[idx] = [str(v) for v in vals]   # plain str (not numpy's str_): one type to write
        self.status[idx] = [str(v) for v in res.status]
        self.message[idx] = [str(v) for v in res.message]

    def record(self, i: int) -> dict[str, Any]:
        """Point ``i`` as stored (used to resume a continuation)."""
        out: dict[str, Any] = {"status": self.status[i]}
        for name, col in self.values.items():
            out[name] = col[i]
        for name, col in self.strings.items():
            out[name] = col[i]
        return out

    def dataset(self, attrs: dict[str, Any]):
        xr = xarray()
        g = self.grid
        dims = list(g.names)
        coords = {a.name: (a.name, np.asarray(a.values), {"units": a.units} if a.units else {}) for a in g.axes}
        data: dict[str, Any] = {}
        for name, col in self.values.items():
            if col.ndim == 1:
                data[name] = (dims, col.reshape(g.shape))
            else:
                data[name] = ([*dims, f"{name}_index"], col.reshape(*g.shape, col.shape[1]))
        # the strings stay Python objects (written as variable-length strings): a fixed-width copy
        # (``astype(str)``) takes 4 bytes a character of the longest, 1.2 kB a point for a 300-character message
        for name, col in self.strings.items():
            data[name] = (dims, col.reshape(g.shape))
        data["status"] = (dims, self.status.reshape(g.shape))
        data["message"] = (dims, self.message.reshape(g.shape))
        ds = xr.Dataset(data, coords=coords, attrs=attrs)
        for name in self.values:
            if self.units.get(name):
                ds[name].attrs["units"] = self.units[name]
        ds["status"].attrs["meaning"] = ("ok, or why the point has no result: " + ", ".join(STATUSES[1:])
                                         + f"; {PENDING}: not computed yet")
        return ds


# ---------------------------------------------------------------------------------------------
# the run
# ---------------------------------------------------------------------------------------------
@dataclass
class RunCounts:
    computed: int = 0
    reused: int = 0
    failed: int = 0
    distrusted: str = ""   # why a stored file was not reused (its points computed again); "" if it was
    kept_failed: int = 0   # failed points of the file not computed again (a deterministic failure would repeat)


def execute(task, grid: Grid, *, executor: Executor | None = None, workers: int | None = None,
            out: str | os.PathLike | None = None, attrs: dict[str, Any], progress: bool = True,
            write_every: float = 5.0, shard: Any = None, max_memory: Any = None, load: bool = True):
    """Run ``task`` over ``grid`` and return ``(dataset, counts)``; with ``out`` and not ``load``,
    ``(facts, counts)``: the file's statuses and variables (:func:`landau.analyses.sweep_store.scan`),
    the Dataset not loaded (a grid of 10⁷ points in bounded memory).

    See :func:`landau.analyses.sweep.sweep` for the parameters.
    """
    table, counts = run_table(task, grid, executor=executor, workers=workers, out=out, attrs=attrs,
                              progress=progress, write_every=write_every, shard=shard, max_memory=max_memory)
    if isinstance(table, FileTable):
        return (table.dataset() if load else table.facts), counts
    return table.dataset({**attrs, **_shard_attrs(table), "computed": counts.computed,
                          "reused": counts.reused}), counts


def _shard_attrs(table) -> dict[str, Any]:
    """The attributes naming a shard's part of the grid (none for an unsharded run)."""
    if table.shard is None:
        return {}
    return {"shard": f"{table.shard[0]}/{table.shard[1]}", "shard_points": int(table.shard_points)}


def _spans(all_chunks: Sequence[Chunk]) -> Iterator[tuple[int, Any]]:
    """Each chunk's number and flat indices (a slice for a :class:`ChunkList`: no chunk is made)."""
    if isinstance(all_chunks, ChunkList):
        for n in range(len(all_chunks)):
            yield n, all_chunks.span(n)
    else:
        for ch in all_chunks:
            yield ch.number, np.asarray(ch.index, dtype=np.int64)


def _owned(all_chunks: Sequence[Chunk], grid: Grid, shard: tuple[int, int] | None) -> np.ndarray | None:
    """For a shard, the flags of the points of its chunks (every N-th, :func:`shard_of`); None otherwise."""
    if shard is None:
        return None
    i, n = shard
    owned = np.zeros(grid.size, dtype=bool)
    for number, idx in _spans(all_chunks):
        if shard_of(number, n) == i:
            owned[idx] = True
    return owned


def _open_table(task, grid: Grid, out: str | os.PathLike | None, attrs: dict[str, Any], write_every: float):
    """The run's table and the flags of the points to compute: in memory without ``out``, else a
    :class:`~landau.analyses.sweep_store.FileTable` (the file checked, its trusted finished points and
    the journal's taken)."""
    if out is None:
        table = Table(grid, task.units())
        return table, np.ones(grid.size, dtype=bool)
    path = Path(out)
    if path.suffix.lower() not in (".nc", ".nc4", ".netcdf"):
        raise InputError(f"--out {str(path)!r}: a sweep is written as netCDF (.nc)")
    if path.exists() and not path.is_file():
        raise InputError(f"--out {str(path)!r} is not a regular file")
    ftable = FileTable(path, grid, task.units(), attrs, write_every)
    return ftable, ftable.open(attrs)


def _work(task, all_chunks: Sequence[Chunk], table, todo_mask: np.ndarray) -> tuple[int, Iterator[Chunk]]:
    """How many chunks have a point to compute, and those chunks, made one at a time (a
    continuation's finished points passed in ``done``)."""
    if isinstance(all_chunks, ChunkList):
        numbers = all_chunks.with_todo(todo_mask)
    else:
        numbers = np.array([n for n, idx in _spans(all_chunks) if todo_mask[idx].any()], dtype=np.int64)

    def made() -> Iterator[Chunk]:
        for n in numbers:
            ch = all_chunks[int(n)]
            pending = todo_mask[ch.index]
            if not pending.all() and task.continuation:
                ch.done = {j: table.record(int(i)) for j, i in enumerate(ch.index) if not todo_mask[i]}
            # a partly finished chunk is computed whole (the same batch as in an uninterrupted run, so the
            # same numbers to the last bit) and only its missing points are stored
            yield ch
    return len(numbers), made()


def local_pool(workers: int) -> ProcessPoolExecutor:
    """``workers`` local processes that end with this one (:func:`landau.support.lifetime.die_with_parent`:
    a killed sweep leaves no worker behind)."""
    from landau.support.lifetime import die_with_parent

    return ProcessPoolExecutor(max_workers=workers, initializer=die_with_parent, initargs=(os.getpid(),))


def _stop(pool: ProcessPoolExecutor, now: bool) -> None:
    """Shut the local pool down; ``now`` (the run is interrupted or failed): its workers are ended
    first, since the chunks they are running would be thrown away."""
    if now:
        for proc in list((getattr(pool, "_processes", None) or {}).values()):
            try:
                proc.terminate()
            except (OSError, ValueError):   # already gone
                pass
    pool.shutdown(wait=True, cancel_futures=True)


def _drain(executor: Executor, work: Iterator[Chunk], task, workers: int, take, strict: bool) -> None:
    """Run ``work`` on ``executor``, at most ``2 × workers`` chunks in flight, each result to ``take``."""
    inflight: set = set()
    try:
        more = True
        while more or inflight:
            while more and len(inflight) < 2 * workers:
                ch = next(work, None)
                if ch is None:
                    more = False
                    break
                inflight.add(executor.submit(run_chunk, task, ch, not strict))
            if not inflight:
                break
            done, inflight = wait(inflight, return_when=FIRST_COMPLETED)
            for f in done:
                take(f.result())
    except BaseException:
        for f in inflight:  # keep whatever finished, drop the rest
            if not strict and f.done() and not f.cancelled() and f.exception() is None:
                take(f.result())
            else:
                f.cancel()
        raise


def run_table(task, grid: Grid, *, executor: Executor | None = None, workers: int | None = None,
              out: str | os.PathLike | None = None, attrs: dict[str, Any] | None = None, progress: bool = True,
              write_every: float = 5.0, strict: bool = False, shard: Any = None,
              max_memory: Any = None) -> tuple[Any, RunCounts]:
    """Run ``task`` over ``grid`` and return ``(table, counts)``: the engine under :func:`execute`,
    without the Dataset (xarray is needed only with ``out``).

    Parameters
    ----------
    task, grid, executor, workers, out, progress, write_every, shard, max_memory
        As :func:`landau.analyses.sweep.sweep` (``out`` here is the file itself, a shard's included).
    attrs : dict, optional
        The dataset's attributes (with ``out``).
    strict : bool
        The first chunk that fails ends the run with its exception (for callers that want the
        exception, not a ``failed`` status); the chunks in flight are cancelled, a failing chunk
        is not re-run point by point.

    Returns
    -------
    (Table or FileTable, RunCounts)
        In memory without ``out``; with ``out``, the file's table (:mod:`landau.analyses.sweep_store`).

    Raises
    ------
    InputError
        A bad ``shard``, a grid over the memory budget (:func:`check_memory`), an ``out`` that holds
        another sweep.
    OutputError
        ``out`` cannot be written (a full disk, a folder without write permission).
    KeyboardInterrupt
        Ctrl-C, or SIGTERM (:class:`landau.support.lifetime.Terminated`) when called from the main
        thread: the finished points are written first.

    Notes
    -----
    On local processes (no ``executor``, ``workers`` > 1), whatever the workers need is compiled or
    loaded in this process before they start (forked, they inherit it): ``task.prepare()``, and for
    a task with ``lead = True`` (a per-point callable that builds what it needs lazily) its first
    chunk is run here first.  The numbers do not depend on where a chunk ran.
    """
    shard = parse_shard(shard)
    # before anything is allocated: the table in memory, or one flag a point with a file
    check_memory(grid, max_memory, stored=out is not None)
    attrs = dict(attrs or {})
    table, todo_mask = _open_table(task, grid, out, attrs, write_every)
    counts = RunCounts(distrusted=getattr(table, "distrusted", ""), kept_failed=getattr(table, "kept_failed", 0))
    all_chunks = task.chunks(grid)
    owned = _owned(all_chunks, grid, shard)
    if owned is not None:   # a shard computes its own points only
        todo_mask &= owned
        table.shard, table.shard_points = shard, int(np.count_nonzero(owned))
        attrs.update(_shard_attrs(table))
        del owned
    counts.reused = int(table.shard_points - np.count_nonzero(todo_mask))
    n_work, work = _work(task, all_chunks, table, todo_mask)
    return table, _run(task, table, todo_mask, n_work, work, counts, executor=executor, workers=workers,
                       attrs=attrs, progress=progress, strict=strict)


def _run(task, table, todo_mask: np.ndarray, n_work: int, work: Iterator[Chunk], counts: RunCounts, *,
         executor: Executor | None, workers: int | None, attrs: dict[str, Any], progress: bool,
         strict: bool) -> RunCounts:
    """The chunks ``work`` computed on the executor, each result put in ``table``; the file (if any)
    written at the end, whatever ends the run."""
    from landau.support.lifetime import terminate_as_interrupt
    from landau.support.progress import progress as bar_for

    n_todo = int(np.count_nonzero(todo_mask))
    own = None
    lead: list[Chunk] = []
    if executor is None:
        workers = int(workers or os.cpu_count() or 1)
        if workers < 1:
            raise InputError(f"--workers must be >= 1, got {workers}")
        if workers > 1 and n_work > 1:
            task.prepare()  # compile (or load) in this process: forked workers inherit it
            if getattr(task, "lead", False):
                lead = [next(work)]
    else:  # a foreign executor (a cluster's size is not known here): many chunks in flight
        workers = int(workers or getattr(executor, "_max_workers", None) or IN_FLIGHT // 2)
    bar = bar_for(total=n_todo, desc=f"sweep {task.name}", unit="pt") if progress else None

    def take(res: ChunkResult):
        if strict and res.error is not None:
            raise res.error
        res = _only(res, todo_mask)
        table.put(res)
        counts.computed += len(res.index)
        counts.failed += sum(1 for s in res.status if s == "failed")
        if bar is not None:
            bar.update(len(res.index))

    finished = False
    with terminate_as_interrupt():
        try:
            for ch in lead:  # before the pool starts: forked workers inherit what it built
                take(run_chunk(task, ch, not strict))
            if lead or (executor is None and workers > 1 and n_work > 1):
                # never more processes than chunks (a large --workers on a short sweep starts no idle process)
                own = executor = local_pool(max(1, min(workers, n_work)))
            if executor is None:
                for ch in work:
                    take(run_chunk(task, ch, not strict))
            else:
                _drain(executor, work, task, workers, take, strict)
            finished = True
        finally:
            if bar is not None:
                bar.close()
            if own is not None:
                _stop(own, now=not finished)
            if isinstance(table, FileTable):
                table.finish({**attrs, "computed": counts.computed, "reused": counts.reused})
    return counts
