"""A compiled event-driven loop: DOPRI5 with exact contact switching, and a stiff step for the
stick phases, built for a given field.

:func:`switching_integrator` ``(fun, stiff_step)`` specialises the loop (source in
``templates/switching.py``) to a kernel ``fun(t, y, p, out)`` and a stick-phase step — nothing
here knows a model; :mod:`landau.verify.skurativskyi.simulate` builds it for eq. (1) with the
SDIRK4 of :mod:`landau.verify.skurativskyi.sdirk`.  Its ``integrate_mixed`` (the default path
of :func:`landau.verify.skurativskyi.simulate.run`) takes every step that starts with |ẋ|
below a threshold (stick: the cart rests on the obstacle or on the track, |ẋ| ~ 1e-9…1e-6
m/s) with the L-stable SDIRK4 (stage equations solved as scalar monotone equations, robust on
the |ẋ|^{n₃} cusp) and all other steps with DOPRI5 (the arithmetic of the DOPRI5 of
:mod:`landau.verify.hybrid.compiled`, term for term);
``integrate`` is the explicit path alone.  Event location (the compiled locator of
:mod:`landau.verify.hybrid.crossing`), stroboscopic clipping and tangent renormalisation are
the same for both steppers.

Why explicit outside stick (measured, see ``verify/benchmarks/skurativskyi_work_precision.py``): the
Hertz damping term sgn(ẋ)|ẋ|^{n₃} (n₃ ≈ 0.187) is not Lipschitz at ẋ = 0 inside contact:
its slope grows like |ẋ|^{−0.81}, so the Newton iteration of an implicit method (Radau,
BDF) diverges whenever a stage velocity is near zero — the classic failure of Newton on a
cusp-type root (a first version of this module was a compiled Radau IIA and diverged at the
very first step from rest).  The stiffness of the regularised friction is moderate
(T/(εm) ≈ 7.2e4 1/s), so an error-controlled explicit method runs at its stability bound
(h ≈ 3e-5 s) through stick phases and takes long steps elsewhere.  Compiled, a step costs
~1 µs, which is what makes the method fast — not its stability.  (In stick phases on the
obstacle the explicit steps are in fact ~1e-6 s, chattering across ẋ = 0 on the cusp: >95 %
of all steps at ω = 15; that is what the SDIRK4 of the mixed path removes.)

Method (Dormand & Prince 1980; Hairer, Nørsett & Wanner, *Solving ODEs I*, II.5): 7 stages
with FSAL, 5th-order solution, embedded 4th-order error estimate, step factor
0.9 err^{−1/5} clipped to [0.2, 10].

Loose tolerances (``templates/switching.py``: ``LOOSE_RTOL``, ``LOW_ORDER_RTOL``): at rtol ≥ 1e-6
the explicit steps are PI-controlled (Gustafsson 1991; Hairer, Nørsett & Wanner II.4: factor
0.9 err^{−α} err_prev^{β}, no growth right after a rejection), and at rtol ≥ 1e-5 they are
Bogacki–Shampine 3(2) steps (Bogacki & Shampine 1989; 4 stages with FSAL, 3 f evaluations) —
the non-smooth layers of eq. (1) (the friction regularised over |ẋ| < ε, the Hertz damping's
|ẋ|^{n₃}) cap the steps below where DOPRI5's order pays.  Measured at ω = 16, 20 periods from
rest: f evaluations 22.5k → 18.4k at rtol 1e-4, 33.0k → 28.9k at 1e-5, 45.0k → 40.2k at 1e-6,
with smaller final-state errors.  Tighter tolerances run the loop exactly as before, step for
step (the published bifurcation values are computed at rtol 1e-7…1e-9, and the period-doubling
cascade near ω = 20.4 follows the last bit of the step sequence).

Contact switching (guard g = x − x_I), exact to rounding:
1. each accepted step is scanned on the cubic Hermite interpolant of x (values and slopes
   ẋ at both ends) at its interior critical points, so a short excursion across x = x_I
   inside one step (near-grazing impact) is not missed; the first crossing is bisected;
2. the step is *re-taken* from its start with the length s*·h, and the length is corrected
   by Newton's method on g(t + h*) (slope ẋ) until |g| is at rounding level — the event time
   does not depend on the interpolant's accuracy, and every step lies on one side of the
   surface (the field is only C¹ there).  The end state is projected onto x = x_I.
No saltation is needed: the field is continuous across x = x_I (see ``model``).

Stroboscopic samples t = t₀ + i·2π/ω are step ends (steps are clipped onto them); with the
4-D variational system the tangent vector is renormalised there (top Lyapunov exponent).

Speed (not the arithmetic): the field and the steps are inlined into the loop, the stage
vectors are preallocated, and the loop works on views without numba's atomic reference
counts (:func:`borrowed`).  Measured at ω = 16, 20 periods from rest (2 shared cores): 3.9 →
2.0 ms at rtol 1e-5, 4.9 → 2.5 ms at 1e-6, 7.6 → 3.9 ms at 1e-7 — every step, event and
final state unchanged to the bit.
"""

from __future__ import annotations

import math
from functools import lru_cache
from pathlib import Path

import numpy as np
from numba import njit

from dataclasses import dataclass

from landau.verify.hybrid import compiled as _compiled
from landau.verify.hybrid.kernel import Kernel
from landau.verify.hybrid.nrt import borrowed  # noqa: F401  (re-exported: used by templates/switching.py)
from landau.verify.hybrid.specialise import specialise

OK, MAX_STEPS, STEP_TOO_SMALL, MAX_EVENTS = 0, 1, 2, 3
STATUS = {OK: "t_end", MAX_STEPS: "max_steps", STEP_TOO_SMALL: "step-size-underflow", MAX_EVENTS: "max_events"}


@lru_cache(maxsize=None)
def switching_integrator(fun, stiff_step):
    """The compiled event-driven loop over a second-order field (x, ẋ[, δx, δẋ]).

    Parameters
    ----------
    fun : numba function
        The kernel ``fun(t, y, p, out)`` (len(y) = 2, or 4 with one tangent vector).
    stiff_step : numba function
        The stick-phase step ``stiff_step(p, t, y, h, rtol, atol, ynew, fnew, err) ->
        (ok, nfev)`` (e.g. the SDIRK4 of :mod:`landau.verify.skurativskyi.sdirk` built for the
        same field).

    Returns
    -------
    (integrate, integrate_mixed)
        The jitted loops documented below (the module docstring describes the method).
    """
    mod = specialise(Path(__file__).parent / "templates" / "switching.py",
                     {"fun": fun, "stiff_step": stiff_step}, "switching")
    return mod.integrate, mod.integrate_mixed


# ---------------------------------------------------------------------------------------
#: a numba field with its packed parameters (the name the engine models of this package use)
CompiledField = Kernel


@dataclass(frozen=True)
class CompiledDOPRI5(_compiled.CompiledDOPRI5):
    """The generic compiled DOPRI5 stepper factory with defaults for eq. (1): atol in (m, m/s),
    first step 10 µs, steps ≤ 10 ms (a few hundredths of a forcing period)."""

    rtol: float = 1e-8
    atol: tuple = (1e-12, 1e-10)
    first_step: float = 1e-5
    max_step: float = 0.01

__all__ = ["CompiledDOPRI5", "CompiledField", "STATUS", "borrowed", "switching_integrator"]
