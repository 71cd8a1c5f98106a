"""Where landau keeps its disk caches, and whether it may trust them: one rule, defined here only.

Every cache of the toolkit lives under one root folder:

* the root is ``$LANDAU_CACHE_DIR`` when that is set, else the per-user cache folder of landau
  (``platformdirs.user_cache_dir("landau")``, e.g. ``~/.cache/landau`` on Linux);
* derivations and closed forms (:mod:`landau.support.cache`) are kept in sub-folders of the root named
  by their kind;
* generated code (:mod:`landau.verify.jitcache`: kernels, lambdified
  formulas, and numba's cache of them) is kept in ``<root>/jit``; ``$LANDAU_JIT_DIR`` names
  that folder directly when ``LANDAU_CACHE_DIR`` is not set (an older setting, still accepted).

Trust (the threat model is in ``docs/guarantees.md``, section "The cache: threat model"):

* a folder of the cache is used only when it is the user's own: created with mode 0700, and an
  existing one must be a folder owned by the effective user that neither the group nor others
  may write (:func:`secure_folder`); otherwise one :class:`CacheWarning` is issued and that
  cache is bypassed (results are computed, nothing is read or written);
* every entry carries an HMAC-SHA256 (:func:`sign`, :func:`verify`) under a per-user key that is
  *not* kept in the cache: ``$LANDAU_CACHE_KEY`` (hex, at least 32 digits, e.g. a CI secret), else
  the file ``cache.key`` (32 random bytes, mode 0600) in the user's configuration folder
  (``platformdirs.user_config_dir("landau")``), created on first use.  A copied or restored cache
  folder therefore carries no key with which its entries could be forged;
* temporaries left by a killed writer (``.<name>.<token>.tmp`` of :mod:`landau.support.io`,
  ``<name>.tmp.<id>`` of numba) are removed at the first use of the root in a process
  (:func:`usable_root`), once they are older than :data:`TEMP_AGE` seconds.

This module imports neither sympy nor numba: the simulation layer uses it too.
"""

from __future__ import annotations

import hashlib
import hmac
import os
import re
import secrets
import stat
import time
import warnings
from pathlib import Path

#: the root of every landau cache
ENV_ROOT = "LANDAU_CACHE_DIR"
#: the generated-code folder alone (older setting; ``LANDAU_CACHE_DIR`` wins when both are set)
ENV_JIT = "LANDAU_JIT_DIR"
#: the HMAC key of the cache, as hex digits (else the key file of the user's configuration folder)
ENV_KEY = "LANDAU_CACHE_KEY"
#: seconds after which a temporary file of the cache is taken as left by a killed writer
TEMP_AGE = 30.0
#: length of a generated key, in bytes
KEY_BYTES = 32

_TEMP = re.compile(r"^\..+\.[0-9a-f]{8}\.tmp$|\.tmp\.[0-9a-f]{16}$")


class CacheWarning(RuntimeWarning):
    """The cache cannot be trusted or written; results are computed without it."""


_WARNED: set[str] = set()
_FOLDERS: dict[str, bool] = {}
_KEYS: dict[tuple, bytes | None] = {}
_CLEANED: set[str] = set()


def warn_once(topic: str, message: str) -> None:
    """Issue ``message`` as a :class:`CacheWarning`, once per ``topic`` in a process."""
    if topic in _WARNED:
        return
    _WARNED.add(topic)
    warnings.warn(f"landau: {message}", CacheWarning, stacklevel=3)


def cache_root() -> Path:
    """The root folder of every landau cache (not created here).

    Returns
    -------
    pathlib.Path
        ``$LANDAU_CACHE_DIR``, else ``platformdirs.user_cache_dir("landau")``.
    """
    env = os.environ.get(ENV_ROOT)
    if env:
        return Path(env)
    import platformdirs

    return Path(platformdirs.user_cache_dir("landau", appauthor=False))


def code_dir() -> Path:
    """The folder of generated code and numba's cache of it (not created here).

    Returns
    -------
    pathlib.Path
        ``$LANDAU_CACHE_DIR/jit``, else ``$LANDAU_JIT_DIR``, else ``jit`` in :func:`cache_root`.
    """
    if not os.environ.get(ENV_ROOT):
        jit = os.environ.get(ENV_JIT)
        if jit:
            return Path(jit)
    return cache_root() / "jit"


