"""The smooth slip field of the damped one block as a ``landau`` system (for the Hopf engine).

Slipping with r = Ẋ − V < 0 the one block obeys Ẍ + cẊ + X = F_k(Ẋ − V) with the smooth
branch F_k⁻(r) = (1 − δ)/(1 − γr) + δ (Galvanetto 2004, eqs 4a, 7).  In u = X − F_k⁻(−V),
w = Ẋ the equilibrium (steady sliding, block at rest, r = −V) is the origin:

    u̇ = w,   ẇ = −u − c w + F_k⁻(w − V) − F_k⁻(−V).

The Hopf parameter is the damping c; the Hopf point is c₁ = F_k⁻'(−V) = γ(1 − δ)/(1 + γV)²
with ω = 1.  :func:`damped_slip_system` returns it as a :class:`landau.system.DynamicalSystem`
so that the landau engine computes the criticality (Λ) — see
:func:`landau.verify.galvanetto.bifurcations.hopf_c1_normal_form`.
"""

from __future__ import annotations

import sympy as sp


def damped_slip_system(V: float = 0.5, gamma: float = 3.0, delta: float = 0.0):
    from landau.system import DynamicalSystem
    u, w, c = sp.symbols("u w c", real=True)
    Vs, gs, ds = sp.symbols("V gamma delta", positive=True)
    Fneg = lambda r: (1 - ds) / (1 - gs * r) + ds
    rhs = (w, -u - c * w + Fneg(w - Vs) - Fneg(-Vs))
    return DynamicalSystem(
        name="galvanetto2004-damped-one-block-slip", states=(u, w), rhs=rhs, mass=(sp.Integer(1), sp.Integer(1)),
        parameter=c, equilibrium=(sp.Integer(0), sp.Integer(0)),
        defaults={"V": V, "gamma": gamma, "delta": delta}, normalise=0,
        description="Galvanetto 2004 eq. (4a) with friction branch r<0 of eq. (7); Hopf in c at c1 = F_k'(-V)")
