"""The quasi-dynamic spring–block (M = 0, η > 0): the force balance solved for the slip rate.

Without inertia the momentum equation of the spring–block with radiation damping (Rice 1993;
:mod:`landau.systems.springblock_terms`) is algebraic:

    0 = k(Vt − x) − σ(x, t) μ(v, φ) − η v,        σ = σ_ss − γ_LD k X  (σ_ss without γ_LD),

and determines the slip rate v = ẋ at every instant.  With η > 0 and ∂μ/∂v ≥ 0 (a direct effect
a > 0) its left-hand side decreases strictly in v, so the root is unique; it is found at every
evaluation of the right-hand side by a safeguarded Newton iteration in w = ln(v/V) (a bracket kept
and bisected where a Newton step would leave it).  The remaining ordinary differential equations,
in the scaled variables of :mod:`landau.verify.springblock.model` (ξ = X/ℓ, ψᵢ = ln(φᵢ/φᵢ,₀),
τ = tV/ℓ, X = x − x₀(t) the slip from steady sliding),

    ξ' = e^w − 1,        ψᵢ' = (ℓ/V) rateᵢ(v, φ)/φᵢ,

are integrated together with w by the compiled Radau IIA of :mod:`landau.verify.hybrid.radau`: the
force balance R = 0 differentiated once and fed back, w' = −(R_y·y' + λR)/R_w, makes (ξ, w, ψ…) an
ODE whose solutions include the DAE's and whose manifold R = 0 attracts
(:mod:`landau.verify.springblock.compiled_runs` gives the reasons for this form and for Radau IIA
over DOP853).  Its field and exact Jacobian are generated from the same symbolic residual and
field as the cell's lambdified functions (:func:`_expressions`) and compiled once per law and set
of terms (:func:`cell_kernel`, any parameter values); the Newton solve above gives the starting
slip rate, and the implicit-function Jacobian f_y − f_w R_y/R_w of the reduced system in (ξ, ψ…)
gives the critical mode at steady sliding.  This is the cell of QDYN and of the SEAS benchmark
BP1 (Erickson et al. 2020).

:func:`simulate_quasidynamic` returns a :class:`~landau.verify.hybrid.result.Simulation` with
the series X [m], v [m/s], μ and the states; the cell's periodic orbits (the first return to the
section v = V) and the bistability probe are in :mod:`landau.verify.springblock.quasidynamic_orbits`.

References
----------
Rice, J. R. (1993), Spatio-temporal complexity of slip on a fault, J. Geophys. Res. 98(B6), 9885–9907.
Erickson, B. A. et al. (2020), The community code verification exercise for simulating sequences of
earthquakes and aseismic slip (SEAS), Seismol. Res. Lett. 91(2A), 874–890.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from functools import cached_property
from typing import Any, Callable, Mapping

import numpy as np
import sympy as sp

from landau.errors import InputError, IntegratorError
from landau.laws.law import FrictionLaw
from landau.laws.law import v as v_slip
from landau.systems.springblock_terms import (
    Balance,
    check_terms,
    mechanical_rhs,
    parameters,
    state_scales,
    states,
    steady_values,
)
from landau.verify.hybrid.log import Event, EventLog
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
from landau.verify.springblock.forcebalance import W_BOUND, solve_log_rate


@dataclass(frozen=True)
class QuasiDynamicCell:
    """The spring–block at M = 0 with η > 0, for one law at driving velocity V [m/s] and stiffness k [N/m].

    Build it with :meth:`build`; ``params`` are resolved (law parameters, sigma, eta, gamma_ld,
    alpha_ld).  ``ell`` is the length unit of ξ (the law's L if it has one).
    """

    law: FrictionLaw
    V: float
    k: float
    params: Mapping[str, float]
    ell: float
    phi0: tuple[float, ...]
    mu0: float
    sigma_ss: float
    terms: tuple[str, ...]
    _fn: Callable[..., Any] = field(repr=False, compare=False)

    @classmethod
    def build(cls, law: FrictionLaw, V: float, k: float, params: Mapping[str, float] | None = None,
              length_scale: float | None = None) -> "QuasiDynamicCell":
        """The quasi-dynamic cell; InputError unless M = 0 and η > 0, and where μ decreases in v there."""
        from landau.systems.system import SpringBlock
        from landau.verify.springblock.model import _steady_state

        block = SpringBlock.for_params(law, params)
        p = block.resolve(params)
        if not (np.isfinite(V) and V > 0):
            raise InputError(f"driving velocity V must be > 0, got {V!r}")
        if not (np.isfinite(k) and k > 0):
            raise InputError(f"stiffness k must be > 0, got {k!r}")
        if p["M"] != 0:
            raise InputError(f"the quasi-dynamic cell has M = 0, got M = {p['M']!r} (M > 0: the compiled model)")
        if not p.get("eta", 0.0) > 0:
            raise InputError("simulating M = 0 needs radiation damping eta > 0 (--param eta=...), the "
                             "quasi-dynamic limit; M = 0 with eta = 0 is the quasi-static limit, whose slip rate "
                             "blows up in finite time past an instability (`landau derive` gives its Hopf point)")
        ell = float(length_scale if length_scale is not None else p.get("L", 1e-6))
        phi0 = tuple(_steady_state(law, V, p))
        vals = {prm.symbol: p[prm.name] for prm in law.parameters}
        mu0 = float(law.mu.subs({v_slip: V, **dict(zip(law.states, phi0, strict=True)), **vals}))
        if not math.isfinite(mu0):
            raise InputError(f"law {law.name!r}: friction coefficient not finite at steady sliding V = {V!r}")
        if block.terms:
            block.argvals(float(V), p)        # no steady sliding (gamma_ld): a named error
        sigma_ss = steady_values(block.terms, p["sigma"], mu0, V, p)[1]   # the terms' steady normal load
        fn = _field(law, block.terms, p, float(V), float(k), ell, phi0, mu0, sigma_ss)
        cell = cls(law, float(V), float(k), dict(p), ell, phi0, mu0, sigma_ss, block.terms, fn)
        _, Rw, *_ = fn(0.0, *([0.0] * cell.n))
        if not Rw < 0:
            raise InputError(f"law {law.name!r} at V = {V:g} m/s: the friction force decreases with the slip "
                             "rate faster than eta*v grows (dmu/dv + eta/sigma <= 0), so the quasi-dynamic "
                             "force balance has no unique slip rate")
        return cell

    @property
    def n(self) -> int:
        """Number of integrated states (ξ, the ψᵢ and the terms' states)."""
        return 1 + len(self.law.states) + len(states(self.terms))

    @cached_property
    def state_scales(self) -> dict[str, float]:
        """The unit of each term state's scaled variable (its excess over steady sliding is S π)."""
        return {n: float(e) for n, e in _scales(_block_terms(self.terms), self.params, self.V, self.k, self.mu0,
                                                self.sigma_ss).items()}

    @property
    def time_unit(self) -> float:
        """Seconds per unit of the scaled time τ = tV/ℓ."""
        return self.ell / self.V

    @property
    def kernel(self) -> CompiledField:
        """The compiled cell in (ξ, w, ψ…) (:func:`cell_kernel`)."""
        return cell_kernel(self.law, self.terms)

    @cached_property
    def kernel_p(self) -> np.ndarray:
        """The parameter vector of :attr:`kernel` (the feedback λ = :data:`FEEDBACK`)."""
        blk = _block_terms(self.terms)
        base = [self.params[prm.name] for prm in self.law.parameters]
        base += [self.V, self.k, self.ell, self.mu0, self.sigma_ss, *self.phi0]
        base += [*(self.params[name] for name, *_ in parameters(blk)), FEEDBACK]
        return self.kernel.parameters(base)

    def slip_rate(self, y, w0: float = 0.0) -> float:
        """w = ln(v/V) solving the force balance at the scaled state y = (ξ, ψ…) (safeguarded Newton,
        :func:`~landau.verify.springblock.forcebalance.solve_log_rate`)."""
        return solve_log_rate(self._fn, y, w0)

    def rhs(self, y, w0: float = 0.0) -> tuple[np.ndarray, float]:
        """(dy/dτ, w) at the scaled state ``y``."""
        w = self.slip_rate(y, w0)
        out = self._fn(w, *[float(q) for q in y])
        return np.asarray(out[2], float), w

    def jacobian(self, y, w: float) -> np.ndarray:
        """d(dy/dτ)/dy with w = w(y) from the force balance (implicit-function derivative)."""
        _, Rw, _, Ry, fw, fy = self._fn(w, *[float(q) for q in y])
        return np.asarray(fy, float) - np.outer(np.asarray(fw, float), np.asarray(Ry, float)) / Rw

    def mu(self, w, y) -> np.ndarray:
        """μ(v, φ) at w = ln(v/V) and the scaled states (arrays broadcast)."""
        vv = self.V * np.exp(np.asarray(w, float))
        phis = [p0 * np.exp(np.asarray(y[1 + i], float)) for i, p0 in enumerate(self.phi0)]
        return np.broadcast_to(np.asarray(self._mu_fn(vv, *phis), float), vv.shape)

    @cached_property
    def _mu_fn(self) -> Callable[..., Any]:
        """μ(v, φ…) with the law's parameters substituted (numpy, lambdified once per cell)."""
        vals = {prm.symbol: self.params[prm.name] for prm in self.law.parameters}
        return sp.lambdify([v_slip, *self.law.states], self.law.mu.subs(vals), "numpy")

    def critical_mode(self) -> tuple[complex, np.ndarray]:
        """Eigenvalue with the largest real part of the Jacobian at steady sliding (per unit τ) and its
        eigenvector with ξ-component 1."""
        lam, vec = np.linalg.eig(self.jacobian(np.zeros(self.n), 0.0))
        i = int(np.argmax(lam.real + 1e-12 * np.abs(lam.imag)))
        if abs(vec[0, i]) == 0:
            raise InputError("the critical mode has no slip component")
        return complex(lam[i]), vec[:, i] / vec[0, i]

    def perturbed(self, amplitude: float) -> np.ndarray:
        """Steady sliding displaced along the critical mode so that X = ``amplitude`` [m]."""
        _, vec = self.critical_mode()
        return (amplitude / self.ell) * vec.real

    def from_physical(self, X: float, phis, extra: Mapping[str, float] | None = None) -> np.ndarray:
        """The scaled state of slip X [m], states φ and (``extra``, default 0) the term states' excesses over
        steady sliding by name (the slip rate follows from the force balance)."""
        if any(not ph > 0 for ph in phis):
            raise InputError("the states must be > 0 for the log variables")
        ex = [(extra or {}).get(name, 0.0) / S for name, S in self.state_scales.items()]
        return np.array([X / self.ell, *(math.log(ph / p0) for ph, p0 in zip(phis, self.phi0, strict=True)), *ex])


def _expressions(law, terms, p, V, k, ell, phi0, mu0, sigma_ss):
    """(w, ys, R, f): the force residual R(w, ξ, ψ…) ÷ σ_ss and the field f of ys = (ξ, ψ…), from the
    law and the terms.  The parameters (``p`` by name, V, k, ℓ, φ₀, μ₀, σ_ss) are numbers (the cell's
    lambdified functions) or sympy symbols (its compiled kernel, :func:`cell_kernel`): both are built
    from these expressions."""
    ns = len(law.states)
    terms = check_terms(("eta", *terms))
    tstates = states(terms)
    w, xi = sp.symbols("w_ xi_", real=True)
    psi = sp.symbols(f"psi_0:{ns}", real=True)
    pis = sp.symbols(f"pi_0:{len(tstates)}", real=True)
    vals = {prm.symbol: p[prm.name] for prm in law.parameters}
    vv = V * sp.exp(w)
    phis = [p0 * sp.exp(q) for p0, q in zip(phi0, psi, strict=True)]
    sub = {v_slip: vv, **dict(zip(law.states, phis, strict=True))}

    def tidy(e):
        return sp.expand_log(e.subs(vals).xreplace(sub), force=True)

    # the force balance and the state rates of every term, from their one declaration
    # (springblock_terms.mechanical_rhs) in X = ℓξ, u = V(e^w − 1); η, which M = 0 needs, always built in;
    # each term state (pore pressure, temperature) as S π, S its scale at steady sliding
    scales = _scales(terms, p, V, k, mu0, sigma_ss)
    extra = {st.symbol.name: scales[st.symbol.name] * q for st, q in zip(tstates, pis, strict=True)}
    force, rates = mechanical_rhs(law, terms, ell * xi, V * (sp.exp(w) - 1), {s: s for s in (v_slip, *law.states)},
                                  tuple(phi0), k, p.get("sigma", sigma_ss), V, mu0=mu0, sigma_ss=sigma_ss,
                                  symbol={name: p[name] for name, *_ in parameters(terms)},
                                  extra=extra if tstates else None)
    R = tidy(force) / sigma_ss
    f = [sp.exp(w) - 1]
    for rate, ph in zip(rates[:ns], phis, strict=True):
        f.append((ell / V) * sp.expand(tidy(rate) / ph))
    for rate, st in zip(rates[ns:], tstates, strict=True):
        f.append((ell / V) * sp.expand(tidy(rate) / scales[st.symbol.name]))
    return w, [xi, *psi, *pis], R, f


def _scales(terms, p, V, k, mu0, sigma_ss) -> dict:
    """Each term state's scale at steady sliding (numbers, or the kernel's symbols)."""
    if not states(terms):
        return {}
    sym = {name: p[name] for name, *_ in parameters(terms)}
    b = Balance(v=V, phis=(), F=sp.Integer(0), F_dot=sp.Integer(0), V_lp=V, k=k, sigma0=sigma_ss, sigma=sigma_ss,
                mu=mu0, symbol=sym)
    return state_scales(terms, b)


def _stray(law, exprs, known) -> None:
    stray = set().union(*(sp.sympify(e).free_symbols for e in exprs)) - set(known)
    if stray:
        raise InputError(f"law {law.name!r}: undeclared symbol(s) {sorted(map(str, stray))} in the field")


def _field(law, terms, p, V, k, ell, phi0, mu0, sigma_ss):
    """fn(w, ξ, ψ…) -> (R, R_w, f, R_y, f_w, f_y): the force residual (÷ σ_ss) and the field, by lambdify."""
    w, ys, R, f = _expressions(law, terms, p, V, k, ell, phi0, mu0, sigma_ss)
    Rw = sp.diff(R, w)
    Ry = [sp.diff(R, q) for q in ys]
    fw = [sp.diff(e, w) for e in f]
    fy = [[sp.diff(e, q) for q in ys] for e in f]
    _stray(law, [R, *f], [w, *ys])
    return sp.lambdify([w, *ys], (R, Rw, f, Ry, fw, fy), "math")


def _block_terms(terms) -> tuple[str, ...]:
    """The block parameters of the compiled kernels: η always (M = 0 needs it), and the terms built in."""
    return check_terms(("eta", *terms))


def cell_kernel(law: FrictionLaw, terms: tuple[str, ...] = ()) -> CompiledField:
    """The cell in (ξ, w, ψ…) with the force balance index-reduced and fed back
    (:mod:`landau.verify.springblock.compiled_runs`), compiled once per law and terms; its parameter
    vector (``names``): the law's parameters, V, k, ℓ, μ₀, σ_ss, φ₀…, η, [γ_LD, α_LD], λ (the feedback
    is λ (1 + v/V) per unit τ)."""
    return per_law(law, ("quasi-dynamic cell", tuple(terms)), lambda: _build_cell_kernel(law, tuple(terms)))


def _build_cell_kernel(law: FrictionLaw, terms: tuple[str, ...]) -> CompiledField:
    from landau.verify.springblock.model import _law_key

    key = ("quasi-dynamic cell", _law_key(law), terms)
    hit = cached_field(key)
    if hit is not None:
        return hit
    blk = _block_terms(terms)
    lp = {prm.name: sp.Symbol(f"_q{i}", real=True) for i, prm in enumerate(law.parameters)}
    V, k, ell, mu0, sig = sp.symbols("_V _k _ell _mu0 _sigma_ss", positive=True)
    phi0 = [sp.Symbol(f"_phi0_{i}", positive=True) for i in range(len(law.states))]
    tsyms = {name: sp.Symbol(f"_{name}", real=True) for name, *_ in parameters(blk)}
    lam = sp.Symbol("_lambda", positive=True)
    w, ys, R, f = _expressions(law, terms, {**lp, **tsyms}, V, k, ell, phi0, mu0, sig)
    # the feedback at the slip rate of the moment, λ (1 + v/V) per unit τ (compiled_runs)
    field = [f[0], index_reduced(R, f, w, ys, lam * (1 + sp.exp(w))), *f[1:]]
    params = [*lp.values(), V, k, ell, mu0, sig, *phi0, *tsyms.values(), lam]
    _stray(law, field, [w, *ys, *params])
    names = (*lp, "V", "k", "ell", "mu0", "sigma_ss", *(f"phi0_{i}" for i in range(len(phi0))), *tsyms, "lambda")
    return compile_field(key, [ys[0], w, *ys[1:]], field, params, names, f"{law.name} (quasi-dynamic cell)")


def simulate_quasidynamic(law: FrictionLaw, V: float, k: float,
                          params: Mapping[str, float] | QuasiDynamicCell | None = None,
                          t_end: float = 20.0, y0=None, *, rtol: float = 1e-9, max_steps: int = 1_000_000,
                          max_points: int = 200_000, sections: bool = False) -> Simulation:
    """Integrate the quasi-dynamic spring–block (module docstring) from ``y0`` over [0, ``t_end``] s.

    Parameters
    ----------
    law : FrictionLaw
        The rate-and-state law μ(v, φ), dφᵢ/dt.
    V, k : float
        Driving velocity [m/s] and stiffness [N/m].
    params : mapping or QuasiDynamicCell, optional
        Law and block parameters with M = 0 and eta > 0 (and gamma_ld, alpha_ld if wanted), or a
        cell already built (its V and k then hold).
    t_end : float
        End of the run [s].
    y0 : array_like, optional
        Initial scaled state (ξ, ψ…) (:meth:`QuasiDynamicCell.from_physical`); default: steady
        sliding displaced by X = 0.01 ℓ along the critical mode.
    rtol : float
        Relative and absolute tolerance of the Radau IIA (the scaled variables are O(1)).
    max_steps : int
        Budget of step attempts (accepted and rejected, ≥ 1); at it the run ends with status
        ``max-steps`` and the series up to there.
    max_points : int
        Bound on the recorded points (evenly thinned past it).
    sections : bool
        Log the upward crossings of v = V (the minima of X) as ``"section"`` events.

    Returns
    -------
    Simulation
        ``state_names`` = (X, v, mu, states…) in physical units, sampled at the integrator's steps.

    Raises
    ------
    InputError
        M ≠ 0, η ≤ 0, bad V, k, t_end or y0.
    IntegratorError
        The integrator failed (with the time and the state).
    """
    cell = params if isinstance(params, QuasiDynamicCell) else QuasiDynamicCell.build(law, V, k, params)
    if not (math.isfinite(t_end) and t_end > 0):
        raise InputError(f"the end time must be a finite number > 0, got {t_end!r}")
    if not (0 < rtol < 1):
        raise InputError(f"rtol must be in (0, 1), got {rtol!r}")
    y = cell.perturbed(0.01 * cell.ell) if y0 is None else np.asarray(y0, float)
    if y.shape != (cell.n,) or not np.all(np.isfinite(y)):
        raise InputError(f"initial state must be {cell.n} finite numbers (xi, psi...), got {y0!r}")
    if not int(max_steps) >= 1:
        raise InputError(f"max_steps must be >= 1, got {max_steps!r}")
    tu = cell.time_unit
    z0 = np.r_[y[0], cell.slip_rate(y), y[1:]]
    run = drive(cell.kernel, cell.kernel_p, z0, 0.0, t_end / tu, rtol=rtol, atol=np.full(cell.n + 1, rtol),
                max_steps=int(max_steps), ev_idx=1 if sections else -1)
    if run.status in (-1, -3):
        raise IntegratorError(f"quasi-dynamic spring-block[{law.name}]: {STATUS[run.status]} "
                              "(state = xi, w, psi...)", t=float(run.t * tu), state=list(run.y))
    status = Status.MAX_STEPS if run.status == -2 else Status.FINISHED
    log = EventLog()
    for tc, zc in zip(run.ev_t[run.ev_dir > 0], run.ev_y[run.ev_dir > 0], strict=True):
        row = _physical(cell, np.array([tc * tu]), np.delete(zc, 1)[:, None], zc[1:2])[:, 0]
        log.append(Event(float(tc * tu), row, "crossing", "slip", "slip", "section", row, "up"))
    t = run.rec_t * tu
    Z = run.rec_y.T
    if len(t) > max_points:
        keep = np.unique(np.r_[np.linspace(0, len(t) - 1, max_points).astype(int), len(t) - 1])
        t, Z = t[keep], Z[:, keep]
    out = _physical(cell, t, np.delete(Z, 1, axis=0), Z[1])
    names = ("X", "v", "mu") + tuple(s.name for s in law.states) + tuple(cell.state_scales)
    msg = status.advice
    if status is Status.MAX_STEPS:
        msg = (f"stopped at the step limit ({max_steps} step attempts) at t = {t[-1]:.6g} s before the end "
               f"t = {t_end:.6g} s: {status.advice}")
    return Simulation("spring-block (quasi-dynamic, M = 0)", t, out, log, status, msg, float(t[-1]),
                      out[:, -1].copy(), int(run.counts[0]), int(run.counts[2]), None, names)


def _physical(cell: QuasiDynamicCell, t, Y, W) -> np.ndarray:
    """Rows X [m], v [m/s], μ, φᵢ from scaled states and w."""
    X = Y[0] * cell.ell
    v = cell.V * np.exp(W)
    mu = cell.mu(W, Y)
    phis = [p0 * np.exp(Y[1 + i]) for i, p0 in enumerate(cell.phi0)]
    ns = len(cell.phi0)
    extra = [S * Y[1 + ns + j] for j, S in enumerate(cell.state_scales.values())]   # the term states' excesses
    return np.vstack([X, v, mu, *phis, *extra])


__all__ = ["W_BOUND", "QuasiDynamicCell", "simulate_quasidynamic"]