def folder_problem(path: Path) -> str | None:
    """Why the existing folder ``path`` cannot hold a trusted cache, or None when it can.

    A cache folder must be a folder (a symbolic link is followed: its target counts), owned by
    the effective user, and writable by neither its group nor others.
    """
    try:
        st = os.stat(path)
    except OSError as exc:
        return f"it cannot be examined ({exc.strerror or exc})"
    if not stat.S_ISDIR(st.st_mode):
        return "it is not a folder"
    if st.st_uid != os.geteuid():
        return f"it belongs to another user (uid {st.st_uid})"
    if st.st_mode & (stat.S_IWGRP | stat.S_IWOTH):
        return f"others may write to it (mode {stat.S_IMODE(st.st_mode):04o})"
    return None


def secure_folder(path: Path, what: str = "the landau cache") -> bool:
    """Create ``path`` with mode 0700 (its missing parents with the default mode), or check the
    existing folder (:func:`folder_problem`).

    Returns
    -------
    bool
        True when the folder may be used; False after one :class:`CacheWarning` naming the
        folder and the reason (the caller then bypasses that cache).
    """
    path = Path(path)
    key = os.fspath(path)
    hit = _FOLDERS.get(key)
    if hit is False or (hit and os.path.isdir(path)):    # a removed folder is made and checked again
        return hit
    problem = None
    if not os.path.lexists(path):
        try:
            path.parent.mkdir(parents=True, exist_ok=True)
            os.mkdir(path, 0o700)
            os.chmod(path, 0o700)
        except FileExistsError:                 # a concurrent process made it: check it below
            pass
        except OSError as exc:
            problem = f"it cannot be created ({exc.strerror or exc})"
    if problem is None:
        problem = folder_problem(path)
    ok = problem is None
    if not ok:
        warn_once(f"folder {key}", f"not using {what} in {path}: {problem}; results are computed without it "
                                   f"(set {ENV_ROOT} to a folder of your own that only you may write, e.g. mode 0700)")
    _FOLDERS[key] = ok
    return ok


def key_file() -> Path:
    """The file holding the per-user HMAC key of the cache (when ``$LANDAU_CACHE_KEY`` is not set)."""
    import platformdirs

    return Path(platformdirs.user_config_dir("landau", appauthor=False)) / "cache.key"


def _read_key(path: Path) -> bytes | str:
    """The key in ``path``, or the reason it cannot be used."""
    try:
        fd = os.open(path, os.O_RDONLY | getattr(os, "O_NOFOLLOW", 0))
    except OSError as exc:
        return f"it cannot be opened ({exc.strerror or exc})"
    try:
        st = os.fstat(fd)
        if not stat.S_ISREG(st.st_mode):
            return "it is not a regular file"
        if st.st_uid != os.geteuid():
            return f"it belongs to another user (uid {st.st_uid})"
        if st.st_mode & 0o077:
            return f"others may read or write it (mode {stat.S_IMODE(st.st_mode):04o})"
        data = os.read(fd, 4 * KEY_BYTES)
    finally:
        os.close(fd)
    if len(data) != KEY_BYTES:
        return f"it holds {len(data)} bytes instead of {KEY_BYTES}"
    return data


def _make_key(path: Path) -> None:
    """Write a new random key to ``path`` (0600) unless a concurrent process already has."""
    tmp = path.with_name(f".{path.name}.{secrets.token_hex(4)}.tmp")
    fd = os.open(tmp, os.O_WRONLY | os.O_CREAT | os.O_EXCL, 0o600)
    try:
        os.write(fd, secrets.token_bytes(KEY_BYTES))
        os.fsync(fd)
    finally:
        os.close(fd)
    try:
        os.link(tmp, path)                      # never replaces a key another process made
    except FileExistsError:
        pass
    finally:
        os.unlink(tmp)


def cache_key() -> bytes | None:
    """The per-user HMAC key of the cache, or None (after one :class:`CacheWarning`) when there is
    no usable key: the cache is then bypassed.

    ``$LANDAU_CACHE_KEY`` (at least 32 hex digits) when set, else the key file
    (:func:`key_file`), created with mode 0600 in a folder of mode 0700 on first use.
    """
    env = os.environ.get(ENV_KEY)
    memo = ("env", env) if env else ("file", os.fspath(key_file()))
    if memo in _KEYS:
        return _KEYS[memo]
    key: bytes | None = None
    if env:
        try:
            key = bytes.fromhex(env.strip())
        except ValueError:
            key = None
        if key is None or len(key) < 16:
            warn_once("key env", f"${ENV_KEY} is not a key of at least 32 hex digits; the cache is not used")
            key = None
    else:
        path = key_file()
        got: bytes | str = "its folder is not safe"
        if secure_folder(path.parent, "the folder of the cache key"):
            got = _read_key(path)
            if isinstance(got, str) and not os.path.lexists(path):
                try:
                    _make_key(path)
                    got = _read_key(path)
                except OSError as exc:
                    got = f"it cannot be created ({exc.strerror or exc})"
        if isinstance(got, bytes):
            key = got
        else:
            warn_once(f"key {path}", f"the cache key {path} cannot be used: {got}; the cache is not used "
                                     f"(remove the file, or set {ENV_KEY})")
    _KEYS[memo] = key
    return key


