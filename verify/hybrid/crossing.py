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

The functions are defined beside the Radau IIA loop (:mod:`landau.verify.hybrid.radau`), in the
one file whose edits numba's disk cache of that loop notices; this module is their public name.
"""

from __future__ import annotations

from landau.verify.hybrid.radau import cubic, cubic_crossing

__all__ = ["cubic", "cubic_crossing"]
