"""Synthetic laboratory records for the fitting tests: three parameter sets, made by landau's forward model.

The velocity-step values are rsfmodel's README example (Leeman et al., rsfmodel): μ₀ = 0.6,
a = 0.005, b = 0.01, D_c = 10 µm, k′ = 1e-3/µm, 1 → 10 µm/s; the slip-law and two-state sets
are of the same magnitudes (Marone 1998, Annu. Rev. Earth Planet. Sci. 26, Table 1 ranges).
"""

from __future__ import annotations

import numpy as np

from landau.lab.data import LabData
from landau.lab.forward import ForwardModel
from landau.laws import FrictionLaw, get_law

UM = 1e-6


def aging_slip_law() -> FrictionLaw:
    """Two states: one ageing (Dieterich 1979), one slip (Ruina 1983)."""
    return FrictionLaw.from_strings(
        "aging+slip", "a_v + a*log(v/V_s) + b1*log(V_s*phi1/L1) + b2*log(V_s*phi2/L2)",
        {"phi1": "1 - v*phi1/L1", "phi2": "-(v*phi2/L2)*log(v*phi2/L2)"},
        {"a_v": 0.6, "a": 0.006, "b1": 0.004, "L1": 5 * UM, "b2": 0.006, "L2": 50 * UM, "V_s": 1 * UM})


#: name -> (law factory, true parameters (SI), k' (1/m), velocity steps [(t_start s, V µm/s)], t_end s, dt s)
SETS = {
    "aging": (lambda: get_law("dieterich"), dict(a_v=0.6, a=0.005, b=0.01, L=10 * UM, V_s=1 * UM), 1e3,
              [(0.0, 1.0), (10.0, 10.0), (40.0, 1.0)], 80.0, 0.04),
    "slip": (lambda: get_law("ruina"), dict(a_v=0.55, a=0.008, b=0.006, L=20 * UM, V_s=3 * UM), 5e3,
             [(0.0, 3.0), (5.0, 30.0), (20.0, 3.0)], 60.0, 0.03),
    "two-state": (aging_slip_law, dict(a_v=0.6, a=0.006, b1=0.004, L1=5 * UM, b2=0.006, L2=50 * UM, V_s=1 * UM),
                  1e3, [(0.0, 1.0), (10.0, 10.0), (60.0, 1.0)], 160.0, 0.08),
}


def protocol(steps, t_end: float, dt: float) -> tuple[np.ndarray, np.ndarray]:
    """Sample times and the load-point velocity (m/s) of each, rsfmodel's convention (V of a sample
    holds until the next)."""
    t = np.round(np.arange(0.0, t_end + dt / 2, dt), 12)
    V = np.empty_like(t)
    for start, vel in steps:
        V[t >= start - 1e-9] = vel * UM
    return t, V


def record(name: str, noise: float = 0.0, seed: int = 0, dt: float | None = None
           ) -> tuple[FrictionLaw, LabData, dict, float]:
    """(law, record, true parameters, k') of set ``name``, with Gaussian noise of standard deviation ``noise``
    (and another sampling interval ``dt``)."""
    make, params, k, steps, t_end, dt0 = SETS[name]
    dt = dt or dt0
    law = make()
    t, V = protocol(steps, t_end, dt)
    mu = ForwardModel(law, []).run(t, V, params, k, rtol=1e-12).mu
    if noise:
        mu = mu + noise * np.random.default_rng(seed).standard_normal(mu.size)
    x = np.concatenate([[0.0], np.cumsum(V[:-1] * np.diff(t))])
    return law, LabData(t, V, mu, x, name), dict(params), k
