"""The store of a sweep written to a file: a journal of finished chunks, then one checked netCDF file.

Why a journal, not netCDF appended in place.  Writing a run's results into the netCDF file itself
(netCDF4 variables written by slices) makes a write O(chunk), but HDF5, under netCDF4, is not
crash-safe: a process killed (SIGKILL, a node lost, a full disk) while HDF5 writes its metadata
can leave the file unreadable, and with it every point finished before.  A zarr store (one file
per chunk) is crash-safe but would be a new dependency and another format for ``--out``.  So a run
writes each batch of finished chunks as one small file of its own, atomically (a temporary,
then :func:`os.replace`: a killed run leaves whole parts or none), into a journal folder beside
the target (``map.nc`` → ``.map.nc.parts/``): a write costs O(batch), whatever was written
before (measured: ``benchmarks/sweep_store_bench.py``).  The netCDF file a user reads — the same
labelled Dataset as before, the same variables, attributes and units — is assembled from the
journal and the previous file at the end of the run, also when the run is interrupted (Ctrl-C,
SIGTERM), streaming block by block (:data:`BLOCK` points at a time: the memory of the chunking,
never of the grid), written atomically, and the journal removed.  A killed run leaves its
journal; the next run takes its parts as finished points (none computed twice).

Why a finished file is not trusted.  A file can be edited, truncated by hand, written by another
version, or be another sweep's.  Another sweep's file (task, model, law, fixed parameters, task
options, grid) is refused (:func:`~landau.analyses.sweep_files.sweep_difference`).  Of a file of
this sweep, before any point is reused (:func:`distrust`): every status is a known one, every
variable the file lists (``variables``) is there, every variable that was finite at every ``ok``
point when written (``finite_where_ok``) still is, the landau version is this one, and the
SHA-256 of its results (``results_sha256``: each variable's values streamed in C order, its
name, dimensions and the sweep's identity; written with the file, so atomically) matches.  A
file that fails any check is not reused: every point is recomputed and the reason said (a
warning; ``landau sweep`` prints it and puts it in its JSON document).

netCDF4 (the ``sweep`` extra) is needed here: it writes a file by slices, which xarray cannot.
"""

from __future__ import annotations

import hashlib
import io
import json
import os
import socket
import time
import zipfile
from pathlib import Path
from typing import TYPE_CHECKING, Any, Iterator

import numpy as np

from landau.errors import InputError

if TYPE_CHECKING:
    from landau.analyses.sweep_engine import ChunkResult, Grid

#: points read or written at a time when a file is assembled or checked (the memory of a block)
BLOCK = 1 << 16
#: statuses a stored point may have
KNOWN = ("ok", "no-hopf", "degenerate", "outside-validity", "failed", "pending")
#: attributes that change at every run and are not part of the checksum
VOLATILE = ("computed", "reused", "results_sha256", "finite_where_ok", "variables")


def netcdf4():
    """The netCDF4 module, or an InputError saying how to install it."""
    try:
        import netCDF4
    except ImportError:
        raise InputError("writing a sweep needs netCDF4: pip install 'landau-friction[sweep]'") from None
    return netCDF4


# ---------------------------------------------------------------------------------------------
# flat index ranges as hyperrectangles of the grid
# ---------------------------------------------------------------------------------------------
def blocks(start: int, stop: int, shape: tuple[int, ...]) -> list[tuple[slice, ...]]:
    """The flat C-order range ``start:stop`` of an array of ``shape`` as at most ``2 ndim - 1``
    hyperrectangles (tuples of slices), in C order: their elements, each flattened in C order and
    concatenated, are the range."""
    if start >= stop:
        return []
    if len(shape) == 1:
        return [(slice(start, stop),)]
    inner = int(np.prod(shape[1:], dtype=np.int64))
    i0, r0 = divmod(start, inner)
    i1, r1 = divmod(stop, inner)
    if i0 == i1:
        return [(slice(i0, i0 + 1), *b) for b in blocks(r0, r1, shape[1:])]
    out: list[tuple[slice, ...]] = []
    if r0:
        out += [(slice(i0, i0 + 1), *b) for b in blocks(r0, inner, shape[1:])]
        i0 += 1
    if i1 > i0:
        out.append((slice(i0, i1), *(slice(0, n) for n in shape[1:])))
    if r1:
        out += [(slice(i1, i1 + 1), *b) for b in blocks(0, r1, shape[1:])]
    return out


