"""Generated numba kernels cached across processes, keyed by their source.

Numba's disk cache (``cache=True``) finds a function's compiled code through the file that
defines it, so a kernel built from a string with ``exec`` is compiled again in every process.
:func:`load_generated` writes the generated source once to a file named by its SHA-256 in a
per-user cache folder, executes that file's code (with only the builtins the caller allows)
and returns its functions; :func:`njit_cached` compiles one of them with ``cache=True``, so the
second process loads the machine code from disk.  A changed source is a new file (a new key);
a cache file that does not hold the source its name promises, or a numba cache entry that
cannot be loaded, is rebuilt.

The cache folder is ``$LANDAU_CACHE_DIR`` if set, else ``$XDG_CACHE_HOME/landau/kernels``,
else ``~/.cache/landau/kernels``.
"""

from __future__ import annotations

import builtins
import hashlib
import os
import sys
import types
from pathlib import Path
from typing import Iterable, Mapping

from landau.io import atomic_write_text

_PREFIX = "landau_kernel_"


def cache_dir() -> Path:
    """The per-user folder holding generated kernel sources and numba's cache of them.

    Returns
    -------
    pathlib.Path
        ``$LANDAU_CACHE_DIR``, else ``$XDG_CACHE_HOME/landau/kernels``, else
        ``~/.cache/landau/kernels`` (not created here).
    """
    env = os.environ.get("LANDAU_CACHE_DIR")
    if env:
        return Path(env)
    xdg = os.environ.get("XDG_CACHE_HOME")
    base = Path(xdg) if xdg else Path.home() / ".cache"
    return base / "landau" / "kernels"


def source_key(source: str) -> str:
    """The cache key of a generated source: the first 24 hex digits of its SHA-256."""
    return hashlib.sha256(source.encode("utf-8")).hexdigest()[:24]


def source_path(source: str) -> Path:
    """Where :func:`load_generated` keeps ``source``."""
    return cache_dir() / f"{_PREFIX}{source_key(source)}.py"


def load_generated(source: str, globals_: Mapping[str, object], allowed_builtins: Iterable[str]) -> dict:
    """Execute generated ``source`` from its cache file and return the namespace it defines.

    Parameters
    ----------
    source : str
        Python source of the kernels (already checked by the caller: it is executed as is).
    globals_ : mapping
        Names the source may use (e.g. ``{"math": math}``).
    allowed_builtins : iterable of str
        The only builtins reachable from the executed code.

    Returns
    -------
    dict
        The module namespace after execution; its functions' code objects name the cache file,
        so :func:`njit_cached` can cache their compiled code on disk.
    """
    path = source_path(source)
    try:
        on_disk = path.read_text(encoding="utf-8")
    except (OSError, UnicodeDecodeError):
        on_disk = None
    if on_disk != source:                       # absent, truncated or otherwise not ours: (re)write
        try:
            atomic_write_text(path, source)
            _drop_numba_entries(path)
        except OSError:                         # read-only home: still run, just without a disk cache
            path = Path(f"<generated {source_key(source)}>")
    name = path.stem
    ns: dict = {"__name__": name, "__file__": str(path),
                "__builtins__": {b: getattr(builtins, b) for b in allowed_builtins}}
    ns.update(globals_)
    module = types.ModuleType(name)
    module.__dict__.update(ns)
    sys.modules.setdefault(name, module)        # numba rebuilds cached code against its module
    exec(compile(source, str(path), "exec"), module.__dict__)
    return module.__dict__


def njit_cached(fn, signature):
    """``numba.njit(signature, cache=True)(fn)``; a numba cache entry that cannot be loaded is
    dropped and the kernel compiled afresh.

    Parameters
    ----------
    fn : function
        A function from :func:`load_generated`.
    signature : numba signature
        The explicit signature (compilation happens here, not at the first call).

    Returns
    -------
    numba dispatcher
    """
    import numba as nb

    path = Path(fn.__code__.co_filename)
    if not path.is_file():                      # no cache file could be written: compile in memory
        return nb.njit(signature)(fn)
    try:
        return nb.njit(signature, cache=True)(fn)
    except Exception:                           # e.g. a truncated index or object file
        _drop_numba_entries(path)
        return nb.njit(signature, cache=True)(fn)


def _drop_numba_entries(path: Path) -> None:
    """Remove numba's cache files (index ``.nbi``, code ``.nbc``) belonging to the source ``path``."""
    pycache = path.parent / "__pycache__"
    if not pycache.is_dir():
        return
    for f in pycache.glob(f"{path.stem}.*.nb[ic]"):
        try:
            f.unlink()
        except OSError:
            pass
