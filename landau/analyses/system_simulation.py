"""Compiled simulation of any smooth :class:`~landau.systems.system.DynamicalSystem`: :func:`simulate_system`.

A user's system E·ẏ = f(y; p) (built in Python or by
:meth:`~landau.systems.system.DynamicalSystem.from_strings`) is integrated by the project's compiled
order-5 Radau IIA (:func:`landau.verify.hybrid.radau.radau_core`; Hairer & Wanner 1996, Sec. IV.8),
the stiff integrator, chosen as the one default because a user's system may be stiff without saying
so (a Brusselator far from its Hopf point, a rate-and-state law at a small L): it is never the wrong
choice, only a slower one for a non-stiff field.

The field and its exact Jacobian are generated once per system by the project's code generator
(:func:`landau.codegen.kernels.kernel_source`: sympy differentiates, common subexpressions are
eliminated, the source passes the generator's whitelist) and compiled through the cross-process code
cache (:func:`landau.codegen.kernels.compile_source`, :mod:`landau.verify.jitcache`: the source file is
content-addressed and rewritten unless it holds exactly the text, numba's files are signed and verified
before they are read); the compiled loop receives them as first-class functions
(:mod:`landau.verify.hybrid.callbacks`).  The mass matrix enters as parameters, not as expressions:
the generated field is g = W·f with W = E⁻¹ a block of the parameter vector (its diagonal for a
diagonal E), so one compiled kernel serves every parameter value and every mass E(p).

The compiled Radau IIA integrates y' = g(t, y) only (no mass-matrix form): a zero diagonal entry of E
(an algebraic row, a differential-algebraic system) is refused with an :class:`~landau.errors.InputError`
that names the alternative (eliminate the algebraic state), never handed to another integrator.

References
----------
Hairer, E., Wanner, G. (1996). Solving Ordinary Differential Equations II, 2nd ed., Springer,
Sec. IV.8 (Radau IIA).
"""

from __future__ import annotations

import math
import weakref
from dataclasses import dataclass
from typing import Any, Callable, Mapping, Sequence

import numba as nb
import numpy as np
import sympy as sp

from landau.codegen.kernels import compile_source, kernel_source
from landau.errors import InputError, IntegratorError
from landau.support.lambdify import lambdify_positional
from landau.verify.hybrid.callbacks import call_pointer, make_pointers
from landau.verify.hybrid.log import EventLog
from landau.verify.hybrid.radau import SIG, SIG_JAC, STATUS, radau_core
from landau.verify.hybrid.result import Simulation, Status, status_from_text

__all__ = ["CompiledSystem", "FlowSolution", "compile_system", "shooting_flow", "simulate_system"]

#: step attempts per compiled call (each call records its accepted steps; the run continues from the
#: previous call's state and step size)
CHUNK_STEPS = 100_000
#: the largest condition number of E accepted (above it E⁻¹·f loses every digit)
MASS_CONDITION = 1e14


