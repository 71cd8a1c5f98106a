"""The smooth slip mode of the frictional impact oscillator as a :class:`DynamicalSystem`.

Lancioni, Lenci & Galvanetto, eq. (1) (re-derived from the energies and virtual work):

    [m₁l²       m₁l sin φ] [φ̈]   [l sin φ  l cos φ] [λ_N]   [c_φφ̇ + k_φ(φ − φ₀) + m₁gl sin φ             ]
    [m₁l sin φ  m₁ + m₂  ] [ÿ] = [1        0      ] [λ_T] − [c_yẏ + k_y(y − y₀) + m₁lφ̇² cos φ + (m₁+m₂)g]

While the tip slides on the belt the gap g_N = y − l cos φ stays 0, so (Sec. 2.2 of the paper)
y = l cos φ, ẏ = −lφ̇ sin φ, ÿ = −lφ̇² cos φ − lφ̈ sin φ, and Coulomb friction gives
λ_T = −s μ λ_N with s = sign g_T, g_T = lφ̇ cos φ − v.  Substituting y, ÿ and λ_T, the two
rows of eq. (1) are linear in the two unknowns (φ̈, λ_N); eliminating λ_N leaves the planar
smooth ODE  φ̇ = ω,  ω̇ = F(φ, ω; μ)  (``slip_system``), which the landau engine
(:func:`landau.derivation.general.hopf_normal_form`) analyses with μ as the Hopf parameter.

Belt direction.  For a constant belt velocity v the slip equilibrium (ω = 0) has g_T = −v,
so s = −sign v and neither the equilibrium nor its linearisation depend on |v|.  Only one
direction has a Hopf point (see :func:`hopf_direction_scan`): with both parameter sets of
the paper it is v < 0 (s = +1, *positive slip* g_T > 0, friction λ_T = −μλ_N).  Why: the
c_y-damping of the reduced ODE is c_y l² sin φ (sin φ − sμ cos φ), which for s = +1
changes sign at μ ≈ tan φ_e (≈ tan π/8 = 0.414) — the Hopf point near μ ≈ 0.41; for
s = −1 it stays positive and the equilibrium stays stable for all μ in [0, 1].  The
denominator of F, l²(m₁cos²φ + m₂ sin φ (sin φ − sμ cos φ)) (the Painlevé coefficient
of :mod:`landau.verify.lancioni.contact`), stays positive on the slip branch for s = +1 only
while μ < (m₁ cot φ + m₂ tan φ)/m₂.

Equilibrium.  ω = 0, and φ_e solves the transcendental
    λ_N(φ)·l(sin φ − sμ cos φ) = k_φ(φ − φ₀) + m₁gl sin φ,  λ_N(φ) = k_y(l cos φ − y₀) + (m₁+m₂)g,
which has no closed form; the system declares one Newton step from φ₀ as its
(approximate) equilibrium expression and the engine refines it by Newton at 50 digits.

Friction law.  Every function takes an optional ``friction`` (a
:class:`~landau.laws.velocity.VelocityFriction` coefficient law; default the paper's
Coulomb μ): the slip mode then has λ_T = −F_s(g_T) λ_N with the law's symbolic branch of
the slip sign s at g_T = lω cos φ − v_belt, so the field depends on the belt velocity
``v_belt`` (default −s m/s) as soon as F depends on the velocity.  The Hopf (bifurcation)
parameter is μ for the Coulomb law; for a law, one of its parameters (``parameter``,
default the first) or a mechanical parameter.

g.  The published Hopf values (μ = 0.40977, set 1; 0.353, set 2) are reproduced with
g = 10 m/s²; g = 9.81 moves them to ≈ 0.40986 and ≈ 0.3541.  g stays a parameter.
"""

from __future__ import annotations

import warnings
from dataclasses import dataclass
from functools import lru_cache
from typing import Any, Callable, Mapping

import numpy as np
import sympy as sp

from landau.derivation.general import hopf_normal_form
from landau.derivation.hopf import HopfResult
from landau.errors import InputError, NoHopfError
from landau.laws.velocity import V_SLIP, VelocityFriction
from landau.support.lambdify import lambdify_positional
from landau.systems.system import DynamicalSystem

