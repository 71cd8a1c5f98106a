"""A disk cache of derivations and closed forms, so a second run on the same law is instant.

Entries live in a per-user cache directory (``platformdirs.user_cache_dir("landau")``, e.g.
``~/.cache/landau`` on Linux), or in ``$LANDAU_CACHE_DIR`` when that is set (the one rule of
:mod:`landau.support.cachedir`; generated code is kept in its ``jit`` folder).  Set
``LANDAU_CACHE=off`` (or call :func:`set_enabled` with ``False``) to neither read nor write.

An entry is keyed by a SHA-256 of the library version (with a fingerprint of the deriving
modules' source and the versions of sympy, numba and python-flint), the kind of result and the
canonical form of what it was computed from (:func:`system_key`: ``sympy.srepr`` of the
mechanical system's equations, never its name), so a changed law, a changed system or a new
release never sees an old entry.

An entry verifies before it is trusted.  Its file is one header line, ``landau-cache/2 <HMAC>``,
followed by the value in the JSON format of :mod:`landau.support.cachecodec` (sympy expressions as
``srepr`` atoms and a table of whitelisted operations: nothing is unpickled or executed).  The
HMAC-SHA256 covers the kind, the key and the JSON text, under the per-user key of
:mod:`landau.support.cachedir`; it is checked before the JSON is parsed.  An entry that fails the
check or cannot be read — truncated, edited, planted, from another format — is removed with a
logged warning and rebuilt; it is never fatal.  Writes are atomic (a temporary file renamed into
place): concurrent writers of the same entry each leave a complete file.  A write that fails
(full disk, read-only folder) is one :class:`~landau.support.cachedir.CacheWarning`, never a failed
command.  A cache folder that is not the user's own (another owner, writable by group or others)
is refused with one warning and the cache bypassed.
"""

from __future__ import annotations

import hashlib
import logging
import os
from pathlib import Path
from typing import Any, Callable

import sympy as sp

from landau.support import cachecodec, cachedir
from landau.support.cachedir import ENV_ROOT

logger = logging.getLogger(__name__)

ENV_DIR = ENV_ROOT
ENV_SWITCH = "LANDAU_CACHE"
_MAGIC = "landau-cache/2"
_SUFFIX = ".json"
_enabled: bool | None = None


_FINGERPRINT: str | None = None
#: the modules whose code decides what a cached formula, closed form or LaTeX text is (paths in
#: the package ``landau``)
DERIVING_MODULES = ("support/cx.py", "derivation/fredholm.py", "derivation/jets.py", "derivation/linear.py",
                    "derivation/multiscale.py", "derivation/coefficients.py", "derivation/rational.py",
                    "derivation/latex.py", "report/latex.py", "systems/system.py", "support/cachecodec.py")
#: the libraries whose versions are part of every key
KEYED_LIBRARIES = ("sympy", "numba", "python-flint")


def _version() -> str:
    """The library version, the versions of :data:`KEYED_LIBRARIES` and a fingerprint of the
    deriving code: a development tree that changes a formula, or another sympy, never reads an
    entry written before the change."""
    global _FINGERPRINT
    if _FINGERPRINT is None:
        from importlib.metadata import PackageNotFoundError, version

        try:
            __version__ = version("landau-friction")
        except PackageNotFoundError:  # a source tree that was never installed
            __version__ = "0+unknown"
        h = hashlib.sha256(__version__.encode())
        for lib in KEYED_LIBRARIES:
            try:
                h.update(f"{lib} {version(lib)}".encode())
            except PackageNotFoundError:
                h.update(f"{lib} -".encode())
        package = Path(__file__).resolve().parent.parent
        for name in DERIVING_MODULES:
            try:
                h.update((package / name).read_bytes())
            except OSError:
                h.update(name.encode())
        _FINGERPRINT = f"{__version__}+{h.hexdigest()[:16]}"
    return _FINGERPRINT


def enabled() -> bool:
    """Whether results are read from and written to the disk cache."""
    if _enabled is not None:
        return _enabled
    return os.environ.get(ENV_SWITCH, "on").strip().lower() not in ("0", "off", "false", "no")


def set_enabled(flag: bool | None) -> None:
    """Turn the cache on or off for this process (``None``: back to the ``LANDAU_CACHE`` setting)."""
    global _enabled
    _enabled = flag


