"""Run every Galvanetto (2004) reproduction once and report value, published value, time.

``python -m landau.verify.benchmarks.galvanetto_reproductions`` (one core, default tolerances:
DOP853 rtol 1e-11).  Acceptance: all together under 60 s.
"""

from __future__ import annotations

import time

from landau.verify.galvanetto import bifurcations as B

CASES = [
    ("one-block type II (δ=0.2)", lambda: B.one_block_sliding("II", delta=0.2), "1.241 (Sec. 4.1)"),
    ("one-block type I (δ=0.2)", lambda: B.one_block_sliding("I", delta=0.2), "10.801 (Sec. 4.1)"),
    ("one-block type II (δ=0)", lambda: B.one_block_sliding("II", delta=0.0), "printed δ; gives ≈0.642"),
    ("one-block type I (δ=0)", lambda: B.one_block_sliding("I", delta=0.0), "printed δ; gives ≈4.424"),
    ("two-block type II", lambda: B.two_block_sliding("II", bracket=(0.18, 0.19), period=2), "(0.18, 0.19) Fig. 8"),
    ("two-block type I", lambda: B.two_block_sliding("I", bracket=(0.725, 0.74), period=1), "(0.725, 0.740) Fig. 9"),
    ("discontinuous fold", B.discontinuous_fold, "1.7217 Fig. 12"),
    ("period doubling", B.period_doubling, "1.7231 Fig. 12"),
    ("border collision", B.border_collision, "1.7236 Fig. 12"),
    ("boundary crisis", B.boundary_crisis, "tick label 1.7280 Fig. 12"),
    ("grazing-sliding", B.grazing_sliding, "(1.7652, 1.7656) Fig. 15"),
    ("multi-sliding", B.multi_sliding, "10.75265 Fig. 16"),
    ("damped one block c2", B.nonsmooth_fold_c2, "no number (Fig. 10c)"),
]


def main() -> None:
    total = 0.0
    print(f"{'case':28s} {'located':>18s}  {'published':26s} {'seconds':>8s}")
    for name, fn, pub in CASES:
        t0 = time.perf_counter()
        loc = fn()
        sec = time.perf_counter() - t0
        total += sec
        print(f"{name:28s} {loc.value:18.12f}  {pub:26s} {sec:8.2f}")
    h = B.hopf_c1_normal_form()
    print(f"c1 = F_k'(-V) = {B.hopf_c1():.12g} (closed form), engine {h.p_c:.12g}, "
          f"Lambda = {h.Lambda:.6g}: {h.criticality}")
    print(f"total {total:.1f} s")


if __name__ == "__main__":
    main()
