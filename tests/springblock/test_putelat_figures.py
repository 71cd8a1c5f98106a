"""Putelat et al. (2010) figures: key features asserted on the computed data (not on images)."""

from __future__ import annotations

import math

import numpy as np
import pytest

from landau.analyses.transition import transition_curve
from landau.paper_figures.putelat2010 import FIGURES, fig4, fig5, fig8, fig9, fig10, fig13, fig14, fig15, fig17
from landau.paper_figures.putelat2010._common import derivation, fresh

a, b, L, M, s = 0.0349, 0.0489, 0.9e-6, 1.2, 11.772


def test_figure_table_lists_every_requested_figure():
    assert list(FIGURES) == ["fig4", "fig5", "fig8", "fig9", "fig10", "fig13", "fig14", "fig15", "fig17"]


@pytest.mark.parametrize("panel, law", [(fig9.kc_panel, "spinodal"), (fig10.kc_panel, "spinodal"),
                                        (fig15.kc_panel, "nanoscale")])
def test_kc_panels_never_build_cubic_derivatives(panel, law):
    d = fresh(law)
    out = panel(d)
    assert out  # computed something
    assert 3 not in d.jets.built and 2 not in d.jets.built
    assert d.jets.built == [1]


def test_fig4_dieterich_ruina():
    d = fig4.data()
    V = d["V"]
    # (c) Γ with inertia peaks near 0.552 V̂ (Sec. 3.2); M = 0: Γ ∝ V (slope 1 in log-log)
    Vhat = math.sqrt(a * s * L / M)
    i = int(np.nanargmax(d["Gamma"]))
    assert 0 < i < len(V) - 1                      # non-monotonic: interior maximum
    # Γ/(k_c − k) = 2Γ̄ is the quantity whose maximum Sec. 3.2 locates (Γ_DR^max)
    j = int(np.nanargmax(d["Gamma"] / (1e-3 * d["kc"])))
    assert abs(V[j] / (0.552 * Vhat) - 1) < 0.05   # grid spacing: 240 points over 5 decades
    slope = np.polyfit(np.log(V), np.log(d["Gamma_M0"]), 1)[0]
    assert abs(slope - 1) < 1e-9
    # (b) inertia raises k_c (eq. 30); k̂ < k_c for Δx = 1 µm, and further below for larger Δx
    assert np.all(d["kc"] >= d["kc_M0"])
    assert np.all(d["khat"][1.0] < d["kc"]) and np.all(d["khat"][10.0] < d["khat"][1.0])
    # (d) Λ_R < 0 everywhere; Λ_D changes sign once (eq. 34), positive at low V
    assert np.all(d["Lambda_R"] < 0)
    sD = np.sign(d["Lambda_D"])
    assert np.count_nonzero(np.diff(sD)) == 1 and sD[0] > 0 > sD[-1]
    # (e) Dieterich slip amplitude exists only where Λ_D < 0
    assert np.all(np.isnan(d["slip_D"][d["Lambda_D"] > 0]))


def test_fig5_codim2_point():
    d = fig5.data()
    (p,) = d["codim2"]
    assert abs(p.kc / 2.08e5 - 1) < 5e-3  # Fig. 5(b)


def test_fig8_spinodal_c_1e3():
    d = fig8.data()
    assert np.all(d["Lambda"] <= 0) and np.all(d["Lambda_M0"] <= 0)   # Fig. 8(d): always supercritical
    assert np.all(d["khat"] < d["kc"])
    # Sec. 4.2: with inertia k̂ is not displaced towards small V as much as without
    V = d["V"]
    last = lambda kh: V[np.nonzero(kh > 0)[0].max()]
    assert last(d["khat"]) > 2 * last(d["khat_M0"])
    # (e): high-velocity slip amplitudes below the memory length L
    assert d["slip"][np.nanargmax(V)] < L


def test_fig9_effect_of_c():
    kc = fig9.kc_panel()
    lam = fig9.lambda_panel()
    ends = [kc[c][0][-1] for c in fig9.CS]
    # consecutive pairs: V_m moves to larger V as c decreases
    assert all(x < y for x, y in zip(ends, ends[1:], strict=False))
    assert not np.any(lam[1e-3][1] > 0)                 # c = 1e-3 > c*: supercritical everywhere
    for c in (7e-4, 5e-4, 3e-4):                        # c < c*: subcritical band just below V_m
        V, l_ = lam[c]
        assert np.any(l_ > 0) and np.all(V[l_ > 0] > 0.5 * V[-1])


def test_fig10_inertia_makes_the_band():
    d = fig10.data()
    assert np.any(d["Lambda"] > 0) and np.all(d["Lambda_M0"] <= 0)    # Fig. 10(d)
    (p,) = d["codim2"]
    assert p.sign_above == 1 and p.V > 0.8 * d["V"][-1]


def test_fig13_transition_velocity():
    pa = fig13.panel_a()
    assert abs(max(p.V for p in pa["codim2"]) / 1.109e-3 - 1) < 5e-3
    pb = fig13.panel_b()
    Vm = (b / a - 1) * 1e-6 / pb["c"]
    assert np.all(pb["V_star"] <= Vm * (1 + 1e-12))
    assert abs(pb["c_star"] / 9.02e-4 - 1) < 5e-3 and abs(pb["V_m_c_star"] / 4.447e-4 - 1) < 5e-3


def test_fig14_transition_line_and_inertial_boundary():
    pa = fig14.panel_a()
    # the transition line ends with k* → 0 at V_m(c*) ≈ 4.447e-4 m/s (Sec. 4.2)
    j = int(np.argmin(pa["line_k"]))
    assert pa["line_k"][j] == 0.0 and abs(pa["line_V"][j] / 4.447e-4 - 1) < 5e-3
    # the spinodal codimension-two points lie close to the law-(39) line ("very good agreement")
    md = derivation("modified-dieterich")
    for c in (3e-4, 5e-4):
        (p,) = pa["diagrams"][c].codim2
        k39 = md.evaluate([p.V], {"c": c}, ["kc"])["kc"][0]
        assert abs(p.kc / k39 - 1) < 0.1
    # Sec. 4.2: the transition points (V*, k_c*) lie in the creep domain k > Mω_c²
    curve = transition_curve(md, "c", 1e-4, 8e-4, n=6)
    rows = [r for r in curve.rows if r.kc > 0 and np.isfinite(r.V_ext)]
    assert rows and all(r.kc > M * r.omega_c ** 2 for r in rows)
    # the naive crossover M/k = (L/V)^2 does not follow the transition line
    k_naive = M * (pa["line_V"] / L) ** 2
    assert np.any(np.abs(np.log(k_naive[pa["line_k"] > 0] / pa["line_k"][pa["line_k"] > 0])) > 1)


def test_fig15_and_fig17_two_transitions():
    lp = fig15.lambda_panel()
    assert len(lp["codim2"]) == 2                       # Fig. 15(c): Λ changes sign twice
    l14 = fig17.lambda_panel(fig17.LAW, {"c": 1.4e-2})
    l25 = fig17.lambda_panel(fig17.LAW, {"c": 2.5e-2})
    assert len(l14["codim2"]) == 2
    # Fig. 17 caption: Λ ≥ 0 at low velocity; the high-velocity change only for c small enough
    assert len(l25["codim2"]) == 1 and l25["codim2"][0].sign_below == 1
    assert l14["Lambda"][0] > 0 and l25["Lambda"][0] > 0


def test_one_figure_is_written(tmp_path):
    paths = FIGURES["fig5"](tmp_path)
    assert len(paths) == 1 and paths[0].exists() and paths[0].stat().st_size > 10_000