def runs(index: np.ndarray) -> list[tuple[int, int, np.ndarray]]:
    """The flat indices ``index`` as runs of consecutive values: ``(start, stop, positions)`` with
    ``positions`` where the run's values are in ``index``."""
    index = np.asarray(index, dtype=np.int64)
    if not len(index):
        return []
    order = np.argsort(index, kind="stable")
    s = index[order]
    cuts = np.flatnonzero(np.diff(s) != 1) + 1
    out = []
    for a, b in zip(np.concatenate([[0], cuts]), np.concatenate([cuts, [len(s)]]), strict=True):
        out.append((int(s[a]), int(s[b - 1]) + 1, order[a:b]))
    return out


# ---------------------------------------------------------------------------------------------
# the journal
# ---------------------------------------------------------------------------------------------
def journal_path(path: Path) -> Path:
    """The journal folder of the sweep file ``path``: ``map.nc`` → ``.map.nc.parts``."""
    return path.with_name(f".{path.name}.parts")


def _pack_strings(values: list[str]) -> tuple[np.ndarray, np.ndarray]:
    encoded = [str(v).encode() for v in values]
    offsets = np.cumsum([0, *map(len, encoded)]).astype(np.int64)
    return offsets, np.frombuffer(b"".join(encoded), dtype=np.uint8)


def _unpack_strings(offsets: np.ndarray, data: np.ndarray) -> list[str]:
    raw = data.tobytes()
    return [raw[a:b].decode() for a, b in zip(offsets[:-1], offsets[1:], strict=True)]


