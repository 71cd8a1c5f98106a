"""Run an analysis over a parameter grid on local processes or a dask cluster, written to netCDF.

``landau sweep TASK MODEL [LAW] --grid NAME=LO:HI:N[:log] | --grid NAME=v1,v2,... [--grid ...]
[--param NAME=VALUE ...] [--workers N | --dask ADDRESS | --dask local:N] --out FILE.nc [--shard I/N]
[--max-memory SIZE] [--json]``

Tasks: ``hopf`` (any model of ``landau hopf``; the spring–block's a whole chunk at a time),
``check`` (spring-block: the direct-simulation verdict of ``landau.check`` and its numbers), ``simulate``
(forced-oscillator: the attractor by continuation in omega), ``regime`` (spring-block: steady
sliding, small cycle, large stick-slip or bistable, by simulation started on both sides), ``scene``
(MODEL is a scene of ``landau scene list``: its value as a function of its parameters).

The result is an xarray Dataset in FILE.nc (dimensions: the swept parameters; variables: the
task's quantities as in ``--json``, ``status`` and ``message`` per point).  It is written as the
sweep goes; running the same command again reuses the finished points (``computed``/``reused``
in the summary), also after Ctrl-C or SIGTERM (both write what is done and exit 130), and tries the
failed ones again; a point that fails its chunk fails alone.  A finished file is checked before its
points are reused (statuses, variables, finiteness, version, the checksum of its results): an
edited file is computed again, with a note on stderr saying why.  Exit code 0, 1 when every point
computed in the run failed (each point's ``status`` and ``message`` say why), 2 for bad input or a
file that cannot be written (``cannot write FILE: no space left on device``).

``--shard I/N`` (a SLURM job array: ``--shard $SLURM_ARRAY_TASK_ID/8``) computes only the I-th of
N disjoint parts of the grid (every N-th chunk: the points of the unsharded run, bit for bit) into
FILE.shard-I-of-N.nc; ``landau sweep-merge FILE.nc FILE.shard-*.nc`` joins them.  A grid whose
estimated memory exceeds ``--max-memory`` (default: half of this machine's memory) is refused
before any work.

Examples::

    landau sweep hopf spring-block dieterich --grid V=1e-6:1e-3:60:log --grid a=0.01:0.04:30 --out kc.nc
    landau sweep check spring-block dieterich --grid V=1e-5,1e-4 --eps2 1e-3 --out check.nc
    landau sweep simulate forced-oscillator --grid omega=19.9:23.2:67 --direction down --out om.nc
    landau sweep regime spring-block dieterich --grid V=1e-6:1e-3:40:log --grid k=1e4:1e6:40:log --out map.nc
    landau sweep scene skurativskyi2019/static-equilibrium --grid kI=1e8:1e9:10:log --out x0.nc
    landau sweep hopf spring-block dieterich --grid V=1e-7:1e-2:2000:log --grid a=0.01:0.04:400 --shard 3/8 --out kc.nc
"""

from __future__ import annotations

import math
import sys
from typing import Any

from landau.cli.common import add_friction_arguments, add_law_arguments, parse_params
from landau.cli.model_args import add_model_options
from landau.errors import InputError

#: --param names refused for a rate-and-state model (the swept or computed ones are fine)
_RESERVED = {"v": "v is the slip rate, the variable of the friction law, not a parameter"}


