"""A sweep on MPI: ``mpirun -n 2 python -m mpi4py.futures`` with ``executor=MPIPoolExecutor()`` gives
the numbers of the sweep in one process, bit for bit (the chunks do not depend on the executor).

CI installs Open MPI (``.ci/install-mpi``) and the ``mpi`` extra, and sets ``LANDAU_REQUIRE_MPI=1``:
there a missing MPI fails the test instead of skipping it."""

from __future__ import annotations

import os
import shutil
import subprocess
import sys
import textwrap

import numpy as np
import pytest

pytest.importorskip("xarray")
pytest.importorskip("netCDF4")

GRID = {"V": [1e-5, 3e-5, 1e-4, 3e-4, 1e-3], "a": [0.01, 0.02, 0.03]}

SCRIPT = textwrap.dedent("""
    import sys
    from mpi4py.futures import MPIPoolExecutor
    import landau

    if __name__ == "__main__":   # the workers import this file too
        with MPIPoolExecutor() as pool:
            workers = pool.num_workers
            ds, counts = landau.sweep("hopf", %r, law="dieterich", executor=pool, out=sys.argv[1],
                                      progress=False, options={"chunk_size": 2}, return_counts=True)
        print("workers", workers, "computed", counts["computed"], flush=True)
""" % GRID)


def _mpi() -> str | None:
    """Why MPI cannot run here (None: it can)."""
    try:
        import mpi4py  # noqa: F401
    except ImportError:
        return "mpi4py is not installed (pip install 'landau-friction[mpi]')"
    if shutil.which("mpirun") is None:
        return "mpirun is not on PATH (.ci/install-mpi installs Open MPI)"
    return None


def test_an_mpi_pool_sweep_equals_the_sweep_in_one_process(tmp_path):
    import landau

    why = _mpi()
    if why is not None:
        if os.environ.get("LANDAU_REQUIRE_MPI"):
            pytest.fail(f"LANDAU_REQUIRE_MPI is set but {why}")
        pytest.skip(why)
    out = tmp_path / "mpi.nc"
    script = tmp_path / "run.py"
    script.write_text(SCRIPT)
    env = {**os.environ, "LANDAU_PROGRESS": "off", "OMPI_ALLOW_RUN_AS_ROOT": "1",
           "OMPI_ALLOW_RUN_AS_ROOT_CONFIRM": "1", "OMPI_MCA_rmaps_base_oversubscribe": "1"}
    proc = subprocess.run(["mpirun", "-n", "2", sys.executable, "-m", "mpi4py.futures", str(script), str(out)],
                          capture_output=True, text=True, env=env, timeout=300, cwd=tmp_path)
    assert proc.returncode == 0, proc.stderr[-3000:]
    assert "workers 1 computed 15" in proc.stdout, proc.stdout   # rank 0 runs the sweep, rank 1 the chunks
    import xarray as xr

    with xr.open_dataset(out) as ds:
        ds = ds.load()
    serial = landau.sweep("hopf", GRID, law="dieterich", workers=1, progress=False, options={"chunk_size": 2})
    assert (ds.status.values == serial.status.values).all() and int((ds.status == "ok").sum()) >= 10
    for name in ("k_c", "omega_c", "Lambda", "chi", "C"):
        assert np.array_equal(ds[name].values, serial[name].values, equal_nan=True), name
