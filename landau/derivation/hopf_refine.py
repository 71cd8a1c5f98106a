"""The Hopf point of a numeric system at the working precision, from its float64 location.

:func:`refine_hopf` is the last stage of every numeric Hopf route (:mod:`landau.derivation.general`,
the chains of :mod:`landau.analyses.chain`, the Hopf curves of :mod:`landau.analyses.continuation`):
the bisection of :func:`landau.derivation.general.locate_crossing` gives (p, ω, y₀) in float64, and
Newton's method on det(iωE − J) takes them to the digits of ``mpmath.mp.dps``.
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

import mpmath

from landau.errors import SingularPointError

if TYPE_CHECKING:
    from landau.derivation.general import NumericSystem

__all__ = ["REFINE_STEPS", "refine_hopf"]

#: most Newton steps of :func:`refine_hopf` (from a float64 start it takes two to four)
REFINE_STEPS = 30


def refine_hopf(num: NumericSystem, p0: float, omega0: float, y_guess) -> tuple[Any, Any, list]:
    """(p_c, ω_c, y₀) at the working precision: Newton's method on
    F(p, ω) = det(iωE(p) − J(y₀(p), p)) = 0 (its real and imaginary parts) from the float64 point.

    The Jacobian of (Re F, Im F) is taken by forward differences with steps 10^(−dps/2)·max(|x|, 1)
    for x = p, ω (relative for large values; absolute below 1, as ``mpmath.findroot`` took them: F's
    rounding is absolute at the scale of the matrix entries, so a step relative to a p_c that is
    zero to round-off would be lost in it).  The Jacobian's error, of that order, is the factor by
    which each iteration shrinks the distance to the root, so the float64 start (~1e-13) reaches
    the working precision in two or three iterations.  The step in ω moves no equilibrium (y₀ and
    J depend on p only): an iteration costs two equilibria, not three.  The iteration stops when
    the Newton step is below 10^(6−dps) on the same scales (the tolerance of
    :meth:`NumericSystem.equilibrium_mp`), or no longer halves once below the square root of it
    (the rounding floor of F).  The residual |F| is no criterion: F carries the determinant's
    scale (a product of n frequencies), which no fixed tolerance fits; ``mpmath.findroot``, used
    before, halved its last steps until they vanished on that criterion and evaluated F about
    twelve times where seven suffice.
    """
    n = num.n
    dps = mpmath.mp.dps
    tol = mpmath.mpf(10) ** (6 - dps)
    rel = mpmath.mpf(10) ** (-(dps // 2))
    p, om = mpmath.mpf(p0), mpmath.mpf(omega0)
    one = mpmath.mpf(1)
    y = [mpmath.mpf(x) for x in y_guess]

    def field_at(p, guess):
        y = num.equilibrium_mp(p, guess)
        return y, num.J_mp(y, p), num.E_mp(p)

    def F(om, J, E):
        A = mpmath.matrix(n, n)
        for i in range(n):
            for j in range(n):
                A[i, j] = 1j * om * E[i, j] - J[i, j]
        d = mpmath.det(A)
        return mpmath.re(d), mpmath.im(d)

    last = None
    for _ in range(REFINE_STEPS):
        y, J, E = field_at(p, y)
        fr, fi = F(om, J, E)
        hp, hw = rel * max(abs(p), one), rel * max(abs(om), one)
        _, Jh, Eh = field_at(p + hp, y)
        pr, pi = F(om, Jh, Eh)
        wr, wi = F(om + hw, J, E)
        a11, a21 = (pr - fr) / hp, (pi - fi) / hp          # ∂(Re F, Im F)/∂p
        a12, a22 = (wr - fr) / hw, (wi - fi) / hw          # ∂(Re F, Im F)/∂ω
        # [a11 a12; a21 a22] (Δp, Δω) = −(Re F, Im F), by Cramer's rule
        det = a11 * a22 - a12 * a21
        if det == 0:
            raise SingularPointError(f"{num.sys.name}: Newton refinement of the Hopf point failed: the "
                                     f"Jacobian of det(iωE − J) in ({num.p.name}, ω) is singular")
        dp = (-fr * a22 + fi * a12) / det
        dw = (-a11 * fi + a21 * fr) / det
        p, om = p + dp, om + dw
        size = max(abs(dp) / max(abs(p), one), abs(dw) / max(abs(om), one))
        if size <= tol or (last is not None and last <= mpmath.sqrt(tol) and size > last / 2):
            break
        last = size
    else:
        raise SingularPointError(f"{num.sys.name}: Newton refinement of the Hopf point did not converge in "
                                 f"{REFINE_STEPS} steps from {num.p.name} = {float(p0):.10g}")
    y0 = num.equilibrium_mp(p, y)
    return p, abs(om), y0
