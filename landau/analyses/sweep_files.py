"""The files of a sweep: its netCDF backend, atomic writes, temporaries and write errors.

:mod:`landau.analyses.sweep_engine` stores a sweep's table here.  A write goes to a temporary file
next to the target, named after this host and process, then :func:`os.replace` (a reader never
sees half a file); the temporary is removed whatever ends the write, and one left by a killed
run is removed by the next run once its writer is known dead (:func:`remove_stale_temporaries`).
A write that fails is an :class:`~landau.errors.OutputError` naming the file and its cause
(:func:`write_error`): the netCDF4 backend (HDF5) reports a full disk as "Permission denied" or
"NetCDF: HDF error", so a full disk is recognised by the free space left.

The shards of one sweep (``shard=(I, N)``: :mod:`landau.analyses.sweep_engine`) are files named
after the sweep's file (:func:`shard_path`: ``map.nc`` → ``map.shard-3-of-8.nc``), so that N jobs
given the same ``--out`` never write one file, and joined by :func:`merge_files`: one Dataset
holding every finished point of the shards, refused for files of different sweeps (the identity
a resumed run checks, :func:`sweep_difference`), each shard's missing points reported.  A point
finished in a shard is the point of the unsharded run bit for bit (its chunk is the same), so the
merged file equals the unsharded run's file point for point.

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
    this process's), sealed (a sweep file's checksum, :func:`landau.analyses.sweep_store.seal`, with
    the netCDF4 backend), then os.replace.  The temporary is removed whatever ends the write (an error,
    Ctrl-C, SIGTERM inside :func:`landau.support.lifetime.terminate_as_interrupt`).

    Raises
    ------
    OutputError
        The file cannot be written (:func:`write_error`: a full disk by that name, else the errno's
        own message).
    """
    tmp = _temporary(path)
    try:
        engine = _engine()
        ds.to_netcdf(tmp, engine=engine)
        if engine == "netcdf4" and "status" in ds:   # a sweep file: its checksum, so that a run may reuse it
            from landau.analyses.sweep_store import netcdf4, seal

            with netcdf4().Dataset(tmp, "a") as nc:
                seal(nc, tuple(int(n) for n in nc.variables["status"].shape))
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


#: the attributes that make two files the same sweep (with the grid): what a resumed run checks
IDENTITY = ("task", "model", "law", "law_declaration", "fixed_parameters", "task_options")


def sweep_difference(ds, attrs: dict[str, Any], axes: list[tuple[str, np.ndarray]]) -> str | None:
    """What makes the dataset ``ds`` another sweep than the one of ``attrs`` over ``axes`` (its
    ``(name, values)`` in order): "law differs", "the grid of V differs", ...; None if the same."""
    for key in IDENTITY:
        if str(ds.attrs.get(key, "")) != str(attrs.get(key, "")):
            return f"{key} differs"
    if "status" not in ds:
        return "it has no status"
    for name, values in axes:
        if name not in ds.coords or not np.array_equal(np.asarray(ds[name].values), np.asarray(values)):
            return f"the grid of {name} differs"
    if tuple(ds["status"].dims) != tuple(name for name, _ in axes):
        return f"its axes are {', '.join(map(str, ds['status'].dims))}"
    return None


def _open(path: Path, what: str):
    """The dataset at ``path``, loaded and closed; InputError if it is not a readable netCDF file."""
    xr = xarray()
    try:
        with xr.open_dataset(path, engine=_engine()) as ds:
            return ds.load()
    except (OSError, ValueError) as exc:
        raise InputError(f"{path} {what} ({_first_line(exc)})") from None


def read_stored(path: Path, grid: Grid, attrs: dict[str, Any]):
    """The dataset stored at ``path`` if it is the same sweep (task, model, law, fixed parameters, grid);
    InputError if it holds another."""
    ds = _open(path, "exists but is not a readable sweep file; use another --out")
    why = sweep_difference(ds, attrs, [(a.name, np.asarray(a.values)) for a in grid.axes])
    if why is not None:
        raise InputError(f"{path} holds a different sweep ({why}); use another --out")
    return ds