class Journal:
    """The parts of a run, one file per batch of finished chunks, written atomically.

    ``meta.json`` holds the sweep's identity: a journal of another sweep is refused, one of
    another landau version is discarded (its parts recomputed)."""

    def __init__(self, path: Path, identity: dict[str, Any]):
        self.folder = journal_path(path)
        self.identity = identity
        self.seq = 0

    def exists(self) -> bool:
        return self.folder.is_dir()

    def check(self) -> tuple[str, str] | None:
        """None if the journal is this sweep's (or there is none); else ``("other", why)`` for another
        sweep's journal, ``("stale", why)`` for one of another landau version (its parts are recomputed)."""
        if not self.exists():
            return None
        try:
            meta = json.loads((self.folder / "meta.json").read_text())
        except (OSError, ValueError):
            return "stale", "its journal has no readable meta.json"
        if meta == self.identity:
            return None
        same = {k: v for k, v in meta.items() if k != "landau_version"} == {
            k: v for k, v in self.identity.items() if k != "landau_version"}
        if same:
            return "stale", f"its journal was written by landau {meta.get('landau_version', '(unknown)')}"
        return "other", "its journal is of another sweep"

    def open(self) -> None:
        """Create the journal (and its meta.json, atomically) if missing; remove the temporaries of
        writers on this host that are dead (a killed run)."""
        from landau.analyses.sweep_files import _alive

        self.folder.mkdir(exist_ok=True)
        meta = self.folder / "meta.json"
        if not meta.exists():
            _atomic_bytes(meta, json.dumps(self.identity, sort_keys=True).encode())
        host = socket.gethostname()
        for name in os.listdir(self.folder):
            bits = name.split("~")
            if name.endswith(".tmp") and len(bits) == 4 and bits[1].isdigit() and bits[2] == host \
                    and int(bits[1]) != os.getpid() and not _alive(int(bits[1])):
                try:
                    (self.folder / name).unlink()
                except OSError:
                    pass

    def parts(self) -> list[Path]:
        """The parts, oldest first (a later part's point replaces an earlier one's: a failed point tried again)."""
        if not self.exists():
            return []
        return sorted(p for p in self.folder.iterdir() if p.suffix == ".npz")

    def write(self, res: ChunkResult) -> Path:
        """Write ``res`` as one part (atomically); O(len(res.index))."""
        arrays: dict[str, np.ndarray] = {"index": np.asarray(res.index, dtype=np.int64)}
        schema: dict[str, Any] = {}
        for name, arr in res.values.items():
            arr = np.asarray(arr, dtype=float)
            arrays[f"v:{name}"] = arr
            schema[name] = {"kind": "f", "width": None if arr.ndim == 1 else int(arr.shape[1])}
        for name, vals in {"status": res.status, "message": res.message, **res.strings}.items():
            offsets, data = _pack_strings(list(vals))
            arrays[f"o:{name}"], arrays[f"s:{name}"] = offsets, data
            if name not in ("status", "message"):
                schema[name] = {"kind": "s", "width": None}
        arrays["schema"] = np.frombuffer(json.dumps(schema).encode(), dtype=np.uint8)
        buf = io.BytesIO()
        savez: Any = np.savez   # (numpy's stub types the keyword arrays as its own flags)
        savez(buf, **arrays)
        self.seq += 1
        part = self.folder / f"{time.time_ns():020d}-{os.getpid()}-{self.seq:06d}.npz"
        _atomic_bytes(part, buf.getvalue())
        return part

    @staticmethod
    def read(part: Path) -> tuple[np.ndarray, dict[str, Any], dict[str, np.ndarray], dict[str, list[str]]]:
        """A part: its flat indices, schema, variables and strings (status and message among them)."""
        try:
            with np.load(part, allow_pickle=False) as z:
                index = z["index"]
                schema = json.loads(z["schema"].tobytes().decode())
                values = {k[2:]: z[k] for k in z.files if k.startswith("v:")}
                strings = {k[2:]: _unpack_strings(z[f"o:{k[2:]}"], z[k]) for k in z.files if k.startswith("s:")}
        except (OSError, ValueError, KeyError, zipfile.BadZipFile) as exc:
            raise InputError(f"{part}: a damaged part of a sweep's journal ({type(exc).__name__}); "
                             f"remove {part.parent} to recompute its points") from None
        return index, schema, values, strings

    @staticmethod
    def read_index(part: Path, what: str = "index") -> Any:
        """Only a part's flat indices (``what="index"``) or its schema (``"schema"``)."""
        try:
            with np.load(part, allow_pickle=False) as z:
                got = z[what]
        except (OSError, ValueError, KeyError, zipfile.BadZipFile) as exc:
            raise InputError(f"{part}: a damaged part of a sweep's journal ({type(exc).__name__}); "
                             f"remove {part.parent} to recompute its points") from None
        return json.loads(got.tobytes().decode()) if what == "schema" else got

    def remove(self) -> None:
        """Remove the journal: its parts first, its meta.json last (a removal cut short leaves a
        journal still known to be this sweep's)."""
        import shutil

        for part in self.parts():
            try:
                part.unlink()
            except OSError:
                pass
        shutil.rmtree(self.folder, ignore_errors=True)


def _atomic_bytes(path: Path, data: bytes) -> None:
    """``data`` to ``path`` through a temporary of this host and process, then os.replace."""
    tmp = path.with_name(f"~{os.getpid()}~{socket.gethostname()}~{path.name}.tmp")
    try:
        with open(tmp, "wb") as fh:
            fh.write(data)
        os.replace(tmp, path)
    finally:
        try:
            tmp.unlink()
        except OSError:
            pass


# ---------------------------------------------------------------------------------------------
# the netCDF file: schema, reading by blocks, checksum
# ---------------------------------------------------------------------------------------------
def file_schema(nc) -> dict[str, dict[str, Any]]:
    """The variables of an open netCDF sweep file (status and message excluded), in file order."""
    dims = set(nc.variables["status"].dimensions)
    out: dict[str, dict[str, Any]] = {}
    for name, var in nc.variables.items():
        if name in dims or name in ("status", "message"):
            continue
        kind = "s" if var.dtype is str or getattr(var.dtype, "kind", "") in "OUS" else "f"
        extra = [d for d in var.dimensions if d not in dims]
        out[name] = {"kind": kind, "width": int(len(nc.dimensions[extra[0]])) if extra else None}
    return out


