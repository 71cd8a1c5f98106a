"""The smooth slip field of the damped one block as a ``landau`` system (for the Hopf engine).

Slipping with r = Ẋ − V < 0 the one block obeys Ẍ + cẊ + X = F_k(Ẋ − V) with the smooth
branch F_k⁻ of the kinetic law (Galvanetto 2004, eqs 4a, 7: F_k⁻(r) = (1 − δ)/(1 − γr) + δ).
In u = X − F_k⁻(−V), w = Ẋ the equilibrium (steady sliding, block at rest, r = −V) is the
origin:

    u̇ = w,   ẇ = −u − c w + F_k⁻(w − V) − F_k⁻(−V).

The Hopf parameter is the damping c; the Hopf point is c₁ = F_k⁻'(−V) (= γ(1 − δ)/(1 + γV)²
for eq. 7) with ω = 1.  :func:`damped_slip_system` returns it as a
:class:`landau.systems.system.DynamicalSystem` so that the landau engine computes the criticality (Λ) —
see :func:`landau.verify.galvanetto.bifurcations.hopf_c1_normal_form`.
"""

from __future__ import annotations

import sympy as sp

from landau.laws.kinetic import DELTA, GAMMA, KineticFriction, R, resolve_kinetic_law


def kinetic_law(gamma: float | None = None, delta: float | None = None,
                law: KineticFriction | None = None) -> KineticFriction:
    """The kinetic law of a damped one-block computation: ``law`` if given, else Galvanetto's
    eq. (7) with ``gamma`` (default 3) and ``delta`` (default 0); see
    :func:`landau.laws.kinetic.resolve_kinetic_law`."""
    return resolve_kinetic_law(law, gamma, delta)


def damped_slip_system(V: float = 0.5, gamma: float | None = None, delta: float | None = None,
                       law: KineticFriction | None = None):
    """The damped one block's r < 0 slip field, shifted to its equilibrium, as a DynamicalSystem.

    Parameters
    ----------
    V : belt velocity.
    gamma, delta : parameters of the default law (Galvanetto 2004 eq. 7: γ = 3, δ = 0).
    law : kinetic law (:class:`landau.laws.kinetic.KineticFriction`); its symbolic r < 0 branch
        is the friction force.  Default: eq. (7) with ``gamma``, ``delta``.

    Returns
    -------
    landau.systems.system.DynamicalSystem
        States (u, w), Hopf parameter c, parameters V (and γ, δ if the law uses them).

    References
    ----------
    U. Galvanetto, J. Sound Vib. 276 (2004) 121–139, eqs (4a), (7), Sec. 4.2.
    """
    from landau.systems.system import DynamicalSystem
    law = kinetic_law(gamma, delta, law)
    u, w, c = sp.symbols("u w c", real=True)
    Vs = sp.Symbol("V", positive=True)
    branch = law.branch("neg", symbolic=True)
    Fneg = lambda r: branch.subs(R, r)
    rhs = (w, -u - c * w + Fneg(w - Vs) - Fneg(-Vs))
    return DynamicalSystem(
        name="galvanetto2004-damped-one-block-slip", states=(u, w), rhs=rhs, mass=(sp.Integer(1), sp.Integer(1)),
        parameter=c, equilibrium=(sp.Integer(0), sp.Integer(0)),
        defaults={"V": V, GAMMA.name: law.gamma, DELTA.name: law.delta}, normalise=0,
        description="Galvanetto 2004 eq. (4a) with the r<0 branch of the kinetic law; Hopf in c at c1 = F_k'(-V)")
