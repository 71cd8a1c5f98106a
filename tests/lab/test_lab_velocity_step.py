"""The quasi-static velocity step of the lab preset against the closed form and an independent integration.

The rsfmodel example's published parameters (μ₀ = 0.6, a = 0.005, b = 0.01, D_c = 10 µm,
k′ = 1e-3/µm, 1 → 10 µm/s; Dieterich's aging law), run quasi-statically (M = 0, η = 0) per unit
normal stress: the friction settles at Δμ_ss = (a − b) ln(V₂/V₁) (Ruina 1983), and the whole
transient agrees with the independent integration of :mod:`lab_reference` (scipy's DOP853 on
(μ, θ) at rtol 1e-12).  The direct-effect peak located on the dense solution as a root of dμ/dt
agrees with the reference's event to 1e-9, where the largest μ at the run's output points is
about 4e-7 low at the run's default rtol 1e-9 (it was the only reading before).
"""

from __future__ import annotations

import math

import lab_reference as ref
import pytest

from landau.lab import measure
from landau.lab.protocols import run_protocol, velocity_step

P = {"a_v": 0.6, "a": 0.005, "b": 0.01, "L": 10e-6, "V_s": 1e-6}
KP = 1e-3 * 1e6          # k' = 1e-3 / um in 1/m
# the step after 100 um at 1 um/s (t = 100.00000000000001 s in floating point), 100 s at 10 um/s after it
STEP = velocity_step("1um/s", "10um/s", displacement="100um", after="100s")


@pytest.fixture(scope="module")
def run():
    return run_protocol(STEP, "dieterich", "1e-3/um", P)


@pytest.fixture(scope="module")
def reference():
    pieces = [(V, b - a) for V, a, b in STEP.pieces()]
    return ref.run(pieces, P, KP)


def test_the_step_settles_at_the_closed_form(run):
    # 100 s = 100 D_c/V2 after the step the transient (decay rate ~ V2/D_c at k' = 2 k_c) is below
    # round-off: the steady states agree with (a - b) ln(V2/V1) to the run's rtol 1e-9 times mu
    closed = (P["a"] - P["b"]) * math.log(10.0)
    assert measure.steady_state_change(run) == pytest.approx(closed, abs=1e-12)
    assert measure.mu_at_end(run, 0) == pytest.approx(ref.mu_ss(1e-6, P), abs=1e-14)


def test_the_transient_matches_the_independent_integration(run, reference):
    # the piece ends (exact end points of both runs) agree to the Radau IIA's rtol 1e-9 on ln v and
    # ln theta, times a = 0.005 and b = 0.01 in mu: 1e-10 is a factor ~10 above that
    for i, (_, end, _, _) in enumerate(reference):
        assert measure.mu_at_end(run, i) == pytest.approx(end, abs=1e-10)
    theta = run.column("phi")[-1]
    assert theta == pytest.approx(reference[-1][3][1], rel=1e-8)


def test_the_direct_effect_peak_is_a_root_of_dmu_dt_on_the_dense_solution(run, reference):
    peaks = reference[1][2]
    t_ref, mu_ref = peaks[0]          # the first (largest) peak after the step
    pk = measure.direct_effect_peak(run)
    assert pk.mu == pytest.approx(mu_ref, abs=1e-9)
    # mu is stationary at the peak: its time is known to ~sqrt(error / |mu''|), here ~1e-6 s
    assert pk.t - STEP.history.times[1] == pytest.approx(t_ref, abs=1e-5)
    # at the peak dmu/dt = k'(V - v) = 0: the slip rate is the load point's
    assert pk.v == pytest.approx(1e-5, rel=1e-7)
    assert pk.x_lp == pytest.approx(1e-4 + 1e-5 * t_ref, rel=1e-9)
    # the reading at the output points (the integrator's steps) is low by ~(1/2)|mu''| (h/2)^2
    low = mu_ref - pk.mu_output
    assert 1e-8 < low < 1e-5
    assert abs(pk.mu - mu_ref) < 1e-3 * low


def test_no_peak_after_a_step_down_is_a_named_error(run):
    from landau.errors import InputError

    down = run_protocol(velocity_step("10um/s", "1um/s", at="10s"), "dieterich", "1e-3/um", P)
    with pytest.raises(InputError, match="step up"):
        measure.direct_effect_peak(down)
    with pytest.raises(InputError, match="no peak of mu in piece 0"):
        measure.locate_peak(down, 0)
