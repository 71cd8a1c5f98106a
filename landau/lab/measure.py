"""What a laboratory reads off a protocol's run: Δμ_ss, the direct-effect peak, healing, relaxation.

On a velocity step V₁ → V₂ the friction first jumps with the slip rate (the direct effect, a
peak for V₂ > V₁) and then evolves over the memory length to the new steady state; for
Dieterich's law Δμ_ss = μ_ss(V₂) − μ_ss(V₁) = (a − b) ln(V₂/V₁) (Dieterich 1979; Ruina 1983).
On a slide-hold-slide test the friction relaxes during a hold (the block creeps on, unloading
the spring) and peaks on reloading above the steady state before the hold by Δμ_peak, which
grows with the hold time t_h (healing), about linearly in log₁₀ t_h for long holds (Dieterich
1972; Beeler, Tullis & Weeks 1994; Marone 1998).

* :func:`steady_state_change` — Δμ_ss across a step, μ at the end of the pieces after and before;
* :func:`direct_effect_peak` — the peak of μ after a step;
* :func:`hold_measures` — per hold: Δμ_peak on reloading and the relaxation during the hold;
* :func:`healing_rate` — the slope of Δμ_peak per decade of hold time (least squares in log₁₀ t_h).

A peak lies between the integrator's steps; read at the recorded points it is low by about
½|μ̈|(Δt/2)² (~1e-6 for a direct-effect peak at rtol 1e-9).  :func:`locate_peak` finds it
instead as the root of dμ/dt on the dense solution of the run
(:class:`~landau.verify.springblock.history_flow.HistoryFlow`: the state at any time an end
point of the compiled run, dμ/dt = ∇μ·y′ from the symbolic law) by Brent's method, bracketed by
the recorded points around the largest recorded μ.  At the root μ is stationary, so an error δt
in its time changes μ by ½|μ̈|δt² only: the peak is as accurate as the run.

References
----------
Dieterich, J. H. (1972), Time-dependent friction in rocks, J. Geophys. Res. 77, 3690–3697.
Dieterich, J. H. (1979), J. Geophys. Res. 84, 2161–2168.
Ruina, A. (1983), J. Geophys. Res. 88, 10359–10370.
Beeler, N. M., Tullis, T. E. & Weeks, J. D. (1994), The roles of time and displacement in the
evolution effect in rock friction, Geophys. Res. Lett. 21, 1987–1990.
Marone, C. (1998), Annu. Rev. Earth Planet. Sci. 26, 643–696.
Brent, R. P. (1973), Algorithms for Minimization without Derivatives, Prentice-Hall, ch. 4.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from landau.errors import InputError
from landau.lab.protocols import ProtocolRun


@dataclass(frozen=True)
class Peak:
    """A friction peak: its time [s], load-point displacement [m], μ, slip rate v [m/s] and the law's
    states there, located on the dense solution; ``mu_output`` is the largest μ at the run's recorded
    points (for comparison)."""

    t: float
    x_lp: float
    mu: float
    mu_output: float
    v: float
    states: tuple[float, ...]


@dataclass(frozen=True)
class HoldMeasure:
    """One hold of a slide-hold-slide run: its duration [s], μ at its start (the steady state before it),
    μ at its end, the relaxation μ_start − μ_end during it, the peak on reloading and
    Δμ_peak = μ_peak − μ_start."""

    hold: float
    mu_start: float
    mu_end: float
    relaxation: float
    peak: Peak
    dmu_peak: float


def _piece(run: ProtocolRun, i: int) -> tuple[float, float, float]:
    pieces = run.protocol.pieces()
    if not (0 <= i < len(pieces)):
        raise InputError(f"piece {i}: the protocol has pieces 0..{len(pieces) - 1}")
    return pieces[i]


def _end_index(run: ProtocolRun, t: float) -> int:
    """The recorded point at the end of the piece ending at ``t`` (the last one at or before ``t``)."""
    return int(np.searchsorted(run.sim.t, t, side="right") - 1)


def mu_at_end(run: ProtocolRun, i: int) -> float:
    """μ at the end of piece ``i`` (an end point of the compiled run)."""
    _, _, b = _piece(run, i)
    return float(run.column("mu")[_end_index(run, b)])


def steady_state_change(run: ProtocolRun, step: int = 1) -> float:
    """Δμ_ss across the step into piece ``step``: μ at the end of that piece minus μ at the end of the
    piece before (each the steady state where the pieces are long enough to settle)."""
    if step < 1:
        raise InputError(f"step {step}: a step is into piece 1 or later")
    return mu_at_end(run, step) - mu_at_end(run, step - 1)


def locate_peak(run: ProtocolRun, i: int) -> Peak:
    """The largest μ in piece ``i``, as the root of dμ/dt on the dense solution (module docstring).

    Raises
    ------
    InputError
        No interior maximum of μ in the piece (μ monotone there, or the peak at its end).
    """
    from scipy.optimize import brentq

    _, a, b = _piece(run, i)
    t, mu, flow = run.sim.t, run.column("mu"), run.flow
    idx = np.flatnonzero((t >= a) & (t <= b))
    j = int(idx[np.argmax(mu[idx])])
    # a peak rises above both ends of the piece by more than the run's error (a flat piece has none)
    rise = mu[j] - max(mu[idx[0]], mu[idx[-1]])
    if j in (idx[0], idx[-1]) or not rise > 100 * flow.rtol * max(1.0, abs(mu[j])):
        raise InputError(f"no peak of mu in piece {i} (t = {a:g} .. {b:g} s): mu is largest at the piece's "
                         f"{'end' if j == idx[-1] else 'start'}" if j in (idx[0], idx[-1]) else
                         f"no peak of mu in piece {i} (t = {a:g} .. {b:g} s): mu is flat there")

    def rate(k: int) -> float:
        return flow.mu_rate(t[k], flow.state_of(run.sim, k), i)

    g = rate(j)
    if g == 0:
        lo = hi = j
    elif g > 0:
        lo, hi = j, j + 1
    else:
        lo, hi = j - 1, j
    y_lo = flow.state_of(run.sim, lo)
    if lo == hi:
        t_pk = float(t[j])
    else:
        def drate(s: float) -> float:
            return flow.mu_rate(s, flow.advance(t[lo], y_lo, s), i)

        if not (rate(lo) > 0 > rate(hi)):
            raise InputError(f"no peak of mu in piece {i}: dmu/dt does not change sign around t = {t[j]:g} s")
        t_pk = float(brentq(drate, float(t[lo]), float(t[hi]), xtol=1e-15 * max(1.0, abs(t[hi])),
                            rtol=4 * np.finfo(float).eps, maxiter=200))
    y_pk = flow.advance(t[lo], y_lo, t_pk)
    return Peak(t_pk, float(run.protocol.history.displacement(t_pk)), flow.mu(y_pk), float(mu[j]),
                float(np.exp(y_pk[1])), tuple(float(x) for x in np.exp(y_pk[2:])))


def direct_effect_peak(run: ProtocolRun, step: int = 1) -> Peak:
    """The direct-effect peak of μ after the velocity step into piece ``step`` (:func:`locate_peak`)."""
    V, _, _ = _piece(run, step)
    if not V > _piece(run, step - 1)[0]:
        raise InputError(f"piece {step}: a direct-effect peak follows a step up in velocity")
    return locate_peak(run, step)


def hold_measures(run: ProtocolRun) -> list[HoldMeasure]:
    """Every hold (a piece at V = 0 between two slides): its relaxation and the peak on reloading."""
    pieces = run.protocol.pieces()
    out = []
    for i in range(1, len(pieces) - 1):
        V, a, b = pieces[i]
        if V != 0 or not pieces[i - 1][0] > 0 or not pieces[i + 1][0] > 0:
            continue
        start, end = mu_at_end(run, i - 1), mu_at_end(run, i)
        peak = locate_peak(run, i + 1)
        out.append(HoldMeasure(b - a, start, end, start - end, peak, peak.mu - start))
    if not out:
        raise InputError("the protocol has no hold between two slides (a slide-hold-slide test)")
    return out


def healing_rate(measures: list[HoldMeasure]) -> float:
    """dΔμ_peak/dlog₁₀ t_h: the least-squares slope of Δμ_peak against log₁₀ of the hold time."""
    if len({m.hold for m in measures}) < 2:
        raise InputError("the healing rate needs at least two different hold times")
    x = np.array([math.log10(m.hold) for m in measures])
    y = np.array([m.dmu_peak for m in measures])
    # the slope of the straight line through (log10 t_h, Δμ_peak) by least squares: the normal
    # equations of [x 1] β = y, solved by lstsq
    A = np.column_stack([x, np.ones_like(x)])
    beta = np.linalg.lstsq(A, y, rcond=None)[0]
    return float(beta[0])


__all__ = ["HoldMeasure", "Peak", "direct_effect_peak", "healing_rate", "hold_measures", "locate_peak",
           "mu_at_end", "steady_state_change"]
