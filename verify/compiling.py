"""Compile a numba function on first use, and say so on the terminal when that takes a while.

Nothing in landau compiles at import: a compiled loop is built the first time a call needs it,
for the one signature that call uses, and numba's disk cache (``cache=True``) keeps the machine
code for every later process.  The first build on a fresh machine (or a fresh CI runner) can
take several seconds; :func:`compile_once` prints one line on standard error while it does, so
a user is never left in front of a silent terminal.  A build loaded from the disk cache is
quick and prints nothing (the line appears only after :data:`NOTICE_AFTER` seconds).

Which folders to keep between CI runs so that the build happens once: the landau cache root
(``$LANDAU_CACHE_DIR``, else the per-user cache folder, see :mod:`landau.support.cachedir`) and numba's
cache (``$NUMBA_CACHE_DIR`` when set, else the ``__pycache__`` folders of the installed package).

No stale machine code after an edit.  numba's disk cache checks only the source file of the
function it caches: a loop whose helpers, constants or callees live in other modules would load
old machine code after one of those is edited.  :func:`compile_once` therefore keys the cache on
content: it hashes the source of every module the loop can reach through its module's globals
(the modules whose names start with one of :data:`WATCHED`), keeps that hash beside the landau
cache (``<cache root>/jit/stamps``), and when it differs from the one recorded at the last build,
removes numba's entries of the loop's file before building again.

Trust.  numba reads its own cache files (it unpickles the index ``.nbi`` and loads the machine
code of ``.nbc``); landau does not reach into that.  The ``__pycache__`` beside the package's
modules is as trusted as the modules themselves.  When ``$NUMBA_CACHE_DIR`` is set, its files
of the loop's module are verified before the build (:func:`landau.verify.jitcache.verify_numba_entries`:
unsigned files are removed and the loop is built afresh) and signed after it, so a restored or
shared ``NUMBA_CACHE_DIR`` cannot hand a compiled loop planted or swapped machine code; every other
file in ``NUMBA_CACHE_DIR`` is numba's business, and that folder must be trusted.  A build whose
files cannot be written (full disk, read-only folder) keeps its machine code in memory, with one
warning.

This module imports numba only when a function is compiled.
"""

from __future__ import annotations

import hashlib
import os
import sys
import threading
import types
from pathlib import Path
from typing import Any

__all__ = ["NOTICE_AFTER", "WATCHED", "compile_once", "source_stamp"]

#: modules whose source is part of a compiled loop's cache key (the simulation code)
WATCHED: tuple[str, ...] = ("landau.verify.",)

#: seconds a first build may take before the terminal line is printed
NOTICE_AFTER = 0.5
#: set to "0" to silence the line (e.g. in a notebook that shows its own progress)
ENV_NOTICE = "LANDAU_COMPILE_NOTICE"


def _notice(what: str) -> None:
    print(f"landau: compiling {what} (once for this machine; cached afterwards)...",
          file=sys.stderr, flush=True)


def _reachable_modules(module: types.ModuleType, watched: tuple[str, ...]) -> dict[str, Path]:
    """The source files of ``module`` and of every watched module reachable through globals."""
    found: dict[str, Path] = {}
    stack = [module]
    while stack:
        mod = stack.pop()
        name, file = mod.__name__, getattr(mod, "__file__", None)
        if name in found or not file:
            continue
        found[name] = Path(file)
        for value in list(vars(mod).values()):
            if isinstance(value, types.ModuleType):
                other = value
            else:   # a function, a numba dispatcher (its Python function), a class
                owner = getattr(getattr(value, "py_func", value), "__module__", None)
                other = sys.modules.get(owner) if isinstance(owner, str) else None
            if other is not None and other.__name__ not in found and other.__name__.startswith(watched):
                stack.append(other)
    return found


def source_stamp(py_func: Any, watched: tuple[str, ...] = WATCHED) -> str:
    """SHA-256 of the sources a compiled function can reach (its module and the watched modules
    reachable from it through module globals), in a fixed order.

    Parameters
    ----------
    py_func : function
        The Python function behind a numba dispatcher.
    watched : tuple of str
        Module-name prefixes whose sources count.

    Returns
    -------
    str
        The hex digest.
    """
    files = _reachable_modules(sys.modules[py_func.__module__], watched)
    h = hashlib.sha256()
    for name in sorted(files):
        h.update(name.encode())
        try:
            h.update(files[name].read_bytes())
        except OSError:
            h.update(b"<unreadable>")
    return h.hexdigest()


def _stamp_file(py_func: Any) -> Path:
    from landau.support.cachedir import code_dir

    return code_dir() / "stamps" / f"{py_func.__module__}.{py_func.__qualname__}.sha256"