# ---------------------------------------------------------------------------------------------
# shards
# ---------------------------------------------------------------------------------------------
def shard_path(out: str | os.PathLike, shard: tuple[int, int]) -> Path:
    """The file of shard ``(I, N)`` of the sweep written to ``out``: ``map.nc`` → ``map.shard-I-of-N.nc``."""
    path = Path(out)
    return path.with_name(f"{path.stem}.shard-{shard[0]}-of-{shard[1]}{path.suffix}")


#: the statuses of a point that is not finished (a merge takes a finished point first)
UNFINISHED = ("pending", "failed")


def _shard_label(ds, path: Path) -> tuple[int, int] | None:
    text = str(ds.attrs.get("shard", ""))
    if not text:
        return None
    try:
        i, n = (int(t) for t in text.split("/"))
    except ValueError:
        raise InputError(f"{path}: its shard attribute {text!r} is not I/N") from None
    return i, n


class _Merged:
    """The merged table: status, message and variables of every point, filled file by file."""

    def __init__(self, first):
        self.dims = tuple(first["status"].dims)
        self.shape = tuple(int(first.sizes[d]) for d in self.dims)
        self.coords = {d: first[d].copy() for d in self.dims}
        self.status = np.full(self.shape, "pending", dtype=object)
        self.message = np.full(self.shape, "", dtype=object)
        self.vars: dict[str, np.ndarray] = {}
        self.var_attrs: dict[str, dict] = {"status": dict(first["status"].attrs)}

    def take(self, ds) -> None:
        """The points of ``ds`` finished there and not here, then its failed points still pending here."""
        st = np.asarray(ds["status"].values, dtype=object)
        mine = np.asarray(self.status, dtype=object)
        finished_there = ~np.isin(st, UNFINISHED)
        mask = finished_there & np.isin(mine, UNFINISHED)
        mask |= (st == "failed") & (mine == "pending")
        if not mask.any():
            return
        for name, var in ds.data_vars.items():
            if name in ("status", "message"):
                continue
            self._put(name, var, mask)
        self.status[mask] = st[mask]
        self.message[mask] = np.asarray(ds["message"].values, dtype=object)[mask]

    def _put(self, name: str, var, mask: np.ndarray) -> None:
        arr = np.asarray(var.values)
        self.var_attrs.setdefault(name, dict(var.attrs))
        if arr.dtype.kind in "OUS":
            col = self.vars.setdefault(name, np.full(self.shape, "", dtype=object))
            col[mask] = arr.astype(object)[mask]
            return
        arr = arr.astype(float)
        col = self.vars.get(name)
        if col is None:
            col = self.vars[name] = np.full(arr.shape if arr.ndim > len(self.shape) else self.shape, np.nan)
        if arr.ndim > len(self.shape):   # a per-point list: widened to the longest, padded with NaN
            width = max(col.shape[-1], arr.shape[-1])
            if col.shape[-1] < width:
                wide = np.full((*self.shape, width), np.nan)
                wide[..., :col.shape[-1]] = col
                col = self.vars[name] = wide
            col[mask] = np.nan
            col[mask, :arr.shape[-1]] = arr[mask]
        else:
            col[mask] = arr[mask]

    def dataset(self, attrs: dict[str, Any]):
        xr = xarray()
        data: dict[str, Any] = {}
        for name, col in self.vars.items():
            dims = self.dims if col.ndim == len(self.dims) else (*self.dims, f"{name}_index")
            data[name] = (dims, col, self.var_attrs.get(name, {}))
        data["status"] = (self.dims, self.status, self.var_attrs.get("status", {}))
        data["message"] = (self.dims, self.message)
        return xr.Dataset(data, coords=self.coords, attrs=attrs)


