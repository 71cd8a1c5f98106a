"""The stiffest Hopf point of many velocities at once: the roots W = ω² of the Hopf polynomial
H(W) (:mod:`landau.derivation.hopf_polynomial`) for every point, and among the real positive
ones the root with the largest positive stiffness p = −Re(P Q̄)/|Q|² (steady sliding is
unstable below the stiffest Hopf point; Putelat et al. 2010, eqs 7–8, for one state).

Vectorised over the points, so that a Hopf line without closed form (several state variables)
costs about what the closed form does:

* degree 1: W = −c₀/c₁;
* degree 2: the quadratic formula in the form that never subtracts nearly equal numbers,
  q = −(c₁ + sign(c₁)√Δ)/2, W = q/c₂ and c₀/q (Press et al., *Numerical Recipes*, 3rd ed.,
  Sec. 5.6), a complex pair where Δ < 0;
* degree ≥ 3: the eigenvalues of the companion matrices, stacked (``numpy.linalg.eigvals`` on
  an (n, d, d) array), which is what ``numpy.roots`` does for one point.

Rows whose leading coefficients vanish are solved at their true degree, as ``numpy.roots``
strips leading zeros; a row with a non-finite coefficient has no root.  A root counts as real
where |Im W| ≤ ``real_tol``·|W|, the rule of :func:`landau.derivation.linear._stiffest_hopf_root`
(the one-point version, used with mpmath).
"""

from __future__ import annotations

from typing import Callable

import numpy as np


def roots(C: np.ndarray) -> np.ndarray:
    """Complex roots of Σⱼ C[:, j] W^(d−j) for every row (highest power first), shape (n, d);
    NaN in the places of the missing roots of a row of lower degree.

    Parameters
    ----------
    C : numpy.ndarray
        Coefficients, shape (n, d + 1), highest power first.

    Returns
    -------
    numpy.ndarray
        complex, shape (n, d).
    """
    C = np.asarray(C, dtype=float)
    n, d1 = C.shape
    out = np.full((n, max(d1 - 1, 0)), np.nan, dtype=complex)
    finite = np.all(np.isfinite(C), axis=1)
    nz = C != 0
    # the true degree of each row: the number of coefficients after the leading zeros, minus one
    lead = np.where(nz.any(axis=1), np.argmax(nz, axis=1), d1)
    for s in np.unique(lead[finite]):
        deg = d1 - 1 - int(s)
        if deg < 1:
            continue
        rows = np.flatnonzero(finite & (lead == s))
        out[rows, :deg] = _roots_of_degree(C[rows, s:])
    return out


def _roots_of_degree(c: np.ndarray) -> np.ndarray:
    """Roots of rows of exact degree d = c.shape[1] − 1 (c[:, 0] ≠ 0)."""
    deg = c.shape[1] - 1
    if deg == 1:
        return (-c[:, 1] / c[:, 0]).astype(complex)[:, None]
    if deg == 2:
        a, b, e = c[:, 0], c[:, 1], c[:, 2]
        disc = b * b - 4.0 * a * e
        sq = np.sqrt(np.abs(disc))
        out = np.empty((c.shape[0], 2), dtype=complex)
        real = disc >= 0
        # real pair: q = −(b + sign(b)√Δ)/2, roots q/a and e/q (no cancellation in either)
        q = -0.5 * (b + np.copysign(sq, b))
        with np.errstate(divide="ignore", invalid="ignore"):
            r1 = q / a
            r2 = np.where(q != 0, e / np.where(q != 0, q, 1.0), r1)
        # complex pair: −b/(2a) ± i√(−Δ)/(2|a|)
        re_c = -b / (2.0 * a)
        im_c = sq / (2.0 * np.abs(a))
        out[:, 0] = np.where(real, r1, re_c + 1j * im_c)
        out[:, 1] = np.where(real, r2, re_c - 1j * im_c)
        return out
    # companion matrices, stacked: first row −c[1:]/c[0], ones on the subdiagonal
    n = c.shape[0]
    A = np.zeros((n, deg, deg))
    A[:, 0, :] = -c[:, 1:] / c[:, :1]
    idx = np.arange(deg - 1)
    A[:, idx + 1, idx] = 1.0
    return np.linalg.eigvals(A)


def stiffest(C: np.ndarray, stiffness: Callable[[np.ndarray, np.ndarray], np.ndarray],
             real_tol: float = 1e-9) -> tuple[np.ndarray, np.ndarray]:
    """(k_c, W) of every point: among the real positive roots of its Hopf polynomial, the one
    with the largest positive stiffness; NaN, NaN where there is none.

    Parameters
    ----------
    C : numpy.ndarray
        Hopf-polynomial coefficients, shape (n, d + 1), highest power first.
    stiffness : callable
        ``stiffness(W, rows)``: p(W) at the points ``rows`` (an index array) for real W there.
    real_tol : float
        A root is real where |Im W| ≤ real_tol·|W|.

    Returns
    -------
    kc, W : numpy.ndarray
        Shape (n,).
    """
    R = roots(C)
    n = R.shape[0]
    best_k = np.full(n, np.nan)
    best_W = np.full(n, np.nan)
    for j in range(R.shape[1]):
        r = R[:, j]
        with np.errstate(invalid="ignore"):
            ok = np.isfinite(r) & (np.abs(r.imag) <= real_tol * np.abs(r)) & (r.real > 0)
        rows = np.flatnonzero(ok)
        if rows.size == 0:
            continue
        Wr = r.real[rows]
        with np.errstate(all="ignore"):
            kk = np.asarray(stiffness(Wr, rows), dtype=float)
            better = (kk > 0) & ~(kk <= best_k[rows])
        best_k[rows[better]] = kk[better]
        best_W[rows[better]] = Wr[better]
    return best_k, best_W
