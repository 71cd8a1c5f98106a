"""The non-smooth mode-coupling model: unilateral contact, stick and slip, as a hybrid model.

The structure of Hoffmann, Fischer, Allgaier & Gaul (2002) and its N-DOF family,

    M x'' + C x' + K x = f_c,   f_c[n] = P − N(δ),   f_c[t] = F(v_rel) N(δ),

with δ = x[n] the penetration of the normal coordinate n into the belt, v_rel = v₀ − x'[t] the
belt's speed relative to the tangential coordinate t, the contact law N(δ) (``linear`` k_H δ,
``cubic`` k_H δ + k_NL δ³, ``hertz`` k_H δ^{3/2}) while the contact is closed and N = 0 when it
opens, and the friction coefficient F(v_rel) of a velocity law (constant Coulomb μ by default).
Four modes:

* ``slip+`` (v_rel > 0) and ``slip-`` (v_rel < 0): closed contact, friction F(v_rel)·N;
* ``stick`` (v_rel = 0): x'[t] = v₀ held; the tangential force λ that holds it is, with
  r = f₀ − C x' − K x (f₀ the known forces, f₀[t] = 0),
  λ = −(M⁻¹r)[t] / (M⁻¹)[t, t] (so that (M⁻¹(r + λ e_t))[t] = 0), and the mass sticks while
  −μ₋N ≤ λ ≤ μ₊N (μ₊ = F(0⁺), μ₋ = −F(0⁻), the law's static levels);
* ``flight`` (δ < 0): N = 0, no friction.

Transitions: the contact opens when δ reaches 0 (slip, stick → flight) and closes when it comes
back (→ slip± by the sign of v_rel); at v_rel = 0 the mass sticks if λ lies in the stick cone,
else slips on the side λ points to; it slips again when λ leaves the cone.  A softening cubic
contact (k_NL < 0) has a largest penetration δ_max = sqrt(−k_H/(3k_NL)) past which N'(δ) < 0 (the
contact collapses): a terminal guard ends the run there, named.

The fields and the guards are written once symbolically (every number a kernel parameter) and
compiled by :func:`landau.codegen.kernels.generate_kernel` (one compiled source per mode,
dimension, contact law and friction branch, cached on disk), integrated by the compiled DOP853 of
:mod:`landau.verify.hybrid.dop853` with the guards screened in its compiled loop; the events are
located on its 7th-order dense output by the hybrid engine (:mod:`landau.verify.hybrid.simulate`).

References
----------
Hoffmann, N., Fischer, M., Allgaier, R. & Gaul, L. (2002), "A minimal model for studying properties
of the mode-coupling type instability in friction induced oscillations", Mech. Res. Commun. 29,
197–205.
"""

from __future__ import annotations

import functools
import math
from dataclasses import dataclass, field, replace

import numpy as np

from landau.errors import InputError
from landau.laws.velocity import V_SLIP, VelocityFriction, coulomb
from landau.verify.hybrid.model import Guard, HybridModel, Jump, Mode

__all__ = ["CONTACT_LAWS", "Contact", "Structure", "hoffmann_structure", "hybrid_model", "initial_mode",
           "sliding_equilibrium", "MODES"]

#: the contact laws N(δ) while the contact is closed
CONTACT_LAWS = ("linear", "cubic", "hertz")
#: the modes of the hybrid model
MODES = ("slip+", "slip-", "stick", "flight")


