"""Cost of reaching the friction law through C callbacks in the forced oscillator of
Skurativskyi et al. (2019).

The event-driven loop of :mod:`landau.verify.skurativskyi.rk` is compiled once for every law;
the law reaches it as C callbacks (:mod:`landau.verify.skurativskyi.friction`), except the
paper's law c ẋ + T ẋ/sqrt(ẋ² + ε²) (eq. 1), which the field also holds compiled in
(:mod:`landau.verify.skurativskyi.field`).  This benchmark times, in the same process, the same
loop with the paper's law three ways — compiled in, through the callbacks generated from the law
object, through callbacks typed by hand (below) — on the work-precision problems (ω = 16, 20
periods; ω = 15, 2 periods; from rest at X₀; the top Lyapunov exponent at ω = 20.6), best of
``repeat`` process times, interleaved.  It prints the ratios to the compiled-in law (1 = no
cost) and checks that all three give the same final state (the same floating-point operations,
so max |Δy| = 0).

Run: ``python -m landau.verify.benchmarks.skurativskyi_friction_kernel [--repeat N]``.
"""

from __future__ import annotations

import argparse
import time

import numpy as np
from numba import cfunc, types

from landau.verify.skurativskyi import rk as R
from landau.verify.skurativskyi import simulate as S
from landau.verify.skurativskyi.friction import Callbacks, quiet_first_class
from landau.verify.skurativskyi.model import ILAW, Params, compiled_field

IC, IT, IEPS = ILAW, ILAW + 1, ILAW + 2      # the paper's law packs (c, T, eps) from ILAW on
_PTR = types.CPointer(types.float64)


def _hand_friction(v, p):
    eps = p[IEPS]
    return p[IC] * v + p[IT] * v / np.sqrt(v * v + eps * eps)


def _hand_derivative(v, p):
    eps = p[IEPS]
    s = v * v + eps * eps
    return p[IC] + p[IT] * eps * eps / (s * np.sqrt(s))


def _hand_subtract(a, v, p):
    eps = p[IEPS]
    return a - p[IC] * v - p[IT] * v / np.sqrt(v * v + eps * eps)


CASES = [("ω=16, 20 periods, rtol 1e-8", 16.0, 20, 1e-8, "mixed", False),
         ("ω=15, 2 periods, rtol 1e-8", 15.0, 2, 1e-8, "mixed", False),
         ("ω=16, explicit path, rtol 1e-8", 16.0, 20, 1e-8, "dopri5", False),
         ("ω=20.6, Lyapunov, rtol 1e-8", 20.6, 20, 1e-8, "mixed", True)]


def _loop(fr, p: Params, n: int, rtol: float, method: str, lyapunov: bool):
    y = S.rest_state(p)
    if lyapunov:
        y = np.concatenate([y, [1.0, 0.0]])
    at = np.array([rtol * 1e-4, rtol * 1e-2] + ([1e-9, 1e-9] if lyapunov else []))
    with quiet_first_class():
        return R.mixed_loop()(p.packed(), 0.0, y, n * p.period, rtol, at, 1e-5, p.period / 20, p.xI, True, 0.0,
                              p.period if lyapunov else 0.0, 1, lyapunov, 200_000, 50_000_000,
                              *S.METHODS[method], 0, fr)


def main(repeat: int = 7) -> list[str]:
    built_in = compiled_field(Params()).pointers
    one = types.float64(types.float64, _PTR)
    hand = (cfunc(one)(_hand_friction), cfunc(one)(_hand_derivative),
            cfunc(types.float64(types.float64, types.float64, _PTR))(_hand_subtract))
    ways = {"built-in": built_in, "generated": Callbacks(built_in[:3] + (False,) + built_in[4:]),
            "hand": Callbacks(hand + (False,) + built_in[4:])}
    lines = ["| problem | compiled in [ms] | generated callbacks / compiled in | hand callbacks / compiled in "
             "| max |Δy| |", "|---|---|---|---|---|"]
    for label, w, n, rtol, method, ly in CASES:
        p = Params(omega=w)
        best = dict.fromkeys(ways, np.inf)
        ends = {}
        for fr in ways.values():
            _loop(fr, p, 1, rtol, method, ly)          # compile / load
        for _ in range(repeat):
            for key, fr in ways.items():
                t0 = time.process_time()
                out = _loop(fr, p, n, rtol, method, ly)
                best[key] = min(best[key], time.process_time() - t0)
                ends[key] = out[1][:2]
        dy = max(float(np.max(np.abs(ends[k] - ends["built-in"]))) for k in ways)
        lines.append(f"| {label} | {best['built-in'] * 1e3:.2f} | {best['generated'] / best['built-in']:.3f} | "
                     f"{best['hand'] / best['built-in']:.3f} | {dy:.1e} |")
    return lines


if __name__ == "__main__":
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--repeat", type=int, default=7)
    print("\n".join(main(ap.parse_args().repeat)))
