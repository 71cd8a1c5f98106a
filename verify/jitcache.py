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

Nothing is executed or handed to numba before it is verified:

* a content-addressed source is compiled from the text in memory; its file is rewritten unless
  it holds exactly that text;
* a source stored under a caller's key (:func:`store_keyed_source`) carries an HMAC of its tag,
  key and text under the per-user key of :mod:`landau.support.cachedir`, checked before the text is
  returned (an edited or planted file is removed and rebuilt);
* numba's files of a generated source (index ``.nbi``, machine code ``.nbc``) are signed: an
  HMAC of each file's name and bytes is recorded (an empty file named by it in
  ``<folder>/signatures``).  Before numba can read any file of a source in a process
  (:func:`verify_numba_entries`, called when the source is executed and when a function of it is
  compiled), every file of that source must carry its signature, else all of them are removed
  and the code is compiled afresh: a planted index (a pickle numba would load), a truncated or
  swapped machine-code file is never loaded.  Files written while a process runs are signed by
  it (at the next verification of the same source, after a compilation of :func:`njit_cached`,
  and at exit); a process killed before that leaves files that the next one rebuilds.

The folder must be the user's own (:func:`landau.support.cachedir.secure_folder`); when it is not,
or cannot be written, generated code runs from memory (compiled once per process).
"""

from __future__ import annotations

import atexit
import builtins
import hashlib
import logging
import os
import sys
import types
from pathlib import Path
from typing import Iterable, Mapping

from landau.errors import OutputError
from landau.support import cachedir
from landau.support.cachedir import ENV_JIT, ENV_ROOT, code_dir  # noqa: F401  (re-exported names)
from landau.support.io import atomic_write_text

logger = logging.getLogger(__name__)

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
        if cachedir.usable_code_dir() is None:  # not the user's own folder, or no key: from memory
            return None
    except (OSError, RuntimeError):             # no home directory to put the cache in
        return None
    try:
        on_disk = path.read_text(encoding="utf-8")
    except (OSError, UnicodeDecodeError):
        on_disk = None
    if on_disk != source:                       # absent, truncated or otherwise not ours: (re)write
        try:
            atomic_write_text(path, source)
        except (OSError, OutputError) as exc:   # read-only or full: run without a disk cache
            cachedir.warn_once(f"write {cachedir.cache_root()}",
                               f"could not write generated code to the cache ({exc}); it is compiled in memory")
            return None
        _drop_numba_entries(path)
    verify_numba_entries(path)
    return path


def keyed_source_path(key: str, tag: str) -> Path:
    """Where :func:`store_keyed_source` keeps the source stored under ``key``."""
    if not tag.isidentifier() or not key.isalnum():
        raise ValueError(f"cache tag {tag!r} or key {key!r} is not a plain name")
    return cache_dir() / f"landau_{tag}_{key}.py"


_KEYED_PREFIX = "# landau generated code: "


def _keyed_header(key: str, tag: str, mac: str) -> str:
    return f"{_KEYED_PREFIX}{tag} {key} {mac}\n"


def load_keyed_source(key: str, tag: str) -> tuple[str, Path] | None:
    """The source stored under ``key`` by :func:`store_keyed_source`, with its file.

    For generated code whose key is a hash of what it was generated *from* (e.g. a formula)
    rather than of the source itself.  The file's header names the tag, the key and an HMAC of
    both and of the source (:func:`landau.support.cachedir.sign`); a file whose header or HMAC does
    not verify, or that is not text, is removed (and rebuilt by the caller): a truncated, edited
    or planted file is never returned, so never executed.

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
        if cachedir.usable_code_dir() is None:
            return None
        text = path.read_text(encoding="utf-8")
    except FileNotFoundError:
        return None
    except (OSError, RuntimeError, UnicodeDecodeError):
        discard_keyed_source(key, tag)
        return None
    head, _, source = text.partition("\n")
    fields = head[len(_KEYED_PREFIX):].split(" ") if head.startswith(_KEYED_PREFIX) else []
    if len(fields) == 2 and fields == [tag, key]:   # written by an older release, unsigned: rebuilt
        discard_keyed_source(key, tag)
        return None
    if (len(fields) != 3 or fields[:2] != [tag, key]
            or not cachedir.verify(fields[2], "keyed-source", tag, key, source)):
        logger.warning("ignoring generated code %s: its signature does not verify; it is rebuilt", path)
        discard_keyed_source(key, tag)
        return None
    return source, path


def store_keyed_source(key: str, tag: str, source: str) -> Path | None:
    """Write ``source`` atomically under ``key`` (see :func:`load_keyed_source`).

    Returns
    -------
    pathlib.Path or None
        The file, or None when the cache folder cannot be written (nothing is cached then).
    """
    try:
        path = keyed_source_path(key, tag)
        if cachedir.usable_code_dir() is None:
            return None
        source = source.rstrip("\n") + "\n"
        mac = cachedir.sign("keyed-source", tag, key, source)
        if mac is None:
            return None
        atomic_write_text(path, _keyed_header(key, tag, mac) + source)
    except (OSError, RuntimeError) as exc:
        logger.debug("generated code not kept (%s)", exc)
        return None
    except OutputError as exc:
        cachedir.warn_once(f"write {cachedir.cache_root()}",
                           f"could not write generated code to the cache ({exc}); it is generated again in the "
                           "next process")
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

    from landau.verify.compiling import address_space_for_compiling

    address_space_for_compiling(f"the generated function {fn.__name__!r}")
    path = Path(fn.__code__.co_filename)
    if not path.is_file() or not _cache_file(path):   # no verified cache file: compile in memory
        disp = nb.njit(signature)(fn)
    else:
        verify_numba_entries(path)              # nothing unsigned reaches numba
        try:
            disp = nb.njit(signature, cache=True)(fn)
        except OSError as exc:                  # numba could not write its files (e.g. a full disk)
            cachedir.warn_once(f"write {cachedir.cache_root()}",
                               f"could not write compiled code to the cache ({exc}); it is compiled in memory")
            disp = nb.njit(signature)(fn)
        except Exception:                       # a file numba cannot use: rebuilt
            _drop_numba_entries(path)
            disp = nb.njit(signature, cache=True)(fn)
        if signature is not None:
            sign_numba_entries(path)
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