@dataclass(frozen=True, eq=False)
class CompiledSystem:
    """A :class:`~landau.systems.system.DynamicalSystem` compiled for the Radau IIA: ẏ = W·f(y; p), W = E⁻¹.

    Attributes
    ----------
    system : DynamicalSystem
        The system.
    arguments : tuple of sympy.Symbol
        The order of the parameter vector: the Hopf parameter, the other parameters, then the entries
        of W (the inverse mass; its diagonal when E is diagonal, only where E_ii is not 1).
    fun, jac : FunctionPointer
        ``fun(t, y, p, out)`` (out = W·f) and ``jac(t, y, p, out)`` (out = W·∂f/∂y), compiled.
    source : str
        The generated source of both.
    """

    system: Any
    arguments: tuple
    fun: Any
    jac: Any
    source: str
    _weights: tuple                     # (i, j) of each entry of W in the parameter vector
    _mass: Callable                     # E(p, params…) as nested lists (numpy)

    @property
    def n(self) -> int:
        """The number of states."""
        return len(self.system.states)

    def resolve(self, params: Mapping[str, float] | None) -> dict[str, float]:
        """The system's defaults with ``params`` applied, checked: every value a finite number, every
        name a parameter of the system, the Hopf parameter given.

        Raises
        ------
        InputError
            Naming the unknown, missing or non-finite parameter.
        """
        from landau.systems.system import finite_parameter

        s = self.system
        if params is not None and not isinstance(params, Mapping):
            raise InputError(f"{s.name}: params must map parameter names to numbers, got {type(params).__name__}")
        known = {a.name for a in s.parameters} | {s.parameter.name}
        values = dict(s.defaults)
        for key, val in (params or {}).items():
            if key not in known:
                raise InputError(f"{s.name}: unknown parameter {key!r} (parameters: {', '.join(sorted(known))})")
            values[key] = finite_parameter(key, val)
        if s.parameter.name not in values:
            raise InputError(f"{s.name}: give the Hopf parameter {s.parameter.name!r} a value (a simulation runs "
                             "at one value of it)")
        missing = [a.name for a in s.parameters if a.name not in values]
        if missing:
            raise InputError(f"{s.name}: no value for parameter(s) {', '.join(missing)}")
        return {k: finite_parameter(k, v) for k, v in values.items() if k in known}

    def vector(self, params: Mapping[str, float] | None) -> np.ndarray:
        """The parameter vector of :attr:`fun` and :attr:`jac` at ``params`` (mapping of names, with the
        Hopf parameter), the inverse mass included.

        Raises
        ------
        InputError
            A bad parameter (:meth:`resolve`), or a mass matrix that is not finite or not invertible at
            these values (a zero entry: an algebraic row, which the Radau IIA cannot integrate).
        """
        s = self.system
        values = self.resolve(params)
        base = [values[a.name] for a in self.arguments[:1 + len(s.parameters)]]
        with np.errstate(all="ignore"):
            E = np.asarray(self._mass(*base), dtype=float).reshape(self.n, self.n)
        if not np.all(np.isfinite(E)):
            raise InputError(f"{s.name}: the mass matrix E is not finite at these parameters")
        if s.mass_is_diagonal:
            zero = [st.name for st, e in zip(s.states, np.diag(E), strict=True) if e == 0.0]
            if zero:
                raise InputError(_dae_message(s, zero))
            W = np.diag(1.0 / np.diag(E))
        else:
            if np.linalg.cond(E) > MASS_CONDITION:
                raise InputError(f"{s.name}: the mass matrix E is singular at these parameters (condition "
                                 f"number {np.linalg.cond(E):.3g}); {_DAE_ADVICE}")
            # E·ẏ = f  ⇒  ẏ = E⁻¹·f: W = E⁻¹ by LU with partial pivoting (n is small; E is well
            # conditioned, checked above)
            W = np.linalg.inv(E)
        return np.ascontiguousarray(base + [float(W[i, j]) for i, j in self._weights], dtype=float)

    def field(self, y, pvec: np.ndarray) -> np.ndarray:
        """ẏ = W·f(y) at one state, by the compiled code the integrator runs."""
        out = np.empty(self.n)
        call_pointer(self.fun, 0.0, np.ascontiguousarray(y, dtype=float), pvec, out)
        return out

    def jacobian(self, y, pvec: np.ndarray) -> np.ndarray:
        """∂ẏ/∂y = W·∂f/∂y at one state, by the compiled code the integrator runs."""
        out = np.empty((self.n, self.n))
        call_pointer(self.jac, 0.0, np.ascontiguousarray(y, dtype=float), pvec, out)
        return out


_DAE_ADVICE = ("the compiled Radau IIA integrates E·ẏ = f with an invertible E only; eliminate the algebraic "
               "state(s) (solve their equation f_i = 0 for them and substitute it into the other rows) and "
               "simulate the reduced ODE — the Hopf analysis (landau.hopf_normal_form) takes the "
               "differential-algebraic system as it is")


def _dae_message(system, zero: Sequence[str]) -> str:
    rows = ", ".join(repr(z) for z in zero)
    which = f"state {rows} has" if len(zero) == 1 else f"states {rows} have"
    return f"{system.name}: {which} mass E_ii = 0 (an algebraic row: a differential-algebraic system); " + _DAE_ADVICE


_COMPILED: "weakref.WeakKeyDictionary[Any, CompiledSystem]" = weakref.WeakKeyDictionary()


