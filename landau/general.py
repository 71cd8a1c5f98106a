"""Hopf points and their amplitude equation for any smooth system E·ẏ = f(y; p).

The spring–block has closed forms; a general model (the slip mode of an impact
oscillator, a damped stick–slip block, …) has a numeric equilibrium and a Hopf
parameter that may move it.  :func:`hopf_normal_form` locates the Hopf point
(bracketing the real part of the critical eigenvalue pair, then Newton on
det(iωE − J(p)) = 0 at 50 digits) and runs the *same* Fredholm code as the
spring–block (:mod:`landau.fredholm`) on mpmath numbers.

Convention: dA/dT = a·(p − p_c)A + b·A|A|² with the critical mode's ``normalise``
component equal to 1; a = dλ/dp (the eigenvalue's speed across the axis),
Λ = 2 Re b (Λ < 0: supercritical), χ = 2 Im b.  The cycle's amplitude in the
normalised coordinate is max|y − y₀| ≈ C·sqrt|p − p_c|, C = 2 sqrt(2|Re a|/|Λ|), on
the side where Re a·(p − p_c) and Λ have opposite signs.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any, Mapping

import mpmath
import numpy as np
import scipy.linalg
import scipy.optimize
import sympy as sp

from landau.errors import InputError, NoHopfError, SingularPointError
from landau.fredholm import _pencil, best_drop, cubic_coefficient, linear_coefficient, null_vectors
from landau.jets import Jets
from landau.system import DynamicalSystem


@dataclass(frozen=True)
class HopfNormalForm:
    """A located Hopf point of a general system with its amplitude-equation coefficients."""

    system: str
    parameter: str
    p_c: float
    omega_c: float
    equilibrium: tuple[float, ...]
    dlambda_dp: complex
    Lambda: float
    chi: float
    normalise: str
    params: Mapping[str, float] = field(default_factory=dict)

    @property
    def criticality(self) -> str:
        if not np.isfinite(self.Lambda) or self.Lambda == 0:
            return "degenerate"
        return "supercritical" if self.Lambda < 0 else "subcritical"

    @property
    def C(self) -> float:
        """Amplitude coefficient: max|y_n − y₀,n| ≈ C·sqrt|p − p_c| (y_n the normalised state)."""
        return 2.0 * float(np.sqrt(2 * abs(self.dlambda_dp.real) / abs(self.Lambda)))

    @property
    def cycle_side(self) -> int:
        """+1 if the (stable or unstable) cycle exists for p > p_c, −1 for p < p_c."""
        return int(-np.sign(self.dlambda_dp.real * self.Lambda))

    def amplitude(self, p: float) -> float:
        """Predicted cycle amplitude of the normalised state at parameter p (NaN on the wrong side)."""
        d = p - self.p_c
        if np.sign(d) != self.cycle_side:
            return float("nan")
        return self.C * float(np.sqrt(abs(d)))

    def frequency(self, p: float) -> float:
        """Predicted cycle angular frequency ω_c + (Im a − χ Re a/Λ)(p − p_c)."""
        a = self.dlambda_dp
        return self.omega_c + (a.imag - self.chi * a.real / self.Lambda) * (p - self.p_c)

    def as_dict(self) -> dict[str, Any]:
        return {"system": self.system, "parameter": self.parameter, "p_c": self.p_c, "omega_c": self.omega_c,
                "equilibrium": list(self.equilibrium), "dRe_lambda_dp": self.dlambda_dp.real,
                "dIm_lambda_dp": self.dlambda_dp.imag, "Lambda": self.Lambda, "chi": self.chi, "C": self.C,
                "criticality": self.criticality, "normalise": self.normalise}

    def __repr__(self) -> str:
        return (f"HopfNormalForm({self.system}: {self.parameter}_c = {self.p_c:.10g}, ω_c = {self.omega_c:.6g}, "
                f"Λ = {self.Lambda:.6g} ({self.criticality}), C = {self.C:.6g})")

    def _repr_latex_(self) -> str:
        return (rf"${self.parameter}_c = {self.p_c:.10g},\ \omega_c = {self.omega_c:.6g},\ "
                rf"\Lambda = {self.Lambda:.6g}$ ({self.criticality})")


class _Numeric:
    """Numeric evaluation of a system's equilibrium and jets at given parameter values."""

    def __init__(self, system: DynamicalSystem, params: Mapping[str, float]):
        self.sys = system
        self.y0s = tuple(sp.Symbol(f"{s.name}__eq", real=True) for s in system.states)
        probe = DynamicalSystem(system.name, system.states, system.rhs, system.mass, system.parameter,
                                self.y0s, system.defaults, system.normalise)
        self.jets = Jets(probe)
        missing = [s.name for s in system.parameters if s.name not in params]
        if missing:
            raise InputError(f"{system.name}: missing parameter(s) {', '.join(missing)}")
        self.params = {s: params[s.name] for s in system.parameters}
        self.p = system.parameter
        self._f = sp.lambdify([*system.states, self.p, *self.params], list(system.rhs), "mpmath")
        self._J = sp.lambdify([*system.states, self.p, *self.params],
                              sp.Matrix(system.rhs).jacobian(system.states), "mpmath")
        self._eq = sp.lambdify([self.p, *self.params], list(system.equilibrium), "mpmath")
        self._E = sp.lambdify([*self.params], list(system.mass), "mpmath")
        if system.unknowns:
            raise InputError(f"{system.name}: numeric-unknown equilibria are not supported by the general route")

    def equilibrium(self, p) -> list:
        y0 = self._eq(p, *self.params.values())
        f = self._f(*y0, p, *self.params.values())
        scale = max(1.0, max(abs(float(x)) for x in y0))
        if max(abs(float(x)) for x in f) > 1e-8 * scale * max(1.0, max(abs(float(v)) for v in self.params.values())):
            # the declared equilibrium is not one: refine it with Newton (it must be close)
            y0 = list(mpmath.findroot(lambda *y: self._f(*y, p, *self.params.values()), y0))
        return list(y0)

    def jacobian(self, p) -> tuple[mpmath.matrix, list]:
        y0 = self.equilibrium(p)
        J = mpmath.matrix(self._J(*y0, p, *self.params.values()))
        return J, list(self._E(*self.params.values()))

    def atoms(self, y0, p) -> dict:
        subs = {**dict(zip(self.y0s, y0)), self.p: p, **self.params}
        return {a: mpmath.mpf(sp.N(e.xreplace({k: sp.Float(str(v), 60) for k, v in subs.items()}), 60))
                for a, e in self.jets.atoms.items()}


