"""Generated code cached across processes: one content-addressed folder of Python modules.

Numba's disk cache (``cache=True``) finds a function's compiled code through the file that
defines it, so code built from a string with ``exec`` would be compiled again in every
process.  Everything the toolkit generates at run time therefore goes through one mechanism:

* :func:`cached_source_file` writes a generated source once to a file named by its SHA-256
  (``landau_<tag>_<hash>.py``) in :func:`cache_dir`, atomically (:mod:`landau.support.io`); a file
  that does not hold the source its name promises is rewritten, and numba cache entries
  that cannot be read are removed first, so a corrupt entry is rebuilt, never loaded;
* :func:`exec_cached` executes that file's code as a module registered in ``sys.modules``
  under the file's name, with only the globals and builtins the caller allows;
* :func:`njit_cached` compiles one of its functions with ``cache=True`` (so the second
  process loads the machine code from disk) and binds the compiled function in the module
  in place of the Python one, so that other generated code can import it by name.

Kernels generated from a symbolic declaration use it (:func:`load_generated`, used by
:mod:`landau.codegen.kernels`), and so can any generated source that imports such a kernel by
name (e.g. a compiled-method template bound to one kernel).  A changed source is a new file (a new
key); files are only ever replaced whole, so concurrent processes see either no file or a
complete one.  When the folder cannot be written the code runs from memory (compiled once per
process).

The folder is ``$LANDAU_CACHE_DIR/jit`` when ``LANDAU_CACHE_DIR`` is set (the root of every
landau cache), else ``$LANDAU_JIT_DIR`` (the folder itself, an older setting still accepted),
else ``jit`` in the per-user cache folder (``~/.cache/landau/jit`` on Linux).
"""

from __future__ import annotations

import builtins
import hashlib
import os
import pickle
import sys
import types
from pathlib import Path
from typing import Iterable, Mapping

from landau.errors import OutputError
from landau.support.cachedir import ENV_JIT, ENV_ROOT, code_dir  # noqa: F401  (re-exported names)
from landau.support.io import atomic_write_text

#: file-name prefix of generated kernels (:func:`load_generated`)
_KERNEL_TAG = "kernel"


def cache_dir() -> Path:
    """The per-user folder holding generated sources and numba's cache of them.

    Returns
    -------
    pathlib.Path
        ``$LANDAU_CACHE_DIR/jit``, else ``$LANDAU_JIT_DIR``, else ``jit`` in the per-user
        cache folder of landau (the one rule of :func:`landau.support.cachedir.code_dir`); not created here.
    """
    return code_dir()


def source_key(source: str) -> str:
    """The cache key of a generated source: the first 24 hex digits of its SHA-256."""
    return hashlib.sha256(source.encode("utf-8")).hexdigest()[:24]


def module_name(source: str, tag: str = _KERNEL_TAG) -> str:
    """The module (and file stem) name of ``source``: ``landau_<tag>_<key>``."""
    if not tag.isidentifier():
        raise ValueError(f"cache tag {tag!r} is not an identifier")
    return f"landau_{tag}_{source_key(source)}"


def source_path(source: str, tag: str = _KERNEL_TAG) -> Path:
    """Where :func:`cached_source_file` keeps ``source``."""
    return cache_dir() / f"{module_name(source, tag)}.py"


def cached_source_file(source: str, tag: str = _KERNEL_TAG) -> Path | None:
    """The cache file holding ``source``, written (atomically) if absent or not ``source``.

    Numba cache entries of the file that cannot be read are removed (they are rebuilt at the
    next compilation); a rewritten file loses all of its numba entries.

    Parameters
    ----------
    source : str
        Generated Python source.
    tag : str
        A label in the file name (an identifier).

    Returns
    -------
    pathlib.Path or None
        The file, or None when the cache folder cannot be written (run from memory then).
    """
    try:
        path = source_path(source, tag)
    except (OSError, RuntimeError):             # no home directory to put the cache in
        return None
    try:
        on_disk = path.read_text(encoding="utf-8")
    except (OSError, UnicodeDecodeError):
        on_disk = None
    if on_disk != source:                       # absent, truncated or otherwise not ours: (re)write
        try:
            atomic_write_text(path, source)
        except (OSError, OutputError):          # read-only or missing home: run without a disk cache
            return None
        _drop_numba_entries(path)
    else:
        _drop_unreadable_numba_entries(path)
    return path


