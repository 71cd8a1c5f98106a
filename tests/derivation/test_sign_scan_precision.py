"""A sign scan's points in doubt are settled at 50 digits (landau.derivation.multiscale): the 80-digit rung
of the precision ladder is climbed only where the float estimate cannot bound the 50-digit error."""

import numpy as np

from landau.derivation.multiscale import derive
from landau.laws import get_law
from landau.systems.system import SpringBlock


def _dps_used(d, monkeypatch):
    used = []
    real = type(d).evaluate_mp

    def spy(self, V0, params, names, dps=50):
        used.append(dps)
        return real(self, V0, params, names, dps)

    monkeypatch.setattr(type(d), "evaluate_mp", spy)
    return used


def test_sign_estimate_settles_at_50_digits(monkeypatch):
    d = derive(SpringBlock(get_law("dieterich")), ["kc", "omega_c", "Lambda"])
    V0 = 1e-4
    lam = float(d.evaluate(np.array([V0]), None, ["Lambda"])["Lambda"][0])
    full, _ = d._evaluate_mp_checked(V0, {}, ["Lambda"])                 # the whole ladder
    used = _dps_used(d, monkeypatch)
    # an estimate 30 % off (float64 that lost half a digit): the 50-digit value is still exact
    # to ~1e-30, so its sign is certain and no finer precision is needed
    fast, degenerate = d._evaluate_mp_checked(V0, {}, ["Lambda"], {"Lambda": 1.3 * lam})
    assert used == [50] and not degenerate
    assert np.sign(float(fast["Lambda"])) == np.sign(float(full["Lambda"])) == np.sign(lam)
    assert abs(float(fast["Lambda"]) / float(full["Lambda"]) - 1) < 1e-15


def test_an_estimate_of_zero_climbs_the_ladder(monkeypatch):
    d = derive(SpringBlock(get_law("dieterich")), ["kc", "omega_c", "Lambda"])
    used = _dps_used(d, monkeypatch)
    # a float value of exactly 0 bounds nothing (the quantity might vanish identically)
    d._evaluate_mp_checked(1e-4, {}, ["Lambda"], {"Lambda": 0.0})
    assert used[:2] == [50, 80]
