"""Beyond the cubic: the quintic amplitude equation, generalised-Hopf (Bautin) points and the fold of cycles.

At a point of the Hopf line where the Landau coefficient Λ changes sign the cubic amplitude
equation says nothing (its amplitude C = 2 sqrt(2|Re a|/|Λ|) diverges).  One order further,

    dA/dT = a (p − p_c) A + b A|A|² + c A|A|⁴,   Λ = 2 Re b,  Λ₅ = 2 Re c,

(landau's convention: the critical mode's ``normalise`` component equals 1; for the spring–block
p = k, a = −Γ̄ + iΩ̄ and the slip X is normalised).  Its cycles |A| = r satisfy

    Re a (p − p_c) + (Λ/2) r² + (Λ₅/2) r⁴ = 0,

so where Λ and Λ₅ have opposite signs a stable and an unstable cycle coexist and meet at the
**fold of cycles**

    r_fold² = −Λ/(2Λ₅),   p_fold − p_c = Λ²/(8 Λ₅ Re a),

whose amplitude in the normalised coordinate is max|y_n − y₀,n| = 2 r_fold = sqrt(−2Λ/Λ₅).  Near a
Bautin point (Λ = 0) Λ is linear in the distance to it, so the fold emanates from the Hopf line
tangentially: p_fold − p_c ∝ (distance)², amplitude ∝ |distance|^{1/2}.  The terms the
truncation omits ((p − p_c) A|A|², A|A|⁶, …) change p_fold − p_c by a relative amount
O(distance), which is the order at which the prediction's error must vanish.

Two independent routes give Λ₅: the Fredholm condition at O(ε⁵)
(:func:`landau.derivation.fredholm.quintic_coefficient`: closed forms in the law's derivatives for the
spring–block through ``Derivation.coefficient("Lambda5")``, numbers here for any system) and
Kuznetsov's normal form with multilinear forms up to fifth order
(:func:`landau.derivation.lyapunov.lyapunov_coefficients`, which also reports l₂ as MatCont and
BifurcationKit print it).

The point and the fold are :class:`landau.analyses.codim2.GeneralisedHopfPoint` and
:class:`landau.analyses.codim2.FoldOfCycles`, the types every route shares.

References
----------
Kuznetsov, Yu. A. (2004). Elements of Applied Bifurcation Theory, 3rd ed., Springer, §8.3 (Bautin).
Putelat, T., Dawes, J. H. P., Willis, J. R. (2010). Regimes of frictional sliding of a spring–block
system. J. Mech. Phys. Solids 58, 27–53 (eq. 20; Figs 11–12: the fold of cycles).
"""

from __future__ import annotations

import math
from typing import Mapping

import mpmath

from landau.analyses.codim2 import SPRING_BLOCK_PARAMETERS, FoldOfCycles, GeneralisedHopfPoint
from landau.derivation.fredholm import _pencil, best_drop, linear_coefficient, null_vectors, quintic_coefficient
from landau.derivation.hopf import GENERAL, HopfResult
from landau.derivation.jets import Jets
from landau.derivation.lyapunov import _NumericJets, equilibrium_floats, numeric_values
from landau.errors import InputError, NoHopfError, SingularPointError
from landau.support.cx import as_expr
from landau.support.lambdify import lambdify_positional
from landau.systems.system import DynamicalSystem


# --------------------------------------------------------------------------------------
# the fold of cycles of the truncated amplitude equation
def fold_of_cycles(Lambda: float, Lambda5: float, re_a: float, p_c: float, *,
                   parameter: str = "p") -> FoldOfCycles | None:
    """The fold of cycles of Re a (p − p_c) + (Λ/2) r² + (Λ₅/2) r⁴ = 0, or None where there is none.

    Parameters
    ----------
    Lambda, Lambda5 : float
        Λ = 2 Re b and Λ₅ = 2 Re c (landau's convention).
    re_a : float
        Re a = d Re λ/dp (spring–block: −Γ̄).
    p_c : float
        The Hopf point.
    parameter : str
        Name of the parameter p.

    Returns
    -------
    FoldOfCycles or None
        None unless Λ and Λ₅ have opposite signs (no fold near the Hopf point otherwise).
    """
    if not all(math.isfinite(x) for x in (Lambda, Lambda5, re_a)) or re_a == 0 or Lambda5 == 0:
        raise InputError("fold_of_cycles: Lambda, Lambda5 and Re a must be finite, Lambda5 and Re a non-zero")
    if Lambda * Lambda5 >= 0:
        return None
    off = Lambda ** 2 / (8.0 * Lambda5 * re_a)
    return FoldOfCycles(parameter, p_c + off, math.sqrt(-2.0 * Lambda / Lambda5), p_c=p_c)