def cache_dir() -> Path:
    """The cache directory: ``$LANDAU_CACHE_DIR`` or the per-user cache directory
    (:func:`landau.support.cachedir.cache_root`, the one rule for every landau cache)."""
    from landau.support.cachedir import cache_root

    return cache_root()


def system_key(system) -> str:
    """Canonical text of a :class:`~landau.systems.system.DynamicalSystem` (or a ``SpringBlock``):
    ``srepr`` of its states, equations, mass matrix, parameter, equilibrium and unknowns —
    not its name, so the same law declared under two names shares its entries."""
    system = getattr(system, "system", system)
    parts = (system.states, system.rhs, system.mass, system.parameter, system.equilibrium, system.unknowns,
             system.unknown_equations, system.normalise)
    return sp.srepr(parts)


def make_key(kind: str, *parts: Any) -> str:
    """SHA-256 over the library version, ``kind`` and the text of ``parts``."""
    h = hashlib.sha256()
    for p in (_MAGIC, _version(), kind, *parts):
        h.update(str(p).encode())
        h.update(b"\0")
    return h.hexdigest()


def _folder(kind: str) -> Path | None:
    """The folder of ``kind``'s entries when the cache may be used (safe, key available), else None."""
    if not (kind.isidentifier() or kind.replace("-", "_").isidentifier()):
        raise ValueError(f"cache kind {kind!r} is not a plain name")
    root = cachedir.usable_root()
    if root is None:
        return None
    folder = root / kind
    if not cachedir.secure_folder(folder):
        return None
    if os.fspath(folder) not in _SWEPT:         # entries of the pickled format of older releases
        _SWEPT.add(os.fspath(folder))
        for old in folder.glob("*.pkl"):
            try:
                old.unlink()
            except OSError:
                pass
    return folder


_SWEPT: set[str] = set()


def _path(kind: str, key: str) -> Path:
    if not key.isalnum():
        raise ValueError(f"cache key {key!r} is not a plain name")
    return cache_dir() / kind / f"{key}{_SUFFIX}"


def _discard(path: Path, why: str) -> None:
    logger.warning("ignoring cache entry %s (%s); it is rebuilt", path, why)
    try:
        path.unlink()
    except OSError:
        pass


def get(kind: str, key: str) -> Any | None:
    """The value stored under ``(kind, key)``, or None (missing, disabled, unsafe or not verified).

    The HMAC of the entry is checked before anything in it is parsed; an entry that fails the
    check or does not parse is removed (and rebuilt by the caller)."""
    if not enabled() or _folder(kind) is None:
        return None
    path = _path(kind, key)
    body = cachedir.read_signed(path, _MAGIC, kind, key, _discard)
    if body is None:
        return None
    try:
        return cachecodec.loads(body)
    except cachecodec.Undecodable as exc:
        _discard(path, str(exc))
        return None


def put(kind: str, key: str, value: Any) -> None:
    """Store ``value`` atomically, signed; a failure to write (read-only folder, full disk) is one
    warning, never an error.  A value the format cannot hold is not stored (and computed again
    next time)."""
    if not enabled() or _folder(kind) is None:
        return
    from landau.errors import OutputError
    from landau.support.io import atomic_write

    path = _path(kind, key)
    try:
        body = cachecodec.dumps(value)
    except (cachecodec.Unencodable, RecursionError) as exc:
        logger.debug("not caching %s entry %s (%s)", kind, key, exc)
        return
    mac = cachedir.sign(_MAGIC, kind, key, body)
    if mac is None:
        return
    data = f"{_MAGIC} {mac}\n".encode() + body
    try:
        atomic_write(path, lambda fh: fh.write(data), mode="wb")
    except (OSError, OutputError) as exc:
        cachedir.warn_once(f"write {cachedir.cache_root()}",
                           f"could not write to the cache ({exc}); results are computed and returned, but not kept")


def cached(kind: str, key: str, build: Callable[[], Any]) -> Any:
    """``get(kind, key)``, or ``build()`` stored under it."""
    value = get(kind, key)
    if value is None:
        value = build()
        if value is not None:
            put(kind, key, value)
    return value


def clear() -> None:
    """Remove every entry of the cache directory."""
    import shutil

    shutil.rmtree(cache_dir(), ignore_errors=True)
