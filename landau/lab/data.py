"""Laboratory friction records read from CSV: landau's own columns, or any other layout with a mapping.

A record is the time t, the load-point velocity V_lp (or the load-point displacement x_lp, from
which the velocity follows) and the friction coefficient μ at each sample.  landau's own columns are
``t``, ``x_lp``, ``V_lp`` and ``mu``, each optionally followed by its unit in brackets
(``V_lp [um/s]``); a unit-less column is SI.  Another program's layout is read with a mapping from
landau's names to its columns, e.g. rsfmodel's (Leeman et al., rsfmodel) results
``time``, ``loadpoint_displacement``, ``loadpoint_velocity``, ``friction`` in s, µm, µm/s
(:data:`FORMATS` ``"rsfmodel"``).  Every quantity is SI once read.

The load-point velocity of a sample holds until the next sample (rsfmodel's convention): when only
the displacement is given, V_lp[i] = (x_lp[i+1] − x_lp[i]) / (t[i+1] − t[i]).
"""

from __future__ import annotations

import csv
import math
import os
import re
from dataclasses import dataclass
from typing import Mapping

import numpy as np

from landau.errors import InputError
from landau.lab.units import KINDS, unit_kind

#: landau's column names and what each is
COLUMNS = {"t": "time (s)", "x_lp": "load-point displacement (m)", "V_lp": "load-point velocity (m/s)",
           "mu": "friction coefficient"}

#: known layouts: landau's name -> (the layout's column, its unit)
FORMATS: dict[str, dict[str, tuple[str, str]]] = {
    "landau": {"t": ("t", "s"), "x_lp": ("x_lp", "m"), "V_lp": ("V_lp", "m/s"), "mu": ("mu", "")},
    "rsfmodel": {"t": ("time", "s"), "x_lp": ("loadpoint_displacement", "um"),
                 "V_lp": ("loadpoint_velocity", "um/s"), "mu": ("friction", "")},
}

_DIMENSION = {"t": "time", "x_lp": "length", "V_lp": "velocity", "mu": "number"}


def unit_factor(unit: str, column: str) -> float:
    """The factor to SI of ``unit`` for landau's column ``column`` (e.g. "um/s" for V_lp: 1e-6), read by
    :func:`landau.lab.units.unit_kind`; an InputError where the unit is unknown or of another kind."""
    kind = _DIMENSION[column]
    u = "" if unit.strip() == "-" else unit
    try:
        got, factor = unit_kind(u)
    except InputError as exc:
        raise InputError(f"column {column!r}: {exc}") from None
    if got != kind:
        raise InputError(f"column {column!r}: the unit {unit!r} is of {got}, expected a {kind} "
                         f"({KINDS[kind][1]})")
    return float(factor)


@dataclass(frozen=True)
class LabData:
    """One record, SI.

    Attributes
    ----------
    t : ndarray
        Sample times (s), strictly increasing.
    V_lp : ndarray
        Load-point velocity of each sample (m/s), held until the next sample.
    mu : ndarray
        Friction coefficient.
    x_lp : ndarray
        Load-point displacement (m), from the record or the integral of V_lp.
    source : str
        Where it came from.
    """

    t: np.ndarray
    V_lp: np.ndarray
    mu: np.ndarray
    x_lp: np.ndarray
    source: str = ""

    def __len__(self) -> int:
        return int(self.t.size)


def _split_header(name: str) -> tuple[str, str | None]:
    m = re.fullmatch(r"\s*(.*?)\s*\[(.*)\]\s*", name)
    return (m.group(1), m.group(2)) if m else (name.strip(), None)


def _table(path: str | os.PathLike) -> tuple[list[str], list[list[str]]]:
    try:
        with open(path, newline="", encoding="utf-8") as fh:
            rows = [r for r in csv.reader(fh) if r and not r[0].lstrip().startswith("#")]
    except FileNotFoundError:
        raise InputError(f"no such data file: {os.fspath(path)}") from None
    except IsADirectoryError:
        raise InputError(f"{os.fspath(path)} is a folder, not a CSV file") from None
    except UnicodeDecodeError:
        raise InputError(f"{os.fspath(path)} is not a text (UTF-8) CSV file") from None
    if not rows:
        raise InputError(f"{os.fspath(path)} is empty: expected a header line and samples")
    return [h.strip() for h in rows[0]], rows[1:]