def cycle_amplitudes(Lambda: float, Lambda5: float, re_a: float, p_c: float, p: float) -> tuple[float, ...]:
    """Amplitudes max|y_n − y₀,n| = 2r of every cycle of the quintic amplitude equation at p (ascending).

    The positive roots r² of (Λ₅/2) r⁴ + (Λ/2) r² + Re a (p − p_c) = 0; where the cubic
    prediction diverges (Λ → 0) these stay finite."""
    A, B, C = Lambda5 / 2.0, Lambda / 2.0, re_a * (p - p_c)
    if A == 0:
        roots = [-C / B] if B != 0 else []
    else:
        disc = B * B - 4 * A * C
        if disc < 0:
            return ()
        s = math.sqrt(disc)
        qq = -0.5 * (B + math.copysign(s, B)) if B != 0 else -0.5 * s
        roots = [qq / A, C / qq] if qq != 0 else [0.0]
    return tuple(sorted(2.0 * math.sqrt(x) for x in roots if x > 0))


# --------------------------------------------------------------------------------------
# the Fredholm route at fifth order for any system
def quintic_normal_form(system: DynamicalSystem, values: Mapping[str, float], p_c: float, omega_c: float, *,
                        dps: int = 50, jets: Jets | None = None) -> HopfResult:
    """Hopf point, a, Λ, χ and Λ₅ of a general system by the Fredholm condition to O(ε⁵).

    Parameters
    ----------
    system : DynamicalSystem
        E·ẏ = f(y; p) (E diagonal; zero entries allowed).
    values : mapping
        Every parameter by name, and the ``unknowns`` where the equilibrium has no closed form.
    p_c, omega_c : float
        Estimates of the Hopf point, refined by Newton on det(iωE − J(p)) = 0 at ``dps`` digits.
    dps : int
        Working precision.

    Returns
    -------
    HopfResult
        With ``Lambda5`` = 2 Re c (critical mode's ``normalise`` component 1) and
        ``Im_c`` (gauge-dependent: h₂₁'s normalised component is 0).
    """
    jets = jets or Jets(system)
    with mpmath.workdps(dps):
        vals = numeric_values(system, values)
        nj = _NumericJets(system, jets, vals, max_order=5)
        fp_s, Jp_s = jets.parameter_derivatives()
        pexprs = [nj.expand(as_expr(x)) for x in fp_s] + [nj.expand(as_expr(x)) for row in Jp_s for x in row]
        syms = sorted(set().union(*(e.free_symbols for e in pexprs)) - {system.parameter}, key=lambda s: s.name)
        missing = [s.name for s in syms if s not in vals]
        if missing:
            raise InputError(f"{system.name}: no value for {', '.join(missing)}")
        pfn = lambdify_positional([system.parameter, *syms], pexprs, modules="mpmath")
        n = nj.n

        def det_eq(p, om):
            E, tens = nj.raw(p)
            A = mpmath.matrix(n, n)
            for i in range(n):
                A[i, i] = 1j * om * E[i]
            for (i, j), v in tens[1].items():
                A[i, j] -= v
            d = mpmath.det(A)
            return [mpmath.re(d), mpmath.im(d)]

        try:
            pc, wc = mpmath.findroot(det_eq, (mpmath.mpf(p_c), mpmath.mpf(omega_c)))
        except (ZeroDivisionError, ValueError) as exc:
            raise SingularPointError(f"{system.name}: Newton refinement of the Hopf point failed: {exc}") from None
        if not wc > 0:
            raise NoHopfError(f"{system.name}: no Hopf point near p = {p_c:g} (omega -> {float(wc):g})")
        E, tens = nj.raw(pc)
        J = [[mpmath.mpf(0)] * n for _ in range(n)]
        for (i, j), v in tens[1].items():
            J[i][j] = v
        pv = pfn(pc, *[vals[s] for s in syms])
        fp = [mpmath.mpf(x) for x in pv[:n]]
        Jp = [[mpmath.mpf(pv[n + i * n + j]) for j in range(n)] for i in range(n)]
        A = _pencil(J, E, wc)

        def absdet(rows):
            if not rows:
                return 1.0
            return float(abs(mpmath.det(mpmath.matrix([[mpmath.mpc(z.re, z.im) for z in r] for r in rows]))))

        r, c = best_drop(A, system.normalise, absdet)
        vec = null_vectors(J, E, wc, system.normalise, r, c)
        a = linear_coefficient(vec, J, Jp, fp, tens[2])
        bc = quintic_coefficient(vec, J, E, wc, {m: tens[m] for m in (2, 3, 4, 5)}, mpmath.mpf(1))
        eq = equilibrium_floats(system, pc, vals, dps)
        return HopfResult(
            system=system.name, parameter=system.parameter.name, p_c=float(pc), omega_c=float(wc),
            equilibrium=tuple(eq), dlambda_dp=complex(float(a.re), float(a.im)), Lambda=float(2 * bc.b.re),
            chi=float(2 * bc.b.im), convention=GENERAL, normalise=system.states[system.normalise].name,
            Lambda5=float(2 * bc.c.re), params={s.name: float(v) for s, v in vals.items()},
            Im_c=float(bc.c.im),
        )


