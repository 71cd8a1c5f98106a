"""Periodic orbits of the quasi-dynamic spring–block (M = 0, η > 0) and its bistability probe.

The cell of :mod:`landau.verify.springblock.quasidynamic` has the state y = (ξ, ψ₁, …, ψₙ)
(ξ = X/ℓ, ψᵢ = ln(φᵢ/φᵢ,₀)); the slip rate w = ln(v/V) follows from the force balance.  Its
Poincaré section is Σ = {w = 0, w decreasing}: there v = V and X is at its maximum, so every
cycle (small Hopf cycles and large stick–slip cycles alike) crosses it once per period, as the
section of the block with mass (:mod:`landau.verify.springblock.orbits`).  A point of Σ is
z = (ξ, ψ₂, …, ψₙ): ψ₁ follows from the force balance at v = V, R(0, ξ, ψ) = 0, a scalar root
(R is monotone in ψ₁ for a Dieterich-type first state).

* :func:`return_map` — the first return P(z) to Σ;
* :func:`find_cycle` — the cycle near a predicted amplitude: for one state the fixed point of the
  scalar map by Brent's method, for several states Newton shooting on P(z) − z = 0
  (:func:`shoot`) with the Jacobian DP by central differences (its eigenvalues are the
  non-trivial Floquet multipliers);
* :func:`fate` and :func:`settle` — the bistability probe of a subcritical point (the same
  procedure as the block with mass, :func:`landau.verify.springblock.checks.subcritical_check`):
  from a point of Σ on the linear critical mode, follow the maxima of X until they fall below a
  lower bound (decay to steady sliding) or grow past an upper one or settle on a larger cycle.

Every run is the cell's compiled Radau IIA in (ξ, w, ψ…) (:attr:`QuasiDynamicCell.kernel`,
:func:`landau.verify.springblock.compiled_runs.drive`): the crossings of w = 0 are located by the
compiled loop on its collocation cubic, and a run can stop at the first (or n-th) downward one.
"""

from __future__ import annotations

import math

import numpy as np

from landau.errors import InputError, IntegratorError, LandauError
from landau.verify.hybrid.analysis import ShootingError, shoot_fixed_point
from landau.verify.hybrid.radau import STATUS
from landau.verify.springblock.compiled_runs import drive
from landau.verify.springblock.orbits import PeriodicOrbit
from landau.verify.springblock.quasidynamic import QuasiDynamicCell, simulate_quasidynamic

#: relative step of the central differences of the return map (truncation ~h², round-off ~rtol/h)
FD_STEP = 1e-4


def linear_period(cell: QuasiDynamicCell) -> float:
    """2π/Im λ of the critical mode at steady sliding, in the scaled time τ (1e3 without rotation)."""
    lam, _ = cell.critical_mode()
    return 2 * math.pi / abs(lam.imag) if lam.imag else 1e3


def _dw(cell: QuasiDynamicCell, y) -> float:
    """dw/dτ at the state ``y`` (w from the force balance): −R_y·f / R_w."""
    w = cell.slip_rate(y)
    _, Rw, f, Ry, _, _ = cell._fn(w, *[float(q) for q in y])
    return -float(np.dot(Ry, f)) / Rw


def _psi1(cell: QuasiDynamicCell, xi: float, rest) -> float:
    """ψ₁ with w(ξ, ψ₁, rest) = 0 (v = V): the root of the force residual at w = 0."""
    from scipy.optimize import brentq

    rest = [float(q) for q in rest]

    def R(psi):
        return cell._fn(0.0, float(xi), float(psi), *rest)[0]

    lo, hi = -1.0, 1.0
    for _ in range(60):
        if R(lo) * R(hi) < 0:
            return float(brentq(R, lo, hi, xtol=1e-15, rtol=1e-15))
        lo, hi = 2 * lo, 2 * hi
    raise InputError(f"no state on the section v = V at X = {xi * cell.ell:g} m")


def on_section(cell: QuasiDynamicCell, z) -> np.ndarray:
    """The state y = (ξ, ψ₁, ψ₂, …) of the section point z = (ξ, ψ₂, …)."""
    z = np.atleast_1d(np.asarray(z, float))
    if z.shape != (cell.n - 1,):
        raise InputError(f"a point of the section has {cell.n - 1} coordinates (xi, psi_2..., the terms' states), "
                         f"got {z!r}")
    return np.r_[z[0], _psi1(cell, z[0], z[1:]), z[1:]]


