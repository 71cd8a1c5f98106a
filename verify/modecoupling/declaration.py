"""The friction-induced flutter of Hoffmann et al. (2002) declared as the model ``mode-coupling``.

A mass m on a belt moving at v0, held by springs k1, k2 at angles alpha1, alpha2 (degrees), pressed on
by a preload P through a contact N(y) (``contact`` option: linear k_H y, cubic k_H y + k_NL y^3, Hertz
k_H y^{3/2}), with diagonal damping c1, c2 (Hoffmann & Gaul 2003) and Coulomb friction mu (or any
velocity law of the friction coefficient, ``friction`` option).  The N-DOF family: the structure's
matrices as options (``mass_matrix``, ``damping_matrix``, ``stiffness_matrix``: JSON rows such as
``[[2,0],[0,1]]``, or arrays) with the ``normal`` and ``tangential`` coordinate indices; its damping
scaled by the parameter ``c_scale``.  The defaults of the 2-DOF model are illustrative (not a
figure of the papers): a flutter near mu = 0.51 at about 26 Hz.

The Hopf analysis (:func:`landau.analyses.flutter.flutter_hopf`): in the bifurcation parameter
(``parameter`` option, default mu) within ``bracket`` (default 0 to 2 for mu), the Hopf point with
its amplitude equation where the sliding motion is damped (``kind = "hopf"``), and the named
mode-coupling result (``kind = "mode-coupling"``: mu_c, the merging frequency and the two modes)
where it is undamped.

References
----------
Hoffmann, N., Fischer, M., Allgaier, R. & Gaul, L. (2002), A minimal model for studying properties of the
mode-coupling type instability in friction induced oscillations, Mech. Res. Commun. 29, 197–205.
Hoffmann, N. & Gaul, L. (2003), Effects of damping on mode-coupling instability in friction induced
oscillations, Z. Angew. Math. Mech. 83, 524–534.
"""

from __future__ import annotations

import json
from typing import Any

from landau.errors import InputError
from landau.models import LawKind, Model, Option, Parameter, Setup

SOURCE = "Hoffmann et al. (2002), eqs (1)-(2); illustrative values"
SOURCE_DAMPING = "Hoffmann & Gaul (2003), diagonal damping; illustrative values"
#: the 2-DOF model's parameters: domain, unit, meaning (defaults: HOFFMANN_DEFAULTS)
_HOFFMANN = {"m": ("positive", "kg", "mass", SOURCE),
             "k1": ("nonnegative", "N/m", "stiffness of the first spring", SOURCE),
             "k2": ("nonnegative", "N/m", "stiffness of the second spring", SOURCE),
             "alpha1": ("real", "deg", "angle of the first spring to the belt (degrees)", SOURCE),
             "alpha2": ("real", "deg", "angle of the second spring to the belt (degrees)", SOURCE),
             "c1": ("nonnegative", "N s/m", "damping of the tangential coordinate x", SOURCE_DAMPING),
             "c2": ("nonnegative", "N s/m", "damping of the normal coordinate y", SOURCE_DAMPING)}
#: the contact's and the friction's parameters (every member of the family)
_CONTACT = {"kH": ("positive", "N/m", "contact stiffness k_H (N/m^1.5 for Hertz)"),
            "kNL": ("real", "N/m^3", "cubic contact stiffness k_NL (> 0 hardening, < 0 softening; cubic only)"),
            "P": ("real", "N", "preload pressing the mass onto the belt"),
            "v0": ("positive", "m/s", "belt speed")}
_MATRIX_OPTIONS = ("mass_matrix", "damping_matrix", "stiffness_matrix")


def _matrices_given(setup: Setup) -> bool:
    return any(setup.option(o) is not None for o in _MATRIX_OPTIONS)


