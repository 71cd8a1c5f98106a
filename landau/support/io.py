"""Atomic file output: a result is either written whole or not at all.

The content is rendered in memory first; only then is a temporary file created next to the
target, written, flushed to disk (fsync) and renamed over the target, so a run killed while
rendering leaves nothing behind and one killed afterwards leaves either the old or the new file.
A symbolic link is written through (its target is replaced, the link kept); an existing file
keeps its permissions; anything that is not a regular file (a folder, a device) is refused.
Every failure is an :class:`~landau.errors.OutputError` naming the path.
"""

from __future__ import annotations

import io
import json
import os
import secrets
import stat
from pathlib import Path
from typing import Any, Callable

from landau.errors import OutputError

#: longest file name most file systems accept (NAME_MAX)
_NAME_MAX = 255


def _target(path: Path) -> Path:
    """The file actually written: ``path`` itself, or what a symbolic link points to."""
    if str(path) == "" or path.name in ("", ".", ".."):
        raise OutputError(f"output file name {str(path)!r} is empty or a folder")
    if path.is_symlink():
        path = Path(os.path.realpath(path))
    if path.exists() and not path.is_file():
        kind = "a folder" if path.is_dir() else "not a regular file"
        raise OutputError(f"cannot write {path}: it is {kind}")
    if len(os.fsencode(path.name)) > _NAME_MAX:
        raise OutputError(f"cannot write {path}: the file name is longer than {_NAME_MAX} bytes")
    return path


def check_output(path: str | os.PathLike) -> Path:
    """Refuse early (:class:`OutputError`) an output path that :func:`atomic_write` would refuse:
    empty, a folder, not a regular file, a name over NAME_MAX bytes.  Returns the path."""
    _target(Path(path))
    return Path(path)


def _temporary_name(path: Path) -> Path:
    """A hidden name next to ``path`` that never exceeds NAME_MAX when ``path``'s name does not."""
    token = secrets.token_hex(4)
    stem = os.fsencode(path.name)[: _NAME_MAX - len(token) - 6].decode("utf-8", "ignore")
    return path.with_name(f".{stem}.{token}.tmp")


def atomic_write(path: str | os.PathLike, writer: Callable[[Any], None], mode: str = "w") -> Path:
    """Call ``writer(fh)`` on an in-memory buffer, then write the result atomically to ``path``.

    Parameters
    ----------
    path : the target file (its folder is created if missing).
    writer : writes the content to the file object it is given.
    mode : "w" (text, UTF-8) or "wb" (bytes).

    Returns
    -------
    Path
        The path given.

    Raises
    ------
    OutputError
        The target is a folder or not a regular file, its name is too long, or the file
        system refuses (missing permission, read-only, full disk).
    """
    path = Path(path)
    target = _target(path)
    buf: io.StringIO | io.BytesIO = io.BytesIO() if "b" in mode else io.StringIO()
    writer(buf)
    data = buf.getvalue()
    payload = data if isinstance(data, bytes) else data.encode("utf-8")
    tmp: Path | None = None
    try:
        target.parent.mkdir(parents=True, exist_ok=True)
        if target.exists():
            perms = stat.S_IMODE(target.stat().st_mode)
        else:
            umask = os.umask(0)
            os.umask(umask)
            perms = 0o666 & ~umask
        tmp = _temporary_name(target)
        fd = os.open(tmp, os.O_WRONLY | os.O_CREAT | os.O_EXCL, 0o600)
        try:
            view = memoryview(payload)
            while view:
                n = os.write(fd, view)
                view = view[n:]
            os.fchmod(fd, perms)
            os.fsync(fd)
        finally:
            os.close(fd)
        os.replace(tmp, target)
        tmp = None
        try:  # make the rename itself durable
            dfd = os.open(target.parent, os.O_RDONLY)
            try:
                os.fsync(dfd)
            finally:
                os.close(dfd)
        except OSError:
            pass
    except OSError as exc:
        raise OutputError(f"cannot write {path}: {exc.strerror or exc}") from None
    finally:
        if tmp is not None:
            try:
                os.unlink(tmp)
            except OSError:
                pass
    return path


def atomic_write_text(path: str | os.PathLike, text: str) -> Path:
    return atomic_write(path, lambda fh: fh.write(text))


def atomic_write_json(path: str | os.PathLike, doc: Any) -> Path:
    return atomic_write(path, lambda fh: json.dump(doc, fh, indent=2, default=float))


def atomic_savefig(fig, path: str | os.PathLike, **kwargs) -> Path:
    """Save a matplotlib figure atomically (format from the suffix)."""
    path = Path(path)
    fmt = kwargs.pop("format", path.suffix.lstrip(".") or "png")
    return atomic_write(path, lambda fh: fig.savefig(fh, format=fmt, **kwargs), mode="wb")


def latex_escape(text: str) -> str:
    """``text`` safe inside LaTeX running text (a title, a name): special characters escaped,
    so a user string can never open a group or run a command (``}``, ``\\input{...}``)."""
    out = []
    for ch in str(text):
        if ch in "&%$#_{}":
            out.append("\\" + ch)
        elif ch == "\\":
            out.append(r"\textbackslash{}")
        elif ch == "~":
            out.append(r"\textasciitilde{}")
        elif ch == "^":
            out.append(r"\textasciicircum{}")
        elif ch in "\n\r\t":
            out.append(" ")
        elif ch.isprintable() and ord(ch) < 128:
            out.append(ch)
        else:
            out.append("?")
    return "".join(out)