def _read(var, sl: tuple[slice, ...]) -> np.ndarray:
    """The block ``sl`` (of the grid's axes) of a netCDF variable, flattened (C order; a per-point
    list keeps its last axis)."""
    var.set_auto_mask(False)
    extra = len(var.dimensions) - len(sl)
    arr = np.asarray(var[tuple(sl) + (slice(None),) * extra])
    if var.dtype is str:
        return arr.astype(object).reshape(-1)
    n = int(np.prod([s.stop - s.start for s in sl], dtype=np.int64))
    return arr.reshape(n, -1) if extra else arr.reshape(-1)


def flat_blocks(shape: tuple[int, ...], size: int | None = None) -> Iterator[tuple[int, int, list[tuple[slice, ...]]]]:
    """The grid of ``shape`` in flat ranges of ``size`` points (default :data:`BLOCK`), each with its
    hyperrectangles."""
    size = int(size or BLOCK)
    total = int(np.prod(shape, dtype=np.int64))
    for s in range(0, total, size):
        e = min(total, s + size)
        yield s, e, blocks(s, e, shape)


def read_flat(var, start: int, stop: int, shape: tuple[int, ...]) -> np.ndarray:
    """The flat range ``start:stop`` of a grid-shaped netCDF variable (C order)."""
    parts = [_read(var, sl) for sl in blocks(start, stop, shape)]
    return np.concatenate(parts) if len(parts) > 1 else parts[0]


def _hash_update(h, arr: np.ndarray, kind: str) -> None:
    if kind == "s":
        h.update("".join(f"{v}\x00" for v in arr).encode())
    else:
        h.update(np.ascontiguousarray(arr, dtype="<f8").tobytes())


def scan(nc, shape: tuple[int, ...], identity: dict[str, Any]) -> dict[str, Any]:
    """One pass over an open sweep file: its checksum (:func:`checksum_of`), the variables finite
    at every ``ok`` point, the statuses and their counts, the first failed point's message.  O(BLOCK)
    memory."""
    schema = file_schema(nc)
    kinds = {**{k: v["kind"] for k, v in schema.items()}, "status": "s", "message": "s"}
    hashes = {k: hashlib.sha256() for k in kinds}
    finite = {k for k, v in schema.items() if v["kind"] == "f"}
    counts: dict[str, int] = {}
    first_failed: str | None = None      # the message of the first failed point (a run that failed says it)
    for s, e, _ in flat_blocks(shape):
        status = read_flat(nc.variables["status"], s, e, shape)
        ok = status == "ok"
        names, n = np.unique(status.astype(str), return_counts=True)
        for name, c in zip(names, n, strict=True):
            counts[str(name)] = counts.get(str(name), 0) + int(c)
        for name, kind in kinds.items():
            arr = status if name == "status" else read_flat(nc.variables[name], s, e, shape)
            _hash_update(hashes[name], arr, kind)
            if name == "message" and first_failed is None and np.any(status == "failed"):
                first_failed = str(arr[status == "failed"][0])
            if name in finite and ok.any():
                vals = arr[ok]
                if not np.all(np.isfinite(vals)):
                    finite.discard(name)
    total = hashlib.sha256(json.dumps(identity, sort_keys=True, default=str).encode())
    for name in sorted(kinds):
        total.update(f"{name}:{','.join(nc.variables[name].dimensions)}:{hashes[name].hexdigest()}\n".encode())
    return {"sha256": total.hexdigest(), "finite": sorted(finite), "status": counts, "schema": schema,
            "first_failed": first_failed}


def identity_of(attrs: dict[str, Any]) -> dict[str, Any]:
    """The attributes a file's checksum covers: all but the counts of a run and the checksum's own."""
    return {k: (v.item() if isinstance(v, np.generic) else v) for k, v in sorted(attrs.items()) if k not in VOLATILE}


