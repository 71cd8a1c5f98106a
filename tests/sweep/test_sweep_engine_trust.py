"""What a sweep promises when something goes wrong (landau.analyses.sweep_engine): a bad point fails
alone, a killed sweep leaves no worker and no temporary behind, SIGTERM writes what is done, a full
disk is called a full disk."""

from __future__ import annotations

import errno
import math
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

import landau  # noqa: E402
from landau.analyses.sweep_engine import Chunk, ChunkResult, chunks, make_grid, run_table  # noqa: E402
from landau.cli import main  # noqa: E402

ROOT = Path(__file__).resolve().parents[2]


def _kc_rice_ruina(V: float, a: float = 0.0349, b: float = 0.0489, L: float = 9e-7, M: float = 1.2,
                   sigma: float = 11.772) -> float:
    """The spring–block's critical stiffness for the Dieterich law with inertia (Rice & Ruina 1983;
    Putelat et al. 2010 eq. 33): k_c = sigma (b - a)/L · (1 + M V²/(sigma a L))."""
    return sigma * (b - a) / L * (1.0 + M * V * V / (sigma * a * L))


# ---------------------------------------------------------------------------------------------
# 1. one bad point fails alone
# ---------------------------------------------------------------------------------------------
def test_a_point_beyond_float64_fails_alone_and_the_valid_point_keeps_its_value(tmp_path, capsys):
    out = tmp_path / "s.nc"
    argv = ["sweep", "hopf", "spring-block", "dieterich", "--grid", "b=1e300,1e305,1e308,0.0489",
            "--param", "V=1e-4", "--workers", "1", "--out", str(out), "--json"]
    assert main(argv) == 0   # not every point failed: the run worked
    import xarray as xr

    with xr.open_dataset(out) as ds:
        ds = ds.load()
    assert list(ds.status.values) == ["failed", "failed", "failed", "ok"]
    # each failing point says why it failed, with its own value of b
    for b, msg in zip(("1e+300", "1e+305", "1e+308"), ds.message.values[:3], strict=True):
        assert "beyond the float64 range" in msg and f"b = {b}" in msg
    assert ds.message.values[3] == ""
    # the default b = 0.0489 gets k_c of the closed form (accurate to 1e-10 relative, Derivation.evaluate),
    kc = float(ds.kc.sel(b=0.0489))
    assert kc == pytest.approx(_kc_rice_ruina(1e-4), rel=1e-10)
    # and the same number, to the last bit, as in a sweep where it has no failing neighbour
    alone = landau.sweep("hopf", {"b": [0.0489]}, law="dieterich", params={"V": 1e-4}, workers=1, progress=False)
    assert float(alone.kc.sel(b=0.0489)) == kc
    # a re-run keeps the failed points (a value beyond float64 fails again whatever the run: it was tried
    # again and failed again, exit 1) and reuses the ok one, and says so
    capsys.readouterr()
    assert main(argv) == 0
    doc = __import__("json").loads(capsys.readouterr().out)
    assert (doc["computed"], doc["reused"], doc["failed"], doc["kept_failed"]) == (0, 4, 0, 3)
    assert main(argv[:-1]) == 0
    assert capsys.readouterr().err.strip() == (f"landau: note: 3 failed point(s) of {out} kept, not computed "
                                               "again: their failures do not depend on the run (delete the file "
                                               "to compute them again)")


def test_a_point_failed_for_a_transient_reason_is_computed_again(tmp_path, capsys):
    """A point that failed for want of memory (or time, or a lost worker) is computed by a re-run; one
    that failed deterministically is not (landau.analyses.sweep_store.to_compute)."""
    from landau.analyses.sweep_store import to_compute

    todo, kept = to_compute(["ok", "failed", "failed", "pending", "failed"],
                            ["", "MemoryError: out of memory", "InputError: a must be > 0", "",
                             "spring-block: parameter 'a' must be > 0, got -0.01"])
    assert list(todo) == [False, True, False, True, False] and list(kept) == [False, False, True, False, True]


def test_a_point_outside_the_law_fails_alone():
    ds = landau.sweep("hopf", {"a": [-0.01, 0.0, 0.0349]}, law="dieterich", params={"V": 1e-4}, workers=1,
                      progress=False)
    # a = -0.01 and a = 0 lie outside the declared domain a > 0: failed with the domain error (never
    # no-hopf, a physical verdict), as landau hopf refuses them; a = 0.0349 (the default) has its
    # closed-form k_c
    assert list(ds.status.values) == ["failed", "failed", "ok"]
    assert [str(m) for m in ds.message.values[:2]] == [
        f"spring-block: parameter 'a' (direct-effect coefficient a) must be > 0, got {a!r}" for a in (-0.01, 0.0)]
    assert float(ds.kc.values[2]) == pytest.approx(_kc_rice_ruina(1e-4), rel=1e-10)


