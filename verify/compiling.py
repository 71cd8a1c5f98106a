"""Compile a numba function on first use, and say so on the terminal when that takes a while.

Nothing in landau compiles at import: a compiled loop is built the first time a call needs it,
for the one signature that call uses, and numba's disk cache (``cache=True``) keeps the machine
code for every later process.  The first build on a fresh machine (or a fresh CI runner) can
take several seconds; :func:`compile_once` prints one line on standard error while it does, so
a user is never left in front of a silent terminal.  A build loaded from the disk cache is
quick and prints nothing (the line appears only after :data:`NOTICE_AFTER` seconds).

Which folders to keep between CI runs so that the build happens once: numba's cache
(``$NUMBA_CACHE_DIR`` when set, else the ``__pycache__`` folders of the installed package) and,
when ``$NUMBA_CACHE_DIR`` is set, the landau cache root too (``$LANDAU_CACHE_DIR``, else the
per-user cache folder, see :mod:`landau.support.cachedir`): it holds the key that signs numba's
files there (see *Trust* below).

No stale machine code after an edit.  numba's disk cache checks only the source file of the
function it caches: a loop whose helpers, constants or callees live in other modules would load
old machine code after one of those is edited.  :func:`compile_once` therefore keys the cache on
content: it hashes the source of every module the loop can reach through its module's globals
(the modules whose names start with one of :data:`WATCHED`) and keeps that hash *beside numba's
index of the loop* (``<module>.<function>.landau-stamp`` in the same folder), so that the stamp
and the machine code it describes are kept or lost together: a CI that keeps numba's
``__pycache__`` folders (a cached virtual environment) loads the loop without building it, with or
without the landau cache.  When the stamp
differs from the sources (or is missing) numba's entries of the loop's file are removed before
building again, and the new stamp is written after the build.

Trust.  numba reads its own cache files (it unpickles the index ``.nbi`` and loads the machine
code of ``.nbc``); landau does not reach into that.  The ``__pycache__`` beside the package's
modules is as trusted as the modules themselves.  When ``$NUMBA_CACHE_DIR`` is set, its files
of the loop's module are verified before the build (:func:`landau.verify.jitcache.verify_numba_entries`:
unsigned files are removed and the loop is built afresh) and signed after it, so a restored or
shared ``NUMBA_CACHE_DIR`` cannot hand a compiled loop planted or swapped machine code; the files of
every other module of landau there are verified when ``landau.verify`` is imported
(:func:`secure_numba_cache`, which also refuses a ``NUMBA_CACHE_DIR`` that others may write).  A build whose
files cannot be written (full disk, read-only folder) keeps its machine code in memory, with one
warning.

This module imports numba only when a function is compiled.
"""

from __future__ import annotations

import contextlib
import gc
import glob
import hashlib
import os
import sys
import threading
import types
from pathlib import Path
from typing import Any, Iterator

__all__ = ["COMPILE_ADDRESS_SPACE", "NOTICE_AFTER", "WATCHED", "address_space_for_compiling", "compile_once",
           "paused_gc", "secure_numba_cache", "source_stamp"]

#: address space (bytes) an LLVM build may need beyond what the process holds: the forced oscillator's
#: integrator, the largest loop, took 190 MB (754 780 kB of VmSize before its build, 948 256 kB after),
#: with margin.  Below it LLVM aborts the process ("LLVM ERROR: Unable to allocate section memory",
#: SIGABRT) where Python could have said why.
COMPILE_ADDRESS_SPACE = 256 * 2**20

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


def _index_name(py_func: Any) -> tuple[Path, str]:
    """The source file of ``py_func`` and the name numba gives its cache index, up to the line
    number: ``<file stem>.<qualified name>-`` (``<`` and ``>`` removed, as numba does)."""
    path = Path(py_func.__code__.co_filename)
    return path, f"{path.stem}.{py_func.__qualname__.replace('<', '').replace('>', '')}-"


