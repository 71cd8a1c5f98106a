"""The hybrid simulation loop.

``simulate(model, mode, y0, (t0, t_end), stepper)`` integrates one mode at a time with a
stepper that has dense output (see :mod:`landau.verify.hybrid.steppers`), scans the mode's
guards on every step (:mod:`landau.verify.hybrid.locate`; when no trajectory is recorded, a
step is first screened on its cubic Hermite interpolant and the dense output is built only
where a guard may cross; with a compiled stepper that offers ``run_quiet`` and a mode whose
guards are all affine, the quiet steps run in one compiled call, tested on the stepper's own
dense output; a stepper that offers ``affine_root`` also refines an affine guard's root in compiled
code), applies the earliest switching transition at its root (taken on the new side of the
guard), logs every event, and
watches for Zeno accumulation (:mod:`landau.verify.hybrid.zeno`).

Phase starts and zero-length phases
-----------------------------------
At the start of a phase each guard is classified by its value g0:

* g0 > ``guard_atol``: armed;
* g0 < -``guard_atol``: already violated -> its transition fires at once (a zero-length
  phase, logged with kind ``"zero-length"``);
* |g0| <= ``guard_atol`` (the state sits on that switching surface, e.g. just after the
  transition that put it there): *pending*.  A pending guard is armed once a sample is
  positive; if it goes negative first, the flow leaves the mode at once and the guard
  fires at the last sample where it was still ~0 (again a zero-length phase).

Simultaneous guards: the earliest root wins; guards whose roots lie within
``simultaneous_tol`` of it are named in the event's note, and each of them fires in turn
as a zero-length phase of the next mode if it is still violated there.
"""

from __future__ import annotations

import functools
import warnings
from dataclasses import dataclass, field, replace
from typing import Any, Callable

import numpy as np

from landau.errors import InputError, IntegratorError
from landau.verify.hybrid.locate import HermiteScreen, first_crossing, guard_on_dense, root_new_side
from landau.verify.hybrid.log import Event, EventLog
from landau.verify.hybrid.model import Guard, HybridModel, as_jump
from landau.verify.hybrid.record import Recorder, Segment, close_segment
from landau.verify.hybrid.result import Simulation, status_from_text
from landau.verify.hybrid.steppers import DEFAULT_STEPPER
from landau.verify.hybrid.zeno import ZenoDiagnosis, ZenoMonitor


@dataclass(frozen=True)
class EngineOptions:
    """Knobs of the hybrid loop (not of the mode integrator).

    samples: interior dense-output samples per step used to scan the guards (0: guards are
        checked at step ends only — fastest, but a double crossing inside one step can then
        be missed; the dense output is only built when a root must be located).
    guard_atol: |g| below this counts as "on the surface" at a phase start.
    xtol: absolute tolerance of the root (event time) search.
    zeno_interval: an event spacing below this (relative to max(1, |t|)) with shrinking
        spacings is Zeno accumulation.
    max_event_rate, rate_window: cap on events per unit time.
    max_events: total cap; max_zero_length: cap on consecutive zero-length phases (a
        transition loop).
    recover_tol: a guard within this of 0 at a phase start that increases (``Guard.rate``)
        does not fire.
    zeno_relative: True (default): ``zeno_interval`` is relative to max(1, |t|); False: it is
        an absolute time (ending chattering when the inter-impact time < a fixed tolerance).
    record: keep the sampled trajectory (for plots); off for fast maps.
    max_steps: step budget of the whole run; past it the run ends with status ``"max_steps"``
        (:attr:`~landau.verify.hybrid.result.Status.MAX_STEPS`) at the last step taken.
    max_samples: bound on the recorded samples: past it the recorded trajectory is thinned
        (every other sample dropped, each segment's ends kept) and from then on only every
        2ᵏ-th step end is recorded, so a long run keeps at most ~``max_samples`` points spread
        over the whole run.
    screen: with a mode whose guards come compiled (``Mode.guard_kernel``) and the compiled
        DOP853, screen each step on its dense output inside the compiled loop (recording or
        not, ``samples`` > 0); otherwise, when not recording, first sample the guards on each
        step's cubic Hermite interpolant with an error bound and build the dense output only
        for steps where that could trigger the scan
        (:class:`~landau.verify.hybrid.locate.HermiteScreen`): the same events, without the
        dense output's extra stages on quiet steps; with a stepper that
        has ``run_quiet`` and a mode whose guards declare ``affine``, the same scan test on the
        stepper's dense output inside its compiled loop).  False: scan every step on the
        dense output.
    """

    samples: int = 4
    guard_atol: float = 1e-13
    xtol: float = 1e-14
    simultaneous_tol: float = 1e-10
    zeno_interval: float = 1e-6
    max_event_rate: float = 1e7
    rate_window: float = 1e-3
    max_events: int = 1_000_000
    max_zero_length: int = 64
    recover_tol: float = 1e-9
    record: bool = True
    zeno_relative: bool = True
    screen: bool = True
    max_steps: int = 2_000_000
    max_samples: int = 200_000