def _critical_real_part(num: _Numeric, p: float) -> tuple[float, float]:
    J, E = num.jacobian(mpmath.mpf(p))
    Jf = np.array(J.tolist(), dtype=float)
    Ef = np.diag(np.array([float(e) for e in E]))
    lam = scipy.linalg.eigvals(Jf, Ef)
    lam = lam[np.isfinite(lam) & (np.abs(lam.imag) > 1e-9 * (1 + np.abs(lam.real)))]
    if lam.size == 0:
        return -np.inf, np.nan
    i = int(np.argmax(lam.real))
    return float(lam[i].real), float(abs(lam[i].imag))


def hopf_normal_form(system: DynamicalSystem, params: Mapping[str, float], bracket: tuple[float, float],
                     dps: int = 50) -> HopfNormalForm:
    """Locate the Hopf point of ``system`` in its parameter inside ``bracket`` and derive its amplitude equation.

    ``bracket`` must contain exactly one crossing of the critical complex pair; the
    equilibrium is ``system.equilibrium`` (closed form in p and the parameters, refined
    by Newton if it is only approximate).

    Parameters
    ----------
    system : DynamicalSystem
        E·ẏ = f(y; p, q) with its Hopf parameter p.
    params : mapping of str to float
        Values of the other parameters q, by name.
    bracket : (float, float)
        An interval of p containing exactly one crossing of the critical pair.
    dps : int, optional
        Decimal digits of the refinement and of the coefficients (default 50).

    Returns
    -------
    HopfNormalForm
        p_c, ω_c, the equilibrium, a = dλ/dp, Λ and χ in landau's convention (the
        ``normalise`` component of the critical mode is 1), with the cycle amplitude C.

    Raises
    ------
    NoHopfError
        If the critical real part does not change sign over ``bracket``.
    SingularPointError
        If the Newton refinement of the Hopf point fails.

    References
    ----------
    Kuznetsov, Yu. A. (2004). Elements of Applied Bifurcation Theory, 3rd ed., Springer, §3.5.
    Putelat, T., Dawes, J. H. P., Willis, J. R. (2010). J. Mech. Phys. Solids 58, 27–53,
    Sec. 2.2 (the Fredholm route, written here for a general parameter).
    """
    num = _Numeric(system, params)
    lo, hi = map(float, bracket)
    rlo, _ = _critical_real_part(num, lo)
    rhi, _ = _critical_real_part(num, hi)
    if not (np.isfinite(rlo) and np.isfinite(rhi)) or rlo * rhi > 0:
        raise NoHopfError(f"{system.name}: no Hopf crossing of {system.parameter.name} in [{lo:g}, {hi:g}] "
                          f"(max Re λ = {rlo:.3g} and {rhi:.3g} at the ends)")
    p0 = scipy.optimize.brentq(lambda p: _critical_real_part(num, p)[0], lo, hi, xtol=1e-14, rtol=1e-14)
    w0 = _critical_real_part(num, p0)[1]
    with mpmath.workdps(dps):
        def det_eq(p, om):
            J, E = num.jacobian(p)
            n = len(E)
            A = mpmath.matrix(n, n)
            for i in range(n):
                for j in range(n):
                    A[i, j] = (1j * om * E[i] if i == j else 0) - J[i, j]
            d = mpmath.det(A)
            return [mpmath.re(d), mpmath.im(d)]

        try:
            pc, wc = mpmath.findroot(det_eq, (mpmath.mpf(p0), mpmath.mpf(w0)))
        except (ZeroDivisionError, ValueError) as exc:
            raise SingularPointError(f"{system.name}: Newton refinement of the Hopf point failed: {exc}") from None
        y0 = num.equilibrium(pc)
        for order in (1, 2, 3):
            num.jets.order(order)
        num.jets.parameter_derivatives()
        atoms = num.atoms(y0, pc)
        base = {**dict(zip(num.y0s, y0)), num.p: pc, **num.params}
        subs = {**{k: sp.Float(str(v), dps + 10) for k, v in base.items()},
                **{a: sp.Float(str(v), dps + 10) for a, v in atoms.items()}}

        def conv(e):
            if not isinstance(e, sp.Basic):
                return mpmath.mpf(e)
            return mpmath.mpf(sp.N(e.xreplace(subs), dps + 5))
        n = len(system.states)
        J1 = num.jets.jacobian()
        J = [[conv(J1[i][j]) for j in range(n)] for i in range(n)]
        E = [conv(e) for e in num._E(*num.params.values())]
        B2 = {k: conv(v) for k, v in num.jets.order(2).items()}
        C3 = {k: conv(v) for k, v in num.jets.order(3).items()}
        fp, Jp = num.jets.parameter_derivatives()
        fp = [conv(x) for x in fp]
        Jp = [[conv(x) for x in row] for row in Jp]
        A = _pencil(J, E, wc)

        def absdet(rows):
            if not rows:
                return 1.0
            m = mpmath.matrix([[mpmath.mpc(z.re, z.im) for z in r] for r in rows])
            return float(abs(mpmath.det(m)))

        r, c = best_drop(A, system.normalise, absdet)
        vec = null_vectors(J, E, wc, system.normalise, r, c)
        a = linear_coefficient(vec, J, Jp, fp, B2)
        b = cubic_coefficient(vec, J, E, wc, B2, C3, mpmath.mpf(1) / 2)
        return HopfNormalForm(
            system=system.name, parameter=system.parameter.name, p_c=float(pc), omega_c=float(wc),
            equilibrium=tuple(float(x) for x in y0), dlambda_dp=complex(float(a.re), float(a.im)),
            Lambda=float(2 * b.re), chi=float(2 * b.im), normalise=system.states[system.normalise].name,
            params=dict(params),
        )
