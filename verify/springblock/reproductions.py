"""Reproductions of Putelat et al. (2010) Figs 6, 11 and the codimension-two points (Figs 5b, 12, 14)
from periodic orbits alone (shooting + continuation, :mod:`landau.verify.springblock.continuation`).

    python -m landau.verify.springblock.reproductions [OUT_DIR]

writes fig6_ruina.png, fig6_dieterich.png, fig11_c1e-3.png, fig11_c3e-4.png and reproductions.json
(Hopf points vs the engine's k_c, folds, codimension-two velocities vs the engine's V*).
"""

from __future__ import annotations

import sys
import time
from pathlib import Path
from typing import Mapping

import numpy as np
from scipy.optimize import brentq

from landau.analyses.codim2 import FoldOfCycles
from landau.errors import NoHopfError
from landau.laws import get_law
from landau.support.io import atomic_write_json
from landau.verify.springblock.checks import predict
from landau.verify.springblock.continuation import (
    Branch,
    codim2_velocity,
    continue_in_k,
    continue_in_logV,
    fold_curve,
    plot_branch,
)
from landau.verify.springblock.model import SpringBlockModel
from landau.verify.springblock.orbits import hopf_stiffness

KAPPA_FIG11 = 1e-3
V_FIG6 = 1e-4  # V/V_* = 100


def _kc(law, V: float, params: Mapping[str, float] | None = None) -> float:
    """The engine's critical stiffness k_c at V (a spring-block Hopf result always carries it)."""
    kc = predict(law, V, params).kc
    assert kc is not None
    return kc


def fig6_branch(name: str, steps: int = 25) -> Branch:
    """Fig. 6: continuation in k at V/V_* = 100 (Ruina: supercritical; Dieterich: subcritical + fold)."""
    law = get_law(name)
    kc = _kc(law, V_FIG6)
    m = SpringBlockModel.build(law, V_FIG6, kc)
    return continue_in_k(m, 0.8 * kc, 1.2 * kc, steps=steps, lam_bounds=(0.5, 1.5))


def fig11_branch(c: float, steps: int = 60) -> Branch:
    """Fig. 11: spinodal law, κ = 1e-3, continuation in log V from the Hopf point near V_m."""
    law = get_law("spinodal")
    p = law.defaults()
    m = SpringBlockModel.from_dimensionless(law, p["V_s"] ** 2 / (9.81 * p["L"]), KAPPA_FIG11, 1000.0, {"c": c})
    # bracket the Hopf point near V_m with the engine's k_c(V) = k (the Hopf point itself is found from
    # the steady state's eigenvalues)
    f = lambda lv: _kc(law, 10 ** lv, {"c": c}) - m.k  # noqa: E731
    lvs = np.linspace(-5, -2.5, 60)
    vals = []
    for lv in lvs:
        try:
            vals.append(f(lv))
        except NoHopfError:
            vals.append(-m.k)  # velocity strengthening: no Hopf point, steady sliding stable (k_c = 0)
    vals = np.array(vals)
    i = [j for j in range(len(lvs) - 1) if np.isfinite(vals[j]) and np.isfinite(vals[j + 1])
         and np.sign(vals[j]) != np.sign(vals[j + 1])][-1]
    return continue_in_logV(m, 10 ** lvs[i], 10 ** lvs[i + 1], steps=steps, ds=0.05, ds_max=8.0,
                            lam_bounds=(-5.0, np.log10(10 ** lvs[i + 1]) + 0.5))


def fig12_fold_curve(c: float = 3e-4, branch: Branch | None = None) -> list[FoldOfCycles]:
    """Fig. 12: the fold of cycles continued in (V, κ) from the κ = 1e-3 fold of Fig. 11, towards the
    codimension-two point (larger κ) and to small κ (down to 5.6e-5)."""
    br = branch or fig11_branch(c, steps=45)
    if not br.folds:
        return []
    f = br.folds[0]
    base = SpringBlockModel.build(get_law("spinodal"), f.p_fold, br.points[0].orbit.k, {"c": c})
    up = fold_curve(base, f.p_fold, f.z, list(np.logspace(-3, -2.05, 12)))
    down = fold_curve(base, f.p_fold, f.z, list(np.logspace(-3, -4.25, 6)))
    return sorted(up + down[1:], key=lambda p: p.value("kappa"))


