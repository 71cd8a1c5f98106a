"""The e_N = 0 detached branch near μ = 0.38957 (set 1, Fig. 2(c)): why eq. (1) has no period adding.

Paper (Sec. 3): for decreasing μ the detached periodic motion is free flight–slip–stick–slip
down to μ = 0.38965; then the stick phase disappears from one "period" (pattern S n), then
from two consecutive ones (S n n), …, a cascade accumulating at μ = 0.38957 where the
attractor disappears.  Belt v = −1 m/s, g = 10, set 1 throughout (see model/slip docstrings).

What eq. (1) with exact Coulomb/Poisson contact does (hybrid engine, DOP853 rtol 1e-11)
--------------------------------------------------------------------------------------
1. *Stick is a reset.*  In stick (g_N = 0, γ_T = 0) the state is a function of φ alone
   (φ̇ = v/(l cos φ) < 0, so φ decreases).  Stick is admissible on one interval
   φ ∈ [φ_P, φ_Q] = [0.39017, 0.42855] (μ = 0.38957; :func:`stick_exit`) and every stick
   phase ends at its lower end P (λ_T = −μλ_N, slip+ onset).  Hence *every* orbit with a
   stick phase passes through the same point P(μ), and an orbit S n^(k−1) exists iff the
   trajectory from P (:func:`exit_orbit`) sticks again for the first time in its k-th cycle
   (a cycle = impact to impact).  Other initial conditions cannot add orbits with stick
   phases, only stick-free attractors: 12 random starts (8 in flight, 4 perturbed slip
   equilibria) end on the period-1 stick orbit at μ = 0.38960 and on the slip
   equilibrium at μ = 0.38955.
2. *A 1-D map and a border collision.*  With e_N = 0 a cycle is flight → plastic impact →
   slip → (stick) → slip → lift-off, and lift-off states lie on the curve λ_N = 0 of the
   slip surface, so cycle-to-cycle dynamics is a 1-D map.  Its stick-free branch has an
   unstable fixed point (a flight–slip orbit, multiplier λ = 1.2127) whose slip phase
   misses γ_T = 0 by g_F ≈ 32.3 (μ − μ*) for μ > μ* (:func:`stick_free_saddle`; a saddle
   coexisting with the stick orbit, separating its basin from the slip equilibrium's); for
   μ < μ* it is virtual.  The trajectory from P misses stick in its first cycle by
   g_1 = 6.88 (μ* − μ) for μ < μ*.  At μ* both vanish: the stick orbit's stick time → 0
   (∝ sqrt(μ − μ*): it grazes γ_T = 0 at P, where the slip acceleration γ̇_T vanishes) and
   it becomes the saddle.  Below μ* the stick-free iterates from P move away from the
   (virtual) saddle, i.e. away from stick: the minima of γ_T grow by 1.2127 per cycle and
   after ~80 cycles the motion decays onto the slip equilibrium.  An S n^(k−1) window
   would need 0 < g_1 < g_F (P's first miss between the stick boundary and a *real*
   saddle); the slopes' signs exclude that near μ*, and scans find period 1 or nothing.

   Result: the stick orbit ends at μ* = 0.38956911 (:func:`end_of_stick_orbit`, bisection to
   1e-10; the linear extrapolation of g_1 gives the same to 1e-10), equal to the printed
   accumulation point 0.38957 within half a unit of its 5th digit.  There is no
   period-adding cascade: in the paper's window (0.38957, 0.38965) our attractor is the
   period-1 stick orbit; the first three steps do not exist in this model.
3. *Stick tolerance* (``stick_tol=η`` of :class:`landau.verify.lancioni.contact.ContactModel`, off by
   default): codes of the paper's era detected stick as |γ_T| < η.  With ``"project"``
   (γ_T set to 0 at the tolerance stick) the reset stays P and the first miss must exceed
   η: μ_end = μ* − η/6.88 = μ* − 0.1453 η.  With ``"hold"`` (Karnopp-like band, γ_T kept at
   η in stick) the model *is* eq. (1) with belt speed |v| − η (slip forces do not depend on
   |v|): μ_end = μ* + 0.0309 η, and the exact model with v = −0.999 gives μ* = 0.38960000
   against 0.38959998 for hold with η = 1e-3.  Both shifts are linear in η (η = 1e-5, 1e-4,
   1e-3 agree to 1e-3 relative) and *neither produces a cascade*: every bisection point has
   period 1 or loses the stick orbit.  A late stick exit (leaving stick up to 1e-3 rad past
   P, as a step-end check would) does not either: at μ* + 2e-5 and μ* + 8.1e-5 the orbit
   still sticks in every cycle.  A cascade needs the reset to land between the stick
   boundary and the real saddle (0 < g_1 < g_F; g_F = 2.6e-3 m/s at the paper's first step
   0.38965): some feature of the paper's integration that is not given.  We do not tune
   ours: the printed accumulation value is reproduced (as the end of the stick orbit), the
   cascade is documented as not reproduced (README, scene ``lancioni/period-adding``).
   Side result: μ* depends on the unprinted belt speed as dμ*/d|v| = −0.0309, so the
   5-digit agreement is consistent with |v| = 1 m/s to about ±2e-4 m/s.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Mapping

import numpy as np
from scipy.optimize import brentq

from landau.errors import NoHopfError
from landau.verify.hybrid import simulate
from landau.verify.hybrid.dop853 import CompiledDOP853
from landau.verify.lancioni.contact import Section, default_options
from landau.verify.lancioni.model import ConstantBelt, build, slip_state
from landau.verify.lancioni.slip import resolve

STEPPER = CompiledDOP853(1e-11, 1e-13)
#: μ inside the paper's cascade window (0.38957, 0.38965) and the window itself
PAPER_STEP, PAPER_ACCUMULATION = 0.38965, 0.38957


def _gT(p, y):
    return p["l"] * np.cos(y[0]) * y[2] - (-1.0)  # γ_T = lφ̇ cos φ − v, belt v = −1


@dataclass(frozen=True)
class _MinusGammaTDot:
    """−γ̇_T = −(l cos φ φ̈ − l sin φ φ̇²) at (t, y, q̈): numpy arrays, or sympy expressions with
    ``symbolic`` (compared by value, so the models of one bar share their compiled guards)."""

    l: float
    symbolic: bool = False

    def __call__(self, t, y, acc):
        if self.symbolic:
            import sympy as sp

            cos, sin = sp.cos, sp.sin
        else:
            cos, sin = np.cos, np.sin
        return -(self.l * cos(y[0]) * acc[0] - self.l * sin(y[0]) * y[2] ** 2)


def _gT_min_section(p) -> Section:
    """Section at the minima of γ_T (γ̇_T = l cos φ φ̈ − l sin φ φ̇² crossing 0 upwards)."""
    l = float(p["l"])
    return Section("gT-min", _MinusGammaTDot(l), symbolic=_MinusGammaTDot(l, True))


def _model(mu: float, p, stick_tol: float = 0.0, stick_tol_reset: str = "project"):
    return build(mu, 0.0, p, ConstantBelt(-1.0), sections=(_gT_min_section(p),), stick_tol=stick_tol,
                 stick_tol_reset=stick_tol_reset)


@dataclass(frozen=True)
class StickExit:
    """The point P where every stick phase ends (slip+ onset, λ_T = −μλ_N) and the stick interval."""

    mu: float
    phi: float                         # φ_P
    interval: tuple[float, float]      # admissible stick angles [φ_P, φ_Q]
    state: np.ndarray                  # (φ, y, φ̇, ẏ) at P, γ_N = γ_T = 0

    def __repr__(self) -> str:
        return (f"StickExit(mu={self.mu:.9g}, phi_P={self.phi:.10f}, "
                f"stick for phi in [{self.interval[0]:.5f}, {self.interval[1]:.5f}])")


def stick_exit(cm) -> StickExit:
    """Scan the stick set (φ̇ = v/(l cos φ)) for admissibility; P = the lower end of its one interval."""
    mech = cm.mech
    l = mech.params["l"]

    def state(phi):
        return slip_state(mech, phi, float(mech.belt(0.0)) / (l * np.cos(phi)))

    phis = np.linspace(-1.4, 1.4, 2801)
    margin = np.array([float(cm.stick_margin(0.0, state(x))) for x in phis])
    ok = margin >= 0
    edges = np.nonzero(np.diff(ok.astype(int)))[0]
    if len(edges) != 2 or ok[0]:
        raise ValueError(f"expected one stick interval, found admissibility changes at {phis[edges]}")

    def m(x):
        return float(cm.stick_margin(0.0, state(x)))
    lo = brentq(m, phis[edges[0]], phis[edges[0] + 1], xtol=1e-15)
    hi = brentq(m, phis[edges[1]], phis[edges[1] + 1], xtol=1e-15)
    return StickExit(mech.mu, lo, (lo, hi), mech.project_stick(0.0, state(lo)))


@dataclass(frozen=True)
class ExitOrbit:
    """The trajectory from P, cycle by cycle (cycle 0: P to the first impact)."""

    mu: float
    stick_tol: float
    pattern: str                # per completed cycle: S (has a stick phase) / n (none)
    stick_times: np.ndarray
    gT_minima: np.ndarray       # smallest γ_T at a slip-phase minimum of each cycle (inf: none)
    final_mode: str
    last_impact: float
    t_end: float

    @property
    def period(self) -> int:
        """Cycles between the stick phases after the first one (1: S S S …); 0: never sticks again."""
        idx = [i for i, c in enumerate(self.pattern) if c == "S"]
        if len(idx) < 2:
            return 0
        gaps = np.diff(idx)
        return int(gaps[-1]) if np.all(gaps == gaps[-1]) else -1

    @property
    def decayed(self) -> bool:
        """Ended in slip with no impact in the last 2 s (on the slip equilibrium's basin)."""
        return self.final_mode.startswith("slip") and self.last_impact < self.t_end - 2.0

    def __repr__(self) -> str:
        return f"ExitOrbit(mu={self.mu:.10g}, eta={self.stick_tol:g}, period={self.period}, {self.pattern[:30]}…)"


def exit_orbit(mu: float, params: Mapping[str, float] | None = None, t_end: float = 3.0,
               stick_tol: float = 0.0, stick_tol_reset: str = "project") -> ExitOrbit:
    """Simulate from the stick exit P (the only point every orbit with a stick phase visits)."""
    p = resolve(params)
    cm = _model(mu, p, stick_tol, stick_tol_reset)
    P = stick_exit(cm)
    sol = simulate(cm.model, "slip+", P.state, (0.0, t_end), STEPPER, default_options(record=False))
    pat, st, gm = [], [], []
    cur_st, cur_gm, t_in = 0.0, np.inf, None
    last_imp = 0.0
    for e in sol.events:
        if e.guard == "impact":
            pat.append("S" if cur_st > 0 else "n")
            st.append(cur_st)
            gm.append(cur_gm)
            cur_st, cur_gm, last_imp = 0.0, np.inf, e.t
        elif e.guard == "gT-min" and e.from_mode.startswith("slip"):
            cur_gm = min(cur_gm, float(_gT(p, e.y)))
        if e.to_mode == "stick" and e.from_mode != "stick":
            t_in = e.t
        elif e.from_mode == "stick" and e.to_mode != "stick" and t_in is not None:
            cur_st += e.t - t_in
            t_in = None
    return ExitOrbit(float(mu), float(stick_tol), "".join(pat), np.array(st), np.array(gm), sol.final_mode, last_imp,
                     float(t_end))


def stick_orbit_window(params: Mapping[str, float] | None = None) -> tuple[float, float]:
    """The μ interval searched for the end of the stick orbit, derived from the model.

    The detached stick orbit lives below the Hopf point μ_c of the slip equilibrium (computed by
    :func:`landau.verify.lancioni.slip.slip_hopf`): the upper end is μ_c, the lower end
    μ_c(1 − 0.02·2^k), the first k = 0, 1, … (at most 5) where the orbit through P no longer
    sticks again; :func:`end_of_stick_orbit` checks both ends.

    Parameters
    ----------
    params : mapping, optional
        Mechanical parameters (default: set 1).

    Returns
    -------
    tuple of float
        (lo, hi).
    """
    from landau.verify.lancioni.slip import slip_hopf
    hi = float(slip_hopf(params, s=1).p_c)
    for k in range(6):
        lo = hi * (1 - 0.02 * 2 ** k)
        if exit_orbit(lo, params, 3.0).period == 0:
            return lo, hi
    raise NoHopfError(f"the orbit through the stick exit P still sticks at mu={lo:.6g} (Hopf point {hi:.6g})")


def end_of_stick_orbit(params: Mapping[str, float] | None = None, bracket: tuple[float, float] | None = None,
                       xtol: float = 1e-10, stick_tol: float = 0.0,
                       stick_tol_reset: str = "project") -> tuple[float, tuple[tuple[float, int], ...]]:
    """μ where the orbit through P stops sticking again (bisection); also every (μ, period) seen.

    Period 1 at the top of ``bracket`` (default: :func:`stick_orbit_window`, from the model) and
    no further stick at the bottom are checked; a period other than 0 or 1 met anywhere is
    returned in the list (a cascade would show there).
    """
    if bracket is None:
        bracket = stick_orbit_window(params)
    lo, hi = map(float, bracket)
    seen = []

    def period(m):
        r = exit_orbit(m, params, 3.0, stick_tol, stick_tol_reset)
        seen.append((m, r.period))
        return r.period
    if period(hi) != 1 or period(lo) != 0:
        raise NoHopfError(f"bracket {bracket} does not enclose the end of the period-1 stick orbit: {seen}")
    while hi - lo > xtol:
        mid = 0.5 * (lo + hi)
        if period(mid) == 0:
            lo = mid
        else:
            hi = mid
    return 0.5 * (lo + hi), tuple(seen)


@dataclass(frozen=True)
class FirstMiss:
    """Below μ*: the exit orbit's γ_T minima g_k (k = 1, 2, …) and their growth factor."""

    mu: float
    gT_minima: np.ndarray
    multiplier: float           # (g_{k+1} − g_k)/(g_k − g_{k−1}): the stick-free map's expansion

    @property
    def g1(self) -> float:
        """Miss of the first cycle after P (m/s)."""
        return float(self.gT_minima[0])


def first_miss(mu: float, params: Mapping[str, float] | None = None, cycles: int = 8) -> FirstMiss:
    """γ_T minima of the first stick-free cycles from P (needs μ < μ*)."""
    r = exit_orbit(mu, params, t_end=0.2 * (cycles + 2))
    g = r.gT_minima[1:cycles + 1]
    if not np.all(np.isfinite(g)) or "S" in r.pattern[1:]:
        raise ValueError(f"mu={mu} is not below the end of the stick orbit (pattern {r.pattern})")
    d = np.diff(g)
    return FirstMiss(float(mu), g, float(np.median(d[1:] / d[:-1])))


@dataclass(frozen=True)
class SaddleOrbit:
    """The unstable stick-free flight–slip orbit for μ > μ* (found as the stick/decay basin boundary)."""

    mu: float
    gT_min: float               # its slip phase's minimum of γ_T (> 0: real, no stick)
    cycles_near: int            # stick-free cycles spent near it by the boundary trajectory


def stick_free_saddle(mu: float, params: Mapping[str, float] | None = None, tol: float = 1e-12) -> SaddleOrbit:
    """Bisect a 1-D family of flight states (φ̇ shifted) between 'sticks again' and 'decays'.

    The family starts 0.1 s after P (in flight); the boundary trajectory follows the stable
    manifold of the saddle and lingers near it; its γ_T minimum at the closest approach
    (smallest change between consecutive cycles) is the saddle's.
    """
    p = resolve(params)
    cm = _model(mu, p)
    P = stick_exit(cm)
    base = simulate(cm.model, "slip+", P.state, (0.0, 0.1), STEPPER, default_options(record=False))
    if base.final_mode != "flight":
        raise ValueError("expected flight 0.1 s after the stick exit")

    def run(s):
        y = base.y_final.copy()
        y[2] += s
        sol = simulate(cm.model, "flight", y, (0.0, 12.0), STEPPER, default_options(record=False))
        ev = list(sol.events)
        imp = [i for i, e in enumerate(ev) if e.guard == "impact"]
        gm, stuck = [], False
        for a, b in zip(imp[:-1], imp[1:], strict=True):
            if any(e.to_mode == "stick" for e in ev[a:b]):
                stuck = True
                break
            gm.append(min((float(_gT(p, e.y)) for e in ev[a:b] if e.guard == "gT-min"
                           and e.from_mode.startswith("slip")), default=np.inf))
        return stuck, np.array(gm)
    ss = -np.logspace(-6, -1.5, 19)
    flags = [run(s)[0] for s in ss]
    j = next((i for i in range(len(ss) - 1) if flags[i] and not flags[i + 1]), None)
    if j is None:
        raise ValueError(f"no stick/decay boundary in the family at mu={mu}")
    lo, hi = ss[j], ss[j + 1]
    gm_lo = run(lo)[1]
    while abs(hi - lo) > tol:
        mid = 0.5 * (lo + hi)
        stuck, gm = run(mid)
        if stuck:
            lo, gm_lo = mid, gm
        else:
            hi = mid
    g = gm_lo[np.isfinite(gm_lo)]
    k = int(np.argmin(np.abs(np.diff(g)))) + 1
    return SaddleOrbit(float(mu), float(g[k]), len(g))


@dataclass(frozen=True)
class PeriodAdding:
    accumulation: float                 # μ* where the detached stick orbit ends (the paper's 0.38957)
    steps: tuple[float, ...]            # period-adding steps found (none for eq. (1); see docstring)
    periods: tuple[tuple[float, int], ...]  # (μ, period of the orbit through P) at every point tried
    multiplier: float                   # expansion of the stick-free map below μ*
    first_miss_slope: float             # g_1 = slope·(μ* − μ)
    method: str

    def __repr__(self) -> str:
        return (f"PeriodAdding(mu*={self.accumulation:.10g}, steps={self.steps}, periods seen="
                f"{sorted({p for _, p in self.periods})}, multiplier={self.multiplier:.4f})")


def period_adding_steps(params: Mapping[str, float] | None = None, n_steps: int = 3,
                        bracket: tuple[float, float] | None = None, xtol: float = 1e-10) -> PeriodAdding:
    """End of the stick orbit through P and any period-adding steps met on a scan of ``bracket``
    (default: :func:`stick_orbit_window`, from the Hopf point of the model).

    Scan: 24 points approaching the end geometrically from above (down to 1e-9 from it) plus
    the bisection points.  A step is a μ where the period of the orbit through P exceeds 1
    (at most ``n_steps`` reported).  For eq. (1) none exist (module docstring).
    """
    if bracket is None:
        bracket = stick_orbit_window(params)
    mu_end, seen_bisection = end_of_stick_orbit(params, bracket, xtol)
    seen = list(seen_bisection)
    for k in range(24):
        m = mu_end + (bracket[1] - mu_end) * 0.5 ** k
        seen.append((m, exit_orbit(m, params).period))
    fm = first_miss(mu_end - 1e-6, params)
    steps = sorted((m for m, per in seen if per not in (0, 1)), reverse=True)[:n_steps]
    return PeriodAdding(mu_end, tuple(steps), tuple(seen), fm.multiplier, fm.g1 / 1e-6,
                        f"orbit through the stick exit P; bisection xtol={xtol:g} + geometric scan")
