"""Parallel ω-sweeps (bifurcation diagrams) streamed to disk and resumable.

A diagram is a continuation: the attractor at ω_i is started from the one at ω_{i−1}
(:func:`landau.verify.skurativskyi.analysis.continuation`).  To run it on many cores the ω list is
cut into chunks that run independently; each chunk starts its continuation ``overlap``
points *before* its first ω (those warm-up points are computed, not recorded), so near a
hysteresis the chunk has already settled on the branch the serial sweep would follow.

Every computed point is appended at once as one JSON line to ``<out>/chunk_XXXX.jsonl``
(flushed and fsynced), so an interrupted sweep resumes: a chunk restarts from its last
recorded attractor (state at phase 0) and computes only what is missing.  A line that was
cut in the middle by the interruption is ignored.

The compiled loop is built (or loaded from numba's disk cache) once in the calling process
before the workers start (:func:`warm_up`), so no worker compiles it.

Executors: local processes (``concurrent.futures.ProcessPoolExecutor``, default), or a
dask.distributed cluster when ``scheduler`` (an address such as ``tcp://host:8786``, or a
``distributed.Client``) is given — then ``out`` must be a folder the workers can write to
(a shared file system); the client also writes back whatever the chunks return.  A tqdm
progress bar counts finished points.
"""

from __future__ import annotations

import json
import os
from concurrent.futures import ProcessPoolExecutor, as_completed
from dataclasses import asdict, dataclass
from pathlib import Path

import numpy as np

from landau.errors import InputError
from landau.verify.skurativskyi.analysis import Attractor, attractor
from landau.verify.skurativskyi.model import PAPER


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


def _chunk_file(out: Path, c: int) -> Path:
    return out / f"chunk_{c:04d}.jsonl"


def _read_chunk(path: Path) -> dict[int, dict]:
    done: dict[int, dict] = {}
    if not path.exists():
        return done
    with open(path) as fh:
        for line in fh:
            try:
                rec = json.loads(line)
            except json.JSONDecodeError:
                continue  # a line cut by an interruption
            done[int(rec["i"])] = rec
    return done


def _run_chunk(c: int, omegas: list[float], idx: list[int], warm: list[float], spec: SweepSpec,
               out: str | None) -> list[dict]:
    """Compute the points ``idx`` (ω = omegas) after the warm-up ω values ``warm``."""
    params = PAPER.with_(**dict(spec.params)) if spec.params else PAPER
    path = _chunk_file(Path(out), c) if out else None
    done = _read_chunk(path) if path else {}
    todo = [k for k, i in enumerate(idx) if i not in done]
    recs = [done[i] for i in idx if i in done]
    if not todo:
        return recs
    y = None
    first = True
    k0 = todo[0]
    if k0 > 0:  # resume from the last recorded point before the first missing one
        y = np.array(done[idx[k0 - 1]]["y_end"])
        first = False
        seq = []
    else:
        seq = list(warm)
    if path and path.exists() and path.stat().st_size:
        with open(path, "rb") as fr:  # a line cut by an interruption: start a fresh line
            fr.seek(-1, os.SEEK_END)
            cut = fr.read(1) != b"\n"
        if cut:
            with open(path, "a") as fa:
                fa.write("\n")
    fh = open(path, "a") if path else None
    try:
        for w in seq:
            y = attractor(w, y, spec.n_first if first else spec.n_step, 1, params, spec.rtol).y_end
            first = False
        for k in range(k0, len(idx)):
            if idx[k] in done:
                y = np.array(done[idx[k]]["y_end"])
                continue
            a = attractor(omegas[k], y, spec.n_first if first else spec.n_step, spec.n_keep, params, spec.rtol,
                          lyapunov=spec.lyapunov)
            first = False
            y = a.y_end
            rec = {"i": idx[k], **a.to_json()}
            recs.append(rec)
            if fh:
                fh.write(json.dumps(rec) + "\n")
                fh.flush()
                os.fsync(fh.fileno())
    finally:
        if fh:
            fh.close()
    return sorted(recs, key=lambda r: r["i"])


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


