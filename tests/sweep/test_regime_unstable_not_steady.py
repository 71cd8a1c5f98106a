"""A regime map never calls a linearly unstable point steady: at k < k_c steady sliding repels every
run (its linearisation has a pair with Re λ > 0), so a run that shrinks there is collapsing onto a
cycle, not decaying onto steady sliding.  The Dieterich law at V = 1e-3 m/s is supercritical
(V > V* = 2.07e-4 m/s, Putelat, Dawes & Willis 2010 Fig. 12): just below k_c both starts end on the
small cycle of the amplitude equation, of half swing C √(k_c − k) (their eq. 23)."""

from __future__ import annotations

import math

import numpy as np
import pytest

pytest.importorskip("xarray")

import landau  # noqa: E402
from landau.models import Setup  # noqa: E402
from landau.verify.springblock.declaration import spring_block_hopf  # noqa: E402
from landau.verify.springblock.regime_map import _geometric_decay, prediction_at  # noqa: E402

# Putelat et al. (2010) Table 1 (the dieterich law's defaults) and the default block
A_, B_, L_, M_, SIGMA_ = 0.0349, 0.0489, 9e-7, 1.2, 1.2 * 9.81


def test_just_below_a_supercritical_kc_both_starts_end_on_the_small_cycle():
    V = 1e-3
    h = spring_block_hopf(Setup(landau.laws.get_law("dieterich"), {"V": V}))
    # eq. (30): k_c = σ(b − a)/L · (1 + M V²/(σ a L)), the value the users quote
    assert float(h.p_c) == pytest.approx(SIGMA_ * (B_ - A_) / L_ * (1 + M_ * V ** 2 / (SIGMA_ * A_ * L_)), rel=1e-12)
    assert float(h.p_c) == pytest.approx(777410.5656372706, rel=1e-12)
    assert str(h.criticality) == "supercritical"
    ds = landau.sweep("regime", {"V": [V], "k": [0.99 * float(h.p_c)]}, law="dieterich", workers=1, progress=False)
    row = {n: ds[n].values.ravel()[0] for n in ds.data_vars}
    assert str(row["regime_near"]) == str(row["regime_far"]) == str(row["regime"]) == "small-cycle"
    pr = prediction_at(h, V, 0.99)
    # the near start (1e-3 ℓ) grows towards the cycle, the far one collapses onto it from above
    assert row["amplitude_near"] < pr["amplitude_predicted"] < row["amplitude_far"]
    assert row["amplitude_far"] == pytest.approx(pr["amplitude_predicted"], rel=0.05)
    # a small cycle: the slip rate's low point 1 − A ω_c/V of the weakly nonlinear cycle (swing 0.13)
    assert row["v_min_far"] == pytest.approx(1 - pr["swing_predicted"], abs=0.01)


@pytest.mark.parametrize("per_cycle, linear, expected", [
    (0.9985, 2 * math.pi * 3.833e-4 / 0.6300, False),   # the users' collapse at an unstable point
    (math.exp(-0.08 * 0.006), -0.006, False),           # 8 % of the linear rate: a slow passage
    (math.exp(-0.006), -0.006, True),                   # the linear decay itself
    (math.exp(-1.5 * 0.006), -0.006, True),             # within the cubic terms' factor 2
])
def test_a_geometric_decay_is_steady_only_at_the_linear_rate(per_cycle, linear, expected):
    x = 0.24 * L_ * per_cycle ** np.arange(21)
    assert _geometric_decay(x, linear) is expected
