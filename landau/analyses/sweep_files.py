"""The files of a sweep: its netCDF backend, atomic writes, temporaries and write errors.

:mod:`landau.analyses.sweep_engine` stores a sweep's table here.  A write goes to a temporary file
next to the target, named after this host and process, then :func:`os.replace` (a reader never
sees half a file); the temporary is removed whatever ends the write, and one left by a killed
run is removed by the next run once its writer is known dead (:func:`remove_stale_temporaries`).
A write that fails is an :class:`~landau.errors.OutputError` naming the file and its cause
(:func:`write_error`): the netCDF4 backend (HDF5) reports a full disk as "Permission denied" or
"NetCDF: HDF error", so a full disk is recognised by the free space left.

xarray and a netCDF backend (h5netcdf, netCDF4 or scipy) are needed only here, imported on first
use (``pip install landau-friction[sweep]``).
"""

from __future__ import annotations

import errno
import os
import socket
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np

from landau.errors import InputError, OutputError

if TYPE_CHECKING:
    from landau.analyses.sweep_engine import Grid


def _first_line(exc: BaseException) -> str:
    text = str(exc).strip()
    return f"{type(exc).__name__}: {(text.splitlines()[0] if text else '')[:300]}"


def _engine() -> str:
    import importlib.util

    for needs, engine in ((("netCDF4",), "netcdf4"), (("h5netcdf", "h5py"), "h5netcdf"), (("scipy",), "scipy")):
        if all(importlib.util.find_spec(name) is not None for name in needs):
            return engine
    raise InputError("writing a sweep needs a netCDF backend: pip install 'landau-friction[sweep]'")


def xarray():
    """The xarray module, or an InputError saying how to install it."""
    try:
        import xarray as xr
    except ImportError:
        raise InputError("sweeps return an xarray Dataset: pip install 'landau-friction[sweep]'") from None
    return xr


def _temporary(path: Path) -> Path:
    """The temporary file of this process next to ``path`` (host and pid in its name)."""
    return path.with_name(f".{path.name}.{socket.gethostname()}.{os.getpid()}.tmp")


def _alive(pid: int) -> bool:
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return False
    except PermissionError:   # another user's process: alive
        return True
    return True


def remove_stale_temporaries(path: Path) -> list[Path]:
    """Remove the temporaries of ``path`` left by earlier runs on this host that were killed
    (SIGKILL, a power cut: no ``finally`` ran) and return them.  Only a temporary whose writer is
    known dead goes: its host is this one and no process has its pid (also the older name
    ``.NAME.PID.tmp``); one of another host, or of a live process, is left alone."""
    host = socket.gethostname()
    gone = []
    try:
        names = os.listdir(path.parent if str(path.parent) else ".")
    except OSError:
        return []
    prefix = f".{path.name}."
    for name in names:
        if not (name.startswith(prefix) and name.endswith(".tmp")):
            continue
        middle = name[len(prefix):-len(".tmp")]
        owner, _, pid = middle.rpartition(".")
        if not pid.isdigit() or owner not in ("", host) or int(pid) == os.getpid() or _alive(int(pid)):
            continue
        try:
            (path.parent / name).unlink()
            gone.append(path.parent / name)
        except OSError:
            pass
    return gone


def _free_bytes(folder: Path) -> int | None:
    try:
        st = os.statvfs(folder)
    except (OSError, AttributeError):
        return None
    return int(st.f_bavail) * int(st.f_frsize)


#: free bytes below which a folder's device counts as full when a write failed without saying why
NEARLY_FULL = 1 << 20


def write_error(exc: BaseException, path: Path, need: int) -> OutputError:
    """The OutputError naming ``path`` and the cause of a failed write of about ``need`` bytes.

    A full disk is reported as such whatever the backend raised: netCDF4 (HDF5) reports a disk
    full at the file's creation as ``EACCES`` ("Permission denied") and one full during the write
    as ``RuntimeError('NetCDF: HDF error')``, so the free space of the folder is asked
    (``os.statvfs``) when the error is ``EACCES`` on a folder this process may write in, or not an
    OSError at all: less than the file's size (or than :data:`NEARLY_FULL`) free there is a full
    disk.  Any other errno is reported by its own ``os.strerror``."""
    folder = path.parent if str(path.parent) else Path(".")
    code = getattr(exc, "errno", None) if isinstance(exc, OSError) else None
    free = _free_bytes(folder)
    full = code == errno.ENOSPC or (
        (code in (errno.EACCES, None) and os.access(folder, os.W_OK)) and free is not None
        and free < max(need, NEARLY_FULL))
    if full:
        left = "" if free is None else f" ({free} bytes free there, about {need} needed)"
        return OutputError(f"cannot write {path}: no space left on device{left}")
    if code is not None:
        return OutputError(f"cannot write {path}: {os.strerror(code)}")
    return OutputError(f"cannot write {path}: {_first_line(exc)}")


def write_atomic(ds, path: Path) -> None:
    """Write ``ds`` to netCDF at ``path`` atomically: a temporary file next to it (this host's and
    this process's), then os.replace.  The temporary is removed whatever ends the write (an error,
    Ctrl-C, SIGTERM inside :func:`landau.support.lifetime.terminate_as_interrupt`).

    Raises
    ------
    OutputError
        The file cannot be written (:func:`write_error`: a full disk by that name, else the errno's
        own message).
    """
    tmp = _temporary(path)
    try:
        ds.to_netcdf(tmp, engine=_engine())
        os.replace(tmp, path)
    except (OSError, RuntimeError) as exc:   # RuntimeError: netCDF4's "NetCDF: HDF error" of a full disk
        raise write_error(exc, path, int(ds.nbytes)) from None
    finally:
        try:
            tmp.unlink()
        except FileNotFoundError:
            pass
        except OSError:   # the folder itself is gone or not writable any more: nothing to clean
            pass


def read_stored(path: Path, grid: Grid, attrs: dict[str, Any]):
    """The dataset stored at ``path`` if it is the same sweep (task, model, law, fixed parameters, grid);
    InputError if it holds another."""
    xr = xarray()
    try:
        with xr.open_dataset(path, engine=_engine()) as ds:
            ds = ds.load()
    except (OSError, ValueError) as exc:
        raise InputError(f"{path} exists but is not a readable sweep file ({_first_line(exc)}); "
                         "use another --out") from None
    for key in ("task", "model", "law", "law_declaration", "fixed_parameters", "task_options"):
        if str(ds.attrs.get(key, "")) != str(attrs.get(key, "")):
            raise InputError(f"{path} holds a different sweep ({key} differs); use another --out")
    for a in grid.axes:
        if a.name not in ds.coords or not np.array_equal(np.asarray(ds[a.name].values), np.asarray(a.values)):
            raise InputError(f"{path} holds a different sweep (the grid of {a.name} differs); use another --out")
    if tuple(ds["status"].dims) != grid.names:
        raise InputError(f"{path} holds a different sweep (its axes are {', '.join(ds['status'].dims)}); "
                         "use another --out")
    return ds
