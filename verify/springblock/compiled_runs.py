"""Compiled Radau IIA runs of the spring–block's quasi-dynamic cell and load-point histories.

The quasi-dynamic spring–block (M = 0, η > 0; Rice 1993) is a semi-explicit index-1 DAE: the
states y (slip or spring stretch, log states) obey y' = f(w, y), and the log slip rate w is fixed
by the force balance R(w, y) = 0, whose residual decreases strictly in w (R_w < 0).  Here it is
integrated as the ODE in (y, w) obtained by differentiating the constraint once, with the
constraint fed back (Baumgarte 1972):

    w' = −(R_y · f(w, y) + λ R(w, y)) / R_w,        λ > 0.

Every solution of the DAE solves this ODE (R ≡ 0 along it, so the λ term vanishes), and
R' = −λR off it: the manifold R = 0 attracts, so the integration error cannot accumulate in the
force balance over long runs.  The runs take λ = :data:`FEEDBACK` × (1 + v/V) per unit of the
slip time ℓ/V (the fastest rates of the field grow like v), so that λh ≫ 1 at the steps of slow
and fast phases alike: then the stiffly accurate Radau IIA drives R to zero at every stage, the
limit in which it is the Radau IIA of the DAE itself (Hairer & Wanner 1996, VI.1, the
ε-embedding), and L-stability makes a large λ harmless.  Measured on the BP1-like cell of
``tests/springblock/test_quasidynamic.py`` with γ_LD = 0.2, α_LD = 0.3 at k = 0.7 k_c (stick–slip,
v from 1e-3 V to 4e5 V, four periods): the final-state errors against scipy's Radau IIA of the
implicit slip rate at rtol 1e-12 are 6.4e-7, 2.2e-9, 7.9e-12 at rtol 1e-6, 1e-8, 1e-10, the
same (to 10 %) for every λ from 0 to 1e9, and along ten periods at rtol 1e-8 |R| stays below
1.2e-11 (the differentiated constraint alone drifts little: a Runge–Kutta method keeps linear
invariants exactly, and R is linear in (ξ, w, ψ) for Dieterich's law up to the η e^w and γ_LD
terms); the feedback is the guarantee for laws and runs where it is not.

Why this form, and not a Newton solve of the force balance inside the compiled f (the slip rate
implicit, the Jacobian from the implicit-function theorem) or an algebraic row in the Radau IIA:

* the right-hand side and its exact Jacobian are the generated kernels of
  :mod:`landau.codegen.kernels` (closed-form expressions, no loop: the kernel whitelist admits
  none, and a hand-written Newton loop bound to each law's residual would need a compiled
  closure per law, which numba does not cache);
* the integrator is the unchanged compiled Radau IIA of :mod:`landau.verify.hybrid.radau`
  (no mass matrix to thread through its Newton iteration and error estimate);
* w is a state, so the crossings of v = V (Poincaré sections) are located by the loop itself on
  the collocation cubic, and a load-point velocity jump leaves (y, w) exactly continuous: the
  force balance does not contain the load-point velocity.

Why Radau IIA and not the compiled DOP853, by measurement: the cell itself is not stiff.  At
rtol 1e-9, without the feedback (λ = 0, which an explicit method needs: the feedback is stiff by
design), scipy's DOP853 on the same compiled field takes 13–17× fewer steps and 6–8× fewer field
evaluations than the Radau IIA (BP1-like Dieterich cell at k = 0.5 k_c, v from 6e-5 V to 5e8 V:
216 steps / 3650 evaluations against 2874 / 21487; the slip law at 0.5 k_c 167 / 2810 against
2267 / 17169; the nanoscale and two-state laws near k_c 262–276 / 4000–4100 against
4256–4715 / 29800–33000).  The Radau IIA is kept because (i) its compiled loop records the steps
and locates the crossings of a state component on its collocation cubic in one call, which the
sections, the return map and the bistability probe need, where the compiled DOP853 is the hybrid
engine's screened stepper that returns to Python at every candidate event; (ii) the same loop
runs the load histories at M > 0, which are stiff (the inertial relaxation σa/(Mv) of w is 1e4
times the slip rate V/L at the default block); (iii) the feedback that guarantees the force
balance needs an L-stable method; and (iv) it already meets the speed goal against the scipy
route at equal error (``benchmarks/sections_springblock_paths.py``: 215–310× on the cell, whose
compiled run at rtol 1e-9 costs about 2 ms, a third of it the per-call set-up).  A DOP853 route would
save most of the loop's share (6–8× fewer evaluations, no LU), not the set-up.

This module holds the kernels' compilation (:func:`compile_field`: hoisted parameters, exact
Jacobian, numba through the code cache; one build per law and set of terms, any parameter
values) and the restartable compiled run (:func:`drive`: chunks of step attempts, every
accepted step recorded, the crossings of one component located, a first step chosen by the
rule of Hairer, Nørsett & Wanner 1993, II.4).

References
----------
Baumgarte, J. (1972), Stabilization of constraints and integrals of motion in dynamical systems,
Comput. Methods Appl. Mech. Eng. 1, 1–16.
Hairer, E., Nørsett, S. P., Wanner, G. (1993), Solving Ordinary Differential Equations I, 2nd ed.,
Springer, Sec. II.4 (starting step size).
Hairer, E., Wanner, G. (1996), Solving Ordinary Differential Equations II, 2nd ed., Springer,
Sec. IV.8 and VI.1 (Radau IIA for index-1 problems).
Rice, J. R. (1993), Spatio-temporal complexity of slip on a fault, J. Geophys. Res. 98(B6), 9885–9907.
"""

