"""The continuum fault's length scales and the spring–block stiffness of a fault patch.

For a rate-and-state law at slip rate V on a fault under effective normal stress σ in an
elastic medium of shear modulus G (or density ρ and shear-wave speed c_s, G = ρ c_s²) and
Poisson's ratio ν, :func:`nucleation` gives the lengths below.  Every formula is listed with its
source and its regime of validity in :data:`FORMULAS` (and in the result's ``formulas``).

* **The effective modulus** μ′: G for antiplane (mode III) slip, G/(1 − ν) for in-plane (mode II)
  slip (Rice 1993).
* **The critical stiffness** k_c (Pa/m): the quasi-static (M = 0) critical stiffness of the
  spring–block with this law at V (Putelat, Dawes & Willis 2010, eq. 7, computed by landau's
  Hopf line); σ(b − a)/L for the Dieterich and Ruina laws (Ruina 1983).
* **The critical wavelength** h*: a sinusoidal slip of wavelength λ on a uniform fault between two
  elastic half-spaces loads it with the stiffness k = π μ′/λ (Rice & Ruina 1983); steady sliding
  is linearly unstable for wavelengths above h* = π μ′/k_c (Rice & Ruina 1983; Rice 1993), which
  is π μ′ L/((b − a) σ) for the Dieterich and Ruina laws.  Circular geometry: the diameter of a
  circular patch whose stiffness (below) equals k_c.
* **The patch stiffness** (:func:`patch_stiffness`): 2-D, k(h) = π μ′/h with h the wavelength
  (Rice & Ruina 1983), so that k(h*) = k_c; 3-D circular patch of diameter h = 2r under a uniform
  stress drop, k = Δτ/δ̄ = 3π(2 − ν) G/(16 (1 − ν) r) (Eshelby 1957; 7πG/(16 r) at ν = 1/4).
* **The Rubin–Ampuero lengths** (Rubin & Ampuero 2005; 2-D, ageing law): L_b = μ′L/(bσ); for
  a/b ≤ 0.3781 nucleation localises to a half-length L_ν = 1.3774 L_b; for 0.3781 < a/b < 1 it
  grows towards the half-length L_∞ = (1/π) [b/(b − a)]² L_b.  a and b are the law's local values
  at V (a = ∂μ/∂ln v at fixed state, b = a − dμ_ss/d ln V; the parameters a, b themselves for the
  Dieterich law), L is the law's parameter ``L``.

References
----------
Rice, J. R. & Ruina, A. L. (1983), Stability of steady frictional slipping, J. Appl. Mech. 50, 343–349.
Rice, J. R. (1993), Spatio-temporal complexity of slip on a fault, J. Geophys. Res. 98(B6), 9885–9907.
Rubin, A. M. & Ampuero, J.-P. (2005), Earthquake nucleation on (aging) rate and state faults,
J. Geophys. Res. 110, B11312.
Eshelby, J. D. (1957), The determination of the elastic field of an ellipsoidal inclusion, and
related problems, Proc. R. Soc. Lond. A 241, 376–396.
Ruina, A. L. (1983), Slip instability and state variable friction laws, J. Geophys. Res. 88, 10359–10370.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Any, Mapping

from landau.errors import InputError

#: the geometries and what they mean
GEOMETRIES = {
    "antiplane": "2-D antiplane (mode III) slip on a planar fault, mu' = G",
    "inplane": "2-D in-plane (mode II) slip on a planar fault, mu' = G/(1 - nu)",
    "circular": "3-D circular patch under a uniform stress drop (Eshelby 1957)",
}
#: Rubin & Ampuero (2005): the a/b boundary between their two nucleation regimes (ageing law)
A_OVER_B_BOUNDARY = 0.3781
#: Rubin & Ampuero (2005): L_nu / L_b in the localised regime a/b <= 0.3781
L_NU_OVER_L_B = 1.3774

#: every formula with its source and regime of validity
FORMULAS: dict[str, dict[str, str]] = {
    "mu_prime": {"formula": "G (antiplane); G/(1 - nu) (inplane)", "source": "Rice 1993",
                 "validity": "2-D slip on a planar fault in a homogeneous linear elastic whole space"},
    "k_c": {"formula": "quasi-static critical stiffness of the spring-block at V (sigma(b - a)/L for the "
                       "Dieterich and Ruina laws)",
            "source": "Putelat, Dawes & Willis 2010, eq. (7) with M = 0; Ruina 1983",
            "validity": "steady sliding at V; velocity weakening at V (else no k_c)"},
    "h_star": {"formula": "pi mu'/k_c (2-D: the critical wavelength); circular: the diameter 2r with "
                          "3 pi (2 - nu) G/(16 (1 - nu) r) = k_c",
               "source": "Rice & Ruina 1983 (k = pi mu'/lambda); Rice 1993; Eshelby 1957 (circular)",
               "validity": "linear stability of quasi-static steady sliding on a uniform fault; wavelengths "
                           "above h* are unstable"},
    "k_patch": {"formula": "pi mu'/h (2-D, h the wavelength); 3 pi (2 - nu) G/(8 (1 - nu) h) (circular, "
                           "h the diameter)",
                "source": "Rice & Ruina 1983; Eshelby 1957",
                "validity": "elastic stiffness of a patch of size h in a uniform medium; k(h*) = k_c"},
    "L_b": {"formula": "mu' L/(b sigma)", "source": "Rubin & Ampuero 2005",
            "validity": "2-D, ageing (Dieterich) law; a, b local values at V"},
    "L_nu": {"formula": "1.3774 L_b (half-length)", "source": "Rubin & Ampuero 2005",
             "validity": "2-D ageing law with a/b <= 0.3781"},
    "L_inf": {"formula": "(1/pi) (b/(b - a))^2 L_b (half-length)", "source": "Rubin & Ampuero 2005",
              "validity": "2-D ageing law with 0.3781 < a/b < 1"},
}


def effective_modulus(shear_modulus: float, poisson: float | None, geometry: str) -> float:
    """μ′ of the geometry: G (antiplane), G/(1 − ν) (in-plane), G (circular, its own stiffness uses ν)."""
    if geometry == "inplane":
        return shear_modulus / (1.0 - _poisson(poisson, geometry))
    return shear_modulus


def patch_stiffness(h: float, shear_modulus: float, poisson: float | None = None,
                    geometry: str = "antiplane") -> float:
    """The elastic stiffness (Pa/m) of a fault patch of size ``h`` (m).

    2-D geometries: k = π μ′/h with h the wavelength of a sinusoidal slip (Rice & Ruina 1983);
    circular: a patch of diameter h = 2r under a uniform stress drop, k = Δτ/δ̄ =
    3π(2 − ν) G/(16 (1 − ν) r) with δ̄ the mean slip (Eshelby 1957).

    Raises
    ------
    InputError
        A size, modulus or Poisson's ratio out of range, or an unknown geometry.
    """
    geometry = check_geometry(geometry)
    h = _positive(h, "the patch size h (m)")
    G = _positive(shear_modulus, "the shear modulus G (Pa)")
    if geometry == "circular":
        nu = _poisson(poisson, geometry)
        return 3.0 * math.pi * (2.0 - nu) * G / (16.0 * (1.0 - nu) * (h / 2.0))
    return math.pi * effective_modulus(G, poisson, geometry) / h


def critical_size(k_c: float, shear_modulus: float, poisson: float | None = None,
                  geometry: str = "antiplane") -> float:
    """h* such that :func:`patch_stiffness` (h*) = k_c (the inverse of the patch stiffness, which is ∝ 1/h)."""
    return patch_stiffness(1.0, shear_modulus, poisson, geometry) / k_c


@dataclass(frozen=True)
class Nucleation:
    """The lengths of :func:`nucleation` (SI units; None where a formula does not apply, with the reason
    in ``notes``)."""

    law: str
    V: float
    sigma: float
    shear_modulus: float
    poisson: float | None
    geometry: str
    mu_prime: float
    a: float
    b: float
    L: float | None
    k_c: float | None
    h_star: float | None
    L_b: float | None
    L_nu: float | None
    L_inf: float | None
    regime: str
    notes: tuple[str, ...] = ()
    formulas: Mapping[str, Mapping[str, str]] = field(default_factory=lambda: FORMULAS)

    @property
    def a_over_b(self) -> float | None:
        """a/b (None where b = 0)."""
        return self.a / self.b if self.b != 0 else None

    def k_patch(self, h: float) -> float:
        """The stiffness of a patch of size ``h`` in this geometry (:func:`patch_stiffness`)."""
        return patch_stiffness(h, self.shear_modulus, self.poisson, self.geometry)

    def as_dict(self) -> dict[str, Any]:
        return {"law": self.law, "V": self.V, "sigma": self.sigma, "shear_modulus": self.shear_modulus,
                "poisson": self.poisson, "geometry": self.geometry, "mu_prime": self.mu_prime, "a": self.a,
                "b": self.b, "a_over_b": self.a_over_b, "L": self.L, "k_c": self.k_c, "h_star": self.h_star,
                "L_b": self.L_b, "L_nu": self.L_nu, "L_inf": self.L_inf, "regime": self.regime,
                "a_over_b_boundary": A_OVER_B_BOUNDARY, "notes": list(self.notes),
                "units": {"V": "m/s", "sigma": "Pa", "shear_modulus": "Pa", "mu_prime": "Pa", "L": "m",
                          "k_c": "Pa/m", "h_star": "m", "L_b": "m", "L_nu": "m", "L_inf": "m"},
                "formulas": {k: dict(v) for k, v in self.formulas.items()}}

    def __str__(self) -> str:
        def f(x, unit="m"):
            return "n/a" if x is None else f"{x:.6g} {unit}"
        what = "critical diameter" if self.geometry == "circular" else "critical wavelength pi mu'/k_c"
        r = self.a_over_b
        lines = [f"{self.law} at V = {self.V:g} m/s, sigma = {self.sigma:g} Pa, G = {self.shear_modulus:g} Pa, "
                 f"{self.geometry} (mu' = {self.mu_prime:.6g} Pa)",
                 f"  a = {self.a:.6g}, b = {self.b:.6g}, a/b = {'n/a' if r is None else f'{r:.6g}'}",
                 f"  k_c   = {f(self.k_c, 'Pa/m')}   (quasi-static critical stiffness)",
                 f"  h*    = {f(self.h_star)}   ({what})",
                 f"  L_b   = {f(self.L_b)}   (mu' L/(b sigma))",
                 f"  L_nu  = {f(self.L_nu)}   (1.3774 L_b, a/b <= 0.3781)",
                 f"  L_inf = {f(self.L_inf)}   ((b/(b-a))^2 L_b/pi, 0.3781 < a/b < 1)",
                 f"  regime: {self.regime}"]
        return "\n".join(lines + [f"  note: {n}" for n in self.notes])


def check_geometry(geometry: str) -> str:
    if geometry not in GEOMETRIES:
        raise InputError(f"unknown geometry {geometry!r} (known: {', '.join(GEOMETRIES)})")
    return geometry


def _positive(x, what: str) -> float:
    try:
        val = float(x)
    except (TypeError, ValueError):
        raise InputError(f"{what} must be a number, got {x!r}") from None
    if not (math.isfinite(val) and val > 0):
        raise InputError(f"{what} must be finite and > 0, got {x!r}")
    return val


def _poisson(nu, geometry: str) -> float:
    if nu is None:
        raise InputError(f"the {geometry} geometry needs Poisson's ratio nu (--poisson)")
    try:
        val = float(nu)
    except (TypeError, ValueError):
        raise InputError(f"Poisson's ratio nu must be a number, got {nu!r}") from None
    if not (math.isfinite(val) and -1.0 < val < 0.5):
        raise InputError(f"Poisson's ratio nu must lie in (-1, 0.5), got {nu!r}")
    return val


def shear_modulus_of(shear_modulus=None, density=None, shear_speed=None) -> float:
    """G given, or ρ c_s² from the density and the shear-wave speed (exactly one of the two ways)."""
    if shear_modulus is not None:
        if density is not None or shear_speed is not None:
            raise InputError("give the shear modulus G or the density and shear-wave speed (rho, c_s), not both")
        return _positive(shear_modulus, "the shear modulus G (Pa)")
    if density is None or shear_speed is None:
        raise InputError("give the shear modulus G (--shear-modulus PA) or both the density rho (--density KG_M3) "
                         "and the shear-wave speed c_s (--shear-speed M_S)")
    rho = _positive(density, "the density rho (kg/m^3)")
    return rho * _positive(shear_speed, "the shear-wave speed c_s (m/s)") ** 2


def local_a_b(law, V: float, params: Mapping[str, float]) -> tuple[float, float]:
    """(a, b) of ``law`` at slip rate V: a = V ∂μ/∂v at fixed state, b = a − V dμ_ss/dV (the parameters a and b
    themselves for the Dieterich law)."""
    import numpy as np
    import sympy as sp

    from landau.laws.law import v
    from landau.support.lambdify import lambdify_positional

    values = [float(params[p.name]) for p in law.parameters]
    phis = law.steady_state_values(np.array(V), params)
    args = [v, *law.states, *(p.symbol for p in law.parameters)]
    dmu_dv = lambdify_positional(args, sp.diff(law.mu, v), modules="numpy")
    a = V * float(dmu_dv(V, *(float(x) for x in phis), *values))
    ss = law.steady_state_closed_form
    if ss is not None:
        mu_ss = law.mu.subs(dict(zip(law.states, ss, strict=True)))
        slope = V * float(lambdify_positional([v, *(p.symbol for p in law.parameters)], sp.diff(mu_ss, v),
                                              modules="numpy")(V, *values))
    else:
        mu = lambdify_positional(args, law.mu, modules="numpy")
        h = 1e-4     # central difference in ln V: error ~ h^2 |d^3 mu_ss/d ln V^3| / 6
        up, dn = V * math.exp(h), V * math.exp(-h)
        slope = (float(mu(up, *law.steady_state_values(np.array(up), params), *values))
                 - float(mu(dn, *law.steady_state_values(np.array(dn), params), *values))) / (2 * h)
    return a, a - slope


def nucleation(law, V: float, sigma: float, *, shear_modulus: float | None = None, density: float | None = None,
               shear_speed: float | None = None, poisson: float | None = None, geometry: str = "antiplane",
               params: Mapping[str, float] | None = None) -> Nucleation:
    """The continuum fault's length scales for ``law`` at slip rate ``V`` (module docstring).

    Parameters
    ----------
    law : FrictionLaw or str
        A rate-and-state law or a built-in law's name (``"dieterich"``, ``"dieterich+flash"``).
    V : float
        The slip rate of steady sliding (m/s), e.g. the plate rate.
    sigma : float
        The effective normal stress σ (Pa).
    shear_modulus : float, optional
        G (Pa); or give ``density`` (kg/m³) and ``shear_speed`` (m/s), G = ρ c_s².
    poisson : float, optional
        ν, needed for the ``inplane`` and ``circular`` geometries.
    geometry : str
        ``antiplane``, ``inplane`` or ``circular`` (:data:`GEOMETRIES`).
    params : mapping, optional
        The law's parameter values (defaults: the law's).

    Returns
    -------
    Nucleation

    Raises
    ------
    InputError
        A bad or missing input, named.
    """
    import numpy as np

    from landau.derivation.linear import critical_stiffness
    from landau.laws import get_law
    from landau.laws.law import FrictionLaw
    from landau.systems.system import SpringBlock

    if isinstance(law, str):
        law = get_law(law)
    if not isinstance(law, FrictionLaw):
        raise InputError(f"nucleation needs a rate-and-state law (a FrictionLaw or a built-in name), "
                         f"got {type(law).__name__}")
    geometry = check_geometry(geometry)
    V = _positive(V, "the slip rate V (m/s)")
    sigma = _positive(sigma, "the effective normal stress sigma (Pa)")
    G = shear_modulus_of(shear_modulus, density, shear_speed)
    if geometry != "antiplane":
        poisson = _poisson(poisson, geometry)
    elif poisson is not None:
        poisson = _poisson(poisson, geometry)
    mu_p = effective_modulus(G, poisson, geometry)
    law_params = {k: float(x) for k, x in (params or {}).items()}
    for name in ("M", "sigma", "g"):
        if name in law_params:
            raise InputError(f"nucleation: {name!r} is not a law parameter (sigma is given on its own; the continuum "
                             "fault has no block mass)")
    block = SpringBlock(law)
    full = block.resolve({**law_params, "M": 0.0, "sigma": sigma})
    notes: list[str] = []
    a, b = local_a_b(law, V, full)
    kc = float(np.asarray(critical_stiffness(block, np.array([V]), full), dtype=float).ravel()[0])
    if math.isfinite(kc) and kc > 0:
        k_c: float | None = kc
        h_star: float | None = critical_size(kc, G, poisson, geometry)
    else:
        k_c = h_star = None
        notes.append("steady sliding is stable at every stiffness at this V (no critical stiffness): no h*")
    L = float(full["L"]) if any(p.name == "L" for p in law.parameters) else None
    L_b = L_nu = L_inf = None
    if geometry == "circular":
        notes.append("the Rubin-Ampuero lengths are 2-D results: not given for the circular geometry")
        regime = "n/a (3-D)"
    elif L is None:
        notes.append(f"law {law.name!r} has no memory length parameter 'L': L_b, L_nu, L_inf not given")
        regime = "n/a (no L)"
    elif not b > 0:
        notes.append(f"b = {b:.6g} <= 0 at V: L_b = mu' L/(b sigma) is not defined")
        regime = "n/a (b <= 0)"
    else:
        L_b = mu_p * L / (b * sigma)
        ratio = a / b
        if ratio <= A_OVER_B_BOUNDARY:
            L_nu = L_NU_OVER_L_B * L_b
            regime = (f"a/b = {ratio:.4g} <= {A_OVER_B_BOUNDARY}: nucleation localises to the half-length "
                      f"L_nu = 1.3774 L_b (Rubin & Ampuero 2005)")
        elif ratio < 1:
            L_inf = (b / (b - a)) ** 2 * L_b / math.pi
            regime = (f"{A_OVER_B_BOUNDARY} < a/b = {ratio:.4g} < 1: nucleation grows as a crack towards the "
                      f"half-length L_inf = (b/(b-a))^2 L_b/pi (Rubin & Ampuero 2005)")
        else:
            regime = f"a/b = {ratio:.4g} >= 1: velocity strengthening at V, no nucleation"
        if not law.name.startswith("dieterich") or "+" in law.name:
            notes.append(f"Rubin & Ampuero's lengths are derived for the ageing (Dieterich) law; for {law.name!r} "
                         "they use the law's local a and b at V (an estimate)")
    return Nucleation(law.name, V, sigma, G, poisson, geometry, mu_p, a, b, L, k_c, h_star, L_b, L_nu, L_inf,
                      regime, tuple(notes))


__all__ = ["A_OVER_B_BOUNDARY", "FORMULAS", "GEOMETRIES", "L_NU_OVER_L_B", "Nucleation", "critical_size",
           "effective_modulus", "local_a_b", "nucleation", "patch_stiffness", "shear_modulus_of"]
