"""Cost of the law-generated friction term in the forced oscillator of Skurativskyi et al. (2019).

The model's field is compiled from its friction law (:mod:`landau.verify.skurativskyi.friction`).
This benchmark builds, in the same process, the same event-driven integrators over a field with
the paper's friction c ẋ + T ẋ/sqrt(ẋ² + ε²) (eq. 1) typed by hand in numba (below), and
times both on the work-precision problems (ω = 16, 20 periods; ω = 15, 2 periods; from rest at
X₀; the top Lyapunov exponent at ω = 20.6), best of ``repeat`` process times, interleaved.  It
prints the ratio generated / hand-written (1 = no cost) and checks that both give the same final
state (the generated field does the same floating-point operations for the paper's law, the
stick-phase partials included — they subtract the friction's terms one by one —, so max |Δy| = 0).

Run: ``python -m landau.verify.benchmarks.skurativskyi_friction_kernel [--repeat N]``.
"""

from __future__ import annotations

import argparse
import time

import numpy as np
from numba import njit

from landau.verify.skurativskyi import rk as R
from landau.verify.skurativskyi import simulate as S
from landau.verify.skurativskyi.model import IB, IK, IKI, IM, IM0E, IN1, IN2, IN3, ILAW, IOM, IVF, IXI, Params
from landau.verify.skurativskyi.sdirk import cusp_sdirk_method

IC, IT, IEPS = ILAW, ILAW + 1, ILAW + 2      # the paper's law packs (c, T, eps) from ILAW on


@njit(cache=True)
def _contact(x, v, p):
    d = x - p[IXI]
    if d <= 0.0:
        return 0.0
    sv = 1.0 if v > 0 else (-1.0 if v < 0 else 0.0)
    f = d ** p[IN1] + p[IB] * d ** p[IN2] * sv * abs(v) ** p[IN3]
    return p[IKI] * f if f > 0.0 else 0.0


@njit(cache=True)
def hand_accel(t, x, v, p):
    eps = p[IEPS]
    fr = p[IC] * v + p[IT] * v / np.sqrt(v * v + eps * eps)
    om = p[IOM]
    return (p[IM0E] * om * om * np.sin(om * t) - p[IK] * x - fr - _contact(x, v, p)) / p[IM]


@njit(cache=True)
def hand_grad(t, x, v, p):
    eps = p[IEPS]
    s = v * v + eps * eps
    dv = -(p[IC] + p[IT] * eps * eps / (s * np.sqrt(s)))
    dx = -p[IK]
    d = x - p[IXI]
    if d > 0.0:
        av = abs(v)
        sv = 1.0 if v > 0 else (-1.0 if v < 0 else 0.0)
        pw = av ** p[IN3]
        f = d ** p[IN1] + p[IB] * d ** p[IN2] * sv * pw
        if f > 0.0:
            dx -= p[IKI] * (p[IN1] * d ** (p[IN1] - 1.0) + p[IB] * p[IN2] * d ** (p[IN2] - 1.0) * sv * pw)
            dv -= p[IKI] * p[IB] * d ** p[IN2] * p[IN3] * max(av, p[IVF]) ** (p[IN3] - 1.0)
    return dx / p[IM], dv / p[IM]


@njit(cache=True)
def hand_partials(t, x, v, p):
    eps = p[IEPS]
    s = v * v + eps * eps
    rs = np.sqrt(s)
    om = p[IOM]
    m = p[IM]
    a = p[IM0E] * om * om * np.sin(om * t) - p[IK] * x - p[IC] * v - p[IT] * v / rs
    av = -(p[IC] + p[IT] * eps * eps / (s * rs)) / m
    ax = -p[IK]
    kap = 0.0
    d = x - p[IXI]
    if d > 0.0:
        sv = 1.0 if v > 0 else (-1.0 if v < 0 else 0.0)
        pw = abs(v) ** p[IN3]
        dn2 = d ** p[IN2]
        f = d ** p[IN1] + p[IB] * dn2 * sv * pw
        if f > 0.0:
            a -= p[IKI] * f
            ax -= p[IKI] * (p[IN1] * d ** (p[IN1] - 1.0) + p[IB] * p[IN2] * d ** (p[IN2] - 1.0) * sv * pw)
            kap = p[IKI] * p[IB] * dn2 / m
    return a / m, ax / m, av, kap


@njit(cache=True)
def _rhs2(t, y, p, out):
    out[0] = y[1]
    out[1] = hand_accel(t, y[0], y[1], p)


@njit(cache=True)
def _rhs4(t, y, p, out):
    out[0] = y[1]
    out[1] = hand_accel(t, y[0], y[1], p)
    ax, av = hand_grad(t, y[0], y[1], p)
    out[2] = y[3]
    out[3] = ax * y[2] + av * y[3]


@njit(cache=True)
def hand_rhs(t, y, p, out):
    # structured as the field was before it was generated from the law (rhs -> rhs2 | rhs4)
    if y.shape[0] == 4:
        _rhs4(t, y, p, out)
    else:
        _rhs2(t, y, p, out)


CASES = [("ω=16, 20 periods, rtol 1e-8", 16.0, 20, 1e-8, "mixed", False),
         ("ω=15, 2 periods, rtol 1e-8", 15.0, 2, 1e-8, "mixed", False),
         ("ω=16, explicit path, rtol 1e-8", 16.0, 20, 1e-8, "dopri5", False),
         ("ω=20.6, Lyapunov, rtol 1e-8", 20.6, 20, 1e-8, "mixed", True)]


def _loop(integrate_mixed, p: Params, n: int, rtol: float, method: str, lyapunov: bool):
    y = S.rest_state(p)
    if lyapunov:
        y = np.concatenate([y, [1.0, 0.0]])
    at = np.array([rtol * 1e-4, rtol * 1e-2] + ([1e-9, 1e-9] if lyapunov else []))
    return integrate_mixed(p.packed(), 0.0, y, n * p.period, rtol, at, 1e-5, p.period / 20, p.xI, True, 0.0,
                           p.period if lyapunov else 0.0, 1, lyapunov, 200_000, 50_000_000,
                           *S.METHODS[method], 0)


def main(repeat: int = 7) -> list[str]:
    _, hand_sdirk = cusp_sdirk_method(hand_partials, hand_grad, IN3)
    _, hand_mixed = R.switching_integrator(hand_rhs, hand_sdirk)
    _, gen_mixed = S.integrators(Params())
    lines = ["| problem | hand-written [ms] | generated from the law [ms] | generated / hand | max |Δy| |",
             "|---|---|---|---|---|"]
    for label, w, n, rtol, method, ly in CASES:
        p = Params(omega=w)
        best = {"hand": np.inf, "gen": np.inf}
        ends = {}
        for fn in (hand_mixed, gen_mixed):
            _loop(fn, p, 1, rtol, method, ly)          # compile / load
        for _ in range(repeat):
            for key, fn in (("hand", hand_mixed), ("gen", gen_mixed)):
                t0 = time.process_time()
                out = _loop(fn, p, n, rtol, method, ly)
                best[key] = min(best[key], time.process_time() - t0)
                ends[key] = out[1][:2]
        dy = float(np.max(np.abs(ends["gen"] - ends["hand"])))
        lines.append(f"| {label} | {best['hand'] * 1e3:.2f} | {best['gen'] * 1e3:.2f} | "
                     f"{best['gen'] / best['hand']:.3f} | {dy:.1e} |")
    return lines


if __name__ == "__main__":
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--repeat", type=int, default=7)
    print("\n".join(main(ap.parse_args().repeat)))