@dataclass(frozen=True, kw_only=True)
class HybridSolution(Simulation):
    """Outcome of :func:`simulate`: a :class:`~landau.verify.hybrid.result.Simulation` with the
    hybrid engine's extras.

    The common fields: ``t``, ``y`` the concatenated recorded segments (empty when the run
    records nothing, ``EngineOptions(record=False)``); ``t_final``, ``y_final`` where the run
    ended; ``status`` — :attr:`~Status.FINISHED` (reached the final time),
    :attr:`~Status.STOPPED` (the ``stop`` predicate or a terminal guard), :attr:`~Status.ZENO` /
    :attr:`~Status.EVENT_RATE` (accumulation; see ``zeno``), :attr:`~Status.MAX_EVENTS`,
    :attr:`~Status.MAX_STEPS`; ``regimes`` read off the mode changes (:func:`regime_of`).

    Attributes
    ----------
    final_mode : str
        The mode the run ended in.
    segments : tuple of Segment
        The recorded pieces of trajectory, one per phase (empty when not recording).
    zeno : ZenoDiagnosis or None
        The accumulation diagnosis when the status is ``ZENO`` or ``EVENT_RATE``.
    """

    final_mode: str
    segments: tuple[Segment, ...] = field(default=(), repr=False)
    zeno: ZenoDiagnosis | None = None

    def __repr__(self) -> str:
        z = f", zeno={self.zeno!r}" if self.zeno else ""
        return (f"HybridSolution({self.model}, {self.status.value}, t_final={self.t_final:.12g}, "
                f"final_mode={self.final_mode!r}, {len(self.t)} points, {len(self.events)} events, "
                f"{self.nsteps} steps, {self.nfev} fev{z})")

    def simulation(self, model: str | None = None) -> Simulation:
        """Deprecated: the record is already a :class:`Simulation`.

        Parameters
        ----------
        model : str, optional
            A name for the run (default: keep ``self.model``).

        Returns
        -------
        HybridSolution
            ``self``, or a copy named ``model``.
        """
        warnings.warn("HybridSolution.simulation() is deprecated: the record is already a Simulation "
                      "(use it directly; dataclasses.replace(sol, model=...) renames it)",
                      DeprecationWarning, stacklevel=2)
        return self if model is None or model == self.model else replace(self, model=model)

    def trajectory(self) -> tuple[np.ndarray, np.ndarray, list[str]]:
        """The recorded samples with the mode of each point.

        Returns
        -------
        t : numpy.ndarray, shape (m,)
            The field ``t``.
        y : numpy.ndarray, shape (n, m)
            The field ``y``.
        modes : list of str
            The mode of each recorded point.
        """
        return self.t, self.y, [s.mode for s in self.segments for _ in s.t]


def _regimes(events: EventLog, final_mode: str, t0: float, t_end: float) -> tuple[tuple[float, float, str], ...]:
    """The run's regimes from ``t0`` to ``t_end``, ``(t_start, t_end, name)``, read off the mode
    changes in the event log (:func:`regime_of` names each mode)."""
    out, start, mode = [], float(t0), None
    for e in events:
        if e.from_mode == e.to_mode:
            continue
        if mode is None:
            mode = e.from_mode
        if e.t > start:
            start_next = float(e.t)
            out.append((start, start_next, regime_of(mode)))
            start = start_next
        mode = e.to_mode
    if mode is None:
        mode = final_mode
    if t_end > start or not out:
        out.append((start, float(t_end), regime_of(mode)))
    return tuple(out)


_EMPTY: dict[int, tuple[np.ndarray, np.ndarray]] = {}


def _empty_series(n: int) -> tuple[np.ndarray, np.ndarray]:
    """The (read-only, shared) empty ``t`` and ``y`` of a run that recorded nothing (event maps
    call the engine thousands of times)."""
    hit = _EMPTY.get(n)
    if hit is None:
        t, y = np.empty(0), np.empty((n, 0))
        t.flags.writeable = y.flags.writeable = False
        hit = _EMPTY[n] = (t, y)
    return hit


def _solution(model: HybridModel, t0: float, t: float, y: np.ndarray, mname: str, status: str,
              log: EventLog, segs: list[Segment], zeno: ZenoDiagnosis | None, nsteps: int,
              nfev: int) -> HybridSolution:
    """The :class:`HybridSolution` of a run that ended at ``(t, y)`` in mode ``mname``."""
    if segs:
        ts = np.concatenate([s.t for s in segs])
        ys = np.concatenate([s.y for s in segs], axis=1)
    else:
        ts, ys = _empty_series(len(y))
    st = status_from_text(status)
    msg = st.advice + (f" ({zeno!r})" if zeno else "")
    return HybridSolution(model.name, ts, ys, log, st, msg, t, y, nsteps, nfev,
                          regimes=_regimes(log, mname, t0, t), final_mode=mname, segments=tuple(segs),
                          zeno=zeno)