@dataclass(frozen=True)
class Contact:
    """The normal contact law N(δ) of the penetration δ > 0: ``linear`` k_H δ, ``cubic`` k_H δ + k_NL δ³,
    ``hertz`` k_H δ^{3/2}."""

    law: str = "linear"
    kH: float = 1.0
    kNL: float = 0.0

    def __post_init__(self) -> None:
        if self.law not in CONTACT_LAWS:
            raise InputError(f"contact law must be one of {', '.join(CONTACT_LAWS)}, got {self.law!r}")
        if not (math.isfinite(self.kH) and self.kH > 0):
            raise InputError(f"contact stiffness kH must be a finite number > 0, got {self.kH!r}")
        if not math.isfinite(self.kNL):
            raise InputError(f"contact coefficient kNL must be finite, got {self.kNL!r}")
        if self.law != "cubic" and self.kNL != 0:
            raise InputError(f"kNL = {self.kNL!r} applies to the cubic contact law only (contact law {self.law!r})")

    @property
    def delta_max(self) -> float:
        """The largest penetration with N'(δ) > 0 (inf unless the contact is cubic and softening)."""
        if self.law == "cubic" and self.kNL < 0:
            return math.sqrt(-self.kH / (3.0 * self.kNL))
        return math.inf

    def force(self, delta):
        """N(δ) (0 where δ ≤ 0), elementwise."""
        d = np.maximum(np.asarray(delta, dtype=float), 0.0)
        if self.law == "hertz":
            return self.kH * d * np.sqrt(d)
        return self.kH * d + self.kNL * d ** 3

    def stiffness(self, delta: float) -> float:
        """N'(δ) at a closed contact δ > 0."""
        if self.law == "hertz":
            return 1.5 * self.kH * math.sqrt(max(delta, 0.0))
        return self.kH + 3.0 * self.kNL * delta * delta

    def symbolic(self, delta, kH, kNL):
        """N(δ) as a sympy expression (δ clipped at 0 for the Hertz law's root)."""
        import sympy as sp

        if self.law == "hertz":
            d = sp.Max(delta, 0)
            return kH * d * sp.sqrt(d)
        if self.law == "cubic":
            return kH * delta + kNL * delta ** 3
        return kH * delta


