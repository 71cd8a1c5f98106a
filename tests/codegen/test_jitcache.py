"""Generated code cached on disk, keyed by its source (landau.verify.jitcache): generated kernels
and compiled-method templates specialised to a kernel share one folder and one mechanism."""

import math
import os
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest
from numba import types

from landau.verify import jitcache

SIG = types.void(types.float64[::1], types.float64[::1])
SRC = "def kern(y, out):\n    out[0] = math.sin(y[0]) + abs(y[1])\n"


@pytest.fixture()
def cache(tmp_path, monkeypatch):
    from landau.codegen import kernels

    monkeypatch.setenv("LANDAU_CACHE_DIR", str(tmp_path))
    # a kernel source compiled earlier in this process (another test file) would be reused
    # from its own cache folder: start from an empty in-process memo, as a new process does
    monkeypatch.setattr(kernels, "_COMPILED", {})
    return tmp_path / "jit"


def _compile(src):
    ns = jitcache.load_generated(src, {"math": math}, {"abs"})
    return jitcache.njit_cached(ns["kern"], SIG)


def _run(kern, y0=0.3, y1=-2.0):
    out = np.zeros(1)
    kern(np.array([y0, y1]), out)
    return out[0]


def _hits(kern):
    return sum(kern.stats.cache_hits.values()), sum(kern.stats.cache_misses.values())


def test_second_load_hits_the_disk_cache(cache):
    first = _compile(SRC)
    assert _hits(first) == (0, 1)                    # compiled and written
    second = _compile(SRC)                           # a new function object from the same file
    assert _hits(second) == (1, 0)                   # machine code loaded from disk, not compiled
    # the value is the formula itself (closed form), both times
    assert _run(first) == _run(second) == math.sin(0.3) + 2.0
    assert len(list(cache.glob("landau_kernel_*.py"))) == 1


def test_changed_source_gets_a_new_entry(cache):
    _compile(SRC)
    other = _compile(SRC.replace("math.sin", "math.cos"))
    assert _hits(other) == (0, 1)
    assert _run(other) == math.cos(0.3) + 2.0
    assert len(list(cache.glob("landau_kernel_*.py"))) == 2


def _numba_files(cache, pattern):
    """numba's cache files of generated sources in ``cache``: in its __pycache__, or under
    $NUMBA_CACHE_DIR when that is set (a folder shared with every other test of the session:
    ``pattern`` must name this test's own source, or the test would damage the others' entries)."""
    return [f for d in jitcache.numba_cache_folders(cache / "any.py") for f in d.glob(pattern)]


def _own_entries(source):
    """The pattern of numba's files of the generated ``source`` (named by its content hash)."""
    return f"{jitcache.source_path(source).stem}.*.nb[ic]"


def test_corrupt_entries_are_rebuilt(cache):
    _compile(SRC)
    path = jitcache.source_path(SRC)
    path.write_text("def kern(y, out):\n    out[0] = 12345.0\n")   # not the source its name promises
    for f in _numba_files(cache, _own_entries(SRC)):
        f.write_bytes(b"garbage")                                 # unreadable numba entries
    kern = _compile(SRC)
    assert _run(kern) == math.sin(0.3) + 2.0
    assert path.read_text() == SRC
    assert _hits(_compile(SRC)) == (1, 0)            # and the rebuilt entry is served again


def test_only_allowed_builtins_are_reachable(cache):
    ns = jitcache.load_generated("def g():\n    return open\n", {}, {"abs"})
    with pytest.raises(NameError):
        ns["g"]()


def test_corrupt_numba_entry_alone_is_rebuilt(cache):
    _compile(SRC)
    for f in _numba_files(cache, _own_entries(SRC)):
        f.write_bytes(b"garbage")                    # the source file is intact, numba's entry not
    kern = _compile(SRC)
    assert _run(kern) == math.sin(0.3) + 2.0
    assert _hits(_compile(SRC)) == (1, 0)


# --- one folder, one mechanism -------------------------------------------------------------
def test_cache_folder_settings(tmp_path, monkeypatch):
    monkeypatch.setenv("LANDAU_JIT_DIR", str(tmp_path / "old"))
    monkeypatch.setenv("LANDAU_CACHE_DIR", str(tmp_path / "root"))
    assert jitcache.cache_dir() == tmp_path / "root" / "jit"      # the root of every landau cache wins
    monkeypatch.delenv("LANDAU_CACHE_DIR")
    assert jitcache.cache_dir() == tmp_path / "old"               # the older setting is still accepted
    monkeypatch.delenv("LANDAU_JIT_DIR")
    monkeypatch.setenv("XDG_CACHE_HOME", str(tmp_path / "xdg"))
    assert jitcache.cache_dir() == tmp_path / "xdg" / "landau" / "jit"


TEMPLATE = '''"""A one-function template: y <- y + h f(t, y) (explicit Euler) over the free name fun."""
import numpy as np


@jit
def euler(p, t, y, h):
    out = np.empty_like(y)
    fun(t, y, p, out)
    return y + h * out
'''