@functools.lru_cache(maxsize=1024)
def regime_of(mode: str) -> str:
    """The regime a mode name stands for: ``"flight"`` (a mode named with flight), ``"stick"``
    (``"stick"``, or a stick–slip code of ``s``/``n``/``p`` letters, one per block, all ``s``),
    ``"partial stick"`` (some blocks stuck), else ``"slip"``."""
    if "flight" in mode:
        return "flight"
    if mode == "stick":
        return "stick"
    if mode and set(mode) <= {"s", "n", "p"} and "s" in mode:
        return "stick" if set(mode) == {"s"} else "partial stick"
    return "slip"


ARMED, PENDING, DISARMED = 1, 0, -1


def _leaving(guard: Guard, g: float, t: float, y: np.ndarray, recover_tol: float) -> bool:
    """A guard violated at a phase start by at most ``recover_tol`` whose rate says the flow is
    already leaving it (no zero-length phase)."""
    return guard.rate is not None and g > -recover_tol and guard.rate(t, y) > 0


def _eval_guards(guards, t, y) -> np.ndarray:
    return np.array([float(g.fun(t, y)) for g in guards]) if guards else np.empty(0)


def simulate(model: HybridModel, mode: str, y0, t_span: tuple[float, float],
             stepper: Callable = DEFAULT_STEPPER, options: EngineOptions = EngineOptions(),
             stop: Callable[[Event], bool] | None = None) -> HybridSolution:
    """Integrate a hybrid model from ``(t0, y0)`` in ``mode`` until ``t_end``.

    ``stop(event) -> bool`` ends the run after a logged event (used for event maps).
    Raises :class:`~landau.errors.IntegratorError` if a mode integrator fails or the state
    becomes non-finite, or if the vector field is not finite at the initial state (never
    returns a silently truncated result), and :class:`~landau.errors.InputError` for an
    unknown mode, a non-finite initial state or a time span that is not finite and increasing.

    The loop runs phase by phase: a guard already violated at the phase start fires at once
    (:func:`_violated_at_start`); otherwise the mode is integrated until a switching guard
    crosses, the run stops or ends (:func:`_run_phase`); the transition is then applied, logged
    and watched for accumulation (:func:`_apply_transition`).

    Parameters
    ----------
    model : HybridModel
        The modes, guards and jumps.
    mode : str
        The starting mode.
    y0 : array_like
        The starting state.
    t_span : tuple of float
        ``(t0, t_end)``.
    stepper : callable, optional
        Integrator of one mode's smooth field (default
        :data:`~landau.verify.hybrid.steppers.DEFAULT_STEPPER`: the compiled DOP853, rtol 1e-10,
        atol 1e-12).
    options : EngineOptions, optional
        Event location, Zeno and recording settings.
    stop : callable, optional
        ``stop(event) -> bool``: end the run after a logged event.

    Returns
    -------
    HybridSolution
        A :class:`~landau.verify.hybrid.result.Simulation`: the recorded trajectory, the event
        log, the status, the final state and mode.
    """
    run = _Run(model, mode, y0, t_span, stepper, options, stop)
    while True:
        m = model.mode(run.mname)
        g0 = _eval_guards(m.guards, run.t, run.y)
        fire_now = _violated_at_start(m.guards, g0, run.t, run.y, options.guard_atol, options.recover_tol)
        if fire_now is None:
            outcome = _run_phase(run, m, g0)
            if isinstance(outcome, HybridSolution):
                return outcome
            j, kind, simul = outcome
        else:
            j, kind, simul = fire_now, "zero-length", []
        ended = _apply_transition(run, m.guards, j, kind, simul)
        if ended is not None:
            return ended


class _Run:
    """The state of one :func:`simulate` run that outlives a phase: where the run is (``t``,
    ``y``, mode ``mname``), what it has logged and recorded, its step and evaluation counts, and
    the settings and helpers every phase uses."""

    __slots__ = ("model", "t0", "t_end", "t", "y", "mname", "stepper", "options", "stop", "log", "segs",
                 "monitor", "nodes", "screen", "nsteps", "nfev", "n_zero", "rec", "rbufs", "checked", "atol")

    def __init__(self, model: HybridModel, mode: str, y0, t_span: tuple[float, float], stepper: Callable,
                 options: EngineOptions, stop: Callable[[Event], bool] | None) -> None:
        """Check the inputs (:class:`~landau.errors.InputError` naming what is wrong) and set the
        run up at ``(t0, y0)`` in ``mode``."""
        t0, t_end = map(float, t_span)
        if not (np.isfinite(t0) and np.isfinite(t_end) and t_end > t0):
            raise InputError(f"time span must be finite and increasing (t0 < t_end), got {tuple(t_span)!r}")
        y = np.array(y0, dtype=float)
        if not np.all(np.isfinite(y)):
            raise InputError(f"initial state must be finite, got {y.tolist()!r}")
        if mode not in model.modes:
            raise InputError(f"model {model.name!r} has no mode {mode!r} (modes: {', '.join(sorted(model.modes))})")
        self.model, self.t0, self.t_end = model, t0, t_end
        self.t, self.y, self.mname = t0, y, mode
        self.stepper, self.options, self.stop = stepper, options, stop
        self.log = EventLog()
        self.segs: list[Segment] = []
        self.monitor = ZenoMonitor(options.zeno_interval, options.max_event_rate, options.rate_window,
                                   relative=options.zeno_relative)
        self.nodes = np.arange(1, options.samples + 2) / (options.samples + 1)
        self.screen = (HermiteScreen(options.samples) if options.screen and options.samples > 0
                       and not options.record else None)
        self.nsteps = self.nfev = 0
        self.n_zero = 0
        self.rec = Recorder(options.max_samples)
        self.rbufs: dict[int, Any] = {}   # the compiled loop's record buffers, one per state dimension
        self.checked: dict[str, bool] = {}  # modes whose compiled guards agreed with the Python guards
        self.atol = options.guard_atol

    def finish(self, status: str, zeno: ZenoDiagnosis | None = None) -> HybridSolution:
        """The run's :class:`HybridSolution`, ended at the current ``(t, y)`` with ``status``."""
        extra = self.screen.nfev if self.screen is not None else 0  # the screen's y'' at phase starts
        return _solution(self.model, self.t0, self.t, self.y, self.mname, status, self.log, self.segs, zeno,
                         self.nsteps, self.nfev + extra)


