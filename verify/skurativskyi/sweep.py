"""ω-sweeps (bifurcation diagrams) of the forced oscillator, on the sweep mechanism of landau.sweep.

A diagram is a continuation: the attractor at ω_i is started from the one at ω_{i−1}
(:func:`landau.verify.skurativskyi.analysis.continuation`).  The sweep mechanism
(:mod:`landau.analyses.sweep_engine`) cuts each line of the grid along ω into chunks of
``chunk_size`` points (a fixed number: the cut, hence every number, does not depend on the
executor or the number of workers); each chunk starts its continuation ``overlap`` points
*before* its first ω (those warm-up points are computed, not recorded), so near a hysteresis the
chunk has already settled on the branch the serial sweep would follow.  Many small equal chunks
keep every worker busy to the end.

This module gives the task ``simulate`` of the model ``forced-oscillator``
(``landau.sweep("simulate", {"omega": ...}, model="forced-oscillator")``, ``landau sweep simulate
forced-oscillator --grid omega=...``): per point the impacts per forcing period, the Poincaré
points (``x_section``, one per recorded period), the inter-impact intervals, the state at the last
section point (``y_end``, phase ωt ≡ 0: the warm start of the next ω) and, on request, the largest
Lyapunov exponent.  An interrupted sweep resumes a chunk from its last recorded ``y_end``: a
continuation step depends only on that state, so the resumed numbers equal the uninterrupted
ones.  :func:`run_sweep` is the same sweep with the :class:`Attractor` objects of
:mod:`~landau.verify.skurativskyi.analysis` as its result.

The compiled loop is built (or loaded from numba's disk cache) once in the calling process
before local workers start (:func:`warm_up`), so no worker compiles it.
"""

from __future__ import annotations

import os
from dataclasses import asdict, dataclass
from pathlib import Path

import numpy as np

from landau.analyses.sweep_engine import Chunk, ChunkResult, make_grid
from landau.analyses.sweep_tasks import ModelTask
from landau.errors import InputError
from landau.verify.hybrid.analysis import SweepResult
from landau.verify.skurativskyi.analysis import Attractor, attractor
from landau.verify.skurativskyi.model import MECHANICAL, PAPER

#: units of the task's variables and of the swept mechanical parameters
UNITS = {"omega": "rad/s", "impacts_per_period": "1", "x_section": "m", "intervals": "s", "lyapunov": "1/s",
         "periods": "1", "m": "kg", "m0e": "kg m", "k": "N/m", "xI": "m"}


@dataclass(frozen=True)
class SweepSpec:
    """What each point computes (the same for every chunk)."""

    n_first: int = 100          # transient at a chunk's first point (paper: 100 periods)
    n_step: int = 50            # transient after each change of ω (paper: 50)
    n_keep: int = 50            # recorded periods
    rtol: float = 1e-8
    lyapunov: bool = False
    overlap: int = 3            # warm-up points before each chunk
    params: tuple = ()          # Params overrides as (name, value) pairs


#: the default number of ω values per chunk
CHUNK_SIZE = 8


def make_task(task: str, model: str, law, fixed: tuple, options: tuple) -> ModelTask:
    """The ``simulate`` task of the forced oscillator (called by
    :func:`landau.analyses.sweep_tasks.make_task`); options: ``n_first``, ``n_step``, ``n_keep``,
    ``rtol``, ``lyapunov``, ``overlap``, ``direction`` ("up"/"down"), ``chunk_size``."""
    opts = dict(options)
    known = {"n_first", "n_step", "n_keep", "rtol", "lyapunov", "overlap", "direction", "chunk_size"}
    unknown = sorted(set(opts) - known)
    if unknown:
        raise InputError(f"simulate forced-oscillator: option(s) {', '.join(unknown)} do not apply (known: "
                         f"{', '.join(sorted(known))})")
    direction = opts.get("direction", "up")
    if direction not in ("up", "down"):
        raise InputError(f"direction must be 'up' or 'down' (got {direction!r})")
    spec = _spec(opts)
    if spec.n_keep < 1 or spec.n_first < 0 or spec.n_step < 0 or spec.overlap < 0 or not spec.rtol > 0:
        raise InputError("simulate forced-oscillator: need n_keep >= 1, n_first, n_step, overlap >= 0, rtol > 0")
    PAPER.with_(**dict(fixed))  # an unknown parameter is refused here, by name
    return ModelTask(task, model, None, fixed, options, chunk_size=int(opts.get("chunk_size", CHUNK_SIZE)),
                     continuation=True, along="omega", overlap=spec.overlap, descending=direction == "down",
                     chunk_fn=simulate_chunk, grid_fn=check_grid, prepare_fn=prepare, extra_units=tuple(UNITS.items()))