def _declare(setup: Setup) -> tuple[Parameter, ...]:
    from landau.laws.velocity import declared_names
    from landau.systems.mode_coupling import HOFFMANN_DEFAULTS as D

    out: list[Parameter] = []
    if _matrices_given(setup):
        out.append(Parameter("c_scale", 1.0, "1", "nonnegative", "factor of the damping matrix", "the user's matrices"))
    else:
        out += [Parameter(n, D[n], unit, dom, meaning, src) for n, (dom, unit, meaning, src) in _HOFFMANN.items()]
    out += [Parameter(n, D[n], unit, dom, meaning, SOURCE) for n, (dom, unit, meaning) in _CONTACT.items()]
    if setup.option("friction") is None:
        out.append(Parameter("mu", D["mu"], "1", "nonnegative", "Coulomb friction coefficient", SOURCE))
    else:
        names = declared_names(setup.option("friction"), None)
        taken = sorted(set(names) & {p.name for p in out})
        if taken:
            raise InputError(f"mode-coupling: the friction law's parameter {taken[0]!r} is a parameter of the model "
                             f"({_CONTACT.get(taken[0], _HOFFMANN.get(taken[0], ('', '', '')))[2]}): rename it in "
                             "--friction")
        out += [Parameter(n, setup.params.get(n), "1", "real", "a parameter of the friction law", "the user's law")
                for n in names]
    return tuple(out)


def _hopf_parameter(setup: Setup) -> str | None:
    parameter = setup.option("parameter")
    if parameter is not None:
        return str(parameter)
    if setup.option("friction") is None:
        return "mu"
    from landau.laws.velocity import declared_names

    names = declared_names(setup.option("friction"), None)
    return "mu" if "mu" in names else (names[0] if names else None)


def _matrix_option(setup: Setup, name: str) -> Any:
    value = setup.option(name)
    if isinstance(value, str):
        try:
            value = json.loads(value)
        except ValueError:
            raise InputError(f"mode-coupling: --{name.replace('_', '-')} must be rows of numbers such as "
                             f"[[2,0],[0,1]], got {value!r}") from None
    return value


def _index(setup: Setup, name: str, default: int) -> int:
    value = setup.option(name, default)
    if isinstance(value, bool) or not (isinstance(value, int) or (isinstance(value, str) and value.strip().isdigit())):
        raise InputError(f"mode-coupling: --{name} must be a coordinate index (0, 1, ...), got {value!r}")
    return int(value)


def system_of(setup: Setup):
    """The :class:`~landau.systems.mode_coupling.ModeCoupling` of the setup (the 2-DOF model, or the matrices)."""
    import numpy as np

    from landau.laws.velocity import coulomb, law_from_options
    from landau.systems.mode_coupling import HOFFMANN_DEFAULTS, ContactLaw, ModeCoupling

    if setup.option("friction_neg") is not None:
        raise InputError("mode-coupling: --friction-neg does not apply (the belt slides one way: v0 - xdot > 0)")
    params = dict(setup.params)
    user = setup.option("friction") is not None
    law = law_from_options(setup.option("friction"), None, setup.option("friction_name"), coulomb(), params) \
        if user else None
    declared = {p.name: p for p in _declare(setup)}
    for k in list(params):
        if k not in declared:
            raise InputError(f"mode-coupling: unknown parameter {k!r} (known: {', '.join(sorted(declared))})")
        params[k] = declared[k].check(params[k], "mode-coupling")
    contact = setup.option("contact", "cubic")
    if not _matrices_given(setup):
        return ModeCoupling.hoffmann2002(contact=contact, friction=law, **params)
    M, C, K = (_matrix_option(setup, o) for o in _MATRIX_OPTIONS)
    if M is None or K is None:
        raise InputError("mode-coupling: an N-DOF system needs its mass and stiffness matrices (--mass-matrix, "
                         "--stiffness-matrix; --damping-matrix default 0)")
    if C is None:
        C = np.zeros(np.shape(np.array(M, dtype=float)))
    v = {**{k: HOFFMANN_DEFAULTS[k] for k in ("kH", "kNL", "P", "v0", "mu")}, "c_scale": 1.0, **params}
    friction = law if user else v["mu"]
    mc = ModeCoupling(M, C, K, _index(setup, "normal", 1), _index(setup, "tangential", 0), v["P"], v["v0"],
                      ContactLaw(contact, v["kH"], v["kNL"]), friction)
    return mc.with_value("c_scale", v["c_scale"]) if v["c_scale"] != 1.0 else mc


def mode_coupling_hopf(setup: Setup):
    """The flutter onset of the setup's system (:func:`landau.analyses.flutter.flutter_hopf`)."""
    from landau.analyses.flutter import flutter_hopf

    hp, setup = _hopf_setup(setup)
    return flutter_hopf(system_of(setup), hp, setup.option("bracket"))