class _Phase:
    """One phase of a run (the integration of one mode from a phase start): the mode's guards
    and their scan state (``state`` armed/pending/disarmed, the last values ``g_last``, whether
    each was decreasing ``dec_before``), the mode's solver, the segment being recorded, and the
    compiled helpers the phase uses (``affine``: guards screened inside the stepper's compiled
    loop; ``gk``: the compiled guard vector; ``roots``: the affine forms for compiled root
    refinement; ``active``: the Hermite screen)."""

    __slots__ = ("m", "guards", "solver", "state", "dec_before", "g_last", "seg_t", "seg_y", "affine", "gk",
                 "rbuf", "gvals", "roots", "active")

    m: Any
    guards: tuple[Guard, ...]
    solver: Any
    state: np.ndarray
    dec_before: np.ndarray
    g_last: np.ndarray
    seg_t: list[np.ndarray]
    seg_y: list[np.ndarray]
    affine: tuple[np.ndarray, np.ndarray, np.ndarray] | None
    gk: Any
    rbuf: Any
    gvals: np.ndarray | None
    roots: tuple[np.ndarray, np.ndarray, np.ndarray] | None
    active: HermiteScreen | None


def _violated_at_start(guards, g0: np.ndarray, t: float, y: np.ndarray, atol: float,
                       recover_tol: float) -> int | None:
    """The first switching guard already violated at the phase start (``g0 < -atol``) that is not
    leaving it (:func:`_leaving`): its transition fires at once (a zero-length phase); None when
    there is none."""
    is_switch = np.array([gd.transition is not None for gd in guards], bool)
    viol = [j for j in np.nonzero((g0 < -atol) & is_switch)[0]
            if not _leaving(guards[j], g0[j], t, y, recover_tol)]
    return int(viol[0]) if len(viol) else None


def _run_phase(run: _Run, m, g0: np.ndarray) -> HybridSolution | tuple[int, str, list[str]]:
    """Integrate mode ``m`` from the phase start until a switching guard crosses, the run stops
    or it ends.  Returns the run's :class:`HybridSolution` when it ends in this phase, else the
    hit ``(j, kind, simul)``: the guard that fired, the event kind and the simultaneous guards'
    names; ``run.t``, ``run.y`` are then the root and the state there."""
    ph = _start_phase(run, m, g0)
    while True:
        all_quiet, msg = _take_steps(run, ph)
        if all_quiet is _AGAIN:
            continue
        solver = ph.solver
        if solver.status == "failed":
            raise IntegratorError(f"mode {run.mname!r}: {msg}", t=solver.t, state=solver.y)
        if all_quiet is None or (run.nsteps >= run.options.max_steps and solver.status != "finished"):
            # the step budget ran out (every step so far quiet or scanned)
            return _end_at_solver(run, ph, "max_steps", np.array(solver.y, dtype=float))
        if all_quiet:
            return _end_at_solver(run, ph, "t_end", solver.y.copy())
        t_old, t_new = solver.t_old, solver.t
        if _screened_quiet(run, ph, t_old, t_new):
            if solver.status == "finished":
                return _end_at_solver(run, ph, "t_end", solver.y.copy())
            continue
        dense = _LazyDense(solver)  # built only if a sample or a root needs it
        ts_int = t_old + (t_new - t_old) * run.nodes[:-1]
        # the samples' states (for the Python guards and the record; the compiled loop gave
        # the compiled guards' values at the same samples)
        Y = (None if ph.gvals is not None and not run.options.record else
             np.column_stack([dense(ts_int), solver.y]) if len(ts_int) else solver.y[:, None])
        ts = np.concatenate([[t_old], ts_int, [t_new]])
        cands = _scan_guards(run, ph, ts, Y, dense)
        if cands:
            located = _locate_roots(run, ph, cands, dense)
            if _log_sections(run, ph, located, ts, Y, dense):
                return run.finish("stop")
            hit = _switch_hit(run, ph, located, ts, Y, dense, t_new)
            if hit is not None:
                return hit
        if run.options.record:
            run.rec.push(ph.seg_t, ph.seg_y, ts[1:], Y)
            run.rec.bound(run.segs, ph.seg_t, ph.seg_y)
        if solver.status == "finished":
            return _end_at_solver(run, ph, "t_end", solver.y.copy())