@dataclass(frozen=True)
class Structure:
    """The N-DOF structure M x'' + C x' + K x = f_c in contact at coordinate ``normal`` (penetration δ)
    with a belt moving at ``v0`` along coordinate ``tangential``, preload ``preload`` on the normal
    coordinate, the contact law ``contact`` and the friction coefficient law ``friction`` of v_rel.

    The arrays are checked (square, finite, M symmetric positive definite); ``mu`` gives the Coulomb
    law where ``friction`` is None.
    """

    M: np.ndarray
    C: np.ndarray
    K: np.ndarray
    normal: int
    tangential: int
    preload: float
    v0: float
    contact: Contact = Contact()
    friction: VelocityFriction | None = None
    mu: float | None = None
    _Minv: np.ndarray = field(init=False, repr=False, compare=False)
    _law_values: tuple = field(init=False, repr=False, compare=False)
    _static: tuple = field(init=False, repr=False, compare=False)

    def __post_init__(self) -> None:
        mats = {}
        for name in ("M", "C", "K"):
            a = np.array(getattr(self, name), dtype=float)
            if a.ndim != 2 or a.shape[0] != a.shape[1] or a.shape[0] < 2:
                raise InputError(f"mode-coupling: {name} must be a square matrix of size >= 2, got shape {a.shape}")
            if not np.all(np.isfinite(a)):
                raise InputError(f"mode-coupling: {name} must be finite")
            mats[name] = a
        n = mats["M"].shape[0]
        if mats["C"].shape != (n, n) or mats["K"].shape != (n, n):
            raise InputError(f"mode-coupling: M, C and K must have the same size (M is {n}x{n})")
        M = mats["M"]
        if not np.allclose(M, M.T, rtol=1e-12, atol=0.0) or np.linalg.eigvalsh(0.5 * (M + M.T)).min() <= 0:
            raise InputError("mode-coupling: the mass matrix M must be symmetric positive definite")
        for name in ("normal", "tangential"):
            i = getattr(self, name)
            if not isinstance(i, (int, np.integer)) or not 0 <= int(i) < n:
                raise InputError(f"mode-coupling: {name} must be a coordinate index in 0..{n - 1}, got {i!r}")
        if self.normal == self.tangential:
            raise InputError("mode-coupling: the normal and the tangential coordinate must differ")
        if not math.isfinite(self.preload):
            raise InputError(f"mode-coupling: the preload P must be finite, got {self.preload!r}")
        if not (math.isfinite(self.v0) and self.v0 > 0):
            raise InputError(f"mode-coupling: the belt speed v0 must be a finite number > 0, got {self.v0!r}")
        for name, a in mats.items():
            a.flags.writeable = False
            object.__setattr__(self, name, a)
        law = self.friction
        if law is None:
            mu = 0.0 if self.mu is None else float(self.mu)
            if not (math.isfinite(mu) and mu >= 0):
                raise InputError(f"mode-coupling: the friction coefficient mu must be a finite number >= 0, got "
                                 f"{self.mu!r}")
            law = coulomb(mu)
        elif self.mu is not None:
            raise InputError("mode-coupling: give the friction either as mu or as a law, not both")
        vals = tuple(float(law.defaults()[p.name]) for p in law.parameters if p.name in law.defaults())
        if len(vals) != len(law.parameters):
            raise InputError(f"mode-coupling: friction law {law.name!r}: every parameter needs a value")
        lo, hi = law.limits_at_zero()
        object.__setattr__(self, "friction", law)
        object.__setattr__(self, "_law_values", vals)
        object.__setattr__(self, "_static", (float(hi), float(-lo)))
        # M⁻¹ once: every field below is M⁻¹ times a force (M x'' = f)
        object.__setattr__(self, "_Minv", np.linalg.inv(M))

    @property
    def law(self) -> VelocityFriction:
        """The friction coefficient law F(v_rel) (Coulomb μ where none was given)."""
        assert self.friction is not None, "set in __post_init__"
        return self.friction

    @property
    def n(self) -> int:
        """The number of degrees of freedom (the state has 2n components: x, then x')."""
        return int(self.M.shape[0])

    @property
    def static(self) -> tuple[float, float]:
        """(μ₊, μ₋) = (F(0⁺), −F(0⁻)): the stick cone −μ₋N ≤ λ ≤ μ₊N."""
        return self._static

    def with_(self, **kw) -> "Structure":
        """A copy with fields replaced (``mu=`` replaces the friction law by Coulomb μ)."""
        if "mu" in kw and "friction" not in kw:
            kw["friction"] = None
        return replace(self, **kw)

    def amplitude_check(self, eps2=1e-2, *, tolerance: float | None = None):
        """The flutter onset's amplitude equation checked by this structure's non-smooth simulation
        (:func:`landau.verify.modecoupling.check.check_flutter`; what :func:`landau.check` runs for it)."""
        from landau.verify.modecoupling.check import check_flutter

        return check_flutter(self, eps2, tolerance=tolerance)

    def coefficient(self, side: int, vrel):
        """F(v_rel) on the slip side ``side`` (+1: v_rel > 0, −1: v_rel < 0), elementwise."""
        v = side * np.maximum(side * np.asarray(vrel, dtype=float), 0.0)
        return np.broadcast_to(self.law.numeric(side)(v, *self._law_values), np.shape(v)) + 0.0

    def forces(self, y):
        """(N, λ, r) at states ``y`` (shape (2n,) or (2n, m)): the contact force, the tangential force
        that holds a stuck mass and r = f₀ − C x' − K x (f₀: preload minus N on the normal coordinate)."""
        y = np.asarray(y, dtype=float)
        n = self.n
        x, v = y[:n], y[n:]
        N = self.contact.force(x[self.normal])
        r = -(self.C @ v) - (self.K @ x)
        r[self.normal] = r[self.normal] + self.preload - N
        Mi = self._Minv
        lam = -(Mi[self.tangential] @ r) / Mi[self.tangential, self.tangential]
        return N, lam, r

    def parameter_vector(self) -> np.ndarray:
        """The kernels' parameters: M⁻¹, C, K (row by row), P, v₀, k_H, k_NL, the law's values, μ₊, μ₋, δ_max."""
        dmax = self.contact.delta_max
        return np.array([*self._Minv.ravel(), *self.C.ravel(), *self.K.ravel(), self.preload, self.v0,
                         self.contact.kH, self.contact.kNL, *self._law_values, *self._static,
                         dmax if math.isfinite(dmax) else 0.0], dtype=float)

    def kernel_key(self) -> tuple:
        """What the generated sources depend on (besides the mode)."""
        law = self.law
        return (self.n, int(self.normal), int(self.tangential), self.contact.law,
                math.isfinite(self.contact.delta_max), law.branch(1), law.branch(-1),
                tuple(p.symbol for p in law.parameters))