def distrust(nc, shape: tuple[int, ...]) -> str | None:
    """Why the open sweep file ``nc`` of this sweep must not be reused (None: it may be).

    Checked in order: the landau version, the variables the file lists, the statuses, the
    finiteness at ``ok`` points, the checksum."""
    from landau import __version__

    attrs = {k: nc.getncattr(k) for k in nc.ncattrs()}
    if str(attrs.get("landau_version", "")) != __version__:
        return f"it was written by landau {attrs.get('landau_version', '(unknown)')}, this is {__version__}"
    if "results_sha256" not in attrs or "variables" not in attrs:
        return "it has no checksum of its results"
    try:
        listed = json.loads(str(attrs["variables"]))
        finite_listed = json.loads(str(attrs.get("finite_where_ok", "[]")))
    except ValueError:
        return "its list of variables is not readable"
    missing = [v for v in listed if v not in nc.variables]
    if missing:
        return f"its variable {missing[0]} is missing"
    facts = scan(nc, shape, identity_of(attrs))
    unknown = sorted(set(facts["status"]) - set(KNOWN))
    if unknown:
        return f"it has a status {unknown[0]!r} that no sweep gives"
    lost = [v for v in finite_listed if v not in facts["finite"]]
    if lost:
        return f"its {lost[0]} is not finite at a point whose status is ok"
    if facts["sha256"] != str(attrs["results_sha256"]):
        return "the checksum of its results differs (the file was changed after it was written)"
    return None


# ---------------------------------------------------------------------------------------------
# writing the file: by blocks from the previous file and the journal
# ---------------------------------------------------------------------------------------------
def write_flat(var, start: int, stop: int, shape: tuple[int, ...], data: np.ndarray) -> None:
    """``data`` (flat, C order; a per-point list as rows) into the flat range ``start:stop`` of a
    grid-shaped netCDF variable."""
    at = 0
    for sl in blocks(start, stop, shape):
        sizes = [s.stop - s.start for s in sl]
        n = int(np.prod(sizes, dtype=np.int64))
        piece = data[at:at + n]
        at += n
        if piece.ndim == 2:
            var[tuple(sl) + (slice(0, piece.shape[1]),)] = piece.reshape(*sizes, piece.shape[1])
        else:
            var[sl] = piece.reshape(sizes)


def _default(kind: str, width: int | None, n: int, name: str) -> np.ndarray:
    if kind == "s":
        return np.full(n, "pending" if name == "status" else "", dtype=object)
    return np.full((n, width) if width else n, np.nan)


def merged_schema(schemas: list[dict[str, Any]]) -> dict[str, dict[str, Any]]:
    """One schema from several (the order of first appearance; a per-point list as wide as the widest)."""
    out: dict[str, dict[str, Any]] = {}
    for schema in schemas:
        for name, spec in schema.items():
            have = out.setdefault(name, dict(spec))
            if spec["width"] is not None:
                have["width"] = max(int(have["width"] or 0), int(spec["width"]))
    floats = {k: v for k, v in out.items() if v["kind"] == "f"}
    return {**floats, **{k: v for k, v in out.items() if v["kind"] == "s"}}


def _create(tmp: Path, grid: Grid, schema: dict[str, dict[str, Any]], units: dict[str, str]):
    """The netCDF4 file of ``grid`` with the variables of ``schema``, as xarray would write them."""
    nc = netcdf4().Dataset(tmp, "w", format="NETCDF4")
    dims = tuple(grid.names)
    for a in grid.axes:
        nc.createDimension(a.name, len(a.values))
        coord = nc.createVariable(a.name, "f8", (a.name,))
        coord[:] = np.asarray(a.values, dtype=float)
        if a.units:
            coord.setncattr("units", a.units)
    for name, spec in schema.items():
        if spec["kind"] == "s":
            nc.createVariable(name, str, dims)
            continue
        extra = ()
        if spec["width"] is not None:
            nc.createDimension(f"{name}_index", int(spec["width"]))
            extra = (f"{name}_index",)
        var = nc.createVariable(name, "f8", dims + extra, fill_value=np.nan)
        if units.get(name):
            var.setncattr("units", units[name])
    status = nc.createVariable("status", str, dims)
    status.setncattr("meaning", "ok, or why the point has no result: no-hopf, degenerate, outside-validity, "
                                "failed; pending: not computed yet")
    nc.createVariable("message", str, dims)
    return nc