#: :func:`_take_steps`' answer when the compiled loop stopped only to hand over its record buffer
_AGAIN = object()


def _start_phase(run: _Run, m, g0: np.ndarray) -> _Phase:
    """Set a phase up: classify the guards by their values ``g0`` at the phase start (armed above
    ``guard_atol``, else pending for a switching guard and disarmed for a section), check the
    vector field at the run's very start, make the mode's solver and choose how its steps are
    screened (the stepper's compiled quiet loop with affine guards, the compiled guard vector, the
    Hermite screen, or a dense-output scan of every step)."""
    options, atol, screen, t, y = run.options, run.atol, run.screen, run.t, run.y
    ph = _Phase()
    ph.m, ph.guards = m, m.guards
    is_switch = np.array([gd.transition is not None for gd in ph.guards], bool)
    ph.state = np.where(g0 > atol, ARMED, np.where(is_switch, PENDING, DISARMED))
    g0 = np.maximum(g0, -atol)  # recovering guards start as pending
    ph.dec_before = np.zeros(len(ph.guards), bool)
    ph.g_last = g0.copy()
    if t == run.t0 and len(run.log) == 0:
        # scipy's initial step selection never ends on a NaN vector field
        f0 = np.asarray(m.rhs(t, y), dtype=float)
        if not np.all(np.isfinite(f0)):
            raise IntegratorError(f"mode {run.mname!r}: the vector field is not finite at the initial "
                                  f"state ({f0.tolist()!r})", t=t, state=y)
    fun = m.kernel() if m.kernel is not None and _is_compiled(run.stepper) else m.rhs
    solver = ph.solver = run.stepper(fun, t, y, run.t_end, m.jac)
    ph.seg_t, ph.seg_y = [np.array([t])], [y[:, None]]
    # the Hermite screen needs the vector field at the step ends; it is off when samples
    # are recorded for plots.  A compiled stepper with run_quiet screens affine guards on
    # its own dense output inside its compiled loop instead.
    ph.affine = _affine_guards(m) if screen is not None and hasattr(solver, "run_quiet") else None
    # guards compiled as one vector function: screened inside the compiled loop as well
    ph.gk = (_guard_kernel(m, solver, t, y, g0, atol, run.checked)
             if ph.affine is None and options.screen and options.samples > 0 else None)
    ph.rbuf = _step_record(run.rbufs, len(y)) if ph.gk is not None and options.record else None
    ph.gvals = (np.empty((len(ph.guards), 3 * len(run.nodes) - 2)) if ph.gk is not None
                else None)  # a step's values
    ph.roots = _affine_guards(m) if hasattr(solver, "affine_root") else None
    ph.active = (screen if ph.affine is None and ph.gk is None and screen is not None and _keeps_current_f(solver)
                 else None)
    if ph.active is not None:
        ph.active.start(solver.y, solver.f, len(ph.guards), m.rhs)
    return ph


def _take_steps(run: _Run, ph: _Phase) -> tuple[Any, Any]:
    """Advance the phase's solver: many quiet steps in one compiled call (the stepper's
    ``run_quiet`` with affine guards, or the compiled guard vector's loop), else one step.
    Returns ``(all_quiet, msg)``: ``all_quiet`` True when the run reached its end with every step
    quiet, False when the last step taken must be scanned, None when the step budget ran out,
    :data:`_AGAIN` when the compiled loop only handed over its full record buffer; ``msg`` the
    solver's message."""
    options, screen, solver = run.options, run.screen, ph.solver
    if ph.affine is not None and screen is not None:   # (affine is only built with a screen)
        msg, all_quiet, k = solver.run_quiet(*ph.affine, run.nodes[:-1], ph.g_last, ph.dec_before, ph.state,
                                             run.atol, screen.dip_factor, max(1, options.max_steps - run.nsteps))
        run.nsteps += k
    elif ph.gk is not None:
        from landau.verify.hybrid.guarded import guarded_steps

        if ph.rbuf is not None:
            ph.rbuf.load(run.rec)
        msg, code, k = guarded_steps(solver, ph.gk, run.nodes[:-1], ph.g_last, ph.dec_before, ph.state, run.atol,
                                     screen.dip_factor if screen is not None else 2.0,
                                     max(1, options.max_steps - run.nsteps), ph.rbuf, ph.gvals)
        run.nsteps += k
        if ph.rbuf is not None:   # the quiet steps' samples, as the per-step record keeps them
            ph.rbuf.flush(run.rec, ph.seg_t, ph.seg_y)
            run.rec.bound(run.segs, ph.seg_t, ph.seg_y)
        if code == 4 and run.nsteps < options.max_steps:
            return _AGAIN, msg
        all_quiet = None if code in (3, 4) else code == 2
    else:
        msg, all_quiet = solver.step(), False
        run.nsteps += 1
    return all_quiet, msg