def compile_system(system) -> CompiledSystem:
    """The system's field and Jacobian, generated and compiled once (per process; across processes the
    source and the machine code come from the verified caches of :mod:`landau.verify.jitcache`).

    Parameters
    ----------
    system : DynamicalSystem
        Any smooth system E·ẏ = f(y; p) with E invertible.

    Returns
    -------
    CompiledSystem

    Raises
    ------
    InputError
        Not a DynamicalSystem, a diagonal entry of E that is identically 0 (an algebraic row), or a
        field that uses a symbol that is neither a state nor a parameter.
    """
    from landau.systems.system import DynamicalSystem

    if not isinstance(system, DynamicalSystem):
        raise InputError(f"simulate_system takes a DynamicalSystem, got {type(system).__name__}")
    hit = _COMPILED.get(system)
    if hit is not None:
        return hit
    n = len(system.states)
    zero = [st.name for st, e in zip(system.states, system.mass, strict=True) if e == 0] \
        if system.mass_is_diagonal else []
    if zero:
        raise InputError(_dae_message(system, zero))
    unknown = sorted(u.name for u in system.unknowns if any(u in f.free_symbols for f in system.rhs))
    if unknown:
        raise InputError(f"{system.name}: the field uses the equilibrium unknown(s) {', '.join(unknown)}, "
                         "which have no value in a simulation; write the field without them")
    base = (system.parameter, *system.parameters)
    # W = E⁻¹ enters as parameters: w_ij symbols named so that no user symbol can take them
    weights: list[tuple[int, int]] = []
    if system.mass_is_diagonal:
        weights = [(i, i) for i in range(n) if system.mass[i] != 1]
    else:
        weights = [(i, j) for i in range(n) for j in range(n)]
    wsym = {ij: sp.Symbol(f"_w{ij[0]}_{ij[1]}", real=True) for ij in weights}
    f = sp.Matrix(system.rhs)
    if system.mass_is_diagonal:
        g = [wsym[(i, i)] * f[i] if (i, i) in wsym else f[i] for i in range(n)]
    else:
        g = [sum((wsym[(i, j)] * f[j] for j in range(n)), sp.Integer(0)) for i in range(n)]
    args = (*base, *(wsym[ij] for ij in weights))
    src = kernel_source(list(system.states), g, list(args))
    compiled = compile_source(src, f"system {system.name}")
    fun, jac = make_pointers(compiled.fun, compiled.jac, SIG, SIG_JAC)
    mass = lambdify_positional(list(base), system.mass_matrix.tolist(), "numpy")
    out = CompiledSystem(system, args, fun, jac, src, tuple(weights), mass)
    _COMPILED[system] = out
    return out


@nb.njit(cache=True)
def _field_along(fun, ts, Y, p, F):
    """F[k] = fun(ts[k], Y[k]) for every recorded point (the slopes of the Hermite interpolant)."""
    for k in range(ts.shape[0]):
        fun(ts[k], Y[k], p, F[k])


def _initial_step(y0: np.ndarray, f0: np.ndarray, span: float, rtol: float, atol: np.ndarray) -> float:
    """The first step of Hairer, Nørsett & Wanner (1993), Sec. II.4 (the low-cost form): 1 % of
    ‖y₀‖/‖f₀‖ in the tolerance's norm, 1e-6 when either is negligible, at most the span."""
    sc = atol + np.abs(y0) * rtol
    d0 = float(np.sqrt(np.mean((y0 / sc) ** 2)))
    d1 = float(np.sqrt(np.mean((f0 / sc) ** 2)))
    h = 1e-6 if d0 < 1e-5 or d1 < 1e-5 else 0.01 * d0 / d1
    return float(min(h, span))