def merge_files(paths: list[str | os.PathLike], out: str | os.PathLike | None) -> tuple[Any, dict[str, Any]]:
    """Join the shards ``paths`` of one sweep into one Dataset, written atomically to ``out``.

    Each point is taken from the first file where it is finished (any status but ``pending`` and
    ``failed``), else from one where it failed; a point finished in two files is the same
    computation (the same chunk), so which file gives it does not change it.  The files are read
    one at a time (the memory of the merged grid and one file).  The merged file holds no shard
    attributes: an unsharded run given it as ``--out`` resumes it (computes the points still missing).

    Returns
    -------
    (xarray.Dataset, dict)
        The merged Dataset and the report: per file its shard, its points, how many are finished,
        failed and pending; N (``shards``, None without a sharded file) and the shards of N not
        given; the merged statuses and pending points.

    Raises
    ------
    InputError
        No file, a file that is not a readable sweep, files of different sweeps (task, model, law
        declaration, fixed parameters, task options, grid), a shard given twice or shards of
        different N, ``out`` one of the shards or not a ``.nc`` file.
    OutputError
        ``out`` cannot be written.
    """
    if not paths:
        raise InputError("merge: give the shard files to merge")
    files = [Path(p) for p in paths]
    target = None if out is None else Path(out)
    if target is not None:
        if target.suffix.lower() not in (".nc", ".nc4", ".netcdf"):
            raise InputError(f"merge: the merged file {str(target)!r} is written as netCDF (.nc)")
        if any(target.resolve() == f.resolve() for f in files):
            raise InputError(f"merge: the merged file {target} is one of the shards; give another name")
    seen: dict[tuple[int, int], Path] = {}
    report: dict[str, Any] = {"files": []}
    merged: _Merged | None = None
    attrs: dict[str, Any] = {}
    axes: list[tuple[str, np.ndarray]] = []
    for f in files:
        if not f.is_file():
            raise InputError(f"merge: {f}: no such file")
        ds = _open(f, "is not a readable sweep file")
        if "status" not in ds or not ds.attrs.get("task"):
            raise InputError(f"merge: {f} is not a landau sweep file (no task or status)")
        if merged is None:
            attrs = dict(ds.attrs)
            axes = [(str(d), np.asarray(ds[d].values)) for d in ds["status"].dims]
            merged = _Merged(ds)
        else:
            why = sweep_difference(ds, attrs, axes)
            if why is not None:
                raise InputError(f"merge: {f} is a shard of another sweep than {files[0]} ({why})")
        label = _shard_label(ds, f)
        if label is not None:
            if label in seen:
                raise InputError(f"merge: shard {label[0]}/{label[1]} is given twice ({seen[label]} and {f})")
            if seen and next(iter(seen))[1] != label[1]:
                raise InputError(f"merge: {f} is shard {label[0]}/{label[1]}, the others are of "
                                 f"{next(iter(seen))[1]} shards")
            seen[label] = f
        report["files"].append(_file_report(ds, f, label))
        merged.take(ds)
    assert merged is not None
    n = next(iter(seen))[1] if seen else None
    report["shards"] = n
    report["missing_shards"] = [] if n is None else [i for i in range(1, n + 1) if (i, n) not in seen]
    keep = {k: v for k, v in attrs.items() if k not in ("shard", "shard_points", "computed", "reused")}
    ds = merged.dataset({**keep, "merged_from": ", ".join(f.name for f in files)})
    statuses, counts = np.unique(merged.status.astype(str), return_counts=True)
    report["status"] = {str(s): int(c) for s, c in zip(statuses, counts, strict=True)}
    report["points"] = int(merged.status.size)
    report["pending"] = int(np.count_nonzero(merged.status == "pending"))
    if target is not None:
        write_atomic(ds, target)
    return ds, report


def _file_report(ds, path: Path, label: tuple[int, int] | None) -> dict[str, Any]:
    """One file's part of a merge's report: its shard, its points, finished, failed, pending."""
    st = np.asarray(ds["status"].values, dtype=object)
    finished = int(np.count_nonzero(~np.isin(st, UNFINISHED)))
    failed = int(np.count_nonzero(st == "failed"))
    points = int(ds.attrs.get("shard_points", st.size)) if label is not None else int(st.size)
    return {"file": str(path), "shard": "" if label is None else f"{label[0]}/{label[1]}", "points": points,
            "finished": finished, "failed": failed, "pending": max(0, points - finished - failed)}
