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

one constant-velocity piece at a time with the compiled Radau IIA of
:mod:`landau.verify.hybrid.radau` (field and exact Jacobian generated from the symbolic law and
compiled once per law and set of terms, :func:`history_kernel`; V(t) is an entry of the parameter
vector), every piece a fresh run from the state the previous one left.  At M = 0 with η > 0 (the
quasi-dynamic limit, Rice 1993) or η = 0 (the quasi-static spring–slider of the laboratory models,
Ruina 1983; Gu et al. 1984, where v is fixed only while ∂μ/∂v > 0, checked at every sliding
velocity of the history) the momentum equation is the force balance
k u = σ(u) μ(v, φ) + η v; differentiated once and fed back, w' = −(R_y·y' + λR)/R_w
(:mod:`landau.verify.springblock.compiled_runs`), it keeps w a state of the same compiled run, and
as it does not contain V the state (u, w, ψ…) is exactly continuous across a jump of V.  Every run
starts from steady sliding at the first velocity (v = V₀, φ = φ_ss(V₀),
k u = (σ₀ μ_ss + ηV₀)/(1 − γ_LD μ_ss)).  :func:`parse_history` reads the command line's
``"V0@t0,V1@t1,..."``; :func:`simulate_history` returns a
:class:`~landau.verify.hybrid.result.Simulation` whose series are the load-point velocity ``V``,
the slip rate ``v``, the friction coefficient ``mu`` = μ(v, φ) and the states, and with ``eta``
or ``gamma_ld`` also the spring force ``F`` = k u [N] and (``gamma_ld``) the normal load
``sigma`` [N], and last the load-point displacement ``x_lp`` = ∫V dt and the slip ``slip`` =
x − x(t₀) [m], both from the start (:mod:`landau.verify.springblock.history_flow` gives the
solution between the recorded points).

Gu, J.-C., Rice, J. R., Ruina, A. L. & Tse, S. T. (1984), J. Mech. Phys. Solids 32, 167–196.
Ruina, A. (1983), J. Geophys. Res. 88, 10359–10370.
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
from landau.verify.hybrid.radau import STATUS
from landau.verify.hybrid.result import Simulation, Status
from landau.verify.springblock.compiled_runs import (
    FEEDBACK,
    CompiledField,
    cached_field,
    compile_field,
    drive,
    index_reduced,
    per_law,
)

#: budget of step attempts of one piece of a history
MAX_STEPS = 5_000_000


#: the slowest load-point velocity of a history [m/s] (0 is a hold): plate rates are ~1e-9 m/s
V_MIN = 1e-20


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
        slow = [x for x in V if 0 < x < V_MIN]
        if slow:   # the slip rate's logarithm and the scaled states leave float64's range below it
            raise InputError(f"a load-point velocity of {slow[0]:g} m/s is below {V_MIN:g} m/s, the slowest a history "
                             "integrates (give 0 for a hold)")
        if not V[0] > 0:
            raise InputError("the first load-point velocity must be > 0: the run starts from steady sliding there")
        if not all(math.isfinite(t) for t in T) or any(b <= a for a, b in zip(T, T[1:], strict=False)):
            raise InputError(f"the times of a load-point history must be finite and increasing, got {list(T)}")

    def velocity(self, t) -> np.ndarray:
        """The load-point velocity at ``t`` (the piece that starts at or before ``t``)."""
        i = np.clip(np.searchsorted(self.times, np.asarray(t, float), side="right") - 1, 0, len(self.times) - 1)
        return np.asarray(self.velocities, float)[i]

    def displacement(self, t) -> np.ndarray:
        """The load-point displacement x_lp(t) = ∫ V dt from ``times[0]`` [m] (piecewise linear in t)."""
        t = np.asarray(t, float)
        V, T = np.asarray(self.velocities, float), np.asarray(self.times, float)
        ends = np.r_[T[1:], np.inf]
        # each piece contributes V_i (min(t, T_{i+1}) − T_i) once t has passed its start
        spans = np.clip(np.minimum(t[..., None], ends) - T, 0.0, None)
        return spans @ V

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
    """(φ_ss, μ_ss) at sliding velocity V, computed once per law, V and law parameters in this process."""
    memo = per_law(law, ("steady states",), dict)
    key = (float(V), tuple(float(p[prm.name]) for prm in law.parameters))
    if key not in memo:
        from landau.verify.springblock.model import _steady_state as ss

        phi = ss(law, V, p)
        vals = {prm.symbol: p[prm.name] for prm in law.parameters}
        mu = float(law.mu.subs({v_slip: V, **dict(zip(law.states, phi, strict=True)), **vals}))
        if not math.isfinite(mu):
            raise InputError(f"law {law.name!r}: the friction coefficient is not finite at steady sliding "
                             f"V = {V:g} m/s")
        memo[key] = (tuple(phi), mu)
    phi, mu = memo[key]
    return list(phi), mu


