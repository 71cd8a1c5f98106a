"""Set-2 free-flight onset: 0.44986 here vs ≈ 0.453 in Lancioni, Lenci & Galvanetto (Sec. 3, Fig. 4).

See :mod:`landau.verify.lancioni.flight_onset` and the docstring of
:func:`landau.verify.lancioni.analysis.flight_onset_mu` for the numbers these tests pin.
"""

import pytest

from landau.verify.lancioni import slip as S
from landau.verify.lancioni.analysis import stick_onset_mu
from landau.verify.lancioni.flight_onset import continued_phidot_max, flies, flight_cycle


@pytest.mark.parametrize("eN", [0.0, 0.2])
def test_fig4_section_value_is_blind_to_the_flight(eN):
    """At μ = 0.453 the attractor flies once per period, yet its Fig. 4 quantity (φ̇ maxima,
    φ̇ > 0) equals the contact branch continued without lift-off, computed independently
    (stick exit P + reduced slip ODE, no hybrid engine)."""
    fc = flight_cycle(0.453, eN)
    assert fc.flights_per_period == 1.0
    # a real flight, far above integration noise: 20 μm gap, 49 ms, 3.9 mm/s at impact
    assert 1e-5 < fc.gap_max < 4e-5 and 0.03 < fc.flight_time < 0.07 and fc.impact_speed > 1e-3
    assert fc.lift_off_after_max                     # the flight comes after the section point
    # literal section φ = 0, φ̇ > 0 of the paper's text: never reached on this attractor
    assert fc.phi_min > 0.05 and fc.phi_zero_crossings == 0
    assert len(fc.phidot_max) == 1                   # period 1, no extra impact-related points
    # tolerance: hybrid run DOP853 rtol 1e-10 + root-found section, reference rtol 1e-12
    # (observed 2e-11); the value itself moves by 1.4e-2 between μ = 0.4498 and 0.453, so a
    # flight-induced departure of the diagram's visible size (1e-3) would fail by far
    assert fc.phidot_max[0] == pytest.approx(continued_phidot_max(0.453), rel=1e-8)


def test_unprinted_belt_speed_brackets_the_published_flight_onset():
    """Paper: stick appears at μ ≈ 0.360, free flight from μ ≈ 0.453 (Sec. 3, Fig. 4); the
    constant belt speed is not printed.  |v| = 0.990 and 0.992 both reproduce the printed stick
    onset, and the published flight onset μ = 0.453 lies between their flight onsets
    (0.45340 and 0.45269, i.e. ±3.5e-4 around 0.453: 35× the bisection width 1e-5 that
    measured them), while |v| = 1 already flies there (onset 0.44986)."""
    p = S.resolve(S.SET2)
    for v in (-0.990, -0.992):
        mu_stick, _ = stick_onset_mu(p, v=v)
        assert 0.3595 <= mu_stick <= 0.3605                 # printed "0.360", 3 decimals
    assert not flies(0.453, v=-0.990)
    assert flies(0.453, v=-0.992)
    assert flies(0.4502, v=-1.0) and not flies(0.4495, v=-1.0)