def keyed_source_path(key: str, tag: str) -> Path:
    """Where :func:`store_keyed_source` keeps the source stored under ``key``."""
    if not tag.isidentifier() or not key.isalnum():
        raise ValueError(f"cache tag {tag!r} or key {key!r} is not a plain name")
    return cache_dir() / f"landau_{tag}_{key}.py"


def _keyed_header(key: str, tag: str) -> str:
    return f"# landau generated code: {tag} {key}\n"


def load_keyed_source(key: str, tag: str) -> tuple[str, Path] | None:
    """The source stored under ``key`` by :func:`store_keyed_source`, with its file.

    For generated code whose key is a hash of what it was generated *from* (e.g. a formula)
    rather than of the source itself.  A file that does not start with the header naming its
    key, or is not text, is removed (and rebuilt by the caller): a truncated or foreign file is
    never executed.

    Parameters
    ----------
    key : str
        The caller's cache key (hex digits).
    tag : str
        A label in the file name (an identifier).

    Returns
    -------
    tuple of (str, pathlib.Path) or None
        The source without its header line and the file, or None (absent or unreadable).
    """
    try:
        path = keyed_source_path(key, tag)
        text = path.read_text(encoding="utf-8")
    except (OSError, RuntimeError, UnicodeDecodeError):
        return None
    header = _keyed_header(key, tag)
    if not text.startswith(header) or not text.endswith("\n"):
        discard_keyed_source(key, tag)
        return None
    return text[len(header):], path


def store_keyed_source(key: str, tag: str, source: str) -> Path | None:
    """Write ``source`` atomically under ``key`` (see :func:`load_keyed_source`).

    Returns
    -------
    pathlib.Path or None
        The file, or None when the cache folder cannot be written (nothing is cached then).
    """
    try:
        path = keyed_source_path(key, tag)
        atomic_write_text(path, _keyed_header(key, tag) + source.rstrip("\n") + "\n")
    except (OSError, RuntimeError, OutputError):
        return None
    return path


def discard_keyed_source(key: str, tag: str) -> None:
    """Remove the file stored under ``key`` (a corrupt entry; it is rebuilt at the next use)."""
    try:
        keyed_source_path(key, tag).unlink()
    except (OSError, RuntimeError):
        pass


def exec_cached(source: str, tag: str = _KERNEL_TAG, globals_: Mapping[str, object] | None = None,
                allowed_builtins: Iterable[str] | None = None) -> types.ModuleType:
    """Execute ``source`` from its cache file as a module (registered in ``sys.modules``).

    Parameters
    ----------
    source : str
        Python source (already checked by the caller: it is executed as is).
    tag : str
        A label in the module name (an identifier).
    globals_ : mapping, optional
        Names the source may use besides its own definitions (e.g. ``{"math": math}``).
    allowed_builtins : iterable of str, optional
        The only builtins reachable from the executed code (default: all of them, for the
        toolkit's own generated code).

    Returns
    -------
    module
        Its functions' code objects name the cache file, so numba can cache their compiled
        code on disk (``cache=True``); when no file could be written they name
        ``<generated ...>`` and must be compiled without ``cache``.
    """
    name = module_name(source, tag)
    path = cached_source_file(source, tag)
    filename = str(path) if path is not None else f"<generated {name}>"
    module = types.ModuleType(name)
    module.__file__ = filename
    if allowed_builtins is not None:
        module.__dict__["__builtins__"] = {b: getattr(builtins, b) for b in allowed_builtins}
    module.__dict__.update(globals_ or {})
    sys.modules[name] = module                  # numba rebuilds cached code against its module
    exec(compile(source, filename, "exec"), module.__dict__)
    return module


