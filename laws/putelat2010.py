"""The rate-and-state laws of Putelat, Dawes & Willis, J. Mech. Phys. Solids (2010).

Parameter values: Table 1 (a_v, a, b, L, V_*), with L = 0.9e-6 m and V_* = 1e-6 m/s
— the set that reproduces the paper's numbers (Sec. 3.1 prints V_* = 0.9e-6, which does not).  States
are dimensional (seconds) as in the paper; G = −dφ/dt.
"""

from __future__ import annotations

import sympy as sp

from landau.laws.law import TABLE1, FrictionLaw, Parameter, v

phi = sp.Symbol("phi", positive=True)
a_v, a, b, L, V_s = (TABLE1[n].symbol for n in ("a_v", "a", "b", "L", "V_s"))
_T1 = tuple(TABLE1.values())


def _c(default: float, source: str) -> Parameter:
    return Parameter("c", default, "", source, "residual strength c")


def dieterich() -> FrictionLaw:
    """Dieterich (ageing) law: μ = a_v + a ln(v/V_*) + b ln(V_*φ/L) (eq. 26), dφ/dt = 1 − vφ/L (eq. 28)."""
    return FrictionLaw(
        "dieterich",
        a_v + a * sp.log(v / V_s) + b * sp.log(V_s * phi / L),
        (phi,), (1 - v * phi / L,), _T1,
        source="Putelat et al. 2010, eqs (26)+(28)",
        description="Dieterich ageing law", steady_state=(L / v,),
    )


def ruina() -> FrictionLaw:
    """Ruina (slip) law: μ of eq. (26), dφ/dt = −(vφ/L) ln(vφ/L) (eq. 29)."""
    return FrictionLaw(
        "ruina",
        a_v + a * sp.log(v / V_s) + b * sp.log(V_s * phi / L),
        (phi,), (-(v * phi / L) * sp.log(v * phi / L),), _T1,
        source="Putelat et al. 2010, eqs (26)+(29)",
        description="Ruina slip law", steady_state=(L / v,),
    )


def spinodal() -> FrictionLaw:
    """Spinodal law: μ = a asinh[(e^{a_v/a}/2)(v/V_*)(c + φ/φ_*)^{b/a}] (eq. 37),
    dφ/dt = −(φ − 1)/t_** − vφ/L (eq. 38), φ_* = (1 + t_** V_*/L)^{-1}.

    t_** = 90 s, i.e. R = t_** V_*/L = 100 with Table 1; c = 1e-3 as in Sec. 4.1/Fig. 8.
    """
    c = sp.Symbol("c", positive=True)
    t = sp.Symbol("t_ss", positive=True)
    phi_s = 1 / (1 + t * V_s / L)
    mu = a * sp.asinh(sp.exp(a_v / a) / 2 * (v / V_s) * (c + phi / phi_s) ** (b / a))
    return FrictionLaw(
        "spinodal", mu, (phi,), (-(phi - 1) / t - v * phi / L,),
        _T1 + (_c(1e-3, "Putelat et al. 2010, Sec. 4.1 (Fig. 8)"),
               Parameter("t_ss", 90.0, "s", "Putelat et al. 2010, Sec. 4.1: R = t** V_*/L = 100", "ageing time t_**")),
        source="Putelat et al. 2010, eqs (37)+(38)",
        description="spinodal law (non-monotonic steady state)", steady_state=(L / (L + v * t),),
    )


def modified_dieterich() -> FrictionLaw:
    """Modified Dieterich law (eq. 39): μ = a_v + a ln(v/V_*) + b ln(c + φV_*/L), dφ/dt = 1 − vφ/L.

    The paper writes a_* for the constant term; it is a_v (μ_ss(V_*) ≈ a_v for small c).
    Default c = 3e-4 (Sec. 4.2, Fig. 13).
    """
    c = sp.Symbol("c", positive=True)
    return FrictionLaw(
        "modified-dieterich",
        a_v + a * sp.log(v / V_s) + b * sp.log(c + phi * V_s / L),
        (phi,), (1 - v * phi / L,),
        _T1 + (_c(3e-4, "Putelat et al. 2010, Sec. 4.2 (Fig. 13)"),),
        source="Putelat et al. 2010, eq. (39)",
        description="Dieterich law with high-velocity residual strength c", steady_state=(L / v,),
    )


