"""Periodic orbits of the spring–block: shooting on a Poincaré section, Floquet multipliers.

Section Σ = {w = ln(v/V) = 0, w decreasing}: there ẋ = V and X = x − x₀ is at its
maximum, so every limit cycle (small Hopf cycles and stick–slip cycles alike) crosses it
once per period.  A point of Σ is z = (ξ, ψ…) (the scaled state without w).  The return
map P(z) and its derivative come from one integration of the state together with the
variational equations Φ' = J(y)Φ (:func:`landau.verify.springblock.model.compile_variational`);
the derivative of the map on Σ is the monodromy Φ(T) corrected for the change of return
time, DP = (I − f(y_T) e_wᵀ / f_w(y_T)) Φ(T) restricted to Σ.  Its eigenvalues are the
non-trivial Floquet multipliers.  Newton on P(z) − z = 0 (:func:`shoot`) converges to
stable and unstable cycles alike.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Callable

import numpy as np

from landau.errors import IntegratorError
from landau.verify.hybrid.analysis import ShootingError as _ShootingError
from landau.verify.hybrid.analysis import shoot_fixed_point
from landau.verify.hybrid.result import Status
from landau.verify.springblock.model import SpringBlockModel
from landau.verify.springblock.simulate import W_INDEX, integrate

ShootingError = _ShootingError  # the toolkit's error (one class: ``except`` works with either name)


@dataclass(frozen=True)
class PeriodicOrbit:
    """A periodic orbit of eq. (4) at (V, k): X = x − x₀ [m], v [m/s], period [s]."""

    V: float
    k: float
    period: float
    x_max: float
    x_min: float
    v_max: float
    v_min: float
    multipliers: tuple[complex, ...]
    newton_iterations: int
    residual: float
    z: np.ndarray = field(repr=False)

    @property
    def amplitude(self) -> float:
        """max|x − x₀| over the cycle [m] (the quantity of eq. 23)."""
        return max(self.x_max, -self.x_min)

    @property
    def stable(self) -> bool:
        return bool(max(abs(m) for m in self.multipliers) < 1.0)

    @property
    def frequency(self) -> float:
        return 2 * np.pi / self.period

    def __repr__(self) -> str:
        mults = ", ".join(f"{abs(m):.6g}" for m in self.multipliers)
        return (f"PeriodicOrbit(V={self.V:.4g}, k={self.k:.8g}, T={self.period:.6g} s, "
                f"max|x-x0|={self.amplitude:.6g} m, v in [{self.v_min:.3g}, {self.v_max:.3g}] m/s, "
                f"|multipliers|=[{mults}], {'stable' if self.stable else 'unstable'})")


def _on_section(model: SpringBlockModel, z: np.ndarray) -> np.ndarray:
    return np.insert(np.asarray(z, dtype=float), W_INDEX, 0.0)


def _off_section(y: np.ndarray) -> np.ndarray:
    return np.delete(np.asarray(y, dtype=float), W_INDEX)


def return_map(model: SpringBlockModel, z, *, rtol: float = 1e-10, t_max: float | None = None,
               monodromy: bool = True):
    """(P(z), DP or None, period [s], run) for the section w = 0, w decreasing."""
    n = model.n
    y0 = _on_section(model, z)
    if model.f(y0)[W_INDEX] >= 0:
        raise ShootingError(f"z = {z} is not a downward crossing of the section (dw/dt >= 0)")
    tmax = t_max if t_max is not None else 200.0 * _period_guess(model)
    if monodromy:
        y0 = np.concatenate([y0, np.eye(n).ravel()])
    run = integrate(model, y0, (0.0, tmax), rtol=rtol, atol=rtol * np.r_[np.ones(n), np.ones(n * n)][:len(y0)],
                    event_index=W_INDEX, event_direction=-1, stop_after=1, variational=monodromy)
    if run.status is not Status.STOPPED:
        raise ShootingError(f"no return to the section within {tmax:.3g} s (orbit left or decayed to steady sliding)")
    # the crossing itself (located on the dense output), not the end of the step that contains it
    yT_full = run.event_y[-1]
    T = float(run.event_t[-1])
    yT = yT_full[:n].copy()
    yT[W_INDEX] = 0.0
    DP = None
    if monodromy:
        Phi = yT_full[n:].reshape(n, n)
        fT = model.f(yT)
        S = np.eye(n) - np.outer(fT, np.eye(n)[W_INDEX]) / fT[W_INDEX]
        D = S @ Phi
        idx = [i for i in range(n) if i != W_INDEX]
        DP = D[np.ix_(idx, idx)]
    return _off_section(yT), DP, T, run


def _period_guess(model: SpringBlockModel) -> float:
    lam, _ = model.critical_mode()
    om = abs(lam.imag) / model.time_unit
    return 2 * np.pi / om if om > 0 else 1e3 * model.time_unit


def describe(model: SpringBlockModel, z, DP, period: float, run, iterations: int, residual: float) -> PeriodicOrbit:
    """Extremes over one period from a (non-variational) pass with recorded steps and crossings."""
    y0 = _on_section(model, z)
    r = integrate(model, y0, (0.0, 1.5 * period), rtol=1e-10, event_index=W_INDEX, event_direction=-1,
                  stop_after=1, record=200_000)
    xs = r.event_y[:, 0] * model.ell
    x_max = max(y0[0] * model.ell, float(xs.max()))
    x_min = float(xs.min()) if len(xs) else x_max
    w = r.y[W_INDEX]
    mults = tuple(complex(m) for m in np.linalg.eigvals(DP)) if DP is not None else ()
    return PeriodicOrbit(model.V, model.k, float(period), x_max, x_min, float(model.V * np.exp(w.max())),
                         float(model.V * np.exp(w.min())), mults, iterations, residual, np.asarray(z, dtype=float))


def shoot(model: SpringBlockModel, z_guess, *, rtol: float = 1e-10, tol: float = 1e-9,
          maxiter: int = 30) -> PeriodicOrbit:
    """Newton on P(z) − z = 0 with the exact monodromy; ``tol`` is relative to |z| (with floor 1e-6·ℓ)."""
    z = np.asarray(z_guess, dtype=float).copy()
    if model.f(_on_section(model, z))[W_INDEX] >= 0:
        z = first_return(model, _on_section(model, z))

    def pmap(zz):
        try:
            return return_map(model, zz, rtol=rtol)
        except IntegratorError as exc:
            raise ShootingError(f"shooting at k = {model.k:.8g}: {exc}") from exc

    # damp steps that would leave the section's domain (w must be decreasing there)
    fp = shoot_fixed_point(pmap, z, tol=tol, maxiter=maxiter,
                           admissible=lambda zz: model.f(_on_section(model, zz))[W_INDEX] < 0,
                           label=f"V = {model.V:.4g}, k = {model.k:.8g}")
    T, run = fp.extra
    return describe(model, fp.z, fp.DP, T, run, fp.iterations, fp.residual)


def first_return(model: SpringBlockModel, y0, rtol: float = 1e-10) -> np.ndarray:
    """The first downward crossing of Σ of the orbit through ``y0`` (a point of Σ)."""
    run = integrate(model, np.asarray(y0, dtype=float), (0.0, 200.0 * _period_guess(model)), rtol=rtol,
                    event_index=W_INDEX, event_direction=-1, stop_after=1)
    if run.status is not Status.STOPPED:
        raise ShootingError("the orbit through the initial guess never crosses the section downwards")
    return _off_section(run.event_y[-1])


def section_point(model: SpringBlockModel, amplitude: float) -> np.ndarray:
    """A point of Σ on the linear critical mode with X = ``amplitude`` [m] (initial guess near a Hopf point)."""
    _, vec = model.critical_mode()
    # phase where the w-component of a·Re(e^{iθ} vec) vanishes and ξ is maximal
    # e^{iθ}·vec_w purely imaginary  ⇒  w = 0 there, and ξ is extremal (ξ' = e^w − 1)
    th = np.pi / 2 - np.angle(vec[W_INDEX]) if abs(vec[W_INDEX]) > 0 else 0.0
    y = np.real(np.exp(1j * th) * vec)
    if y[0] < 0:
        y = -y
    y = y * (amplitude / model.ell) / y[0]
    return _off_section(y)


def leading_growth_rate(model: SpringBlockModel) -> float:
    """Largest real part of the eigenvalues of J at steady sliding (per unit of the scaled time τ).

    Parameters
    ----------
    model : SpringBlockModel

    Returns
    -------
    float
        Negative where steady sliding is linearly stable.
    """
    return float(np.max(np.linalg.eigvals(model.J(np.zeros(model.n))).real))


def hopf_parameter(make: Callable[[float], SpringBlockModel], lo: float, hi: float, *, xtol: float,
                   rtol: float) -> float:
    """The parameter q in [lo, hi] where the steady state of ``make(q)`` loses (or gains) stability:
    the root of :func:`leading_growth_rate` along the equilibrium branch, by Brent's method.

    Parameters
    ----------
    make : callable
        q -> SpringBlockModel.
    lo, hi : float
        A bracket: the growth rate changes sign between them.
    xtol, rtol : float
        Tolerances of :func:`scipy.optimize.brentq`.

    Returns
    -------
    float
    """
    from scipy.optimize import brentq

    return float(brentq(lambda q: leading_growth_rate(make(q)), lo, hi, xtol=xtol, rtol=rtol))


def hopf_stiffness(model: SpringBlockModel, k_lo: float, k_hi: float, rtol: float = 1e-13) -> float:
    """Stiffness where the steady state's leading eigenvalue pair crosses the imaginary axis
    (along the equilibrium branch in k, located by Brent's method on max Re λ(J(0; k)))."""
    return hopf_parameter(lambda kk: model.with_(k=kk), k_lo, k_hi, xtol=1e-14 * k_hi, rtol=rtol)
