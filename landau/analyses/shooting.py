"""Periodic orbits of a user's smooth system by shooting: the general route of :func:`landau.check`.

For a :class:`~landau.systems.system.DynamicalSystem` E·ẏ = f(y; p) near a Hopf point p_c, the
check measures the cycle at p = p_c + side·ε²·scale.  This module finds that cycle:

* the system's right-hand side, Jacobian and inverse mass matrix come from its one numeric field
  builder, :func:`landau.systems.numeric_field.numeric_field`;
* :func:`shoot` — one periodic orbit by Newton's method on the closure of the flow over a
  period, with its nontrivial Floquet multipliers (the solver contract is in its docstring);
* :class:`CycleShooter` — the cycles of one check: the seed from the critical eigenvector scaled
  by the predicted amplitude, a seed from a cycle already found at another ε² (scaled by the
  amplitude law A ∝ sqrt(ε²)), and natural continuation in ε² from the nearest cycle found.

Solver contract of :func:`shoot`
--------------------------------
Inputs: the field ``rhs(t, y)`` and its Jacobian ``jac(t, y)`` (E⁻¹ applied), a seed ``y0`` on
or near the cycle, a period estimate ``T0``, the anchor ``f(y0)`` of the phase condition, and
the integration tolerance ``rtol`` (absolute tolerance ``rtol·max(1e-12, max|z|)``).
Unknowns (z, T); equations y(T; z) − z = 0 (closure) and (z − y0)·f(y0) = 0 (phase anchor, which
removes the orbit's time-translation freedom), solved by MINPACK's hybrd to ``xtol`` 1e-11.
Outcome: ``(z, T, sol, mult)``, a point of the cycle, its period, the dense Radau solution over
one period and the n − 1 nontrivial Floquet multipliers (eigenvalues of the monodromy matrix of the
variational equations, :func:`monodromy`; the one closest to 1 dropped).  Accepted: a converged
solve whose closure max|y(T; z) − z| is at most 1e-7·max(1, max|z|), or a stalled one ("not making good progress",
when the seed is already within the integration's noise of the cycle) closed to the
integrator's own tolerance rtol·max(1e-12, max|z|) with a finite period above T0/2.
Failures (:class:`~landau.errors.IntegratorError`): "integration failed while shooting: <the
integrator's message>" and "shooting did not converge: <hybrd's message> (closure <value>)".

References
----------
Kuznetsov, Y. A. (2004). Elements of Applied Bifurcation Theory, 3rd ed., Springer, Ch. 10
(numerical analysis of limit cycles: the periodic boundary-value problem with a phase condition,
the monodromy matrix).
"""

from __future__ import annotations

import math
import warnings
from typing import Any, Callable, Iterator, Mapping

import numpy as np

from landau.errors import IntegratorError
from landau.systems.numeric_field import numeric_field

#: a seed generator: ``seeds(y0, jac)`` yields ``(start, T0)`` pairs to shoot from, around the
#: equilibrium ``y0``
Seeds = Callable[[np.ndarray, Callable], Iterator[tuple[np.ndarray, float]]]