def _check_direct_effect(law: FrictionLaw, V: float, p: Mapping[str, float]) -> None:
    """The quasi-static force balance k u = σ μ(v, φ) (M = 0, η = 0) fixes v only where μ grows with v:
    ∂μ/∂ln v > 0 at steady sliding at V (the direct effect a > 0), else an InputError."""
    phi, _ = _steady_state(law, V, p)
    vals = {prm.symbol: p[prm.name] for prm in law.parameters}
    at = {v_slip: V, **dict(zip(law.states, phi, strict=True)), **vals}
    slope = float((v_slip * sp.diff(law.mu, v_slip)).subs(at))
    if not slope > 0:
        raise InputError(f"law {law.name!r}: the quasi-static run (M = 0, eta = 0) needs a friction coefficient "
                         f"that grows with the slip rate (a direct effect dmu/dln v > 0), got {slope:g} at steady "
                         f"sliding V = {V:g} m/s (give radiation damping eta > 0, or M > 0)")


def _value(x):
    """A parameter value as the expressions take it: a float, or a sympy symbol of a compiled kernel."""
    return x if isinstance(x, sp.Basic) else float(x)


def _history_law(law: FrictionLaw, p: Mapping[str, float], k: float, terms: tuple[str, ...]):
    """The law and the terms in the history's variables, shared by the fields at M > 0 and M = 0: the
    symbols u (the spring's extension, F = k u), w = ln v, ψ = ln φ…, V_lp, and from the terms' one
    declaration (:func:`landau.systems.springblock_terms.force_balance`) the normal load σ, μ, the
    terms' forces and the state rates, every law parameter substituted.  The values in ``p`` and ``k``
    are numbers, or sympy symbols for the compiled kernel (:func:`history_kernel`): both are built from
    these expressions."""
    from landau.systems.springblock_terms import force_balance

    ns = len(law.states)
    u, w = sp.symbols("u_ w_", real=True)
    psi = sp.symbols(f"psi_0:{ns}", real=True)
    Vlp = sp.Symbol("V_lp_", real=True)
    vals = {prm.symbol: p[prm.name] for prm in law.parameters}
    sub = {v_slip: sp.exp(w), **{s: sp.exp(q) for s, q in zip(law.states, psi, strict=True)}}

    def tidy(e):
        return sp.expand_log(e.subs(vals).xreplace(sub), force=True)

    # the law's own symbols are kept for tidy (parameters first, then the variables, as before)
    at = {s: s for s in (v_slip, *law.states)}
    sigma, mu, forces, rates = force_balance(law, terms, at, v=sp.exp(w), F=k * u, F_dot=k * (Vlp - sp.exp(w)),
                                             V_lp=Vlp, k=k, sigma0=_value(p["sigma"]),
                                             symbol={t: _value(p[t]) for t in terms})
    return u, w, psi, Vlp, sigma, tidy(mu), tidy(forces), [tidy(r) for r in rates]


