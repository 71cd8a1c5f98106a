"""The compiled event locator: crossings of a guard that is a cubic in the step fraction.

The compiled loops locate events on a cubic per step: the DOPRI5 loop on the cubic Hermite
interpolant of the guarded component, the Radau IIA on its collocation polynomial (both
g(s) = g₀ + c₁s + c₂s² + c₃s³ for s ∈ [0, 1]).  The scan is exact for a cubic: g is monotone
between its critical points, so evaluating g at every critical point inside the interval and
at its end finds the first sign change, including a guard that dips across and back inside
one step (a double crossing that sampling at the step ends — or at a few points — misses).
The bracket is bisected to adjacent floating-point numbers and the root is returned on the
*new side* (the side the guard is crossing to), so a switch is applied to a state that is
already past the surface.  :mod:`landau.verify.hybrid.locate` is the same procedure for an
arbitrary guard on any stepper's dense output (sampled, with a bounded minimisation for the
dips, Brent's method for the root).

The Radau IIA loop builds its own copy of :func:`cubic_crossing` inside its machine code; the
other callers use the function here, which numba caches on disk.
"""

from __future__ import annotations

import math

import numba as nb
import numpy as np

__all__ = ["cubic", "cubic_crossing"]


@nb.njit(cache=True)
def cubic(c1, c2, c3, s):
    """c₁s + c₂s² + c₃s³ (Horner)."""
    return s * (c1 + s * (c2 + s * c3))


@nb.njit(cache=True)
def cubic_crossing(g0, c1, c2, c3, lo, outside_sign, inclusive):
    """First s in (lo, 1] where g(s) = g0 + c1 s + c2 s² + c3 s³ is on the side
    ``outside_sign`` (g·sign > 0, or g = 0 too when ``inclusive``), or −1 if none.

    g(lo) must be on the other side.  The scan is exact for a cubic: g is monotone between its
    critical points, so evaluating g at every critical point inside the interval and at its end
    finds the first sign change, including a guard that dips across and back inside one step.
    The bracket is bisected to adjacent floating-point numbers and the root is returned on the
    *new side* (the side the guard is crossing to)."""
    pts = np.empty(3)
    npts = 0
    a, b, c = 3 * c3, 2 * c2, c1
    if a != 0.0:
        disc = b * b - 4 * a * c
        if disc >= 0:
            r = math.sqrt(disc)
            s1 = (-b - r) / (2 * a)
            s2 = (-b + r) / (2 * a)
            if s1 > s2:
                s1, s2 = s2, s1
            if lo < s1 < 1.0:
                pts[npts] = s1
                npts += 1
            if lo < s2 < 1.0:
                pts[npts] = s2
                npts += 1
    elif b != 0.0:
        s = -c / b
        if lo < s < 1.0:
            pts[npts] = s
            npts += 1
    pts[npts] = 1.0
    npts += 1
    for k in range(npts):
        hi = pts[k]
        gh = (g0 + cubic(c1, c2, c3, hi)) * outside_sign
        if gh > 0.0 or (inclusive and gh == 0.0):
            for _ in range(100):
                mid = 0.5 * (lo + hi)
                if mid <= lo or mid >= hi:
                    break
                gm = (g0 + cubic(c1, c2, c3, mid)) * outside_sign
                if gm > 0.0 or (inclusive and gm == 0.0):
                    hi = mid
                else:
                    lo = mid
            return hi
        lo = hi
    return -1.0