from __future__ import annotations

import math
import time
import weakref
from dataclasses import dataclass
from typing import Any, Callable, Sequence

import numpy as np
import sympy as sp

from landau.codegen.kernels import DerivedParameters, compile_source, hoist_parameters, kernel_source
from landau.errors import InputError
from landau.verify.hybrid.callbacks import call_pointer, pointer
from landau.verify.hybrid.radau import SIG, radau_core

#: the constraint feedback of the force balance, λ = FEEDBACK (1 + v/V) per unit of the slip time
#: ℓ/V (module docstring)
FEEDBACK = 1e6

#: step attempts per compiled call of :func:`drive`
CHUNK_STEPS = 200_000


def index_reduced(R: sp.Expr, f: Sequence[sp.Expr], w: sp.Symbol, ys: Sequence[sp.Symbol],
                  lam: sp.Symbol) -> sp.Expr:
    """dw/dt = −(R_y·f + λR)/R_w: the force balance R(w, y) = 0 differentiated along y' = f, with
    the feedback λR that makes R = 0 attracting (module docstring)."""
    return -(sum(sp.diff(R, q) * e for q, e in zip(ys, f, strict=True)) + lam * R) / sp.diff(R, w)


@dataclass(frozen=True)
class CompiledField:
    """A generated field f(t, y; p) and its exact Jacobian, compiled, with its parameter vector.

    ``parameters(base)`` appends the hoisted parameter-only subexpressions to the base values
    (in the order of ``names``); ``rhs``, ``jac`` are what :func:`radau_core` calls.
    """

    label: str
    n: int
    names: tuple[str, ...]
    rhs: Callable[..., None]
    jac: Callable[..., None]
    parameters: DerivedParameters

    def f(self, t: float, y, p) -> np.ndarray:
        """The field at ``(t, y)``, by the compiled code the integrator calls."""
        out = np.empty(self.n)
        call_pointer(pointer(self.rhs, SIG, "right-hand side"), float(t), np.ascontiguousarray(y, dtype=float),
                     p, out)
        return out


_FIELDS: dict[tuple, CompiledField] = {}


#: what was built for each law object seen (identity lookup: a structural key prints the law's
#: expressions, which costs more than a short run)
_BY_LAW: "weakref.WeakKeyDictionary[object, dict[tuple, Any]]" = weakref.WeakKeyDictionary()


