"""Published linear-stability facts of Putelat, Dawes & Willis, J. Mech. Phys. Solids (2010).

Each scene computes its value with the toolkit (nothing typed in) next to the number the
paper prints.
"""

from __future__ import annotations

import math

from landau.errors import InputError
from landau.scenes import Scene, register
from landau.multiscale import Derivation
from landau.transition import extrema
from landau.system import SpringBlock
from landau.laws import get_law

_T1 = {"a_v": 0.369, "a": 0.0349, "b": 0.0489, "L": 0.9e-6, "V_s": 1e-6}
_MECH = {"M": 1.2, "g": 9.81}


def _v_hat(p: dict) -> float:
    # eq. (31): V̂ = sqrt(a σ L / M), σ = M g
    return math.sqrt(p["a"] * p["M"] * p["g"] * p["L"] / p["M"])


def _spinodal_extremum(kind: str):
    def compute(p: dict) -> dict:
        d = Derivation(SpringBlock(get_law("spinodal")))
        ex = [e for e in extrema(d, {**p, "sigma": p["M"] * p["g"]}, 1e-12, 1.0) if e.kind == kind]
        if not ex:
            raise InputError(f"the spinodal law has no {kind} of mu_ss for these parameters")
        return {"value": ex[0].V, "mu_ss": ex[0].mu}
    return compute


def _modified_dieterich_vm(p: dict) -> dict:
    d = Derivation(SpringBlock(get_law("modified-dieterich")))
    ex = [e for e in extrema(d, {**p, "sigma": p["M"] * p["g"]}, 1e-9, 10.0) if e.kind == "minimum"]
    closed = (p["b"] / p["a"] - 1) * p["V_s"] / p["c"]  # eq. (41)
    return {"value": ex[0].V, "closed_form_eq41": closed}


register(Scene(
    name="putelat2010/V-hat", parameter="V_hat", units="m/s",
    source="Putelat et al. 2010, eq. (31) (prints 5.6e-4, rounded)",
    compute=_v_hat, defaults={**_T1, **_MECH}, published=5.6e-4, tolerance=0.01,
    description="inertial crossover velocity V̂ = sqrt(aσL/M) of the Dieterich–Ruina laws"))

register(Scene(
    name="putelat2010/spinodal-V_M", parameter="V_M", units="m/s",
    source="Putelat et al. 2010, Sec. 4.1 (c = 1e-3): V_M = 2.493e-8 m/s",
    compute=_spinodal_extremum("maximum"), defaults={**_T1, **_MECH, "c": 1e-3, "t_ss": 90.0},
    published=2.493e-8, tolerance=5e-4,
    description="local maximum of μ_ss of the spinodal law (37)–(38): lower end of the stick–slip domain"))

register(Scene(
    name="putelat2010/spinodal-V_m", parameter="V_m", units="m/s",
    source="Putelat et al. 2010, Sec. 4.1 (c = 1e-3): V_m = 4.052e-4 m/s",
    compute=_spinodal_extremum("minimum"), defaults={**_T1, **_MECH, "c": 1e-3, "t_ss": 90.0},
    published=4.052e-4, tolerance=5e-4,
    description="local minimum of μ_ss of the spinodal law (37)–(38): upper end of the stick–slip domain"))

register(Scene(
    name="putelat2010/modified-dieterich-V_m", parameter="V_m", units="m/s",
    source="Putelat et al. 2010, eq. (41) and Sec. 4.2 (c = 3e-4): V_m ≈ 1.337e-3 m/s",
    compute=_modified_dieterich_vm, defaults={**_T1, **_MECH, "c": 3e-4},
    published=1.337e-3, tolerance=5e-4,
    description="minimum of μ_ss of law (39), found numerically; eq. (41) closed form reported beside it"))