@pytest.mark.parametrize("grid, fixed", [
    ({"b": list(np.linspace(0.036, 0.2, 23)), "a": [0.01, 0.0349]}, {"V": 3e-5}),   # screened float route
    ({"V": list(np.logspace(-7, -2, 40))}, {}),                                      # exactly cancelled route
])
def test_hopf_values_do_not_depend_on_the_chunk_they_are_computed_in(grid, fixed):
    # the engine re-runs a failing chunk point by point: a valid point's value must be the value it has in
    # a whole chunk (one evaluation route per grid, elementwise), bit for bit, over a varied grid
    whole = landau.sweep("hopf", grid, law="dieterich", params=fixed, workers=1, progress=False)
    single = landau.sweep("hopf", grid, law="dieterich", params=fixed, workers=1, progress=False,
                          options={"chunk_size": 1})
    assert (whole.status == "ok").sum() >= 40
    for name in ("kc", "omega_c", "Gamma_bar", "Omega_bar", "Lambda", "chi", "C"):
        assert np.array_equal(whole[name].values, single[name].values, equal_nan=True), name


class Roots:
    """A vectorised task (its whole chunk at once, like the hopf task): sqrt(x) and the list
    [x, 2x, ..., nx] with n = int(x); one negative x raises for the whole chunk."""

    name = "roots"
    continuation = False
    lead = False

    def __init__(self, size: int = 4, continuation: bool = False):
        self.size, self.continuation = size, continuation
        self.calls = 0

    def units(self):
        return {}

    def prepare(self):
        pass

    def chunks(self, grid):
        return chunks(grid, self.size)

    def run(self, chunk: Chunk) -> ChunkResult:
        self.calls += 1
        x = np.asarray(chunk.points["x"])
        if np.any(x < 0):
            raise ValueError(f"x = {x[x < 0][0]:g} is negative")
        n = len(x)
        width = max(1, int(x.max()))
        lists = np.full((n, width), np.nan)
        for j, v in enumerate(x):
            lists[j, :int(v)] = v * np.arange(1, int(v) + 1)
        return ChunkResult(chunk.index, ["ok"] * n, [""] * n, {"root": np.sqrt(x), "multiples": lists},
                           {"label": [f"x={v:g}" for v in x]})


def test_the_engine_splits_a_failing_chunk_of_any_task():
    xs = [4.0, -1.0, 9.0, -2.0, 2.0, 16.0]
    task = Roots(size=4)
    table, counts = run_table(task, make_grid({"x": xs}), workers=1, progress=False)
    assert list(table.status) == ["ok", "failed", "ok", "failed", "ok", "ok"]
    assert list(table.message[[1, 3]]) == ["ValueError: x = -1 is negative", "ValueError: x = -2 is negative"]
    ok = [0, 2, 4, 5]
    assert [table.values["root"][i] for i in ok] == [math.sqrt(xs[i]) for i in ok]   # sqrt is correctly rounded
    assert np.isnan(table.values["root"][[1, 3]]).all()
    assert list(table.strings["label"]) == ["x=4", "", "x=9", "", "x=2", "x=16"]
    # the lists, padded to the longest (16 multiples): x = 9 has 9 of them
    assert table.values["multiples"].shape == (6, 16)
    assert list(table.values["multiples"][2, :9]) == [9.0 * k for k in range(1, 10)]
    assert np.isnan(table.values["multiples"][2, 9:]).all()
    # chunk 1 ran whole, then in halves [4, -1], [9, -2] (both raise), then alone; chunk 2 (no negative x) once
    assert task.calls == 1 + 2 + 4 + 1
    assert (counts.computed, counts.failed) == (6, 2)


def test_a_chunk_with_one_bad_point_is_bisected_not_run_point_by_point():
    xs = [float(i) for i in range(64)]
    xs[37] = -5.0
    task = Roots(size=64)
    table, _ = run_table(task, make_grid({"x": xs}), workers=1, progress=False)
    assert [i for i, s in enumerate(table.status) if s != "ok"] == [37]
    assert table.message[37] == "ValueError: x = -5 is negative"
    good = np.arange(64) != 37
    assert np.array_equal(table.values["root"][good], np.sqrt(np.asarray(xs)[good]))
    # the whole chunk, then two halves per level down to the bad point: 1 + 2 log2(64) runs, not 1 + 64
    assert task.calls == 1 + 2 * 6