@dataclass(frozen=True)
class SweepResult:
    """Attractors in sweep order, the direction and where they were streamed."""

    direction: str
    attractors: tuple
    out: str | None

    @property
    def omegas(self) -> np.ndarray:
        return np.array([a.omega for a in self.attractors])

    def __repr__(self) -> str:
        return f"SweepResult({self.direction}, {len(self.attractors)} points, out={self.out!r})"


def run_sweep(omegas, direction: str = "up", out: str | os.PathLike | None = None, spec: SweepSpec = SweepSpec(),
              workers: int | None = None, scheduler=None, chunk_size: int | None = None,
              progress: bool = True) -> SweepResult:
    """Bifurcation diagram along ``omegas`` for increasing (``"up"``) or decreasing (``"down"``) ω.

    ``workers``: local processes (default: os.cpu_count(); 1 runs in this process).
    ``scheduler``: a dask.distributed address or Client (overrides ``workers``).
    ``out``: folder for the streamed JSON lines (resumable); None keeps results in memory.
    """
    if direction not in ("up", "down"):
        raise InputError(f"direction must be 'up' or 'down' (got {direction!r})")
    om = np.asarray(omegas, float)
    if om.ndim != 1 or len(om) == 0 or not np.all(np.isfinite(om)) or np.any(om <= 0):
        raise InputError("omegas must be a non-empty 1-D list of positive numbers")
    om = np.sort(om) if direction == "up" else np.sort(om)[::-1]
    n = len(om)
    workers = workers or os.cpu_count() or 1
    n_chunks = max(1, min(n, workers * 2 if scheduler is None else n // 5 or 1))
    chunk_size = chunk_size or -(-n // n_chunks)
    chunks = []
    for c, s in enumerate(range(0, n, chunk_size)):
        idx = list(range(s, min(n, s + chunk_size)))
        warm = [float(w) for w in om[max(0, s - spec.overlap):s]]
        chunks.append((c, [float(om[i]) for i in idx], idx, warm))
    outp = None
    if out is not None:
        outp = Path(out)
        outp.mkdir(parents=True, exist_ok=True)
        meta = {"direction": direction, "omegas": om.tolist(), "chunk_size": chunk_size, "spec": asdict(spec)}
        mpath = outp / "sweep.json"
        if mpath.exists():
            old = json.loads(mpath.read_text())
            if old.get("omegas") != meta["omegas"] or old.get("chunk_size") != chunk_size \
                    or old.get("direction") != direction:
                raise InputError(f"{outp} holds a different sweep (ω list, chunking or direction); "
                                 "use another folder")
        else:
            from landau.support.io import atomic_write_json
            atomic_write_json(mpath, meta)
    from tqdm import tqdm

    if scheduler is not None or (workers > 1 and len(chunks) > 1):
        warm_up(PAPER.with_(**dict(spec.params)) if spec.params else PAPER)
    bar = tqdm(total=n, disable=not progress, desc=f"sweep {direction}", unit="ω")
    recs: dict[int, dict] = {}
    out_s = str(outp) if outp else None
    if scheduler is not None:
        from distributed import Client
        from distributed import as_completed as d_as_completed
        client = scheduler if isinstance(scheduler, Client) else Client(scheduler)
        futs = [client.submit(_run_chunk, *ch, spec, out_s, pure=False) for ch in chunks]
        for f in d_as_completed(futs):
            for r in f.result():
                recs[r["i"]] = r
            bar.update(len(f.result()))
        if not isinstance(scheduler, Client):
            client.close()
    elif workers == 1 or len(chunks) == 1:
        for ch in chunks:
            rs = _run_chunk(*ch, spec, out_s)
            for r in rs:
                recs[r["i"]] = r
            bar.update(len(rs))
    else:
        with ProcessPoolExecutor(max_workers=workers) as ex:
            futs = [ex.submit(_run_chunk, *ch, spec, out_s) for ch in chunks]
            for f in as_completed(futs):
                rs = f.result()
                for r in rs:
                    recs[r["i"]] = r
                bar.update(len(rs))
    bar.close()
    atts = tuple(Attractor.from_json(recs[i]) for i in range(n))
    return SweepResult(direction, atts, out_s)
