"""The spring–block driven by a load-point velocity history: velocity steps and slide-hold-slide.

The laboratory protocols of rate-and-state friction (Dieterich 1979; Ruina 1983; Marone 1998)
drive the spring's far end — the load point — at a piecewise-constant velocity V(t): a
*velocity step* V₁ → V₂, or a *slide-hold-slide* V → 0 → V.  With the load point at
x_lp(t) = ∫V dt, the block of Putelat et al. (2010), eq. (4), obeys

    M ẍ = k (x_lp(t) − x) − σ μ(ẋ, φ) − η ẋ,    dφᵢ/dt = rateᵢ(ẋ, φ),

with the optional terms of :mod:`landau.systems.springblock_terms`: radiation damping η
(``eta``; Rice 1993) and a normal load that follows the spring, σ = σ₀ + γ_LD k (x_lp − x)
(``gamma_ld``), whose changes also move the first state, dφ₁/dt gains −α_LD σ̇/(σ ∂μ/∂φ₁)
(``alpha_ld``; Linker & Dieterich 1992).  This module integrates it in the variables
u = x_lp − x (the spring's stretch, m), w = ln v and ψᵢ = ln φᵢ (v and φ stay positive and are
resolved over the tens of decades a hold spans):

    u' = V(t) − v,    w' = (k u − σ(u) μ − η v) / (M v),    ψᵢ' = rateᵢ / φᵢ,

one constant-velocity piece at a time with scipy's Radau IIA (exact Jacobian from the symbolic
law).  At M = 0 with η > 0 (the quasi-dynamic limit, Rice 1993) the momentum equation is the force
balance k u = σ(u) μ(v, φ) + η v, solved for w at every evaluation
(:func:`~landau.verify.springblock.forcebalance.solve_log_rate`, as the constant-velocity cell of
:mod:`landau.verify.springblock.quasidynamic`), and (u, ψ…) are integrated with the Jacobian
f_y − f_w R_y/R_w of the implicit slip rate.  Every run starts from steady sliding at the first
velocity (v = V₀, φ = φ_ss(V₀), k u = (σ₀ μ_ss + ηV₀)/(1 − γ_LD μ_ss)).  :func:`parse_history` reads the command line's
``"V0@t0,V1@t1,..."``; :func:`simulate_history` returns a
:class:`~landau.verify.hybrid.result.Simulation` whose series are the load-point velocity ``V``,
the slip rate ``v``, the friction coefficient ``mu`` = μ(v, φ) and the states, and with ``eta``
or ``gamma_ld`` also the spring force ``F`` = k u [N] and (``gamma_ld``) the normal load
``sigma`` [N].
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Mapping

import numpy as np
import sympy as sp

from landau.errors import InputError, IntegratorError
from landau.laws.law import FrictionLaw
from landau.laws.law import v as v_slip
from landau.verify.hybrid.log import EventLog
from landau.verify.hybrid.result import Simulation, Status


@dataclass(frozen=True)
class LoadHistory:
    """A piecewise-constant load-point velocity: ``velocities[i]`` [m/s] from ``times[i]`` [s] on.

    ``times[0]`` is the start of the run, where the block slides steadily at ``velocities[0]``
    (> 0); a velocity 0 is a hold.
    """

    velocities: tuple[float, ...]
    times: tuple[float, ...]

    def __post_init__(self):
        V, T = self.velocities, self.times
        if len(V) != len(T) or not V:
            raise InputError("a load-point history needs one start time per velocity, at least one")
        if not all(math.isfinite(x) and x >= 0 for x in V):
            raise InputError(f"load-point velocities must be finite and >= 0 (0: a hold), got {list(V)}")
        if not V[0] > 0:
            raise InputError("the first load-point velocity must be > 0: the run starts from steady sliding there")
        if not all(math.isfinite(t) for t in T) or any(b <= a for a, b in zip(T, T[1:], strict=False)):
            raise InputError(f"the times of a load-point history must be finite and increasing, got {list(T)}")

    def velocity(self, t) -> np.ndarray:
        """The load-point velocity at ``t`` (the piece that starts at or before ``t``)."""
        i = np.clip(np.searchsorted(self.times, np.asarray(t, float), side="right") - 1, 0, len(self.times) - 1)
        return np.asarray(self.velocities, float)[i]

    def __str__(self) -> str:
        return ",".join(f"{v:g}@{t:g}" for v, t in zip(self.velocities, self.times, strict=True))


def parse_history(text: str) -> LoadHistory:
    """``"V0@t0,V1@t1,..."`` (m/s @ s) as a :class:`LoadHistory`.

    Examples: ``"1e-6@0,1e-5@20"`` (a velocity step at t = 20 s), ``"1e-5@0,0@10,1e-5@110"``
    (a 100 s hold).
    """
    if not isinstance(text, str) or not text.strip():
        raise InputError("--V-history: give 'V0@t0,V1@t1,...' (velocity in m/s from each time in s on)")
    vel, times = [], []
    for item in text.split(","):
        parts = item.split("@")
        if len(parts) != 2:
            raise InputError(f"--V-history: {item.strip()!r} is not 'V@t' (velocity @ start time)")
        try:
            vel.append(float(parts[0]))
            times.append(float(parts[1]))
        except ValueError:
            raise InputError(f"--V-history: {item.strip()!r}: velocity and time must be numbers") from None
    return LoadHistory(tuple(vel), tuple(times))


def _steady_state(law: FrictionLaw, V: float, p: Mapping[str, float]) -> tuple[list[float], float]:
    from landau.verify.springblock.model import _steady_state as ss

    phi = ss(law, V, p)
    vals = {prm.symbol: p[prm.name] for prm in law.parameters}
    mu = float(law.mu.subs({v_slip: V, **dict(zip(law.states, phi, strict=True)), **vals}))
    if not math.isfinite(mu):
        raise InputError(f"law {law.name!r}: the friction coefficient is not finite at steady sliding V = {V:g} m/s")
    return phi, mu


def _history_law(law: FrictionLaw, p: Mapping[str, float], k: float, terms: tuple[str, ...]):
    """The law in the history's variables, shared by the fields at M > 0 and M = 0: the symbols
    u, w = ln v, ψ = ln φ…, V_lp, the normal load σ = σ₀ + γ_LD k u (Linker & Dieterich 1992), μ and
    the state rates (the first with the α_LD response to dσ/dt), every law parameter substituted."""
    ns = len(law.states)
    u, w = sp.symbols("u_ w_", real=True)
    psi = sp.symbols(f"psi_0:{ns}", real=True)
    Vlp = sp.Symbol("V_lp_", real=True)
    vals = {prm.symbol: p[prm.name] for prm in law.parameters}
    sub = {v_slip: sp.exp(w), **{s: sp.exp(q) for s, q in zip(law.states, psi, strict=True)}}

    def tidy(e):
        return sp.expand_log(e.subs(vals).xreplace(sub), force=True)

    gam = float(p.get("gamma_ld", 0.0)) if "gamma_ld" in terms else 0.0
    sigma = float(p["sigma"]) + gam * k * u          # the normal load follows the spring force
    rates = [tidy(r) for r in law.rates]
    if "alpha_ld" in terms and gam != 0:
        sig_dot = gam * k * (Vlp - sp.exp(w))
        rates[0] = rates[0] - float(p["alpha_ld"]) * sig_dot / (sigma * tidy(sp.diff(law.mu, law.states[0])))
    return u, w, psi, Vlp, sigma, tidy(law.mu), rates


def _field(law: FrictionLaw, p: Mapping[str, float], k: float, terms: tuple[str, ...] = ()):
    """f(t, y; V) and its Jacobian in (u, w, ψ…), and μ(w, ψ…), compiled by lambdify from the law
    (with the optional ``terms``: η, γ_LD, α_LD, module docstring)."""
    u, w, psi, Vlp, sigma, mu, rates = _history_law(law, p, k, terms)
    M = float(p["M"])
    if M == 0:       # quasi-dynamic: the field is _field_m0's
        return None, None, sp.lambdify([[u, w, *psi]], mu, "numpy")
    eta = float(p.get("eta", 0.0)) if "eta" in terms else 0.0
    f = [Vlp - sp.exp(w), (k * u - sigma * mu - eta * sp.exp(w)) * sp.exp(-w) / M]
    f += [sp.expand(r * sp.exp(-q)) for r, q in zip(rates, psi, strict=True)]
    ys = [u, w, *psi]
    J = sp.Matrix(f).jacobian(sp.Matrix(ys))
    fn = sp.lambdify([ys, Vlp], f, "numpy")
    jn = sp.lambdify([ys, Vlp], J, "numpy")
    mun = sp.lambdify([ys], mu, "numpy")
    return fn, jn, mun


def _field_m0(law: FrictionLaw, p: Mapping[str, float], k: float, terms: tuple[str, ...]):
    """The quasi-dynamic history (M = 0): the force residual R(w, u, ψ…) ÷ σ₀ with R_w and R_y, and the
    field (u', ψ'…) with its derivatives in w and y = (u, ψ…), compiled by lambdify (w = ln v)."""
    u, w, psi, Vlp, sigma, mu, rates = _history_law(law, p, k, terms)
    sigma0 = float(p["sigma"])
    eta = float(p["eta"])
    R = (k * u - sigma * mu - eta * sp.exp(w)) / sigma0
    f = [Vlp - sp.exp(w)] + [sp.expand(r * sp.exp(-q)) for r, q in zip(rates, psi, strict=True)]
    ys = [u, *psi]
    res = sp.lambdify([w, *ys], (R, sp.diff(R, w), [sp.diff(R, q) for q in ys]), "math")
    fld = sp.lambdify([w, *ys, Vlp], (f, [sp.diff(e, w) for e in f], [[sp.diff(e, q) for q in ys] for e in f]),
                      "math")
    return res, fld


def _piece_times(t_eval: np.ndarray | None, a: float, b: float, last: bool) -> np.ndarray | None:
    """The output times of the piece [a, b) ([a, b] for the last one), or None (the steps)."""
    if t_eval is None:
        return None
    return t_eval[(t_eval >= a) & ((t_eval <= b) if last else (t_eval < b))]


def _pieces_m0(law, p, k, terms, h: LoadHistory, y, T, ends, t_end, rtol, scale, t_eval=None):
    """Integrate the history at M = 0 piece by piece: the slip rate from the force balance at every
    evaluation (:func:`~landau.verify.springblock.forcebalance.solve_log_rate`), (u, ψ…) by Radau IIA
    with the implicit-function Jacobian f_y − f_w R_y/R_w.  Returns the pieces' (t, Y, V) in (u, w, ψ…):
    at the accepted steps, or at the times ``t_eval`` from the integrator's dense output."""
    from scipy.integrate import solve_ivp

    from landau.verify.springblock.forcebalance import solve_log_rate

    res, fld = _field_m0(law, p, k, terms)
    centre = float(y[1])
    last = [centre]

    def rate(yy):
        last[0] = solve_log_rate(res, yy, last[0], centre)
        return last[0]

    def f(_t, yy, V):
        return np.asarray(fld(rate(yy), *yy, V)[0], float)

    def jac(_t, yy, V):
        w = rate(yy)
        _, Rw, Ry = res(w, *yy)
        _, fw, fy = fld(w, *yy, V)
        return np.asarray(fy, float) - np.outer(np.asarray(fw, float), np.asarray(Ry, float)) / Rw

    z = np.r_[y[0], y[2:]]
    zscale = np.r_[scale[0], scale[2:]]
    out, nsteps, nfev = [], 0, 0
    for V, a, b in zip(h.velocities, T, ends, strict=True):
        if a >= t_end:
            break
        b = min(b, t_end)
        te = _piece_times(t_eval, a, b, b >= t_end)
        try:
            sol = solve_ivp(f, (a, b), z, method="Radau", rtol=rtol, atol=rtol * zscale, jac=jac, args=(V,),
                            dense_output=te is not None)
        except IntegratorError as exc:
            raise IntegratorError(f"load-point history (M = 0), piece V = {V:g} m/s from t = {a:g} s: {exc}",
                                  t=a, state=list(z)) from exc
        if not sol.success or not np.all(np.isfinite(sol.y[:, -1])):
            raise IntegratorError(f"load-point history (M = 0), piece V = {V:g} m/s from t = {a:g} s: "
                                  f"{sol.message}", t=float(sol.t[-1]), state=sol.y[:, -1])
        tt, Z = (sol.t[1:], sol.y[:, 1:]) if te is None else (te, sol.sol(te).reshape(len(z), -1))
        W = np.array([solve_log_rate(res, q, centre, centre) for q in Z.T])
        Y = np.vstack([Z[0], W.reshape(-1), Z[1:]])
        out.append((tt, Y, np.full(len(tt), V)))
        nsteps += len(sol.t) - 1
        nfev += int(sol.nfev)
        z = sol.y[:, -1]
    return out, nsteps, nfev