def _fill_base(nc, old, grid: Grid, schema: dict[str, dict[str, Any]], covered: np.ndarray) -> None:
    """The points of the new file from the previous file (``old``, None: none or not trusted) or
    pending, in the blocks where a point is not ``covered`` by the journal (whose parts give every
    variable of their points: a block they cover whole is not written twice)."""
    names = [*schema, "status", "message"]
    for s, e, _ in flat_blocks(grid.shape):
        if covered[s:e].all():
            continue
        for name in names:
            spec = schema.get(name, {"kind": "s", "width": None})
            data = _default(spec["kind"], spec["width"], e - s, name)
            if old is not None and name in old.variables:
                got = read_flat(old.variables[name], s, e, grid.shape)
                if data.ndim == 2:
                    data[:, :got.shape[1]] = got.reshape(e - s, -1)
                else:
                    data = got if spec["kind"] == "s" else got.astype(float)
            write_flat(nc.variables[name], s, e, grid.shape, data)


def _overlay(nc, part: Path, grid: Grid, schema: dict[str, dict[str, Any]]) -> None:
    """The points of one journal part into the new file (every variable: a recomputed point replaces
    all of the old one's)."""
    index, _, values, strings = Journal.read(part)
    for start, stop, pos in runs(index):
        n = stop - start
        for name, spec in [*schema.items(), ("status", {"kind": "s", "width": None}),
                           ("message", {"kind": "s", "width": None})]:
            data = _default(spec["kind"], spec["width"], n, name)
            if spec["kind"] == "s" and name in strings:
                data = np.array([strings[name][j] for j in pos], dtype=object)
            elif name in values:
                got = np.asarray(values[name])[pos]
                if data.ndim == 2:
                    data[:, :got.reshape(n, -1).shape[1]] = got.reshape(n, -1)
                else:
                    data = got.astype(float)
            write_flat(nc.variables[name], start, stop, grid.shape, data)


def seal(nc, shape: tuple[int, ...]) -> dict[str, Any]:
    """Write the checksum, the variables and those finite at every ok point into the open file ``nc``
    (:func:`scan`); its facts returned."""
    attrs = {k: nc.getncattr(k) for k in nc.ncattrs()}
    facts = scan(nc, shape, identity_of(attrs))
    nc.setncattr("variables", json.dumps([*facts["schema"], "status", "message"]))
    nc.setncattr("finite_where_ok", json.dumps(facts["finite"]))
    nc.setncattr("results_sha256", facts["sha256"])
    return facts


def _attr(v: Any) -> Any:
    if isinstance(v, (bool, np.bool_)):
        return int(v)
    if isinstance(v, (int, float, str, np.integer, np.floating)):
        return v
    return str(v)


def assemble(path: Path, journal: Journal, grid: Grid, attrs: dict[str, Any], units: dict[str, str],
             base: bool) -> dict[str, Any]:
    """Write the sweep file ``path`` from the previous file (if ``base``: it exists and is trusted) and
    the journal's parts, block by block, atomically (a temporary, then os.replace), sealed
    (:func:`seal`); then remove the journal.  Returns the file's facts (statuses, variables).

    Raises
    ------
    OutputError
        The file cannot be written (:func:`~landau.analyses.sweep_files.write_error`).
    """
    from landau.analyses.sweep_files import _temporary, write_error

    nc4 = netcdf4()
    parts = journal.parts()
    old = nc4.Dataset(path, "r") if base and path.exists() else None
    tmp = _temporary(path)
    schemas: list[dict[str, Any]] = []
    try:
        schemas = [] if old is None else [file_schema(old)]
        schemas += [Journal.read_index(p, "schema") for p in parts]
        schema = merged_schema(schemas)
        covered = np.zeros(grid.size, dtype=bool)   # one flag a point, as the run's own
        for p in parts:
            covered[Journal.read_index(p)] = True
        nc = _create(tmp, grid, schema, units)
        try:
            nc.setncatts({k: _attr(v) for k, v in attrs.items()})
            _fill_base(nc, old, grid, schema, covered)
            del covered
            for part in parts:
                _overlay(nc, part, grid, schema)
            nc.sync()
            facts = seal(nc, grid.shape)
        finally:
            nc.close()
        if old is not None:
            old.close()
            old = None
        os.replace(tmp, path)
    except (OSError, RuntimeError) as exc:
        raise write_error(exc, path, grid.size * 8 * (len(schemas[0]) if schemas else 4)) from None
    finally:
        if old is not None:
            old.close()
        try:
            tmp.unlink()
        except OSError:
            pass
    journal.remove()
    return facts