def _momentum(law: FrictionLaw, p: Mapping[str, float], k: float, terms: tuple[str, ...] = ()):
    """M > 0: (ys, f, V_lp), the field f(y; V_lp) in y = (u, w, ψ…): M v̇ = k u − σ μ + Σ forces (with the
    optional ``terms``, module docstring)."""
    u, w, psi, Vlp, sigma, mu, forces, rates = _history_law(law, p, k, terms)
    M = _value(p["M"])
    f = [Vlp - sp.exp(w), (k * u - sigma * mu + forces) * sp.exp(-w) / M]
    f += [sp.expand(r * sp.exp(-q)) for r, q in zip(rates, psi, strict=True)]
    return [u, w, *psi], f, Vlp


def _force_balance(law: FrictionLaw, p: Mapping[str, float], k: float, terms: tuple[str, ...]):
    """M = 0: (w, ys, R, f, V_lp), the force residual R(w, u, ψ…) = (k u − σ μ + Σ forces)/σ₀ and the
    field (u', ψ'…) of ys = (u, ψ…) with w = ln v implicit (η, which M = 0 needs, always among the terms)."""
    from landau.systems.springblock_terms import check_terms

    u, w, psi, Vlp, sigma, mu, forces, rates = _history_law(law, p, k, check_terms(("eta", *terms)))
    R = (k * u - sigma * mu + forces) / _value(p["sigma"])
    f = [Vlp - sp.exp(w)] + [sp.expand(r * sp.exp(-q)) for r, q in zip(rates, psi, strict=True)]
    return w, [u, *psi], R, f, Vlp


def _mu_function(law: FrictionLaw, p: Mapping[str, float], k: float, terms: tuple[str, ...]):
    """μ at the states y = (u, w, ψ…) (arrays): the law's μ lambdified once per law, with its
    parameters as arguments."""
    def build():
        lp = {prm.name: sp.Symbol(f"_q{i}", real=True) for i, prm in enumerate(law.parameters)}
        u, w, psi, _, _, mu, _, _ = _history_law(law, {**lp, "sigma": 1.0}, 1.0, ())
        return sp.lambdify([[u, w, *psi], *lp.values()], mu, "numpy")

    fn = per_law(law, ("history mu",), build)
    vals = [float(p[prm.name]) for prm in law.parameters]
    return lambda Y: fn(Y, *vals)


def _kernel_terms(terms: tuple[str, ...], quasidynamic: bool) -> tuple[str, ...]:
    """The block parameters of a history kernel, after the law's: σ₀, k, M (M > 0), the terms."""
    from landau.systems.springblock_terms import check_terms

    blk = check_terms(("eta", *terms)) if quasidynamic else check_terms(terms)
    return ("sigma", "k") + (() if quasidynamic else ("M",)) + blk


def history_kernel(law: FrictionLaw, terms: tuple[str, ...], quasidynamic: bool) -> CompiledField:
    """The history's field in y = (u, w, ψ…), compiled once per law, terms and kind (any parameter values).

    M > 0: the momentum equation (:func:`_momentum`).  M = 0: the force balance index-reduced and fed
    back, w' = −(R_y·f + λR)/R_w (:mod:`landau.verify.springblock.compiled_runs`).  The parameter
    vector (``names``): the law's parameters, :func:`_kernel_terms`, V_lp, then at M = 0 the feedback
    λ (V_ref + v) [1/s] as λ [1/m] and V_ref [m/s].
    """
    return per_law(law, ("load history", tuple(terms), bool(quasidynamic)),
                   lambda: _build_history_kernel(law, tuple(terms), bool(quasidynamic)))