def _mac(key: bytes, parts) -> hmac.HMAC:
    h = hmac.new(key, digestmod=hashlib.sha256)
    for p in parts:
        b = p if isinstance(p, bytes) else str(p).encode("utf-8")
        h.update(len(b).to_bytes(8, "little"))
        h.update(b)
    return h


def sign(*parts: bytes | str) -> str | None:
    """HMAC-SHA256 (hex) of ``parts`` (each length-prefixed) under :func:`cache_key`; None
    without a key."""
    key = cache_key()
    return None if key is None else _mac(key, parts).hexdigest()


def verify(mac: str, *parts: bytes | str) -> bool:
    """Whether ``mac`` is :func:`sign` of ``parts`` (compared in constant time); False without a key."""
    key = cache_key()
    if key is None or not isinstance(mac, str):
        return False
    return hmac.compare_digest(_mac(key, parts).hexdigest(), mac)


def read_signed(path: Path, magic: str, kind: str, key: str, discard) -> bytes | None:
    """The body of the signed entry at ``path``, checked before anything in it is parsed, or None.

    An entry is one header line ``MAGIC HMAC`` and the body; the HMAC (:func:`sign`) covers the
    magic, the ``kind``, the ``key`` and the body, so an entry written by someone else, altered, or
    copied under another key does not verify. A missing file is None quietly; an unreadable file,
    a foreign format or a failed signature is handed to ``discard(path, reason)`` (the caller's
    report-and-remove) and gives None. Shared by the kernel cache and the answer store, so the two
    stores trust the same things."""
    try:
        with open(path, "rb") as fh:
            data = fh.read()
    except FileNotFoundError:
        return None
    except OSError as exc:
        discard(path, f"unreadable: {exc.strerror or exc}")
        return None
    head, sep, body = data.partition(b"\n")
    fields = head.split(b" ")
    if not sep or len(fields) != 2 or fields[0] != magic.encode():
        discard(path, "not an entry of this format")
        return None
    if not verify(fields[1].decode("ascii", "replace"), magic, kind, key, body):
        discard(path, "its signature does not verify: written by someone else, or altered")
        return None
    return body


def clean_temporaries(folder: Path, depth: int = 3, age: float = TEMP_AGE) -> int:
    """Remove the temporaries of killed writers under ``folder`` (down to ``depth`` levels) that
    are older than ``age`` seconds; returns how many were removed."""
    removed = 0
    now = time.time()
    try:
        entries = list(os.scandir(folder))
    except OSError:
        return 0
    for e in entries:
        try:
            if e.is_dir(follow_symlinks=False):
                if depth > 1:
                    removed += clean_temporaries(Path(e.path), depth - 1, age)
            elif _TEMP.search(e.name) and now - e.stat(follow_symlinks=False).st_mtime > age:
                os.unlink(e.path)
                removed += 1
        except OSError:
            pass
    return removed


def usable_root() -> Path | None:
    """The cache root when it may be used: a safe folder (made if missing) and a usable key;
    else None (the caller bypasses the cache).  The first call for a root in a process removes
    the temporaries killed writers left there."""
    root = cache_root()
    if not secure_folder(root) or cache_key() is None:
        return None
    key = os.fspath(root)
    if key not in _CLEANED:
        _CLEANED.update((key, os.fspath(root / "jit")))      # the code folder is cleaned with it
        clean_temporaries(root)
    return root


def usable_code_dir() -> Path | None:
    """:func:`code_dir` when it may be used (safe, made if missing, with its ``__pycache__`` for
    numba made 0700 too), else None."""
    folder = code_dir()
    if folder.parent == cache_root() and usable_root() is None:
        return None
    if not secure_folder(folder, "the generated-code cache") or cache_key() is None:
        return None
    if not secure_folder(folder / "__pycache__", "numba's cache of generated code"):
        return None
    if not (os.access(folder, os.W_OK) and os.access(folder / "__pycache__", os.W_OK)):
        # numba would put its files of generated code in a fallback folder landau does not check
        warn_once(f"read-only {folder}", f"the generated-code cache {folder} is read-only: generated code is "
                                         "compiled in memory")
        return None
    key = os.fspath(folder)
    if key not in _CLEANED:
        _CLEANED.add(key)
        clean_temporaries(folder)
    return folder
