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

are integrated by scipy's Radau IIA with the exact Jacobian (the implicit-function derivative
dw/dy = −R_y/R_w of the force residual R joins the partial derivatives).  This is the cell of
QDYN and of the SEAS benchmark BP1 (Erickson et al. 2020).

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
from typing import Any, Callable, Mapping

import numpy as np
import sympy as sp

from landau.errors import InputError, IntegratorError
from landau.laws.law import FrictionLaw
from landau.laws.law import v as v_slip
from landau.verify.hybrid.log import Event, EventLog
from landau.verify.hybrid.result import Simulation, Status
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
        g = p.get("gamma_ld", 0.0) if "gamma_ld" in block.terms else 0.0
        sigma_ss = (p["sigma"] + g * p["eta"] * V) / (1.0 - g * mu0)
        fn = _field(law, block.terms, p, float(V), float(k), ell, phi0, mu0, sigma_ss)
        cell = cls(law, float(V), float(k), dict(p), ell, phi0, mu0, sigma_ss, block.terms, fn)
        _, Rw, *_ = fn(0.0, *([0.0] * (1 + len(phi0))))
        if not Rw < 0:
            raise InputError(f"law {law.name!r} at V = {V:g} m/s: the friction force decreases with the slip "
                             "rate faster than eta*v grows (dmu/dv + eta/sigma <= 0), so the quasi-dynamic "
                             "force balance has no unique slip rate")
        return cell

    @property
    def n(self) -> int:
        """Number of integrated states (ξ and the ψᵢ)."""
        return 1 + len(self.law.states)

    @property
    def time_unit(self) -> float:
        """Seconds per unit of the scaled time τ = tV/ℓ."""
        return self.ell / self.V

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
        vals = {prm.symbol: self.params[prm.name] for prm in self.law.parameters}
        f = sp.lambdify([v_slip, *self.law.states], self.law.mu.subs(vals), "numpy")
        return np.broadcast_to(np.asarray(f(vv, *phis), float), vv.shape)

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

    def from_physical(self, X: float, phis) -> np.ndarray:
        """The scaled state of slip X [m] and states φ (the slip rate follows from the force balance)."""
        if any(not ph > 0 for ph in phis):
            raise InputError("the states must be > 0 for the log variables")
        return np.array([X / self.ell, *(math.log(ph / p0) for ph, p0 in zip(phis, self.phi0, strict=True))])