phi, omega = sp.symbols("phi omega", real=True)
mu = sp.Symbol("mu", nonnegative=True)
m1, m2, l, k_y, k_phi, c_y, c_phi, phi0, y0, g = sp.symbols(
    "m1 m2 l k_y k_phi c_y c_phi phi0 y0 g", real=True)

#: paper's first parameter set (Sec. 3; Leine, Brogliato & Nijmeijer 2002) with g = 10 m/s²
SET1: dict[str, float] = {"m1": 0.1, "m2": 1.0, "l": 1.0, "k_y": 100.0, "k_phi": 100.0, "c_y": 10.0,
                          "c_phi": 0.0, "phi0": float(np.pi / 8), "y0": 1.0, "g": 10.0}
#: second set (Sec. 3, Figs 4–5): m₁ = 0.4 kg, k_φ = 25 N·m
SET2: dict[str, float] = {**SET1, "m1": 0.4, "k_phi": 25.0}
PARAM_NAMES = tuple(SET1)
#: the mechanical parameters' symbols, by name
MECHANICAL = dict(zip(PARAM_NAMES, (m1, m2, l, k_y, k_phi, c_y, c_phi, phi0, y0, g), strict=True))
#: the belt velocity v in the slip mode's relative velocity g_T = lω cos φ − v (m/s)
v_belt = sp.Symbol("v_belt", real=True)
_TAKEN = {*PARAM_NAMES, "phi", "omega", "v_belt"}


def check_friction(friction) -> VelocityFriction:
    """Refuse anything but a friction-coefficient law of the sliding velocity.

    Parameters
    ----------
    friction : VelocityFriction
        The law to check.

    Returns
    -------
    VelocityFriction
        ``friction`` itself.

    Raises
    ------
    InputError
        Not a :class:`~landau.laws.velocity.VelocityFriction`, a force law (the impact
        oscillator's friction multiplies the normal force), or a law parameter named like a
        mechanical parameter of the model.
    """
    if not isinstance(friction, VelocityFriction):
        raise InputError(f"the impact oscillator's friction must be a VelocityFriction law (e.g. "
                         f"landau.laws.velocity.coulomb(0.4)), got {type(friction).__name__}")
    if friction.quantity != "coefficient":
        raise InputError(f"the impact oscillator's friction must be a friction coefficient (it multiplies the "
                         f"normal force), but law {friction.name!r} gives a {friction.quantity}")
    clash = sorted({p.name for p in friction.parameters} & _TAKEN)
    if clash:
        raise InputError(f"friction law {friction.name!r}: parameter name(s) {', '.join(clash)} are taken by the "
                         f"impact oscillator ({', '.join(sorted(_TAKEN))}); rename them")
    return friction


def _law(friction):
    from landau.laws.velocity import coulomb

    return coulomb() if friction is None else check_friction(friction)


def _law_symbol(name: str) -> sp.Symbol:
    return mu if name == "mu" else sp.Symbol(name, real=True)


def friction_branch(s: int = 1, friction: VelocityFriction | None = None) -> sp.Expr:
    """F_s(g_T): the law's branch for slip sign ``s`` at g_T = lω cos φ − v_belt (sympy).

    Parameters
    ----------
    s : {+1, -1}
        Slip sign (sign of g_T).
    friction : VelocityFriction, optional
        Friction-coefficient law (default: Coulomb, F_s = s μ).

    Returns
    -------
    sympy.Expr
        In φ, ω, ``v_belt`` and the law's parameters (a parameter ``mu`` is the module's μ).
    """
    if s not in (-1, 1):
        raise InputError(f"slip sign must be +1 or -1, got {s!r}")
    law = _law(friction)
    F = law.branch(s).xreplace({p.symbol: _law_symbol(p.name) for p in law.parameters})
    return F.xreplace({V_SLIP: l * omega * sp.cos(phi) - v_belt})


