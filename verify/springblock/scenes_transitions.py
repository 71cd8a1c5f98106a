"""Published transition values of Putelat, Dawes & Willis (2010): V*, c*, codimension-two points, Γ_DR^max.

Every value is computed by the toolkit (:mod:`landau.analyses.transition`, :mod:`landau.analyses.amplitude`)
from the law; the paper's number is only the reference.  Tolerances reflect the printed
digits (0.5 % for 3–4 digits).
"""

from __future__ import annotations

import math
from functools import lru_cache

from landau.derivation.multiscale import Derivation
from landau.errors import InputError
from landau.laws import get_law
from landau.scenes import Scene, register
from landau.systems.system import SpringBlock

_T1 = {"a_v": 0.369, "a": 0.0349, "b": 0.0489, "L": 0.9e-6, "V_s": 1e-6}
_MECH = {"M": 1.2, "g": 9.81}
_TOL = 5e-3


@lru_cache(maxsize=None)
def _derivation(law: str) -> Derivation:
    return Derivation(SpringBlock(get_law(law)))


def _params(p: dict) -> dict:
    q = {k: v for k, v in p.items() if k != "g"}
    q["sigma"] = p["M"] * p["g"]  # σ = Mg (Table 1: M = 1.2 kg, σ = 11.772 N)
    return q


def _v_hat(q: dict) -> float:
    """Inertial crossover velocity V̂ = sqrt(aσL/M) (eq. 31): the velocity scale of the transitions."""
    return math.sqrt(q["a"] * q["sigma"] * q["L"] / q["M"])


def _c_crit(q: dict) -> float:
    """c_crit = (b/a − 1) V_* / V̂ (Sec. 4.1): the residual-strength scale of c*."""
    return (q["b"] / q["a"] - 1) * q["V_s"] / _v_hat(q)


def _codim2(law: str, index: int, what: str = "V"):
    def compute(p: dict) -> dict:
        from landau.analyses.transition import codim2_points

        q = _params(p)
        # V window from the law's velocity scale: the published V* lie within 1e-2..2 V̂ (eq. 31)
        pts = codim2_points(_derivation(law), 1e-5 * _v_hat(q), 1e2 * _v_hat(q), q)
        if len(pts) <= index:
            raise InputError(f"{law}: Λ changes sign {len(pts)} time(s) on the Hopf line for "
                             f"{1e-5 * _v_hat(q):.3g} < V < {1e2 * _v_hat(q):.3g} m/s; no point number {index + 1}")
        pt = pts[index]
        return {"value": getattr(pt, what), "V": pt.V, "k_c": pt.k_c, "kc": pt.k_c, "omega_c": pt.omega_c,
                "sign_below": pt.sign_below, "sign_above": pt.sign_above, "n_points": len(pts)}
    return compute


def _c_star(what: str):
    def compute(p: dict) -> dict:
        from landau.analyses.transition import critical_parameter

        q = _params(p)
        q.pop("c", None)
        # c window from the closed-form scale c_crit (Sec. 4.1); c* ≈ 1.25 c_crit for Table 1
        cs = critical_parameter(_derivation("modified-dieterich"), "c", _c_crit(q) / 8, 3 * _c_crit(q), q)
        if not cs:
            raise InputError(f"modified-dieterich: no critical residual strength c* in "
                             f"[{_c_crit(q) / 8:.3g}, {3 * _c_crit(q):.3g}] for these parameters")
        return {"value": cs[0].value if what == "c" else cs[0].V_ext, "c_star": cs[0].value, "V_m": cs[0].V_ext}
    return compute


def _spinodal_c_crit(p: dict) -> dict:
    # Sec. 4.1: c_crit = (b/a − 1) V_* / sqrt(Laσ/M), the c for which V_m ≈ V̂ (inertia matters for c < c_crit)
    return {"value": _c_crit(_params(p))}


def _spinodal_critical_c(p: dict) -> dict:
    from landau.analyses.transition import critical_parameter

    q = _params(p)
    q.pop("c", None)
    cs = critical_parameter(_derivation("spinodal"), "c", _c_crit(q) / 4, 3 * _c_crit(q), q, n=12)
    if not cs:
        raise InputError(f"spinodal: no critical residual strength c* in "
                         f"[{_c_crit(q) / 4:.3g}, {3 * _c_crit(q):.3g}] for these parameters")
    return {"value": cs[0].value, "V_m": cs[0].V_ext}


def _gamma_max_velocity(p: dict) -> dict:
    from landau.analyses.amplitude import growth_rate_max

    q = _params(p)
    V_hat = _v_hat(q)
    g = growth_rate_max(_derivation("dieterich"), q, 1e-4 * V_hat, 1e2 * V_hat)  # window on the scale V̂
    return {"value": g.V / V_hat, "V": g.V, "V_hat": V_hat, "Gamma_max_per_dk": g.value}