def _end_at_solver(run: _Run, ph: _Phase, status: str, y: np.ndarray) -> HybridSolution:
    """End the run where the phase's solver is (state ``y``), with ``status``: count the solver's
    evaluations and close the recorded segment (a thinned record keeps the final state)."""
    run.nfev += ph.solver.nfev
    run.t, run.y = ph.solver.t, y
    if run.options.record:
        if ph.seg_t[-1][-1] < run.t:
            ph.seg_t.append(np.array([run.t]))
            ph.seg_y.append(y[:, None])
        run.segs.append(Segment(run.mname, np.concatenate(ph.seg_t), np.concatenate(ph.seg_y, axis=1)))
    return run.finish(status)


def _screened_quiet(run: _Run, ph: _Phase, t_old: float, t_new: float) -> bool:
    """Whether the step just taken is quiet by the Hermite screen (no guard can cross on it, so
    it needs no dense output); raises :class:`~landau.errors.IntegratorError` on a non-finite
    state."""
    solver, active = ph.solver, ph.active
    probe = (active.advance(t_old, t_new, np.asarray(solver.y, dtype=float), np.asarray(solver.f, dtype=float))
             if active is not None else 0 if np.isfinite(solver.y).all() else -1)
    if probe < 0:
        raise IntegratorError(f"mode {run.mname!r}: non-finite state", t=t_old, state=run.y)
    return bool(probe > 0 and active is not None
                and active.quiet(ph.guards, ph.g_last, ph.dec_before, ph.state, run.atol))


def _scan_guards(run: _Run, ph: _Phase, ts: np.ndarray, Y: np.ndarray | None,
                 dense: _LazyDense) -> list[tuple[Any, int, str]]:
    """Scan every guard on the step's samples ``ts`` (states ``Y``, or the compiled loop's guard
    values): arm pending guards at their first positive sample, and collect the candidates
    ``(bracket or time, guard, kind)`` — a crossing bracket (``"cross"``), or the time of a
    pending guard that leaves the mode before ever entering it (``"zero"``)."""
    atol, guards, state, g_last, dec_before = run.atol, ph.guards, ph.state, ph.g_last, ph.dec_before
    cands: list[tuple[Any, int, str]] = []   # (bracket or time, guard, kind)
    for j, g in enumerate(guards):
        if ph.gvals is not None:
            G_step = ph.gvals[j, :len(ts) - 1]
        else:   # Y is built whenever the compiled loop gave no guard values
            assert Y is not None
            G_step = np.atleast_1d(g.fun(ts[1:], Y))
        G = np.concatenate([[g_last[j]], G_step])
        st = state[j]
        g_last[j] = G[-1]
        start = 0
        if st != ARMED:  # arm at the first positive sample
            pos = np.nonzero(G[1:] > atol)[0]
            kpos = pos[0] + 1 if len(pos) else len(G)
            if st == PENDING and g.transition is None:
                st = DISARMED  # a section never fires at a phase start
            if st == PENDING:
                negs = np.nonzero(G[1:] < -atol)[0]
                if len(negs) and negs[0] + 1 < kpos:
                    _pending_leaves(cands, j, g, ts, negs, state, dense, atol)
                    continue
            if kpos == len(G):
                continue
            start = kpos
            state[j] = ARMED
        br = first_crossing(G, ts, start, guard_on_dense(g.fun, dense), bool(dec_before[j]))
        if br is not None:
            cands.append((br, j, "cross"))
        dec_before[j] = G[-1] < G[-2]
    return cands


def _pending_leaves(cands: list, j: int, g: Guard, ts: np.ndarray, negs: np.ndarray, state: np.ndarray,
                    dense: _LazyDense, atol: float) -> None:
    """A pending guard ``j`` whose samples go negative before they go positive: a short
    excursion into the mode between samples (the mirror of the double-crossing check: g is
    maximised before the first negative sample) arms it with a crossing bracket; otherwise the
    flow leaves the mode before ever entering it, a zero-length phase at the last sample where
    the guard was still ~0."""
    kneg = negs[0] + 1
    gs = guard_on_dense(g.fun, dense)
    from scipy.optimize import minimize_scalar

    res = minimize_scalar(lambda s, gs=gs: -gs(s), bounds=(ts[0], ts[kneg]),
                          method="bounded",
                          options={"xatol": 1e-10 * (ts[kneg] - ts[0]) + 1e-15})
    if -res.fun > atol:
        cands.append(((float(res.x), ts[kneg]), j, "cross"))
        state[j] = ARMED
    else:
        # leaves the mode before ever entering it: zero-length phase
        cands.append((ts[negs[0]], j, "zero"))


