"""The store of a sweep written to a file (landau.analyses.sweep_store): O(chunk) writes, memory bounded
by the chunking, a finished file checked before it is reused, kill -9 and resume."""

from __future__ import annotations

import json
import os
import signal
import subprocess
import sys
import textwrap
import time
from pathlib import Path

import numpy as np
import pytest

pytest.importorskip("xarray")
netCDF4 = pytest.importorskip("netCDF4")

import landau  # noqa: E402
from landau.analyses.sweep_budget import STORED_OVERHEAD, check_memory, memory_estimate  # noqa: E402
from landau.analyses.sweep_engine import ChunkResult, make_grid  # noqa: E402
from landau.analyses.sweep_store import Journal, blocks, runs, seal  # noqa: E402
from landau.cli import main  # noqa: E402
from landau.errors import InputError  # noqa: E402

GRID = {"V": [1e-5, 3e-5, 1e-4, 3e-4], "a": [0.01, 0.02, 0.03]}


# ---------------------------------------------------------------------------------------------
# flat ranges as hyperrectangles
# ---------------------------------------------------------------------------------------------
@pytest.mark.parametrize("shape", [(7,), (3, 5), (4, 3, 5), (2, 1, 3, 4)])
def test_blocks_cover_a_flat_range_in_c_order(shape):
    """Every flat range start:stop, cut into hyperrectangles, is the same elements as np.arange's
    C-order slice (an independent computation), in order, in at most 2 ndim - 1 pieces."""
    size = int(np.prod(shape))
    grid = np.arange(size).reshape(shape)
    for start in range(size):
        for stop in range(start + 1, size + 1):
            pieces = blocks(start, stop, shape)
            got = np.concatenate([grid[sl].reshape(-1) for sl in pieces])
            assert np.array_equal(got, np.arange(start, stop)), (start, stop, pieces)
            assert len(pieces) <= 2 * len(shape) - 1


def test_runs_of_an_unordered_index():
    index = np.array([7, 3, 4, 5, 9, 8, 0])
    got = [(a, b, list(pos)) for a, b, pos in runs(index)]
    assert got == [(0, 1, [6]), (3, 6, [1, 2, 3]), (7, 10, [0, 5, 4])]


# ---------------------------------------------------------------------------------------------
# 1. a write costs O(chunk)
# ---------------------------------------------------------------------------------------------
def _result(start: int, n: int) -> ChunkResult:
    idx = np.arange(start, start + n)
    return ChunkResult(idx, ["ok"] * n, [""] * n, {"x": idx * 0.5, "y": np.sqrt(idx)}, {"tag": ["a"] * n})


def test_a_journal_write_is_one_new_file_of_the_chunks_size(tmp_path):
    """Writing chunk k creates one file whose size does not depend on k and touches no earlier file:
    the cost of a write is O(chunk), whatever was written before (the old store rewrote the whole
    file, O(dataset), at every write)."""
    journal = Journal(tmp_path / "s.nc", {"task": "t"})
    journal.open()
    sizes, before = [], {}
    for k in range(60):
        part = journal.write(_result(1000 * k, 1000))
        files = {p.name: (p.stat().st_size, p.stat().st_mtime_ns) for p in journal.parts()}
        assert len(files) == k + 1 and part.name in files
        assert all(files[name] == stat for name, stat in before.items())   # no earlier part rewritten
        sizes.append(files[part.name][0])
        before = files
    assert max(sizes) - min(sizes) <= 16   # the same bytes a chunk (digits of the indices aside)
    index, _, values, strings = Journal.read(journal.parts()[37])
    assert np.array_equal(index, np.arange(37000, 38000)) and np.array_equal(values["x"], index * 0.5)
    assert strings["status"] == ["ok"] * 1000 and strings["tag"] == ["a"] * 1000


# ---------------------------------------------------------------------------------------------
# 2. memory bounded by the chunking
# ---------------------------------------------------------------------------------------------
def test_a_1e8_grid_written_to_a_file_fits_a_gigabyte_and_in_memory_is_refused():
    """10⁸ points written to a file hold two flags a point and the blocks (under 0.5 GiB): accepted
    under a 1 GiB budget; the same grid returned in memory (528 bytes a point, 49 GiB) is refused
    up front, naming the estimate."""
    grid = make_grid({"V": "1e-7:1e-2:10000:log", "a": "0.005:0.04:10000"})
    assert grid.size == 10**8
    assert memory_estimate(grid, stored=True) == 2 * 10**8 + STORED_OVERHEAD < 1 << 29
    check_memory(grid, "1G", stored=True)
    with pytest.raises(InputError, match="100000000 points, about 49.2 GiB"):
        check_memory(grid, "1G")