def _off_section(y) -> np.ndarray:
    return np.r_[y[0], y[2:]]


def section_point(cell: QuasiDynamicCell, amplitude: float) -> np.ndarray:
    """A point z of Σ on the linear critical mode with X = ``amplitude`` [m] (a guess near a Hopf point).

    The phase of the mode is the one where its slip-rate component vanishes and ξ is maximal
    (w = −R_y·y/R_w to first order); ψ₁ is then put on Σ exactly (:func:`on_section`).
    """
    _, vec = cell.critical_mode()
    _, Rw, _, Ry, _, _ = cell._fn(0.0, *([0.0] * cell.n))
    vw = -np.dot(np.asarray(Ry, float), vec) / Rw
    th = math.pi / 2 - np.angle(vw) if abs(vw) > 0 else 0.0
    y = np.real(np.exp(1j * th) * vec)
    if y[0] < 0:
        y = -y
    y = y * (amplitude / cell.ell) / y[0]
    return _off_section(y)


def _run(cell: QuasiDynamicCell, y, t0: float, t1: float, rtol: float, ev_dir: int = 0, ev_stop: int = 0,
         events: bool = False):
    """The compiled run of the cell (:attr:`QuasiDynamicCell.kernel`, state (ξ, w, ψ…)) from the state
    ``y`` = (ξ, ψ…) over [t0, t1] (scaled time), the crossings of w = 0 located when ``events``."""
    y = np.asarray(y, float)
    z0 = np.r_[y[0], cell.slip_rate(y), y[1:]]
    run = drive(cell.kernel, cell.kernel_p, z0, t0, t1, rtol=rtol, atol=np.full(cell.n + 1, rtol),
                ev_idx=1 if events else -1, ev_dir=ev_dir, ev_stop=ev_stop)
    if run.status < 0:
        raise IntegratorError(f"quasi-dynamic cell (M = 0): {STATUS[run.status]} (state = xi, w, psi...)",
                              t=float(run.t * cell.time_unit), state=list(run.y))
    return run


def return_map(cell: QuasiDynamicCell, z, *, rtol: float = 1e-11, periods: float = 50.0):
    """First return to Σ (w = 0, w decreasing: v = V, X maximal).

    Parameters
    ----------
    cell : QuasiDynamicCell
    z : float or array_like
        The point of Σ: ξ = X/ℓ for a one-state law, (ξ, ψ₂, …) for several states.
    rtol : float
        Tolerance of the Radau IIA.
    periods : float
        Bound on the return time, in linear periods.

    Returns
    -------
    (float or ndarray, float, float)
        The return point (of the type of ``z``), the return time [s] and the smallest ξ on the way
        (at v = V, v rising).
    """
    scalar = np.ndim(z) == 0
    T = linear_period(cell)
    y0 = on_section(cell, z)
    # leave the section first (a quarter period without events), then stop at the next downward crossing
    first = _run(cell, y0, 0.0, 0.25 * T, rtol)
    sol = _run(cell, np.delete(first.y, 1), first.t, periods * T, rtol, ev_dir=-1, ev_stop=1, events=True)
    down = np.flatnonzero(sol.ev_dir < 0)
    if sol.status != 1 or not down.size:
        raise IntegratorError(f"no return to the section v = V within {periods:g} periods",
                              t=float(sol.t * cell.time_unit), state=list(sol.y))
    ups = sol.ev_y[sol.ev_dir > 0]
    x_min = min([float(q[0]) for q in ups] or [float(y0[0])])
    zr = _off_section(np.delete(sol.ev_y[down[0]], 1))
    return (float(zr[0]) if scalar else zr), float(sol.ev_t[down[0]] * cell.time_unit), x_min


def _map_error(cell: QuasiDynamicCell, z, exc) -> ShootingError:
    return ShootingError(f"quasi-dynamic return map at X = {np.ravel(z)[0] * cell.ell:.6g} m: {exc}")


def _jacobian(cell: QuasiDynamicCell, z: np.ndarray, rtol: float) -> np.ndarray:
    """DP(z) by central differences, step FD_STEP relative to |z|."""
    n = len(z)
    h = FD_STEP * max(float(np.linalg.norm(z)), 1e-12)
    D = np.empty((n, n))
    for j in range(n):
        e = np.zeros(n)
        e[j] = h
        D[:, j] = (return_map(cell, z + e, rtol=rtol)[0] - return_map(cell, z - e, rtol=rtol)[0]) / (2 * h)
    return D


