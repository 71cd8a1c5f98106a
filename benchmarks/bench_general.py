"""Cost of the general Hopf engine (Hopf point + first Lyapunov coefficient) against the state dimension n.

A dense test system (every component of f depends on every state, quadratic, cubic and
transcendental terms) is analysed for n = 2 … 7 by two routes measured side by side in one run:
the symbolic jets (sympy derivatives of the right-hand side, as the engine did before) and the
numeric Taylor jets (truncated multivariate Taylor arithmetic on the expression tree).  Prints the
times, their ratio, and the growth exponent d log t / d log n fitted over n = 3 … 7.

Run:  python benchmarks/bench_general.py [--max-n 7] [--json]
Timings are wall-clock on a shared machine: compare the two columns of one run, not runs.
"""

from __future__ import annotations

import argparse
import json
import time

import numpy as np
import sympy as sp


def dense_test_system(n: int, seed: int = 0):
    """A dense n-dimensional system ẏ = (A₀ + pI)y + N(y) with one Hopf point for p in (−1, 1).

    A₀ = −2I + a rotation in (y₁, y₂) + a small dense rational perturbation, so the rightmost
    eigenvalues are one complex pair near ±i; N has dense quadratic, cubic and tanh terms.
    """
    from landau.systems.system import DynamicalSystem

    rng = np.random.default_rng(seed)
    ys = sp.symbols(f"y1:{n + 1}", real=True)
    p = sp.Symbol("p", real=True)
    R = lambda lo, hi, den: sp.Rational(int(rng.integers(lo, hi + 1)), den)
    A = sp.Matrix(n, n, lambda i, j: R(-3, 3, 20))
    A += -2 * sp.eye(n)
    A[0, 0] += 2
    A[1, 1] += 2
    A[0, 1] += -1
    A[1, 0] += 1
    W = sp.Matrix(n, n, lambda i, j: R(-9, 9, 10))
    s = list(W * sp.Matrix(ys))
    rhs = []
    for i in range(n):
        lin = sum(A[i, j] * ys[j] for j in range(n)) + p * ys[i]
        nl = R(-5, 5, 10) * s[i] ** 2 + R(-5, 5, 10) * s[i] ** 3 + R(1, 5, 10) * sp.tanh(s[(i + 1) % n]) * s[i]
        rhs.append(sp.expand(lin) + nl)
    return DynamicalSystem(name=f"dense{n}", states=ys, rhs=tuple(rhs), mass=(sp.Integer(1),) * n,
                           parameter=p, equilibrium=(sp.Integer(0),) * n)


def _time(fn) -> float:
    t0 = time.perf_counter()
    fn()
    return time.perf_counter() - t0


def main(argv=None) -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--max-n", type=int, default=7)
    ap.add_argument("--min-n", type=int, default=2)
    ap.add_argument("--routes", default="taylor,symbolic")
    ap.add_argument("--json", action="store_true")
    a = ap.parse_args(argv)
    from landau.derivation.general import hopf_normal_form

    routes = a.routes.split(",")
    rows = []
    for n in range(a.min_n, a.max_n + 1):
        row = {"n": n}
        for route in routes:
            sysn = dense_test_system(n)
            row[route] = _time(lambda: hopf_normal_form(sysn, {}, (-1.0, 1.0), jets=route))
        rows.append(row)
        if not a.json:
            print(n, "  ".join(f"{r}={row[r]:.2f}s" for r in routes), flush=True)
    out = {"rows": rows}
    for route in routes:
        ns = np.array([r["n"] for r in rows if r["n"] >= 3], float)
        ts = np.array([r[route] for r in rows if r["n"] >= 3], float)
        if len(ns) >= 2:
            out[f"exponent_{route}"] = float(np.polyfit(np.log(ns), np.log(ts), 1)[0])
    if "symbolic" in routes and "taylor" in routes:
        out["ratio_symbolic_over_taylor"] = [r["symbolic"] / r["taylor"] for r in rows]
    print(json.dumps(out, indent=None if a.json else 1))


if __name__ == "__main__":
    main()