def _integrate(cs: CompiledSystem, pvec: np.ndarray, t0: float, y0: np.ndarray, t_end: float, rtol: float,
               atol: np.ndarray, max_steps: int, first_step: float | None, max_step: float):
    """The compiled loop in calls of at most :data:`CHUNK_STEPS` attempts, recording every accepted step.

    Returns (status code, t, y, counters[:5] summed, recorded times, recorded states (m, n))."""
    f0 = cs.field(y0, pvec)
    if not np.all(np.isfinite(f0)):
        return -3, t0, y0, np.zeros(5, dtype=np.int64), np.array([t0]), y0[None, :].copy()
    h = float(first_step) if first_step else _initial_step(y0, f0, t_end - t0, rtol, atol)
    t, y = t0, y0
    rec_t, rec_y = [np.array([t0])], [y0[None, :].copy()]
    counts = np.zeros(5, dtype=np.int64)
    used, st = 0, 0
    while True:
        budget = min(CHUNK_STEPS, max_steps - used)
        st, tn, yn, cnt, _, _, rt, ry, hn, _ = radau_core(cs.fun, cs.jac, t, y, t_end, pvec, rtol, atol, h,
                                                           max_step, budget, -1, 0.0, 0, 0, budget + 1)
        used += int(cnt[0]) + int(cnt[1])
        counts += cnt[:5]
        rec_t.append(rt[1:])     # a call records its start: the previous call's end (or t0)
        rec_y.append(ry[1:])
        t, y, h = float(tn), yn.copy(), float(hn)
        if st != -2 or used >= max_steps:
            break
    return int(st), t, y, counts, np.concatenate(rec_t), np.concatenate(rec_y)


def _tolerances(rtol, atol, y0: np.ndarray) -> tuple[float, np.ndarray]:
    try:
        rtol = float(rtol)
    except (TypeError, ValueError):
        raise InputError(f"rtol must be a number, got {rtol!r}") from None
    if not (1e-14 <= rtol < 1):
        raise InputError(f"rtol must be in [1e-14, 1), got {rtol!r}")
    if atol is None:
        at = np.full(y0.size, rtol * max(float(np.max(np.abs(y0))), 1e-12))
    else:
        try:
            at = np.array(np.broadcast_to(np.asarray(atol, dtype=float), y0.shape), dtype=float)
        except (TypeError, ValueError):
            raise InputError(f"atol must be a number or one number per state ({y0.size}), got {atol!r}") from None
        if not np.all(np.isfinite(at)) or np.any(at <= 0):
            raise InputError(f"atol must be positive and finite, got {atol!r}")
    return rtol, np.ascontiguousarray(at)


def _start(cs: CompiledSystem, values: Mapping[str, float], pvec: np.ndarray, y0) -> np.ndarray:
    """The initial state: ``y0`` checked, or the equilibrium (Newton's method on the compiled field from
    the declared equilibrium or guess) displaced by 1e-3·max(1, |y₀|) in the normalised state."""
    s = cs.system
    n = cs.n
    if y0 is not None:
        if isinstance(y0, Mapping):
            extra = sorted(set(y0) - {st.name for st in s.states})
            if extra:
                raise InputError(f"y0: {extra[0]!r} is not a state (states: {', '.join(st.name for st in s.states)})")
            missing = [st.name for st in s.states if st.name not in y0]
            if missing:
                raise InputError(f"y0: no value for state {missing[0]!r}")
            y0 = [y0[st.name] for st in s.states]
        try:
            y = np.array(y0, dtype=float).reshape(-1)
        except (TypeError, ValueError):
            raise InputError(f"y0 must be {n} numbers (one per state), got {y0!r}") from None
        if y.size != n:
            raise InputError(f"y0 must have {n} values (states {', '.join(st.name for st in s.states)}), "
                             f"got {y.size}")
        if not np.all(np.isfinite(y)):
            raise InputError(f"y0 must be finite, got {y0!r}")
        return np.ascontiguousarray(y)
    sub = {a: sp.Float(values[a.name]) for a in (s.parameter, *s.parameters)}
    guess = dict(zip(s.unknowns, s.unknown_guess, strict=False))
    try:
        y = np.array([float(e.xreplace(guess).xreplace(sub)) for e in s.equilibrium], dtype=float)
    except (TypeError, ValueError):
        raise InputError(f"{s.name}: the equilibrium cannot be evaluated at these parameters; give y0") from None
    for _ in range(50):          # Newton's method on W·f(y) = 0 (the same zeros as f)
        F = cs.field(y, pvec)
        if not np.all(np.isfinite(F)):
            break
        # J·Δy = −F: the Newton step (n small; a singular J is a degenerate equilibrium)
        try:
            dy = np.linalg.solve(cs.jacobian(y, pvec), -F)
        except np.linalg.LinAlgError:
            break
        y = y + dy
        if np.max(np.abs(dy)) <= 1e-13 * (1 + np.max(np.abs(y))):
            break
    if not np.all(np.isfinite(y)):
        raise InputError(f"{s.name}: no equilibrium found at these parameters; give y0")
    k = s.normalise
    y[k] += 1e-3 * max(1.0, abs(y[k]))
    return np.ascontiguousarray(y)