def shoot(cell: QuasiDynamicCell, z_guess, *, rtol: float = 1e-11, tol: float = 1e-9,
          maxiter: int = 20) -> PeriodicOrbit:
    """Newton on P(z) − z = 0 from ``z_guess`` (a point of Σ; any number of states).

    The Jacobian DP is the central difference of the return map (:data:`FD_STEP`); its
    eigenvalues at the cycle are the Floquet multipliers.  Stable and unstable cycles alike.

    Raises
    ------
    ShootingError
        No convergence, or the orbit does not return to Σ.
    """
    z0 = np.atleast_1d(np.asarray(z_guess, float))

    def pmap(zz):
        try:
            return return_map(cell, zz, rtol=rtol)[0], _jacobian(cell, zz, rtol)
        except (IntegratorError, InputError) as exc:
            raise _map_error(cell, zz, exc) from exc

    def admissible(zz):
        try:
            return _dw(cell, on_section(cell, zz)) < 0
        except LandauError:
            return False

    fp = shoot_fixed_point(pmap, z0, tol=tol, maxiter=maxiter, admissible=admissible,
                           label=f"V = {cell.V:.4g}, k = {cell.k:.8g} (M = 0)")
    mults = tuple(complex(m) for m in np.linalg.eigvals(fp.DP))
    return _describe(cell, fp.z, mults, fp.iterations, fp.residual, rtol)


def _describe(cell: QuasiDynamicCell, z: np.ndarray, mults, iterations: int, residual: float | None,
              rtol: float) -> PeriodicOrbit:
    """The cycle through the point z of Σ: period, extremes of X and v over one period."""
    try:
        z_ret, T, z_min = return_map(cell, z, rtol=rtol)
        run = simulate_quasidynamic(cell.law, cell.V, cell.k, cell, T, on_section(cell, z), rtol=rtol)
    except (IntegratorError, InputError) as exc:
        raise _map_error(cell, z, exc) from exc
    v = run.y[1]
    z = np.atleast_1d(z)
    res = float(np.max(np.abs(np.atleast_1d(z_ret) - z))) if residual is None else residual
    return PeriodicOrbit(cell.V, cell.k, T, float(z[0]) * cell.ell, z_min * cell.ell, float(v.max()),
                         float(v.min()), tuple(mults), iterations, res, z)


def find_cycle(cell: QuasiDynamicCell, amplitude_guess: float, *, rtol: float = 1e-11) -> PeriodicOrbit:
    """The periodic orbit of the quasi-dynamic cell near X = ``amplitude_guess`` [m].

    One state: the fixed point of the return map to Σ by Brent's method on P(ξ) − ξ over a
    bracket grown from [0.7, 1.4]·guess, its Floquet multiplier the central difference of P.
    Several states: Newton shooting (:func:`shoot`) from the linear mode at the guessed amplitude.
    Stable and unstable cycles alike.

    Parameters
    ----------
    cell : QuasiDynamicCell
    amplitude_guess : float
        The predicted largest slip X of the cycle [m] (e.g. C·sqrt|k − k_c|).
    rtol : float
        Tolerance of the Radau IIA.

    Returns
    -------
    PeriodicOrbit
        As the compiled route's (:class:`landau.verify.springblock.orbits.PeriodicOrbit`), with one
        multiplier per state of the law.

    Raises
    ------
    ShootingError
        No fixed point of the return map, or the orbit does not return.
    """
    if cell.n > 2:     # several states (or a term's state): Newton on the section's return map
        return shoot(cell, section_point(cell, amplitude_guess), rtol=rtol)
    from scipy.optimize import brentq

    def g(z):
        try:
            return return_map(cell, z, rtol=rtol)[0] - z
        except (IntegratorError, InputError) as exc:
            raise _map_error(cell, z, exc) from exc

    x0 = amplitude_guess / cell.ell
    lo, hi = 0.7 * x0, 1.4 * x0
    glo, ghi = g(lo), g(hi)
    for _ in range(6):
        if glo * ghi < 0:
            break
        if abs(glo) < abs(ghi):
            lo, hi, ghi = 0.6 * lo, lo, glo
            glo = g(lo)
        else:
            lo, hi, glo = hi, 1.6 * hi, ghi
            ghi = g(hi)
    if not glo * ghi < 0:
        raise ShootingError(f"no cycle of the quasi-dynamic cell between X = {lo * cell.ell:.3g} and "
                            f"{hi * cell.ell:.3g} m (the return map has no fixed point there)")
    z = brentq(g, lo, hi, xtol=1e-13 * x0, rtol=1e-14)
    h = 1e-4 * z
    mult = (return_map(cell, z + h, rtol=rtol)[0] - return_map(cell, z - h, rtol=rtol)[0]) / (2 * h)
    return _describe(cell, np.array([z]), (complex(mult),), 0, None, rtol)


