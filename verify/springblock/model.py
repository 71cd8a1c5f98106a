"""The spring–block of Putelat et al. (2010), eq. (4)/(5), compiled for direct simulation.

For any :class:`~laws.FrictionLaw` the equations M ẍ = k(Vt − x) − σμ(ẋ, φ),
dφᵢ/dt = rateᵢ(ẋ, φ) are written in variables that keep the slip rate and the states
positive and O(1) over stick phases where v falls by tens of decades:

    ξ = X/ℓ  (X = x − x₀(t), ℓ = the law's memory length L, or ``length_scale``),
    w = ln(v/V),   ψᵢ = ln(φᵢ/φᵢ,₀),   τ = t V/ℓ,

    ξ' = e^w − 1,
    w' = (ℓ/V) e^{−w} [−kℓξ − σ(μ(v, φ) − μ₀)] / (M V),
    ψᵢ' = (ℓ/V) rateᵢ(v, φ)/φᵢ,

so that steady sliding is the origin.  The right-hand side is written from the symbolic
law (logs of products expanded so that ln v = ln V + w is never formed from an underflowed
v); its parameter-only subexpressions (the logarithms of parameters that this expansion
produces, products and quotients of parameters) become derived entries of the parameter vector,
computed once per model (:func:`landau.codegen.kernels.hoist_parameters`), so that a call of the
compiled field does only state-dependent work; the field and its exact Jacobian are then
generated and compiled by :mod:`landau.codegen.kernels` (common-subexpression elimination, the
whitelist of generated syntax, numba through the cross-process code cache).  The dimensionless parameters of the paper
(eq. 6) are
m = M V_*²/(σL) and κ = kL/σ (σ = Mg); :meth:`SpringBlockModel.from_dimensionless`
builds the model from (m, κ, V/V_*).
"""

from __future__ import annotations

import math
import weakref
from dataclasses import dataclass, field
from functools import cached_property
from typing import Callable, Mapping

import numpy as np
import sympy as sp

from landau.codegen.kernels import DerivedParameters, compile_source, hoist_parameters, kernel_source
from landau.errors import InputError
from landau.laws.law import FrictionLaw
from landau.laws.law import v as v_slip
from landau.support.lambdify import lambdify_positional
from landau.systems.springblock_terms import Balance, mechanical_rhs, parameters, state_scales, states, steady_values
from landau.systems.system import SpringBlock
from landau.verify.hybrid.callbacks import call_pointer, pointer
from landau.verify.hybrid.radau import SIG, SIG_JAC


@dataclass(frozen=True)
class CompiledLaw:
    """Generated source and compiled f, J of the scaled spring–block for one law (any parameters).

    The kernels read the parameter vector ``parameters(base)``: the base vector (law
    parameters in the order of ``param_names``, then M, σ, k, V, ℓ, μ₀, φ₀) followed by the
    parameter-only subexpressions of the field (logarithms of parameters, products and
    quotients), evaluated once per model rather than at every call
    (:func:`landau.codegen.kernels.hoist_parameters`).
    """

    law_name: str
    n: int
    param_names: tuple[str, ...]
    source: str = field(repr=False)
    rhs: Callable[..., None] = field(repr=False)
    jac: Callable[..., None] = field(repr=False)
    rhs_py: Callable[..., None] = field(repr=False)
    jac_py: Callable[..., None] = field(repr=False)
    parameters: DerivedParameters = field(repr=False)


_CACHE: dict[tuple, CompiledLaw] = {}
_SYS_NAMES = ("M", "sigma", "k", "V", "ell", "mu0")


def _law_key(law: FrictionLaw) -> tuple:
    return (sp.srepr(law.mu), tuple(sp.srepr(r) for r in law.rates), tuple(s.name for s in law.states),
            tuple(p.name for p in law.parameters))


#: the compiled pieces of each law object seen (identity lookup: the structural key below prints
#: the law's expressions, which costs more than a loose-tolerance integration)
_BY_LAW: "weakref.WeakKeyDictionary[FrictionLaw, CompiledLaw]" = weakref.WeakKeyDictionary()