def simulate_system(system, params: Mapping[str, float] | None, t_end: float, y0=None, *, rtol: float = 1e-8,
                    atol: float | Sequence[float] | None = None, t_eval: Sequence[float] | None = None,
                    max_steps: int = 1_000_000, t0: float = 0.0, first_step: float | None = None,
                    max_step: float = math.inf) -> Simulation:
    """Simulate E·ẏ = f(y; p) with the compiled Radau IIA (order 5, stiff; module docstring).

    Parameters
    ----------
    system : DynamicalSystem
        The system (E invertible; a zero mass entry is refused).
    params : mapping of str to float
        Parameter values by name, the Hopf parameter included (the others default to
        ``system.defaults``).
    t_end : float
        The final time (> ``t0``).
    y0 : sequence of float or mapping of state name to float, optional
        The initial state; default the equilibrium at ``params`` (Newton's method from the declared
        equilibrium or guess) displaced by 1e-3·max(1, |y₀|) in the normalised state
        (``system.normalise``).
    rtol : float
        Relative tolerance of the step-size control (1e-14 to 1).
    atol : float or sequence of float, optional
        Absolute tolerance (one per state or one for all); default rtol·max|y0| (at least rtol·1e-12),
        the rule of the check's shooting.
    t_eval : sequence of float, optional
        Times at which to report the state (inside [t0, t_end]); default every accepted step.  Values
        between steps are the cubic Hermite interpolant of the step ends (state and field at both ends).
    max_steps : int
        Budget of step attempts (accepted and rejected).
    t0 : float
        The initial time.
    first_step, max_step : float, optional
        The first step (default: Hairer–Nørsett–Wanner's estimate) and the largest step.

    Returns
    -------
    Simulation
        ``t``, ``y`` (shape (n, m)), the field ``f`` at those points (so ``at`` interpolates with cubic
        Hermite), the state names, ``nsteps``, ``nfev`` and the status: ``FINISHED``, or
        ``MAX_STEPS``, ``STEP_SIZE_UNDERFLOW``, ``NON_FINITE`` with the time reached and the advice.

    Raises
    ------
    InputError
        Not a DynamicalSystem, an algebraic row (E_ii = 0), an unknown, missing or non-finite parameter, a
        bad ``y0``, tolerance, ``t_end`` or ``t_eval``.

    Examples
    --------
    >>> from landau import DynamicalSystem
    >>> s = DynamicalSystem.from_strings({"x": "a - (b + 1)*x + x^2*y", "y": "b*x - x^2*y"}, "b",
    ...                                  {"a": 1.5}, equilibrium={"x": "a", "y": "b/a"})
    >>> run = simulate_system(s, {"b": 3.3}, 50.0)
    >>> run.status.value
    'finished'
    """
    cs = compile_system(system)
    values = cs.resolve(params)
    pvec = cs.vector(values)
    for name, v in (("t0", t0), ("t_end", t_end)):
        if isinstance(v, bool) or not isinstance(v, (int, float, np.integer, np.floating)) or not math.isfinite(v):
            raise InputError(f"{name} must be a finite number, got {v!r}")
    t0, t_end = float(t0), float(t_end)
    if not t_end > t0:
        raise InputError(f"t_end must be after t0 = {t0:g}, got {t_end!r}")
    if isinstance(max_steps, bool) or not isinstance(max_steps, (int, np.integer)) or max_steps < 1:
        raise InputError(f"max_steps must be a positive integer, got {max_steps!r}")
    if not (max_step > 0) or (first_step is not None and not (0 < first_step <= t_end - t0)):
        raise InputError("max_step must be > 0 and first_step in (0, t_end - t0]")
    y = _start(cs, values, pvec, y0)
    rtol, at = _tolerances(rtol, atol, y)
    te = None
    if t_eval is not None:
        te = np.asarray(t_eval, dtype=float).reshape(-1)
        if te.size == 0 or not np.all(np.isfinite(te)) or np.any(np.diff(te) < 0) or te[0] < t0 or te[-1] > t_end:
            raise InputError(f"t_eval must be increasing finite times inside [{t0:g}, {t_end:g}]")
    st, t, yf, counts, rt, ry = _integrate(cs, pvec, t0, y, t_end, rtol, at, int(max_steps), first_step,
                                           float(max_step))
    return _simulation(cs, pvec, st, t, yf, counts, rt, ry, te, t_end)


