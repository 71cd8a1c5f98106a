"""Benchmark of the multiple-scales engine.  A script, not a test:

    python benchmarks/bench_engine.py [--points 1000000] [--baseline-points 300]

Prints, in one run:
1. derivation + compile seconds per built-in law (fresh interpreter per law, so no law
   profits from another's sympy cache; goal ≤ 2 s);
2. throughput of the vectorised Λ(V) (``Derivation.evaluate``) in points/s (goal ≥ 1e6): best
   of 3 repeated calls, and the first call on a fresh derivation (for the Dieterich, Ruina and
   modified Dieterich laws it includes deriving the exactly cancelled form, ~0.2 s);
3. the baseline: Λ evaluated point by point from Putelat et al. (2010) eqs (7)–(8),
   (11)–(19) and (21) written out directly with mpmath (``paper_lambda`` below: F = σμ,
   G = −dφ/dt and their partial derivatives F_V, F_φ, G_V, …, z, Y₀, Y₂, W₀, W₂, γ_F, γ_G,
   δ, β) — the same quantity, measured in the same run; and the ratio (goal ≥ 100×).

The baseline doubles as an independent check: it shares nothing with the engine (no
jets, no Fredholm module) and is asserted to agree with the engine's 50-digit value.
"""

from __future__ import annotations

import argparse
import subprocess
import sys
import time
from pathlib import Path

import mpmath
import numpy as np
import sympy as sp

sys.path.insert(0, str(Path(__file__).resolve().parent.parent / "tests"))

from vw_ranges import LAWS, vw_range  # noqa: E402

from landau.derivation.multiscale import derive  # noqa: E402
from landau.laws import get_law  # noqa: E402
from landau.laws.law import v as v_slip  # noqa: E402
from landau.systems.system import SpringBlock  # noqa: E402

ALL_LAWS = (*LAWS, "two-state-dieterich")
GOAL_DERIVE_S, GOAL_THROUGHPUT, GOAL_RATIO = 2.0, 1e6, 100.0

_DERIVE_SNIPPET = """
import time
t0 = time.perf_counter()
from landau.laws import get_law
from landau.systems.system import SpringBlock
from landau.derivation.multiscale import QUANTITIES, derive
t1 = time.perf_counter()
d = derive(SpringBlock(get_law({name!r})), list(QUANTITIES))
t2 = time.perf_counter()
d.evaluate([1e-5], {{}}, list(QUANTITIES))   # compiles every coefficient
t3 = time.perf_counter()
print(t2 - t1, t3 - t2)
"""


def derive_and_compile_seconds(name: str) -> tuple[float, float]:
    """(derivation s, compile s) for ``name`` in a fresh interpreter (imports excluded)."""
    out = subprocess.run([sys.executable, "-c", _DERIVE_SNIPPET.format(name=name)], capture_output=True,
                         text=True, check=True)
    a, b = map(float, out.stdout.split()[-2:])
    return a, b


