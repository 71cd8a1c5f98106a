"""Integrate the compiled spring–block (:mod:`landau.verify.springblock.model`) with the numba Radau IIA.

:func:`integrate` runs the default integrator between physical times (seconds), optionally
locating crossings of one component (e.g. w = ln(v/V) = 0, where X = x − x₀ is extremal)
and stopping after a given number of them; every failure raises
:class:`~landau.errors.IntegratorError` carrying the time and the physical state.

Methods (``method=``): ``"radau5"`` (default, the 3-stage Radau IIA of
:mod:`landau.verify.hybrid.radau`, with event location), ``"radau9"`` (the 5-stage, order-9
Radau IIA of :mod:`landau.verify.hybrid.collocation`, no event location or recording),
``"radau5t"`` (the same order-5 Radau IIA with its Newton system transformed to one real and
one complex 3 × 3 system, Hairer & Wanner 1996, IV.8; with event location; agrees with
``"radau5"`` to the tolerance, not to the bit), ``"rodas4"`` (the Rosenbrock method of
:mod:`landau.verify.hybrid.rosenbrock`) and ``"auto"``, which picks by the requested tolerance
(:func:`choose_method`).  The kernels are passed to the
compiled code by machine address (:mod:`landau.verify.hybrid.fastcall`), so a call costs a few
microseconds on top of the integration itself.
"""

from __future__ import annotations

import time
from dataclasses import dataclass, field

import numpy as np

from landau.errors import InputError, IntegratorError
from landau.verify.hybrid.log import Event, EventLog
from landau.verify.hybrid.result import Simulation, status_from_text
from landau.verify.springblock.model import SpringBlockModel, compile_variational
from landau.verify.hybrid.collocation import radau_tableau
from landau.verify.hybrid.fastcall import addresses, collocation_at, radau_at, radau_split_at, rosenbrock_at
from landau.verify.hybrid.radau import A_RADAU, ALPHA_SPLIT, BETA_SPLIT, GAMMA_SPLIT, STATUS, T_SPLIT, TI_SPLIT, VINV
from landau.verify.hybrid.rosenbrock import (RODAS4_A, RODAS4_C, RODAS4_CNODES, RODAS4_D, RODAS4_E,
                                             RODAS4_M)

#: index of w = ln(v/V) in the scaled state; w = 0 ⇔ ẋ = V ⇔ X = x − x₀ extremal
W_INDEX = 1

#: the methods :func:`integrate` knows
METHODS = ("radau5", "radau5t", "radau9", "rodas4", "auto")
#: ``"auto"`` takes the order-9 Radau IIA at and below this rtol when no event or recording is asked
AUTO_HIGH_ORDER_RTOL = 1e-7


def choose_method(rtol: float, events: bool) -> str:
    """The method ``method="auto"`` uses.

    The rule comes from the work–precision study of one period of the Fig. 3 stick–slip cycle
    of Putelat et al. (2010) (``benchmarks/run.py --only springblock``): at rtol ≤ 1e-7 the
    order-9 Radau IIA reaches the same end-of-period error as the order-5 one in about half
    the CPU time (a third of the steps); at looser tolerances its stage iteration fails often
    on the stick–slip transitions and the order-5 method is cheaper.  RODAS4 (one LU of n×n,
    six right-hand sides, no Newton iteration) costs about half as much per step as the
    order-5 Radau IIA but is about 30 times less accurate at the same step count on this
    cycle, so it is never chosen; it remains available by name.  Event location and step
    recording need the order-5 method's dense output.  The order-5 method is taken in its
    transformed form (``"radau5t"``: one real and one complex 3 × 3 LU per step instead of a
    9 × 9 one, Hairer & Wanner 1996, IV.8), the same steps at less CPU per step.

    Parameters
    ----------
    rtol : float
        The requested relative tolerance.
    events : bool
        Whether crossings are located or steps recorded.

    Returns
    -------
    str
        ``"radau5t"`` or ``"radau9"``.
    """
    return "radau9" if (rtol <= AUTO_HIGH_ORDER_RTOL and not events) else "radau5t"


