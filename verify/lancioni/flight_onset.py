"""Why the set-2 free-flight onset is μ = 0.44986 here and ≈ 0.453 in the paper (Fig. 4).

Lancioni, Lenci & Galvanetto, Sec. 3 (second set m₁ = 0.4 kg, k_φ = 25 N·m): "for μ > 0.453
a more complex free flight–slip–stick–slip motion takes place"; the bifurcation diagram
(Fig. 4) plots φ̇_max on the Poincaré section.  What eq. (1) does (belt v = −1 m/s, g = 10):

* :func:`flight_cycle` — the attractor just past lift-off: the flight starts 14 ms *after*
  the φ̇ maximum of the slip phase, ends in an impact, then slip → stick → slip.  Stick is a
  reset (its state is a function of φ alone and it always ends at the same point P(μ), see
  :mod:`landau.verify.lancioni.period_adding`), so the section value φ̇_max — reached on the slip
  flow from P before any flight — is *exactly* that of the continued contact (no lift-off)
  branch, for e_N = 0 and 0.2 alike.  The diagram cannot show the onset.
* :func:`continued_phidot_max` — that contact-branch value computed independently: the
  reduced slip ODE (:mod:`landau.verify.lancioni.slip`) from P to its first maximum of φ̇.
* The belt speed |v| is not printed; the printed stick onset (≈ 0.360, i.e. [0.3595, 0.3605])
  pins it only to |v| ∈ [0.9542, 1.0156], across which the flight onset runs from 0.4663 to
  0.4444 (d μ_flight/d|v| ≈ −0.36, d μ_stick/d|v| ≈ +0.017).  |v| ≈ 0.991 reproduces all
  three published values (Hopf 0.3531, stick 0.3601, flight 0.4530); :func:`flies` lets a
  test check that at μ = 0.453 without a bisection.

Every function also takes a ``friction`` law (:class:`~landau.laws.velocity.VelocityFriction`,
default the paper's Coulomb μ) and its bifurcation ``parameter``; ``mu`` is then that
parameter's value.  :func:`first_lift_off` follows the slip phase from a state on the belt to
its first event (lift-off, or the end of slip) — the lift-off of a slip motion with any law.
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass

import numpy as np
from scipy.integrate import solve_ivp

from landau.errors import IntegratorError
from landau.verify.hybrid import Status, simulate
from landau.verify.hybrid.dop853 import CompiledDOP853
from landau.verify.lancioni import slip as S
from landau.verify.lancioni.analysis import _flow
from landau.verify.lancioni.contact import default_options
from landau.verify.lancioni.model import (
    PHI_ZERO_UP,
    PHIDOT_MAX,
    ConstantBelt,
    build,
    build_at,
    slip_state,
)
from landau.verify.lancioni.period_adding import stick_exit

STEPPER = CompiledDOP853(1e-10, 1e-12)


@dataclass(frozen=True)
class FlightCycle:
    """Per-period measurements on the attractor at μ (after a transient)."""

    mu: float
    eN: float
    v: float
    flights_per_period: float
    flight_time: float            # longest free-flight phase (s)
    gap_max: float                # max g_N = y − l cos φ during flight (m)
    impact_speed: float           # largest |γ_N⁻| at an impact (m/s)
    phidot_max: tuple[float, ...]  # distinct section values (φ̇ maxima, φ̇ > 0; rounded to 1e-9)
    lift_off_after_max: bool      # every lift-off follows a φ̇ maximum within the same slip phase
    phi_min: float                # smallest φ: > 0 means the literal section φ = 0 is never crossed
    phi_zero_crossings: int

    def __repr__(self) -> str:
        return (f"FlightCycle(mu={self.mu:g}, eN={self.eN:g}, {self.flights_per_period:.3g} flights/period, "
                f"flight {self.flight_time:.4g} s, gap_max={self.gap_max:.3g} m, |γ_N⁻|={self.impact_speed:.3g} m/s, "
                f"phidot_max={self.phidot_max}, phi_min={self.phi_min:.4g})")


def _model(mu, eN, p, v, friction, parameter, **kw):
    """The hybrid model at bifurcation-parameter value ``mu`` (Coulomb μ by default)."""
    return build_at(mu, eN, p, ConstantBelt(v), friction=friction, parameter=parameter, **kw)


def _start(mu: float, p, v: float, friction=None, parameter=None):
    cm = _model(mu, 0.0, p, v, friction, parameter)
    vv = v if friction is not None else None
    return slip_state(cm.mech, S.equilibrium_phi(cm.mech.params, None, 1, cm.mech.friction, None, vv) + 0.05)


def flight_cycle(mu: float, eN: float = 0.0, v: float = -1.0, params: Mapping[str, float] | None = None,
                 t_transient: float = 14.0, t_keep: float = 6.0, *, friction=None,
                 parameter: str | None = None) -> FlightCycle:
    """Run from the slip equilibrium + 0.05 rad (set 2 by default) and measure the last ``t_keep`` s."""
    p = S.resolve(params or S.SET2)
    cm = _model(mu, eN, p, v, friction, parameter, sections=(PHIDOT_MAX, PHI_ZERO_UP))
    y0 = _start(mu, p, v, friction, parameter)
    T = t_transient + t_keep
    sol = simulate(cm.model, cm.initial_mode(0.0, y0), y0, (0.0, T), STEPPER, default_options(1e-6, record=True))
    if sol.status is not Status.FINISHED:
        raise IntegratorError(f"set-2 attractor run stopped early ({sol.status.value}) at mu={mu}", t=sol.t_final,
                              state=sol.y_final)
    ev = [e for e in sol.events if e.t >= t_transient]
    maxima = [e for e in ev if e.guard == "phidot-max" and e.y[2] > 0]
    lifts = [e for e in ev if e.guard == "lift-off"]
    fl = [s for s in sol.segments if s.mode == "flight" and s.t[0] >= t_transient and len(s.t) > 1]
    gaps = [float(np.max(s.y[1] - p["l"] * np.cos(s.y[0]))) for s in fl]
    imp = [abs(float(e.y[3] + p["l"] * np.sin(e.y[0]) * e.y[2])) for e in ev if e.guard == "impact"]
    # a lift-off "follows a maximum" if the previous non-section event before it is older than the last maximum
    after = True
    for e in lifts:
        prev_max = max((m.t for m in maxima if m.t < e.t), default=-np.inf)
        prev_switch = max((s.t for s in sol.events if s.kind != "section" and s.t < e.t), default=-np.inf)
        after &= prev_max > prev_switch
    t, y = sol.t, sol.y
    k = t >= t_transient
    n_per = max(len(maxima), 1)
    return FlightCycle(mu, eN, v, len(lifts) / n_per, max((s.t[-1] - s.t[0] for s in fl), default=0.0),
                       max(gaps, default=0.0), max(imp, default=0.0),
                       tuple(sorted({round(float(m.y[2]), 9) for m in maxima})), bool(after and lifts),
                       float(np.min(y[0, k])), sum(e.guard == "phi=0 up" for e in ev))


def continued_phidot_max(mu: float, v: float = -1.0, params: Mapping[str, float] | None = None, *,
                         friction=None, parameter: str | None = None) -> float:
    """φ̇_max of the stick–slip branch with the contact kept closed (λ_N < 0 allowed).

    Independent of the hybrid engine: the stick exit P(μ) (lower end of the admissible stick
    interval, :func:`landau.verify.lancioni.period_adding.stick_exit`), then the reduced slip+ ODE
    φ̈ = F(φ, φ̇; μ) (g_N ≡ 0) to the first maximum of φ̇ with φ̇ > 0.
    """
    p = S.resolve(params or S.SET2)
    cm = _model(mu, 0.0, p, v, friction, parameter)
    P = stick_exit(cm)
    rhs, _ = _flow(cm.mech.params, None, 1, cm.mech.friction, None, v if friction is not None else None)

    def top(t, y):  # φ̈ = 0 going down, only once φ̇ > 0
        return rhs(t, y)[1] if y[1] > 0 else 1.0
    top.direction, top.terminal = -1, True  # type: ignore[attr-defined]  # scipy's event attributes
    sol = solve_ivp(rhs, (0.0, 5.0), [P.state[0], P.state[2]], method="DOP853", rtol=1e-12, atol=1e-14,
                    events=top)
    if not sol.t_events[0].size:
        raise IntegratorError(f"no φ̇ maximum on the slip flow from the stick exit at mu={mu}")
    return float(sol.y_events[0][0][1])


def flies(mu: float, v: float = -1.0, params: Mapping[str, float] | None = None, t_end: float = 16.0,
          t_keep: float = 4.0, *, friction=None, parameter: str | None = None) -> bool:
    """Does the set-2 attractor at (μ, v) lift off in the last ``t_keep`` s (e_N = 0)?"""
    p = S.resolve(params or S.SET2)
    cm = _model(mu, 0.0, p, v, friction, parameter)
    y0 = _start(mu, p, v, friction, parameter)
    sol = simulate(cm.model, cm.initial_mode(0.0, y0), y0, (0.0, t_end), STEPPER, default_options(1e-6))
    return any(e.guard == "lift-off" and e.t > t_end - t_keep for e in sol.events)


@dataclass(frozen=True)
class FirstEvent:
    """The first event of a slip phase: when, which (``lift-off``: λ_N = 0; ``stop``: g_T = 0), where."""

    t: float
    guard: str
    state: np.ndarray       # (φ, y, φ̇, ẏ) at the event
    next_mode: str

    def __repr__(self) -> str:
        return (f"FirstEvent({self.guard} at t={self.t:.10g} s, phi={self.state[0]:.10g}, "
                f"phidot={self.state[2]:.10g}, then {self.next_mode})")


def first_lift_off(mu: float | None = None, phi: float | None = None, phidot: float = 0.0, v: float = -1.0,
                   params: Mapping[str, float] | None = None, t_end: float = 20.0, *, friction=None,
                   parameter: str | None = None, kick: float = 0.05) -> FirstEvent:
    """Simulate the impact oscillator from a state on the belt to the first end of its slip phase.

    Parameters
    ----------
    mu : float, optional
        Value of the bifurcation parameter (Coulomb μ; with a law, its ``parameter``); None keeps
        the law's own values.
    phi, phidot : float, optional
        Start on the belt (g_N = γ_N = 0) at this angle and rate; default the slip equilibrium
        + ``kick`` rad, at rest.
    v : float
        Constant belt velocity (m/s).
    params : mapping, optional
        Mechanical parameters (default set 1).
    t_end : float
        Give up after this time (s).
    friction : VelocityFriction, optional
        Friction-coefficient law (default: Coulomb).
    parameter : str, optional
        Its bifurcation parameter.
    kick : float
        Default start offset from the slip equilibrium (rad).

    Returns
    -------
    FirstEvent

    Raises
    ------
    IntegratorError
        No event before ``t_end``, or the start is not in slip.
    """
    p = S.resolve(params)
    if mu is None:
        law = friction
        cm = build(None if law is not None else 0.4, 0.0, p, ConstantBelt(v), friction=law)
    else:
        cm = _model(mu, 0.0, p, v, friction, parameter)
    if phi is None:
        vv = v if cm.mech.velocity_dependent else None
        phi = S.equilibrium_phi(cm.mech.params, None, 1 if v < 0 else -1, cm.mech.friction, None, vv) + kick
    y0 = slip_state(cm.mech, phi, phidot)
    mode = cm.initial_mode(0.0, y0)
    if not mode.startswith("slip"):
        raise IntegratorError(f"the start (phi={phi:.6g}, phidot={phidot:.6g}) is not in slip but in {mode}",
                              t=0.0, state=y0)
    ends = ("lift-off", "stop")
    sol = simulate(cm.model, mode, y0, (0.0, t_end), STEPPER, default_options(1e-6, record=False),
                   stop=lambda e: e.guard in ends)
    ev = [e for e in sol.events if e.guard in ends]
    if not ev:
        raise IntegratorError(f"the slip phase did not end before t={t_end:g} s ({sol.status.value})",
                              t=sol.t_final, state=sol.y_final)
    e = ev[0]
    return FirstEvent(float(e.t), e.guard, np.array(e.y, float), e.to_mode)


__all__ = ["FirstEvent", "FlightCycle", "continued_phidot_max", "first_lift_off", "flies", "flight_cycle"]