def compile_law(law: FrictionLaw, terms: tuple[str, ...] = ()) -> CompiledLaw:
    """Generate and compile the scaled right-hand side and analytic Jacobian of eq. (4) for ``law``
    (with the optional spring–block ``terms`` of :mod:`landau.systems.springblock_terms`: their
    values follow φ₀ in the base parameter vector, and σ there is the steady-sliding σ_ss)."""
    if not terms:
        hit = _BY_LAW.get(law)
        if hit is not None:
            return hit
    key = _law_key(law) + ((tuple(terms),) if terms else ())
    if key in _CACHE:
        if not terms:
            _BY_LAW[law] = _CACHE[key]
        return _CACHE[key]
    ns = len(law.states)
    tstates = states(terms)
    n = 2 + ns + len(tstates)
    # the model's own symbols carry names no law symbol can take (a law's names are plain
    # identifiers starting with a letter), and the law's symbols are replaced all at once
    # (xreplace): a law parameter named like an internal symbol is renamed once, never twice
    ys = sp.symbols(f"_y0:{n}", real=True)
    xi, w, psis, pis = ys[0], ys[1], ys[2:2 + ns], ys[2 + ns:]
    lp = [sp.Symbol(f"_q{i}", positive=True) for i in range(len(law.parameters))]
    Msym, sig, ksym, Vsym, ell, mu0 = sp.symbols("_M _sigma _k _V _ell _mu0", positive=True)
    phi0 = [sp.Symbol(f"_phi0_{i}", positive=True) for i in range(ns)]
    tnames = [name for name, *_ in parameters(terms)]
    tsyms = [sp.Symbol(f"_{t}", real=True) for t in tnames]
    # each term state π scaled by its typical size S (a parameter): the state's excess is S π
    scales = [sp.Symbol(f"_S{i}", positive=True) for i in range(len(tstates))]
    sub = {p.symbol: s for p, s in zip(law.parameters, lp, strict=True)}
    vv = Vsym * sp.exp(w)
    phis = [p0 * sp.exp(ps) for p0, ps in zip(phi0, psis, strict=True)]
    sub.update({v_slip: vv, **dict(zip(law.states, phis, strict=True))})
    internal = {*ys, *lp, Msym, sig, ksym, Vsym, ell, mu0, *phi0, *tsyms, *scales}

    def tidy(e):
        out = sp.expand_log(e.xreplace(sub), force=True)   # (the law's symbols are replaced already: a no-op)
        stray = out.free_symbols - internal
        if stray:   # FrictionLaw declares every symbol; a stray one would be a wrong field
            raise InputError(f"law {law.name!r}: undeclared symbol(s) {sorted(map(str, stray))} in the field")
        return out

    # the force balance and the state rates of every term, from their one declaration
    # (springblock_terms.mechanical_rhs), in X = ℓξ, u = V(e^w − 1); σ here is σ_ss
    tv = dict(zip(tnames, tsyms, strict=True))
    extra = {st.symbol.name: S * pi for st, S, pi in zip(tstates, scales, pis, strict=True)}
    force, rates = mechanical_rhs(law, terms, ell * xi, Vsym * (sp.exp(w) - 1), sub, tuple(phi0), ksym, sig, Vsym,
                                  mu0=mu0, sigma_ss=sig, symbol=tv, extra=extra if tstates else None)
    f = [sp.exp(w) - 1, (ell / Vsym) * sp.exp(-w) * tidy(force) / (Msym * Vsym)]
    for rate, ph in zip(rates[:ns], phis, strict=True):
        f.append((ell / Vsym) * sp.expand(tidy(rate) / ph))
    for rate, S in zip(rates[ns:], scales, strict=True):
        f.append((ell / Vsym) * sp.expand(tidy(rate) / S))
    psyms = [*lp, Msym, sig, ksym, Vsym, ell, mu0, *phi0, *tsyms, *scales]
    # the logarithms of parameters that expand_log produced, and every other parameter-only
    # subexpression, become entries of the parameter vector computed once per model
    h = hoist_parameters(f, psyms)
    full = [*psyms, *h.derived]
    _SYMBOLIC[key] = (ys, h.field, full)
    _DERIVED[key] = DerivedParameters(psyms, h.values)
    out = _compile(ys, h.field, full, law.name, tuple(p.name for p in law.parameters), _DERIVED[key])
    _CACHE[key] = out
    if not terms:
        _BY_LAW[law] = out
    return out