def _crossings(cell: QuasiDynamicCell, y, t: float, count: int, t_end: float, rtol: float):
    """The next ``count`` downward crossings of Σ from the state ``y`` at τ = ``t`` (before ``t_end``):
    (states (rows), times)."""
    T = linear_period(cell)
    first = _run(cell, y, t, t + 0.25 * T, rtol)
    sol = _run(cell, np.delete(first.y, 1), first.t, max(t_end, first.t + T), rtol, ev_dir=-1, ev_stop=count,
               events=True)
    down = sol.ev_dir < 0
    return np.delete(sol.ev_y[down], 1, axis=1), sol.ev_t[down]


def fate(cell: QuasiDynamicCell, z0, low: float, high: float, *, settle_above: float | None = None,
         chunk: int = 50, max_periods: int = 4000, trend: int | None = 3, rtol: float = 1e-8) -> tuple[str, np.ndarray]:
    """Where the orbit from the point ``z0`` of Σ goes: ('decays' | 'grows' | 'undecided', last point of Σ).

    'decays' when a maximum of X falls below ``low`` [m]; 'grows' when one exceeds ``high`` or the
    maxima settle (the last five within 1e-5 of each other) on a cycle larger than ``settle_above``
    (default 1.05 × the start) — the stick–slip attractor may be only a few times larger than the
    unstable cycle.  With ``trend``, also as soon as the maxima after the first crossing fall (decays) or
    rise (grows) ``trend`` times in a row, each by more than 1e-7 of X: for a one-state law the flow is
    planar and its return map to Σ a monotone map of one variable, so the maxima move monotonically
    from the unstable cycle to steady sliding or to the next cycle; with several states the other
    multipliers are small (the extra states relax within a period) and the same holds after a few
    crossings.  Integrated ``chunk`` crossings of Σ at a time, up to ``max_periods`` linear periods.
    """
    y = on_section(cell, z0)
    x_ref = settle_above if settle_above is not None else 1.05 * y[0] * cell.ell
    t_end = max_periods * linear_period(cell)
    t, xs = 0.0, []
    while t < t_end:
        rows, times = _crossings(cell, y, t, chunk, t_end, rtol)
        for row in rows:
            x = row[0] * cell.ell
            xs.append(x)
            if x < low:
                return "decays", _off_section(row)
            if x > high:
                return "grows", _off_section(row)
            if trend and len(xs) > trend + 1:
                d = np.diff(xs[-trend - 1:])
                if np.all(np.abs(d) > 1e-7 * abs(x)):
                    if np.all(d < 0):
                        return "decays", _off_section(row)
                    if np.all(d > 0):
                        return "grows", _off_section(row)
        if len(xs) >= 5 and xs[-1] > x_ref and max(xs[-5:]) - min(xs[-5:]) < 1e-5 * xs[-1]:
            return "grows", _off_section(rows[-1])
        if not len(rows):
            break
        y, t = rows[-1], float(times[-1])
    return "undecided", _off_section(y)


def settle(cell: QuasiDynamicCell, z, above: float, *, chunk: int = 5, max_periods: int = 4000) -> np.ndarray:
    """Follow the orbit from the point ``z`` of Σ until its maxima of X settle (the last five within 1e-5)
    on a cycle larger than ``above`` [m]; the last point of Σ (a start for shooting that attractor).

    Without the trend rule of :func:`fate`: near the unstable cycle the maxima move slowly, and only
    their settling far from it shows the attractor.

    Raises
    ------
    ShootingError
        The orbit did not settle above ``above`` within ``max_periods`` linear periods.
    """
    outcome, z = fate(cell, z, -math.inf, math.inf, settle_above=above, chunk=chunk, max_periods=max_periods,
                      trend=None)
    if outcome != "grows":
        raise ShootingError(f"the orbit did not settle on a cycle larger than X = {above:.3g} m within "
                            f"{max_periods} periods")
    return z


__all__ = ["find_cycle", "fate", "on_section", "return_map", "section_point", "settle", "shoot"]