def _locate_roots(run: _Run, ph: _Phase, cands: list[tuple[Any, int, str]],
                  dense: _LazyDense) -> list[tuple[float, int, str]]:
    """The candidates' event times, sorted: each crossing bracket refined to its root on the new
    side of the guard (in compiled code for affine guards or the compiled guard vector, else on the
    dense output), to ``xtol``."""
    solver, roots, gk, xtol = ph.solver, ph.roots, ph.gk, run.options.xtol
    located: list[tuple[float, int, str]] = []
    for c, j, kind in cands:
        if kind == "zero":
            located.append((c, j, "zero-length"))
        else:
            a, b = c
            if roots is not None:   # the guard's affine form, in compiled code
                r = solver.affine_root(roots[0][j], roots[1][j], roots[2][j], a, b, xtol)
            elif gk is not None and hasattr(solver, "kernel_root"):   # compiled guard vector
                r = solver.kernel_root(gk, j, len(ph.guards), a, b, xtol)
            else:
                r = root_new_side(guard_on_dense(ph.guards[j].fun, dense), a, b, xtol)
            located.append((r, j, "switch"))
    located.sort(key=lambda x: (x[0], x[1]))
    return located


def _log_sections(run: _Run, ph: _Phase, located: list[tuple[float, int, str]], ts: np.ndarray,
                  Y: np.ndarray | None, dense: _LazyDense) -> bool:
    """Log the section crossings up to the first switching guard's root (the run goes on past
    them); True when one of them is terminal or ``stop`` says so (``run.t``, ``run.y`` are then
    the crossing and the segment is closed there)."""
    guards, state = ph.guards, ph.state
    t_sw = min((x[0] for x in located if guards[x[1]].transition is not None), default=np.inf)
    for th, j, _kind in located:
        if guards[j].transition is None and th <= t_sw:
            yh = dense(th)
            ev = Event(th, yh, guards[j].name, run.mname, run.mname, "section", yh)
            run.log.append(ev)
            if ph.g_last[j] <= run.atol:
                state[j] = DISARMED
            if guards[j].terminal or (run.stop is not None and run.stop(ev)):
                run.t, run.y = th, yh
                close_segment(run.segs, run.options, run.mname, ph.seg_t, ph.seg_y, ts, Y, th, yh)
                return True
    return False


def _switch_hit(run: _Run, ph: _Phase, located: list[tuple[float, int, str]], ts: np.ndarray,
                Y: np.ndarray | None, dense: _LazyDense, t_new: float) -> tuple[int, str, list[str]] | None:
    """The earliest switching guard among the located roots, ``(j, kind, simul)`` with the names
    of the guards within ``simultaneous_tol`` of it, or None when none switches: the phase ends
    at its root (``run.t``, ``run.y``; the segment closed there, the solver's evaluations
    counted)."""
    options, guards = run.options, ph.guards
    sw = [x for x in located if guards[x[1]].transition is not None]
    if not sw:
        return None
    hit = sw[0]
    simul = [guards[x[1]].name for x in sw[1:] if x[0] - hit[0] <= options.simultaneous_tol]
    th = hit[0]
    yh = dense(th) if th < t_new else ph.solver.y.copy()
    close_segment(run.segs, options, run.mname, ph.seg_t, ph.seg_y, ts, Y, th, yh)
    if options.record:
        run.rec.count += len(ts)
        run.rec.bound(run.segs, [np.empty(0)], [np.empty((len(yh), 0))])
    run.nfev += ph.solver.nfev
    run.t, run.y = th, yh
    return hit[1], hit[2], simul


def _apply_transition(run: _Run, guards, j: int, kind: str, simul: list[str]) -> HybridSolution | None:
    """Apply the transition of guard ``j`` at ``(run.t, run.y)`` and log it; the run's
    :class:`HybridSolution` when it ends here (a terminal guard, ``stop``, the event cap, or
    accumulation that the mode's ``on_zeno`` does not handle), else None.  Raises
    :class:`~landau.errors.IntegratorError` after ``max_zero_length`` consecutive zero-length
    phases (a transition loop)."""
    options, t, y, mname = run.options, run.t, run.y, run.mname
    g = guards[j]
    assert g.transition is not None  # j is a switching guard
    jump = as_jump(g.transition(t, y))
    run.n_zero = run.n_zero + 1 if kind == "zero-length" else 0
    if run.n_zero > options.max_zero_length:
        raise IntegratorError(f"{run.n_zero} consecutive zero-length phases (transition loop) "
                              f"at guard {g.name!r} of mode {mname!r}", t=t, state=y)
    note = jump.note + (f"; simultaneous with {simul}" if simul else "")
    ev = Event(t, y, g.name, mname, jump.mode, kind, jump.y, note)
    run.log.append(ev)
    run.mname, run.y = jump.mode, np.array(jump.y, dtype=float)
    if g.terminal or (run.stop is not None and run.stop(ev)):
        return run.finish("stop")
    if len(run.log) >= options.max_events:
        return run.finish("max_events")
    return _watch_accumulation(run, ev)


