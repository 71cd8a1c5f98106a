"""landau.fit on a two-step velocity record of 10⁴ samples with one state variable, warm (CPU and wall seconds).

    python benchmarks/bench_fit.py [--repeat N] [--samples N]

The record: the Dieterich (ageing) law with rsfmodel's README values (μ₀ = 0.6, a = 0.005,
b = 0.01, D_c = 10 µm, k′ = 1e-3/µm), load point 1 → 10 → 1 µm/s (steps at 20 s and 60 s, 120 s in
all), 10⁴ samples, Gaussian noise 1e-4; the fit of a_v, a, b, D_c starts 15-25 % off.  A first fit
builds and compiles the forward model (cold); the fits timed after it are warm (the goal: under
10 s).  Prints one line per fit and the median.
"""

from __future__ import annotations

import argparse
import statistics
import time

import numpy as np


def record(samples: int):
    from landau.lab.data import LabData
    from landau.lab.forward import forward_model
    from landau.laws import get_law

    law = get_law("dieterich")
    true = dict(a_v=0.6, a=0.005, b=0.01, L=10e-6, V_s=1e-6)
    t = np.linspace(0.0, 120.0, samples)
    V = np.where((t >= 20.0) & (t < 60.0), 10e-6, 1e-6)
    mu = forward_model(law, ()).run(t, V, true, 1e3).mu
    mu = mu + 1e-4 * np.random.default_rng(0).standard_normal(samples)
    x = np.concatenate([[0.0], np.cumsum(V[:-1] * np.diff(t))])
    return law, LabData(t, V, mu, x, "benchmark"), true


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--repeat", type=int, default=3)
    ap.add_argument("--samples", type=int, default=10_000)
    args = ap.parse_args()
    from landau.lab.fit import fit

    law, data, true = record(args.samples)
    start = {"V_s": 1e-6, "a_v": 0.6, "a": 0.006, "b": 0.0085, "L": 12.5e-6}
    walls, cpus = [], []
    for i in range(args.repeat + 1):
        w, c = time.perf_counter(), time.process_time()
        res = fit(data, law, k=1e3, params=start)
        w, c = time.perf_counter() - w, time.process_time() - c
        err = max(abs(res.params[n] - true[n]) / res.standard_errors[n] for n in res.names)
        print(f"{'cold' if i == 0 else 'warm'} fit: {w:.2f} s wall, {c:.2f} s CPU, {res.nfev} forward runs, "
              f"largest |error|/standard error {err:.2f}")
        if i:
            walls.append(w)
            cpus.append(c)
    print(f"median warm fit of {args.samples} samples: {statistics.median(walls):.2f} s wall, "
          f"{statistics.median(cpus):.2f} s CPU (goal < 10 s)")


if __name__ == "__main__":
    main()