class PaperLambda:
    """Λ of a one-state law from the paper's formulas (7), (8), (11)–(19), (21), with mpmath."""

    def __init__(self, name: str):
        law = get_law(name)
        if len(law.states) != 1:
            raise ValueError("the paper's formulas are for one state variable")
        block = SpringBlock(law)
        self.block = block
        phi = law.states[0]
        sigma = sp.Symbol("sigma", positive=True)
        F = sigma * law.mu                      # F(v, φ; σ) = σ μ (Sec. 3.1)
        G = -law.rates[0]                       # dφ/dt = −G (eq. 4)
        ss = law.steady_state_closed_form[0]
        ders = []
        for f in (F, G):
            for i, j in ((1, 0), (0, 1), (2, 0), (1, 1), (0, 2), (3, 0), (2, 1), (1, 2), (0, 3)):
                ders.append(sp.diff(f, *([v_slip] * i + [phi] * j)))
        ders = [e.subs(phi, ss) for e in ders]
        self.params = [p.symbol for p in law.parameters]
        self._f = sp.lambdify([v_slip, *self.params, sigma], ders, modules="mpmath")

    def __call__(self, V0, law_values, sigma, M) -> mpmath.mpf:
        (F_V, F_p, F_VV, F_Vp, F_pp, F_VVV, F_VVp, F_Vpp, F_ppp,
         G_V, G_p, G_VV, G_Vp, G_pp, G_VVV, G_VVp, G_Vpp, G_ppp) = self._f(V0, *law_values, sigma)
        I = mpmath.mpc(0, 1)
        Fss = F_V - F_p * G_V / G_p
        W2 = -G_p ** 2 * Fss / F_V                                   # eq. (8)
        if W2 <= 0:
            return mpmath.nan
        w = mpmath.sqrt(W2)
        kc = (F_p * G_V - F_V * G_p) * (1 + M * G_p / F_V)           # eq. (7)
        z = -I * w * G_V / (G_p + I * w)                             # eq. (11)
        zb = mpmath.conj(z)
        Y2 = [w ** 2 * F_VV / 2 - I * w * z * F_Vp - z ** 2 * F_pp / 2,
              w ** 2 * G_VV / 2 - I * w * z * G_Vp - z ** 2 * G_pp / 2]
        Y0 = [-w ** 2 * F_VV - I * w * (zb - z) * F_Vp - z * zb * F_pp,
              -w ** 2 * G_VV - I * w * (zb - z) * G_Vp - z * zb * G_pp]

        def solve(s, Y):                                             # W_l = M(s)⁻¹ Y_l, eq. (12)
            m11, m12 = M * s ** 2 + F_V * s + kc, F_p
            m21, m22 = G_V * s, s + G_p
            det = m11 * m22 - m12 * m21
            return [(m22 * Y[0] - m12 * Y[1]) / det, (m11 * Y[1] - m21 * Y[0]) / det]

        W21, W22 = solve(2 * I * w, Y2)
        W01, W02 = solve(0, Y0)

        def gamma(f_VV, f_Vp, f_pp, f_VVV, f_VVp, f_Vpp, f_ppp):     # eqs (15)–(16)
            return (2 * w ** 2 * W21 * f_VV + I * w * (W02 - W22 + 2 * zb * W21) * f_Vp + (z * W02 + zb * W22) * f_pp
                    + (I * w ** 3 * f_VVV + w ** 2 * (2 * z - zb) * f_VVp + I * w * z * (2 * zb - z) * f_Vpp
                       + zb * z ** 2 * f_ppp) / 2)

        gF = gamma(F_VV, F_Vp, F_pp, F_VVV, F_VVp, F_Vpp, F_ppp)
        gG = gamma(G_VV, G_Vp, G_pp, G_VVV, G_VVp, G_Vpp, G_ppp)
        delta = F_p * (z + G_V) - (G_p + I * w) * (F_V + 2 * I * w * M)   # eq. (17)
        beta = (G_p + I * w) * gF - F_p * gG                               # eq. (19)
        return 2 * mpmath.re(beta / delta)                                 # eq. (21)

    def at(self, V0: float, params: dict) -> mpmath.mpf:
        p = self.block.resolve(params)
        vals = [mpmath.mpf(p[s.name]) for s in self.params]
        return self(mpmath.mpf(V0), vals, mpmath.mpf(p["sigma"]), mpmath.mpf(p["M"]))


