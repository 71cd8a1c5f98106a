"""A per-point callable on the sweep mechanism: parameter loops of independent points, in parallel.

The figure scripts and the scans of :mod:`landau.analyses.transition` evaluate a function at each
value of a parameter, each value on its own (no point starts from another).  :func:`map_points`
runs such a loop on the engine of :func:`landau.sweep` (:mod:`landau.analyses.sweep_engine`):
the same chunks, executors (this process, local processes, any ``concurrent.futures`` executor)
and the same guarantee that no number depends on the executor or the number of workers, since
every point is computed by the same deterministic code from its own parameters.

The callable must be picklable (a module-level function, or a :func:`functools.partial` of one)
and return a mapping ``name -> value`` with, for every point, the same names: a float, or a 1-D
sequence of floats (stored padded with NaN to the longest; return its length too when NaN is a
value).  An object the callable needs but that cannot be pickled (a derivation with its compiled
kernels) travels as a :class:`Shared` reference: forked local workers inherit it, other executors
rebuild it once per process from a recipe.

Continuations (a point started from the previous one) are not for this: they are tasks with
``continuation = True`` (the ω-sweep of the forced oscillator, :mod:`landau.verify.skurativskyi.sweep`).
"""

from __future__ import annotations

import math
import uuid
from concurrent.futures import Executor
from dataclasses import dataclass
from typing import Any, Callable, ClassVar, Mapping

import numpy as np

from landau.analyses.sweep_engine import Chunk, ChunkResult, make_grid, run_table
from landau.analyses.sweep_tasks import Task
from landau.errors import InputError

#: objects sent by reference (:class:`Shared`), by token; inherited by forked workers
_SHARED: dict[str, Any] = {}


class Shared:
    """An object the points need, sent to the workers by reference.

    In this process and in the local workers (forked after it was registered) the reference
    resolves to the object itself; in a process that does not have it (a dask worker), to
    ``rebuild()``, called once per process.  Use as a context manager, so that the registry
    forgets the object when the loop is over.

    Parameters
    ----------
    obj : object
        The object (e.g. a :class:`~landau.derivation.multiscale.Derivation`).
    rebuild : callable, optional
        A picklable function of no argument that builds an equal object in another process.
    """

    def __init__(self, obj: Any, rebuild: Callable[[], Any] | None = None):
        self.token = uuid.uuid4().hex
        self.rebuild = rebuild
        _SHARED[self.token] = obj

    def get(self) -> Any:
        obj = _SHARED.get(self.token)
        if obj is None:
            if self.rebuild is None:
                raise InputError("a shared object of this sweep cannot be rebuilt in this worker (it has no "
                                 "recipe): run the sweep on local processes")
            obj = _SHARED[self.token] = self.rebuild()
        return obj

    def release(self) -> None:
        _SHARED.pop(self.token, None)

    def __enter__(self) -> "Shared":
        return self

    def __exit__(self, *exc) -> None:
        self.release()

    def __getstate__(self) -> dict:
        return {"token": self.token, "rebuild": self.rebuild}

    def __setstate__(self, state: dict) -> None:
        self.token, self.rebuild = state["token"], state["rebuild"]


@dataclass(frozen=True)
class PointTask(Task):
    """The task of :func:`map_points`: ``fn(**fixed, **point)`` at every point, independently.

    ``lead``: on local processes the first chunk runs in this process before the workers start,
    so that what the callable builds lazily (a derivation's kernels) is built once and inherited.
    """

    fn: Callable[..., Mapping[str, Any]] | None = None
    lead: ClassVar[bool] = True

    def units(self) -> dict[str, str]:
        return {}

    def attrs(self) -> dict[str, Any]:
        fn = getattr(self.fn, "func", self.fn)
        return {"task": "points", "function": f"{getattr(fn, '__module__', '')}.{getattr(fn, '__qualname__', fn)}"}

    def run(self, chunk: Chunk) -> ChunkResult:
        if self.fn is None:
            raise InputError("a per-point sweep needs a function")
        n = len(chunk.index)
        rows = []
        for j in range(n):
            point = {k: float(v[j]) for k, v in chunk.points.items()}
            rows.append(dict(self.fn(**dict(self.fixed), **point)))
        names = list(dict.fromkeys(k for r in rows for k in r))
        values: dict[str, np.ndarray] = {}
        for name in names:
            cells = [r.get(name, math.nan) for r in rows]
            if any(np.ndim(c) for c in cells):
                width = max([1, *(len(np.atleast_1d(c)) for c in cells)])
                arr = np.full((n, width), np.nan)
                for j, c in enumerate(cells):
                    c = np.atleast_1d(np.asarray(c, dtype=float))
                    arr[j, :len(c)] = c
                values[name] = arr
            else:
                values[name] = np.array(cells, dtype=float)
        return ChunkResult(chunk.index, ["ok"] * n, [""] * n, values)


def map_points(fn: Callable[..., Mapping[str, Any]], grid: Any, *, fixed: Mapping[str, Any] | None = None,
               workers: int | None = 1, executor: Executor | None = None, chunk_size: int = 1,
               progress: bool = False) -> list[dict[str, Any]]:
    """``fn(**fixed, **point)`` at every point of ``grid``, on the sweep engine.

    Parameters
    ----------
    fn : callable
        Picklable; returns a mapping of floats and 1-D float sequences (see the module docstring).
    grid : mapping
        ``{name: values}`` (as :func:`landau.sweep`); points in C order.
    fixed : mapping, optional
        Keyword arguments passed unchanged to every call (picklable: a :class:`Shared` for an
        object that is not).
    workers : int, optional
        Local processes when no executor is given (1: this process, the default; None:
        ``os.cpu_count()``).
    executor : concurrent.futures.Executor, optional
        Where the chunks run (a dask ``Client(...).get_executor()``).
    chunk_size : int
        Points per chunk.
    progress : bool
        A progress bar.

    Returns
    -------
    list of dict
        Per point (C order), ``name -> float`` or a 1-D array (NaN-padded to the longest).

    Raises
    ------
    Exception
        The exception of the first point that raised (the loop stops there), as a plain loop
        would raise it.
    """
    g = make_grid(grid)
    task = PointTask("points", "", None, tuple(sorted((fixed or {}).items())), (), chunk_size=int(chunk_size),
                     fn=fn)
    table, _ = run_table(task, g, executor=executor, workers=workers, progress=progress, strict=True)
    return [{name: (col[i] if col.ndim == 1 else col[i].copy()) for name, col in table.values.items()}
            for i in range(g.size)]
