"""The amplitude equation's boundaries drawn on a spring–block regime map over (V, k).

Three predictions of the weakly nonlinear analysis go on top of a regime map computed by direct
simulation (``landau sweep regime``):

* the Hopf line k = k_c(V) with the sign of the Landau coefficient Λ (Λ < 0 supercritical,
  Λ > 0 subcritical; Putelat, Dawes & Willis 2010, eq. 20);
* the fold of cycles of the quintic amplitude equation, k_fold = k_c − Λ²/(8 Λ₅ Γ̄), where Λ and
  Λ₅ have opposite signs (:func:`landau.analyses.bautin.spring_block_fold`);
* the codimension-two (generalised-Hopf, Bautin) velocities V* where Λ changes sign on the Hopf
  line (:func:`landau.analyses.transition.codim2_points`, as ``landau derive --codim2``).

:func:`regime_overlay` computes them as arrays from a regime sweep's Dataset; the plot draws
exactly these arrays.

References
----------
Putelat, T., Dawes, J. H. P., Willis, J. R. (2010). Regimes of frictional sliding of a spring–block
system. J. Mech. Phys. Solids 58, 27–53 (Fig. 12: Hopf and fold-of-cycles loci).
"""

from __future__ import annotations

import json
import math
from typing import Any, Mapping

import numpy as np

from landau.errors import InputError, NoHopfError

#: at most this many velocities on the fold-of-cycles curve (each is a 50-digit evaluation of Λ₅)
MAX_FOLD_POINTS = 200


def fold_velocities(V, n_max: int = MAX_FOLD_POINTS) -> np.ndarray:
    """The velocities of the drawn fold curve: the map's V values and, between them, log-spaced
    velocities up to ``n_max`` in all (the map's values alone when they are ``n_max`` or more;
    ``n_max`` of them, log-spaced over their range, when they are more)."""
    V = np.unique(np.asarray(V, dtype=float))
    if V.size >= n_max:
        return V if V.size == n_max else np.geomspace(V[0], V[-1], n_max)
    if V.size < 2:
        return V
    return np.unique(np.concatenate([V, np.geomspace(V[0], V[-1], n_max - V.size)]))


def boundaries(law, params: Mapping[str, float], V, *, n_line: int = 300,
               n_fold: int = MAX_FOLD_POINTS) -> dict[str, Any]:
    """The Hopf line, the fold of cycles and the codimension-two velocities over the range of ``V``.

    Parameters
    ----------
    law : FrictionLaw
        The spring–block's rate-and-state law.
    params : mapping
        Fixed parameter values (anything not given takes the law's default).
    V : array_like
        The map's velocities, m/s (the range of every curve; the fold is evaluated at each of them).
    n_line : int
        Log-spaced velocities on the Hopf line.
    n_fold : int
        At most this many velocities on the fold curve (:func:`fold_velocities`).

    Returns
    -------
    dict
        ``V_line``, ``kc``, ``Lambda`` (the Hopf line k_c(V), N/m, and Λ along it; NaN where there
        is no Hopf point); ``V_fold``, ``k_fold`` (k_fold(V), N/m, NaN where Λ and Λ₅ have the same
        sign, where there is no Hopf point or where k_fold ≤ 0), ``kc_fold`` (k_c at those
        velocities, NaN with k_fold); ``V_star``, ``kc_star`` (each V*,
        m/s, and k_c there) — all numpy arrays.
    """
    from landau.analyses.bautin import spring_block_fold
    from landau.analyses.transition import codim2_points
    from landau.derivation.multiscale import Derivation
    from landau.systems.system import SpringBlock

    V = np.asarray(V, dtype=float)
    if V.size == 0 or not np.all(np.isfinite(V)) or np.any(V <= 0):
        raise InputError("the regime map's velocities must be finite and > 0")
    lo, hi = float(V.min()), float(V.max())
    d = Derivation(SpringBlock(law))
    p = d.block.resolve({n: v for n, v in params.items() if n not in ("V", "k")})
    V_line = np.geomspace(lo, hi, n_line) if lo < hi else np.array([lo])
    table = d.evaluate(V_line, p, ["kc", "Lambda"])
    V_fold = fold_velocities(V, n_fold)
    k_fold = np.full(V_fold.shape, np.nan)
    kc_fold = np.full(V_fold.shape, np.nan)
    for i, Vi in enumerate(V_fold):
        try:
            f = spring_block_fold(d, float(Vi), p)
        except (NoHopfError, InputError, ArithmeticError):
            continue          # no Hopf point, or Λ₅ = 0 there: no fold to draw
        if f is not None and f.p_fold > 0:
            k_fold[i], kc_fold[i] = f.p_fold, f.p_c
    stars = codim2_points(d, lo, hi, p) if lo < hi else []
    return {"V_line": V_line, "kc": np.asarray(table["kc"], dtype=float),
            "Lambda": np.asarray(table["Lambda"], dtype=float), "V_fold": V_fold, "k_fold": k_fold,
            "kc_fold": kc_fold,
            "V_star": np.array([c.p2 for c in stars], dtype=float),
            "kc_star": np.array([c.p1 for c in stars], dtype=float)}


def regime_overlay(ds, *, n_line: int = 300, n_fold: int = MAX_FOLD_POINTS) -> dict[str, Any] | None:
    """The amplitude equation's boundaries for a ``regime`` sweep's Dataset (see :func:`boundaries`).

    Parameters
    ----------
    ds : xarray.Dataset
        A regime sweep over V and k (its attributes name the law and the fixed parameters).
    n_line, n_fold : int
        As in :func:`boundaries`.

    Returns
    -------
    dict or None
        The arrays of :func:`boundaries`; None when the law is not a built-in one (an inline law's
        declaration is not rebuilt here).
    """
    from landau.laws import get_law, is_law_name

    name = ds.attrs.get("law")
    if not is_law_name(name):
        return None
    params = json.loads(ds.attrs.get("fixed_parameters", "{}") or "{}")
    params = {k: float(v) for k, v in params.items() if isinstance(v, (int, float)) and math.isfinite(v)}
    return boundaries(get_law(name), params, np.asarray(ds.V.values, dtype=float), n_line=n_line, n_fold=n_fold)