@dataclass(frozen=True)
class Run:
    """Result of one integration (times in seconds, states scaled as in the model)."""

    t: float
    y: np.ndarray = field(repr=False)
    status: str
    steps: int
    rejected: int
    nfev: int
    njev: int
    nlu: int
    cpu_seconds: float
    event_t: np.ndarray = field(repr=False)
    event_y: np.ndarray = field(repr=False)
    event_dir: np.ndarray = field(repr=False)
    rec_t: np.ndarray = field(repr=False)
    rec_y: np.ndarray = field(repr=False)

    def simulation(self, model: str = "spring-block") -> Simulation:
        """The run as the common result type: the recorded steps (``integrate(..., record=N)``,
        times in seconds, scaled states, linear between steps) and the located crossings as
        ``"section"`` events (guard ``"crossing"``, ``note`` = direction)."""
        log = EventLog()
        for t, y, d in zip(self.event_t, self.event_y, self.event_dir):
            log.append(Event(float(t), np.asarray(y), "crossing", "slip", "slip", "section",
                             np.asarray(y), "up" if d > 0 else "down"))
        st = status_from_text(self.status)
        return Simulation(model, self.rec_t, self.rec_y.T, log, st, st.advice, self.t, self.y, self.steps,
                          self.nfev)

    def __repr__(self) -> str:
        return (f"Run(t={self.t:.6g} s, {self.status}, steps={self.steps}, rejected={self.rejected}, "
                f"nfev={self.nfev}, events={len(self.event_t)}, cpu={self.cpu_seconds:.3g} s)")