def hoffmann_structure(m: float = 1.0, k1: float = 1.0, k2: float = 0.5, alpha1: float = 30.0,
                       alpha2: float = 60.0, kH: float = 1.0, kNL: float = 0.0, P: float = 1.0, c1: float = 0.02,
                       c2: float = 0.04, mu: float | None = None, v0: float = 1.0, *, contact: str = "linear",
                       friction: VelocityFriction | None = None) -> Structure:
    """The 2-DOF model of Hoffmann et al. (2002) (angles in degrees): x (tangential, index 0) and the
    penetration y (normal, index 1),

        k₁₁ = k₁cos²α₁ + k₂cos²α₂,  k₁₂ = k₁ sinα₁ cosα₁ − k₂ sinα₂ cosα₂,  k₂₂ = k₁sin²α₁ + k₂sin²α₂.

    This is the one small builder the branch's own simulation needs; the model object
    ``landau.systems.mode_coupling.ModeCoupling.hoffmann2002`` builds the same structure.
    """
    for name, val in (("m", m), ("k1", k1), ("k2", k2), ("alpha1", alpha1), ("alpha2", alpha2), ("c1", c1),
                      ("c2", c2)):
        if not math.isfinite(val):
            raise InputError(f"mode-coupling: parameter {name!r} must be finite, got {val!r}")
    if not m > 0:
        raise InputError(f"mode-coupling: parameter 'm' (the mass) must be > 0, got {m!r}")
    if c1 < 0 or c2 < 0:
        raise InputError(f"mode-coupling: the damping c1, c2 must be >= 0, got c1={c1!r}, c2={c2!r}")
    a1, a2 = math.radians(alpha1), math.radians(alpha2)
    k11 = k1 * math.cos(a1) ** 2 + k2 * math.cos(a2) ** 2
    k12 = k1 * math.sin(a1) * math.cos(a1) - k2 * math.sin(a2) * math.cos(a2)
    k22 = k1 * math.sin(a1) ** 2 + k2 * math.sin(a2) ** 2
    return Structure(np.diag([m, m]), np.diag([c1, c2]), np.array([[k11, k12], [k12, k22]]), 1, 0, float(P),
                     float(v0), Contact(contact, float(kH), float(kNL)), friction, mu)


def sliding_equilibrium(s: Structure) -> np.ndarray:
    """The steady sliding state (x*, 0): K x* = (P − N) e_n + F(v₀) N e_t with N = N(δ*), δ* = x*[n] > 0.

    Started from the linear contact's solution (x = (K + k_H (e_n − F e_t) e_nᵀ)⁻¹ P e_n, exact for the
    linear law) and refined by Newton's method (scipy's ``root``, hybrid Powell); InputError when no
    closed-contact equilibrium exists (a preload that lifts the mass off the belt, or a softening contact
    that collapses first).
    """
    from scipy.optimize import root

    n, nrm, tan = s.n, s.normal, s.tangential
    F = float(s.coefficient(1, s.v0))
    load = np.zeros(n)
    load[nrm] = s.preload
    coupling = np.zeros(n)
    coupling[nrm], coupling[tan] = 1.0, coupling[tan] - F
    # (K + k_H (e_n − F e_t) e_nᵀ) x = P e_n: the equilibrium with the contact linearised at k_H
    A = s.K + s.contact.kH * np.outer(coupling, _unit(n, nrm))
    try:
        x = np.linalg.solve(A, load)
    except np.linalg.LinAlgError:
        raise InputError("mode-coupling: the stiffness with the contact closed is singular: no sliding "
                         "equilibrium") from None

    def residual(z):
        return s.K @ z + coupling * float(s.contact.force(z[nrm])) - load

    if s.contact.law != "linear" and x[nrm] > 0:
        sol = root(residual, x, method="hybr", options={"xtol": 1e-15})
        x = sol.x
    d = float(x[nrm])
    scale = max(1.0, float(np.abs(load).max()))
    if not (d > 0 and np.all(np.isfinite(x)) and np.abs(residual(x)).max() <= 1e-11 * scale):
        raise InputError(f"mode-coupling: no sliding equilibrium with the contact closed at P = {s.preload:g}, "
                         f"mu = {F:g} (the preload does not press the mass onto the belt, or the contact law "
                         "has no closed equilibrium)")
    if d >= s.contact.delta_max:
        raise InputError(f"mode-coupling: the sliding equilibrium's penetration {d:.6g} is past the softening "
                         f"contact's limit delta_max = {s.contact.delta_max:.6g} (the contact collapses)")
    return np.concatenate([x, np.zeros(n)])