class Doubles:
    """A trivial vectorised task (x -> 2x, 3x) in chunks of 4096: the engine's and the store's cost alone."""

    name = "doubles"
    continuation = False
    lead = False
    chunk_size = 4096

    def units(self):
        return {}

    def prepare(self):
        pass

    def chunks(self, grid):
        from landau.analyses.sweep_engine import chunks

        return chunks(grid, self.chunk_size)

    def run(self, chunk):
        n = len(chunk.index)
        x = chunk.points["x"] + 10.0 * chunk.points["y"]
        return ChunkResult(chunk.index, ["ok"] * n, [""] * n, {"twice": 2 * x, "thrice": 3 * x})


def test_a_sweep_to_a_file_holds_no_table_of_the_grid(tmp_path, monkeypatch):
    """The same code path as the 10⁷-point run, on 10⁵ points: the Python-side peak (tracemalloc,
    numpy's arrays included) of a sweep to a file is its flags and blocks, under 1.2 MB (the blocks
    shrunk to 4096 points), where the same sweep in memory peaks above 3 MB (its table: two numbers,
    a status and a message a point, 32 bytes); and the file holds every point."""
    import tracemalloc

    from landau.analyses import sweep_store
    from landau.analyses.sweep_engine import run_table

    monkeypatch.setattr(sweep_store, "BLOCK", 4096)
    grid = make_grid({"x": np.arange(200.0), "y": np.arange(500.0)})
    peaks = {}
    for where, out in (("file", tmp_path / "d.nc"), ("memory", None)):
        tracemalloc.start()
        run_table(Doubles(), grid, workers=1, out=out, progress=False, attrs={"task": "doubles"})
        peaks[where] = tracemalloc.get_traced_memory()[1]
        tracemalloc.stop()
    assert peaks["file"] < 1.2e6 and peaks["memory"] > 3e6, peaks
    with netCDF4.Dataset(tmp_path / "d.nc") as nc:
        twice = np.asarray(nc.variables["twice"][:])
    x = np.arange(200.0)[:, None] + 10.0 * np.arange(500.0)[None, :]
    assert np.array_equal(twice, 2 * x)


def test_the_cli_accepts_a_grid_in_a_file_it_would_refuse_in_memory(tmp_path, capsys):
    """The budget the CLI checks before starting is the file's (the CLI always writes one): 9·10⁶
    points under --max-memory 100M are refused at about 0.27 GiB (2 bytes a point + 256 MiB), not at
    4.4 GiB."""
    argv = ["sweep", "hopf", "spring-block", "dieterich", "--grid", "V=1e-6:1e-3:3000:log",
            "--grid", "a=0.01:0.04:3000", "--out", str(tmp_path / "big.nc"), "--max-memory", "100M"]
    assert main(argv) == 2
    err = capsys.readouterr().err
    assert "9000000 points, about 0.267 GiB" in err and "Traceback" not in err
    assert not list(tmp_path.iterdir())


# ---------------------------------------------------------------------------------------------
# 3. a finished file is not trusted
# ---------------------------------------------------------------------------------------------
@pytest.fixture()
def stored(tmp_path):
    out = tmp_path / "kc.nc"
    ds = landau.sweep("hopf", GRID, law="dieterich", workers=1, out=out, progress=False)
    return out, ds


def _rerun(out):
    with pytest.warns(UserWarning) as said:
        ds, counts = landau.sweep("hopf", GRID, law="dieterich", workers=1, out=out, progress=False,
                                  return_counts=True)
    return ds, counts, " ".join(str(w.message) for w in said)


def _edit(out, fn) -> None:
    with netCDF4.Dataset(out, "a") as nc:
        fn(nc)


def test_an_untouched_file_is_reused_silently(stored, recwarn):
    out, _ = stored
    _, counts = landau.sweep("hopf", GRID, law="dieterich", workers=1, out=out, progress=False,
                             return_counts=True)
    assert counts == {"computed": 0, "reused": 12, "failed": 0, "kept_failed": 0}
    assert not [w for w in recwarn if "not reused" in str(w.message)]


