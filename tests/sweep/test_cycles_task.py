"""The sweep task ``cycles``: the first fold of cycles per grid point, against the Bautin normal form.

ṙ = r(μ + b r² − r⁴) (ẋ = μx − y + b x r² − x r⁴, ẏ = x + μy + b y r² − y r⁴; Kuznetsov 2004, §8.3):
the unstable cycle born at the subcritical Hopf point μ = 0 folds with the stable one at
μ = −b²/4, r² = b/2 (the period stays 2π), written out here for b = 0.5 and 1.
"""

from __future__ import annotations

import numpy as np

RHS = {"x": "mu*x - y + b*x*(x**2 + y**2) - x*(x**2 + y**2)**2",
       "y": "x + mu*y + b*y*(x**2 + y**2) - y*(x**2 + y**2)**2"}


def test_cycles_task_locates_the_fold_of_the_bautin_normal_form():
    import landau

    b = np.array([0.5, 1.0])
    opts = {"rhs": RHS, "parameter": "mu", "equilibrium": {"x": "0", "y": "0"}, "bracket": (-1, 1), "steps": 40}
    ds = landau.sweep("cycles", {"b": b.tolist()}, model="system", workers=1, progress=False, options=opts)
    assert list(ds.status.values) == ["ok", "ok"]
    assert np.allclose(ds.lpc_p.values, -b ** 2 / 4, rtol=1e-6)
    assert np.allclose(ds.lpc_amplitude.values, np.sqrt(b / 2), rtol=1e-4)
    assert np.allclose(ds.lpc_period.values, 2 * np.pi, rtol=1e-8)
    assert np.all(np.isnan(ds.pd_p.values)) and np.allclose(ds.p_c.values, 0.0, atol=1e-12)
