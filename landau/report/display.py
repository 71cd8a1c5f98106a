"""Tables for notebooks and terminals: one helper behind every result's ``_repr_html_``.

Every result object of the toolkit displays through the functions here, so that a single
result, a list of results and an evaluated table look alike:

* :func:`html_table` — rows (mappings) as one HTML table, units in the column headers;
* :func:`html_record` — one result as a two-column table (field, value) with a title;
* :func:`display_row` — the flat row of one result (``_display_row()``, else ``as_dict()``,
  else its dataclass fields);
* :class:`ResultList` — a list of results that displays as *one* table (and converts to a
  pandas DataFrame).

Display never computes: it formats numbers that already exist (no symbolic work, no
simulation), so it returns in milliseconds.
"""

from __future__ import annotations

import dataclasses
import html
import math
from typing import Any, Iterable, Mapping, Sequence

#: rows shown before a table is cut (the rest are counted in a footer)
MAX_ROWS = 60
#: characters shown of a long text cell
MAX_CELL = 120


def format_value(x: Any, digits: int = 6) -> str:
    """A compact text form of one cell: numbers to ``digits`` significant figures, None as "—"."""
    if x is None:
        return "—"
    if isinstance(x, bool):
        return str(x)
    if isinstance(x, int):
        return str(x)
    if isinstance(x, complex):
        return f"{x.real:.{digits}g}{x.imag:+.{digits}g}i"
    if isinstance(x, float):
        return f"{x:.{digits}g}" if math.isfinite(x) else str(x)
    if isinstance(x, str):
        return x if len(x) <= MAX_CELL else x[:MAX_CELL - 1] + "…"
    if hasattr(x, "dtype") and getattr(x, "ndim", 1) == 0:      # numpy scalar
        return format_value(x.item(), digits)
    if isinstance(x, (list, tuple)) and len(x) <= 6 and all(isinstance(v, (int, float)) for v in x):
        return "(" + ", ".join(format_value(v, digits) for v in x) + ")"
    text = str(x)
    return text if len(text) <= MAX_CELL else text[:MAX_CELL - 1] + "…"


def display_row(obj: Any) -> dict[str, Any]:
    """The flat fields of one result, for a table row.

    Uses ``obj._display_row()`` when the result defines it, else ``obj.as_dict()``, else the
    fields of a dataclass, else a mapping as it is; anything else becomes ``{"value": obj}``.
    """
    if hasattr(obj, "_display_row"):
        return dict(obj._display_row())
    if hasattr(obj, "as_dict"):
        return dict(obj.as_dict())
    if dataclasses.is_dataclass(obj) and not isinstance(obj, type):
        return {f.name: getattr(obj, f.name) for f in dataclasses.fields(obj) if f.repr}
    if isinstance(obj, Mapping):
        return dict(obj)
    return {"value": obj}


def _columns(rows: Sequence[Mapping[str, Any]], columns: Sequence[str] | None) -> list[str]:
    if columns is not None:
        return list(columns)
    out: list[str] = []
    for r in rows:
        for k in r:
            if k not in out:
                out.append(k)
    return out


def _header(name: str, units: Mapping[str, str] | None) -> str:
    u = (units or {}).get(name)
    return f"{name} [{u}]" if u else name


def html_table(rows: Iterable[Mapping[str, Any]], columns: Sequence[str] | None = None, *,
               units: Mapping[str, str] | None = None, title: str | None = None, note: str | None = None,
               digits: int = 6, max_rows: int = MAX_ROWS) -> str:
    """Rows as one HTML table.

    Parameters
    ----------
    rows : iterable of mappings
        One mapping per row; the columns are the union of their keys in first-seen order.
    columns : sequence of str, optional
        The columns to show, in this order (default: every key).
    units : mapping, optional
        Column name -> unit, shown in the header as ``name [unit]``.
    title, note : str, optional
        A bold caption above and a small note below the table.
    digits : int
        Significant figures of floating-point cells.
    max_rows : int
        Rows shown; the rest are counted in a footer.

    Returns
    -------
    str
        An HTML fragment (every cell escaped).
    """
    rows = list(rows)
    cols = _columns(rows, columns)
    esc = html.escape
    head = "".join(f"<th>{esc(_header(c, units))}</th>" for c in cols)
    body = []
    for r in rows[:max_rows]:
        cells = "".join(f"<td>{esc(format_value(r.get(c), digits))}</td>" for c in cols)
        body.append(f"<tr>{cells}</tr>")
    if len(rows) > max_rows:
        body.append(f"<tr><td colspan='{len(cols)}'>… {len(rows) - max_rows} more rows</td></tr>")
    parts = ["<div class='landau-result'>"]
    if title:
        parts.append(f"<b>{esc(title)}</b>")
    parts.append(f"<table><thead><tr>{head}</tr></thead><tbody>{''.join(body)}</tbody></table>")
    if note:
        parts.append(f"<small>{esc(note)}</small>")
    parts.append("</div>")
    return "".join(parts)


