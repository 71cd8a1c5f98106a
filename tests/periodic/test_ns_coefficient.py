"""The Neimark–Sacker normal-form coefficient against a closed form.

A unit cycle (x, y), period T = 2π, times the transverse Hopf normal form ż = (μ + iΩ) z − z|z|²,
z = u + iv: with v normalised by ∫₀ᵀ⟨v, v⟩ dt = 1 the critical eigenfunction is (0, 0, 1, −i)/√(2T),
so z = 2ξ/√(2T) and dξ/dt = iΩ ξ − (2/T) ξ|ξ|²: Re d = −2/T = −1/π (supercritical: the torus
|z| = √μ exists for μ > 0, where the cycle is unstable).
"""

from __future__ import annotations

import numpy as np
from test_ns_and_errors import _product, _unit_cycle

from landau.periodic import continue_cycles


def test_ns_coefficient_equals_the_closed_form_of_a_transverse_hopf_normal_form():
    br = continue_cycles(_product("focus"), _unit_cycle(-0.3), steps=12, ds=0.1, ntst=20)
    ns = br.points("NS")[0]
    assert abs(ns.coefficient - (-1 / np.pi)) < 1e-4
    assert "supercritical" in ns.message