def _spec(opts: dict) -> SweepSpec:
    d = SweepSpec()
    return SweepSpec(int(opts.get("n_first", d.n_first)), int(opts.get("n_step", d.n_step)),
                     int(opts.get("n_keep", d.n_keep)), float(opts.get("rtol", d.rtol)),
                     bool(opts.get("lyapunov", d.lyapunov)), int(opts.get("overlap", d.overlap)))


def check_grid(task: ModelTask, grid) -> None:
    """The grid sweeps ω (positive) and, besides, mechanical or friction-law parameters."""
    if "omega" not in grid.names:
        raise InputError("simulate forced-oscillator: sweep the forcing frequency, --grid omega=...")
    om = np.asarray(grid.axes[grid.names.index("omega")].values)
    if np.any(om <= 0):
        raise InputError("--grid omega: values must be > 0 rad/s")
    for name in grid.names:
        if name != "omega":
            PAPER.with_(**{name: 1.0})  # refuses an unknown name


def prepare(task: ModelTask) -> None:
    warm_up(PAPER.with_(**dict(task.fixed)) if task.fixed else PAPER)


def simulate_chunk(task: ModelTask, chunk: Chunk) -> ChunkResult:
    """One continuation chunk: the warm-up ω values, then the chunk's points in order (those stored
    already, ``chunk.done``, are passed through with their stored final state)."""
    spec = _spec(dict(task.options))
    base = PAPER.with_(**dict(task.fixed)) if task.fixed else PAPER
    n = len(chunk.index)
    pts = [{k: float(v[j]) for k, v in chunk.points.items()} for j in range(n)]

    def params(pt):
        extra = {k: v for k, v in pt.items() if k != "omega"}
        return base.with_(**extra) if extra else base

    todo = [j for j in range(n) if j not in chunk.done]
    y, first = None, True
    k0 = todo[0] if todo else n
    if k0 > 0:  # resume from the stored final state of the point before the first missing one
        y, first = np.asarray(chunk.done[k0 - 1]["y_end"], dtype=float), False
    else:
        for pt in chunk.warm:
            y = attractor(pt["omega"], y, spec.n_first if first else spec.n_step, 1, params(pt), spec.rtol).y_end
            first = False
    rows: dict[int, Attractor] = {}
    for j in range(k0, n):
        if j in chunk.done:
            y = np.asarray(chunk.done[j]["y_end"], dtype=float)
            continue
        a = attractor(pts[j]["omega"], y, spec.n_first if first else spec.n_step, spec.n_keep, params(pts[j]),
                      spec.rtol, lyapunov=spec.lyapunov)
        first = False
        y = a.y_end
        rows[j] = a
    order = sorted(rows)
    width = max([len(rows[j].intervals) for j in order] + [1])

    def pad(arrs, m):
        out = np.full((len(arrs), m), np.nan)
        for i, a in enumerate(arrs):
            out[i, :len(a)] = a
        return out

    vals = {"impacts_per_period": np.array([rows[j].impacts_per_period for j in order], dtype=float),
            "lyapunov": np.array([rows[j].lyapunov for j in order], dtype=float),
            "periods": np.array([rows[j].periods for j in order], dtype=float),
            "x_section": pad([rows[j].x_section for j in order], spec.n_keep),
            "intervals": pad([rows[j].intervals for j in order], width),
            "y_end": pad([rows[j].y_end for j in order], 2)}
    return ChunkResult(chunk.index[order], ["ok"] * len(order), [""] * len(order), vals)


def attractors_of(ds) -> list[Attractor]:
    """The :class:`Attractor` of every point of a 1-D ``simulate`` dataset, in the order of its ω axis."""
    out = []
    for i in range(ds.sizes["omega"]):
        pt = ds.isel(omega=i)
        xs, iv = np.asarray(pt.x_section.values), np.asarray(pt.intervals.values)
        lam = float(pt.lyapunov)
        out.append(Attractor(float(pt.omega), xs[np.isfinite(xs)], iv[np.isfinite(iv)], np.empty(0),
                             float(pt.impacts_per_period), np.asarray(pt.y_end.values, dtype=float), lam,
                             int(pt.periods)))
    return out