# ------------------------------------------------------------------------------------- generated
def _pieces(key: tuple, mode: str):
    """The symbolic state, parameters, forces and acceleration of ``mode`` for the structure ``key``."""
    import sympy as sp

    n, nrm, tan, claw, soft, branch_p, branch_m, law_symbols = key
    x = sp.symbols(f"_x0:{n}", real=True)
    v = sp.symbols(f"_xd0:{n}", real=True)
    Mi = sp.Matrix(n, n, sp.symbols(f"_Mi0:{n * n}", real=True))
    Cm = sp.Matrix(n, n, sp.symbols(f"_C0:{n * n}", real=True))
    Km = sp.Matrix(n, n, sp.symbols(f"_K0:{n * n}", real=True))
    P, vb, kH, kNL, mup, mum, dmax = sp.symbols("_P _vb _kH _kNL _mup _mum _dmax", real=True)
    params = [*Mi, *Cm, *Km, P, vb, kH, kNL, *law_symbols, mup, mum, dmax]
    X, V = sp.Matrix(x), sp.Matrix(v)
    N = Contact(claw).symbolic(x[nrm], kH, kNL)
    r = -Cm * V - Km * X
    r[nrm] += P
    vrel = vb - v[tan]
    out = dict(states=[*x, *v], params=params, N=N, vrel=vrel, delta=x[nrm], mup=mup, mum=mum, dmax=dmax)
    if mode == "flight":
        acc = Mi * r
    elif mode == "stick":
        r[nrm] -= N
        lam = -(Mi[tan, :] * r)[0] / Mi[tan, tan]
        r[tan] += lam
        acc = Mi * r
        acc[tan] = sp.Integer(0)      # x'[t] = v₀ held (the formula's value is 0 to rounding)
        out["lam"] = lam
    else:
        s = 1 if mode == "slip+" else -1
        branch = branch_p if s > 0 else branch_m
        # F at the current v_rel, taken as 0⁺ (0⁻) a rounding error on the wrong side of 0
        F = branch.subs(V_SLIP, s * sp.Max(s * vrel, 0))
        r[nrm] -= N
        r[tan] += F * N
        acc = Mi * r
    out["field"] = [*v, *acc]
    return out


@functools.lru_cache(maxsize=128)
def _field_kernel(key: tuple, mode: str):
    from landau.codegen.kernels import generate_kernel

    pc = _pieces(key, mode)
    return generate_kernel(pc["states"], pc["field"], pc["params"], [1.0] * len(pc["params"]), jacobian=False,
                           name=f"mode-coupling-{mode}-n{key[0]}-{key[3]}")


def _guard_exprs(key: tuple, mode: str, sections: tuple = ()) -> list:
    pc = _pieces(key, mode)
    soft = key[4]
    if mode == "flight":
        gs = [-pc["delta"]]
    elif mode == "stick":
        gs = [pc["delta"], pc["mup"] * pc["N"] - pc["lam"], pc["mum"] * pc["N"] + pc["lam"]]
    else:
        s = 1 if mode == "slip+" else -1
        gs = [pc["delta"], s * pc["vrel"]]
    if soft and mode != "flight":
        gs.append(pc["dmax"] - pc["delta"])
    return gs + [sign * pc["states"][index] for _, index, sign in sections]


@functools.lru_cache(maxsize=128)
def _guard_kernel(key: tuple, mode: str, sections: tuple = ()):
    from landau.codegen.kernels import generate_vector_function

    pc = _pieces(key, mode)
    return generate_vector_function(pc["states"], _guard_exprs(key, mode, sections), pc["params"],
                                    [1.0] * len(pc["params"]), name=f"mode-coupling-{mode}-n{key[0]}-{key[3]}-guards")


def field_kernel(s: Structure, mode: str):
    """The compiled field of ``mode`` (a :class:`~landau.verify.hybrid.kernel.Kernel` with the structure's
    parameter vector)."""
    if mode not in MODES:
        raise InputError(f"mode-coupling: no mode {mode!r} (modes: {', '.join(MODES)})")
    return replace(_field_kernel(s.kernel_key(), mode), p=s.parameter_vector())


def guard_kernel(s: Structure, mode: str, sections: tuple = ()):
    """The compiled guards of ``mode``, in the order of :func:`hybrid_model`'s guards (its sections last)."""
    return replace(_guard_kernel(s.kernel_key(), mode, tuple(sections)), p=s.parameter_vector())


# ------------------------------------------------------------------------------------- the hybrid model
def _closing_mode(s: Structure, y) -> str:
    """The mode a state at v_rel = 0 (or a closing contact) goes to: stick inside the cone, else the slip
    side the holding force points to."""
    vrel = s.v0 - float(y[s.n + s.tangential])
    N, lam, _ = s.forces(y)
    mup, mum = s.static
    if abs(vrel) > 1e-12 * max(1.0, s.v0):
        return "slip+" if vrel > 0 else "slip-"
    if -mum * N <= lam <= mup * N and N > 0:
        return "stick"
    return "slip+" if lam > mup * N else "slip-"


def _to_stick_or_slip(s: Structure):
    def transition(t, y):
        y = np.array(y, dtype=float)
        mode = _closing_mode(s, y)
        if mode == "stick":
            y[s.n + s.tangential] = s.v0        # x'[t] = v₀ exactly (a rounding-size correction)
        return Jump(mode, y, f"v_rel = 0: {mode}")
    return transition


