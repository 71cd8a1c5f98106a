"""The sweep store (landau.analyses.sweep_store): the cost of a write against the chunks already
written, and the peak memory of a 10⁷-point sweep.

* ``write-cost`` — a run of N chunks of 4096 points with the ``hopf`` task's variables (eleven
  numbers, three strings a point) written to the journal one part a chunk, as a run does: the
  wall time of each write, its median over the first, middle and last hundred writes (flat: a
  write is O(chunk)), and for comparison the former store, the whole netCDF file rewritten with
  xarray (O(dataset)), at 10, 100 and 300 chunks.
* ``big`` — ``landau sweep hopf spring-block dieterich`` over V × a = 3163 × 3163 (10 004 569
  points) on 2 local workers, under ``/usr/bin/time -v``: wall time, the peak resident memory of
  the sweep's process and of its largest worker (``resource.getrusage(RUSAGE_CHILDREN)``), the
  load average before and after.

Run: ``python benchmarks/sweep_store_bench.py write-cost big --json results.json``.
"""

from __future__ import annotations

import argparse
import json
import os
import resource
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

HOPF_FLOATS = ("p_c", "k_c", "kc", "omega_c", "dRe_lambda_dp", "dIm_lambda_dp", "Gamma_bar", "Omega_bar", "Lambda",
               "chi", "C")


def _chunk(start: int, n: int):
    from landau.analyses.sweep_engine import ChunkResult

    rng = np.random.default_rng(start)
    idx = np.arange(start, start + n)
    return ChunkResult(idx, ["ok"] * n, [""] * n, {k: rng.random(n) for k in HOPF_FLOATS},
                       {"criticality": ["supercritical"] * n})


def write_cost(chunks: int = 500, size: int = 4096) -> dict:
    from landau.analyses.sweep_store import Journal

    out: dict = {"chunks": chunks, "chunk_points": size}
    with tempfile.TemporaryDirectory() as tmp:
        journal = Journal(Path(tmp) / "w.nc", {"task": "bench"})
        journal.open()
        times = []
        for k in range(chunks):
            res = _chunk(k * size, size)
            t0 = time.perf_counter()
            journal.write(res)
            times.append(time.perf_counter() - t0)
        t = np.array(times)
        mid = chunks // 2
        out["journal_ms"] = {"first 100": 1e3 * float(np.median(t[:100])),
                             f"{mid}-{mid + 99}": 1e3 * float(np.median(t[mid:mid + 100])),
                             "last 100": 1e3 * float(np.median(t[-100:]))}
        out["journal_part_bytes"] = int(journal.parts()[-1].stat().st_size)
    out["whole_file_rewrite_ms"] = _old_store(size)
    return out


def _old_store(size: int) -> dict:
    """The former store: the whole grid written with xarray at each write (O(dataset))."""
    import xarray as xr

    res = {}
    with tempfile.TemporaryDirectory() as tmp:
        for n in (10, 100, 300):
            pts = n * size
            ds = xr.Dataset({k: (("i",), np.random.default_rng(n).random(pts)) for k in HOPF_FLOATS}
                            | {"status": (("i",), np.full(pts, "ok", dtype=object)),
                               "message": (("i",), np.full(pts, "", dtype=object))})
            t0 = time.perf_counter()
            ds.to_netcdf(Path(tmp) / f"o{n}.nc", engine="netcdf4")
            res[f"{n} chunks"] = 1e3 * (time.perf_counter() - t0)
    return res


def big(n_axis: int = 3163, workers: int = 2) -> dict:
    with tempfile.TemporaryDirectory() as tmp:
        out = Path(tmp) / "big.nc"
        cmd = ["/usr/bin/time", "-v", sys.executable, "-m", "landau", "sweep", "hopf", "spring-block", "dieterich",
               "--grid", f"V=1e-6:1e-3:{n_axis}:log", "--grid", f"a=0.005:0.04:{n_axis}", "--workers", str(workers),
               "--out", str(out), "--json"]
        load0 = os.getloadavg()
        t0 = time.perf_counter()
        proc = subprocess.run(cmd, capture_output=True, text=True, env={**os.environ, "LANDAU_PROGRESS": "off"})
        wall = time.perf_counter() - t0
        kids = resource.getrusage(resource.RUSAGE_CHILDREN)
        peak = [line for line in proc.stderr.splitlines() if "Maximum resident set size" in line]
        doc = json.loads(proc.stdout) if proc.returncode == 0 else {"error": proc.stderr[-2000:]}
        size = out.stat().st_size if out.exists() else 0
    return {"points": n_axis * n_axis, "workers": workers, "wall_s": wall, "rc": proc.returncode,
            "peak_rss_sweep_MB": int(peak[0].split(":")[1]) / 1024 if peak else None,
            "peak_rss_largest_descendant_MB": kids.ru_maxrss / 1024, "file_MB": size / 1e6,
            "status": doc.get("status"), "load_before": load0, "load_after": os.getloadavg(),
            "points_per_s": n_axis * n_axis / wall}


def main(argv: list[str] | None = None) -> None:
    ap = argparse.ArgumentParser(description=(__doc__ or "").splitlines()[0])
    ap.add_argument("what", nargs="+", choices=["write-cost", "big"])
    ap.add_argument("--n-axis", type=int, default=3163)
    ap.add_argument("--json", default=None)
    args = ap.parse_args(argv)
    commit = subprocess.run(["git", "rev-parse", "--short", "HEAD"], capture_output=True, text=True).stdout.strip()
    doc: dict = {"commit": commit, "cpus": os.cpu_count(), "load_at_start": os.getloadavg()}
    if "write-cost" in args.what:
        doc["write_cost"] = write_cost()
    if "big" in args.what:
        doc["big"] = big(args.n_axis)
    text = json.dumps(doc, indent=1)
    print(text)
    if args.json:
        Path(args.json).write_text(text + "\n")


if __name__ == "__main__":
    main()