def _watch_accumulation(run: _Run, ev: Event) -> HybridSolution | None:
    """Feed the event's time to the Zeno monitor: on accumulation the run ends with the
    diagnosis, unless it is Zeno accumulation in a mode with ``on_zeno``, whose jump ends the
    chattering (logged as a ``"zeno"`` event) and the run goes on."""
    t = run.t
    diag = run.monitor.push(t)
    if diag is None:
        return None
    handler = run.model.mode(ev.from_mode).on_zeno
    if handler is None or diag.kind != "zeno":
        return run.finish(diag.kind, diag)
    y = run.y
    jz = as_jump(handler(t, y))
    run.log.append(Event(t, y, "zeno", run.mname, jz.mode, "zeno", jz.y,
                         f"chattering ended: event spacing {diag.last_interval:.3g} < tolerance; "
                         f"accumulation extrapolated at t={diag.t_accumulation:.12g}"))
    run.mname, run.y = jz.mode, np.array(jz.y, dtype=float)
    run.monitor.reset()
    return None


def _is_compiled(stepper) -> bool:
    """Whether ``stepper`` is a compiled stepper factory (it integrates a mode's ``kernel``): one
    that declares ``takes_kernel = True`` (:mod:`landau.verify.hybrid.steppers`)."""
    return getattr(stepper, "takes_kernel", False) is True


_AFFINE: dict[int, tuple] = {}


def _affine_guards(mode) -> tuple[np.ndarray, np.ndarray, np.ndarray] | None:
    """(W, b, U) with the mode's guards = W·y + U·f(t, y) + b when every guard declares ``affine``
    (``(w, b)`` or ``(w, b, u)``), else None."""
    hit = _AFFINE.get(id(mode))
    if hit is not None and hit[0] is mode:
        return hit[1]
    gs = mode.guards
    out = None
    if gs and all(g.affine is not None for g in gs):
        W = np.ascontiguousarray([g.affine[0] for g in gs], dtype=float)
        U = np.ascontiguousarray([g.affine[2] if len(g.affine) > 2 else np.zeros(W.shape[1]) for g in gs],
                                 dtype=float)
        out = (W, np.array([g.affine[1] for g in gs], dtype=float), U)
    if len(_AFFINE) > 256:
        _AFFINE.clear()
    _AFFINE[id(mode)] = (mode, out)
    return out


def _guard_kernel(mode, solver, t: float, y: np.ndarray, g0: np.ndarray, atol: float, checked: dict):
    """The mode's compiled guard vector (``Mode.guard_kernel``) when the solver is the compiled
    DOP853 with numba's compiler on and the kernel agrees with the Python guards at the mode's
    first phase start of the run (``g0``, raised to at least ``-atol`` as the engine does there;
    the verdict is kept in ``checked``), else None (the Python route)."""
    if mode.guard_kernel is None or not mode.guards:
        return None
    from landau.verify.hybrid.callbacks import jit_enabled, warn_once
    from landau.verify.hybrid.dop853 import DOP853Solver

    if not isinstance(solver, DOP853Solver) or not jit_enabled():
        return None
    ok = checked.get(mode.name)
    if ok is False:
        return None
    gk = mode.guard_kernel()
    if gk is None or ok:
        return gk
    out = np.empty(len(mode.guards))
    gk.fun(float(t), np.ascontiguousarray(y, dtype=float), gk.p, out)
    out = np.maximum(out, -atol)
    scale = 1e-7 * (1.0 + np.abs(g0))
    if not np.all(np.abs(out - g0) <= scale):
        warn_once(f"guard-kernel:{gk.name}", f"landau: the compiled guards {gk.name!r} differ from the mode's "
                  f"guards at t = {t:.12g} ({out.tolist()} against {g0.tolist()}): the guards are evaluated "
                  "in Python")
        checked[mode.name] = False
        return None
    checked[mode.name] = True
    return gk


def _step_record(bufs: dict, n: int):
    """The record buffer of the compiled loop for states of dimension ``n`` (one per run)."""
    buf = bufs.get(n)
    if buf is None:
        from landau.verify.hybrid.guarded import StepRecord

        buf = bufs[n] = StepRecord(n)
    return buf


def _keeps_current_f(solver) -> bool:
    """Whether ``solver.f`` is the vector field at ``(solver.t, solver.y)`` after every step:
    scipy's explicit Runge–Kutta solvers and Radau, and a stepper that declares ``keeps_f = True``
    (the compiled DOP853; scipy's BDF/LSODA do not keep it)."""
    from scipy.integrate import DOP853, RK23, RK45, Radau

    return isinstance(solver, (DOP853, RK45, RK23, Radau)) or getattr(solver, "keeps_f", False) is True


class _LazyDense:
    """The step's interpolant, constructed on first use (it costs extra stages in DOP853)."""

    __slots__ = ("solver", "sol")

    def __init__(self, solver):
        self.solver, self.sol = solver, None

    def __call__(self, t):
        if self.sol is None:
            self.sol = self.solver.dense_output()
        return self.sol(t)
