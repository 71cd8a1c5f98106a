"""A point where the float route finds a Hopf point that 50 digits do not (the end of a
velocity-weakening range, k_c and ω_c² within round-off of 0): ``Derivation.evaluate`` returns NaN
there, as it does wherever there is no Hopf point, instead of raising NoHopfError from the 50-digit
re-evaluation of its doubtful points (which lost the whole batch).  Found by
``landau transition`` on the law dφ/dt = 1 − vφ/L − c·atan(V_sφ/L) of
tests/cli/test_special_steady_states.py (numeric steady state, so a numeric Hopf line)."""

from __future__ import annotations

import numpy as np
import pytest

from landau.derivation.multiscale import derive
from landau.errors import NoHopfError
from landau.laws import FrictionLaw
from landau.systems.system import SpringBlock

MU = "a_v + a*log(v/V_s) + b*log(V_s*phi/L)"
#: the velocity the transition scan hit, at c = 2: the Hopf line ends between 4.882e-6 and 4.8823e-6
V_EDGE = 4.882218334988158e-06


def test_a_round_off_hopf_point_is_nan_like_its_50_digit_value():
    law = FrictionLaw.from_strings("atan", MU, {"phi": "1 - v*phi/L - c*atan(V_s*phi/L)"}, {"c": 3.0})
    d = derive(SpringBlock(law), ["Lambda"])
    with pytest.raises(NoHopfError):              # the independent verdict: no Hopf point at 50 digits
        d.evaluate_mp(V_EDGE, {"c": 2.0}, ["kc"], dps=50)
    Vs = np.array([V_EDGE, 4.8823e-6, 1e-4])
    got = d.evaluate(Vs, {"c": 2.0}, ["kc", "Lambda"])
    assert np.isnan(got["kc"][0]) and np.isnan(got["Lambda"][0])
    # the batch's other points are not lost: equal to 50 digits
    for i in (1, 2):
        want = d.evaluate_mp(float(Vs[i]), {"c": 2.0}, ["kc", "Lambda"], dps=50)
        assert got["kc"][i] == pytest.approx(float(want["kc"]), rel=1e-10)
        assert got["Lambda"][i] == pytest.approx(float(want["Lambda"]), rel=1e-10)
