"""The continuum fault's length scales: h*, L_b, the Rubin–Ampuero lengths and a patch's stiffness.

``landau nucleation LAW --V V --sigma PA (--shear-modulus PA | --density KG_M3 --shear-speed M_S)
[--poisson NU] [--geometry antiplane|inplane|circular] [--patch H] [--param NAME=VALUE ...] [--json]``

For a rate-and-state law (a built-in name, with modifiers such as ``dieterich+flash``, or
``--mu``/``--state``) at the slip rate V of steady sliding under the effective normal stress σ:
the quasi-static critical stiffness k_c, the critical wavelength h* = π μ′/k_c (Rice & Ruina
1983; Rice 1993), L_b = μ′L/(bσ) and Rubin & Ampuero's (2005) L_ν or L_∞ with their a/b regime,
and, with ``--patch H``, the stiffness of a patch of size H (the spring–block stiffness
equivalent to it; ``landau hopf spring-block --patch H`` analyses that patch).  μ′ = G
(antiplane), G/(1 − ν) (in-plane); the circular geometry uses the stiffness of a circular patch
(Eshelby 1957).  Every formula's source and regime of validity are in the output
(``formulas``) and in docs/models/nucleation.md.
"""

from __future__ import annotations

from landau.cli.common import add_law_arguments, parse_floats, parse_velocities, resolve_law
from landau.cli.model_args import add_elastic_arguments
from landau.errors import InputError


def _number(text, what: str) -> float | None:
    if text is None:
        return None
    vals = parse_floats(text, what)
    if len(vals) != 1:
        raise InputError(f"{what}: give one number, got {text!r}")
    return vals[0]


def configure(p) -> None:
    add_law_arguments(p)
    p.add_argument("--V", default=None, help="the slip rate of steady sliding in m/s (e.g. the plate rate)")
    p.add_argument("--sigma", default=None, metavar="PA", help="the effective normal stress in Pa")
    add_elastic_arguments(p)
    p.add_argument("--patch", default=None, metavar="H", help="also the stiffness of a patch of size H in m")


def run(args) -> dict:
    from landau.analyses.nucleation import nucleation

    law, params = resolve_law(args)
    if args.V is None:
        raise InputError("landau nucleation: give the slip rate --V in m/s")
    Vs = parse_velocities(args.V)
    if len(Vs) != 1:
        raise InputError("landau nucleation: give one slip rate --V")
    sigma = _number(args.sigma, "--sigma")
    if sigma is None:
        raise InputError("landau nucleation: give the effective normal stress --sigma in Pa")
    res = nucleation(law, Vs[0], sigma, shear_modulus=_number(args.shear_modulus, "--shear-modulus"),
                     density=_number(args.density, "--density"), shear_speed=_number(args.shear_speed, "--shear-speed"),
                     poisson=_number(args.poisson, "--poisson"), geometry=args.geometry or "antiplane", params=params)
    doc = res.as_dict()
    text = str(res)
    patch = _number(args.patch, "--patch")
    if patch is not None:
        kp = res.k_patch(patch)
        doc["patch"] = patch
        doc["k_patch"] = kp
        doc["units"].update(patch="m", k_patch="Pa/m")
        verdict = ("unstable (k_patch < k_c)" if res.k_c is not None and kp < res.k_c else "stable")
        doc["patch_steady_sliding"] = verdict.split()[0]
        text += f"\n  patch h = {patch:g} m: k = {kp:.6g} Pa/m, steady sliding {verdict}"
    doc["text"] = text
    return doc


def render(doc: dict) -> str:
    return doc.get("text") or repr(doc)
