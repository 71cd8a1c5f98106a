"""A fault patch as a spring–block: ``landau hopf spring-block --patch H --shear-modulus G``.

The stiffness of a patch of size H in an elastic medium (:func:`landau.analyses.nucleation.patch_stiffness`:
k = π μ′/H in 2-D, Rice & Ruina 1983; a circular patch of diameter H, Eshelby 1957) is the spring of
a block of unit area (σ in Pa, k in Pa/m, M in kg/m²).  The Hopf analysis of the block gives k_c,
Λ and the criticality; the patch adds its own stiffness, the critical patch size H_c = H k_patch/k_c
(k_patch ∝ 1/H) at which the patch is at onset, the verdict (steady sliding of the patch unstable
for k_patch < k_c, i.e. H > H_c), the distance ε² = (k_c − k_patch)/k_c and, on the side where the
cycle exists, the predicted amplitude C·sqrt|k_c − k_patch|.  Validity: that of the single-degree-of-
freedom reduction of a patch (one slip mode of the patch; Rice 1993) and of the patch stiffness.
"""

from __future__ import annotations

import math
from dataclasses import replace
from typing import Any

from landau.errors import InputError
from landau.models import Option, Setup

#: the patch's options (``--patch``, ``--shear-modulus`` …), by name
OPTIONS = (
    Option("patch", "the size H of a fault patch in m: k from the patch (Pa/m), sigma in Pa"),
    Option("shear_modulus", "the patch's shear modulus G in Pa (or --density and --shear-speed)"),
    Option("density", "the density rho in kg/m^3 (G = rho c_s^2)"),
    Option("shear_speed", "the shear-wave speed c_s in m/s"),
    Option("poisson", "Poisson's ratio nu (inplane, circular)"),
    Option("geometry", "the patch's geometry: antiplane, inplane or circular (default antiplane)"),
)
NAMES = tuple(o.name for o in OPTIONS)


def patch_stiffness_of(setup: Setup) -> float | None:
    """The patch's stiffness (Pa/m) from the setup's options, None without ``patch``; elastic options without
    ``patch`` are an InputError."""
    from landau.analyses.nucleation import patch_stiffness, shear_modulus_of

    h = setup.option("patch")
    if h is None:
        given = [o.cli_flag for o in OPTIONS[1:] if setup.option(o.name) is not None]
        if given:
            raise InputError(f"spring-block: {given[0]} describes a fault patch: give its size with --patch H")
        return None
    if "sigma" not in setup.params:
        raise InputError("spring-block --patch: give the effective normal stress of the patch in Pa "
                         "(--param sigma=PA); the patch is a block of unit area")
    G = shear_modulus_of(setup.option("shear_modulus"), setup.option("density"), setup.option("shear_speed"))
    return patch_stiffness(_float(h, "--patch"), G, setup.option("poisson"), setup.option("geometry") or "antiplane")


def _float(x: Any, what: str) -> float:
    try:
        return float(x)
    except (TypeError, ValueError):
        raise InputError(f"{what}: {x!r} is not a number") from None


def with_patch(res, setup: Setup, k_patch: float):
    """``res`` (the block's HopfResult) with the patch's numbers in its ``extra``."""
    h = _float(setup.option("patch"), "--patch")
    kc = float(res.p_c)
    unstable = k_patch < kc
    amp = res.amplitude(k_patch) if unstable else math.nan
    extra = {**res.extra, "patch": h, "k_patch": k_patch, "patch_critical_size": h * k_patch / kc,
             "patch_eps2": (kc - k_patch) / kc, "patch_steady_sliding": "unstable" if unstable else "stable",
             "patch_amplitude": None if not math.isfinite(amp) else amp}
    return replace(res, extra=extra)


def patch_text(doc: dict) -> str:
    """The patch's line of ``landau hopf``'s text."""
    if "k_patch" not in doc:
        return ""
    amp = doc.get("patch_amplitude")
    tail = f", predicted slip amplitude {amp:.6g} m" if amp is not None else ""
    return (f"\npatch H = {doc['patch']:g} m: k_patch = {doc['k_patch']:.6g} Pa/m, critical size "
            f"H_c = {doc['patch_critical_size']:.6g} m, eps2 = {doc['patch_eps2']:.6g}: steady sliding "
            f"{doc['patch_steady_sliding']}{tail}")
