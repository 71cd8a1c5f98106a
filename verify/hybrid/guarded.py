"""Compiled guards inside the compiled DOP853 loop: a mode's events screened and located without Python.

A mode whose guards come as one compiled vector function (:attr:`landau.verify.hybrid.model.Mode.guard_kernel`,
``gfun(t, y, p, out)`` with ``out[j]`` = guard j) is integrated by :func:`guarded_steps`: the
DOP853 steps follow one another inside one compiled call
(:func:`landau.verify.hybrid.dop853.run_screened`, the loop of the affine guards too), each
tested by the engine's scan test (:func:`landau.verify.hybrid.locate._quiet_guards`) on the
guard values at the step's dense-output samples and at its end, and the call returns to Python
only with the step where a guard may cross (or at ``t_bound``).  The engine brackets the crossing
on that step's samples (:func:`landau.verify.hybrid.locate.first_crossing`) and refines the root
of the compiled guard on the step's dense output (:func:`landau.verify.hybrid.dop853.event_root`,
bisection to the engine's ``xtol``): the steps are those of the Python route (the step-size
control does not see the guards), the guard values those of the Python guards to rounding, so the
event times agree with the Python route's to ``xtol`` plus the rounding of the guard divided by
its slope.

Guards that are not affine in the state (a gap y − l cos φ, a contact force λ_N(φ, φ̇, ẏ)) thus
stay in compiled code.  The guard function reaches the loop as a first-class function of the
kernels' type (:func:`landau.verify.hybrid.dop853.kernel_function`), so the loop compiles once
per machine for every model.
"""

from __future__ import annotations

import numpy as np
from numba import njit, types

from landau.verify.compiling import compile_once
from landau.verify.hybrid.dop853 import FUN_T, advance

__all__ = ["guarded_steps", "StepRecord", "run_to_upcrossing", "upcrossing_step"]


class StepRecord:
    """The buffer in which the compiled loop (:func:`landau.verify.hybrid.dop853.run_screened`)
    records quiet steps for the engine's recorder (the ``Recorder`` of
    :mod:`landau.verify.hybrid.record`: its count, bound, stride and step counter go in, the
    samples come out in one piece per call)."""

    __slots__ = ("t", "y", "info")

    def __init__(self, n: int, size: int = 4096):
        self.t, self.y = np.empty(size), np.empty((n, size))
        self.info = np.zeros(5, dtype=np.int64)

    def load(self, recorder) -> None:
        self.info[:] = (0, recorder.count, recorder.cap, recorder.stride, recorder.k)

    def flush(self, recorder, seg_t: list, seg_y: list) -> None:
        """Hand the samples written to the recorder's lists (its count and step counter follow)."""
        w = int(self.info[0])
        if w:
            seg_t.append(self.t[:w].copy())
            seg_y.append(self.y[:, :w].copy())
        recorder.count, recorder.k = int(self.info[1]), int(self.info[4])
        self.info[0] = 0


def guarded_steps(solver, guard_kernel, s, g_last, dec_before, state, guard_atol, dip_factor,
                  max_steps=1_000_000, record: StepRecord | None = None, values: np.ndarray | None = None):
    """The compiled screened run (:meth:`~landau.verify.hybrid.dop853.DOP853Solver.run_guarded`) of a
    :class:`~landau.verify.hybrid.dop853.DOP853Solver` whose mode's guards are one compiled vector
    function (its state, step size and buffers advanced as by its ``run_quiet``).

    Parameters
    ----------
    solver : DOP853Solver
        A running solver.
    guard_kernel : Kernel
        The mode's guards as one compiled vector function (``fun``, ``p``).
    s : ndarray
        Interior sample fractions of a step.
    g_last, dec_before, state : ndarray
        The engine's guard values at the last step end, whether each was decreasing there and
        its arming state (advanced in place past every quiet step).
    guard_atol, dip_factor : float
        As in :func:`landau.verify.hybrid.locate._quiet_guards`.
    max_steps : int
        Step budget of this call.
    record : StepRecord, optional
        Where the quiet steps are recorded (loaded from the engine's recorder beforehand).
    values : ndarray, optional
        (guards, 3 len(s) + 1) buffer that receives the last step's guard values (the samples,
        then the step end).

    Returns
    -------
    tuple
        (error message or None, code, steps taken): code 1: the last step (``t_old`` → ``t``,
        ``dense_output()``) is the one to scan; 2: ``t_bound`` reached with every step quiet;
        3: ``max_steps`` quiet steps; 4: the record buffer is full or past its bound; 0: the
        step size became too small.
    """
    if values is None:
        values = np.empty((len(g_last), 3 * len(s) + 1))
    rec = (record.t, record.y, record.info) if record is not None else None
    return solver.run_guarded(guard_kernel, s, g_last, dec_before, state, guard_atol, dip_factor, max_steps, values,
                              rec)