def throughput(name: str, n_points: int, n_base: int) -> tuple[float, float, float, float, float, float]:
    """(vectorised points/s, baseline points/s, max rel. diff paper-eqs vs engine, V_lo, V_hi,
    first-call points/s)."""
    lo, hi, ends = vw_range(name)
    lo, hi = (lo * (1 + 1e-3) if lo in ends else lo), (hi * (1 - 1e-3) if hi in ends else hi)
    d = derive(SpringBlock(get_law(name)), ["Lambda"])
    d.evaluate([np.sqrt(lo * hi)], {}, ["Lambda"])          # compile outside the timing
    # a quick probe first: if the full run would take more than ~30 s (e.g. many points fall
    # back to mpmath), measure on fewer points and say so
    probe = np.logspace(np.log10(lo), np.log10(hi), 10_000)
    t0 = time.perf_counter()
    d.evaluate(probe, {}, ["Lambda"])
    est = (time.perf_counter() - t0) / probe.size
    if est * n_points > 30:
        n_points = max(10_000, int(30 / est))
        print(f"   ({name}: {1 / est:.3g} points/s on a probe; timing on {n_points} points only)")
    Vs = np.logspace(np.log10(lo), np.log10(hi), n_points)
    # first call on a fresh derivation (compiled, but no exactly cancelled form cached yet):
    # what one large CLI or script call costs, including that form's derivation where used
    fresh = derive(SpringBlock(get_law(name)), ["Lambda"])
    fresh.evaluate([np.sqrt(lo * hi)], {}, ["Lambda"])
    t0 = time.perf_counter()
    fresh.evaluate(Vs, {}, ["Lambda"])
    first = n_points / (time.perf_counter() - t0)
    best = np.inf
    for _ in range(3 if est * n_points < 10 else 1):
        t0 = time.perf_counter()
        lam = d.evaluate(Vs, {}, ["Lambda"])["Lambda"]
        best = min(best, time.perf_counter() - t0)
    if not np.all(np.isfinite(lam)):
        raise AssertionError(f"{name}: non-finite Lambda inside the velocity-weakening range")
    paper = PaperLambda(name)
    Vb = np.logspace(np.log10(lo), np.log10(hi), n_base)
    with mpmath.workdps(15):
        t0 = time.perf_counter()
        for x in Vb:
            paper.at(float(x), {})
        tb = time.perf_counter() - t0
    # the baseline as an independent check: the paper's eqs at 30 digits vs the engine at 50
    worst = 0.0
    for x in Vb[:: max(1, n_base // 20)]:
        with mpmath.workdps(30):
            ref = paper.at(float(x), {})
        eng = d.evaluate_mp(float(x), {}, ["Lambda"])["Lambda"]
        worst = max(worst, float(abs(ref - eng) / abs(eng)))
    if worst > 1e-20:
        raise AssertionError(f"{name}: paper eqs (15)-(21) disagree with the engine (rel. {worst:.3g})")
    return n_points / best, n_base / tb, worst, lo, hi, first


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--points", type=int, default=1_000_000, help="points for the vectorised throughput")
    ap.add_argument("--baseline-points", type=int, default=300, help="points for the mpmath baseline")
    ap.add_argument("--law", default="all", help="one-state law for the throughput comparison, or 'all'")
    ap.add_argument("--skip-derive", action="store_true", help="skip the per-law derivation timing")
    args = ap.parse_args(argv)

    print("1. derivation + compile per built-in law (fresh interpreter; all 7 quantities)")
    print(f"   {'law':22s} {'derive s':>9s} {'compile s':>10s} {'total s':>8s}  goal <= {GOAL_DERIVE_S:g} s")
    for name in ([] if args.skip_derive else ALL_LAWS):
        a, b = derive_and_compile_seconds(name)
        print(f"   {name:22s} {a:9.2f} {b:10.2f} {a + b:8.2f}  {'ok' if a + b <= GOAL_DERIVE_S else 'MISSED'}")

    print(f"\n2./3. Lambda(V): vectorised ({args.points:.0e} log-spaced V in the velocity-weakening range, incl. "
          f"k_c, omega_c; best of 3) vs the paper's eqs (7)-(21) point by point with mpmath at 15 digits "
          f"({args.baseline_points} points)")
    print(f"   {'law':20s} {'V range (m/s)':>21s} {'vectorised pts/s':>17s} {'first call':>11s} "
          f"{'baseline pts/s':>15s} {'ratio':>8s}  {'paper eqs vs engine (30 vs 50 digits)':>38s}")
    laws = [args.law] if args.law != "all" else list(LAWS)
    for name in laws:
        rate, brate, worst, lo, hi, first = throughput(name, args.points, args.baseline_points)
        ok = "ok" if rate >= GOAL_THROUGHPUT and rate / brate >= GOAL_RATIO else "MISSED"
        print(f"   {name:20s} [{lo:9.3g}, {hi:9.3g}] {rate:17.3g} {first:11.3g} {brate:15.3g} {rate / brate:7.0f}x"
              f"  {worst:38.2g}  {ok}")
    print(f"   goals: >= {GOAL_THROUGHPUT:.0e} points/s, >= {GOAL_RATIO:g}x the baseline")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