# --------------------------------------------------------------------------------------
# the spring–block: Bautin points on the Hopf line k_c(V) and the fold of cycles in (V, k)
def _unit_mode_slip(d, params: Mapping[str, float], V: float, kc, omega, dps: int = 30) -> float:
    """|q_X| of the critical eigenvector of E⁻¹J normalised to ⟨q, q⟩ = 1 (the factor between landau's
    and Kuznetsov's normalisation)."""
    with mpmath.workdps(dps):
        # every compiled argument: V, the parameters and, without a closed-form steady state, φᵢ,₀
        vals = {s: mpmath.mpf(x) for s, x in zip(d.block.args, d.block.argvals(float(V), params), strict=True)}
        nj = _NumericJets(d.system, d.jets, vals, max_order=1)
        A, _, _ = nj.at(kc)
        ev, ER = mpmath.eig(A)
        i = min(range(len(ev)), key=lambda j: abs(ev[j] - mpmath.mpc(0, omega)))
        q = [ER[r, i] for r in range(A.rows)]
        return float(abs(q[d.system.normalise]) / mpmath.sqrt(sum(abs(z) ** 2 for z in q)))


def bautin_point(d, V: float, params: Mapping[str, float] | None = None, *, sign_below: int = 0,
                 sign_above: int = 0, rel_step: float = 1e-6) -> GeneralisedHopfPoint:
    """Λ₅, l₂ and the fold-of-cycles expansion at a codimension-two velocity V* of the spring–block.

    Parameters
    ----------
    d : Derivation
        The law's derivation (Λ₅ is built on first use).
    V : float
        A velocity where Λ = 0 on the Hopf line (e.g. from :func:`landau.analyses.transition.codim2_points`).
    params : mapping, optional
        Parameter overrides.
    sign_below, sign_above : int
        Signs of Λ just below and above V (as :func:`landau.analyses.transition.codim2_points` gives them).
    rel_step : float
        Relative step of the central difference for dΛ/dV.

    Returns
    -------
    GeneralisedHopfPoint
        p₁ = k_c, p₂ = V*, with Λ₅, l₂ = Λ₅ |q_X|⁴/2 (Re c₂ in Kuznetsov's normalisation; NaN for
        M = 0, a DAE), Re a = −Γ̄ and dΛ/dV, hence the fold of cycles
        k_fold − k_c(V) ≈ −Λ'²/(8Λ₅Γ̄)(V − V*)² with slip amplitude sqrt(2|Λ'|/|Λ₅|)|V − V*|^{1/2}.
    """
    from landau.derivation.linear import one_velocity

    V = one_velocity(V, "V", "bautin_points(d, lo, hi)")
    p = d.block.resolve(params)
    mp = d.evaluate_mp(V, p, ["Gamma_bar", "Lambda", "Lambda5"])
    h = V * rel_step
    lp = d.evaluate_mp(V + h, p, ["Lambda"])["Lambda"]
    lm = d.evaluate_mp(V - h, p, ["Lambda"])["Lambda"]
    dlam = float((lp - lm) / (2 * h))
    L5, gb = float(mp["Lambda5"]), float(mp["Gamma_bar"])
    if p["M"] > 0:
        qx = _unit_mode_slip(d, p, V, mp["kc"], mp["omega_c"])
        l2 = L5 * qx ** 4 / 2
    else:
        l2 = math.nan  # the quasi-static limit is a DAE: no Kuznetsov normalisation
    return GeneralisedHopfPoint(d.block.law.name, SPRING_BLOCK_PARAMETERS, float(mp["kc"]), float(V),
                                float(mp["omega_c"]),
                                Lambda5=L5, l2=l2, sign_below=sign_below, sign_above=sign_above, re_a=-gb,
                                dLambda_dp2=dlam)


def bautin_points(d, lo: float, hi: float, params: Mapping[str, float] | None = None) -> list[GeneralisedHopfPoint]:
    """Every Bautin point of the spring–block Hopf line with V in [lo, hi] (see :func:`bautin_point`)."""
    from landau.analyses.transition import codim2_points

    p = d.block.resolve(params)
    return [bautin_point(d, c.V, p, sign_below=c.sign_below, sign_above=c.sign_above)
            for c in codim2_points(d, lo, hi, p)]


def spring_block_fold(d, V: float, params: Mapping[str, float] | None = None) -> FoldOfCycles | None:
    """The fold of cycles at driving velocity V predicted from the quintic amplitude equation with the
    coefficients at V itself (k_fold = k_c − Λ²/(8Λ₅Γ̄); amplitude = max slip, m), or None where Λ and
    Λ₅ have the same sign."""
    from landau.derivation.linear import one_velocity

    V = one_velocity(V, "V", "a loop over V")
    p = d.block.resolve(params)
    mp = d.evaluate_mp(V, p, ["Gamma_bar", "Lambda", "Lambda5"])
    return fold_of_cycles(float(mp["Lambda"]), float(mp["Lambda5"]), -float(mp["Gamma_bar"]), float(mp["kc"]),
                          parameter="k")