def hopf_parameter(friction: VelocityFriction | None = None, parameter: str | None = None) -> str:
    """The bifurcation parameter's name: ``parameter`` if given (a law or mechanical parameter),
    else ``mu`` for the Coulomb law and the law's first parameter otherwise.

    Parameters
    ----------
    friction : VelocityFriction, optional
    parameter : str, optional

    Returns
    -------
    str
    """
    law = _law(friction)
    names = [p.name for p in law.parameters]
    if parameter is None:
        if not names:
            raise InputError(f"friction law {law.name!r} has no parameter to use as the bifurcation parameter; "
                             f"name a mechanical one ({', '.join(PARAM_NAMES)})")
        return names[0]
    if parameter not in names and parameter not in PARAM_NAMES:
        raise InputError(f"bifurcation parameter {parameter!r} is neither a parameter of law {law.name!r} "
                         f"({', '.join(names) or 'none'}) nor a mechanical one ({', '.join(PARAM_NAMES)})")
    return parameter


def _parameter_symbol(name: str) -> sp.Symbol:
    return MECHANICAL.get(name) or _law_symbol(name)


def slip_accelerations(s: int, friction: VelocityFriction | None = None):
    """(φ̈, λ_N) in slip with λ_T = −F_s(g_T)λ_N (Coulomb: −sμλ_N), as sympy expressions of (φ, ω)
    and the parameters.

    Parameters
    ----------
    s : {+1, -1}
        Slip sign.
    friction : VelocityFriction, optional
        Friction-coefficient law (default: Coulomb μ).

    Returns
    -------
    tuple of sympy.Expr
        φ̈ and λ_N.
    """
    return _accelerations(s, friction_branch(s, friction))


@lru_cache(maxsize=16)
def _accelerations(s: int, Fs: sp.Expr):
    ddphi, lamN = sp.symbols("ddphi lamN")
    sn, cs = sp.sin(phi), sp.cos(phi)
    y, yd = l * cs, -l * omega * sn
    ydd = -l * omega**2 * cs - l * ddphi * sn
    lamT = -Fs * lamN
    row_phi = m1 * l**2 * ddphi + m1 * l * sn * ydd - (l * sn * lamN + l * cs * lamT) \
        + (c_phi * omega + k_phi * (phi - phi0) + m1 * g * l * sn)
    row_y = m1 * l * sn * ddphi + (m1 + m2) * ydd - lamN \
        + (c_y * yd + k_y * (y - y0) + m1 * l * omega**2 * cs + (m1 + m2) * g)
    # the rows are linear in (φ̈, λ_N): Cramer's rule (sympy's solve+simplify is ~10x slower)
    A, rhs = sp.linear_eq_to_matrix([sp.expand(row_phi), sp.expand(row_y)], [ddphi, lamN])
    det = sp.factor(A.det())
    x1 = (rhs[0] * A[1, 1] - A[0, 1] * rhs[1])
    x2 = (A[0, 0] * rhs[1] - A[1, 0] * rhs[0])
    return sp.collect(sp.expand(x1), omega) / det, sp.collect(sp.expand(x2), omega) / det


@dataclass(frozen=True, eq=False)
class SlipFunctions:
    """Numeric slip-mode functions of (φ, ω, *args), args named by :attr:`names`
    (the mechanical parameters, ``v_belt``, then the law's parameters)."""

    names: tuple[str, ...]
    F: Callable[..., float]       # φ̈(φ, ω, *args)  (math module: scalars)
    L: Callable[..., float]       # λ_N(φ, ω, *args)
    F0: Callable[..., Any]        # φ̈(φ, 0, *args)  (numpy)
    J: Callable[..., Any]         # Jacobian of (ω, φ̈) in (φ, ω)

    def __repr__(self) -> str:
        return f"SlipFunctions(args={self.names})"


def slip_functions(s: int = 1, friction: VelocityFriction | None = None) -> SlipFunctions:
    """The slip mode's φ̈, λ_N and Jacobian as numeric functions (generated once per law expression).

    Parameters
    ----------
    s : {+1, -1}
        Slip sign.
    friction : VelocityFriction, optional
        Friction-coefficient law (default: Coulomb μ).

    Returns
    -------
    SlipFunctions
    """
    law = _law(friction)
    return _numeric(s, friction_branch(s, friction), tuple(p.name for p in law.parameters))