def per_law(law, tag: tuple, build: Callable[[], Any]) -> Any:
    """``build()`` once per law object and ``tag`` in this process (the law's kernels and
    lambdified helpers of the given kind)."""
    memo = _BY_LAW.get(law)
    if memo is None:
        memo = _BY_LAW[law] = {}
    if tag not in memo:
        memo[tag] = build()
    return memo[tag]


def cached_field(key: tuple) -> CompiledField | None:
    """The field compiled under ``key`` in this process, if any (a caller then skips building its
    expressions)."""
    return _FIELDS.get(key)


def compile_field(key: tuple, states: Sequence[sp.Symbol], field: Sequence[sp.Expr],
                  params: Sequence[sp.Symbol], names: Sequence[str], label: str) -> CompiledField:
    """The field over ``states`` with the parameter vector ``params`` (named ``names``), compiled
    once per ``key`` in this process (and its source and machine code cached on disk)."""
    hit = _FIELDS.get(key)
    if hit is not None:
        return hit
    h = hoist_parameters(list(field), list(params))
    src = kernel_source(list(states), h.field, [*params, *h.derived])
    c = compile_source(src, label)
    assert c.jac is not None       # kernel_source emits the Jacobian by default
    out = CompiledField(label, len(states), tuple(names), c.fun, c.jac, DerivedParameters(list(params), h.values))
    _FIELDS[key] = out
    return out


def first_step(field: CompiledField, p: np.ndarray, t0: float, y0: np.ndarray, t1: float, rtol: float,
               atol: np.ndarray) -> float:
    """The starting step of Hairer, Nørsett & Wanner (1993), II.4, for order 5 (scipy's rule)."""
    scale = atol + np.abs(y0) * rtol
    f0 = field.f(t0, y0, p)
    d0 = float(np.sqrt(np.mean((y0 / scale) ** 2)))
    d1 = float(np.sqrt(np.mean((f0 / scale) ** 2)))
    h0 = 1e-6 if d0 < 1e-5 or d1 < 1e-5 else 0.01 * d0 / d1
    h0 = min(h0, t1 - t0)
    f1 = field.f(t0 + h0, y0 + h0 * f0, p)
    d2 = float(np.sqrt(np.mean(((f1 - f0) / scale) ** 2))) / h0
    h1 = max(1e-6, h0 * 1e-3) if d1 <= 1e-15 and d2 <= 1e-15 else (0.01 / max(d1, d2)) ** (1 / 6)
    h = min(100 * h0, h1, t1 - t0)
    if not (math.isfinite(h) and h > 0):
        raise InputError(f"{field.label}: the field is not finite at the start (t = {t0:g})")
    return h


@dataclass(frozen=True)
class Drive:
    """One compiled run: ``status`` of :data:`~landau.verify.hybrid.radau.STATUS` (0 finished,
    1 stopped at a crossing, −1 step too small, −2 step budget, −3 non-finite), the end (``t``,
    ``y``, next step ``h``), every accepted step (``rec_t``, ``rec_y`` of shape (m, n), the start
    included), the crossings (``ev_t``, ``ev_y``, ``ev_dir``), the counters (accepted, rejected,
    f evaluations, Jacobians, LU) and the CPU time of the compiled calls."""

    status: int
    t: float
    y: np.ndarray
    h: float
    rec_t: np.ndarray
    rec_y: np.ndarray
    ev_t: np.ndarray
    ev_y: np.ndarray
    ev_dir: np.ndarray
    counts: np.ndarray
    cpu: float