def _field(law, terms, p, V, k, ell, phi0, mu0, sigma_ss):
    """fn(w, ξ, ψ…) -> (R, R_w, f, R_y, f_w, f_y): the force residual (÷ σ_ss) and the field, by lambdify."""
    ns = len(law.states)
    w, xi = sp.symbols("w_ xi_", real=True)
    psi = sp.symbols(f"psi_0:{ns}", real=True)
    vals = {prm.symbol: p[prm.name] for prm in law.parameters}
    vv = V * sp.exp(w)
    phis = [p0 * sp.exp(q) for p0, q in zip(phi0, psi, strict=True)]
    sub = {v_slip: vv, **dict(zip(law.states, phis, strict=True))}

    def tidy(e):
        return sp.expand_log(e.subs(vals).xreplace(sub), force=True)

    mu = tidy(law.mu)
    eta = p["eta"]
    g = p.get("gamma_ld", 0.0) if "gamma_ld" in terms else 0.0
    X = ell * xi
    sig = sigma_ss - g * k * X
    R = (-k * X - (sig * mu - sigma_ss * mu0) - eta * V * (sp.exp(w) - 1)) / sigma_ss
    f = [sp.exp(w) - 1]
    for i, (r, ph) in enumerate(zip(law.rates, phis, strict=True)):
        rate = tidy(r)
        if i == 0 and "alpha_ld" in terms and g != 0:
            sig_dot = -g * k * V * (sp.exp(w) - 1)
            rate = rate - p["alpha_ld"] * sig_dot / (sig * tidy(sp.diff(law.mu, law.states[0])))
        f.append((ell / V) * sp.expand(rate / ph))
    ys = [xi, *psi]
    Rw = sp.diff(R, w)
    Ry = [sp.diff(R, q) for q in ys]
    fw = [sp.diff(e, w) for e in f]
    fy = [[sp.diff(e, q) for q in ys] for e in f]
    stray = set().union(*(sp.sympify(e).free_symbols for e in [R, *f])) - {w, *ys}
    if stray:
        raise InputError(f"law {law.name!r}: undeclared symbol(s) {sorted(map(str, stray))} in the field")
    return sp.lambdify([w, *ys], (R, Rw, f, Ry, fw, fy), "math")


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
        Step budget; at it the run ends with status ``max-steps`` and the series up to there.
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
    from scipy.integrate import Radau

    cell = params if isinstance(params, QuasiDynamicCell) else QuasiDynamicCell.build(law, V, k, params)
    if not (math.isfinite(t_end) and t_end > 0):
        raise InputError(f"the end time must be a finite number > 0, got {t_end!r}")
    if not (0 < rtol < 1):
        raise InputError(f"rtol must be in (0, 1), got {rtol!r}")
    y = cell.perturbed(0.01 * cell.ell) if y0 is None else np.asarray(y0, float)
    if y.shape != (cell.n,) or not np.all(np.isfinite(y)):
        raise InputError(f"initial state must be {cell.n} finite numbers (xi, psi...), got {y0!r}")
    tu = cell.time_unit
    w_start = cell.slip_rate(y)
    last_w = [w_start]

    def f(_t, yy):
        out, last_w[0] = cell.rhs(yy, last_w[0])
        return out

    def jac(_t, yy):
        w = cell.slip_rate(yy, last_w[0])
        return cell.jacobian(yy, w)

    solver = Radau(f, 0.0, y, t_end / tu, rtol=rtol, atol=rtol, jac=jac)
    ts, ys, ws = [0.0], [y.copy()], [w_start]
    log = EventLog()
    status, steps = Status.FINISHED, 0
    while solver.status == "running":
        if steps >= max_steps:
            status = Status.MAX_STEPS
            break
        t_prev, w_prev = ts[-1], ws[-1]
        msg = solver.step()
        steps += 1
        if solver.status == "failed" or not np.all(np.isfinite(solver.y)):
            raise IntegratorError(f"quasi-dynamic spring-block[{law.name}]: {msg or 'non-finite state'} "
                                  "(state = xi, psi...)", t=float(solver.t * tu), state=list(solver.y))
        wn = cell.slip_rate(solver.y, w_prev)
        if sections and w_prev < 0 <= wn:
            from scipy.optimize import brentq

            dense = solver.dense_output()
            tc = brentq(lambda s, d=dense: cell.slip_rate(d(s), 0.0), t_prev, solver.t, xtol=1e-14 * max(1.0, solver.t))
            yc = dense(tc)
            row = _physical(cell, np.array([tc]), yc[:, None], np.array([0.0]))[:, 0]
            log.append(Event(float(tc * tu), row, "crossing", "slip", "slip", "section", row, "up"))
        ts.append(float(solver.t))
        ys.append(solver.y.copy())
        ws.append(wn)
    t = np.asarray(ts) * tu
    Y = np.array(ys).T
    W = np.asarray(ws)
    if len(t) > max_points:
        keep = np.unique(np.r_[np.linspace(0, len(t) - 1, max_points).astype(int), len(t) - 1])
        t, Y, W = t[keep], Y[:, keep], W[keep]
    out = _physical(cell, t, Y, W)
    names = ("X", "v", "mu") + tuple(s.name for s in law.states)
    msg = status.advice
    if status is Status.MAX_STEPS:
        msg = (f"stopped at the step limit ({max_steps} steps) at t = {t[-1]:.6g} s before the end "
               f"t = {t_end:.6g} s: {status.advice}")
    return Simulation("spring-block (quasi-dynamic, M = 0)", t, out, log, status, msg, float(t[-1]),
                      out[:, -1].copy(), steps, int(solver.nfev), None, names)


def _physical(cell: QuasiDynamicCell, t, Y, W) -> np.ndarray:
    """Rows X [m], v [m/s], μ, φᵢ from scaled states and w."""
    X = Y[0] * cell.ell
    v = cell.V * np.exp(W)
    mu = cell.mu(W, Y)
    phis = [p0 * np.exp(Y[1 + i]) for i, p0 in enumerate(cell.phi0)]
    return np.vstack([X, v, mu, *phis])


__all__ = ["W_BOUND", "QuasiDynamicCell", "simulate_quasidynamic"]