def configure(p) -> None:
    p.add_argument("task", help="hopf, check, simulate, regime, scene or cycles")
    p.add_argument("model", help="spring-block, forced-oscillator, any model of landau hopf, or a scene's name")
    add_law_arguments(p)
    p.add_argument("--grid", action="append", default=[], metavar="NAME=LO:HI:N[:log] | NAME=v1,v2,...",
                   help="a swept parameter (repeatable; the grid is their product)")
    p.add_argument("--out", default=None, metavar="FILE.nc", help="the netCDF file (resumed if it holds this sweep)")
    ex = p.add_mutually_exclusive_group()
    ex.add_argument("--workers", type=int, default=None, help="local processes (default: the number of cores)")
    ex.add_argument("--dask", default=None, metavar="ADDRESS|local:N",
                    help="a running dask scheduler (tcp://host:8786) or local:N for a LocalCluster of N workers")
    p.add_argument("--chunk-size", type=int, default=None, help="points per task sent to a worker")
    p.add_argument("--shard", default=None, metavar="I/N",
                   help="compute only the I-th of N disjoint parts of the grid, into FILE.shard-I-of-N.nc "
                        "(join them with landau sweep-merge)")
    p.add_argument("--max-memory", dest="max_memory", default=None, metavar="SIZE",
                   help="refuse a grid whose estimated memory exceeds SIZE (8G, 500M; default: half of this "
                        "machine's memory)")
    p.add_argument("--eps2", type=float, default=None, help="check: distance from the Hopf point (default 1e-3)")
    p.add_argument("--k-over-kc", dest="k_over_kc", type=float, default=None, metavar="R",
                   help="regime without k on the grid: each point at k = R k_c of its own parameters (default 1.003)")
    p.add_argument("--direction", choices=("up", "down"), default=None, help="simulate: continuation direction")
    for name, kind, what in (("n-first", int, "periods of transient at a chunk's first point"),
                             ("n-step", int, "periods of transient after each step"),
                             ("n-keep", int, "recorded periods"), ("overlap", int, "warm-up points per chunk"),
                             ("rtol", float, "integration tolerance")):
        p.add_argument(f"--{name}", type=kind, default=None, help=f"simulate: {what}")
    p.add_argument("--lyapunov", action="store_true", help="simulate: also the largest Lyapunov exponent")
    p.add_argument("--steps", type=int, default=None, help="cycles: continuation steps per point (default 60)")
    p.add_argument("--ds", type=float, default=None, help="cycles: the first arclength step (default the engine's)")
    add_friction_arguments(p)
    add_model_options(p)


def _options(args, model) -> dict[str, Any]:
    from landau.cli.model_args import model_options

    opts: dict[str, Any] = {}
    for key in ("chunk_size", "eps2", "k_over_kc", "direction", "n_first", "n_step", "n_keep", "overlap", "rtol",
                "steps", "ds"):
        val = getattr(args, key, None)
        if val is not None:
            if isinstance(val, float) and not math.isfinite(val):
                raise InputError(f"--{key.replace('_', '-')}: must be finite")
            opts[key] = val
    if args.lyapunov:
        opts["lyapunov"] = True
    if model is not None:
        opts.update(model_options(model, args, f"landau sweep {args.task}"))
    return opts


def _model(args):
    """The registered model of the sweep (None for a scene, whose MODEL is a scene's name)."""
    if args.task == "scene":
        return None
    from landau.models import get

    return get(args.model)


def _law(args, model):
    from landau.analyses.sweep_tasks import LawSpec
    from landau.models import LawKind

    if model is None or model.law_kind is not LawKind.RATE_AND_STATE:
        if args.law is not None or args.mu is not None or args.state:
            raise InputError(f"landau sweep {args.task} {args.model}: this model takes no rate-and-state law")
        return None
    if args.mu is not None or args.state:
        if args.mu is None or not args.state:
            raise InputError("an inline law needs both --mu and at least one --state NAME=RATE")
        states = []
        for item in args.state:
            if "=" not in item:
                raise InputError(f"--state {item!r}: expected NAME=RATE")
            name, rate = item.split("=", 1)
            states.append((name.strip(), rate))
        return LawSpec(args.law or "inline", args.mu, tuple(states))
    if args.law is None:
        from landau.laws import BUILTIN

        raise InputError(f"landau sweep {args.task} {args.model}: name a law ({', '.join(BUILTIN)}) or give --mu "
                         "and --state")
    return LawSpec(args.law)


