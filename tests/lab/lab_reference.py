"""An independent integration of the quasi-static spring–slider with Dieterich's aging law, for tests/lab.

Per unit normal stress, with no inertia and no radiation damping (Ruina 1983; Gu et al. 1984):

    dμ/dt = k′ (V_lp(t) − v),   dθ/dt = 1 − vθ/L,   v = V_s exp((μ − μ₀ − b ln(V_s θ/L)) / a),

the slip rate from the law solved for v (the implicit function, here in closed form).  Integrated
in (μ, θ) by scipy's DOP853 at rtol 1e-12 — another method, other variables (μ instead of the
spring stretch, θ instead of ln θ, v explicit instead of an index-reduced state) than landau's
compiled Radau IIA — piece by piece, with the peaks of μ (dμ/dt = 0 falling, i.e. v = V_lp rising
through it) located by the integrator's event finder on its dense output.
"""

from __future__ import annotations

import math

import numpy as np
from scipy.integrate import solve_ivp

RTOL = 1e-12


def slip_rate(mu: float, theta: float, P: dict) -> float:
    return P["V_s"] * math.exp((mu - P["a_v"] - P["b"] * math.log(P["V_s"] * theta / P["L"])) / P["a"])


def mu_ss(V: float, P: dict) -> float:
    return P["a_v"] + (P["a"] - P["b"]) * math.log(V / P["V_s"])


def run(pieces, P: dict, kp: float):
    """Integrate the pieces [(V, duration)] from steady sliding at the first V.

    Returns, per piece: (μ at its start, μ at its end, [(t, μ) of each peak of μ in it], end state).
    """
    y = np.array([mu_ss(pieces[0][0], P), P["L"] / pieces[0][0]])
    out = []

    def field(t, z, V):
        v = slip_rate(z[0], z[1], P)
        return [kp * (V - v), 1.0 - v * z[1] / P["L"]]

    def peak(t, z, V):
        return kp * (V - slip_rate(z[0], z[1], P))

    peak.direction = -1
    for V, dur in pieces:
        sol = solve_ivp(field, (0.0, dur), y, args=(V,), method="DOP853", rtol=RTOL, atol=[1e-15, 1e-15 * y[1]],
                        events=peak if V > 0 else None)
        assert sol.success, sol.message
        peaks = [] if V == 0 else [(float(t), float(z[0])) for t, z in zip(sol.t_events[0], sol.y_events[0],
                                                                            strict=True)]
        out.append((float(y[0]), float(sol.y[0, -1]), peaks, sol.y[:, -1].copy()))
        y = sol.y[:, -1]
    return out