def _index_folders(py_func: Any) -> list[Path]:
    """The folders of numba's cache that hold an index of ``py_func``."""
    from landau.verify.jitcache import numba_cache_folders

    path, prefix = _index_name(py_func)
    pattern = glob.escape(prefix) + "*.nbi"
    return [d for d in numba_cache_folders(path) if any(d.glob(pattern))]


def _stamp_file(folder: Path, py_func: Any) -> Path:
    """Where the source stamp of ``py_func``'s entries in numba's cache ``folder`` is kept."""
    return folder / f"{_index_name(py_func)[1][:-1]}.landau-stamp"


def _invalidate_if_changed(dispatcher: Any, watched: tuple[str, ...]) -> str | None:
    """Drop numba's entries of ``dispatcher``'s file when the sources it can reach changed since
    the build that wrote them (their stamp differs, or there is none); returns the current stamp."""
    py_func = getattr(dispatcher, "py_func", None)
    if py_func is None:
        return None
    stamp = source_stamp(py_func, watched)
    for folder in _index_folders(py_func):
        try:
            recorded = _stamp_file(folder, py_func).read_text().strip()
        except OSError:
            recorded = None
        if recorded != stamp:
            from landau.verify.jitcache import _drop_numba_entries

            _drop_numba_entries(Path(py_func.__code__.co_filename))
            break
    return stamp


def _record(dispatcher: Any, stamp: str | None) -> None:
    """Write ``stamp`` beside every index of ``dispatcher`` in numba's cache (after a build)."""
    if stamp is None:
        return
    from landau.errors import OutputError
    from landau.support.io import atomic_write_text

    for folder in _index_folders(dispatcher.py_func):
        try:
            atomic_write_text(_stamp_file(folder, dispatcher.py_func), stamp + "\n")
        except (OSError, OutputError):   # a read-only or full cache: the next process builds again
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
    address_space_for_compiling(what)
    timer = None
    if os.environ.get(ENV_NOTICE, "1") != "0":
        timer = threading.Timer(NOTICE_AFTER, _notice, args=(what,))
        timer.daemon = True
        timer.start()
    try:
        with paused_gc():
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


@contextlib.contextmanager
def paused_gc() -> Iterator[None]:
    """Pause Python's cyclic garbage collector for the duration of a numba build.

    A build allocates hundreds of thousands of short-lived objects, which trigger collections of
    the oldest generation; each of those traverses every object the process holds (the symbolic
    derivation's sympy expressions, by the time a simulation starts), which made about a sixth of
    the first build of the Radau IIA loop.  Reference counting still frees what a build drops; the
    cycles it leaves are collected once the collector runs again.  Nested use is harmless (only
    the outermost resumes collection, and only if it was running).
    """
    running = gc.isenabled()
    gc.disable()
    try:
        yield
    finally:
        if running:
            gc.enable()


def _shared_numba_folders() -> list[Path]:
    """The sub-folders of ``$NUMBA_CACHE_DIR`` (empty when it is not set)."""
    root = os.environ.get("NUMBA_CACHE_DIR")
    if not root or not Path(root).is_dir():
        return []
    try:
        return [d for d in Path(root).iterdir() if d.is_dir()]
    except OSError:
        return []


def _package_subfolder(directory: Path) -> str:
    """The sub-folder of ``$NUMBA_CACHE_DIR`` where numba keeps the files of the modules in ``directory``:
    the folder's name and the SHA-1 of its absolute path (numba's ``_CacheLocator.get_suitable_cache_subpath``,
    which names it so; SHA-1 there is a short name, not a check)."""
    path = os.path.abspath(directory)
    return "_".join([os.path.split(path)[-1], hashlib.sha1(path.encode()).hexdigest()])