def _hopf_setup(setup: Setup) -> tuple[str, Setup]:
    """The bifurcation parameter and the setup the Hopf analysis builds the system from (a parameter of
    the friction law as the bifurcation parameter gets a starting value: the scan sets it)."""
    hp = _hopf_parameter(setup)
    if hp is None:
        raise InputError("mode-coupling: name the bifurcation parameter (--parameter NAME)")
    if hp in setup.params:
        raise InputError(f"mode-coupling: {hp!r} is the bifurcation parameter: its critical value is computed, it "
                         "cannot be given or swept (choose another with --parameter)")
    if setup.option("friction") is not None and hp not in {p.name for p in _declare(setup) if p.default is not None}:
        from dataclasses import replace

        setup = replace(setup, params={**setup.params, hp: 0.3})
    return hp, setup


def mode_coupling_cycles(setup: Setup):
    """The cycles of the smooth sliding motion (contact closed, v0 − ẋ > 0) from the damped flutter's Hopf
    point (:func:`mode_coupling_hopf`); an undamped mode-coupling onset has no cycle branch to start
    (two imaginary pairs collide: no amplitude equation) and is refused with an InputError.  A cycle is
    the model's motion only while the contact stays closed and the slip positive: the branch says
    nothing past a contact loss or a stick."""
    from landau.analyses.cycle_problems import cycle_problem

    result = mode_coupling_hopf(setup)
    hp, setup = _hopf_setup(setup)
    if getattr(result, "extra", {}).get("kind") != "hopf":
        raise InputError(f"mode-coupling: the onset in {hp!r} is an undamped mode coupling (no Hopf point with an "
                         "amplitude equation): no branch of cycles starts there; give damping (c1, c2 > 0)")
    system = system_of(setup).with_value(hp, result.p_c).sliding_system(hp)
    return cycle_problem(system, dict(system.defaults), result, name="mode-coupling")


def _simulate(setup: Setup, **kw):
    """The non-smooth run (:func:`landau.verify.modecoupling.run.simulate`)."""
    from landau.verify.modecoupling.run import simulate

    return simulate(setup, **kw)


def _check(setup: Setup, eps2, tolerance=None) -> dict:
    """The amplitude check near the flutter onset by direct simulation (:mod:`landau.verify.modecoupling.cli`)."""
    from landau.verify.modecoupling.cli import run

    return run(setup, eps2, tolerance)


MODE_COUPLING = Model(
    name="mode-coupling",
    description="friction-induced flutter (mode coupling) of Hoffmann et al. (2002), or an N-DOF structure given "
                "by its matrices; parameter mu (angles in degrees)",
    law_kind=LawKind.VELOCITY,
    declare=_declare,
    hopf_parameter=_hopf_parameter,
    hopf=mode_coupling_hopf,
    simulate=_simulate,
    cycles=mode_coupling_cycles,
    check=_check,
    options=(Option("friction", "friction coefficient mu(v) of the sliding velocity v = v0 - xdot > 0 (default the "
                                "constant mu)"),
             Option("friction_neg", "does not apply (the belt slides one way)"),
             Option("friction_name", "a name for the friction law"),
             Option("parameter", "the bifurcation parameter (default mu)"),
             Option("bracket", "interval LO:HI of the bifurcation parameter to search (default 0:2 for mu)"),
             Option("contact", "the contact law: linear, cubic (default) or hertz"),
             Option("mass_matrix", "the mass matrix M of an N-DOF structure (JSON rows)"),
             Option("damping_matrix", "the damping matrix C of an N-DOF structure (JSON rows; default 0)"),
             Option("stiffness_matrix", "the stiffness matrix K of an N-DOF structure (JSON rows)"),
             Option("normal", "index of the normal coordinate (the penetration) of an N-DOF structure (default 1)"),
             Option("tangential", "index of the tangential coordinate of an N-DOF structure (default 0)")),
    defaults={"t_end": 300.0, "key_parameters": ("mu", "c1", "c2")},
    convention="general",
    source="Hoffmann et al. (2002); Hoffmann & Gaul (2003)",
)

__all__ = ["MODE_COUPLING", "mode_coupling_cycles", "mode_coupling_hopf", "system_of"]