def plot_diagram(ds, fig):
    """The bifurcation diagram of a ``simulate`` sweep in ω: the Poincaré points x(2πi/ω) and the
    impacts per forcing period against ω (Skurativskyi et al. 2019, Figs 2–4), on two axes of ``fig``.

    Parameters
    ----------
    ds : xarray.Dataset
        The result of ``landau.sweep("simulate", {"omega": ...}, model="forced-oscillator")``.
    fig : matplotlib Figure

    Returns
    -------
    tuple of Axes
    """
    if tuple(ds.status.dims) != ("omega",):
        raise InputError("the bifurcation diagram needs a sweep over omega alone")
    a, b = fig.subplots(2, 1, sharex=True)
    om = np.asarray(ds.omega.values)
    xs = np.asarray(ds.x_section.values)
    a.plot(np.repeat(om, xs.shape[1]), xs.ravel() * 1e3, "k.", ms=1.5)
    import json

    xI = json.loads(ds.attrs.get("fixed_parameters", "{}")).get("xI", PAPER.xI)
    a.axhline(float(xI) * 1e3, color="r", lw=0.6)  # the obstacle
    a.set_ylabel("x [mm] at t = 2πi/ω")
    b.plot(om, np.asarray(ds.impacts_per_period.values), "k.-", ms=3, lw=0.6)
    b.set_ylabel("impacts per period")
    b.set_xlabel("ω [rad/s]")
    a.set_title("forced oscillator: Poincaré section and impacts per period", fontsize=9)
    return a, b


def warm_up(params=PAPER) -> None:
    """Compile the event-driven loop and the friction law's callbacks in this process, before
    any worker starts: both are cached on disk by numba (``cache=True``), so the workers load
    them instead of compiling the same code each (forked workers inherit them loaded).

    Parameters
    ----------
    params : Params
        Whose friction law the sweep uses.
    """
    from landau.verify.skurativskyi import rk
    from landau.verify.skurativskyi.model import compiled_field

    compiled_field(params)
    rk.mixed_loop()


def run_sweep(omegas, direction: str = "up", out: str | os.PathLike | None = None, spec: SweepSpec = SweepSpec(),
              workers: int | None = None, scheduler=None, chunk_size: int | None = None,
              progress: bool = True) -> SweepResult:
    """Bifurcation diagram along ``omegas`` for increasing (``"up"``) or decreasing (``"down"``) ω.

    Parameters
    ----------
    omegas : array_like
        Forcing frequencies [rad/s].
    direction : {"up", "down"}
        The continuation direction.
    out : path, optional
        A netCDF file, or a folder (then ``<out>/sweep.nc``): written as the sweep goes and resumed.
    spec : SweepSpec
        Transients, recorded periods, tolerance, warm-up overlap, parameter overrides.
    workers : int, optional
        Local processes (default: os.cpu_count(); 1 runs in this process).
    scheduler : str or distributed.Client, optional
        A dask.distributed address or Client (overrides ``workers``); ``out`` must then be on a file
        system the client can write (the workers return their results to it).
    chunk_size : int, optional
        ω values per chunk (default :data:`CHUNK_SIZE`).
    progress : bool
        A progress bar.

    Returns
    -------
    SweepResult
        ``params`` the ω values and ``values`` the :class:`Attractor` at each, in sweep order (decreasing
        ω for ``"down"``); ``direction``; ``out`` the netCDF file (None without ``out``).
    """
    from landau.analyses.sweep_engine import execute

    if direction not in ("up", "down"):
        raise InputError(f"direction must be 'up' or 'down' (got {direction!r})")
    om = np.asarray(omegas, float)
    if om.ndim != 1 or len(om) == 0 or not np.all(np.isfinite(om)) or np.any(om <= 0):
        raise InputError("omegas must be a non-empty 1-D list of positive numbers")
    options = {k: v for k, v in asdict(spec).items() if k != "params"}
    options.update(direction=direction, chunk_size=int(chunk_size or CHUNK_SIZE))
    task = make_task("simulate", "forced-oscillator", None, tuple(sorted(dict(spec.params).items())),
                     tuple(sorted(options.items())))
    grid = make_grid({"omega": np.sort(om)}, task.units())
    path = None
    if out is not None:
        path = Path(out)
        if path.suffix.lower() != ".nc":
            path.mkdir(parents=True, exist_ok=True)
            path = path / "sweep.nc"
    executor, client = None, None
    if scheduler is not None:
        from distributed import Client

        client = scheduler if isinstance(scheduler, Client) else Client(scheduler)
        executor = client.get_executor()
    try:
        ds, _ = execute(task, grid, executor=executor, workers=workers, out=path, attrs=task.attrs(),
                        progress=progress)
    finally:
        if client is not None and client is not scheduler:
            client.close()
    failed = [str(m) for m in ds.message.values[ds.status.values != "ok"]]
    if failed:
        from landau.errors import IntegratorError

        raise IntegratorError(f"{len(failed)} point(s) of the ω-sweep failed: {failed[0]}")
    atts = attractors_of(ds)
    if direction == "down":
        atts = atts[::-1]
    return SweepResult(np.array([a.omega for a in atts]), tuple(atts), direction=direction,
                       out=str(path) if path else None)


__all__ = ["CHUNK_SIZE", "MECHANICAL", "SweepResult", "SweepSpec", "attractors_of", "make_task", "plot_diagram",
           "run_sweep", "simulate_chunk", "warm_up"]