@pytest.mark.parametrize("edit, said", [
    (lambda nc: nc.variables["k_c"].__setitem__((1, 1), 1234.5), "checksum of its results differs"),
    (lambda nc: nc.variables["status"].__setitem__((0, 2), "no-hopf"), "checksum of its results differs"),
    (lambda nc: nc.variables["status"].__setitem__((0, 2), "fine"), "a status 'fine' that no sweep gives"),
    (lambda nc: nc.variables["Lambda"].__setitem__((2, 0), np.nan), "Lambda is not finite at a point whose status"),
    (lambda nc: nc.setncattr("landau_version", "0.0.1"), "written by landau 0.0.1"),
    (lambda nc: nc.delncattr("results_sha256"), "no checksum"),
])
def test_an_edited_file_is_recomputed_and_said_so(stored, edit, said):
    """Each edit makes the re-run compute every point again (before: 0 computed, 12 reused, the edited
    value returned) and say why; the result is the original sweep's."""
    out, first = stored
    _edit(out, edit)
    ds, counts, warned = _rerun(out)
    assert counts["computed"] == 12 and counts["reused"] == 0, counts
    assert said in warned and "computed again" in warned
    assert said in counts["distrusted"]
    for name in ("k_c", "Lambda", "omega_c"):
        assert np.array_equal(ds[name].values, first[name].values, equal_nan=True)
    assert (ds.status.values == first.status.values).all()


def test_a_deleted_variable_is_recomputed_and_said_so(stored, tmp_path):
    """A variable deleted (netCDF cannot delete one in place: the file rewritten without it, as a user
    would with xarray) makes the re-run recompute (before: reused, the variable absent)."""
    import xarray as xr

    out, first = stored
    with xr.open_dataset(out) as ds:
        ds = ds.load()
    ds.drop_vars("omega_c").to_netcdf(out)
    again, counts, warned = _rerun(out)
    assert counts["computed"] == 12 and "its variable omega_c is missing" in warned
    assert np.array_equal(again.omega_c.values, first.omega_c.values)


def test_the_cli_says_a_file_is_not_reused(stored, capsys):
    out, _ = stored
    _edit(out, lambda nc: nc.variables["k_c"].__setitem__((0, 0), 1.0))
    argv = ["sweep", "hopf", "spring-block", "dieterich", "--grid", "V=1e-5,3e-5,1e-4,3e-4",
            "--grid", "a=0.01,0.02,0.03", "--workers", "1", "--out", str(out)]
    assert main(argv) == 0
    err = capsys.readouterr().err
    assert f"landau: note: {out} is not reused: the checksum of its results differs" in err
    assert main([*argv, "--json"]) == 0
    doc = json.loads(capsys.readouterr().out)
    assert doc["computed"] == 0 and doc["reused"] == 12 and "distrusted" not in doc


def test_a_sealed_file_is_its_own_checksum(stored):
    """seal() of the untouched file gives the checksum it was written with (the checksum is a
    function of the stored results, not of when they were written)."""
    out, _ = stored
    with netCDF4.Dataset(out, "a") as nc:
        before = nc.getncattr("results_sha256")
        seal(nc, nc.variables["status"].shape)
        assert nc.getncattr("results_sha256") == before


# ---------------------------------------------------------------------------------------------
# 4. kill -9 at random moments, then resume
# ---------------------------------------------------------------------------------------------
KILLED = textwrap.dedent("""
    import sys
    from landau.analyses.sweep_engine import execute, make_grid
    from landau.analyses.sweep_tasks import make_task
    from landau.analyses.sweep import law_spec

    n = int(sys.argv[2])
    task = make_task("hopf", "spring-block", law_spec("dieterich"), {}, {"chunk_size": int(sys.argv[3])})
    grid = make_grid({"V": "1e-6:1e-3:%d:log" % (n // 10), "a": "0.005:0.04:10"}, task.units())
    task = task.for_grid(grid)
    print("started", flush=True)
    _, counts = execute(task, grid, workers=1, out=sys.argv[1], attrs=task.attrs(), progress=False,
                        write_every=0.0, load=False)
    print("finished", counts.computed, counts.reused, flush=True)
""")


