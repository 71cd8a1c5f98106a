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
"""

from __future__ import annotations

import os
from concurrent.futures import Executor
from typing import Any, Mapping

from landau.analyses.sweep_engine import execute, make_grid
from landau.analyses.sweep_tasks import LawSpec, make_task
from landau.errors import InputError


def law_spec(law: Any) -> LawSpec | None:
    """A :class:`LawSpec` from a built-in law's name, a :class:`~landau.laws.FrictionLaw`, a LawSpec, or None."""
    if law is None or isinstance(law, LawSpec):
        return law
    if isinstance(law, str):
        from landau.laws import BUILTIN

        if law not in BUILTIN:
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
          options: Mapping[str, Any] | None = None, return_counts: bool = False):
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
        sweep, its finished points are reused and only the rest computed (the failed ones again).
    progress : bool
        A progress bar on a terminal or in Jupyter.
    options : mapping, optional
        Task options (``eps2`` for ``check``; ``n_first``, ``n_step``, ``n_keep``, ``rtol``,
        ``overlap``, ``direction``, ``lyapunov`` for ``simulate``; ``chunk_size``).
    return_counts : bool
        Also return the counts ``{"computed": n, "reused": m, "failed": f}``.

    Returns
    -------
    xarray.Dataset
        (and the counts with ``return_counts``).  The numbers do not depend on the executor or the
        number of workers.

    Raises
    ------
    InputError
        An unknown task, model or parameter, a bad grid, an ``out`` that holds another sweep,
        xarray or a netCDF backend missing.
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
    from landau.analyses.sweep_engine import xarray

    xarray()
    t = make_task(task, model, law_spec(law), dict(params or {}), dict(options or {}))
    g = make_grid(grid, t.units())
    t.check_grid(g)
    t = t.for_grid(g)
    ds, counts = execute(t, g, executor=executor, workers=workers, out=out, attrs=t.attrs(), progress=progress)
    if return_counts:
        return ds, {"computed": counts.computed, "reused": counts.reused, "failed": counts.failed}
    return ds