def _build_history_kernel(law: FrictionLaw, terms: tuple[str, ...], quasidynamic: bool) -> CompiledField:
    from landau.verify.springblock.model import _law_key

    key = ("load history", _law_key(law), terms, quasidynamic)
    hit = cached_field(key)
    if hit is not None:
        return hit
    lp = {prm.name: sp.Symbol(f"_q{i}", real=True) for i, prm in enumerate(law.parameters)}
    blk = _kernel_terms(terms, quasidynamic)
    bs = {t: sp.Symbol(f"_{t}", positive=t in ("sigma", "k", "M")) for t in blk}
    sym = {**lp, **bs}
    if quasidynamic:
        lam, vref = sp.symbols("_lambda _V_ref", positive=True)
        w, ys, R, g, Vlp = _force_balance(law, sym, bs["k"], terms)
        states = [ys[0], w, *ys[1:]]
        # the feedback at the slip rate of the moment: λ (V_ref + v) per unit length (compiled_runs)
        field = [g[0], index_reduced(R, g, w, ys, lam * (vref + sp.exp(w))), *g[1:]]
        extra = [Vlp, lam, vref]
    else:
        states, field, Vlp = _momentum(law, sym, bs["k"], terms)
        extra = [Vlp]
    params = [*sym.values(), *extra]
    stray = set().union(*(e.free_symbols for e in field)) - set(states) - set(params)
    if stray:
        raise InputError(f"law {law.name!r}: undeclared symbol(s) {sorted(map(str, stray))} in the field")
    names = (*sym, "V_lp") + (("lambda", "V_ref") if quasidynamic else ())
    label = f"{law.name} (load history{', M = 0' if quasidynamic else ''})"
    return compile_field(key, states, field, params, names, label)


def _piece_vector(kern: CompiledField, law: FrictionLaw, p: Mapping[str, float], k: float, terms: tuple[str, ...],
                  quasidynamic: bool, V: float, V0: float, ell: float) -> np.ndarray:
    """The parameter vector of :func:`history_kernel` for the piece at load-point velocity V."""
    base = [p[prm.name] for prm in law.parameters]
    base += [k if t == "k" else p[t] for t in _kernel_terms(terms, quasidynamic)]
    # the feedback of the force balance: FEEDBACK per slip time ℓ/(V₀ + v) (compiled_runs)
    return kern.parameters(base + [V] + ([FEEDBACK / ell, V0] if quasidynamic else []))


def _piece_times(t_eval: np.ndarray | None, a: float, b: float, last: bool) -> np.ndarray | None:
    """The output times of the piece [a, b) ([a, b] for the last one), or None (the steps)."""
    if t_eval is None:
        return None
    return t_eval[(t_eval >= a) & ((t_eval <= b) if last else (t_eval < b))]


def _pieces(law, p, k, terms, h: LoadHistory, y, T, ends, t_end, rtol, scale, quasidynamic, t_eval=None):
    """Integrate the history piece by piece with the compiled Radau IIA (:func:`history_kernel`), each
    piece a fresh run from the state the last one left (exactly continuous: at M = 0 the force balance
    does not contain V_lp).  Returns the pieces' (t, Y, V) in (u, w, ψ…), the steps and f evaluations:
    at the accepted steps, or with ``t_eval`` at those times, each the end of a compiled run (the run
    goes on from it with the step it had reached)."""
    kern = history_kernel(law, terms, quasidynamic)
    out, nsteps, nfev = [], 0, 0
    for V, a, b in zip(h.velocities, T, ends, strict=True):
        if a >= t_end:
            break
        b = min(b, t_end)
        pv = _piece_vector(kern, law, p, k, terms, quasidynamic, V, h.velocities[0], float(scale[0]))
        te = _piece_times(t_eval, a, b, b >= t_end)
        stops = [b] if te is None else [*(x for x in te if a < x < b), b]
        h0, t0, at_t, at_y = None, a, [], []
        if te is not None and len(te) and te[0] == a:
            at_t.append(a)
            at_y.append(np.array(y, float))
        for t1 in stops:
            run = drive(kern, pv, y, t0, t1, rtol=rtol, atol=rtol * scale, max_steps=MAX_STEPS, h0=h0)
            if run.status != 0:
                why = STATUS[run.status] + (f" ({MAX_STEPS} step attempts)" if run.status == -2 else "")
                if quasidynamic and p["eta"] == 0 and run.status in (-1, -3):
                    why += ("; without inertia and damping (M = 0, eta = 0) the slip rate blows up in finite time "
                            "where the spring is softer than k_c (stick-slip): give M > 0 or eta > 0 to follow it")
                raise IntegratorError(f"load-point history{' (M = 0)' if quasidynamic else ''}, piece V = {V:g} "
                                      f"m/s from t = {a:g} s: {why} (state = u [m], ln v, ln phi...)",
                                      t=float(run.t), state=list(run.y))
            if te is None:
                out.append((run.rec_t[1:], run.rec_y[1:].T, np.full(len(run.rec_t) - 1, V)))
            elif t1 in te:
                at_t.append(t1)
                at_y.append(run.y)
            nsteps += int(run.counts[0])
            nfev += int(run.counts[2])
            y, t0, h0 = run.y, t1, (run.h if run.h > 0 else None)
        if te is not None:
            out.append((np.array(at_t), np.array(at_y).reshape(len(at_t), -1).T, np.full(len(at_t), V)))
    return out, nsteps, nfev


