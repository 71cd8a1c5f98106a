"""One BLAS thread around small dense factorisations (OpenBLAS as bundled with numpy and scipy).

A dense eigenvalue problem of a few hundred states gains nothing from OpenBLAS's threads, and on a
loaded machine its waiting threads spin: a 300 × 300 ``numpy.linalg.eigvals`` measured 0.8 CPU-s
with the default threads and 0.05 CPU-s with one, on two shared cores (the spring–block chain's
eigenvalue scan, :mod:`landau.derivation.sparse_hopf`).  :func:`one_blas_thread` sets the thread
count of the OpenBLAS libraries that numpy and scipy load to 1 for the duration of a block and
restores it; where no such library is found (another BLAS) it does nothing.
"""

from __future__ import annotations

import contextlib
import ctypes
import glob
import os
from functools import lru_cache
from typing import Iterator


@lru_cache(maxsize=1)
def _libraries() -> tuple[tuple[object, object], ...]:
    """(get, set) thread-count functions of every bundled OpenBLAS found beside numpy and scipy."""
    found = []
    for package in ("numpy", "scipy"):
        try:
            mod = __import__(package)
        except ImportError:        # pragma: no cover - both are dependencies
            continue
        if not mod.__file__:
            continue
        where = os.path.join(os.path.dirname(os.path.dirname(mod.__file__)), f"{package}.libs")
        for path in glob.glob(os.path.join(where, "*openblas*")):
            try:
                lib = ctypes.CDLL(path)
            except OSError:
                continue
            for suffix in ("64_", ""):
                get = getattr(lib, f"scipy_openblas_get_num_threads{suffix}", None)
                put = getattr(lib, f"scipy_openblas_set_num_threads{suffix}", None)
                if get is not None and put is not None:
                    get.restype = ctypes.c_int
                    put.argtypes = [ctypes.c_int]
                    found.append((get, put))
                    break
    return tuple(found)


@contextlib.contextmanager
def one_blas_thread() -> Iterator[None]:
    """Run the block with one OpenBLAS thread (restored afterwards; a no-op without OpenBLAS)."""
    libs = _libraries()
    before = [get() for get, _ in libs]          # type: ignore[operator]
    try:
        for _, put in libs:
            put(1)                               # type: ignore[operator]
        yield
    finally:
        for (_, put), n in zip(libs, before, strict=True):
            put(n)                               # type: ignore[operator]


__all__ = ["one_blas_thread"]
