"""A disk cache of derivations and closed forms, so a second run on the same law is instant.

Entries live in a per-user cache directory (``platformdirs.user_cache_dir("landau")``, e.g.
``~/.cache/landau`` on Linux), or in ``$LANDAU_CACHE_DIR`` when that is set (the one rule of
:mod:`landau.support.cachedir`; generated code is kept in its ``jit`` folder).  Set
``LANDAU_CACHE=off`` (or call :func:`set_enabled` with ``False``) to neither read nor write.

An entry is keyed by a SHA-256 of the library version (with a fingerprint of the deriving
modules' source), the kind of result and the canonical
form of what it was computed from (:func:`system_key`: ``sympy.srepr`` of the mechanical
system's equations, never its name), so a changed law, a changed system or a new release
never sees an old entry.  Writes are atomic (a temporary file renamed into place): concurrent
writers of the same entry each leave a complete file.  An entry that cannot be read — truncated,
corrupt, from another format — is ignored, removed and rebuilt.

Values are pickled (sympy expressions keep their shared sub-expressions and assumptions); the
directory is the user's own (created with mode 0700) and only this module writes to it.
"""

from __future__ import annotations

import hashlib
import logging
import os
import pickle
from pathlib import Path
from typing import Any, Callable

import sympy as sp

from landau.support.cachedir import ENV_ROOT

logger = logging.getLogger(__name__)

ENV_DIR = ENV_ROOT
ENV_SWITCH = "LANDAU_CACHE"
_MAGIC = "landau-cache/1"
_enabled: bool | None = None


_FINGERPRINT: str | None = None
#: the modules whose code decides what a cached formula, closed form or LaTeX text is (paths in
#: the package ``landau``)
DERIVING_MODULES = ("support/cx.py", "derivation/fredholm.py", "derivation/jets.py", "derivation/linear.py",
                    "derivation/multiscale.py", "derivation/coefficients.py", "derivation/rational.py",
                    "derivation/latex.py", "report/latex.py", "systems/system.py")


def _version() -> str:
    """The library version and a fingerprint of the deriving code: a development tree that
    changes a formula never reads an entry written before the change."""
    global _FINGERPRINT
    if _FINGERPRINT is None:
        from importlib.metadata import PackageNotFoundError, version

        try:
            __version__ = version("landau-friction")
        except PackageNotFoundError:  # a source tree that was never installed
            __version__ = "0+unknown"
        h = hashlib.sha256(__version__.encode())
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


def _path(kind: str, key: str) -> Path:
    return cache_dir() / kind / f"{key}.pkl"


def get(kind: str, key: str) -> Any | None:
    """The value stored under ``(kind, key)``, or None (missing, disabled or unreadable)."""
    if not enabled():
        return None
    path = _path(kind, key)
    try:
        with open(path, "rb") as fh:
            magic, k, value = pickle.load(fh)
        if magic != _MAGIC or k != key:
            raise ValueError("foreign entry")
        return value
    except FileNotFoundError:
        return None
    except Exception as exc:                     # corrupt or truncated: rebuild
        logger.warning("ignoring unreadable cache entry %s (%s)", path, exc)
        try:
            path.unlink()
        except OSError:
            pass
        return None


def put(kind: str, key: str, value: Any) -> None:
    """Store ``value`` atomically; a failure to write (read-only disk, full disk) is logged, not raised."""
    if not enabled():
        return
    from landau.support.io import atomic_write

    path = _path(kind, key)
    try:
        path.parent.mkdir(parents=True, exist_ok=True, mode=0o700)
        data = pickle.dumps((_MAGIC, key, value), protocol=pickle.HIGHEST_PROTOCOL)
        atomic_write(path, lambda fh: fh.write(data), mode="wb")
    except (OSError, pickle.PicklingError, RecursionError, TypeError) as exc:
        logger.warning("could not write cache entry %s (%s)", path, exc)


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