@njit(cache=True)
def run_to_upcrossing(fun, p, t, y, f, h_abs, hmax, t_bound, rtol, atol, max_steps, index, level, t_after, g,
                      K, y_old):
    """Steps of DOP853 from (t, y), f = f(t, y), until the first step at whose ends the section
    g = y[index] − level (masked to −1 up to ``t_after``) goes from g ≤ 0 to g ≥ 0; ``g`` is its
    value at the start.  y, f are advanced in place, K holds the last step's stages and y_old its
    start.  Returns (code, t_old, t, h_used, h_abs_next, nfev, nsteps); code 1: the crossing
    step, 2: ``t_bound`` reached without one, 3: ``max_steps`` steps, 0: step size too small."""
    n = y.shape[0]
    ynew, fnew = np.empty(n), np.empty(n)
    nfev, nsteps, t_old, h_used = 0, 0, t, 0.0
    while nsteps < max_steps:
        ok, tn, hu, h_abs, nf = advance(fun, p, t, y, f, h_abs, hmax, t_bound, rtol, atol, K, ynew, fnew)
        nfev += nf
        if not ok:
            return 0, t_old, t, h_used, h_abs, nfev, nsteps
        nsteps += 1
        h_used = hu
        for a in range(n):
            y_old[a] = y[a]
            y[a] = ynew[a]
            f[a] = fnew[a]
        t_old = t
        t = tn
        g_new = y[index] - level if t > t_after else -1.0
        if g <= 0.0 <= g_new:
            return 1, t_old, t, h_used, h_abs, nfev, nsteps
        if t >= t_bound:
            return 2, t_old, t, h_used, h_abs, nfev, nsteps
        g = g_new
    return 3, t_old, t, h_used, h_abs, nfev, nsteps


_CROSS: list = []


def upcrossing_step(solver, index: int, level: float, t_after: float, max_steps: int = 1_000_000):
    """Advance a :class:`~landau.verify.hybrid.dop853.DOP853Solver` to the first step across which
    y[index] − level goes from ≤ 0 to ≥ 0 at the step ends, the section masked (−1) up to
    ``t_after`` — the event rule of ``scipy.integrate.solve_ivp`` for a terminal event of direction
    +1 — in one compiled call (:func:`run_to_upcrossing`); the same steps as calling
    ``solver.step()`` and testing the section in Python.

    Returns
    -------
    bool
        True: the last step (``t_old`` → ``t``, ``dense_output()``) crosses; False: ``t_bound``
        or ``max_steps`` came first (``solver.status`` says which), or the step size became too
        small (``solver.status == "failed"``).
    """
    if solver.status != "running":
        raise RuntimeError("attempt to step on a finished or failed solver")
    if not _CROSS:
        f64, arr, i64 = types.float64, types.float64[::1], types.int64
        sig = (FUN_T, arr, f64, arr, arr, f64, f64, f64, f64, arr, i64, i64, f64, f64, f64,
               types.float64[:, ::1], arr)
        compile_once(run_to_upcrossing, sig, "the compiled DOP853 loop to a section")
        _CROSS.append(run_to_upcrossing)
    g0 = float(solver.y[index] - level) if solver.t > t_after else -1.0
    code, t_old, t, hu, hn, nf, k = _CROSS[0](
        solver._fun, solver.kernel.p, solver.t, solver.y, solver.f, solver.h_abs, solver.max_step, solver.t_bound,
        solver.rtol, solver.atol, int(max_steps), int(index), float(level), float(t_after), g0, solver._K,
        solver._y_old)
    solver.nfev += nf
    solver.nsteps += k
    solver.t, solver.h_abs = t, hn
    if k:
        solver.t_old, solver._h_used, solver._dense = t_old, hu, None
    if code == 0:
        solver.status = "failed"
        return False
    if solver.t >= solver.t_bound:
        solver.status = "finished"
    return code == 1
