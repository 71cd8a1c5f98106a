"""Every vectorised Λ(V) value within 1e-10 of the 50-digit evaluation, in the ill-conditioned
low-velocity end of the spinodal law's velocity-weakening range (where the float32 round-off
screen once let float64 values 1e-10…5e-10 off through)."""

import numpy as np

from landau.laws import get_law
from landau.multiscale import derive
from landau.system import SpringBlock
from vw_ranges import vw_range


def test_spinodal_low_velocity_tail_within_1e_10():
    lo, _, ends = vw_range("spinodal")
    lo = lo * (1 + 1e-3) if lo in ends else lo
    d = derive(SpringBlock(get_law("spinodal")), ["Lambda"])
    # the decade above V_M holds the points that missed (2.5e-8 ... 4e-8 m/s)
    Vs = np.logspace(np.log10(lo), np.log10(10 * lo), 150)
    got = d.evaluate(Vs, {}, ["Lambda"])["Lambda"]
    worst = 0.0
    for V0, g in zip(Vs, got):
        ref = d.evaluate_mp(float(V0), {}, ["Lambda"], dps=50)["Lambda"]
        worst = max(worst, float(abs(g - ref) / abs(ref)))
    assert worst <= 1e-10, worst