def default_end(h: LoadHistory, params: Mapping[str, float]) -> float:
    """The end of a history's run where none is given: the last piece's start plus as long as the
    longest earlier piece (a single piece: 100 L/V₀) [s]."""
    T = list(h.times)
    longest = max([b - a for a, b in zip(T, T[1:], strict=False)]
                  or [100 * params.get("L", 1e-6) / h.velocities[0]])
    return T[-1] + longest


def prepare_history(law: FrictionLaw, h: LoadHistory, k: float, params: Mapping[str, float] | None):
    """The checked inputs of a history's run: (p, terms, quasidynamic, y₀, scale) — the resolved law and
    block parameters (η = 0 added at M = 0 without it), the optional terms, whether M = 0, the state
    (u, w, ψ…) of steady sliding at the first velocity and the absolute scale of the tolerances."""
    from landau.systems.springblock_terms import check_steady_sliding, loads_block, steady_values
    from landau.systems.system import SpringBlock

    if not (math.isfinite(k) and k > 0):
        raise InputError(f"stiffness k must be a finite number > 0, got {k!r}")
    block = SpringBlock.for_params(law, params)      # with the optional terms given (eta, gamma_ld, alpha_ld)
    p = block.resolve(params)
    terms = block.terms
    quasidynamic = p["M"] == 0
    if not (p["M"] > 0 or (quasidynamic and p.get("eta", 0.0) >= 0)):
        raise InputError("a load-point history is simulated with a block mass M > 0, or at M = 0 with radiation "
                         "damping eta >= 0 (eta > 0 the quasi-dynamic, eta = 0 the quasi-static limit); got "
                         f"M = {p['M']!r}, eta = {p.get('eta', 0.0)!r}")
    if quasidynamic:
        p = {**p, "eta": float(p.get("eta", 0.0))}   # the force balance's damping, 0 in the quasi-static limit
    phi0, mu0 = _steady_state(law, h.velocities[0], p)
    if quasidynamic and p["eta"] == 0:
        for V in sorted({V for V in h.velocities if V > 0}):
            _check_direct_effect(law, V, p)
    if loads_block(terms):   # steady sliding at every sliding velocity of the history needs 1 - gamma mu_ss > 0
        for V in sorted({V for V in h.velocities if V > 0}):
            check_steady_sliding(law, _steady_state(law, V, p)[1], p, V)
    F0 = steady_values(terms, p["sigma"], mu0, h.velocities[0], p)[0]   # spring force k u at steady sliding
    y = np.array([F0 / k, math.log(h.velocities[0]), *(math.log(x) for x in phi0)])
    scale = np.array([p.get("L", 1e-6)] + [1.0] * (len(y) - 1))
    return p, terms, quasidynamic, y, scale


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
        Increasing times in [t₀, ``t_end``] to give the series at (each the end of a compiled run,
        which goes on from there with the step it had reached); default: the accepted steps.
    Returns
    -------
    Simulation
        ``state_names`` = (V, v, mu, states…): the load-point velocity [m/s], the slip rate
        [m/s], μ(v, φ) and the states, then the spring force F [N] with ``eta`` or ``gamma_ld`` and
        the normal load sigma [N] with ``gamma_ld``, then x_lp and slip [m]; sampled at the
        integrator's steps; status ``finished``.

    Raises
    ------
    InputError
        A bad history, stiffness or end time; M < 0, η < 0, or M = 0 and η = 0 with a law whose μ
        does not grow with v at a sliding velocity of the history.
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
    h = parse_history(history) if isinstance(history, str) else history
    p, terms, quasidynamic, y, scale = prepare_history(law, h, k, params)
    T = list(h.times)
    if t_end is None:
        t_end = default_end(h, p)
    if not (math.isfinite(t_end) and t_end > T[-1]):
        raise InputError(f"the end time must be after the last piece's start t = {T[-1]:g} s, got {t_end!r}")
    appended = False
    if t_eval is not None:
        t_eval = np.asarray(t_eval, float).reshape(-1)
        if not (len(t_eval) and np.all(np.isfinite(t_eval)) and np.all(np.diff(t_eval) > 0)
                and t_eval[0] >= T[0] and t_eval[-1] <= t_end):
            raise InputError(f"t_eval must be increasing finite times in [{T[0]:g}, {t_end:g}] s")
        appended = bool(t_eval[-1] < t_end)   # the end of the run, for the final state
        if appended:
            t_eval = np.r_[t_eval, t_end]
    from landau.systems.springblock_terms import load_slope, loads_block

    mun = _mu_function(law, p, k, terms)
    ts, ys, vs = [np.array([T[0]])], [y[:, None]], [np.array([h.velocities[0]])]
    if t_eval is not None:   # the series at the times asked for only
        ts, ys, vs = [], [], []
    ends = T[1:] + [t_end]
    pieces, nsteps, nfev = _pieces(law, p, k, terms, h, y, T, ends, t_end, rtol, scale, quasidynamic, t_eval)
    for tt, Y, Vl in pieces:
        ts.append(tt)
        ys.append(Y)
        vs.append(Vl)
    t = np.concatenate(ts)
    Y = np.concatenate(ys, axis=1)
    Vl = np.concatenate(vs)
    if len(t) > max_points and t_eval is None:
        keep = np.unique(np.linspace(0, len(t) - 1, max_points).astype(int))
        t, Y, Vl = t[keep], Y[:, keep], Vl[keep]
    mu = np.broadcast_to(np.asarray(mun(Y), float), t.shape)
    out = np.vstack([Vl, np.exp(Y[1]), mu, np.exp(Y[2:])])
    names = ("V", "v", "mu") + tuple(s.name for s in law.states)
    if terms:   # the spring force, and the normal load that follows it (loads affine in F)
        out = np.vstack([out, k * Y[0]])
        names += ("F",)
        if loads_block(terms):
            out = np.vstack([out, float(p["sigma"]) + load_slope(terms, p) * k * Y[0]])
            names += ("sigma",)
    # the load-point displacement x_lp = ∫V dt and the slip x − x(t₀) = x_lp − (u − u₀), from t₀
    out = np.vstack([out, h.displacement(t), h.displacement(t) - (Y[0] - y[0])])
    names += ("x_lp", "slip")
    regimes = tuple((a, min(b, t_end), "hold" if V == 0 else "slide")
                    for V, a, b in zip(h.velocities, T, ends, strict=True) if a < t_end)
    final, t_final = out[:, -1].copy(), float(t[-1])
    if t_eval is not None and appended:
        t, out = t[:-1], out[:, :-1]
    return Simulation("spring-block (load-point history)", t, out, EventLog(), Status.FINISHED,
                      Status.FINISHED.advice, t_final, final, nsteps, nfev, None, names, regimes)


def peak_after(sim: Simulation, t_from: float) -> float:
    """The largest friction coefficient μ of ``sim`` at t ≥ ``t_from``, read at the recorded points
    (a peak between two of them is read low, ~1e-6 at rtol 1e-9: :func:`landau.lab.measure.locate_peak`
    finds it as a root of dμ/dt on the dense solution)."""
    i = list(sim.state_names).index("mu")
    keep = sim.t >= t_from
    if not keep.any():
        raise InputError(f"no recorded point at t >= {t_from:g}")
    return float(sim.y[i, keep].max())
