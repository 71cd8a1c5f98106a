"""Closed forms with symbolic parameters: FLINT's multivariate polynomials against sympy's
own rational-function field, measured side by side in one run (CPU seconds).

    python benchmarks/bench_closed_form.py [--budget SECONDS]

The sympy route is stopped after ``--budget`` CPU seconds (default 60): for the README's law
(Dieterich with residual strength c) it takes minutes.
"""

from __future__ import annotations

import argparse
import multiprocessing as mp
import time


def _run(law_name: str, route: str, out) -> None:
    from sympy import QQ
    from sympy.polys.fields import field

    import landau.derivation.rational as R
    from landau import SpringBlock, derive
    from landau.laws import FrictionLaw, get_law
    from landau.support import cache

    cache.set_enabled(False)
    if route == "sympy":
        R._field = lambda gens: field(list(gens), QQ)[0]
    if law_name == "readme":
        law = FrictionLaw.from_strings("my-law", mu="a_v + a*log(v/V_s) + b*log(c + V_s*phi/L)",
                                       state={"phi": "1 - v*phi/L"}, params={"c": 3e-4})
    else:
        law = get_law(law_name)
    d = derive(SpringBlock(law), ["Lambda"])
    _ = d.coefficient("Lambda").formula     # derive Λ (the symbolic cost), then time the closed form
    t = time.process_time()
    R.closed_form(d, "Lambda")
    out.put(time.process_time() - t)


def measure(law: str, route: str, budget: float) -> float | None:
    q: mp.Queue = mp.Queue()
    p = mp.Process(target=_run, args=(law, route, q))
    p.start()
    p.join(budget * 4)          # wall limit: a loaded machine gives the process a fraction of a core
    if p.is_alive():
        p.terminate()
        return None
    return q.get() if not q.empty() else None


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__)
    ap.add_argument("--budget", type=float, default=60.0)
    args = ap.parse_args()
    print(f"{'law':<12} {'FLINT [s]':>10} {'sympy [s]':>12} {'ratio':>8}")
    for law in ("dieterich", "ruina", "readme"):
        fast = measure(law, "flint", args.budget)
        slow = measure(law, "sympy", args.budget)
        ratio = f"{slow / fast:8.0f}" if slow and fast else f"> {args.budget / fast:.0f}" if fast else "-"
        print(f"{law:<12} {fast:10.2f} {slow if slow else float('nan'):12.2f} {ratio:>8}")


if __name__ == "__main__":
    main()