# ---------------------------------------------------------------------------------------------
# the table of a run written to a file
# ---------------------------------------------------------------------------------------------
#: points buffered before a part is written (a part is also written after ``write_every`` seconds)
FLUSH_POINTS = 4096
#: the statuses of a point a re-run computes (again)
TODO = ("pending", "failed")
#: the exceptions of a failure that may not repeat (memory, time, a lost worker, the operating system): a
#: point failed so is computed again by a re-run; any other failure (a parameter outside its domain, a
#: value beyond float64, an integration that cannot succeed) is deterministic and is kept, said once
TRANSIENT = ("MemoryError", "TimeoutError", "BudgetError", "BrokenProcessPool", "OSError", "CancelledError",
             "KilledWorker", "CommClosedError")


def to_compute(status, message) -> tuple[np.ndarray, np.ndarray]:
    """(which points a re-run computes, which failed points it keeps): it computes the pending ones and
    those failed for a :data:`TRANSIENT` reason (the message's leading exception name)."""
    status = np.asarray(status, dtype=object)
    failed = status == "failed"
    transient = np.array([str(m).split(":", 1)[0] in TRANSIENT for m in np.asarray(message, dtype=object)],
                         dtype=bool).reshape(status.shape) if failed.any() else np.zeros(status.shape, dtype=bool)
    todo = (status == "pending") | (failed & transient)
    return todo, failed & ~transient


def _difference(nc, attrs: dict[str, Any], grid: Grid) -> str | None:
    """What makes the open file ``nc`` another sweep than the one of ``attrs`` over ``grid``."""
    from landau.analyses.sweep_files import IDENTITY

    have = {k: nc.getncattr(k) for k in nc.ncattrs()}
    for key in IDENTITY:
        if str(have.get(key, "")) != str(attrs.get(key, "")):
            return f"{key} differs"
    if "status" not in nc.variables:
        return "it has no status"
    for a in grid.axes:
        if a.name not in nc.variables or not np.array_equal(np.asarray(nc.variables[a.name][:]),
                                                           np.asarray(a.values)):
            return f"the grid of {a.name} differs"
    if tuple(nc.variables["status"].dimensions) != grid.names:
        return f"its axes are {', '.join(nc.variables['status'].dimensions)}"
    return None


