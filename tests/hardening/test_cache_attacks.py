"""The cache attacked: a planted pickle, edited generated source, truncated and swapped machine
code, a folder that is not the user's own, a full disk, temporaries of a killed writer.  In every
case no planted code runs, the answer is the one computed without the cache, and nothing crashes.

Each attack is run as a user would meet it: the cache is filled by one process, altered, and
read by the next (files altered while a process runs are that user's own doing, outside the
threat model of docs/guarantees.md)."""

import errno
import json
import os
import pickle
import subprocess
import sys
import time

import pytest

DERIVE = ["derive", "dieterich", "--V", "1e-4", "--quantities", "Lambda,C", "--json"]


class _Planted:
    """A pickle that runs a shell command when it is loaded."""

    def __init__(self, marker):
        self.marker = str(marker)

    def __reduce__(self):
        return os.system, (f"touch {self.marker}",)


@pytest.fixture()
def env(tmp_path, monkeypatch):
    """A cache root and a configuration folder (the key) of the test's own, in this process and
    in the processes it starts."""
    monkeypatch.setenv("LANDAU_CACHE_DIR", str(tmp_path / "cache"))
    monkeypatch.setenv("XDG_CONFIG_HOME", str(tmp_path / "config"))
    monkeypatch.delenv("LANDAU_CACHE_KEY", raising=False)
    monkeypatch.delenv("LANDAU_CACHE", raising=False)
    monkeypatch.delenv("NUMBA_CACHE_DIR", raising=False)
    from landau.support import cache

    cache.set_enabled(None)
    return dict(os.environ)


def _landau(env, *argv):
    p = subprocess.run([sys.executable, "-m", "landau", *argv], capture_output=True, text=True, env=env,
                       timeout=600)
    return p.returncode, p.stdout, p.stderr


def _numbers(out):
    point = json.loads(out)["points"][0]
    return point["Lambda"], point["C"]


def _entries(root):
    return [f for f in root.rglob("*") if f.is_file() and "jit" not in f.relative_to(root).parts]


def test_a_planted_pickle_never_runs(env, tmp_path):
    code, out, _ = _landau(env, *DERIVE)
    assert code == 0
    want = _numbers(out)
    root = tmp_path / "cache"
    marker = tmp_path / "planted-code-ran"
    entries = _entries(root)
    assert entries                                     # the derivation was cached
    for f in entries:                                  # every entry replaced by a pickle that runs code
        f.write_bytes(pickle.dumps(_Planted(marker)))
    code, out, err = _landau(env, *DERIVE)
    assert not marker.exists()
    assert code == 0 and _numbers(out) == want
    assert "does not verify" in err or "not an entry" in err     # said, not silently swallowed


def test_an_edited_generated_source_is_rejected_and_rebuilt(env, tmp_path):
    code, out, _ = _landau(env, *DERIVE)
    assert code == 0
    want = _numbers(out)
    sources = list((tmp_path / "cache" / "jit").glob("landau_lambdify_*.py"))
    assert sources
    for f in sources:                                  # the header kept, every sum turned into a difference
        head, _, body = f.read_text().partition("\n")
        f.write_text(head + "\n" + body.replace(" + ", " - "))
    code, out, _ = _landau(env, *DERIVE)
    assert code == 0 and _numbers(out) == want
    # rebuilt: the next run reads verified sources again and still agrees
    code, out, err = _landau(env, *DERIVE)
    assert code == 0 and _numbers(out) == want and "does not verify" not in err


_KERNELS = """
import sympy as sp
from landau.codegen.kernels import generate_kernel
y, lam = sp.symbols("y lam")
k1 = generate_kernel([y], [-lam * sp.sin(y)], [lam], [2.0], jacobian=False, name="k1")
k2 = generate_kernel([y], [lam * y ** 3 + 7], [lam], [2.0], jacobian=False, name="k2")
print(repr(float(k1(0.0, [0.5])[0])), repr(float(k2(0.0, [0.5])[0])))
"""


def _kernels(env):
    p = subprocess.run([sys.executable, "-c", _KERNELS], capture_output=True, text=True, env=env, timeout=600)
    return p.returncode, p.stdout, p.stderr