@lru_cache(maxsize=16)
def _numeric(s: int, Fs: sp.Expr, law_names: tuple[str, ...]) -> SlipFunctions:
    F, L = _accelerations(s, Fs)
    names = (*PARAM_NAMES, "v_belt", *law_names)
    args = [phi, omega, *MECHANICAL.values(), v_belt, *map(_law_symbol, law_names)]
    J = sp.Matrix([omega, F]).jacobian([phi, omega])
    # positional names: a law parameter named like a printed function (cos, array) cannot shadow it
    return SlipFunctions(names, lambdify_positional(args, F, "math"), lambdify_positional(args, L, "math"),
                         lambdify_positional(args, F.subs(omega, 0)), lambdify_positional(args, J))


def belt_velocity(s: int = 1, v: float | None = None) -> float:
    """The constant belt velocity of slip sign ``s`` (default −s m/s; s·v < 0 is required, as
    g_T = −v on the slip equilibrium)."""
    v = -float(s) if v is None else float(v)
    if not (np.isfinite(v) and s * v < 0):
        raise InputError(f"belt velocity v={v!r}: slip sign s={s:+d} needs s*v < 0 (g_T = -v on the slip equilibrium)")
    return v


def slip_values(params: Mapping[str, float] | None = None, s: int = 1, friction: VelocityFriction | None = None,
                v: float | None = None, **values: float) -> dict[str, float]:
    """Every parameter of the slip mode by name: mechanical (:func:`resolve`), ``v_belt`` and the
    law's (its defaults), with ``values`` overriding any of them.

    Parameters
    ----------
    params : mapping, optional
        Mechanical parameters (default: set 1).
    s : {+1, -1}
    friction : VelocityFriction, optional
    v : float, optional
        Belt velocity (default −s).
    **values : float
        Overrides (e.g. the bifurcation parameter's value).

    Returns
    -------
    dict of str to float
    """
    law = _law(friction)
    out = {**resolve(params), "v_belt": belt_velocity(s, v), **law.defaults()}
    missing = [p.name for p in law.parameters if p.name not in out and p.name not in values]
    if missing:
        raise InputError(f"friction law {law.name!r}: parameter(s) {', '.join(missing)} need a value")
    for k_, x in values.items():
        if k_ not in out and k_ not in {p.name for p in law.parameters}:
            raise InputError(f"unknown parameter {k_!r} of the slip mode")
        out[k_] = float(x)
    return out


def _args(fns: SlipFunctions, values: Mapping[str, float]) -> tuple[float, ...]:
    return tuple(values[n] for n in fns.names)


def _numeric_slip(s: int):
    """Compiled F(φ, 0; μ, params) and the Jacobian of (ω, F) of the Coulomb slip mode."""
    fns = slip_functions(s)
    f0 = lambda x, m_, *p: fns.F0(x, 0.0, *p, -s, m_)  # noqa: E731
    J = lambda x, w, m_, *p: fns.J(x, w, *p, -s, m_)  # noqa: E731
    return f0, J


def slip_system(s: int = 1, friction: VelocityFriction | None = None, parameter: str | None = None) -> DynamicalSystem:
    """The slip mode (g_N = 0, sign g_T = s) as φ̇ = ω, ω̇ = F(φ, ω); Hopf parameter μ (Coulomb) or
    ``parameter`` (default: the law's first).

    ``s = +1`` (g_T > 0, belt velocity v < 0) is the direction with the Hopf point.

    Parameters
    ----------
    s : {+1, -1}
        Slip sign.
    friction : VelocityFriction, optional
        Friction-coefficient law (default: Coulomb μ).
    parameter : str, optional
        The Hopf parameter's name.

    Returns
    -------
    DynamicalSystem
    """
    law = _law(friction)
    par = hopf_parameter(friction, parameter)
    name = f"lancioni-slip[{'+' if s > 0 else '-'}]" if friction is None else \
        f"lancioni-slip[{'+' if s > 0 else '-'}, {law.name}]"
    defaults = tuple(slip_values(None, s, friction).items())
    return _slip_system(s, friction_branch(s, friction), par, name, defaults)