def plot_fig12(c: float, folds: list[FoldOfCycles], v_star: float, path: Path) -> Path:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    from landau.support.io import atomic_savefig

    law = get_law("spinodal")
    p = law.defaults()
    sigma = 1.2 * 9.81
    Vs = np.logspace(-7.5, np.log10(1.5e-3), 300)
    kap = []
    for V in Vs:
        try:
            kap.append(_kc(law, V, {"c": c}) * p["L"] / sigma)
        except NoHopfError:
            kap.append(np.nan)
    fig, ax = plt.subplots(figsize=(6, 4.5))
    ax.loglog(Vs / p["V_s"], kap, "k-", label="Hopf (engine k_c)")
    ax.loglog([f.p_fold / p["V_s"] for f in folds], [f.value("kappa") for f in folds], "b--o", ms=3,
              label="fold of cycles (continued in V, kappa)")
    ax.loglog([v_star / p["V_s"]], [_kc(law, v_star, {"c": c}) * p["L"] / sigma], "ko", mfc="w",
              label="codim-2 point (V*)")
    ax.set_xlabel("V / V*")
    ax.set_ylabel("kappa = kL/(Mg)")
    ax.set_title(f"Fig. 12 (spinodal, c = {c:g}): Hopf and fold-of-cycles loci", fontsize=9)
    ax.legend(fontsize=7)
    out = atomic_savefig(fig, path)
    plt.close(fig)
    return out


def codim2(name: str, params: dict, V_lo: float | None = None, V_hi: float | None = None):
    """(V* from periodic orbits, V* from the engine's Λ = 0) in [V_lo, V_hi]; without a window it
    comes from the model: the engine's first Λ = 0 point over 1e-5..1e2 V̂ (V̂ = sqrt(aσL/M),
    Putelat et al. 2010, eq. 31), ∓ 10 %."""
    law = get_law(name)
    if V_lo is None or V_hi is None:
        from landau.analyses.transition import codim2_points
        from landau.derivation.multiscale import Derivation
        from landau.systems.system import SpringBlock
        q = SpringBlock(law).resolve(params)
        v_hat = float(np.sqrt(q["a"] * q["sigma"] * q["L"] / q["M"]))
        pts = codim2_points(Derivation(SpringBlock(law)), 1e-5 * v_hat, 1e2 * v_hat, params)
        if not pts:
            raise NoHopfError(f"{name}: Λ does not change sign on the Hopf line for {params}")
        V_lo, V_hi = 0.9 * pts[0].V, 1.1 * pts[0].V

    def make(V):
        return SpringBlockModel.build(law, V, predict(law, V, params).kc, params)

    def hk(V):
        kc = predict(law, V, params).kc
        return hopf_stiffness(make(V), 0.9 * kc, 1.1 * kc)

    pt = codim2_velocity(make, hk, V_lo, V_hi)
    v_engine = brentq(lambda V: predict(law, V, params).Lambda, V_lo, V_hi, xtol=1e-16, rtol=1e-13)
    return pt, v_engine


def main(argv=None) -> int:
    argv = sys.argv[1:] if argv is None else argv
    out = Path(argv[0] if argv else "verify-out")
    out.mkdir(parents=True, exist_ok=True)
    doc: dict = {}
    t0 = time.time()
    for name in ("ruina", "dieterich"):
        br = fig6_branch(name)
        kc = _kc(get_law(name), V_FIG6)
        plot_branch(br, out / f"fig6_{name}.png", f"Fig. 6 ({name}): cycles vs k at V/V* = 100")
        doc[f"fig6_{name}"] = {"hopf_k": br.hopf_equilibrium, "engine_kc": kc,
                               "rel_diff": br.hopf_equilibrium / kc - 1, "hopf_from_branch": br.hopf_extrapolated,
                               "folds_k": [f.p_fold for f in br.folds]}
        print(name, doc[f"fig6_{name}"], flush=True)
    branches = {}
    for c in (1e-3, 3e-4):
        br = branches[c] = fig11_branch(c)
        plot_branch(br, out / f"fig11_c{c:g}.png", f"Fig. 11 (spinodal, c = {c:g}): cycles vs V at kappa = 1e-3")
        doc[f"fig11_c{c:g}"] = {"hopf_V": br.hopf_equilibrium, "folds_V": [f.p_fold for f in br.folds]}
        print(c, doc[f"fig11_c{c:g}"], flush=True)
    for name, params in (("dieterich", {}), ("modified-dieterich", {"c": 3e-4}), ("spinodal", {"c": 3e-4})):
        pt, ve = codim2(name, params)
        doc[f"codim2_{name}"] = {"V_orbits": pt.V, "k": pt.k, "V_engine": ve, "rel_diff": pt.V / ve - 1}
        print(name, doc[f"codim2_{name}"], flush=True)
    folds = fig12_fold_curve(3e-4, branches[3e-4])
    vs = doc["codim2_spinodal"]["V_engine"]
    plot_fig12(3e-4, folds, vs, out / "fig12_c3e-4.png")
    doc["fig12_c3e-4"] = {"fold_curve": [{"V": f.p_fold, "kappa": f.value("kappa"), "amplitude": f.amplitude}
                                         for f in folds],
                          "fold_end_V_vs_engine_Vstar": folds[-1].p_fold / vs - 1 if folds else None}
    print("fig12", doc["fig12_c3e-4"], flush=True)
    atomic_write_json(out / "reproductions.json", doc)
    print(f"wrote {out} in {time.time() - t0:.0f} s")
    return 0


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