def _numba_files(tmp_path, suffix):
    return sorted((tmp_path / "cache" / "jit" / "__pycache__").glob(f"landau_kernel_*.{suffix}"))


def _closed_forms():
    import math

    return [-2.0 * math.sin(0.5), 2.0 * 0.125 + 7]


def _check_kernels(env):
    code, out, err = _kernels(env)
    assert code == 0, err[-2000:]
    got = [float(v) for v in out.split()]
    assert got == pytest.approx(_closed_forms(), rel=1e-15)


@pytest.mark.parametrize("attack", ["planted-index", "swapped", "truncated"])
def test_numba_files_of_generated_code_are_verified_before_numba_reads_them(env, tmp_path, attack):
    _check_kernels(env)
    index, data = _numba_files(tmp_path, "nbi"), _numba_files(tmp_path, "nbc")
    assert len(index) == len(data) == 2                 # one index and one machine-code file per kernel
    marker = tmp_path / "planted-code-ran"
    if attack == "planted-index":                       # an index numba (or a check) would unpickle
        for f in index:
            f.write_bytes(pickle.dumps(_Planted(marker)))
    elif attack == "swapped":                           # each kernel's machine code under the other's name
        a, b = data[0].read_bytes(), data[1].read_bytes()
        data[0].write_bytes(b)
        data[1].write_bytes(a)
    else:                                               # cut short, still ending like a pickle
        for f in data:
            raw = f.read_bytes()
            f.write_bytes(raw[: len(raw) // 2] + b".")
    _check_kernels(env)
    assert not marker.exists()
    _check_kernels(env)                                 # rebuilt, signed, served again


_LOOP = """
from numba import njit


@njit(cache=True)
def {name}(x):
    return {body}
"""

_COMPILE_ONCE = """
import sys
from numba import types
sys.path.insert(0, sys.argv[1])
from loop_a import plus_one
from loop_b import times_ten
from landau.verify.compiling import compile_once
for f in (plus_one, times_ten):
    compile_once(f, (types.float64,), f.__name__)
print(repr(plus_one(2.0)), repr(times_ten(2.0)))
"""


def test_a_shared_numba_cache_cannot_swap_a_compiled_loop(env, tmp_path):
    """A restored or shared NUMBA_CACHE_DIR: the files of a loop built through compile_once are
    verified before the build."""
    src = tmp_path / "src"
    src.mkdir()
    (src / "loop_a.py").write_text(_LOOP.format(name="plus_one", body="x + 1.0"))
    (src / "loop_b.py").write_text(_LOOP.format(name="times_ten", body="x * 10.0"))
    env = dict(env, NUMBA_CACHE_DIR=str(tmp_path / "numba"))

    def run():
        p = subprocess.run([sys.executable, "-c", _COMPILE_ONCE, str(src)], capture_output=True, text=True,
                           env=env, timeout=600)
        assert p.returncode == 0, p.stderr[-2000:]
        return [float(v) for v in p.stdout.split()]

    assert run() == [3.0, 20.0]
    data = sorted((tmp_path / "numba").rglob("loop_*.nbc"))
    assert len(data) == 2
    a, b = data[0].read_bytes(), data[1].read_bytes()
    data[0].write_bytes(b)
    data[1].write_bytes(a)
    assert run() == [3.0, 20.0]


@pytest.mark.parametrize("unsafe", ["world-writable", "group-writable", "foreign-owner"])
def test_a_folder_that_is_not_the_users_own_is_bypassed_with_one_warning(env, tmp_path, unsafe):
    code, out, _ = _landau(dict(env, LANDAU_CACHE_DIR=str(tmp_path / "reference")), *DERIVE)
    want = _numbers(out)
    root = tmp_path / "cache"
    root.mkdir()
    if unsafe == "foreign-owner":
        if os.geteuid() != 0:
            pytest.skip("changing a folder's owner needs root")
        os.chown(root, 4242, 4242)
        os.chmod(root, 0o700)
    else:
        os.chmod(root, 0o777 if unsafe == "world-writable" else 0o770)
    # what someone else left there is never read
    (root / "formula").mkdir()
    marker = tmp_path / "planted-code-ran"
    (root / "formula" / "planted.pkl").write_bytes(pickle.dumps(_Planted(marker)))
    code, out, err = _landau(env, *DERIVE)
    assert code == 0 and _numbers(out) == want
    assert err.count("not using the landau cache") == 1
    assert not marker.exists()
    assert [p.name for p in root.rglob("*")] == ["formula", "planted.pkl"]      # nothing written


class _FullDisk:
    """``os`` as landau's atomic writer sees it, on a file system that refuses: a full disk
    (every write fails with ENOSPC) or a read-only one (every new file fails with EROFS)."""

    def __init__(self, kind):
        self.kind = kind

    def __getattr__(self, name):
        return getattr(os, name)

    def write(self, fd, data):
        if self.kind == "full":
            raise OSError(errno.ENOSPC, os.strerror(errno.ENOSPC))
        return os.write(fd, data)

    def open(self, path, flags, *args):
        if self.kind == "read-only" and flags & os.O_CREAT:
            raise OSError(errno.EROFS, os.strerror(errno.EROFS))
        return os.open(path, flags, *args)


@pytest.mark.parametrize("kind", ["full", "read-only"])
def test_a_cache_that_cannot_be_written_is_a_warning_not_a_failed_command(env, monkeypatch, capsys, kind):
    from landau.cli import main
    from landau.support import io

    assert main(["derive", "dieterich", "--V", "1e-4", "--quantities", "Lambda,C", "--json"]) == 0
    want = _numbers(capsys.readouterr().out)
    from landau.support import cache

    cache.clear()                                           # nothing cached: every result is written again
    monkeypatch.setattr(io, "os", _FullDisk(kind))
    with pytest.warns(RuntimeWarning, match="could not write"):
        code = main(["derive", "dieterich", "--V", "1e-4", "--quantities", "Lambda,C", "--json"])
    out, err = capsys.readouterr()
    assert code == 0, err
    assert _numbers(out) == want


def test_temporaries_of_a_killed_writer_are_removed_at_the_next_start(env, tmp_path):
    root = tmp_path / "cache"
    code, _, _ = _landau(env, *DERIVE)
    assert code == 0
    old = time.time() - 3600
    planted = [root / "formula" / ".0123abcd.json.0badc0de.tmp",            # landau's atomic writer
               root / "jit" / ".landau_lambdify_0123.py.12345678.tmp",
               root / "jit" / "__pycache__" / "landau_kernel_0.fun-1.py311.nbi.tmp.0123456789abcdef"]  # numba's
    for f in planted:
        f.parent.mkdir(parents=True, exist_ok=True)
        f.write_bytes(b"half a file")
        os.utime(f, (old, old))
    fresh = root / "formula" / ".4567cdef.json.00c0ffee.tmp"              # a writer at work right now
    fresh.write_bytes(b"being written")
    code, _, _ = _landau(env, *DERIVE)
    assert code == 0
    assert [f for f in planted if f.exists()] == []
    assert fresh.exists()


_SLOW_WRITER = """
import os, sys, time
from landau.support import cache, io

class Stalling:
    def __getattr__(self, name):
        return getattr(os, name)

    def write(self, fd, data):
        n = os.write(fd, data)
        print("writing", flush=True)
        time.sleep(600)                 # killed here: the temporary is written, not yet renamed
        return n

io.os = Stalling()
cache.set_enabled(True)
cache.put("formula", cache.make_key("formula", "killed"), {"x": 1})
"""


def test_a_writer_killed_mid_write_leaves_nothing_the_next_start_keeps(env, tmp_path):
    p = subprocess.Popen([sys.executable, "-c", _SLOW_WRITER], stdout=subprocess.PIPE, text=True, env=env)
    try:
        assert p.stdout.readline().strip() == "writing"
        p.kill()                                            # SIGKILL: no clean-up of its own
    finally:
        p.wait(timeout=60)
    root = tmp_path / "cache"
    (orphan,) = [f for f in root.rglob("*.tmp")]
    old = time.time() - 3600                                # an hour later
    os.utime(orphan, (old, old))
    code, _, _ = _landau(env, *DERIVE)
    assert code == 0
    assert list(root.rglob("*.tmp")) == []