@lru_cache(maxsize=16)
def _slip_system(s: int, Fs: sp.Expr, par: str, name: str, defaults: tuple) -> DynamicalSystem:
    F, _ = _accelerations(s, Fs)
    # approximate equilibrium: one Newton step on F(φ, 0) = 0 from φ₀ (refined by the engine)
    F0 = F.subs(omega, 0)
    phi_e = phi0 - (F0 / sp.diff(F0, phi)).subs(phi, phi0)
    return DynamicalSystem(
        name=name,
        states=(phi, omega),
        rhs=(omega, F),
        mass=(sp.Integer(1), sp.Integer(1)),
        parameter=_parameter_symbol(par),
        equilibrium=(phi_e, sp.Integer(0)),
        defaults={k_: v_ for k_, v_ in defaults
                  if k_ != par and (k_ in PARAM_NAMES or k_ in {x.name for x in F.free_symbols})},
        normalise=0,
        description="Lancioni-Lenci-Galvanetto eq. (1) with g_N = 0 and lambda_T = -F(g_T) lambda_N "
                    "(Coulomb: -s mu lambda_N)",
    )


def resolve(params: Mapping[str, float] | None = None) -> dict[str, float]:
    """SET1 updated by ``params`` (names of :data:`PARAM_NAMES`), checked."""
    p = dict(SET1)
    for k_, v_ in (params or {}).items():
        if k_ not in p:
            raise InputError(f"unknown parameter {k_!r} (known: {', '.join(PARAM_NAMES)})")
        v_ = float(v_)
        if not np.isfinite(v_):
            raise InputError(f"parameter {k_!r} must be finite")
        p[k_] = v_
    for k_ in ("m1", "m2", "l"):
        if p[k_] <= 0:
            raise InputError(f"parameter {k_!r} must be > 0, got {p[k_]!r}")
    for k_, what in (("k_y", "a spring stiffness"), ("k_phi", "a spring stiffness"), ("c_y", "a damping"),
                     ("c_phi", "a damping"), ("g", "the gravitational acceleration")):
        if p[k_] < 0:
            raise InputError(f"parameter {k_!r} is {what} and must be >= 0, got {p[k_]!r}")
    if abs(p["phi0"]) > 2 * np.pi:
        raise InputError(f"parameter 'phi0' is the rest angle of the rotational spring (rad) and must lie in "
                         f"[-2 pi, 2 pi], got {p['phi0']!r}")
    return p


#: the scan for the Hopf point covers friction coefficients 0 < μ ≤ MU_SCAN_MAX (dry friction of
#: engineering materials stays below ~1.5; the slip mode is checked, not assumed, to be well posed)
MU_SCAN_MAX = 2.0
#: any other bifurcation parameter p is scanned over (0, SCAN_FACTOR·p₀] (p₀ its value, with its sign),
#: then, if no crossing is found, outwards over (SCAN_FACTOR·p₀, SCAN_FACTOR²·p₀] and so on, SCAN_STEPS times
SCAN_FACTOR = 5.0
SCAN_STEPS = 3


def scan_range(friction: VelocityFriction | None = None, parameter: str | None = None,
               params: Mapping[str, float] | None = None, s: int = 1) -> tuple[float, float]:
    """The interval :func:`hopf_bracket` scans: (0, MU_SCAN_MAX] for the Coulomb μ (the physical range
    of a friction coefficient), (0, SCAN_FACTOR**SCAN_STEPS·p₀] for another parameter of value p₀
    (scanned outwards from 0 in SCAN_STEPS pieces, each SCAN_FACTOR times the previous).

    Parameters
    ----------
    friction : VelocityFriction, optional
    parameter : str, optional
    params : mapping, optional
        Mechanical parameters.
    s : {+1, -1}

    Returns
    -------
    tuple of float
        (lo, hi), the end away from 0 included.
    """
    par = hopf_parameter(friction, parameter)
    if friction is None and par == "mu":
        return 0.0, MU_SCAN_MAX
    p0 = slip_values(params, s, friction).get(par)
    if p0 is None or p0 == 0 or not np.isfinite(p0):
        raise InputError(f"the Hopf scan of {par!r} needs a nonzero value of it to scale the search "
                         f"(got {p0!r}); give a bracket")
    far = SCAN_FACTOR ** SCAN_STEPS * p0
    return (0.0, far) if p0 > 0 else (far, 0.0)


