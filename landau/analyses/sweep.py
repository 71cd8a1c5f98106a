"""``landau.sweep``: any analysis over a parameter grid, as a labelled xarray Dataset.

Example::

    import landau
    ds = landau.sweep("hopf", {"V": np.logspace(-6, -3, 40), "a": [0.01, 0.02, 0.03]},
                      model="spring-block", law="dieterich", out="k_c.nc")
    ds.k_c.sel(a=0.02).plot()

The Dataset's dimensions are the swept parameters (coordinates with their SI units), its
variables the task's quantities named as in the matching ``--json`` output (``p_c``/``k_c``, ``kc`` deprecated,
``omega_c``, ``Lambda``, ``criticality``, … for ``hopf``; ``verdict`` and its numbers for
``check``) plus ``status`` and ``message`` per point; its attributes the model, the law's
declaration, the convention, the landau version, the fixed parameters and the counts
``computed`` and ``reused``.  The mechanism (chunks, executors, incremental netCDF, resuming) is
:mod:`landau.analyses.sweep_engine`; the tasks are :mod:`landau.analyses.sweep_tasks`.

A sweep too large for one machine runs as shards (a SLURM job array, independent machines), each
computing every N-th chunk into a file of its own, joined by :func:`merge`::

    landau.sweep("hopf", grid, law="dieterich", out="map.nc", shard=(3, 8))   # writes map.shard-3-of-8.nc
    ds, report = merge([f"map.shard-{i}-of-8.nc" for i in range(1, 9)], "map.nc")
"""

from __future__ import annotations

import os
from concurrent.futures import Executor
from typing import Any, Mapping

from landau.analyses.sweep_engine import execute, make_grid, parse_shard
from landau.analyses.sweep_files import merge_files, shard_path
from landau.analyses.sweep_tasks import LawSpec, make_task
from landau.errors import InputError


def law_spec(law: Any) -> LawSpec | None:
    """A :class:`LawSpec` from a built-in law's name, a :class:`~landau.laws.FrictionLaw`, a LawSpec, or None."""
    if law is None or isinstance(law, LawSpec):
        return law
    if isinstance(law, str):
        from landau.laws import BUILTIN, is_law_name

        if not is_law_name(law):
            raise InputError(f"unknown law {law!r} (built-in: {', '.join(BUILTIN)}; an inline law: "
                             "LawSpec(name, mu, states))")
        return LawSpec(law)
    from landau.laws import FrictionLaw

    if isinstance(law, FrictionLaw):
        return LawSpec.of(law)
    raise InputError(f"law: give a built-in law's name, a FrictionLaw or a LawSpec (got {type(law).__name__})")


def sweep(task: str, grid: Any, *, model: str = "spring-block", law: Any = None,
          params: Mapping[str, float] | None = None, executor: Executor | None = None,
          workers: int | None = None, out: str | os.PathLike | None = None, progress: bool = True,
          options: Mapping[str, Any] | None = None, return_counts: bool = False,
          shard: tuple[int, int] | str | None = None, max_memory: int | str | None = None):
    """Run ``task`` at every point of ``grid`` and return the results as an xarray Dataset.

    Parameters
    ----------
    task : {"hopf", "check", "simulate", "regime"}
        What is computed at each point (:data:`landau.analyses.sweep_tasks.TASKS`).
    grid : mapping or list of str
        The swept parameters: ``{"V": values, "a": values}`` (or ``{"V": "1e-6:1e-3:40:log"}``),
        or ``["V=1e-6:1e-3:40:log", "a=0.01,0.02"]``.  Points are numbered in C order.
    model : str
        ``spring-block`` (Putelat et al. 2010; the default), ``forced-oscillator``
        (Skurativskyi et al. 2019), or any model of ``landau hopf`` for the ``hopf`` task.
    law : str, FrictionLaw or LawSpec, optional
        The spring–block's friction law: a built-in law's name, a law object (sent to the workers
        as its declaration) or a :class:`~landau.analyses.sweep_tasks.LawSpec`.
    params : mapping, optional
        Fixed parameter values (law and system parameters; ``V`` if it is not swept).
    executor : concurrent.futures.Executor, optional
        Where the chunks run: any executor (``distributed.Client(...).get_executor()`` for a
        dask cluster).  Default: ``workers`` local processes (one: this process).
    workers : int, optional
        Local processes when no executor is given (default ``os.cpu_count()``).
    out : path, optional
        A netCDF file (``.nc``) written as the sweep goes (atomically) and at the end, also when
        the sweep is interrupted (Ctrl-C, or SIGTERM in the main thread); if it already holds this
        sweep, its finished points are reused and only the rest computed: the pending ones and those that
        failed for a reason that may not repeat (memory, time, a lost worker); a point that failed
        deterministically (a parameter outside its domain) is kept, and the count says so (``kept_failed``).
    progress : bool
        A progress bar on a terminal or in Jupyter.
    options : mapping, optional
        Task options (``eps2`` for ``check``; ``n_first``, ``n_step``, ``n_keep``, ``rtol``,
        ``overlap``, ``direction``, ``lyapunov`` for ``simulate``; ``chunk_size``).
    return_counts : bool
        Also return the counts ``{"computed": n, "reused": m, "failed": f, "kept_failed": k}``.
    shard : (int, int) or str, optional
        ``(I, N)`` or ``"I/N"``: compute only the I-th of N disjoint parts of the grid (every N-th
        chunk, starting with chunk I − 1), written to ``out`` with ``.shard-I-of-N`` before its
        suffix (:func:`~landau.analyses.sweep_files.shard_path`); join the N files with :func:`merge`.
        The points of a shard are those of the unsharded run, bit for bit; the others are ``pending``.
    max_memory : int or str, optional
        The memory the sweep may hold (bytes, or ``"8G"``, ``"500M"``); a grid whose estimate
        exceeds it is refused before any work.  Default: half of this machine's memory
        (:func:`~landau.analyses.sweep_engine.check_memory`).

    Returns
    -------
    xarray.Dataset
        (and the counts with ``return_counts``).  The numbers do not depend on the executor or the
        number of workers.

    Raises
    ------
    InputError
        An unknown task, model or parameter, a bad grid, an ``out`` that holds another sweep,
        xarray or a netCDF backend missing, a bad ``shard``, a grid over the memory budget.
    OutputError
        ``out`` cannot be written (the message names the file and the cause: "no space left on
        device", "Permission denied", ...).
    KeyboardInterrupt
        Ctrl-C or SIGTERM (:class:`~landau.support.lifetime.Terminated`), after the finished points
        were written.

    Notes
    -----
    A point that makes its chunk fail fails alone (its status ``failed``, its own message): the
    chunk is computed again in halves down to the failing points (not for a continuation).  Local worker
    processes end with this process, also when it is killed.
    """
    ds, counts = _execute(task, grid, model=model, law=law, params=params, executor=executor, workers=workers,
                          out=out, progress=progress, options=options, shard=shard, max_memory=max_memory,
                          load=True)
    if return_counts:
        return ds, counts
    return ds


