"""Fig. 17: micron-scale contact law (50) — (a) μ_ss (51), (b) k_c, (c) Λ for c = 2.5e-2 and
1.4e-2 (for c = 1.4e-2: V_l* ≈ 1.039e-5, V_h* ≈ 2.07e-4 m/s; Λ ≥ 0 at low velocity).
Table 1 (L = 0.9e-6 m; the caption's L = 1e-6 contradicts it and does not reproduce the paper's numbers)."""

from __future__ import annotations

from pathlib import Path

from landau.paper_figures.putelat2010.fig15 import kc_panel, lambda_panel, make_law_figure  # noqa: F401

LAW = "micron-scale"
CASES = {"c = 2.5e-2": {"c": 2.5e-2}, "c = 1.4e-2": {"c": 1.4e-2}}


def make(out_dir: Path) -> list[Path]:
    return make_law_figure(out_dir, "fig17", LAW, CASES,
                           "Putelat et al. (2010) Fig. 17 — micron-scale contact law (50), M = 1.2 kg")