def shoot(rhs, jac, y0: np.ndarray, T0: float, anchor_f: np.ndarray, rtol: float, flow=None):
    """Periodic orbit by Newton on (y(T; z) − z, (z − y0)·f(y0)) with the unknowns (z, T).

    Judged by the closure |y(T; z) − z|: hybrd stops "not making good progress" when its seed is already
    within the integration's noise of the cycle (Rayleigh, k = 9, ε² = 1e-3: closure 1e-17), so a stalled
    solve closed to the integrator's tolerance rtol·max|z| (period > T0/2) counts as converged.

    Parameters
    ----------
    rhs, jac : callable
        ``rhs(t, y)`` and ``jac(t, y)`` of the autonomous field ẏ = E⁻¹ f(y).
    y0 : numpy.ndarray
        The seed (a point on or near the cycle); also the anchor point of the phase condition.
    T0 : float
        The period estimate.
    anchor_f : numpy.ndarray
        f(y0), the normal of the phase condition (z − y0)·f(y0) = 0.
    rtol : float
        Relative tolerance of the Radau integration (absolute: rtol·max(1e-12, max|z|)); it also
        sets the closure accepted from a stalled solve.
    flow : callable, optional
        ``flow(z, T)``: the integration over [0, T] from z, with ``.y`` and dense output ``.sol``
        (:func:`landau.analyses.system_simulation.shooting_flow`, the compiled Radau IIA); default
        scipy's Radau on ``rhs``, ``jac``.

    Returns
    -------
    z : numpy.ndarray
        A point of the cycle.
    T : float
        Its period.
    sol : scipy.integrate.OdeResult
        The integration over one period from ``z``, with dense output.
    mult : numpy.ndarray
        The n − 1 nontrivial Floquet multipliers (complex).

    Raises
    ------
    IntegratorError
        "integration failed while shooting: …" when an integration fails, "shooting did not
        converge: … (closure …)" when the orbit does not close (see the module docstring).
    """
    import scipy.integrate
    import scipy.optimize

    n = y0.size

    def scipy_flow(z, T):
        sol = scipy.integrate.solve_ivp(rhs, (0.0, T), z, method="Radau", jac=jac, rtol=rtol,
                                        atol=rtol * max(1e-12, float(np.max(np.abs(z)))), dense_output=True)
        if sol.status != 0:
            raise IntegratorError(f"integration failed while shooting: {sol.message}")
        return sol

    flow = flow or scipy_flow

    def residual(u):
        z, T = u[:n], u[n]
        return np.append(flow(z, T).y[:, -1] - z, np.dot(z - y0, anchor_f))

    # Newton on F(u) = 0, u = (z, T), F = (y(T; z) − z, (z − y0)·f(y0)) by Powell's hybrid method
    # (MINPACK hybrd): each iteration solves the (n + 1) × (n + 1) system DF·Δu = −F (QR of DF, a
    # forward-difference Jacobian updated by Broyden's rank-one formula; the dogleg blends Δu
    # with the gradient step)
    res = scipy.optimize.root(residual, np.append(y0, T0), method="hybr", options={"xtol": 1e-11})
    z, T = res.x[:n], float(res.x[n])
    closure, size = float(np.max(np.abs(res.fun[:n]))), float(np.max(np.abs(z)))
    converged = closure <= 1e-7 * max(1.0, size) if res.success else \
        closure <= rtol * max(1e-12, size) and math.isfinite(T) and T > 0.5 * T0   # stalled on the cycle
    if not converged:
        raise IntegratorError(f"shooting did not converge: {' '.join(res.message.split())} (closure {closure:.3g})")
    sol = flow(z, T)
    mult = np.linalg.eigvals(monodromy(jac, sol, T, n, rtol))
    # drop the trivial multiplier (closest to 1)
    mult = np.delete(mult, int(np.argmin(np.abs(mult - 1.0))))
    return z, T, sol, mult


def monodromy(jac, sol, T: float, n: int, rtol: float) -> np.ndarray:
    """The monodromy matrix Φ(T) of the cycle ``sol`` (dense output over one period) by the variational
    equations Φ' = J(y(t)) Φ, Φ(0) = I, integrated along the cycle's dense output.

    Central differences of the flow took a step of 1e-6 (absolute) in every coordinate: larger than
    a small cycle itself (a chain's 3.4e-7 m), so the difference quotient left the linear range and
    called a stable cycle unstable.  The variational equations have no step: Φ(T) is exact to the
    integration's tolerance.  Φ is stored row by row (vec Φ, C order), so the Jacobian of the
    linear system is J ⊗ I.

    Integrated by LSODA (ODEPACK: Adams where the equations are not stiff, BDF with the Jacobian
    where they are; Hindmarsh 1983, Petzold 1983), whose step loop is compiled Fortran: scipy's
    Radau, stepped in Python, cost 0.2 CPU-s of a Brusselator check's 0.29 (1088 steps at rtol
    1e-10), LSODA brings the check to 0.05 CPU-s; the multipliers of the two agree to 5e-10 at
    rtol 1e-10 on the Brusselator and a rate-and-state block (``benchmarks/sections_usersystem.py``).
    """
    import scipy.integrate

    eye = np.eye(n)

    def rhs(t, phi):
        return (np.asarray(jac(t, sol.sol(t)), dtype=float) @ phi.reshape(n, n)).ravel()

    def rhs_jac(t, phi):
        return np.kron(np.asarray(jac(t, sol.sol(t)), dtype=float), eye)

    out = scipy.integrate.solve_ivp(rhs, (0.0, T), eye.ravel(), method="LSODA", jac=rhs_jac, rtol=rtol,
                                    atol=rtol)
    if out.status != 0:
        raise IntegratorError(f"integration failed along the cycle (its variational equations): {out.message}")
    return out.y[:, -1].reshape(n, n)