def test_a_continuation_chunk_is_not_split_and_strict_runs_keep_the_exception():
    task = Roots(size=4, continuation=True)
    table, _ = run_table(task, make_grid({"x": [4.0, -1.0, 9.0, 1.0]}), workers=1, progress=False)
    # a continuation's point depends on the points before it: run alone it would be another point
    assert list(table.status) == ["failed"] * 4 and task.calls == 1
    with pytest.raises(ValueError, match="x = -1 is negative"):
        run_table(Roots(size=4), make_grid({"x": [4.0, -1.0, 9.0, 1.0]}), workers=1, progress=False, strict=True)


# ---------------------------------------------------------------------------------------------
# child processes: a sweep of a slow task, killed or terminated from outside
# ---------------------------------------------------------------------------------------------
CHILD = textwrap.dedent("""
    import sys, time
    import numpy as np
    import xarray
    from landau.analyses.sweep_engine import ChunkResult, chunks, make_grid, run_table

    class Slow:
        name = "slow"; continuation = False; lead = False
        def units(self): return {}
        def prepare(self): pass
        def chunks(self, grid): return chunks(grid, 1)
        def run(self, chunk):
            time.sleep(0.05)
            n = len(chunk.index)
            return ChunkResult(chunk.index, ["ok"] * n, [""] * n, {"twice": 2.0 * chunk.points["x"]})

    slow_write = sys.argv[3] == "slow-write"
    if slow_write:  # each part of the journal takes 3 s to write: a signal is sure to come mid-write
        import landau.analyses.sweep_store as store
        real = store._atomic_bytes
        def slow(path, data):
            if path.suffix == ".npz":
                print("writing", path.parent, flush=True)
                time.sleep(3.0)
            return real(path, data)
        store._atomic_bytes = slow
    if sys.argv[3] == "watchdog":   # as where prctl is missing: the workers poll their parent
        import landau.support.lifetime as lifetime
        lifetime._kernel_death_signal = lambda: False
    print("started", flush=True)
    try:
        run_table(Slow(), make_grid({"x": [float(i) for i in range(int(sys.argv[2]))]}), workers=2,
                  out=sys.argv[1], progress=False, write_every=0.3)
    except KeyboardInterrupt as exc:
        print("interrupted", type(exc).__name__, flush=True)
        sys.exit(130)
    print("finished", flush=True)
""")


def _child(tmp_path: Path, points: int, mode: str = "") -> tuple[subprocess.Popen, Path]:
    out = tmp_path / "slow.nc"
    env = {**os.environ, "LANDAU_PROGRESS": "off"}
    proc = subprocess.Popen([sys.executable, "-c", CHILD, str(out), str(points), mode or "-"], cwd=tmp_path,
                            stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, env=env)
    return proc, out


def _wait_for_workers(pid: int, n: int, timeout: float = 60.0) -> list[int]:
    psutil = pytest.importorskip("psutil")
    end = time.monotonic() + timeout
    while time.monotonic() < end:
        kids = psutil.Process(pid).children()
        if len(kids) >= n:
            return [k.pid for k in kids]
        time.sleep(0.05)
    raise AssertionError(f"the sweep started fewer than {n} workers in {timeout} s")


def _gone(pids: list[int], timeout: float) -> list[int]:
    """The pids still running (not a zombie) after ``timeout`` seconds."""
    import psutil

    end = time.monotonic() + timeout
    alive = list(pids)
    while alive and time.monotonic() < end:
        still = []
        for pid in alive:
            try:
                if psutil.Process(pid).status() != psutil.STATUS_ZOMBIE:
                    still.append(pid)
            except psutil.NoSuchProcess:
                pass
        alive = still
        if alive:
            time.sleep(0.1)
    return alive


def _kill(pids: list[int]) -> None:
    for pid in pids:
        try:
            os.kill(pid, signal.SIGKILL)
        except ProcessLookupError:
            pass


@pytest.mark.parametrize("mode", ["-", "watchdog"])
def test_workers_die_with_a_killed_sweep(tmp_path, mode):
    proc, _ = _child(tmp_path, 2000, mode)
    workers: list[int] = []
    try:
        workers = _wait_for_workers(proc.pid, 2)
        time.sleep(0.5)   # the workers are running chunks
        os.kill(proc.pid, signal.SIGKILL)
        proc.wait(10)
        # PR_SET_PDEATHSIG ends them at once, the portable watchdog within POLL_S = 0.5 s: 5 s is ample
        left = _gone(workers, 5.0)
        assert not left, f"workers {left} outlived their killed parent"
    finally:
        proc.kill()
        _kill(workers)


