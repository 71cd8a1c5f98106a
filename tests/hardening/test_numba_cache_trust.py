"""numba's cache is input too: with ``NUMBA_CACHE_DIR`` set, numba unpickles the index files of landau's
own compiled modules there and loads their machine code.  A pickle planted over
``hybrid_*/callbacks._call-*.nbi`` ran (it created a file) and a truncated machine-code file was loaded;
now every file of landau's modules there must carry its signature or all of that module's files are
removed and compiled afresh, and a folder others may write is not used
(:func:`landau.verify.compiling.secure_numba_cache`)."""

from __future__ import annotations

import os
import pickle
import subprocess
import sys
import textwrap
from pathlib import Path

PROBE = textwrap.dedent("""
    import numpy as np
    from landau.verify.hybrid.callbacks import call_pointer, pointer
    from landau.verify.hybrid.dop853 import FUN_SIG


    def rhs(t, y, p, out):
        out[0] = -p[0] * y[0]


    out = np.zeros(1)
    call_pointer(pointer(rhs, FUN_SIG), 0.0, np.array([2.0]), np.array([3.0]), out)
    print(out[0])
""")


class _Planted:
    """A pickle that runs a command when it is loaded (what a planted index would do)."""

    def __init__(self, marker: Path):
        self.marker = marker

    def __reduce__(self):
        return (os.system, (f"touch {self.marker}",))


def _run(tmp_path: Path, numba_dir: Path) -> subprocess.CompletedProcess:
    env = {**os.environ, "NUMBA_CACHE_DIR": str(numba_dir), "LANDAU_CACHE_DIR": str(tmp_path / "landau")}
    out = subprocess.run([sys.executable, str(tmp_path / "probe.py")], capture_output=True, text=True, env=env,
                         timeout=300, cwd=tmp_path)
    assert out.returncode == 0, out.stderr
    assert out.stdout.strip() == "-6.0"
    assert "Error" not in out.stderr, out.stderr
    return out


def _index(numba_dir: Path) -> Path:
    (found,) = numba_dir.glob("hybrid_*/callbacks._call-*.nbi")
    return found


def test_a_planted_index_never_runs_and_a_truncated_machine_code_is_rebuilt(tmp_path):
    (tmp_path / "probe.py").write_text(PROBE)
    numba_dir = tmp_path / "numba"
    numba_dir.mkdir(mode=0o700)
    _run(tmp_path, numba_dir)
    index = _index(numba_dir)
    stamp = index.stat().st_mtime_ns
    _run(tmp_path, numba_dir)           # the second process loads what the first wrote and signed
    assert _index(numba_dir).stat().st_mtime_ns == stamp
    marker = tmp_path / "planted-code-ran"
    with open(index, "wb") as fh:       # numba's index: two pickles (a stamp, then the overloads)
        pickle.dump(_Planted(marker), fh)
        pickle.dump(_Planted(marker), fh)
    _run(tmp_path, numba_dir)
    assert not marker.exists()          # before: the planted pickle ran
    with open(_index(numba_dir), "rb") as fh:
        assert b"touch" not in fh.read()   # rebuilt by numba
    (code,) = numba_dir.glob("hybrid_*/callbacks._call-*.nbc")
    code.write_bytes(code.read_bytes()[:40])
    _run(tmp_path, numba_dir)           # before: an internal UnpicklingError
    assert len(next(numba_dir.glob("hybrid_*/callbacks._call-*.nbc")).read_bytes()) > 40


def test_a_numba_cache_folder_others_may_write_is_not_used(tmp_path):
    (tmp_path / "probe.py").write_text(PROBE)
    shared = tmp_path / "shared"
    shared.mkdir()
    shared.chmod(0o777)
    out = _run(tmp_path, shared)
    assert f"not using NUMBA_CACHE_DIR={shared} for numba's cache: others may write to it (mode 0777)" in out.stderr
    assert not list(shared.iterdir())
    assert list((tmp_path / "landau" / "numba").glob("hybrid_*/callbacks._call-*.nbi"))
    assert (tmp_path / "landau" / "numba").stat().st_mode & 0o077 == 0