def html_record(title: str, fields: Mapping[str, Any], *, units: Mapping[str, str] | None = None,
                note: str | None = None, digits: int = 10) -> str:
    """One result as a two-column table (field, value) under a bold title.

    Parameters
    ----------
    title : str
        What the result is (escaped).
    fields : mapping
        Field name -> value; nested lists and mappings are shown abbreviated.
    units : mapping, optional
        Field name -> unit, shown after the value.
    note : str, optional
        A small note below the table (e.g. the convention of the coefficients).
    digits : int
        Significant figures of floating-point values.

    Returns
    -------
    str
        An HTML fragment.
    """
    esc = html.escape
    rows = []
    for k, v in fields.items():
        u = (units or {}).get(k)
        val = format_value(v, digits) + (f" {u}" if u else "")
        rows.append(f"<tr><th style='text-align:left'>{esc(str(k))}</th><td "
                    f"style='text-align:left'>{esc(val)}</td></tr>")
    out = f"<div class='landau-result'><b>{esc(title)}</b><table>{''.join(rows)}</table>"
    if note:
        out += f"<small>{esc(note)}</small>"
    return out + "</div>"


def text_table(rows: Iterable[Mapping[str, Any]], columns: Sequence[str] | None = None, *,
               units: Mapping[str, str] | None = None, digits: int = 6, max_rows: int = MAX_ROWS) -> str:
    """The same table as :func:`html_table` in aligned plain text (for ``repr`` and terminals)."""
    rows = list(rows)
    cols = _columns(rows, columns)
    cells = [[_header(c, units) for c in cols]]
    cells += [[format_value(r.get(c), digits) for c in cols] for r in rows[:max_rows]]
    widths = [max(len(row[i]) for row in cells) for i in range(len(cols))]
    lines = ["  ".join(s.rjust(w) for s, w in zip(row, widths, strict=True)) for row in cells]
    if len(rows) > max_rows:
        lines.append(f"… {len(rows) - max_rows} more rows")
    return "\n".join(lines)


def require_pandas(what: str = "to_dataframe()"):
    """Import pandas or raise an ImportError naming the extra that installs it."""
    try:
        import pandas
    except ImportError:
        raise ImportError(f"{what} needs pandas: pip install 'landau-friction[notebook]'") from None
    return pandas


class ResultList(list):
    """A list of results that displays as one table.

    Any results with ``as_dict()`` (or dataclass fields) can be collected; in a notebook the
    list renders as a single HTML table with one row per result, at the terminal as an
    aligned text table.

    Parameters
    ----------
    items : iterable
        The results.
    title : str, optional
        Caption of the table.
    columns : sequence of str, optional
        Columns to show (default: every field of every result).
    units : mapping, optional
        Column name -> unit.
    """

    def __init__(self, items: Iterable[Any] = (), *, title: str | None = None,
                 columns: Sequence[str] | None = None, units: Mapping[str, str] | None = None):
        super().__init__(items)
        self.title = title
        self.columns = None if columns is None else list(columns)
        self.units = dict(units or {})

    def rows(self, limit: int | None = None) -> list[dict[str, Any]]:
        """One flat mapping per result (the first ``limit`` if given; see :func:`display_row`)."""
        return [display_row(r) for r in (self if limit is None else self[:limit])]

    def to_dataframe(self):
        """The rows as a pandas DataFrame (units in the column names; needs pandas)."""
        pd = require_pandas("ResultList.to_dataframe()")
        rows = self.rows()
        cols = _columns(rows, self.columns)
        df = pd.DataFrame([[r.get(c) for c in cols] for r in rows], columns=[_header(c, self.units) for c in cols])
        df.attrs["units"] = dict(self.units)
        return df

    def _repr_html_(self) -> str:
        shown = "" if len(self) <= MAX_ROWS else f", the first {MAX_ROWS} shown"
        return html_table(self.rows(MAX_ROWS), self.columns, units=self.units, title=self.title,
                          note=f"{len(self)} result(s){shown}")

    def __repr__(self) -> str:
        head = f"{self.title} — " if self.title else ""
        more = f"\n… {len(self) - MAX_ROWS} more" if len(self) > MAX_ROWS else ""
        return (f"{head}{len(self)} result(s)\n" + text_table(self.rows(MAX_ROWS), self.columns, units=self.units)
                + more)