def _writable(folder: Path) -> bool:
    """Whether ``folder`` (or, where it does not exist yet, its nearest existing parent) is writable."""
    while not folder.exists() and folder != folder.parent:
        folder = folder.parent
    return os.access(folder, os.W_OK)


def _invalidate_if_changed(dispatcher: Any, watched: tuple[str, ...]) -> str | None:
    """Drop numba's entries of ``dispatcher``'s file when the sources it can reach changed since
    the last recorded build; returns the current stamp (None where it cannot be kept)."""
    py_func = getattr(dispatcher, "py_func", None)
    if py_func is None:
        return None
    from landau.support.cachedir import usable_code_dir

    if usable_code_dir() is None:       # the cache is bypassed (already said so): nothing is kept
        return None
    stamp = source_stamp(py_func, watched)
    path = _stamp_file(py_func)
    try:
        recorded = path.read_text().strip()
    except OSError:
        recorded = None
    if recorded != stamp and not _writable(path.parent):
        # a stamp that cannot be recorded would make every process rebuild: keep numba's entries
        import warnings

        warnings.warn(f"landau: the build stamps cannot be written to {path.parent}; an edit of a module "
                      "that a compiled loop calls may not be seen until numba's cache is cleared "
                      "(make the landau cache folder writable, or set LANDAU_CACHE_DIR)", RuntimeWarning,
                      stacklevel=3)
        return None
    if recorded != stamp:
        from landau.verify.jitcache import _drop_numba_entries

        _drop_numba_entries(Path(py_func.__code__.co_filename))
    return stamp


def _record(dispatcher: Any, stamp: str | None) -> None:
    if stamp is None:
        return
    from landau.errors import OutputError
    from landau.support.io import atomic_write_text

    path = _stamp_file(dispatcher.py_func)
    try:
        path.parent.mkdir(parents=True, exist_ok=True, mode=0o700)
        atomic_write_text(path, stamp + "\n")
    except (OSError, OutputError):   # a read-only or full cache: the next process checks again
        pass


def compile_once(dispatcher: Any, signature: Any, what: str, watched: tuple[str, ...] = WATCHED) -> Any:
    """Make sure ``dispatcher`` holds machine code for ``signature``; say so if building takes time.

    Parameters
    ----------
    dispatcher : numba dispatcher
        A function decorated with ``numba.njit(cache=True)`` and *no* explicit signature (so
        importing its module compiles nothing).
    signature : numba signature or tuple of numba types
        The argument types of the call about to be made.
    what : str
        What is being compiled, for the terminal line (e.g. ``"the Radau IIA integrator"``).
    watched : tuple of str
        Module-name prefixes whose sources are part of the cache key (module docstring).

    Returns
    -------
    numba dispatcher
        ``dispatcher``, now compiled (or loaded from numba's disk cache) for ``signature``.
    """
    args = tuple(signature.args) if hasattr(signature, "args") else tuple(signature)
    overloads = getattr(dispatcher, "overloads", None)
    if overloads is None or args in overloads:      # NUMBA_DISABLE_JIT=1: a Python function
        return dispatcher
    stamp = _invalidate_if_changed(dispatcher, watched)
    shared = _shared_numba_folders()
    py_file = Path(dispatcher.py_func.__code__.co_filename) if hasattr(dispatcher, "py_func") else None
    if shared and py_file is not None:
        from landau.verify.jitcache import verify_numba_entries

        verify_numba_entries(py_file, shared)
    timer = None
    if os.environ.get(ENV_NOTICE, "1") != "0":
        timer = threading.Timer(NOTICE_AFTER, _notice, args=(what,))
        timer.daemon = True
        timer.start()
    try:
        dispatcher.compile(args)
    except OSError as exc:      # numba built the code (it is in memory) but could not write its files
        if args not in dispatcher.overloads:
            raise
        from landau.support.cachedir import cache_root, warn_once

        warn_once(f"write {cache_root()}", f"could not write {what} to numba's cache ({exc}); it is compiled again "
                                 "in the next process")
        return dispatcher
    finally:
        if timer is not None:
            timer.cancel()
    _record(dispatcher, stamp)
    if shared and py_file is not None:
        from landau.verify.jitcache import sign_numba_entries

        sign_numba_entries(py_file)
    return dispatcher


def _shared_numba_folders() -> list[Path]:
    """The sub-folders of ``$NUMBA_CACHE_DIR`` (empty when it is not set)."""
    root = os.environ.get("NUMBA_CACHE_DIR")
    if not root or not Path(root).is_dir():
        return []
    try:
        return [d for d in Path(root).iterdir() if d.is_dir()]
    except OSError:
        return []