#: seconds a local dask worker is given to end by itself (its exit handlers included) when the sweep closes
WORKER_EXIT_S = 60.0


def _close_local(client, cluster) -> None:
    """Close a ``--dask local:N`` cluster: the client, then each worker with :data:`WORKER_EXIT_S`
    to end, then the scheduler.  ``cluster.close()`` alone gives a worker 4 s (its nanny's close
    timeout, fixed at 5 s) and then kills it with a timestamped warning "Worker process still alive
    after 4.0 seconds, killing" per worker; a worker's exit handlers (numba's cache signed, on a
    loaded machine) can take longer, and a worker killed there leaves its cache unsigned, compiled
    afresh by the next run."""
    import asyncio

    client.close()
    try:
        workers = list(cluster.workers.values())
        cluster.sync(lambda: asyncio.gather(*[w.close(timeout=WORKER_EXIT_S) for w in workers]))
    except Exception:  # noqa: BLE001 - a worker that cannot be closed gracefully: cluster.close() kills it
        pass
    cluster.close()


def _executor(args):
    """(executor or None, closer) for --dask; (None, None) for local processes."""
    if args.dask is None:
        if args.workers is not None and args.workers < 1:
            raise InputError(f"--workers must be >= 1, got {args.workers}")
        return None, None
    try:
        from distributed import Client, LocalCluster
    except ImportError:
        raise InputError("--dask needs dask.distributed: pip install 'landau-friction[dask]'") from None
    if args.dask.startswith("local:"):
        try:
            n = int(args.dask.split(":", 1)[1])
        except ValueError:
            raise InputError(f"--dask {args.dask!r}: expected local:N with N an integer") from None
        if not 1 <= n <= 1024:
            raise InputError(f"--dask local:N needs 1 <= N <= 1024, got {n}")
        cluster = LocalCluster(n_workers=n, threads_per_worker=1, dashboard_address=None)
        client = Client(cluster)
        return client.get_executor(), lambda: _close_local(client, cluster)
    try:
        client = Client(args.dask, timeout="20s")
    except (OSError, TimeoutError, ValueError) as exc:
        raise InputError(f"--dask {args.dask!r}: cannot reach the scheduler ({type(exc).__name__})") from None
    return client.get_executor(), client.close


def run(args) -> dict:
    from landau.analyses.sweep import sweep_file
    from landau.analyses.sweep_budget import check_memory, parse_memory
    from landau.analyses.sweep_engine import make_grid, parse_shard
    from landau.analyses.sweep_files import shard_path
    from landau.support.progress import set_quiet

    if not args.grid:
        raise InputError("--grid NAME=LO:HI:N[:log] or NAME=v1,v2,... is required (repeatable)")
    if args.out is None:
        raise InputError("--out FILE.nc is required (the sweep is written and resumed there)")
    set_quiet(getattr(args, "json", False))
    model = _model(args)
    law = _law(args, model)
    fixed = parse_params(args.param, _RESERVED if law is not None else {})
    options = _options(args, model)
    # checked before a cluster starts: a grid over the memory budget is refused without starting one
    shard, max_memory = parse_shard(args.shard), parse_memory(args.max_memory)
    grid = make_grid(args.grid)
    check_memory(grid, max_memory, stored=True)
    out = args.out if shard is None else shard_path(args.out, shard)
    executor, close = _executor(args)
    try:
        import warnings

        with warnings.catch_warnings():   # a file not reused: said below, once
            warnings.simplefilter("ignore", UserWarning)
            facts, counts = sweep_file(args.task, args.grid, args.out, model=args.model, law=law, params=fixed,
                                       executor=executor, workers=args.workers, progress=True, options=options,
                                       shard=shard, max_memory=max_memory)
    finally:
        if close is not None:
            close()
    if counts.get("distrusted") and not getattr(args, "json", False):
        print(f"landau: note: {counts['distrusted']}", file=sys.stderr)
    if counts.get("kept_failed") and not getattr(args, "json", False):
        print(f"landau: note: {counts['kept_failed']} failed point(s) of {out} kept, not computed again: their "
              "failures do not depend on the run (delete the file to compute them again)", file=sys.stderr)
    # every point computed in this run failed: the run as a whole did not work, and says why on stderr
    all_failed = bool(counts["computed"]) and counts["failed"] == counts["computed"]
    failure = {}
    if all_failed:
        first = facts.get("first_failed")
        failure = {"failure": f"every computed point failed ({counts['failed']}); the first: {first}"}
    return {"task": args.task, "model": args.model, "law": "" if law is None else law.name, "out": str(out),
            "shard": "" if shard is None else f"{shard[0]}/{shard[1]}",
            "dims": {a.name: len(a.values) for a in grid.axes},
            "points": grid.size, **counts, "status": dict(sorted(facts["status"].items())),
            "variables": list(facts["schema"]),
            "fixed_parameters": fixed,
            **failure, "exit_code": 1 if all_failed else 0}