register(Scene(
    name="putelat2010/c-star", parameter="c_star", units="",
    source="Putelat et al. 2010, Sec. 4.2 and 6: c* ≈ 9.02e-4 (law 39)",
    compute=_c_star("c"), defaults={**_T1, **_MECH}, published=9.02e-4, tolerance=_TOL,
    description="critical residual strength: above it V* does not exist (Hopf supercritical on all of the range)"))

register(Scene(
    name="putelat2010/V-m-at-c-star", parameter="V_m(c*)", units="m/s",
    source="Putelat et al. 2010, Secs 4.2 and 6: V_m(c*) ≈ 4.447e-4 m/s",
    compute=_c_star("V"), defaults={**_T1, **_MECH}, published=4.447e-4, tolerance=_TOL,
    description="where the transition line k*(V*) reaches k = 0"))

register(Scene(
    name="putelat2010/V-star-modified-dieterich", parameter="V_star", units="m/s",
    source="Putelat et al. 2010, Sec. 4.2 (c = 3e-4): V* ≈ 1.109e-3 m/s",
    compute=_codim2("modified-dieterich", 0), defaults={**_T1, **_MECH, "c": 3e-4},
    published=1.109e-3, tolerance=_TOL,
    description="transition velocity of law (39): Λ = 0 (zero of P7), supercritical below, subcritical above"))

register(Scene(
    name="putelat2010/dieterich-codim2-kc", parameter="k_c(V*)", units="N/m",
    source="Putelat et al. 2010, Fig. 5(b): k ≈ 2.08e5 N/m (the printed V = 2.31e-5 m/s is not reproducible; Table 1 "
           "gives ≈ 2.07e-4)",
    compute=_codim2("dieterich", 0, "kc"), defaults={**_T1, **_MECH},
    published=2.08e5, tolerance=_TOL,
    description="stiffness of the Dieterich codimension-two point (Λ_D = 0, V from eq. 34 read with V̂)"))

register(Scene(
    name="putelat2010/spinodal-c-crit", parameter="c_crit", units="",
    source="Putelat et al. 2010, Sec. 4.1: c_crit ≈ 7.2e-4",
    compute=_spinodal_c_crit, defaults={**_T1, **_MECH}, published=7.2e-4, tolerance=_TOL,
    description="residual strength below which inertia affects k_c of the spinodal law"))

register(Scene(
    name="putelat2010/spinodal-critical-c", parameter="c*", units="",
    source="Putelat et al. 2010, Figs 9-10, 12: V* exists for c = 3e-4, not for 1e-3 (no value printed; "
           "compared with c* ≈ 9.02e-4 of the approximation (39))",
    compute=_spinodal_critical_c, defaults={**_T1, **_MECH, "t_ss": 90.0}, published=9.02e-4, tolerance=0.02,
    description="critical residual strength of the full spinodal law (37)-(38), found generically"))

register(Scene(
    name="putelat2010/Gamma-DR-max-velocity", parameter="V/V_hat", units="",
    source="Putelat et al. 2010, Sec. 3.2: Γ_DR is maximal at V ≈ 0.552 V̂",
    compute=_gamma_max_velocity, defaults={**_T1, **_MECH}, published=0.552, tolerance=1e-3,
    description="velocity of the maximal growth rate of the Dieterich–Ruina laws, in units of V̂ (eq. 31)"))

for _law, _i, _pub, _src, _extra in (
        ("nanoscale", 0, 6.24e-6, "Fig. 15-16: V_l* ≈ 6.24e-6 m/s", {"a2": 0.0085}),
        ("nanoscale", 1, 3.41e-4, "Fig. 15-16: V_h* ≈ 3.41e-4 m/s", {"a2": 0.0085}),
        ("micron-scale", 0, 1.039e-5, "Fig. 18: V_l* ≈ 1.039e-5 m/s", {"c": 1.4e-2}),
        ("micron-scale", 1, 2.07e-4, "Fig. 18: V_h* ≈ 2.07e-4 m/s (log10 2.3179 → 2.0794e-4)", {"c": 1.4e-2})):
    register(Scene(
        name=f"putelat2010/{_law}-V-star-{'low' if _i == 0 else 'high'}", parameter="V_star", units="m/s",
        source=f"Putelat et al. 2010, {_src}", compute=_codim2(_law, _i),
        defaults={**_T1, **_MECH, **_extra}, published=_pub, tolerance=_TOL,
        description=f"{'low' if _i == 0 else 'high'}-velocity change of nature of the Hopf bifurcation, {_law} law"))
