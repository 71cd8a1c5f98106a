"""Slip cycles, lift-off, stick onset and the simulation check of the Hopf point.

* :func:`slip_cycle` — the periodic orbit of the smooth slip ODE (:mod:`landau.verify.lancioni.slip`)
  by shooting on its return map to φ-maxima (ω = 0, ω decreasing), started from the
  normal-form amplitude; returns the extrema of λ_N and g_T along it;
* :func:`lift_off_mu` — μ where the slip cycle's minimum normal force reaches 0 (the paper's
  end of the slip periodic branch, μ = 0.40983 for set 1);
* :func:`stick_onset_mu` — μ where the slip cycle first touches g_T = 0 (set 2: ≈ 0.360);
* :func:`flight_onset_mu` — μ where the stick–slip attractor of set 2 first lifts off.  We
  get 0.44986 (bracket 1e-5; min λ_N on the attractor falls linearly to 0 there: 0.333 at
  0.44, 0.068 at 0.448, 0.0052 at 0.4498); the paper prints ≈ 0.453.  Not g (9.81 gives
  0.4418), not hysteresis; the gap is the unprinted belt speed |v| (see the function and
  :mod:`landau.verify.lancioni.flight_onset`) — we report it and do not tune;
* :func:`growth_rate` / :func:`hopf_by_simulation` — the growth rate of a small slip
  oscillation measured by the *hybrid* simulation (all modes armed) on both sides of the
  Hopf point; its zero (linear interpolation) is the simulated Hopf point.

Each takes an optional ``friction`` law (:class:`~landau.laws.velocity.VelocityFriction`,
default the paper's Coulomb μ) and ``parameter`` (the bifurcation parameter, see
:func:`landau.verify.lancioni.slip.hopf_parameter`); ``mu`` is then that parameter's value.
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import lru_cache
from typing import Mapping

import numpy as np
from scipy.integrate import solve_ivp
from scipy.optimize import brentq

from landau.errors import IntegratorError, NoHopfError
from landau.verify.hybrid import simulate
from landau.verify.hybrid.dop853 import CompiledDOP853
from landau.verify.lancioni import slip as S
from landau.verify.lancioni.contact import default_options
from landau.verify.lancioni.model import ConstantBelt, build, build_at, slip_state


@dataclass(frozen=True)
class SlipCycle:
    """A periodic orbit of the slip ODE at μ: amplitude, period, extrema along it."""

    mu: float
    phi_e: float
    phi_max: float
    period: float
    phidot_max: float
    lamN_min: float
    gT_min: float
    gT_max: float

    @property
    def amplitude(self) -> float:
        return self.phi_max - self.phi_e

    def __repr__(self) -> str:
        return (f"SlipCycle(mu={self.mu:.8g}, amplitude={self.amplitude:.4g}, T={self.period:.5g}, "
                f"phidot_max={self.phidot_max:.5g}, min λ_N={self.lamN_min:.4g}, g_T in "
                f"[{self.gT_min:.4g}, {self.gT_max:.4g}])")


def _slip_args(p, mu, s, friction=None, parameter=None, v=None):
    """(the slip mode's numeric functions, their parameter values) at bifurcation-parameter value ``mu``."""
    fns = S.slip_functions(s, friction)
    over = {} if mu is None else {S.hopf_parameter(friction, parameter): mu}
    vals = S.slip_values(p, s, friction, v if friction is not None else None, **over)
    return fns, tuple(vals[n] for n in fns.names)


def _flow(p, mu, s, friction=None, parameter=None, v=None):
    """(rhs(t, (φ, ω)), λ_N(φ, ω)) of the slip mode at bifurcation-parameter value ``mu``."""
    fns, args = _slip_args(p, mu, s, friction, parameter, v)
    F, L = fns.F, fns.L

    def rhs(t, y):
        return [y[1], F(y[0], y[1], *args)]
    return rhs, lambda ph, w: L(ph, w, *args)


def _one_turn(p, mu, s, w0, phi_e, T_guess, rtol=1e-12, dense=False, law=()):
    """From (φ_e, w0), w0 > 0, to the next upward crossing of φ = φ_e."""
    rhs, _ = _flow(p, mu, s, *law)

    def back(t, y):  # masked (negative) for the first 3/4 of a period, where φ − φ_e ≤ 0 near its end
        return y[0] - phi_e if t > 0.75 * T_guess else -1.0
    back.direction, back.terminal = 1, True
    sol = solve_ivp(rhs, (0, 20 * T_guess), [phi_e, w0], method="DOP853", rtol=rtol, atol=1e-15,
                    events=back, dense_output=dense)
    if not sol.t_events[0].size:
        raise IntegratorError(f"slip ODE: no return to the section φ = φ_e at μ={mu}")
    return sol


def _return_point(p, mu, s, w0, phi_e, T_guess, rtol=1e-12, law=()):
    """(t, (φ, ω)) at the event of :func:`_one_turn` (the first upward crossing of φ = φ_e after
    3/4 of ``T_guess``), integrated by the compiled DOP853 over the slip mode's kernel
    (:func:`landau.verify.lancioni.kernels.slip_kernel`) with ``solve_ivp``'s event rule: a
    sign change g ≤ 0 ≤ g_new at the step ends, the root by Brent's method on the step's dense
    output to 4 ulp — the steps of scipy's DOP853, to rounding.  The steps up to the crossing run
    in one compiled call (:func:`landau.verify.hybrid.guarded.upcrossing_step`)."""
    from landau.verify.hybrid.guarded import upcrossing_step
    from landau.verify.lancioni.kernels import slip_kernel

    _, args = _slip_args(p, mu, s, *law)
    kern = slip_kernel(s, law[0] if law else None, args)
    solver = CompiledDOP853(rtol, 1e-15)(kern, 0.0, np.array([phi_e, w0]), 20 * T_guess)
    t_mask, eps4 = 0.75 * T_guess, 4 * np.finfo(float).eps

    def back(t, y):
        return y[0] - phi_e if t > t_mask else -1.0
    if solver.status == "running" and upcrossing_step(solver, 0, phi_e, t_mask):
        dense = solver.dense_output()
        te = brentq(lambda t, d=dense: back(t, d(t)), solver.t_old, solver.t, xtol=eps4, rtol=eps4)
        return te, dense(te)
    if solver.status == "failed":
        raise IntegratorError(f"slip ODE at μ={mu}: compiled DOP853: step size too small", t=solver.t,
                              state=solver.y)
    raise IntegratorError(f"slip ODE: no return to the section φ = φ_e at μ={mu}")


def slip_cycle(mu: float, params: Mapping[str, float] | None = None, s: int = 1, v: float = -1.0,
               hopf=None, friction=None, parameter: str | None = None) -> SlipCycle:
    """Periodic orbit of the slip ODE (smooth continuation, admissible or not) on the side of the
    Hopf point where it exists (μ > μ_c for a supercritical point).

    Shooting on the return map of the section φ = φ_e, φ̇ > 0 (unknown: φ̇ there), started
    from the normal-form amplitude ω_c·C·sqrt|μ − μ_c|.  With a ``friction`` law, ``mu`` is the
    value of its bifurcation parameter ``parameter`` and ``v`` the belt velocity.
    """
    p = S.resolve(params)
    law = (friction, parameter, v)
    vv = v if friction is not None else None
    h = hopf or S.slip_hopf(p, s=s, friction=friction, parameter=parameter, v=vv)
    if h.cycle_side == 0 or (mu - h.p_c) * h.cycle_side <= 0:
        raise NoHopfError(f"no slip cycle at {h.parameter}={mu}: the cycle of the Hopf point "
                          f"{h.parameter}_c={h.p_c:.8g} ({h.criticality}) is on the other side")
    phi_e = S.equilibrium_phi(p, mu, s, friction, parameter, vv)
    T_guess = 2 * np.pi / h.omega_c
    w_nf = h.amplitude(mu) * h.omega_c

    def defect(w0):
        return _return_point(p, mu, s, w0, phi_e, T_guess, law=law)[1][1] - w0
    lo, hi = 0.3 * w_nf, 2.5 * w_nf
    e = 1.0 if h.Lambda < 0 else -1.0  # inside a stable cycle small oscillations grow, inside an unstable one decay
    while e * defect(lo) < 0 and lo > 1e-9:
        lo *= 0.5
    while e * defect(hi) > 0 and hi < 50.0:
        hi *= 1.5
    w0 = brentq(defect, lo, hi, xtol=1e-14, rtol=1e-13)
    sol = _one_turn(p, mu, s, w0, phi_e, T_guess, dense=True, law=law)
    T = float(sol.t_events[0][0])
    tt = np.linspace(0, T, 4001)
    ph, w = sol.sol(tt)
    _, L = _flow(p, mu, s, *law)
    _, args = _slip_args(p, mu, s, *law)
    lam = np.broadcast_to(np.asarray(_lam_n_array(s, friction)(ph, w, *args), dtype=float), ph.shape)
    gT = p["l"] * np.cos(ph) * w - v
    i = int(np.argmin(lam))
    lam_min = _parabola_min(lambda t: L(*sol.sol(t)), tt, i)
    return SlipCycle(mu, phi_e, float(np.max(ph)), T, float(np.max(w)), lam_min, float(np.min(gT)),
                     float(np.max(gT)))


def _lam_n_array(s: int, friction):
    """λ_N(φ, ω, *slip parameters) of the slip mode evaluated on arrays (numpy), for the samples
    along a slip cycle (the scalar function of :func:`landau.verify.lancioni.slip.slip_functions`
    refines the minimum)."""
    law = S._law(friction)
    return _lam_n_numpy(int(s), S.friction_branch(s, friction), tuple(q.name for q in law.parameters))


@lru_cache(maxsize=16)
def _lam_n_numpy(s: int, Fs, law_names: tuple):
    from landau.support.lambdify import lambdify_positional

    _, L = S._accelerations(s, Fs)
    args = [S.phi, S.omega, *S.MECHANICAL.values(), S.v_belt, *map(S._law_symbol, law_names)]
    return lambdify_positional(args, L, "numpy")


def _parabola_min(f, tt, i):
    from scipy.optimize import minimize_scalar
    lo, hi = tt[max(i - 1, 0)], tt[min(i + 1, len(tt) - 1)]
    r = minimize_scalar(f, bounds=(lo, hi), method="bounded", options={"xatol": 1e-12})
    return float(min(r.fun, f(tt[i])))


def lift_off_mu(params: Mapping[str, float] | None = None, s: int = 1, span: float = 5e-4, *, friction=None,
                parameter: str | None = None, v: float = -1.0) -> tuple[float, SlipCycle]:
    """μ (or the law's bifurcation parameter) where min λ_N on the slip cycle reaches 0 (end of the
    slip periodic branch), on the side of the Hopf point where the cycle exists.

    Parameters
    ----------
    params : mapping, optional
        Mechanical parameters (default: set 1).
    s : {+1, -1}
        Slip sign.
    span : float
        First distance from the Hopf point tried (doubled until min λ_N < 0).
    friction : VelocityFriction, optional
        Friction-coefficient law (default: Coulomb μ).
    parameter : str, optional
        Its bifurcation parameter (default the first).
    v : float
        Belt velocity (m/s; matters for a velocity-dependent law).

    Returns
    -------
    tuple
        (parameter value, the :class:`SlipCycle` there).
    """
    p = S.resolve(params)
    vv = v if friction is not None else None
    h = S.slip_hopf(p, s=s, friction=friction, parameter=parameter, v=vv)
    side = h.cycle_side
    if side == 0:
        raise NoHopfError(f"degenerate Hopf point at {h.parameter}_c={h.p_c:.8g}: no slip cycle branch")
    f = lambda m: slip_cycle(m, p, s, v, hopf=h, friction=friction, parameter=parameter).lamN_min  # noqa: E731
    m = _root_beyond_hopf(f, h, side, span, 40, "min λ_N on the slip cycle stays positive")
    return m, slip_cycle(m, p, s, v, hopf=h, friction=friction, parameter=parameter)


def _root_beyond_hopf(f, h, side: int, span: float, doublings: int, failure: str) -> float:
    """Root of ``f`` (positive next to the Hopf point ``h``) on the cycle's ``side`` of it: the window
    starts at distance ``span``·max(1, |p_c|) and doubles until f ≤ 0 at its far end (at most
    ``doublings`` times, else NoHopfError with ``failure``); then brentq to 1e-10."""
    scale = max(1.0, abs(h.p_c))
    lo, hi = h.p_c + side * 1e-7 * scale, h.p_c + side * span * scale
    for _ in range(doublings):
        if f(hi) <= 0:
            break
        hi = h.p_c + 2 * (hi - h.p_c)
    else:
        raise NoHopfError(f"{failure} up to {h.parameter}={hi:.6g}")
    return brentq(f, *sorted((lo, hi)), xtol=1e-10)


def stick_onset_mu(params: Mapping[str, float] | None = None, s: int = 1, v: float = -1.0,
                   span: float = 0.05, *, friction=None, parameter: str | None = None) -> tuple[float, SlipCycle]:
    """μ (or the law's bifurcation parameter) where the slip cycle first reaches g_T = 0 (stick
    appears), belt speed v.

    Parameters
    ----------
    params : mapping, optional
        Mechanical parameters (default: set 1).
    s : {+1, -1}
        Slip sign.
    v : float
        Belt velocity (m/s).
    span : float
        First distance from the Hopf point tried (relative to max(1, |p_c|); doubled until the
        cycle reaches g_T = 0), on the cycle's side.
    friction : VelocityFriction, optional
        Friction-coefficient law (default: Coulomb μ).
    parameter : str, optional
        Its bifurcation parameter (default the first).

    Returns
    -------
    tuple
        (parameter value, the :class:`SlipCycle` there).
    """
    p = S.resolve(params)
    h = S.slip_hopf(p, s=s, friction=friction, parameter=parameter, v=v if friction is not None else None)
    side = h.cycle_side or 1

    def f(m):
        c = slip_cycle(m, p, s, v, hopf=h, friction=friction, parameter=parameter)
        return c.gT_min if s > 0 else -c.gT_max
    # the window starts at the Hopf point (model) and is doubled until the cycle reaches g_T = 0
    m = _root_beyond_hopf(f, h, side, span, 8, "the slip cycle does not reach g_T = 0")
    return m, slip_cycle(m, p, s, v, hopf=h, friction=friction, parameter=parameter)


# --------------------------------------------------------------------------- simulation check
@dataclass(frozen=True)
class GrowthRate:
    mu: float
    sigma: float          # 1/s, from the φ̇-maxima envelope
    n_maxima: int
    modes: tuple[str, ...]

    def __repr__(self) -> str:
        return f"GrowthRate(mu={self.mu:.6g}, sigma={self.sigma:.5g}/s, {self.n_maxima} maxima, modes={self.modes})"


def growth_rate(mu: float, params: Mapping[str, float] | None = None, t_end: float = 20.0,
                kick: float = 1e-5, stepper=CompiledDOP853(1e-11, 1e-13), *, friction=None,
                parameter: str | None = None) -> GrowthRate:
    """Exponential growth rate of a small slip oscillation, measured by the hybrid engine.

    The run starts on the surface at φ_e + kick with every mode, guard and the impact law
    armed; the rate is the least-squares slope of log(φ̇-max) after the first 2 s.  With a
    ``friction`` law, ``mu`` is the value of its bifurcation parameter ``parameter``.
    """
    p = S.resolve(params)
    cm = build_at(mu, 0.0, p, ConstantBelt(-1.0), friction=friction, parameter=parameter)
    vv = -1.0 if friction is not None else None
    y0 = slip_state(cm.mech, S.equilibrium_phi(cm.mech.params, None, 1, cm.mech.friction, None, vv) + kick)
    sol = simulate(cm.model, cm.initial_mode(0.0, y0), y0, (0.0, t_end), stepper, default_options(record=False))
    ev = [e for e in sol.events.filter(guard="phidot-max") if e.t > 2.0 and e.y[2] > 0]
    modes = tuple(sorted({e.from_mode for e in sol.events} | {sol.final_mode}))
    t = np.array([e.t for e in ev])
    a = np.array([e.y[2] for e in ev])
    sigma = float(np.polyfit(t, np.log(a), 1)[0])
    return GrowthRate(mu, sigma, len(ev), modes)


def hopf_by_simulation(params: Mapping[str, float] | None = None, delta: float = 2e-3,
                       **kw) -> tuple[float, GrowthRate, GrowthRate]:
    """Simulated Hopf point: zero of the measured growth rate between μ_c ∓ delta (engine's μ_c as centre).

    ``friction=``/``parameter=`` (passed on to :func:`growth_rate`) give a law and its bifurcation
    parameter instead of the Coulomb μ.
    """
    p = S.resolve(params)
    mc = S.slip_hopf(p, friction=kw.get("friction"), parameter=kw.get("parameter"),
                     v=-1.0 if kw.get("friction") is not None else None).p_c
    g1, g2 = growth_rate(mc - delta, p, **kw), growth_rate(mc + delta, p, **kw)
    mu0 = g1.mu - g1.sigma * (g2.mu - g1.mu) / (g2.sigma - g1.sigma)
    return float(mu0), g1, g2


@dataclass(frozen=True)
class FlightOnset:
    mu: float                 # bisection midpoint
    bracket: tuple[float, float]
    lamN_min_below: float     # min λ_N on the stick–slip attractor at the final lower bracket end
    evaluations: int

    def __repr__(self) -> str:
        return (f"FlightOnset(mu={self.mu:.6f}, bracket=[{self.bracket[0]:.6f}, {self.bracket[1]:.6f}], "
                f"min λ_N below={self.lamN_min_below:.3g})")


def _attractor(mu, y0, mode, p, t_end, eN=0.0):
    cm = build(mu, eN, p, ConstantBelt(-1.0))
    sol = simulate(cm.model, mode or cm.initial_mode(0.0, y0), y0, (0.0, t_end), CompiledDOP853(1e-10, 1e-12),
                   default_options(record=True))
    return cm, sol


def flight_onset_mu(params: Mapping[str, float] | None = None, bracket: tuple[float, float] | None = None,
                    xtol: float = 1e-5, t_end: float = 16.0, t_keep: float = 4.0) -> FlightOnset:
    """μ where free flight first appears on the stick–slip attractor (set 2: paper ≈ 0.453).

    Bisection on "a lift-off happens in the last ``t_keep`` s", each run started from the
    attractor at the lower end (found from the slip equilibrium + 0.05 rad).  Without a
    ``bracket`` the window comes from the model: it starts at the stick onset
    (:func:`stick_onset_mu`, below which the attractor is the contact slip cycle) and its upper
    end moves up in doubling steps (from 5 % of that μ) until the attractor flies.
    ``lamN_min_below`` is min λ_N on the attractor at the final lower end.  Belt v = −1,
    g = 10: 0.44986.  Why not 0.453 (numbers from :mod:`landau.verify.lancioni.flight_onset`):

    * Not g: g = 9.81 gives 0.4418 (and moves the Hopf point to 0.3541).
    * Not visibility in Fig. 4: the flight starts 14 ms *after* the φ̇ maximum and stick
      resets the state (it always ends at the same point P(μ)), so the section value φ̇_max
      equals the continued contact branch's (reduced slip ODE from P) to < 1e-9 relative for
      e_N = 0 and 0.2 — Fig. 4 shows no trace of the onset (φ̇_max smooth, slope ≈ 4.35).
      The flight is small but not infinitesimal at 0.453: 0.049 s per 0.98 s period, max
      gap 2.0e-5 m, impact speed 3.9e-3 m/s (6e-3 s, 4e-9 m, 8e-6 m/s at 0.4499).  The
      literal section φ = 0 is never crossed (φ ≥ 0.099).
    * Not hysteresis: a down warm-start sweep from 0.456 (e_N = 0, 0.2) stops flying between
      0.4499 and 0.44985, where the upward bisection puts the onset; every orbit with a
      stick phase passes through P(μ), so there is one attractor with stick (stick-free
      coexisting attractors were not searched for).
    * The belt speed: |v| is not printed; the printed stick onset ≈ 0.360 (i.e. in
      [0.3595, 0.3605]) only pins |v| ∈ [0.9542, 1.0156], over which this onset runs from
      0.4663 to 0.4444 (dμ/d|v| ≈ −0.36, twenty times the stick onset's +0.017); the Hopf
      point does not depend on |v|.  |v| = 0.991 gives Hopf 0.3531, stick 0.3601, flight
      0.4530 — all three published values.  So 0.453 is within what the printed data allow;
      we keep |v| = 1 (the amplitude of the Fig. 6 belt) and report the difference.
    """
    p = S.resolve(params)
    derived = bracket is None
    if bracket is None:
        lo, hi = stick_onset_mu(p)[0], 0.0
    else:
        lo, hi = map(float, bracket)
    cm = build(lo, 0.0, p)
    y0 = slip_state(cm.mech, S.equilibrium_phi(p, lo, 1) + 0.05)
    cm, sol = _attractor(lo, y0, None, p, t_end)
    start = (sol.y_final, sol.final_mode)

    def run(m):
        return _attractor(m, start[0], start[1], p, t_end)[1]

    def flies(m):
        return any(e.guard == "lift-off" and e.t > t_end - t_keep for e in run(m).events)
    n = 2
    if derived:
        step = 0.05 * lo
        for _ in range(6):
            hi = lo + step
            if flies(hi):
                break
            lo, step, n = hi, 2 * step, n + 1
        else:
            raise NoHopfError(f"no free flight on the stick-slip attractor up to mu={hi:.6g}")
    elif flies(lo) or not flies(hi):
        raise NoHopfError(f"free-flight onset not bracketed by [{lo}, {hi}]")
    while hi - lo > xtol:
        mid = 0.5 * (lo + hi)
        n += 1
        if flies(mid):
            hi = mid
        else:
            lo = mid
    cm, sol = _attractor(lo, start[0], start[1], p, t_end)
    t, y, modes = sol.trajectory()
    k = (t > t_end - t_keep) & np.array([m in ("stick", "slip+", "slip-") for m in modes])
    lam = min(float(np.min(cm.forces(m, tt, y[:, i])[1]))
              for i, (tt, m) in enumerate(zip(t, modes, strict=True)) if k[i])
    return FlightOnset(0.5 * (lo + hi), (lo, hi), lam, n)


@dataclass(frozen=True)
class PainleveOnset:
    mu: float
    bracket: tuple[float, float]
    message: str

    def __repr__(self) -> str:
        return f"PainleveOnset(mu={self.mu:.6f}, bracket=[{self.bracket[0]:.6f}, {self.bracket[1]:.6f}])"


def painleve_onset_mu(params: Mapping[str, float] | None = None, bracket: tuple[float, float] | None = None,
                      xtol: float = 1e-5, t_end: float = 13.0) -> PainleveOnset:
    """Smallest μ where the detached (flight–slip–stick) attractor of set 1 (e_N = 0) meets a
    Painlevé situation: the slip phase reaches D₊ = G_NN − μG_NT = 0 (the engine raises
    :class:`~verify.lancioni.contact.PainleveError`).  The paper reports a change of motion type at
    μ ≈ 0.6450 (free flight–stick–slip below, free flight–stick above) — where our model stops
    with a Painlevé situation instead of choosing a continuation silently.

    The attractor is reached from the slip equilibrium + 0.05 rad at 1.1 × the lift-off μ
    (:func:`lift_off_mu`: above it the slip cycle is gone and the motion detaches).  Without a
    ``bracket`` the window comes from the model: its lower end starts there and its upper end
    moves up in doubling steps (from 5 % of that μ) until a Painlevé situation is met.
    """
    from landau.verify.lancioni.contact import PainleveError
    p = S.resolve(params)
    mu0 = 1.1 * lift_off_mu(p)[0]
    cm = build(mu0, 0.0, p)
    _, sol = _attractor(mu0, slip_state(cm.mech, S.equilibrium_phi(p, mu0, 1) + 0.05), None, p, t_end)
    msg = ""

    def hits(m, start):
        nonlocal msg
        try:
            return False, _attractor(m, start[0], start[1], p, t_end)[1]
        except PainleveError as exc:
            msg = str(exc)
            return True, None
    if bracket is None:
        lo, step = mu0, 0.05 * mu0
        for _ in range(6):
            hit, nxt = hits(lo + step, (sol.y_final, sol.final_mode))
            if hit:
                break
            lo, step, sol = lo + step, 2 * step, nxt
        else:
            raise NoHopfError(f"no Painlevé situation on the detached attractor up to mu={lo:.6g}")
        hi = lo + step
    else:
        lo, hi = map(float, bracket)
        _, sol = _attractor(lo, sol.y_final, sol.final_mode, p, t_end)
    start = (sol.y_final, sol.final_mode)
    hits_from_start = lambda m: hits(m, start)[0]  # noqa: E731
    if bracket is not None and (hits_from_start(lo) or not hits_from_start(hi)):
        raise NoHopfError(f"Painlevé onset not bracketed by [{lo}, {hi}]")
    while hi - lo > xtol:
        mid = 0.5 * (lo + hi)
        if hits_from_start(mid):
            hi = mid
        else:
            lo = mid
    return PainleveOnset(0.5 * (lo + hi), (lo, hi), msg)