def _compile(ys, f, psyms, label, param_names, derived) -> CompiledLaw:
    """The field ``f`` over the states ``ys`` and parameter vector ``psyms``, through the kernel
    generator of :mod:`landau.codegen.kernels` (exact Jacobian by sympy, common subexpressions, the
    whitelist of generated syntax, the cross-process code cache)."""
    src = kernel_source(ys, f, psyms)
    c = compile_source(src, label)
    assert c.jac is not None and c.jac_py is not None  # kernel_source emits the Jacobian by default
    return CompiledLaw(label, len(ys), param_names, src, c.fun, c.jac, c.fun_py, c.jac_py, derived)


_SYMBOLIC: dict[tuple, tuple] = {}
_DERIVED: dict[tuple, DerivedParameters] = {}
_VAR_CACHE: dict[tuple, CompiledLaw] = {}


def compile_variational(law: FrictionLaw, terms: tuple[str, ...] = ()) -> CompiledLaw:
    """The system augmented with its variational equations Φ' = J(y)Φ (n + n² states, Φ row-major),
    with the exact Jacobian of the augmented system (second derivatives of f included)."""
    key = _law_key(law) + ((tuple(terms),) if terms else ())
    if key in _VAR_CACHE:
        return _VAR_CACHE[key]
    compile_law(law, terms)
    ys, f, psyms = _SYMBOLIC[key]
    n = len(ys)
    Jm = sp.Matrix(f).jacobian(sp.Matrix(ys))
    Phi = sp.Matrix(n, n, sp.symbols(f"_y{n}:{n + n * n}", real=True))
    JP = Jm * Phi
    faug = list(f) + [JP[i, j] for i in range(n) for j in range(n)]
    yaug = list(ys) + [Phi[i, j] for i in range(n) for j in range(n)]
    out = _compile(yaug, faug, psyms, law.name + " (variational)", _CACHE[key].param_names, _DERIVED[key])
    _VAR_CACHE[key] = out
    return out


