"""Slide-hold-slide tests of the lab preset: healing and relaxation against an independent integration
and the aging law's long-hold asymptote.

Quasi-statically (dμ/dt = k′(V − v)) a peak of μ on reloading is where the slip rate reaches the
load point's, v = V; there μ = μ₀ + a ln(V/V_s) + b ln(V_s θ_p/L), so with μ_ss(V) before the hold

    Δμ_peak = b ln(V θ_p / L)        (exactly, at the peak).

During a long hold the slip rate falls far below L/θ, the aging law's θ grows like the hold time
(dθ/dt ≈ 1: Dieterich 1972; Beeler, Tullis & Weeks 1994), and the slip to the peak on reloading
shrinks θ by a factor that tends to a constant, so d ln θ_p / d ln t_h → 1 and the healing rate
per decade dΔμ_peak/dlog₁₀ t_h = b ln(10) · d ln θ_p/d ln t_h → b ln 10 from below.
"""

from __future__ import annotations

import math

import lab_reference as ref
import numpy as np
import pytest

from landau.lab import measure
from landau.lab.protocols import run_protocol, slide_hold_slide

P = {"a_v": 0.6, "a": 0.005, "b": 0.01, "L": 10e-6, "V_s": 1e-6}
KP = 1e-3 * 1e6
V = 1e-5


@pytest.fixture(scope="module")
def short():
    prot = slide_hold_slide("10um/s", [3, 30, 300], displacement="200um")
    return prot, run_protocol(prot, "dieterich", "1e-3/um", P)


@pytest.fixture(scope="module")
def long():
    prot = slide_hold_slide("10um/s", [1e2, 1e3, 1e4, 1e5, 1e6], displacement="1000um")
    return prot, run_protocol(prot, "dieterich", "1e-3/um", P)


def test_healing_and_relaxation_match_the_independent_integration(short):
    prot, run = short
    reference = ref.run([(v, b - a) for v, a, b in prot.pieces()], P, KP)
    holds = measure.hold_measures(run)
    assert [m.hold for m in holds] == pytest.approx([3, 30, 300], rel=1e-15)
    for m, i in zip(holds, (1, 3, 5), strict=True):
        start, end = reference[i][0], reference[i][1]
        peak = reference[i + 1][2][0][1]
        # the run's rtol 1e-9 on ln v, ln theta enters mu times a, b ~ 0.01: 1e-10 with a margin of ~10
        assert m.relaxation == pytest.approx(start - end, abs=1e-10)
        assert m.dmu_peak == pytest.approx(peak - start, abs=1e-10)
        # the peak on the dense solution, not at the output points (those read it low by up to ~1e-6)
        assert m.peak.mu >= m.peak.mu_output
        assert m.relaxation > 0 and m.dmu_peak > 0


def test_the_peak_is_where_the_slip_rate_meets_the_load_point(long):
    _, run = long
    for m in measure.hold_measures(run):
        theta_p = m.peak.states[0]
        assert m.peak.v == pytest.approx(V, rel=1e-7)
        # the settled slide before each hold: mu_start = mu_ss(V)
        assert m.mu_start == pytest.approx(ref.mu_ss(V, P), abs=1e-9)
        assert m.dmu_peak == pytest.approx(P["b"] * math.log(V * theta_p / P["L"]), abs=1e-9)


def test_the_healing_rate_tends_to_b_ln10_per_decade(long):
    _, run = long
    holds = measure.hold_measures(run)
    bln10 = P["b"] * math.log(10.0)
    local = np.diff([m.dmu_peak for m in holds]) / bln10          # per decade, in units of b ln 10
    # measured 0.98456, 0.99777, 0.99971, 0.99996: from below, the distance to 1 shrinking ~7x a decade
    assert np.all(local < 1.0) and np.all(np.diff(local) > 0)
    assert 1.0 - local[-1] < 1e-4
    # the least-squares slope over the three longest holds, and over all, below the asymptote
    assert measure.healing_rate(holds[2:]) == pytest.approx(bln10, rel=1e-3)
    assert measure.healing_rate(holds) < bln10
    # and the growth of theta at the peak is the hold time's, d ln theta_p / d ln t_h -> 1
    th = np.log([m.peak.states[0] for m in holds])
    assert (th[-1] - th[-2]) / math.log(10.0) == pytest.approx(1.0, abs=1e-4)


def test_a_protocol_without_holds_has_no_healing():
    from landau.errors import InputError
    from landau.lab.protocols import velocity_step

    run = run_protocol(velocity_step("1um/s", "10um/s", at="10s"), "dieterich", "1e-3/um", P)
    with pytest.raises(InputError, match="no hold"):
        measure.hold_measures(run)
    with pytest.raises(InputError, match="two different hold times"):
        measure.healing_rate([])