def render(doc: dict) -> str:
    dims = " x ".join(f"{k} ({n})" for k, n in doc["dims"].items())
    st = ", ".join(f"{k}: {n}" for k, n in doc["status"].items())
    return (f"sweep {doc['task']} {doc['model']}{' ' + doc['law'] if doc['law'] else ''} over {dims}: "
            f"{doc['points']} points ({doc['computed']} computed, {doc['reused']} reused"
            f"{', shard ' + doc['shard'] if doc.get('shard') else ''}) written to {doc['out']}\n"
            f"  status: {st}\n  variables: {', '.join(doc['variables'])}")


def plot_file(path, out, formats=("png", "pdf", "svg")) -> dict:
    """``landau plot --sweep FILE.nc --out FIG``: a ``regime`` map with the amplitude equation's
    boundaries on top (k_c(V), the fold of cycles, V*: :func:`landau.analyses.regime_overlay.regime_overlay`,
    drawn by :func:`landau.verify.springblock.regime_map.plot_regime_map`) or a ``simulate`` bifurcation
    diagram of the forced oscillator (:func:`landau.verify.skurativskyi.sweep.plot_diagram`); the
    JSON document of the command."""
    from pathlib import Path

    from landau.analyses.sweep_engine import _engine, xarray
    from landau.support.io import atomic_savefig

    if out is None:
        raise InputError(f"--out FILE is required ({', '.join('.' + f for f in formats)})")
    if Path(out).suffix.lstrip(".").lower() not in formats:
        raise InputError(f"--out {out!r}: unknown figure type (use .{', .'.join(formats)})")
    if not Path(path).is_file():
        raise InputError(f"--sweep {path!r}: no such file")
    xr = xarray()
    try:
        with xr.open_dataset(path, engine=_engine()) as ds:
            ds = ds.load()
    except (OSError, ValueError):
        raise InputError(f"--sweep {path!r} is not a netCDF sweep file") from None
    from matplotlib.figure import Figure

    task = str(ds.attrs.get("task", ""))
    if "status" not in ds or not task:
        raise InputError(f"--sweep {path!r} is not a landau sweep file (no task or status)")
    plotter = None
    if task != "scene" and ds.attrs.get("model"):
        from landau.models import get

        plotter = get(str(ds.attrs["model"])).plots.get(task)
    from landau.report.sweep_figure import plot_any_sweep

    fig = Figure(figsize=(7.2, 5.6))
    doc: dict[str, Any] = (plotter or plot_any_sweep)(ds, fig)
    fig.tight_layout()
    doc.update({"law": ds.attrs.get("law", ""), "model": ds.attrs.get("model", ""), "points": int(ds.status.size),
                "out": str(atomic_savefig(fig, out, dpi=120))})
    return doc