def hopf_bracket(params: Mapping[str, float] | None = None, s: int = 1, n: int = 201,
                 friction: VelocityFriction | None = None, parameter: str | None = None,
                 v: float | None = None) -> tuple[float, float]:
    """An interval of the bifurcation parameter containing the first crossing of the slip
    equilibrium's complex pair.

    Scans max Re λ of the complex eigenvalue pair of the slip equilibrium over
    :func:`scan_range` (for μ: (0, MU_SCAN_MAX], the physical range of a friction coefficient),
    outwards from 0, and returns the first grid cell where it changes sign — derived from the
    model, not from a published value.

    Parameters
    ----------
    params : mapping, optional
        Mechanical parameters (default: set 1).
    s : {+1, -1}
        Slip sign.
    n : int
        Grid points.
    friction : VelocityFriction, optional
        Friction-coefficient law (default: Coulomb μ).
    parameter : str, optional
        Bifurcation parameter (default: μ, or the law's first parameter).
    v : float, optional
        Belt velocity (default −s m/s).

    Returns
    -------
    tuple of float
    """
    par = hopf_parameter(friction, parameter)
    lo_, hi_ = scan_range(friction, par, params, s)
    far = hi_ if hi_ != 0 else lo_
    if friction is None and par == "mu":
        grid = np.linspace(far / n, far, n)
    else:  # pieces (0, F p0], (F p0, F² p0], ...: fine near the law's own value, wide far from it
        ends = [far / SCAN_FACTOR ** k for k in range(SCAN_STEPS - 1, -1, -1)]
        grid = np.concatenate([np.linspace(a / n if i == 0 else a + (b - a) / n, b, n)
                               for i, (a, b) in enumerate(zip([0.0] + ends[:-1], ends, strict=True))])
    fns = slip_functions(s, friction)
    base = slip_values(params, s, friction, v)
    prev = None
    failed = 0
    for m_ in grid:
        try:
            vals = {**base, par: m_}
            with np.errstate(all="ignore"), warnings.catch_warnings():
                warnings.simplefilter("ignore", RuntimeWarning)   # overflow is counted below, not printed
                pe = _equilibrium(fns, vals)
                J = np.array(fns.J(pe, 0.0, *_args(fns, vals)), float)
            if not np.all(np.isfinite(J)):
                raise OverflowError
            lam = np.linalg.eigvals(J)
        except (ValueError, RuntimeError, ZeroDivisionError, OverflowError, np.linalg.LinAlgError):
            prev = None
            failed += 1
            continue
        cplx = lam[np.abs(lam.imag) > 1e-12 * (1 + np.abs(lam.real))]
        r = float(np.max(cplx.real)) if cplx.size else None
        if r is not None and np.isfinite(r) and prev is not None and prev[1] * r < 0:
            return float(prev[0]), float(m_)
        prev = (m_, r) if r is not None and np.isfinite(r) else None
    if failed * 2 >= len(grid):
        raise InputError(f"the slip equilibrium or its Jacobian cannot be evaluated in float64 at {failed} of the "
                         f"{len(grid)} values of {par} between 0 and {far:g} scanned for a Hopf point (overflow or "
                         "no equilibrium): bring the parameters nearer their physical scale")
    raise NoHopfError(f"no Hopf point of the slip equilibrium (slip sign {s:+d}) for {par} between 0 and {far:g}")