def _simulation(cs: CompiledSystem, pvec, st: int, t: float, yf, counts, rt, ry, te, t_end: float) -> Simulation:
    """The run as a :class:`Simulation` (recorded steps with their slopes, or the samples ``te``)."""
    F = np.empty_like(ry)
    _field_along(cs.fun, np.ascontiguousarray(rt), np.ascontiguousarray(ry), pvec, F)
    status = Status.FINISHED if st in (0, 1) else status_from_text(STATUS[st])
    msg = status.advice if status.success else (f"stopped at t = {t:.6g} before t_end = {t_end:.6g} "
                                                f"({STATUS[st]}): {status.advice}")
    names = tuple(s.name for s in cs.system.states)
    run = Simulation(model=cs.system.name, t=rt, y=ry.T.copy(), events=EventLog(), status=status, message=msg,
                     t_final=float(t), y_final=np.asarray(yf, dtype=float).copy(), nsteps=int(counts[0]),
                     nfev=int(counts[2]), f=F.T.copy(), state_names=names)
    if te is None:
        return run
    inside = te[te <= rt[-1]]
    ys = run.at(inside) if len(rt) > 1 else np.repeat(ry.T, len(inside), axis=1)
    Fs = np.empty((len(inside), cs.n))
    _field_along(cs.fun, np.ascontiguousarray(inside), np.ascontiguousarray(ys.T), pvec, Fs)
    from dataclasses import replace

    return replace(run, t=inside, y=ys, f=Fs.T.copy())


# ---------------------------------------------------------------------------------------------
# the check's shooting
@dataclass(frozen=True)
class FlowSolution:
    """One integration over [0, T] as the check's shooting reads it: ``y`` (n, m), last column the
    state at T, and ``sol(times)`` the interpolated state (the part of scipy's ``solve_ivp`` result
    :func:`landau.analyses.checking._shoot` uses)."""

    simulation: Simulation

    @property
    def y(self) -> np.ndarray:
        return self.simulation.y

    def sol(self, times) -> np.ndarray:
        return self.simulation.at(times)


def shooting_flow(system, params: Mapping[str, float], rtol: float) -> Callable[[np.ndarray, float], FlowSolution]:
    """The check's flow: the compiled integration from z over [0, T] at fixed parameters.

    Parameters
    ----------
    system : DynamicalSystem
        The system (E invertible).
    params : mapping of str to float
        Every parameter value, the Hopf parameter included (names that are not parameters of the
        system are ignored: the check passes every default).
    rtol : float
        The shooting's tolerance; atol = rtol·max(1e-12, max|z|) at each start z (scipy's former rule).

    Returns
    -------
    callable
        ``flow(z, T) -> FlowSolution``; an integration that does not reach T raises
        :class:`~landau.errors.IntegratorError`.
    """
    cs = compile_system(system)
    known = {a.name for a in (system.parameter, *system.parameters)}
    pvec = cs.vector({k: v for k, v in params.items() if k in known})   # (the check passes every default)
    rtol = float(rtol)

    def flow(z, T) -> FlowSolution:
        z = np.ascontiguousarray(z, dtype=float)
        T = float(T)
        if not (math.isfinite(T) and T > 0) or not np.all(np.isfinite(z)):
            raise IntegratorError(f"integration failed while shooting: period {T!r} or state not finite")
        at = np.full(cs.n, rtol * max(1e-12, float(np.max(np.abs(z)))))
        st, t, yf, counts, rt, ry = _integrate(cs, pvec, 0.0, z, T, rtol, at, 1_000_000, None, math.inf)
        if st < 0:
            raise IntegratorError(f"integration failed while shooting: {STATUS[st]} at t = {t:.6g} of {T:.6g}")
        return FlowSolution(_simulation(cs, pvec, st, t, yf, counts, rt, ry, None, T))

    return flow