def _execute(task: str, grid: Any, *, model: str, law: Any, params: Mapping[str, float] | None,
             executor: Executor | None, workers: int | None, out: str | os.PathLike | None, progress: bool,
             options: Mapping[str, Any] | None, shard: Any, max_memory: Any, load: bool):
    """:func:`sweep`'s run: ``(dataset, counts)``, or with ``out`` and not ``load`` ``(facts, counts)``
    (the file's statuses and variables, nothing loaded: :func:`landau.analyses.sweep_engine.execute`).
    A stored file not reused (edited, of another version) is said with a warning."""
    import warnings

    from landau.analyses.sweep_engine import xarray

    xarray()
    t = make_task(task, model, law_spec(law), dict(params or {}), dict(options or {}))
    g = make_grid(grid, t.units())
    t.check_grid(g)
    t = t.for_grid(g)
    part = parse_shard(shard)
    if part is not None and out is not None:
        out = shard_path(out, part)
    ds, counts = execute(t, g, executor=executor, workers=workers, out=out, attrs=t.attrs(), progress=progress,
                         shard=part, max_memory=max_memory, load=load)
    doc: dict[str, Any] = {"computed": counts.computed, "reused": counts.reused, "failed": counts.failed,
                           "kept_failed": counts.kept_failed}
    if counts.distrusted:
        warnings.warn(counts.distrusted, UserWarning, stacklevel=3)
        doc["distrusted"] = counts.distrusted
    return ds, doc


def sweep_file(task: str, grid: Any, out: str | os.PathLike, *, model: str = "spring-block", law: Any = None,
               params: Mapping[str, float] | None = None, executor: Executor | None = None,
               workers: int | None = None, progress: bool = True, options: Mapping[str, Any] | None = None,
               shard: tuple[int, int] | str | None = None, max_memory: int | str | None = None):
    """:func:`sweep` into the file ``out`` without loading it: ``(facts, counts)``, the facts the file's
    statuses (``status``: name -> count) and variables (``schema``), in the memory of the chunking
    whatever the grid (what ``landau sweep`` runs).  Parameters as :func:`sweep`."""
    return _execute(task, grid, model=model, law=law, params=params, executor=executor, workers=workers, out=out,
                    progress=progress, options=options, shard=shard, max_memory=max_memory, load=False)


def merge(paths, out: str | os.PathLike | None = None):
    """Join the shard files ``paths`` of one sweep into one Dataset (written to ``out`` if given).

    Returns ``(dataset, report)``; the report gives per file its shard, points, finished, failed
    and pending counts, the shards not given (``missing_shards``), the merged statuses and the
    points still ``pending``.  Files of different sweeps are refused (InputError).  See
    :func:`landau.analyses.sweep_files.merge_files`.
    """
    return merge_files(list(paths), out)
