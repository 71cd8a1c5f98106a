"""The generic figure of a sweep: its numbers over its axes (``landau plot --sweep``).

A model may declare a figure of its own for a task (:attr:`landau.models.Model.plots`: the
spring–block's regime map, the forced oscillator's bifurcation diagram); every other sweep is drawn
by :func:`plot_any_sweep`.
"""

from __future__ import annotations

from landau.errors import InputError

#: the variables a generic sweep figure draws first, where the sweep has them
_FIRST = ("k_c", "p_c", "Lambda", "C", "omega_c", "value", "rel_diff")


def plot_any_sweep(ds, fig) -> dict:
    """Any sweep's numbers over its axes: up to three float variables (k_c or p_c and Λ first for a
    ``hopf`` sweep), each against the first axis (log-scaled where it spans decades), one line per
    value of a second axis; points without a result are left out.  Returns the command's document."""
    import numpy as np

    dims = list(ds.status.dims)
    floats = [v for v in ds.data_vars if v not in ("status", "message") and ds[v].dtype.kind == "f"
              and ds[v].dims == tuple(dims)]
    chosen = [v for v in _FIRST if v in floats and not (v == "p_c" and "k_c" in floats)][:3] or floats[:3]
    if not chosen or not dims:
        raise InputError("--sweep: the file holds no numbers to draw")
    x = dims[0]
    axes = fig.subplots(len(chosen), 1, sharex=True, squeeze=False)[:, 0]
    xv = np.asarray(ds[x].values, dtype=float)
    for ax, name in zip(axes, chosen, strict=True):
        da = ds[name].where(ds.status.isin(["ok", "degenerate"]))
        rest = [d for d in dims if d != x]
        lines = [da] if not rest else [da.isel({d: 0 for d in rest[1:]}).isel({rest[0]: i})
                                       for i in range(ds.sizes[rest[0]])]
        for i, line in enumerate(lines):
            label = f"{rest[0]} = {float(ds[rest[0]].values[i]):.4g}" if rest else None
            ax.plot(xv, np.asarray(line.transpose(x, ...).values, dtype=float).reshape(len(xv), -1)[:, 0],
                    marker=".", label=label)
        unit = ds[name].attrs.get("units", "")
        ax.set_ylabel(f"{name} [{unit}]" if unit and unit != "1" else name)
        finite = np.asarray(da.values, dtype=float)
        finite = finite[np.isfinite(finite)]
        if finite.size and finite.min() > 0 and finite.max() / finite.min() > 100:
            ax.set_yscale("log")
        if rest and len(lines) <= 12:
            ax.legend(fontsize="small")
    xunit = ds[x].attrs.get("units", "")
    axes[-1].set_xlabel(f"{x} [{xunit}]" if xunit and xunit != "1" else x)
    if xv.min() > 0 and xv.max() / xv.min() > 100:
        axes[-1].set_xscale("log")
    law = ds.attrs.get("law", "")
    fig.suptitle(f"{ds.attrs.get('task', '')} {ds.attrs.get('model', '')}" + (f" ({law})" if law else ""))
    return {"kind": "sweep-lines", "variables": chosen, "x": x}
