"""The quasi-static spring–slider of the laboratory, with its forward sensitivities, compiled.

Per unit normal stress (the lab's convention), with the stiffness k′ = k/σ (1/m), the load point
driven at V_lp(t) and any rate-and-state law μ(v, φ), dφᵢ/dt = Rᵢ(v, φ) of :mod:`landau.laws`:

    dμ/dt = k′ (V_lp(t) − v),      μ = μ(v, φ),      dφᵢ/dt = Rᵢ(v, φ)

(Dieterich 1979; Ruina 1983; the model of rsfmodel and PyRSF).  The slip rate follows from the
friction law in one of two exact forms:

* where μ is linear in ln v (the Dieterich and Ruina laws and every law of that family,
  μ = B(φ) + A ln v), ln v = (μ − B(φ))/A in closed form, and the states are (μ, φ);
* otherwise the constraint is differentiated in time (μ_v v̇ + Σ μ_φᵢ φ̇ᵢ = k′(V_lp − v)), and the
  states are (w = ln v, φ) with ẇ = [k′(V_lp − v) − Σ μ_φᵢ Rᵢ] / (v μ_v); μ is then μ(v, φ).

The forward sensitivities S = ∂y/∂p of every fitted parameter p obey the variational equations
Ṡ = (∂f/∂y) S + ∂f/∂p (Hairer, Nørsett & Wanner 1993, Sec. I.14), whose Jacobians are sympy's
derivatives of the law's expressions.  State and sensitivities are one vector field, generated
and compiled by :mod:`landau.codegen.kernels` and integrated by the compiled DOP853 of
:mod:`landau.verify.hybrid.dop853` over each interval of constant load-point velocity (the
velocity of a sample holds until the next sample, as in rsfmodel), the samples read on its
7th-order dense output.  The run starts at steady sliding at V_lp(t₀): φ = φ_ss(V₀), μ = μ_ss(V₀),
with the sensitivities of that steady state from the implicit function theorem.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from functools import cached_property
from typing import Mapping, Sequence

import numpy as np
import sympy as sp
from numba import njit

from landau.errors import InputError, IntegratorError
from landau.laws.law import FrictionLaw
from landau.verify.hybrid.dop853 import N_DENSE, N_EXT, advance, dense, dense_at, initial_step

#: the name of the stiffness k′ = k/σ (1/m) as a fit parameter
STIFFNESS = "k"
#: the default relative tolerance of the integration
RTOL = 1e-11
#: the most DOP853 steps one run may take
MAX_STEPS = 2_000_000


@njit(cache=True)
def _integrate(fun, p, iV, ts, Vs, y0, rtol, atol, max_steps, out):
    """Integrate from ``y0`` at ts[0] through every sample time, V_lp = Vs[j] on [ts[j], ts[j+1]).

    ``out`` (samples × states) receives the state at each sample.  Returns the number of steps,
    −1 when the step size fell below round-off, −2 past ``max_steps``."""
    n = y0.shape[0]
    m = ts.shape[0]
    y = y0.copy()
    f = np.empty(n)
    K = np.empty((N_EXT, n))
    F = np.empty((N_DENSE, n))
    ynew = np.empty(n)
    fnew = np.empty(n)
    col = np.empty(n)
    for a in range(n):
        out[0, a] = y[a]
    steps = 0
    start = 0
    while start < m - 1:
        end = start + 1
        while end < m - 1 and Vs[end] == Vs[start]:
            end += 1
        p[iV] = Vs[start]
        t = ts[start]
        t_bound = ts[end]
        fun(t, y, p, f)
        h_abs = initial_step(fun, p, t, y, f, t_bound, np.inf, rtol, atol)
        nxt = start + 1
        while t < t_bound:
            ok, t_new, h, h_abs, nf = advance(fun, p, t, y, f, h_abs, np.inf, t_bound, rtol, atol, K, ynew, fnew)
            if not ok:
                return -1
            steps += 1
            if steps > max_steps:
                return -2
            if nxt <= end and ts[nxt] <= t_new:
                dense(fun, p, t, y, ynew, fnew, K, h, F)
                while nxt <= end and ts[nxt] <= t_new:
                    if ts[nxt] == t_new:
                        for a in range(n):
                            out[nxt, a] = ynew[a]
                    else:
                        dense_at(F, y, (ts[nxt] - t) / h, col)
                        for a in range(n):
                            out[nxt, a] = col[a]
                    nxt += 1
            for a in range(n):
                y[a] = ynew[a]
                f[a] = fnew[a]
            t = t_new
        start = end
    return steps


def linear_in_log_v(mu: sp.Expr, v: sp.Symbol) -> tuple[sp.Expr, sp.Expr] | None:
    """(A, B) with μ = B + A ln v when μ is linear in ln v (A, B free of v), else None."""
    A = sp.simplify(sp.expand_log(v * sp.diff(mu, v), force=True))
    if v in A.free_symbols:
        return None
    B = sp.simplify(sp.expand_log(mu - A * sp.log(v), force=True))
    if v in B.free_symbols:
        return None
    return A, B


@dataclass(frozen=True)
class Run:
    """One forward run at the samples: μ, the slip rate, the states and ∂μ/∂p.

    Attributes
    ----------
    mu : ndarray (m,)
        Friction coefficient at each sample.
    v : ndarray (m,)
        Slip rate (m/s).
    states : ndarray (number of states, m)
        The law's states.
    dmu : ndarray (m, number of sensitivity parameters)
        ∂μ/∂p at each sample, in the order of :attr:`ForwardModel.sensitivity`.
    steps : int
        DOP853 steps taken.
    """

    mu: np.ndarray
    v: np.ndarray
    states: np.ndarray
    dmu: np.ndarray
    steps: int


_MODELS: dict[tuple, "ForwardModel"] = {}


def forward_model(law: FrictionLaw, sensitivity: Sequence[str]) -> "ForwardModel":
    """The :class:`ForwardModel` of ``law`` and ``sensitivity``, built once per process for laws with the same
    expressions (its symbolic field, generated code and compiled kernel are reused by every fit)."""
    key = (sp.srepr(law.mu), tuple(sp.srepr(r) for r in law.rates), tuple(s.name for s in law.states),
           tuple((p.name, p.positive) for p in law.parameters), tuple(sensitivity))
    model = _MODELS.get(key)
    if model is None:
        model = _MODELS[key] = ForwardModel(law, sensitivity)
    return model


class ForwardModel:
    """The quasi-static spring–slider of one law, compiled with the sensitivities of chosen parameters.

    Parameters
    ----------
    law : FrictionLaw
        Any rate-and-state law of :mod:`landau.laws` (built-in or a user's).
    sensitivity : sequence of str
        The parameters whose sensitivities ∂μ/∂p are integrated: names of the law's parameters
        and ``"k"`` (the stiffness k′ = k/σ, 1/m).

    Examples
    --------
    >>> from landau.laws import get_law
    >>> fm = ForwardModel(get_law("dieterich"), ["a", "b", "L"])
    >>> fm.closed_form
    True
    """

    def __init__(self, law: FrictionLaw, sensitivity: Sequence[str]) -> None:
        if not isinstance(law, FrictionLaw):
            raise InputError(f"the forward model needs a rate-and-state law, got {type(law).__name__}")
        names = [p.name for p in law.parameters]
        for s in sensitivity:
            if s != STIFFNESS and s not in names:
                raise InputError(f"{s!r} is not a parameter of law {law.name!r} (its parameters: "
                                 f"{', '.join(names)}; and {STIFFNESS!r}, the stiffness)")
        if len(set(sensitivity)) != len(sensitivity):
            raise InputError(f"a parameter is named twice in {list(sensitivity)}")
        self.law = law
        self.sensitivity = tuple(sensitivity)
        self.param_names = tuple(names)
        self._k = sp.Symbol("k_stiff", positive=True)
        self._V = sp.Symbol("V_lp", positive=True)
        self._mu = sp.Symbol("mu_f", real=True)
        self._w = sp.Symbol("w_lnv", real=True)
        self.closed_form = linear_in_log_v(law.mu, law.v) is not None

    # --- the symbolic field ------------------------------------------------------------
    def _symbol(self, name: str) -> sp.Symbol:
        return self._k if name == STIFFNESS else self.law.parameter(name).symbol

    @cached_property
    def _field(self):
        """(states y, field f(y), v(y), μ(y)) of the chosen form."""
        law, v = self.law, self.law.v
        phis = list(law.states)
        if self.closed_form:
            A, B = linear_in_log_v(law.mu, v)
            vy = sp.exp((self._mu - B) / A)
            y = [self._mu, *phis]
            f = [self._k * (self._V - vy), *(r.subs(v, vy) for r in law.rates)]
            return y, f, vy, self._mu
        vy = sp.exp(self._w)
        mu_v = sp.diff(law.mu, v)
        drive = self._k * (self._V - v) - sum(sp.diff(law.mu, s) * r for s, r in zip(phis, law.rates, strict=True))
        y = [self._w, *phis]
        f = [(drive / (v * mu_v)).subs(v, vy), *(r.subs(v, vy) for r in law.rates)]
        return y, f, vy, law.mu.subs(v, vy)

    @cached_property
    def _extended(self):
        """The states, sensitivity symbols and field of the variational system (Ṡ = f_y S + f_p)."""
        y, f, _, _ = self._field
        n, q = len(y), len(self.sensitivity)
        S = [[sp.Symbol(f"S_{i}_{j}", real=True) for j in range(q)] for i in range(n)]
        fy = sp.Matrix(f).jacobian(y)
        ext = list(f)
        for i in range(n):
            for j, name in enumerate(self.sensitivity):
                ext.append(sum(fy[i, l] * S[l][j] for l in range(n)) + sp.diff(f[i], self._symbol(name)))
        states = list(y) + [S[i][j] for i in range(n) for j in range(q)]
        return states, ext, S

    @cached_property
    def _params(self) -> list[sp.Symbol]:
        return [p.symbol for p in self.law.parameters] + [self._k, self._V]

    @cached_property
    def _kernel(self):
        from landau.codegen.kernels import compile_source, kernel_source
        from landau.verify.hybrid.dop853 import kernel_function

        states, ext, _ = self._extended
        src = kernel_source(states, ext, self._params, jacobian=False)
        return kernel_function(compile_source(src, f"lab forward model of {self.law.name}").fun)

    @cached_property
    def _observation(self):
        """Numeric (v, μ, ∂μ/∂p) of the states and sensitivities at the samples."""
        from landau.support.lambdify import lambdify_positional

        y, _, vy, muy = self._field
        _, _, S = self._extended
        args = [*y, *[s for row in S for s in row], *self._params]
        dmu = [sum(sp.diff(muy, y[i]) * S[i][j] for i in range(len(y))) + sp.diff(muy, self._symbol(name))
               for j, name in enumerate(self.sensitivity)]
        return lambdify_positional(args, [vy, muy, *dmu], modules="numpy", cse=True)

    @cached_property
    def _initial(self):
        """Numeric (R_φ, R_p, μ_φ, μ_p) at (v, φ): the steady state's sensitivities."""
        from landau.support.lambdify import lambdify_positional

        law, v = self.law, self.law.v
        phis = list(law.states)
        qs = [self._symbol(n) for n in self.sensitivity]
        R = sp.Matrix(law.rates)
        exprs = [R.jacobian(phis).tolist(), R.jacobian(qs).tolist() if qs else [],
                 [sp.diff(law.mu, s) for s in phis], [sp.diff(law.mu, s) for s in qs], law.mu]
        return lambdify_positional([v, *phis, *self._params], exprs, modules="numpy")

    @cached_property
    def _steady(self):
        """φ_ss(v, law parameters) in closed form, compiled once (None without a closed form)."""
        from landau.support.lambdify import lambdify_positional

        ss = self.law.steady_state_closed_form
        if ss is None:
            return None
        return lambdify_positional([self.law.v, *(p.symbol for p in self.law.parameters)], list(ss), modules="math")

    # --- numbers -----------------------------------------------------------------------
    def values(self, params: Mapping[str, float], k: float, V: float = 1.0) -> np.ndarray:
        """The kernel's parameter vector: the law's parameters, k′ and V_lp."""
        missing = [n for n in self.param_names if n not in params]
        if missing:
            raise InputError(f"law {self.law.name!r}: no value for parameter(s) {', '.join(missing)}")
        return np.array([float(params[n]) for n in self.param_names] + [float(k), float(V)])

    def initial_state(self, params: Mapping[str, float], k: float, V0: float) -> np.ndarray:
        """The state and sensitivities at steady sliding at V0."""
        law = self.law
        n_phi, q = len(law.states), len(self.sensitivity)
        pv = self.values(params, k, V0)
        phi = None
        if self._steady is not None:
            with np.errstate(all="ignore"):
                phi = np.array([float(x) for x in self._steady(V0, *pv[:-2])])
            if not (np.all(np.isfinite(phi)) and np.all(phi > 0)):
                phi = None
        if phi is None:       # no closed form, or not a valid one here: the law's checked numeric route
            phi = law.steady_state_values(np.float64(V0), params).reshape(n_phi)
        Rphi, Rq, muphi, muq, mu0 = self._initial(V0, *phi, *pv)
        Rphi = np.asarray(Rphi, float).reshape(n_phi, n_phi)
        Rq = np.asarray(Rq, float).reshape(n_phi, q)
        # R(V0, φ_ss(p), p) = 0 for every p:  R_φ · ∂φ_ss/∂p = −R_p
        dphi = np.linalg.solve(Rphi, -Rq) if q else np.zeros((n_phi, 0))
        muphi = np.asarray(muphi, float).reshape(n_phi)
        muq = np.asarray(muq, float).reshape(q)
        first = float(mu0) if self.closed_form else math.log(V0)
        dfirst = muphi @ dphi + muq if self.closed_form else np.zeros(q)
        y0 = np.concatenate([[first], phi, np.concatenate([dfirst[None, :], dphi]).ravel()])
        return y0

    def run(self, t: np.ndarray, V_lp: np.ndarray, params: Mapping[str, float], k: float, *,
            rtol: float = RTOL) -> Run:
        """Integrate over the samples ``t`` (s) with load-point velocities ``V_lp`` (m/s).

        Parameters
        ----------
        t : ndarray
            Sample times, strictly increasing.
        V_lp : ndarray
            Load-point velocity of each sample, held until the next sample (m/s, ≥ 0; V_lp[0] > 0).
        params : mapping
            Values of every parameter of the law (SI).
        k : float
            Stiffness k′ = k/σ (1/m).
        rtol : float
            Relative tolerance of the integration.

        Returns
        -------
        Run

        Raises
        ------
        IntegratorError
            The integration did not reach the last sample.
        """
        t = np.ascontiguousarray(t, dtype=float)
        V_lp = np.ascontiguousarray(V_lp, dtype=float)
        if not V_lp[0] > 0:
            raise InputError(f"the load-point velocity at the first sample must be > 0 (steady sliding), "
                             f"got {V_lp[0]:g}")
        y0 = self.initial_state(params, k, float(V_lp[0]))
        n_y = len(self.law.states) + 1
        q = len(self.sensitivity)
        scale = np.concatenate([[1.0], np.abs(y0[1:n_y])])
        qvals = np.array([abs(float(k) if s == STIFFNESS else float(params[s])) or 1.0 for s in self.sensitivity])
        atol = np.concatenate([rtol * scale, (rtol * scale[:, None] / qvals[None, :]).ravel()])
        p = self.values(params, k, V_lp[0])
        out = np.empty((t.size, y0.size))
        steps = int(_integrate(self._kernel, p, p.size - 1, t, V_lp, y0, float(rtol), atol, MAX_STEPS, out))
        if steps < 0:
            why = "the step size fell below round-off" if steps == -1 else f"more than {MAX_STEPS} steps"
            raise IntegratorError(f"the forward model of {self.law.name!r} stopped: {why} (a stiff or "
                                  "diverging run at these parameters)")
        cols = list(out.T) + list(p)
        obs = self._observation(*cols)
        vv = np.broadcast_to(np.asarray(obs[0], float), t.shape).copy()
        mu = np.broadcast_to(np.asarray(obs[1], float), t.shape).copy()
        dmu = np.column_stack([np.broadcast_to(np.asarray(d, float), t.shape) for d in obs[2:]]) if q \
            else np.zeros((t.size, 0))
        return Run(mu, vv, out[:, 1:n_y].T.copy(), dmu, steps)