def read_csv(path: str | os.PathLike, *, columns: Mapping[str, str] | None = None,
             units: Mapping[str, str] | None = None, format: str = "landau") -> LabData:
    """Read a record from a CSV file (a header line, then one sample a line; ``#`` lines skipped).

    Parameters
    ----------
    path : path
        The file.
    columns : mapping, optional
        landau's name (``t``, ``x_lp``, ``V_lp``, ``mu``) -> the file's column, over the layout's own.
    units : mapping, optional
        landau's name -> the unit of its column (``"um/s"``, ``"mm"``, ``"s"``), over the layout's
        own and a unit in brackets in the header.
    format : str
        A layout of :data:`FORMATS` (``"landau"`` or ``"rsfmodel"``).

    Returns
    -------
    LabData

    Raises
    ------
    InputError
        A missing column, a value that is not a number, a NaN row, times that do not increase, a
        negative velocity, or too few samples, each named.
    """
    if format not in FORMATS:
        raise InputError(f"unknown data format {format!r} (known: {', '.join(FORMATS)})")
    layout = {k: list(v) for k, v in FORMATS[format].items()}
    for name, col in (columns or {}).items():
        if name not in COLUMNS:
            raise InputError(f"unknown column name {name!r} in the mapping (landau's names: {', '.join(COLUMNS)})")
        layout[name][0] = col
    header, rows = _table(path)
    found = {}
    for i, h in enumerate(header):
        base, unit = _split_header(h)
        found[base] = (i, unit)
        found.setdefault(h, (i, unit))
    values: dict[str, np.ndarray] = {}
    for name, (col, unit) in layout.items():
        if col not in found:
            continue
        i, head_unit = found[col]
        unit = (units or {}).get(name, head_unit if head_unit is not None else unit)
        factor = unit_factor(unit, name)
        values[name] = _column(rows, i, col, path) * factor
    for name in (units or {}):
        if name not in COLUMNS:
            raise InputError(f"unknown column name {name!r} in the units (landau's names: {', '.join(COLUMNS)})")
    return _assemble(values, layout, header, os.fspath(path))


def _column(rows: list[list[str]], i: int, col: str, path) -> np.ndarray:
    out = np.empty(len(rows))
    for r, row in enumerate(rows):
        line = r + 2
        if i >= len(row) or not row[i].strip():
            raise InputError(f"{os.fspath(path)}, line {line}: no value in column {col!r}")
        try:
            x = float(row[i])
        except ValueError:
            raise InputError(f"{os.fspath(path)}, line {line}: {row[i]!r} in column {col!r} is not a number") from None
        if not math.isfinite(x):
            raise InputError(f"{os.fspath(path)}, line {line}: column {col!r} is {row[i].strip()} (remove or fill "
                             "the rows that are not finite numbers)")
        out[r] = x
    return out


def _assemble(values: dict[str, np.ndarray], layout, header: list[str], source: str) -> LabData:
    """The record from the columns found: time or displacement, velocity or displacement, μ."""
    def missing(name: str) -> str:
        return f"{layout[name][0]!r} ({COLUMNS[name]})"

    if "mu" not in values:
        raise InputError(f"{source}: no column {missing('mu')}; columns found: {', '.join(header)} "
                         "(map yours with --column mu=NAME)")
    mu = values["mu"]
    if mu.size < 2:
        raise InputError(f"{source}: {mu.size} sample(s); a fit needs many")
    t, V, x = values.get("t"), values.get("V_lp"), values.get("x_lp")
    if t is None:
        if x is None or V is None:
            raise InputError(f"{source}: no column {missing('t')}; without time both {missing('x_lp')} and "
                             f"{missing('V_lp')} are needed")
        if np.any(V[:-1] <= 0):
            raise InputError(f"{source}: without a time column the load-point velocity must be > 0 at every sample")
        t = np.concatenate([[0.0], np.cumsum(np.diff(x) / V[:-1])])
    bad = np.flatnonzero(np.diff(t) <= 0)
    if bad.size:
        raise InputError(f"{source}: time is not strictly increasing at line {bad[0] + 3} "
                         f"(t = {t[bad[0] + 1]:g} s after {t[bad[0]]:g} s)")
    if V is None:
        if x is None:
            raise InputError(f"{source}: no column {missing('V_lp')} nor {missing('x_lp')}: the load point's "
                             "motion is needed")
        V = np.diff(x) / np.diff(t)
        V = np.concatenate([V, V[-1:]])
    neg = np.flatnonzero(V < 0)
    if neg.size:
        raise InputError(f"{source}: the load-point velocity is negative at line {neg[0] + 2} ({V[neg[0]]:g} m/s)")
    if x is None:
        x = np.concatenate([[0.0], np.cumsum(V[:-1] * np.diff(t))])
    return LabData(t, V, mu, x, source)

