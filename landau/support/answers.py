"""A store of finished command answers, read back without sympy: a repeated command is a file read.

A command such as ``landau hopf spring-block dieterich --V 1e-4 --json`` is a pure function of its
arguments and of the code that computes it: the law (a built-in law is its declaration in the
source; an inline law is its text in the arguments), the model, the parameters and landau's
version.  Its first run derives (sympy), compiles and evaluates; this module keeps what the
answer is — the exact bytes the command printed and its exit code — so that a repeated run
prints them again without importing sympy, numba or the command's module.

The key is a SHA-256 of

* the command and its argument list (after the command line's own normalisation), and
* :func:`fingerprint`: the text of every module of the package (``landau``, ``landau.laws``,
  ``landau.verify``, ``landau.paper_figures``), the versions of the numerical libraries and of
  Python, and the machine type — so an edited law, a changed derivation or an upgrade never
  reads an answer written before it.

The entry is kept under ``answers/`` of the cache root (:mod:`landau.support.cachedir`: the
same folder checks, the same per-user key).  Its file is one header line,
``landau-answer/1 <HMAC>``, then a JSON document (the command, its arguments, the fingerprint,
the exit code and the output text).  The HMAC-SHA256 covers the key and the JSON text and is
checked before the JSON is parsed; the document's command, arguments and fingerprint must then
equal the caller's.  An entry that fails either check — truncated, edited, written under
another key, copied from another entry — is reported once (a logged warning naming the file),
removed and recomputed.  Writes are atomic (:func:`landau.support.io.atomic_write`); a failed
write is one :class:`~landau.support.cachedir.CacheWarning`, never a failed command.
``LANDAU_CACHE=off`` (or :func:`landau.support.cache.set_enabled` with ``False``) turns the store
off with the rest of the cache.

This module imports neither sympy nor numba.
"""

from __future__ import annotations

import hashlib
import importlib.util
import json
import logging
import os
import platform
import sys
from pathlib import Path
from typing import Sequence

from landau.support import cachedir

logger = logging.getLogger(__name__)

#: the format of an entry (part of the key and of its header)
MAGIC = "landau-answer/1"
#: the sub-folder of the cache root holding the answers
KIND = "answers"
#: the packages whose source decides an answer
PACKAGES = ("landau", "landau.laws", "landau.verify", "landau.paper_figures")
#: the libraries whose versions are part of the fingerprint
LIBRARIES = ("landau-friction", "sympy", "numpy", "scipy", "numba", "llvmlite", "mpmath", "python-flint")

_FINGERPRINT: str | None = None


def enabled() -> bool:
    """Whether the store is used: the switch of :mod:`landau.support.cache` (its in-process
    setting when that module is loaded, else ``$LANDAU_CACHE``)."""
    cache = sys.modules.get("landau.support.cache")
    if cache is not None:
        return bool(cache.enabled())
    return os.environ.get("LANDAU_CACHE", "on").strip().lower() not in ("0", "off", "false", "no")


def _source_folders() -> list[Path]:
    folders: list[Path] = []
    for name in PACKAGES:
        try:
            spec = importlib.util.find_spec(name)
        except (ImportError, ValueError):
            spec = None
        for loc in (spec.submodule_search_locations or []) if spec is not None else []:
            if Path(loc) not in folders:
                folders.append(Path(loc))
    return folders


def fingerprint() -> str:
    """SHA-256 (hex) of every ``.py`` file of :data:`PACKAGES` (relative path and bytes), the
    versions of :data:`LIBRARIES`, Python's version and the machine type; computed once a process."""
    global _FINGERPRINT
    if _FINGERPRINT is None:
        from importlib.metadata import PackageNotFoundError, version

        h = hashlib.sha256(f"{MAGIC}\0{sys.version}\0{platform.machine()}\0".encode())
        for lib in LIBRARIES:
            try:
                h.update(f"{lib} {version(lib)}\0".encode())
            except PackageNotFoundError:
                h.update(f"{lib} -\0".encode())
        for folder in _source_folders():
            for path in sorted(folder.rglob("*.py")):
                if "__pycache__" in path.parts:
                    continue
                h.update(os.fsencode(path.relative_to(folder.parent)) + b"\0")
                try:
                    h.update(path.read_bytes())
                except OSError:
                    h.update(b"unreadable")
                h.update(b"\0")
        _FINGERPRINT = h.hexdigest()
    return _FINGERPRINT


def key(command: str, argv: Sequence[str]) -> str:
    """The entry's name: SHA-256 of the format, :func:`fingerprint`, the command and its arguments."""
    h = hashlib.sha256()
    for part in (MAGIC, fingerprint(), command, json.dumps(list(argv))):
        h.update(part.encode("utf-8", "surrogatepass"))
        h.update(b"\0")
    return h.hexdigest()


def _folder() -> Path | None:
    root = cachedir.usable_root()
    if root is None:
        return None
    folder = root / KIND
    return folder if cachedir.secure_folder(folder) else None


def _discard(path: Path, why: str) -> None:
    logger.warning("ignoring cache entry %s (%s); it is recomputed", path, why)
    try:
        path.unlink()
    except OSError:
        pass


def load(command: str, argv: Sequence[str]) -> tuple[int, str] | None:
    """The stored ``(exit code, output text)`` of ``command`` with ``argv``, or None (no entry,
    store off or unsafe, or an entry that does not verify — which is then reported and removed)."""
    if not enabled():
        return None
    folder = _folder()
    if folder is None:
        return None
    name = key(command, argv)
    path = folder / f"{name}.json"
    body = cachedir.read_signed(path, MAGIC, KIND, name, _discard)
    if body is None:
        return None
    try:
        doc = json.loads(body)
    except ValueError:
        _discard(path, "not JSON")
        return None
    if not (isinstance(doc, dict) and doc.get("command") == command and doc.get("argv") == list(argv)
            and doc.get("fingerprint") == fingerprint() and type(doc.get("exit_code")) is int
            and isinstance(doc.get("output"), str)):
        _discard(path, "it is the answer of another command, arguments or code")
        return None
    return doc["exit_code"], doc["output"]


def store(command: str, argv: Sequence[str], exit_code: int, output: str) -> None:
    """Keep ``output`` (the exact text printed on stdout) and ``exit_code`` of ``command`` with
    ``argv``, signed and written atomically; a failed write is one warning."""
    if not enabled():
        return
    folder = _folder()
    if folder is None:
        return
    from landau.errors import OutputError
    from landau.support.io import atomic_write

    name = key(command, argv)
    body = json.dumps({"command": command, "argv": list(argv), "fingerprint": fingerprint(),
                       "exit_code": int(exit_code), "output": output}, ensure_ascii=True).encode()
    mac = cachedir.sign(MAGIC, KIND, name, body)
    if mac is None:
        return
    data = f"{MAGIC} {mac}\n".encode() + body
    try:
        atomic_write(folder / f"{name}.json", lambda fh: fh.write(data), mode="wb")
    except (OSError, OutputError) as exc:
        cachedir.warn_once(f"write {cachedir.cache_root()}",
                           f"could not write to the cache ({exc}); results are computed and returned, but not kept")
