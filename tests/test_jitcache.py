"""Generated numba kernels cached on disk, keyed by their source (landau.verify.jitcache)."""

import math

import numpy as np
import pytest
from numba import types

from landau.verify import jitcache

SIG = types.void(types.float64[::1], types.float64[::1])
SRC = "def kern(y, out):\n    out[0] = math.sin(y[0]) + abs(y[1])\n"


@pytest.fixture()
def cache(tmp_path, monkeypatch):
    monkeypatch.setenv("LANDAU_CACHE_DIR", str(tmp_path / "kernels"))
    return tmp_path / "kernels"


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


def test_corrupt_entries_are_rebuilt(cache):
    _compile(SRC)
    path = jitcache.source_path(SRC)
    path.write_text("def kern(y, out):\n    out[0] = 12345.0\n")   # not the source its name promises
    for f in (cache / "__pycache__").glob("*.nb[ic]"):
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
    for f in (cache / "__pycache__").glob("*.nb[ic]"):
        f.write_bytes(b"garbage")                    # the source file is intact, numba's entry not
    kern = _compile(SRC)
    assert _run(kern) == math.sin(0.3) + 2.0
    assert _hits(_compile(SRC)) == (1, 0)