def test_sigterm_mid_write_writes_what_is_done_and_leaves_no_temporary(tmp_path):
    import xarray as xr

    proc, out = _child(tmp_path, 2000, "slow-write")
    workers: list[int] = []
    try:
        line = ""
        end = time.monotonic() + 120
        while not line.startswith("writing") and time.monotonic() < end:
            line = proc.stdout.readline()
        assert line.startswith("writing"), "the sweep never wrote its journal"
        journal = Path(line.split()[1])
        assert journal.is_dir() and journal.name == ".slow.nc.parts"   # the journal, mid-write
        workers = _wait_for_workers(proc.pid, 2)
        os.kill(proc.pid, signal.SIGTERM)
        rest, err = proc.communicate(timeout=60)
    finally:
        proc.kill()
        _kill(workers)
    assert proc.returncode == 130 and "interrupted Terminated" in rest, (proc.returncode, rest, err)
    assert "Traceback" not in err
    assert sorted(p.name for p in tmp_path.iterdir()) == ["slow.nc"]   # no temporary, the journal in the file
    assert not _gone(workers, 5.0)
    with xr.open_dataset(out) as ds:
        ds = ds.load()
    ok = ds.status.values == "ok"
    assert ok.sum() >= 1 and (ds.status.values[~ok] == "pending").all()
    assert np.array_equal(ds.twice.values[ok], 2.0 * ds.x.values[ok])


def test_a_stale_temporary_of_a_killed_run_is_removed_and_no_other(tmp_path):
    import socket

    dead = subprocess.run([sys.executable, "-c", "import os; print(os.getpid())"], capture_output=True,
                          text=True, check=True)
    pid = int(dead.stdout)
    host = socket.gethostname()
    out = tmp_path / "s.nc"
    stale = [tmp_path / f".s.nc.{host}.{pid}.tmp", tmp_path / f".s.nc.{pid}.tmp"]   # this host's, dead
    kept = [tmp_path / f".s.nc.{host}.{os.getppid()}.tmp",                          # a live writer
            tmp_path / f".s.nc.other-host.{pid}.tmp", tmp_path / ".t.nc.1.tmp"]    # another host; another file
    for p in stale + kept:
        p.write_bytes(b"x" * 100)
    landau.sweep("hopf", {"V": [1e-4]}, law="dieterich", workers=1, out=out, progress=False)
    assert out.is_file()
    assert not any(p.exists() for p in stale)
    assert all(p.exists() for p in kept)


# ---------------------------------------------------------------------------------------------
# 3. a full disk is a full disk
# ---------------------------------------------------------------------------------------------
ARGV = ["sweep", "hopf", "spring-block", "dieterich", "--grid", "V=1e-5,1e-4", "--workers", "1"]


def _failing_write(monkeypatch, exc: BaseException, free: int | None = None):
    from landau.analyses import sweep_files, sweep_store  # where the file is created, where the free space is asked

    def create(tmp, *args, **kwargs):
        Path(tmp).write_bytes(b"partial")   # the backend had created its file
        raise exc

    monkeypatch.setattr(sweep_store, "_create", create)
    if free is not None:
        monkeypatch.setattr(sweep_files, "_free_bytes", lambda folder: free)


def _no_temporary(folder: Path) -> None:
    """Nothing but the journal of the computed points (``.s.nc.parts``, resumable) is left, no temporary."""
    assert [p.name for p in folder.iterdir()] == [".s.nc.parts"]
    assert not [p for p in (folder / ".s.nc.parts").iterdir() if p.suffix == ".tmp"]


@pytest.mark.parametrize("exc, free", [
    (OSError(errno.ENOSPC, "No space left on device"), None),
    # what netCDF4 (HDF5) raises on a full disk: EACCES at the file's creation, an HDF error during the write
    (PermissionError(errno.EACCES, "Permission denied"), 0),
    (RuntimeError("NetCDF: HDF error"), 1000),
])
def test_a_full_disk_is_reported_as_such(tmp_path, monkeypatch, capsys, exc, free):
    out = tmp_path / "s.nc"
    _failing_write(monkeypatch, exc, free)
    assert main([*ARGV, "--out", str(out)]) == 2   # a write error, as every command reports one
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and err[0].startswith(f"landau: error: cannot write {out}: no space left on device"), err
    _no_temporary(tmp_path)


@pytest.mark.parametrize("exc, said", [
    (PermissionError(errno.EACCES, "Permission denied"), "Permission denied"),   # space left: a real EACCES
    (OSError(errno.EROFS, "whatever the backend says"), os.strerror(errno.EROFS)),
])
def test_another_write_error_is_reported_by_its_own_errno(tmp_path, monkeypatch, capsys, exc, said):
    out = tmp_path / "s.nc"
    _failing_write(monkeypatch, exc, 10**12)
    assert main([*ARGV, "--out", str(out)]) == 2
    err = capsys.readouterr().err.strip()
    assert err == f"landau: error: cannot write {out}: {said}"
    _no_temporary(tmp_path)