class FileTable:
    """The points of a run with a file: finished chunks to the :class:`Journal` as they come
    (O(chunk) a write), the file assembled at the end (:func:`assemble`).  In memory: one flag a point
    (what is still to compute) and the results of at most :data:`FLUSH_POINTS` points."""

    def __init__(self, path: Path, grid: Grid, units: dict[str, str], attrs: dict[str, Any],
                 write_every: float = 5.0):
        from landau import __version__
        from landau.analyses.sweep_files import IDENTITY

        self.path, self.grid, self.units = path, grid, dict(units)
        ident = {k: str(attrs.get(k, "")) for k in IDENTITY}
        ident["landau_version"] = __version__
        ident["grid"] = hashlib.sha256(b"".join(np.asarray(a.values, dtype="<f8").tobytes() + a.name.encode()
                                                for a in grid.axes)).hexdigest()
        self.journal = Journal(path, ident)
        self.shard: tuple[int, int] | None = None
        self.shard_points = grid.size
        self.every, self.last = float(write_every), time.monotonic()
        self.buffer: list[ChunkResult] = []
        self.buffered = 0
        self.base = False
        self.distrusted = ""
        self.kept_failed = 0
        self.facts: dict[str, Any] = {}

    def open(self, attrs: dict[str, Any]) -> np.ndarray:
        """The flags of the points to compute: not finished in a trusted file nor in the journal (a failed
        point is finished unless it failed for a :data:`TRANSIENT` reason; :func:`to_compute`).

        Raises
        ------
        InputError
            The file or the journal is of another sweep, or the file is not a readable sweep file.
        """
        from landau.analyses.sweep_files import _first_line, remove_stale_temporaries

        remove_stale_temporaries(self.path)
        todo = np.ones(self.grid.size, dtype=bool)
        kept = np.zeros(self.grid.size, dtype=bool)     # failed points kept: their failure would repeat
        notes = []
        if self.path.exists():
            try:
                nc = netcdf4().Dataset(self.path, "r")
            except OSError as exc:
                raise InputError(f"{self.path} exists but is not a readable sweep file; use another --out "
                                 f"({_first_line(exc)})") from None
            try:
                why = _difference(nc, attrs, self.grid)
                if why is not None:
                    raise InputError(f"{self.path} holds a different sweep ({why}); use another --out")
                bad = distrust(nc, self.grid.shape)
                if bad is not None:
                    notes.append(bad)
                else:
                    self.base = True
                    for s, e, _ in flat_blocks(self.grid.shape):
                        status = read_flat(nc.variables["status"], s, e, self.grid.shape)
                        message = read_flat(nc.variables["message"], s, e, self.grid.shape)
                        todo[s:e], kept[s:e] = to_compute(status, message)
            finally:
                nc.close()
        check = self.journal.check()
        if check is not None:
            if check[0] == "other":
                raise InputError(f"{self.path} holds a different sweep ({check[1]}); use another --out")
            notes.append(check[1])
            self.journal.remove()
        for part in self.journal.parts():
            index, _, _, strings = Journal.read(part)
            todo[index], kept[index] = to_compute(strings["status"], strings["message"])
        if notes:
            self.distrusted = f"{self.path} is not reused: {'; '.join(notes)}; its points are computed again"
        self.kept_failed = int(np.count_nonzero(kept))
        try:
            self.journal.open()
        except OSError as exc:
            from landau.analyses.sweep_files import write_error

            raise write_error(exc, self.path, 1 << 16) from None
        return todo

    def put(self, res: ChunkResult) -> None:
        """Take a chunk's results; a part is written when :data:`FLUSH_POINTS` points or
        ``write_every`` seconds have gathered."""
        self.buffer.append(res)
        self.buffered += len(res.index)
        if self.buffered >= FLUSH_POINTS or time.monotonic() - self.last > self.every:
            self.flush()

    def flush(self) -> None:
        """Write the gathered results as one journal part (atomically)."""
        from landau.analyses.sweep_engine import _joined
        from landau.analyses.sweep_files import write_error

        if self.buffer:
            res = self.buffer[0] if len(self.buffer) == 1 else _joined(self.buffer)
            try:
                self.journal.write(res)
            except OSError as exc:
                raise write_error(exc, self.path, 64 * len(res.index)) from None
            self.buffer, self.buffered = [], 0
        self.last = time.monotonic()

    def record(self, i: int) -> dict[str, Any]:
        """Point ``i`` as stored (a continuation resumed): the latest part holding it, else the file."""
        for part in reversed(self.journal.parts()):
            index, _, values, strings = Journal.read(part)
            hit = np.flatnonzero(index == i)
            if len(hit):
                j = int(hit[-1])
                return {**{k: v[j] for k, v in values.items()}, **{k: v[j] for k, v in strings.items()
                                                                   if k != "message"}}
        out: dict[str, Any] = {}
        with netcdf4().Dataset(self.path, "r") as nc:
            for name in [*file_schema(nc), "status"]:
                out[name] = read_flat(nc.variables[name], i, i + 1, self.grid.shape)[0]
        return out

    def finish(self, attrs: dict[str, Any]) -> None:
        """Write what is gathered, then the file (:func:`assemble`)."""
        self.flush()
        self.facts = assemble(self.path, self.journal, self.grid, attrs, self.units, self.base)
        self.base = True

    def dataset(self, attrs: dict[str, Any] | None = None):
        """The file as a loaded xarray Dataset (its attributes are those it was written with)."""
        from landau.analyses.sweep_files import xarray

        with xarray().open_dataset(self.path, engine="netcdf4") as ds:
            return ds.load()