class CycleShooter:
    """The cycles of one check of a user system near its Hopf point.

    ``system`` with parameter values ``params``; ``pr`` the normal-form prediction
    (:class:`~landau.derivation.hopf.HopfResult`: ``p_c``, ``cycle_side``, ``omega_c``,
    ``amplitude(p)``, ``frequency(p)``, ``equilibrium``); ``scale`` turns ε² into a parameter
    distance, p = p_c + side·ε²·scale; ``rtol`` the shooting's tolerance.  Every cycle found is
    kept in ``cycles`` (ε² → (equilibrium, point on the cycle, period)) for the seeds of later
    shots.
    """

    def __init__(self, system, params: Mapping[str, float], pr, scale: float, rtol: float) -> None:
        self.system, self.pr, self.scale, self.rtol = system, pr, scale, rtol
        self.params = dict(params)
        self.f, self.J, self.E_inverse, self.vals = numeric_field(system, params)
        self.cycles: dict[float, tuple[np.ndarray, np.ndarray, float]] = {}

    def parameter(self, e: float) -> float:
        """The parameter value at ε² = ``e``: p_c + side·e·scale."""
        return self.pr.p_c + self.pr.cycle_side * e * self.scale

    def field_at(self, pp: float) -> tuple[Callable, Callable]:
        """``(rhs, jac)`` of ẏ = E⁻¹ f(y; pp) at the parameter value ``pp``."""
        f, J, vals = self.f, self.J, self.vals
        Einv = self.E_inverse(pp)
        return (lambda t, y: Einv @ np.asarray(f(*y, pp, *vals), dtype=float),
                lambda t, y: Einv @ np.asarray(J(*y, pp, *vals), dtype=float))

    def equilibrium(self, rhs) -> np.ndarray:
        """The equilibrium of ``rhs`` near the prediction's, by MINPACK's hybrd to xtol 1e-13."""
        import scipy.optimize

        with warnings.catch_warnings():
            warnings.simplefilter("ignore", RuntimeWarning)
            # Newton on rhs(y) = 0 by Powell's hybrid method (MINPACK hybrd): each iteration solves
            # J·Δy = −rhs(y) with a forward-difference, Broyden-updated J
            return scipy.optimize.fsolve(lambda y: rhs(0.0, y), np.asarray(self.pr.equilibrium, dtype=float),
                                         xtol=1e-13)

    def shoot_at(self, e: float, seeds: Seeds) -> tuple[np.ndarray, np.ndarray, float, Any, np.ndarray]:
        """The cycle at ε² = ``e`` from the first of ``seeds`` whose shot converges (:func:`shoot`):
        ``(y0, z, T, sol, mult)`` with the equilibrium ``y0``; the cycle is kept in ``cycles``.
        Raises :class:`~landau.errors.IntegratorError` with the last shot's message when none
        converges."""
        from landau.analyses.system_simulation import shooting_flow

        pp = self.parameter(e)
        rhs, jac = self.field_at(pp)
        y0 = self.equilibrium(rhs)
        flow = shooting_flow(self.system, {**self.params, self.pr.parameter: pp}, self.rtol)   # compiled Radau IIA
        last: Exception | None = None
        for start, T0 in seeds(y0, jac):
            try:
                z, T, sol, mult = shoot(rhs, jac, start, T0, rhs(0.0, start), self.rtol, flow)
            except (IntegratorError, ValueError, np.linalg.LinAlgError) as exc:
                last = exc
                continue
            self.cycles[e] = (y0, z, T)
            return y0, z, T, sol, mult
        raise IntegratorError(str(last) if last else "no seed")

    def from_mode(self, e: float) -> Seeds:
        """The seed of the amplitude equation at ε² = ``e``: the equilibrium plus the predicted
        amplitude times the critical eigenvector (normalised component = 1), with the predicted
        period."""
        pr, system = self.pr, self.system

        def seeds(y0, jac):
            pp = self.parameter(e)
            lam, vecs = np.linalg.eig(jac(0.0, y0))
            i = int(np.argmin(np.abs(lam.imag - pr.omega_c) + np.abs(lam.real)))
            q = vecs[:, i] / vecs[system.normalise, i]      # normalised component = 1
            yield y0 + pr.amplitude(pp) * np.real(q), 2 * np.pi / pr.frequency(pp)
        return seeds

    def from_cycle(self, e: float, known: float) -> Seeds:
        """The known cycle at ε² = known, scaled about the equilibrium by sqrt(e/known) (the amplitude law)."""
        y0k, zk, Tk = self.cycles[known]

        def seeds(y0, jac):
            yield y0 + (zk - y0k) * math.sqrt(e / known), Tk
        return seeds

    def continue_to(self, e: float):
        """Natural continuation in ε² from the nearest cycle already found (steps of a factor 2)."""
        cycles = self.cycles
        known = min(cycles, key=lambda c: abs(math.log(c / e)))
        steps = max(1, math.ceil(abs(math.log(e / known)) / math.log(2.0)))
        out = None
        for j in range(1, steps + 1):
            ej = known * (e / known) ** (j / steps)
            out = self.shoot_at(ej, self.from_cycle(ej, min(cycles, key=lambda c: abs(math.log(c / ej)))))
        return out