def secure_numba_cache() -> None:
    """Before any of landau's compiled modules is imported (``landau.verify``'s package init): a
    ``$NUMBA_CACHE_DIR`` that another user owns or others may write is replaced by a private folder,
    and numba's files there of every landau module are verified.

    numba unpickles its index files (``.nbi``) and loads machine code (``.nbc``) from
    ``$NUMBA_CACHE_DIR`` when that is set; a file planted or damaged there would run.  So:

    * a folder that is not the user's own (:func:`landau.support.cachedir.folder_problem`: owned by
      another user, or writable by its group or others) is not used: one warning, and
      ``NUMBA_CACHE_DIR`` is set to ``numba`` in the landau cache root (made 0700) for this process
      (and numba's loaded configuration with it);
    * the files of each module of the installed package (the sub-folders numba names after the
      package's folders) must carry their signatures
      (:func:`landau.verify.jitcache.verify_numba_entries`): a planted index, a truncated or swapped
      machine-code file makes every file of that module removed and the module's functions compiled
      afresh; files numba writes in this process are signed at its exit (for every module of the
      package, also one that had no files yet).

    Only hashing reads the files here; nothing is unpickled.  Without ``$NUMBA_CACHE_DIR`` numba keeps
    its files in ``__pycache__`` beside the modules, as trusted as the modules themselves.
    """
    root = os.environ.get("NUMBA_CACHE_DIR")
    if not root:
        return
    from landau.support.cachedir import cache_root, folder_problem, secure_folder, warn_once

    if os.path.isdir(root) and (problem := folder_problem(Path(root))) is not None:
        private = cache_root() / "numba"
        if not secure_folder(private, "numba's cache"):
            return
        warn_once(f"numba cache {root}", f"not using NUMBA_CACHE_DIR={root} for numba's cache: {problem}; using "
                                         f"{private} (a folder of your own that only you may write)")
        os.environ["NUMBA_CACHE_DIR"] = root = os.fspath(private)
        numba = sys.modules.get("numba")
        if numba is not None:
            numba.config.CACHE_DIR = root
    if not os.path.isdir(root):
        return
    from landau.verify.jitcache import verify_numba_entries

    package = Path(__file__).resolve().parent      # landau.verify: every compiled module of landau lives below
    for directory in (package, *(d for d in package.rglob("*") if d.is_dir() and d.name != "__pycache__")):
        folder = Path(root) / _package_subfolder(directory)
        # every module, also one without files yet: what numba writes for it in this process is signed at exit
        for module in sorted(directory.glob("*.py")):
            verify_numba_entries(module, [folder] if folder.is_dir() else [])


def _address_space_in_use() -> int | None:
    """The process's virtual memory (bytes, ``VmSize`` of ``/proc/self/status``), or None where unknown."""
    try:
        with open("/proc/self/status", encoding="ascii", errors="replace") as fh:
            for line in fh:
                if line.startswith("VmSize:"):
                    return int(line.split()[1]) * 1024
    except (OSError, ValueError, IndexError):
        return None
    return None


def address_space_for_compiling(what: str) -> None:
    """Refuse by name a build that the address-space limit (``ulimit -v``, RLIMIT_AS) leaves no room for.

    LLVM reserves memory for the machine code as it builds; where the limit leaves less than
    :data:`COMPILE_ADDRESS_SPACE` beyond what the process holds, it aborts the whole process
    (SIGABRT, ``std::bad_alloc`` or "Unable to allocate section memory") with no message of
    landau's.  This raises :class:`~landau.errors.BudgetError` first, naming the limit.  Where
    the limit or the usage cannot be read (not Linux), nothing is checked.
    """
    try:
        import resource
    except ImportError:     # not POSIX
        return
    soft, _ = resource.getrlimit(resource.RLIMIT_AS)
    if soft == resource.RLIM_INFINITY:
        return
    used = _address_space_in_use()
    if used is None or soft - used >= COMPILE_ADDRESS_SPACE:
        return
    from landau.errors import BudgetError

    raise BudgetError(f"not enough address space to compile {what}: the limit (ulimit -v) is {soft // 1024} kB, "
                      f"{used // 1024} kB are in use, and a build may need {COMPILE_ADDRESS_SPACE // 2**20} MB more; "
                      "raise the limit (once compiled, the code is loaded from numba's cache)")