def _kill_and_resume(tmp_path: Path, points: int, chunk: int, kills: int, seed: int, parts: int,
                     window: float = 0.05):
    """Run the sweep, SIGKILL it ``kills`` times at random moments (seeded) of its computation, then run
    it to the end; return the file, the points the killed runs stored (their journal, or the file of
    one that had finished), the finished run's counts."""
    rng = np.random.default_rng(seed)
    out = tmp_path / "k.nc"
    env = {**os.environ, "LANDAU_PROGRESS": "off"}
    cmd = [sys.executable, "-c", KILLED, str(out), str(points), str(chunk)]
    for _ in range(kills):
        proc = subprocess.Popen(cmd, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, env=env)
        try:
            assert proc.stdout.readline().startswith("started")
            # a random moment of the computation (not of the imports): after 1 to ``parts`` more stored
            # parts, then up to ``window`` seconds more (mid-chunk, mid-write)
            target = len(Journal(out, {}).parts()) + int(rng.integers(1, parts + 1))
            end = time.monotonic() + 120
            while len(Journal(out, {}).parts()) < target and proc.poll() is None and time.monotonic() < end:
                time.sleep(0.005)
            time.sleep(float(rng.uniform(0, window)))
            os.kill(proc.pid, signal.SIGKILL)
            proc.wait(30)
        finally:
            proc.kill()
            proc.communicate()
    stored = [Journal.read(p)[0] for p in Journal(out, {}).parts()]
    if out.exists():   # a killed run that had finished: its file
        with netCDF4.Dataset(out) as nc:
            stored.append(np.flatnonzero(np.asarray(nc.variables["status"][:], dtype=object).reshape(-1)
                                         != "pending"))
    flat = np.concatenate(stored) if stored else np.zeros(0, dtype=np.int64)
    done = subprocess.run(cmd, capture_output=True, text=True, env=env, timeout=300)
    assert done.returncode == 0, done.stderr
    _, computed, reused = done.stdout.split()[-3:]
    return out, flat, int(computed), int(reused)


def _check_resumed(out: Path, flat: np.ndarray, computed: int, reused: int, points: int, chunk: int):
    import xarray as xr

    assert len(np.unique(flat)) == len(flat), "a point stored twice by the killed runs"
    assert reused == len(flat) and computed + reused == points   # none lost, none computed twice
    with xr.open_dataset(out) as ds:
        ds = ds.load()
    assert (ds.status.values != "pending").all()
    # the uninterrupted run (the same chunks), and every 12th V at every a alone (one point a chunk:
    # a fresh single call; the values do not depend on the chunk, tests/sweep/test_sweep_engine_trust.py)
    fresh = landau.sweep("hopf", {"V": ds.V.values, "a": ds.a.values}, law="dieterich", workers=1,
                         progress=False, options={"chunk_size": chunk})
    alone = landau.sweep("hopf", {"V": ds.V.values[::12], "a": ds.a.values}, law="dieterich", workers=1,
                         progress=False, options={"chunk_size": 1})
    for ref in (fresh, alone):
        part = ds.sel(V=ref.V.values)
        assert (part.status.values == ref.status.values).all()
        for name in ("k_c", "omega_c", "Lambda", "chi", "C"):
            assert np.array_equal(part[name].values, ref[name].values, equal_nan=True), name   # bit for bit
    assert not Path(f"{out.parent}/.{out.name}.parts").exists()


def test_killed_twice_then_resumed_every_point_once(tmp_path):
    """A 600-point sweep killed with SIGKILL twice mid-run, then run again: every point equals the
    point of an uninterrupted run and computed alone, bit for bit; the killed runs' stored points are
    reused, none lost or computed twice."""
    out, flat, computed, reused = _kill_and_resume(tmp_path, 600, 10, 2, seed=34, parts=25)
    _check_resumed(out, flat, computed, reused, 600, 10)


@pytest.mark.slow
def test_killed_twenty_times_then_resumed_every_point_once(tmp_path):
    """The acceptance: a 10⁴-point sweep killed at 20 random moments (seed 2026), then resumed."""
    out, flat, computed, reused = _kill_and_resume(tmp_path, 10_000, 20, 20, seed=2026, parts=40)
    print(f"the killed runs stored {len(flat)} points, the last run computed {computed}")
    _check_resumed(out, flat, computed, reused, 10_000, 20)