def integrate(model: SpringBlockModel, y0, t_span: tuple[float, float], *, rtol: float = 1e-9,
              atol: float | np.ndarray | None = None, max_steps: int = 5_000_000,
              event_index: int = -1, event_value: float = 0.0, event_direction: int = 0,
              stop_after: int = 0, max_events: int = 100_000, record: int = 0,
              first_step: float | None = None, max_step: float = np.inf, variational: bool = False,
              method: str = "radau5") -> Run:
    """Integrate eq. (4) from ``y0`` (scaled state) over ``t_span`` seconds with the default integrator.

    ``atol`` defaults to ``rtol`` (all variables are O(1) by construction).  ``record`` is the
    maximum number of accepted steps kept for plotting.  ``variational=True`` integrates the
    state augmented with Φ' = J(y)Φ (``y0`` of length n + n², Φ row-major) for monodromy matrices.
    Raises IntegratorError on failure.

    Parameters
    ----------
    model : SpringBlockModel
        Eq. (4) of Putelat et al. (2010) for one law, V and k.
    y0 : array_like
        Initial scaled state (ξ = X/ℓ, ln(v/V), ln(φᵢ/φᵢ₀)); ``model.perturbed(a)`` gives one
        displaced by X = a [m] along the critical mode.
    t_span : (float, float)
        Start and end times (s).
    rtol : float, optional
        Relative tolerance of the Radau IIA step-size control.
    atol : float or array_like, optional
        Absolute tolerance (default: ``rtol``; the scaled variables are O(1)).
    event_index : int, optional
        Component whose crossings of ``event_value`` are located (−1: none).
    event_value : float, optional
        The value crossed.
    event_direction : int, optional
        +1 upward, −1 downward, 0 both.
    stop_after : int, optional
        End the run after that many located crossings (0: run to the end of ``t_span``).
    record : int, optional
        Number of accepted steps kept in ``rec_t``, ``rec_y`` (from the start; 0: none).
    method : {"radau5", "radau5t", "radau9", "rodas4", "auto"}, optional
        The integrator (module docstring; ``"auto"``: :func:`choose_method`).  ``"radau9"``
        locates no events and records no steps.

    Returns
    -------
    Run
        Final time and state, the located events and the recorded steps (convert states
        with ``model.to_physical``), step counts and CPU time.

    Raises
    ------
    IntegratorError
        With the time and the physical state at failure.

    References
    ----------
    Hairer, E., Wanner, G. (1996). Solving Ordinary Differential Equations II, 2nd ed.,
    Springer, Sec. IV.8 (Radau IIA), IV.7 and VI.4 (Rosenbrock methods, RODAS).
    """
    if method not in METHODS:
        raise InputError(f"method must be one of {', '.join(METHODS)}, got {method!r}")
    if method == "auto":
        method = choose_method(float(rtol), event_index >= 0 or record > 0)
    if method == "radau9" and (event_index >= 0 or record > 0):
        raise InputError("method 'radau9' locates no events and records no steps: use 'radau5'")
    c = compile_variational(model.law) if variational else model.compiled
    nn = c.n
    if not (0 < rtol < 1):
        raise InputError(f"rtol must be in (0, 1), got {rtol!r}")
    y0 = np.ascontiguousarray(y0, dtype=float)
    if y0.shape != (nn,):
        raise InputError(f"initial state must have {nn} components, got shape {y0.shape}")
    tu = model.time_unit
    t0, t1 = float(t_span[0]) / tu, float(t_span[1]) / tu
    if not t1 > t0:
        raise InputError("t_span must be increasing")
    at = np.full(nn, rtol if atol is None else 0.0) if atol is None or np.isscalar(atol) else None
    if at is None:
        at = np.ascontiguousarray(atol, dtype=float)
    elif atol is not None:
        at[:] = float(atol)
    h0 = (first_step / tu) if first_step else min(1e-3 * (t1 - t0), 1e-4)
    ms = max_step / tu if np.isfinite(max_step) else np.inf
    evbuf = np.empty((max_events if event_index >= 0 else 1, nn + 1))
    evdir = np.empty(evbuf.shape[0])
    tic = time.process_time()
    af, aj = addresses(c.rhs, c.jac)
    if method == "radau9":
        tb = radau_tableau(5)
        st, t, y, cnt = collocation_at(af, aj, t0, y0, t1, model.p, float(rtol), at, float(h0), float(ms),
                                       int(max_steps), tb.A, tb.c, tb.e, tb.mu, tb.vinv)
        et, ey, rt, ry = np.empty(0), np.empty((0, nn)), np.empty(0), np.empty((0, nn))
    elif method == "rodas4":
        # eq. (4) is autonomous (the loading enters through ξ = X/ℓ in the co-moving frame): no ∂f/∂t
        st, t, y, cnt, et, ey, rt, ry, _, _ = rosenbrock_at(
            af, aj, t0, y0, t1, model.p, float(rtol), at, float(h0), float(ms), int(max_steps), int(event_index),
            float(event_value), int(event_direction), int(stop_after), int(record), 1, 0, RODAS4_A, RODAS4_C,
            RODAS4_CNODES, RODAS4_D, RODAS4_M, RODAS4_E, evbuf, evdir)
    elif method == "radau5t":
        st, t, y, cnt, et, ey, rt, ry, _, _ = radau_split_at(
            af, aj, t0, y0, t1, model.p, float(rtol), at, float(h0), float(ms), int(max_steps), int(event_index),
            float(event_value), int(event_direction), int(stop_after), int(record), A_RADAU, VINV, T_SPLIT, TI_SPLIT,
            GAMMA_SPLIT, ALPHA_SPLIT, BETA_SPLIT, evbuf, evdir)
    else:
        st, t, y, cnt, et, ey, rt, ry, _, _ = radau_at(af, aj, t0, y0, t1, model.p, float(rtol), at, float(h0),
                                                       float(ms), int(max_steps), int(event_index),
                                                       float(event_value), int(event_direction), int(stop_after),
                                                       int(record), A_RADAU, VINV, evbuf, evdir)
    cpu = time.process_time() - tic
    if st < 0:
        phys = model.to_physical(y[:model.n])
        state = [float(phys["X"]), float(phys["v"])] + [float(phys[s.name]) for s in model.law.states]
        raise IntegratorError(f"spring-block[{model.law.name}] integration failed: {STATUS[int(st)]} after "
                              f"{int(cnt[0])} steps (state = X [m], v [m/s], phi...): "
                              f"{status_from_text(STATUS[int(st)]).advice}", t=float(t * tu), state=state)
    return Run(float(t * tu), y.copy(), STATUS[int(st)], int(cnt[0]), int(cnt[1]), int(cnt[2]), int(cnt[3]),
               int(cnt[4]), cpu, et * tu, ey, evdir[:len(et)].astype(int).copy(), rt * tu, ry)