def _generated_decay():
    import sympy as sp

    from landau.codegen.kernels import generate_kernel

    y, lam = sp.symbols("y lam")
    return generate_kernel([y], [-lam * y], [lam], [2.0], name="decay")


def _euler(template, kernel):
    import support_dopri5

    support_dopri5._LOADED.clear()                   # a fresh specialisation, as in a new process
    return support_dopri5.specialise(template.read_text(), {"fun": kernel.fun}, "euler").euler


def test_generated_kernels_and_their_specialised_templates_share_the_cache(cache, tmp_path):
    template = tmp_path / "euler.py"
    template.write_text(TEMPLATE)
    k = _generated_decay()
    # the compiled kernel is a module-level function of its cache file's module
    mod = sys.modules[k.fun.py_func.__module__]
    assert mod.fun is k.fun and Path(mod.__file__).parent == cache
    euler = _euler(template, k)
    y = np.array([1.0])
    # one explicit Euler step of y' = -2y: 1 - 2h (closed form)
    assert euler(k.p, 0.0, y, 0.125)[0] == 0.75
    assert _hits(euler) == (0, 1)
    assert len(list(cache.glob("landau_jit_euler_*.py"))) == 1    # the specialised source, in the same folder
    again = _euler(template, k)
    assert again(k.p, 0.0, y, 0.125)[0] == 0.75
    assert _hits(again) == (1, 0)                    # machine code from disk, not compiled again


def test_corrupt_entry_of_a_lazily_compiled_template_is_rebuilt(cache, tmp_path):
    template = tmp_path / "euler.py"
    template.write_text(TEMPLATE)
    k = _generated_decay()
    _euler(template, k)(k.p, 0.0, np.array([1.0]), 0.125)
    entries = _numba_files(cache, "landau_jit_euler_*.nb[ic]")
    assert entries
    for f in entries:
        f.write_bytes(b"\x80garbage")
    euler = _euler(template, k)
    assert euler(k.p, 0.0, np.array([1.0]), 0.125)[0] == 0.75
    assert _hits(euler) == (0, 1)                    # rebuilt, not loaded


_WORKER = """
import math, sys
import numpy as np
from numba import types
from landau.verify import jitcache
ns = jitcache.load_generated(sys.argv[1], {"math": math}, {"abs"})
k = jitcache.njit_cached(ns["kern"], types.void(types.float64[::1], types.float64[::1]))
out = np.zeros(1)
k(np.array([0.3, -2.0]), out)
print(repr(float(out[0])))
"""


def test_concurrent_processes_share_one_entry(cache):
    src = SRC.replace("abs(y[1])", "abs(y[1]) * 3.0")
    procs = [subprocess.Popen([sys.executable, "-c", _WORKER, src], stdout=subprocess.PIPE, text=True,
                              env=dict(os.environ)) for _ in range(3)]
    outs = [p.communicate(timeout=300)[0] for p in procs]
    assert all(p.returncode == 0 for p in procs)
    assert [float(o) for o in outs] == [math.sin(0.3) + 6.0] * 3
    assert len(list(cache.glob("landau_kernel_*.py"))) == 1      # one complete file, whoever wrote it last
    assert jitcache.source_path(src).read_text() == src
    assert _hits(_compile(src)) == (1, 0)            # and its numba entry serves the next process


def test_generated_source_is_kept_with_the_derivations(tmp_path, monkeypatch):
    import sympy as sp

    from landau.codegen import kernels
    from landau.support import cache as dcache

    monkeypatch.setenv("LANDAU_CACHE_DIR", str(tmp_path))
    monkeypatch.setattr(dcache, "_enabled", True)
    x, v, w = sp.symbols("x v w")
    field = [v, -w ** 2 * x - sp.Rational(1, 10) * v]
    src = kernels.kernel_source([x, v], field, [w])
    assert len(list((tmp_path / "kernel-source").glob("*.json"))) == 1

    def no_emission(*args):
        raise AssertionError("the source was derived again")

    real_emit = kernels._emit
    monkeypatch.setattr(kernels, "_emit", no_emission)
    # the same field under other symbol names is the same source: served from the cache
    a, b, c = sp.symbols("a b c")
    assert kernels.kernel_source([a, b], [b, -c ** 2 * a - sp.Rational(1, 10) * b], [c]) == src
    # an entry that fails the whitelist of generated code is derived again, not executed
    entry = next((tmp_path / "kernel-source").glob("*.json"))
    dcache.put("kernel-source", entry.stem, "import os\n")
    monkeypatch.setattr(kernels, "_emit", real_emit)
    assert kernels.kernel_source([x, v], field, [w]) == src
    # and the generated field is the declared one: x'' + 0.1 x' + w^2 x = 0 at (x, v) = (1, 2), w = 3
    k = kernels.compile_source(src)
    out = np.empty(2)
    k.fun(0.0, np.array([1.0, 2.0]), np.array([3.0]), out)
    assert list(out) == [2.0, -9.0 - 0.2]