def load_generated(source: str, globals_: Mapping[str, object], allowed_builtins: Iterable[str]) -> dict:
    """Execute a generated kernel ``source`` from its cache file and return its namespace.

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
        The module namespace after execution (see :func:`exec_cached`); compile its
        functions with :func:`njit_cached`.
    """
    return exec_cached(source, _KERNEL_TAG, globals_, allowed_builtins).__dict__


def njit_cached(fn, signature):
    """``numba.njit(signature, cache=True)(fn)``, bound in ``fn``'s module under its name.

    A numba cache entry that cannot be loaded is dropped and the function compiled afresh;
    a function whose source is not in a cache file is compiled in memory.

    Parameters
    ----------
    fn : function
        A function of a module from :func:`exec_cached` / :func:`load_generated`.
    signature : numba signature
        The explicit signature (compilation happens here, not at the first call).

    Returns
    -------
    numba dispatcher
    """
    import numba as nb

    path = Path(fn.__code__.co_filename)
    if not path.is_file():                      # no cache file could be written: compile in memory
        disp = nb.njit(signature)(fn)
    else:
        try:
            disp = nb.njit(signature, cache=True)(fn)
        except Exception:                       # e.g. an index or object file numba cannot read
            _drop_numba_entries(path)
            disp = nb.njit(signature, cache=True)(fn)
    if fn.__globals__.get(fn.__name__) is fn:   # as a decorator would: importable by name
        fn.__globals__[fn.__name__] = disp
    return disp


def numba_cache_folders(path: Path) -> list[Path]:
    """The folders where numba may keep the cache files of the source file ``path``.

    numba writes them to ``__pycache__`` beside the source, or, when ``$NUMBA_CACHE_DIR`` is set,
    to a sub-folder of that folder (named by numba after the source's folder).  Generated sources
    carry a content hash in their name, so their entries are found by name in either place.

    Parameters
    ----------
    path : pathlib.Path
        A Python source file.

    Returns
    -------
    list of pathlib.Path
        Existing folders that may hold entries of ``path``.
    """
    folders = [path.parent / "__pycache__"]
    root = os.environ.get("NUMBA_CACHE_DIR")
    if root and Path(root).is_dir():
        folders += [d for d in Path(root).iterdir() if d.is_dir()]
    return [d for d in folders if d.is_dir()]


def _numba_entries(path: Path, suffix: str) -> list[Path]:
    return [f for d in numba_cache_folders(path) for f in d.glob(f"{path.stem}.*.{suffix}")]


def _drop_numba_entries(path: Path) -> None:
    """Remove numba's cache files (index ``.nbi``, code ``.nbc``) belonging to the source ``path``."""
    for f in _numba_entries(path, "nb[ic]"):
        try:
            f.unlink()
        except OSError:
            pass


def _readable_index(f: Path) -> bool:
    """Whether a numba index file unpickles (its version header, then its stamp and overloads)."""
    try:
        with open(f, "rb") as fh:
            pickle.load(fh)
            pickle.loads(fh.read())
        return True
    except Exception:
        return False


def _readable_data(f: Path) -> bool:
    """A cheap test of a numba code file: a pickle (protocol header) that ends with STOP."""
    try:
        with open(f, "rb") as fh:
            head = fh.read(2)
            fh.seek(-1, os.SEEK_END)
            tail = fh.read(1)
    except OSError:
        return False
    return len(head) == 2 and head[0] == 0x80 and tail == b"."


def _drop_unreadable_numba_entries(path: Path) -> None:
    """Remove every numba cache file of ``path`` when one of them cannot be read (numba would
    raise while loading it, and templates compile lazily, at their first call)."""
    entries = _numba_entries(path, "nb[ic]")
    if any(not (_readable_index(f) if f.suffix == ".nbi" else _readable_data(f)) for f in entries):
        _drop_numba_entries(path)