def slip_hopf(params: Mapping[str, float] | None = None, bracket: tuple[float, float] | None = None,
              s: int = 1, friction: VelocityFriction | None = None, parameter: str | None = None,
              v: float | None = None) -> HopfResult:
    """Hopf point of the slip equilibrium in μ (or another parameter) through the landau engine.

    Without ``bracket`` the interval comes from :func:`hopf_bracket` (a scan of the model).

    Parameters
    ----------
    params : mapping of str to float, optional
        Mechanical parameters (default: set 1).
    bracket : tuple of float, optional
        An interval of the bifurcation parameter containing the Hopf point.
    s : int, optional
        Slip sign (+1: positive slip, the belt direction with a Hopf point).
    friction : VelocityFriction, optional
        Friction-coefficient law F(g_T) with its parameter values (default: Coulomb μ).
    parameter : str, optional
        The bifurcation parameter: μ for the Coulomb law; by default the law's first parameter.
    v : float, optional
        Constant belt velocity (default −s m/s); matters only for a velocity-dependent law.

    Returns
    -------
    HopfResult
        p_c, ω_c, the Landau coefficient, c₁ and the criticality.

    References
    ----------
    Kuznetsov, Y. A. (2004), *Elements of Applied Bifurcation Theory*, 3rd ed., Springer,
    Section 3.5.
    """
    par = hopf_parameter(friction, parameter)
    try:   # one analysis per question in a process (a figure asks for the same point several times)
        key = (tuple(sorted(resolve(params).items())), None if bracket is None else tuple(map(float, bracket)),
               int(s), friction, par, v)
        hit = _HOPF.get(key)
    except TypeError:   # an unhashable friction object: not remembered
        key, hit = None, None
    if hit is not None:
        return hit
    if bracket is None:
        bracket = hopf_bracket(params, s, friction=friction, parameter=par, v=v)
    if friction is None:
        out = hopf_normal_form(slip_system(s), resolve(params), bracket=bracket)
    else:
        out = hopf_normal_form(slip_system(s, friction, par), slip_values(params, s, friction, v), bracket=bracket)
    if key is not None:
        if len(_HOPF) >= 32:
            _HOPF.pop(next(iter(_HOPF)))
        _HOPF[key] = out
    return out


#: the slip Hopf points located in this process (:func:`slip_hopf`), by their question
_HOPF: dict = {}


@dataclass(frozen=True)
class DirectionScan:
    """Max Re λ of the slip equilibrium over a μ grid for both belt directions."""

    mu: np.ndarray
    max_re: Mapping[int, np.ndarray]  # keyed by slip sign s (= −sign v)

    def hopf_sign(self) -> list[int]:
        return [s for s, r in self.max_re.items() if np.any(np.diff(np.sign(r[np.isfinite(r)])) != 0)]

    def __repr__(self) -> str:
        return f"DirectionScan(mu in [{self.mu[0]:g}, {self.mu[-1]:g}], Hopf for s = {self.hopf_sign()})"


def equilibrium_phi(p: Mapping[str, float], mu_val: float | None, s: int, friction: VelocityFriction | None = None,
                    parameter: str | None = None, v: float | None = None) -> float:
    """φ_e of the slip equilibrium (Newton on F(φ, 0) = 0 from φ₀).

    Parameters
    ----------
    p : mapping
        Mechanical parameters.
    mu_val : float
        Value of the bifurcation parameter (μ for the Coulomb law, else ``parameter``, default the
        law's first); None keeps the law's own value.
    s : {+1, -1}
        Slip sign.
    friction : VelocityFriction, optional
    parameter : str, optional
    v : float, optional
        Belt velocity (default −s).

    Returns
    -------
    float
    """
    fns = slip_functions(s, friction)
    over = {} if mu_val is None else {hopf_parameter(friction, parameter): mu_val}
    return _equilibrium(fns, slip_values(p, s, friction, v, **over))


def _equilibrium(fns: SlipFunctions, vals: Mapping[str, float]) -> float:
    from scipy.optimize import brentq, newton
    args = _args(fns, vals)
    f = lambda x: fns.F0(x, 0.0, *args)  # noqa: E731
    try:
        return float(newton(f, vals["phi0"], tol=1e-14, maxiter=100))
    except RuntimeError:
        return float(brentq(f, -np.pi / 2 + 1e-6, np.pi / 2 - 1e-6))


def hopf_direction_scan(params: Mapping[str, float] | None = None,
                        mus: np.ndarray = np.linspace(0.0, 1.0, 101)) -> DirectionScan:
    """Which belt direction has the Hopf point: max Re λ of the slip equilibrium for s = ±1."""
    p = resolve(params)
    out = {}
    for s in (-1, 1):
        _, J = _numeric_slip(s)
        vals = []
        for m_ in mus:
            try:
                pe = equilibrium_phi(p, m_, s)
                lam = np.linalg.eigvals(np.array(J(pe, 0.0, m_, *[p[n] for n in PARAM_NAMES]), float))
                vals.append(float(np.max(lam.real)))
            except (ValueError, RuntimeError):
                vals.append(np.nan)
        out[s] = np.array(vals)
    return DirectionScan(np.asarray(mus, float), out)