def _to(mode: str, note: str):
    def transition(t, y):
        return Jump(mode, np.array(y, dtype=float), note)
    return transition


def _closing(s: Structure):
    def transition(t, y):
        y = np.array(y, dtype=float)
        vrel = s.v0 - float(y[s.n + s.tangential])
        mode = "slip+" if vrel > 0 else "slip-" if vrel < 0 else _closing_mode(s, y)
        return Jump(mode, y, f"contact closes: {mode}")
    return transition


def _collapse(t, y):
    return Jump("collapse", np.array(y, dtype=float), "the softening contact collapses (N'(delta) = 0)")


def _component(i: int, scale: float, offset: float = 0.0):
    """The guard ``scale * y[i] + offset`` (vectorised over samples)."""
    def g(t, y):
        return scale * y[i] + offset
    return g


def _unit(size: int, i: int, scale: float = 1.0) -> np.ndarray:
    w = np.zeros(size)
    w[i] = scale
    return w


def hybrid_model(s: Structure, sections: tuple = ()) -> HybridModel:
    """The hybrid model of the module docstring (modes :data:`MODES`, and ``collapse`` where a softening
    contact ends the run), state (x, x') of size 2n, for :func:`landau.verify.hybrid.simulate` with the
    compiled DOP853.

    ``sections``: ``(name, index, sign)`` triples, each a logged section (no switch) where
    ``sign * y[index]`` falls through 0 in every mode (e.g. ``("x-max", n, 1)``: the maxima of x[0]).
    """
    n2, nrm, vt = 2 * s.n, s.normal, s.n + s.tangential
    dmax = s.contact.delta_max
    soft = math.isfinite(dmax)
    mup, mum = s.static
    sections = tuple((str(nm), int(i), float(sg)) for nm, i, sg in sections)
    secs = tuple(Guard(nm, _component(i, sg), affine=(_unit(n2, i, sg), 0.0)) for nm, i, sg in sections)

    def delta(t, y):
        return y[nrm]

    lift = Guard("lift-off", delta, _to("flight", "contact opens"), affine=(_unit(n2, nrm), 0.0))
    limit = (Guard("contact-collapse", lambda t, y: dmax - y[nrm], _collapse, terminal=True,
                   affine=(_unit(n2, nrm, -1.0), dmax)),) if soft else ()

    def stick_up(t, y):
        N, lam, _ = s.forces(y)
        return mup * N - lam

    def stick_down(t, y):
        N, lam, _ = s.forces(y)
        return mum * N + lam

    def mode(name: str, guards: tuple) -> Mode:
        return Mode(name, _rhs(s, name), (*guards, *secs), kernel=_builder(field_kernel, s, name),
                    guard_kernel=_builder(guard_kernel, s, name, sections))

    modes = []
    for name, side in (("slip+", 1), ("slip-", -1)):
        stop = Guard("stop", _component(vt, -float(side), side * s.v0), _to_stick_or_slip(s),
                     affine=(_unit(n2, vt, -float(side)), side * s.v0))
        modes.append(mode(name, (lift, stop, *limit)))
    modes.append(mode("stick", (lift, Guard("slip+ onset", stick_up, _to("slip+", "stick ends: slip+")),
                                Guard("slip- onset", stick_down, _to("slip-", "stick ends: slip-")), *limit)))
    close = Guard("contact", lambda t, y: -y[nrm], _closing(s), affine=(_unit(n2, nrm, -1.0), 0.0))
    modes.append(mode("flight", (close,)))
    if soft:
        modes.append(Mode("collapse", lambda t, y: np.zeros(n2)))
    return HybridModel.from_modes(*modes, name="mode-coupling")


def _builder(make, s: Structure, mode: str, *args):
    @functools.lru_cache(maxsize=None)
    def build():
        return make(s, mode, *args)
    return build


def _rhs(s: Structure, mode: str):
    build = _builder(field_kernel, s, mode)

    def rhs(t, y):
        return build()(t, y)
    return rhs


def initial_mode(s: Structure, y) -> str:
    """The mode of a state: flight where δ ≤ 0 (opening), else by v_rel (stick inside the cone at v_rel = 0)."""
    y = np.asarray(y, dtype=float)
    if y[s.normal] < 0 or (y[s.normal] == 0 and y[s.n + s.normal] < 0):
        return "flight"
    return _closing_mode(s, y)
