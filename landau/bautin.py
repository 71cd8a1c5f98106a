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
(:func:`landau.fredholm.quintic_coefficient`: closed forms in the law's derivatives for the
spring–block through ``Derivation.coefficient("Lambda5")``, numbers here for any system) and
Kuznetsov's normal form with multilinear forms up to fifth order
(:func:`landau.lyapunov.lyapunov_coefficients`, which also reports l₂ as MatCont and
BifurcationKit print it).

References
----------
Kuznetsov, Yu. A. (2004). Elements of Applied Bifurcation Theory, 3rd ed., Springer, §8.3 (Bautin).
Putelat, T., Dawes, J. H. P., Willis, J. R. (2010). Regimes of frictional sliding of a spring–block
system. J. Mech. Phys. Solids 58, 27–53 (eq. 20; Figs 11–12: the fold of cycles).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any, Mapping

import mpmath
import numpy as np
import sympy as sp

from landau.cx import Cx, as_expr
from landau.errors import InputError, NoHopfError, SingularPointError
from landau.fredholm import _pencil, best_drop, linear_coefficient, null_vectors, quintic_coefficient
from landau.hopf import GENERAL, SPRING_BLOCK, HopfResult
from landau.jets import Jets
from landau.lyapunov import _NumericJets
from landau.system import DynamicalSystem


# --------------------------------------------------------------------------------------
# the fold of cycles of the truncated amplitude equation
@dataclass(frozen=True)
class FoldOfCycles:
    """The fold (saddle-node) of cycles predicted by the quintic amplitude equation.

    Parameters
    ----------
    p_fold : float
        Parameter value of the fold, p_c + Λ²/(8 Λ₅ Re a).
    p_c : float
        The Hopf point it belongs to.
    amplitude : float
        max|y_n − y₀,n| of the cycle at the fold (normalised component), sqrt(−2Λ/Λ₅).
    side : int
        +1 if the fold lies at p > p_c, −1 if at p < p_c.
    """

    p_fold: float
    p_c: float
    amplitude: float
    side: int

    @property
    def offset(self) -> float:
        """p_fold − p_c."""
        return self.p_fold - self.p_c

    def as_dict(self) -> dict[str, float]:
        return {"p_fold": self.p_fold, "p_c": self.p_c, "offset": self.offset, "amplitude": self.amplitude,
                "side": self.side}

    def __repr__(self) -> str:
        return (f"FoldOfCycles(p_fold = {self.p_fold:.10g} (p_c {'+' if self.offset >= 0 else '-'} "
                f"{abs(self.offset):.4g}), amplitude {self.amplitude:.4g})")


def fold_of_cycles(Lambda: float, Lambda5: float, re_a: float, p_c: float) -> FoldOfCycles | None:
    """The fold of cycles of Re a (p − p_c) + (Λ/2) r² + (Λ₅/2) r⁴ = 0, or None where there is none.

    Parameters
    ----------
    Lambda, Lambda5 : float
        Λ = 2 Re b and Λ₅ = 2 Re c (landau's convention).
    re_a : float
        Re a = d Re λ/dp (spring–block: −Γ̄).
    p_c : float
        The Hopf point.

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
    return FoldOfCycles(p_c + off, p_c, math.sqrt(-2.0 * Lambda / Lambda5), 1 if off > 0 else -1)


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
        ``extra["Im_c"]`` (gauge-dependent: h₂₁'s normalised component is 0).
    """
    jets = jets or Jets(system)
    by_name = {s.name: s for s in (*system.parameters, *system.unknowns)}
    with mpmath.workdps(dps):
        vals = {by_name[k]: mpmath.mpf(v) for k, v in values.items() if k in by_name}
        nj = _NumericJets(system, jets, vals, max_order=5)
        fp_s, Jp_s = jets.parameter_derivatives()
        pexprs = [nj.expand(as_expr(x)) for x in fp_s] + [nj.expand(as_expr(x)) for row in Jp_s for x in row]
        syms = sorted(set().union(*(e.free_symbols for e in pexprs)) - {system.parameter}, key=lambda s: s.name)
        missing = [s.name for s in syms if s not in vals]
        if missing:
            raise InputError(f"{system.name}: no value for {', '.join(missing)}")
        pfn = sp.lambdify([system.parameter, *syms], pexprs, modules="mpmath")
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
        eq = []
        for e in system.equilibrium:
            e = as_expr(e).xreplace({system.parameter: sp.Float(str(pc), dps)})
            e = e.xreplace({s: sp.Float(str(v), dps) for s, v in vals.items()})
            try:
                eq.append(float(e))
            except TypeError:
                eq.append(float("nan"))
        return HopfResult(
            system=system.name, parameter=system.parameter.name, p_c=float(pc), omega_c=float(wc),
            equilibrium=tuple(eq), dlambda_dp=complex(float(a.re), float(a.im)), Lambda=float(2 * bc.b.re),
            chi=float(2 * bc.b.im), convention=GENERAL, normalise=system.states[system.normalise].name,
            Lambda5=float(2 * bc.c.re), params={s.name: float(v) for s, v in vals.items()},
            extra={"Im_c": float(bc.c.im)},
        )
