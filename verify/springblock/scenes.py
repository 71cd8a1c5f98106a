"""Published linear-stability facts of Putelat, Dawes & Willis, J. Mech. Phys. Solids (2010).

Each scene computes its value with the toolkit (nothing typed in) next to the number the
paper prints.
"""

from __future__ import annotations

import math

from landau.analyses.transition import extrema
from landau.derivation.multiscale import Derivation
from landau.errors import InputError
from landau.laws import get_law
from landau.scenes import Scene, register
from landau.systems.system import SpringBlock

_T1 = {"a_v": 0.369, "a": 0.0349, "b": 0.0489, "L": 0.9e-6, "V_s": 1e-6}
_MECH = {"M": 1.2, "g": 9.81}


def _v_hat(p: dict) -> float:
    # eq. (31): V̂ = sqrt(a σ L / M), σ = M g
    return math.sqrt(p["a"] * p["M"] * p["g"] * p["L"] / p["M"])


def _v_m_eq41(p: dict) -> float:
    """The minimum of μ_ss of law (39) in closed form, V_m = (b/a − 1) V_*/c (eq. 41)."""
    if p["c"] == 0:
        return math.inf
    return (p["b"] / p["a"] - 1) * p["V_s"] / p["c"]


#: the velocity window (m/s) where the extrema of μ_ss are searched: beyond it powers of V leave float64
V_WINDOW = (1e-20, 1e20)


def _window(law: str, kind: str, p: dict, scales: dict[str, float]) -> tuple[float, float]:
    """Three decades beyond the law's velocity scales (name -> value), refused by name where a
    scale is not a positive finite velocity or the window leaves :data:`V_WINDOW`."""
    for what, v in scales.items():
        if not (math.isfinite(v) and v > 0):
            raise InputError(f"the {law} law's velocity scale {what} = {v:g} m/s is not positive and finite for "
                             f"these parameters, so mu_ss has no {kind} to find (c, L, t_ss, V_s > 0 and b > a)")
    lo, hi = 1e-3 * min(scales.values()), 1e3 * max(scales.values())
    if lo < V_WINDOW[0] or hi > V_WINDOW[1]:
        scale = ", ".join(f"{k} = {v:.3g} m/s" for k, v in scales.items())
        raise InputError(f"the {law} law's velocity scales ({scale}) put the search for the {kind} of mu_ss "
                         f"outside {V_WINDOW[0]:g} to {V_WINDOW[1]:g} m/s: bring the parameters nearer their "
                         "physical scale")
    return lo, hi


def _first_extremum(law: str, kind: str, p: dict, lo: float, hi: float):
    d = Derivation(SpringBlock(get_law(law)))
    ex = [e for e in extrema(d, {**p, "sigma": p["M"] * p["g"]}, lo, hi) if e.kind == kind]
    if not ex:
        raise InputError(f"the {law} law has no {kind} of mu_ss in [{lo:.3g}, {hi:.3g}] m/s for these parameters")
    return ex[0]


def _spinodal_extremum(kind: str):
    def compute(p: dict) -> dict:
        # V window from the law's velocity scales: L/t_ss (healing; V_M ≈ 2.5 L/t_ss for Table 1)
        # and V_m of eq. (41) (V_m ≈ 1.01 × eq. 41), three decades beyond each
        scales = {"L/t_ss": p["L"] / p["t_ss"] if p["t_ss"] != 0 else math.inf, "V_m (eq. 41)": _v_m_eq41(p)}
        e = _first_extremum("spinodal", kind, p, *_window("spinodal", kind, p, scales))
        return {"value": e.V, "mu_ss": e.mu}
    return compute


def _modified_dieterich_vm(p: dict) -> dict:
    closed = _v_m_eq41(p)
    # three decades around eq. (41)
    e = _first_extremum("modified-dieterich", "minimum", p, *_window("modified-dieterich", "minimum", p,
                                                                    {"V_m (eq. 41)": closed}))
    return {"value": e.V, "closed_form_eq41": closed}


def _mu_ss_extremum_scene(name: str, parameter: str, source: str, compute, extra: dict, published: float,
                          description: str) -> None:
    register(Scene(name=name, parameter=parameter, units="m/s", source=source, compute=compute,
                   defaults={**_T1, **_MECH, **extra}, published=published, tolerance=5e-4,
                   description=description))


register(Scene(
    name="putelat2010/V-hat", parameter="V_hat", units="m/s",
    source="Putelat et al. 2010, eq. (31) (prints 5.6e-4, rounded)",
    compute=_v_hat, defaults={**_T1, **_MECH}, published=5.6e-4, tolerance=0.01,
    description="inertial crossover velocity V̂ = sqrt(aσL/M) of the Dieterich–Ruina laws"))

_SPINODAL = {"c": 1e-3, "t_ss": 90.0}
_mu_ss_extremum_scene("putelat2010/spinodal-V_M", "V_M", "Putelat et al. 2010, Sec. 4.1 (c = 1e-3): V_M = 2.493e-8 m/s",
                      _spinodal_extremum("maximum"), _SPINODAL, 2.493e-8,
                      "local maximum of μ_ss of the spinodal law (37)–(38): lower end of the stick–slip domain")
_mu_ss_extremum_scene("putelat2010/spinodal-V_m", "V_m", "Putelat et al. 2010, Sec. 4.1 (c = 1e-3): V_m = 4.052e-4 m/s",
                      _spinodal_extremum("minimum"), _SPINODAL, 4.052e-4,
                      "local minimum of μ_ss of the spinodal law (37)–(38): upper end of the stick–slip domain")
_mu_ss_extremum_scene("putelat2010/modified-dieterich-V_m", "V_m",
                      "Putelat et al. 2010, eq. (41) and Sec. 4.2 (c = 3e-4): V_m ≈ 1.337e-3 m/s",
                      _modified_dieterich_vm, {"c": 3e-4}, 1.337e-3,
                      "minimum of μ_ss of law (39), found numerically; eq. (41) closed form reported beside it")
