"""Horner's rule with its running error bound over many points, compiled (the exactly cancelled
rational forms of :mod:`landau.derivation.rational`).

One pass over the points evaluates p(s) and Σ|cᵢ|sⁱ together, in the order of ``numpy.polyval``
(y ← y·s + c from y = 0, no fused multiply-add), so the values and bounds are those of the
numpy evaluation bit for bit; numpy makes two passes of one temporary array per coefficient,
which is memory traffic at 1e6 points (the Λ(V) benchmark of ``benchmarks/sections_engine.py``:
polyval was 40 % of the Dieterich law's evaluation).  Compiled once per machine (numba's disk
cache); batches below :data:`landau.derivation.precision.BOUNDED_MIN` points stay in numpy and
never import numba.

Reference: Higham, N. J. (2002). Accuracy and Stability of Numerical Algorithms, 2nd ed., SIAM,
eq. (5.3): |p̂(s) − p(s)| ≤ γ₂ₙ Σ|cᵢ||s|ⁱ.
"""

from __future__ import annotations

import math

import numba as nb
import numpy as np

__all__ = ["horner_bounded"]


@nb.njit(cache=True, error_model="numpy", nogil=True)
def _horner_bounded(desc, absdesc, k, x, factor, safe, val, rel):
    m = desc.shape[0]
    for j in range(x.shape[0]):
        s = math.ldexp(x[j], -k)
        y = 0.0
        a = 0.0
        for i in range(m):
            y = y * s + desc[i]
            a = a * s + absdesc[i]
        val[j] = y
        r = factor * a / abs(y)
        rel[j] = r if (safe and math.isfinite(r)) else math.inf


def horner_bounded(desc: np.ndarray, absdesc: np.ndarray, k: int, x: np.ndarray, factor: float,
                   safe: bool) -> tuple[np.ndarray, np.ndarray]:
    """(p(s), relative bound) at s = x·2⁻ᵏ for the coefficients ``desc`` (descending powers) and
    their absolute values ``absdesc``: the bound is ``factor``·Σ|cᵢ|sⁱ/|p(s)|, infinite where it
    is not finite or the coefficients are not ``safe`` (a coefficient lost to the float range)."""
    xs = np.ascontiguousarray(x, dtype=float).reshape(-1)
    val, rel = np.empty_like(xs), np.empty_like(xs)
    _horner_bounded(desc, absdesc, int(k), xs, float(factor), bool(safe), val, rel)
    return val.reshape(np.shape(x)), rel.reshape(np.shape(x))