@dataclass(frozen=True)
class SpringBlockModel:
    """Eq. (4) for one law at driving velocity V [m/s] and stiffness k [N/m] (SI units).

    ``params`` is the full parameter dict of :meth:`landau.systems.system.SpringBlock.resolve`
    (law parameters, M, g, sigma).  ``ell`` is the length unit of ξ (the law's L if it has one).
    """

    law: FrictionLaw
    V: float
    k: float
    params: Mapping[str, float]
    ell: float
    phi0: tuple[float, ...]
    mu0: float
    #: the optional spring–block terms built in (``eta``, ``gamma_ld``, ``alpha_ld``)
    terms: tuple[str, ...] = ()

    @classmethod
    def build(cls, law: FrictionLaw, V: float, k: float, params: Mapping[str, float] | None = None,
              length_scale: float | None = None) -> "SpringBlockModel":
        block = SpringBlock.for_params(law, params)    # with the optional terms given
        p = block.resolve(params)
        if not (np.isfinite(V) and V > 0):
            raise InputError(f"driving velocity V must be > 0, got {V!r}")
        if not (np.isfinite(k) and k > 0):
            raise InputError(f"stiffness k must be > 0, got {k!r}")
        if p["M"] <= 0:
            raise InputError("direct simulation needs a block mass M > 0 (M = 0 is the quasi-static DAE)")
        ell = float(length_scale if length_scale is not None else p.get("L", 1e-6))
        phi0 = _steady_state(law, V, p)
        vals = {s: p[s.name] for s in (prm.symbol for prm in law.parameters)}
        mu0 = float(law.mu.subs({v_slip: V, **dict(zip(law.states, phi0, strict=True)), **vals}))
        if not np.isfinite(mu0):
            raise InputError(f"law {law.name!r}: friction coefficient not finite at steady sliding V = {V!r}")
        if block.terms:
            block.argvals(float(V), p)                  # no steady sliding (gamma_ld): a named error
        return cls(law, float(V), float(k), dict(p), ell, tuple(phi0), mu0, block.terms)

    @classmethod
    def from_dimensionless(cls, law: FrictionLaw, m: float, kappa: float, V_over_Vs: float,
                           params: Mapping[str, float] | None = None) -> "SpringBlockModel":
        """The paper's eq. (5): m = V_*²/(gL), κ = kL/(Mg), driving velocity V/V_* (σ = Mg).

        Realised dimensionally with the law's L and V_* (Table 1) and M = 1.2 kg:
        g = V_*²/(mL), σ = Mg, k = κσ/L — every solution of (5) is a rescaling of this one.
        """
        p = SpringBlock(law).resolve(params)
        if "L" not in p or "V_s" not in p:
            raise InputError(f"law {law.name!r} has no L and V_s: the dimensionless form (5) needs them")
        if not (m > 0 and kappa > 0 and V_over_Vs > 0):
            raise InputError("m, kappa and V/V_* must all be > 0")
        g = p["V_s"] ** 2 / (m * p["L"])
        sigma = p["M"] * g
        over = dict(params or {})
        over.update(g=g, sigma=sigma)
        return cls.build(law, V_over_Vs * p["V_s"], kappa * sigma / p["L"], over)

    def with_(self, **changes) -> "SpringBlockModel":
        """Same law and parameters with V and/or k (or parameters, as params=...) changed."""
        V = changes.pop("V", self.V)
        k = changes.pop("k", self.k)
        params = dict(self.params)
        params.update(changes.pop("params", {}))
        if changes:
            raise InputError(f"unknown change(s) {sorted(changes)}")
        block_keys = set(SpringBlock(self.law, self.terms).defaults)
        return SpringBlockModel.build(self.law, V, k, {kk: vv for kk, vv in params.items() if kk in block_keys},
                                      self.ell)

    # --- compiled pieces ------------------------------------------------------------
    @property
    def compiled(self) -> CompiledLaw:
        return compile_law(self.law, self.terms)

    @property
    def n(self) -> int:
        return 2 + len(self.law.states) + len(states(self.terms))

    @cached_property
    def p(self) -> np.ndarray:
        """The parameter vector of the compiled kernels (the same for :func:`compile_law` and
        :func:`compile_variational`): base values, then the derived parameter combinations."""
        vals = [self.params[nm] for nm in self.compiled.param_names]
        vals += [self.params["M"], self.sigma_ss, self.k, self.V, self.ell, self.mu0, *self.phi0]
        vals += [self.params[name] for name, *_ in parameters(self.terms)]
        vals += list(self.state_scales.values())
        return self.compiled.parameters(vals)

    @cached_property
    def state_scales(self) -> dict[str, float]:
        """The unit of each term state's scaled variable (:attr:`TermState.scale` at steady sliding)."""
        if not states(self.terms):
            return {}
        sym = {name: sp.Float(float(self.params[name])) for name, *_ in parameters(self.terms)}
        b = Balance(v=sp.Float(self.V), phis=tuple(map(sp.Float, self.phi0)), F=sp.Integer(0), F_dot=sp.Integer(0),
                    V_lp=sp.Float(self.V), k=sp.Float(self.k), sigma0=sp.Float(self.params["sigma"]),
                    sigma=sp.Float(self.sigma_ss), mu=sp.Float(self.mu0), symbol=sym)
        return {name: float(e) for name, e in state_scales(self.terms, b).items()}

    @cached_property
    def sigma_ss(self) -> float:
        """The normal load at steady sliding: σ, or (σ₀ + γ_LD ηV)/(1 − γ_LD μ₀) with ``gamma_ld``
        (:func:`landau.systems.springblock_terms.steady_values`)."""
        return steady_values(self.terms, self.params["sigma"], self.mu0, self.V, self.params)[1]

    @property
    def time_unit(self) -> float:
        """Seconds per unit of the internal time τ = tV/ℓ."""
        return self.ell / self.V

    @property
    def m(self) -> float:
        """Dimensionless mass of eq. (6), m = M V_*²/(σL) (needs V_s, L)."""
        return self.params["M"] * self.params["V_s"] ** 2 / (self.params["sigma"] * self.params["L"])

    @property
    def kappa(self) -> float:
        """Dimensionless stiffness of eq. (6), κ = kL/σ."""
        return self.k * self.params["L"] / self.params["sigma"]

    def f(self, y) -> np.ndarray:
        """The scaled field of eq. (4) at the scaled state ``y``, by the compiled code the
        integrator calls (the same C callback: one build per law serves both)."""
        out = np.empty(self.n)
        call_pointer(pointer(self.compiled.rhs, SIG, "right-hand side"), 0.0,
                     np.ascontiguousarray(y, dtype=float), self.p, out)
        return out

    def J(self, y) -> np.ndarray:
        """The exact Jacobian of :meth:`f` at ``y`` (the integrator's compiled code, as :meth:`f`)."""
        out = np.empty((self.n, self.n))
        call_pointer(pointer(self.compiled.jac, SIG_JAC, "Jacobian"), 0.0,
                     np.ascontiguousarray(y, dtype=float), self.p, out)
        return out

    # --- physical coordinates ---------------------------------------------------------
    def to_physical(self, y) -> dict[str, np.ndarray]:
        """X = x − x₀ [m], v [m/s], φᵢ, spring-force excess and μ from scaled states (…, n) arrays."""
        y = np.asarray(y, dtype=float)
        out = {"X": y[..., 0] * self.ell, "v": self.V * np.exp(y[..., 1])}
        for i, s in enumerate(self.law.states):
            out[s.name] = self.phi0[i] * np.exp(y[..., 2 + i])
        for j, (name, S) in enumerate(self.state_scales.items()):   # the term states' excesses
            out[name] = S * y[..., 2 + len(self.law.states) + j]
        return out

    def from_physical(self, X: float, v: float, phis, extra: Mapping[str, float] | None = None) -> np.ndarray:
        """Scaled state from X [m], v [m/s], the law's states and (``extra``, default 0) the term states'
        excesses over steady sliding, by name."""
        if v <= 0 or any(ph <= 0 for ph in phis):
            raise InputError("slip rate and states must be > 0 for the log variables")
        ex = [(extra or {}).get(name, 0.0) / S for name, S in self.state_scales.items()]
        return np.array([X / self.ell, math.log(v / self.V),
                         *(math.log(ph / p0) for ph, p0 in zip(phis, self.phi0, strict=True)), *ex])

    def critical_mode(self) -> tuple[complex, np.ndarray]:
        """Eigenvalue with the largest real part of J(0) (per unit τ) and its eigenvector with ξ-component 1."""
        lam, vec = np.linalg.eig(self.J(np.zeros(self.n)))
        i = int(np.argmax(lam.real + 1e-12 * np.abs(lam.imag)))
        if abs(vec[0, i]) == 0:
            raise InputError("the critical mode has no slip component")
        return complex(lam[i]), vec[:, i] / vec[0, i]

    def perturbed(self, amplitude: float) -> np.ndarray:
        """Steady sliding displaced along the critical (oscillatory) mode so that X = ``amplitude`` [m].

        The linear mode's real part at phase 0 is used: ξ = a, the other components follow
        the eigenvector (w, ψ are log-variables: the linear relation holds for small a).
        """
        _, vec = self.critical_mode()
        return (amplitude / self.ell) * vec.real


def _steady_state(law: FrictionLaw, V: float, p: Mapping[str, float]) -> list[float]:
    vals = {prm.symbol: p[prm.name] for prm in law.parameters}
    ss = law.steady_state_closed_form
    if ss is not None:
        out = [float(e.subs({v_slip: V, **vals})) for e in ss]
    else:
        from scipy.optimize import root

        fn = lambdify_positional([law.states], [r.subs({v_slip: V, **vals}) for r in law.rates], "math")
        guess = [p.get("L", 1.0) / V] * len(law.states)
        sol = root(lambda z: fn(list(z)), guess, tol=1e-14)
        if not sol.success:
            raise InputError(f"law {law.name!r}: no steady state found at V = {V!r}")
        out = [float(z) for z in sol.x]
    if not all(np.isfinite(x) and x > 0 for x in out):
        raise InputError(f"law {law.name!r}: steady state {out} at V = {V!r} is not positive "
                         "(the simulation uses log-states)")
    return out