def default_end(h: LoadHistory, params: Mapping[str, float]) -> float:
    """The end of a history's run where none is given: the last piece's start plus as long as the
    longest earlier piece (a single piece: 100 L/V₀) [s]."""
    T = list(h.times)
    longest = max([b - a for a, b in zip(T, T[1:], strict=False)]
                  or [100 * params.get("L", 1e-6) / h.velocities[0]])
    return T[-1] + longest


def simulate_history(law: FrictionLaw, history: LoadHistory | str, k: float,
                     params: Mapping[str, float] | None = None, t_end: float | None = None, *,
                     rtol: float = 1e-9, max_points: int = 200_000, t_eval=None) -> Simulation:
    """The spring–block under a load-point velocity history (module docstring).

    Parameters
    ----------
    law : FrictionLaw
        The rate-and-state law μ(v, φ), dφᵢ/dt.
    history : LoadHistory or str
        The load-point velocities and their start times (or ``"V0@t0,V1@t1,..."``).
    k : float
        Spring (machine) stiffness [N/m]; steady sliding is stable above k_c at each velocity.
    params : mapping, optional
        Law and block parameters (:meth:`landau.systems.system.SpringBlock.resolve`: M, g, sigma,
        and the optional terms eta, gamma_ld, alpha_ld of
        :meth:`~landau.systems.system.SpringBlock.for_params`).
    t_end : float, optional
        End of the run [s] (default: the last piece's start plus as long as the longest earlier piece).
    rtol : float, optional
        Relative tolerance of the Radau IIA (absolute: ``rtol`` in u/L, w and ψ).
    max_points : int, optional
        Bound on the recorded points (evenly thinned past it).
    t_eval : array_like, optional
        Increasing times in [t₀, ``t_end``] to give the series at, from each piece's Radau IIA dense
        output (the same steps as without it); default: the accepted steps.

    Returns
    -------
    Simulation
        ``state_names`` = (V, v, mu, states…): the load-point velocity [m/s], the slip rate
        [m/s], μ(v, φ) and the states, then the spring force F [N] with ``eta`` or ``gamma_ld`` and
        the normal load sigma [N] with ``gamma_ld``; sampled at the integrator's steps; status
        ``finished``.

    Raises
    ------
    InputError
        A bad history, stiffness or end time; M < 0, or M = 0 without radiation damping η > 0.
    NoSteadySlidingError
        1 − γ_LD μ_ss(Vᵢ) ≤ 0 at a velocity of the history (no steady sliding there).
    IntegratorError
        The integrator failed (with the time and state).

    References
    ----------
    Putelat, T., Dawes, J. H. P. & Willis, J. R. (2010), J. Mech. Phys. Solids 58, 27–53, eq. (4).
    Marone, C. (1998), Laboratory-derived friction laws and their application to seismic
    faulting, Annu. Rev. Earth Planet. Sci. 26, 643–696 (velocity steps, slide-hold-slide).
    """
    from scipy.integrate import solve_ivp

    from landau.systems.system import SpringBlock

    h = parse_history(history) if isinstance(history, str) else history
    if not (math.isfinite(k) and k > 0):
        raise InputError(f"stiffness k must be a finite number > 0, got {k!r}")
    block = SpringBlock.for_params(law, params)      # with the optional terms given (eta, gamma_ld, alpha_ld)
    p = block.resolve(params)
    terms = block.terms
    quasidynamic = p["M"] == 0
    if not (p["M"] > 0 or (quasidynamic and p.get("eta", 0.0) > 0)):
        raise InputError("a load-point history is simulated with a block mass M > 0, or at M = 0 with radiation "
                         f"damping eta > 0 (the quasi-dynamic limit); got M = {p['M']!r}, "
                         f"eta = {p.get('eta', 0.0)!r}")
    T = list(h.times)
    if t_end is None:
        t_end = default_end(h, p)
    if not (math.isfinite(t_end) and t_end > T[-1]):
        raise InputError(f"the end time must be after the last piece's start t = {T[-1]:g} s, got {t_end!r}")
    if t_eval is not None:
        t_eval = np.asarray(t_eval, float).reshape(-1)
        if not (len(t_eval) and np.all(np.isfinite(t_eval)) and np.all(np.diff(t_eval) > 0)
                and t_eval[0] >= T[0] and t_eval[-1] <= t_end):
            raise InputError(f"t_eval must be increasing finite times in [{T[0]:g}, {t_end:g}] s")
        appended = bool(t_eval[-1] < t_end)   # the end of the run, for the final state
        if appended:
            t_eval = np.r_[t_eval, t_end]
    phi0, mu0 = _steady_state(law, h.velocities[0], p)
    if "gamma_ld" in terms:   # steady sliding at every sliding velocity of the history needs 1 - gamma mu_ss > 0
        from landau.systems.springblock_terms import check_steady_sliding

        for V in sorted({V for V in h.velocities if V > 0}):
            check_steady_sliding(law, _steady_state(law, V, p)[1], p, V)
    fn, jn, mun = _field(law, p, k, terms)
    eta = float(p.get("eta", 0.0)) if "eta" in terms else 0.0
    gam = float(p.get("gamma_ld", 0.0)) if "gamma_ld" in terms else 0.0
    F0 = (float(p["sigma"]) * mu0 + eta * h.velocities[0]) / (1.0 - gam * mu0)   # spring force k u at steady sliding
    y = np.array([F0 / k, math.log(h.velocities[0]), *(math.log(x) for x in phi0)])
    scale = np.array([p.get("L", 1e-6)] + [1.0] * (len(y) - 1))
    ts, ys, vs = [np.array([T[0]])], [y[:, None]], [np.array([h.velocities[0]])]
    if t_eval is not None:   # the series at the times asked for only
        ts, ys, vs = [], [], []
    ends = T[1:] + [t_end]
    nsteps = nfev = 0
    if quasidynamic:
        pieces, nsteps, nfev = _pieces_m0(law, p, k, terms, h, y, T, ends, t_end, rtol, scale, t_eval)
        for tt, Y, Vl in pieces:
            ts.append(tt)
            ys.append(Y)
            vs.append(Vl)
    for V, a, b in zip(h.velocities, T, ends, strict=True):
        if quasidynamic or a >= t_end:
            break
        b = min(b, t_end)
        te = _piece_times(t_eval, a, b, b >= t_end)
        sol = solve_ivp(lambda t, yy, V=V: fn(yy, V), (a, b), y, method="Radau", rtol=rtol, atol=rtol * scale,
                        jac=lambda t, yy, V=V: np.asarray(jn(yy, V), float), dense_output=te is not None)
        if not sol.success or not np.all(np.isfinite(sol.y[:, -1])):
            raise IntegratorError(f"load-point history, piece V = {V:g} m/s from t = {a:g} s: {sol.message}",
                                  t=float(sol.t[-1]), state=sol.y[:, -1])
        tt, Y = (sol.t[1:], sol.y[:, 1:]) if te is None else (te, sol.sol(te).reshape(len(y), -1))
        ts.append(tt)
        ys.append(Y)
        vs.append(np.full(len(tt), V))
        nsteps += len(sol.t) - 1
        nfev += int(sol.nfev)
        y = sol.y[:, -1]
    t = np.concatenate(ts)
    Y = np.concatenate(ys, axis=1)
    Vl = np.concatenate(vs)
    if len(t) > max_points and t_eval is None:
        keep = np.unique(np.linspace(0, len(t) - 1, max_points).astype(int))
        t, Y, Vl = t[keep], Y[:, keep], Vl[keep]
    mu = np.broadcast_to(np.asarray(mun(Y), float), t.shape)
    out = np.vstack([Vl, np.exp(Y[1]), mu, np.exp(Y[2:])])
    names = ("V", "v", "mu") + tuple(s.name for s in law.states)
    if "eta" in terms or "gamma_ld" in terms:   # the spring force, and the normal load that follows it
        out = np.vstack([out, k * Y[0]])
        names += ("F",)
        if "gamma_ld" in terms:
            out = np.vstack([out, float(p["sigma"]) + gam * k * Y[0]])
            names += ("sigma",)
    regimes = tuple((a, min(b, t_end), "hold" if V == 0 else "slide")
                    for V, a, b in zip(h.velocities, T, ends, strict=True) if a < t_end)
    final, t_final = out[:, -1].copy(), float(t[-1])
    if t_eval is not None and appended:
        t, out = t[:-1], out[:, :-1]
    return Simulation("spring-block (load-point history)", t, out, EventLog(), Status.FINISHED,
                      Status.FINISHED.advice, t_final, final, nsteps, nfev, None, names, regimes)


def peak_after(sim: Simulation, t_from: float) -> float:
    """The largest friction coefficient μ of ``sim`` at t ≥ ``t_from`` (a slide-hold-slide's
    peak on reloading)."""
    i = list(sim.state_names).index("mu")
    keep = sim.t >= t_from
    if not keep.any():
        raise InputError(f"no recorded point at t >= {t_from:g}")
    return float(sim.y[i, keep].max())