def _cache_file(path: Path) -> bool:
    """Whether ``path`` is a source file of the (usable) generated-code folder."""
    folder = cachedir.usable_code_dir()
    return folder is not None and path.parent == folder


def _signature_dir() -> Path | None:
    folder = cachedir.usable_code_dir()
    if folder is None:
        return None
    sig = folder / "signatures"
    if not cachedir.secure_folder(sig, "the signatures of compiled code"):
        return None
    if os.fspath(sig) not in _PRUNED:
        _PRUNED.add(os.fspath(sig))
        _prune(sig)
    return sig


#: days after which a signature nobody used is removed (its file, if still there, is rebuilt)
SIGNATURE_DAYS = 30
_PRUNED: set[str] = set()


def _prune(sigdir: Path) -> None:
    """Remove the signatures not refreshed for :data:`SIGNATURE_DAYS` days (those of files numba
    has since replaced), once per process."""
    import time

    limit = time.time() - SIGNATURE_DAYS * 86400
    try:
        for e in os.scandir(sigdir):
            if e.is_file(follow_symlinks=False) and e.stat(follow_symlinks=False).st_mtime < limit:
                os.unlink(e.path)
    except OSError:
        pass


def _entry_signature(f: Path) -> str | None:
    """The signature of numba's file ``f`` (an HMAC of its name and bytes), or None (unreadable)."""
    try:
        data = f.read_bytes()
    except OSError:
        return None
    return cachedir.sign("numba-entry", f.name, data)


def _plausible(f: Path) -> bool:
    """Whether ``f`` has the shape of a file numba writes (a pickle stream: protocol header first,
    STOP last), tested on its bytes alone; what appears while a process runs is signed only then."""
    try:
        with open(f, "rb") as fh:
            head = fh.read(2)
            fh.seek(-1, os.SEEK_END)
            tail = fh.read(1)
    except OSError:
        return False
    return len(head) == 2 and head[0] == 0x80 and tail == b"."


#: source files whose numba entries were verified in this process (later files are its own)
_VERIFIED: set[str] = set()
_AT_EXIT = False


def sign_numba_entries(path: Path) -> None:
    """Record the signature of every numba file of the source ``path`` (written by this process,
    or by another process of the same user while this one ran)."""
    sigdir = _signature_dir()
    if sigdir is None:
        return
    for f in _numba_entries(path, "nb[ic]"):
        mac = _entry_signature(f)
        if mac is None:
            continue
        try:
            os.close(os.open(sigdir / mac, os.O_WRONLY | os.O_CREAT, 0o600))
            os.utime(sigdir / mac)              # in use: kept by the pruning of old signatures
        except OSError as exc:
            cachedir.warn_once(f"write {cachedir.cache_root()}",
                               f"could not record signatures of compiled code ({exc}); it is compiled again "
                               "in the next process")
            return


def verify_numba_entries(path: Path, folders: list[Path] | None = None) -> None:
    """Before numba may read any file of the source ``path``: remove all of them unless every one
    carries its signature (:func:`sign_numba_entries`).

    The first call for ``path`` in a process checks; later calls sign what appeared since (the
    files numba wrote for this process).  Nothing here unpickles or loads a file: a file is only
    read as bytes and hashed.

    Parameters
    ----------
    path : pathlib.Path
        A generated source file (or a module of the package, see
        :func:`landau.verify.compiling.compile_once`).
    folders : list of pathlib.Path, optional
        Where to look for its files (default :func:`numba_cache_folders`).
    """
    key = os.fspath(path)
    if key in _VERIFIED:
        if any(not _plausible(f) for f in _numba_entries(path, "nb[ic]")):
            _drop_numba_entries(path)           # damaged while this process ran: rebuilt
        sign_numba_entries(path)
        return
    sigdir = _signature_dir()
    if sigdir is None:
        return
    entries = [f for d in (folders if folders is not None else numba_cache_folders(path))
               for f in d.glob(f"{path.stem}.*.nb[ic]")]
    unsigned = [f for f in entries if not (sigdir / (_entry_signature(f) or "-")).is_file()]
    if unsigned:
        logger.info("removing numba's cache of %s: %s carries no valid signature (altered, planted or "
                       "left by a killed process); it is compiled afresh", path.name, unsigned[0].name)
        for f in entries:
            try:
                f.unlink()
            except OSError:
                pass
    _VERIFIED.add(key)
    global _AT_EXIT
    if not _AT_EXIT:
        _AT_EXIT = True
        atexit.register(_sign_verified)


def _sign_verified() -> None:
    """At exit: sign the numba files of every source verified in this process."""
    for key in list(_VERIFIED):
        try:
            sign_numba_entries(Path(key))
        except Exception:                       # never fail an exit
            pass