def nanoscale() -> FrictionLaw:
    """Nanoscale contact law, regularised form of eq. (48):
    μ = a[1 + (b/a_v) ln(φ/φ_*) + a₂ ln²(φ/φ_*)] asinh(v/γ₀), γ₀ = 2 e^{−a_v/a} V_*,
    φ_* = L/V_*, with the Dieterich state law (28). a₂ = 0.0085 (Sec. 5.1, Fig. 15).
    """
    a2 = sp.Symbol("a2", positive=True)
    g0 = 2 * sp.exp(-a_v / a) * V_s
    lnp = sp.log(phi * V_s / L)
    return FrictionLaw(
        "nanoscale",
        a * (1 + (b / a_v) * lnp + a2 * lnp ** 2) * sp.asinh(v / g0),
        (phi,), (1 - v * phi / L,),
        _T1 + (Parameter("a2", 0.0085, "", "Putelat et al. 2010, Sec. 5.1 (Fig. 15)", "second-order memory a_2"),),
        source="Putelat et al. 2010, eq. (48) (regularised) + (28)",
        description="nanoscale contact law", steady_state=(L / v,),
    )


def micron_scale() -> FrictionLaw:
    """Micron-scale contact law (eq. 50): μ = a[1 + (b/a_v) ln(c + V_*φ/L)] asinh(v/γ₀),
    dφ/dt = 1 − vφ/L, γ₀ = 2 e^{−a_v/a} V_* (the printed "^5" is a footnote mark).
    Default c = 1.4e-2 (Fig. 17c).
    """
    c = sp.Symbol("c", positive=True)
    g0 = 2 * sp.exp(-a_v / a) * V_s
    return FrictionLaw(
        "micron-scale",
        a * (1 + (b / a_v) * sp.log(c + V_s * phi / L)) * sp.asinh(v / g0),
        (phi,), (1 - v * phi / L,),
        _T1 + (_c(1.4e-2, "Putelat et al. 2010, Sec. 5.2 (Fig. 17c)"),),
        source="Putelat et al. 2010, eq. (50)",
        description="micron-scale contact law", steady_state=(L / v,),
    )


def two_state_dieterich() -> FrictionLaw:
    """Two Dieterich-type states with memory lengths L₁, L₂ (a standard two-state extension;
    not in the paper): μ = a_v + a ln(v/V_*) + b₁ ln(V_*φ₁/L₁) + b₂ ln(V_*φ₂/L₂), dφᵢ/dt = 1 − vφᵢ/Lᵢ."""
    p1, p2 = sp.symbols("phi1 phi2", positive=True)
    b1, b2, L1, L2 = sp.symbols("b1 b2 L1 L2", positive=True)
    params = (TABLE1["a_v"], TABLE1["a"], TABLE1["V_s"],
              Parameter("b1", 0.0300, "", "illustrative"), Parameter("b2", 0.0189, "", "illustrative"),
              Parameter("L1", 0.9e-6, "m", "illustrative"), Parameter("L2", 9e-6, "m", "illustrative"))
    return FrictionLaw(
        "two-state-dieterich",
        a_v + a * sp.log(v / V_s) + b1 * sp.log(V_s * p1 / L1) + b2 * sp.log(V_s * p2 / L2),
        (p1, p2), (1 - v * p1 / L1, 1 - v * p2 / L2), params,
        source="two-state extension of Putelat et al. 2010 eqs (26)+(28)",
        description="two Dieterich-type states", steady_state=(L1 / v, L2 / v),
    )