def drive(field: CompiledField, p: np.ndarray, y0, t0: float, t1: float, *, rtol: float, atol: np.ndarray,
          h0: float | None = None, max_steps: int = 5_000_000, ev_idx: int = -1, ev_dir: int = 0,
          ev_stop: int = 0, max_events: int = 10_000, chunk_steps: int = CHUNK_STEPS) -> Drive:
    """Integrate ``field`` from ``y0`` over [t0, t1] with the compiled Radau IIA, recording every step.

    Parameters
    ----------
    field, p : CompiledField, ndarray
        The field and its full parameter vector (``field.parameters(base)``).
    y0 : array_like
        Initial state.
    t0, t1 : float
        The interval (the field's own time unit).
    rtol, atol : float, ndarray
        Tolerances of the step-size control.
    h0 : float, optional
        First step (default: :func:`first_step`).
    max_steps : int
        Budget of step attempts (accepted and rejected); the run returns with status −2 at it.
    ev_idx, ev_dir, ev_stop : int
        Crossings of ``y[ev_idx] = 0`` are located (−1: none); the run stops after ``ev_stop`` > 0
        of them in direction ``ev_dir`` (±1, 0 either).
    max_events : int
        Bound on the crossings kept.
    chunk_steps : int
        Step attempts per compiled call (each call continues from the last one's state and step).

    Returns
    -------
    Drive
        The end of the run, its record, crossings and counters.

    Raises
    ------
    InputError
        A budget or chunk below 1, or a stop after more crossings than are kept.
    """
    if not (int(max_steps) >= 1 and int(chunk_steps) >= 1):
        raise InputError(f"max_steps and chunk_steps must be >= 1, got {max_steps!r}, {chunk_steps!r}")
    if ev_stop > max_events:
        raise InputError(f"a run stopping after {ev_stop} crossings keeps at least as many (max_events = "
                         f"{max_events})")
    y = np.ascontiguousarray(y0, dtype=float).copy()
    at = np.ascontiguousarray(atol, dtype=float)
    t = float(t0)
    h = first_step(field, p, t, y, float(t1), rtol, at) if h0 is None else float(h0)
    rec_t, rec_y = [np.array([t])], [y[None, :].copy()]
    ev_t: list[np.ndarray] = []
    ev_y: list[np.ndarray] = []
    ev_d: list[np.ndarray] = []
    kept = 0                           # crossings kept so far
    counts = np.zeros(5, dtype=np.int64)
    steps, found, cpu, st = 0, 0, 0.0, -2
    n = len(y)
    while steps < max_steps:
        budget = min(int(chunk_steps), int(max_steps) - steps)
        room = max(int(max_events) - kept, 0)
        evbuf = np.empty((max(room, 1) if ev_idx >= 0 else 1, n + 1))
        evdir = np.empty(evbuf.shape[0])
        left = max(int(ev_stop) - found, 1) if ev_stop > 0 else 0
        tic = time.process_time()
        st, tn, yn, cnt, et, ey, rt, ry, hn, _ = radau_core(
            field.rhs, field.jac, t, y, float(t1), p, float(rtol), at, float(h), np.inf, budget,
            int(ev_idx) if room or ev_stop else -1, 0.0, int(ev_dir), left, budget + 1, None, None, evbuf, evdir)
        cpu += time.process_time() - tic
        steps += int(cnt[0]) + int(cnt[1])
        counts += cnt[:5]
        keep = min(len(et), room)
        et, ey, d = et[:keep], ey[:keep], evdir[:keep].astype(int)
        kept += keep
        ev_t.append(et)
        ev_y.append(ey)
        ev_d.append(d)
        found += int(np.sum(d == ev_dir)) if ev_dir else len(et)
        rec_t.append(rt[1:])       # a call records its start: the previous call's end
        rec_y.append(ry[1:])
        t, y, h = float(tn), yn.copy(), float(hn)
        if st != -2:
            break
    return Drive(int(st), t, y, h, np.concatenate(rec_t), np.concatenate(rec_y), np.concatenate(ev_t),
                 np.concatenate(ev_y) if ev_y else np.empty((0, n)), np.concatenate(ev_d), counts, cpu)


__all__ = ["CHUNK_STEPS", "FEEDBACK", "CompiledField", "Drive", "cached_field", "compile_field", "drive", "first_step",
           "index_reduced", "per_law"]
