"""The mode-coupling model of Hoffmann, Fischer, Begley & Gaul (2002) declared as the model ``mode-coupling``
(the simulation's part: parameters and ``simulate``).

A mass on a belt moving at v0, two springs at angles alpha1, alpha2 (degrees), a contact of stiffness
law N(y) (the ``contact`` option: linear, cubic, hertz), damping c1, c2 and a preload P; Coulomb
friction mu or a velocity law F(v_rel) (``friction`` options).
"""

from __future__ import annotations

from landau.models import LawKind, Model, Option, Parameter, Setup

SOURCE = "Hoffmann, Fischer, Begley & Gaul (2002), Mech. Res. Commun. 29, 197-205"
#: name -> (domain, unit, meaning)
_MEANINGS = {"m": ("positive", "kg", "mass"), "k1": ("nonnegative", "N/m", "stiffness of spring 1"),
             "k2": ("nonnegative", "N/m", "stiffness of spring 2"),
             "alpha1": ("real", "deg", "angle of spring 1 (degrees)"),
             "alpha2": ("real", "deg", "angle of spring 2 (degrees)"),
             "kH": ("positive", "N/m", "contact stiffness"),
             "kNL": ("real", "N/m^3", "cubic contact coefficient (contact cubic)"),
             "P": ("real", "N", "preload pressing the mass onto the belt"),
             "c1": ("nonnegative", "N s/m", "damping of the tangential coordinate"),
             "c2": ("nonnegative", "N s/m", "damping of the normal coordinate"),
             "mu": ("nonnegative", "1", "Coulomb friction coefficient"),
             "v0": ("positive", "m/s", "belt speed")}


def _declare(setup: Setup) -> tuple[Parameter, ...]:
    from landau.laws.velocity import declared_names
    from landau.verify.modecoupling.run import HOFFMANN

    own = tuple(Parameter(n, setup.params.get(n), "1", "real", "a parameter of the friction law", "the user's law")
                for n in declared_names(setup.option("friction"), setup.option("friction_neg")))
    names = [n for n in HOFFMANN if not (n == "mu" and setup.option("friction") is not None)]
    return (*(Parameter(n, HOFFMANN[n], _MEANINGS[n][1], _MEANINGS[n][0], _MEANINGS[n][2], SOURCE) for n in names),
            *own)


def _check(setup: Setup, eps2, tolerance=None) -> dict:
    from landau.verify.modecoupling.cli import run

    return run(setup, eps2, tolerance)


def _simulate(setup: Setup, **kw):
    from landau.verify.modecoupling.run import simulate

    return simulate(setup, **kw)


MODE_COUPLING = Model(
    name="mode-coupling",
    description="friction-induced flutter of a mass on a belt (Hoffmann et al. 2002): unilateral contact, "
                "stick and slip",
    law_kind=LawKind.VELOCITY,
    declare=_declare,
    hopf_parameter="mu",
    simulate=_simulate,
    check=_check,
    options=(Option("contact", "contact law: linear (default), cubic or hertz"),
             Option("friction", "friction coefficient F(v) for v_rel = v0 - xdot > 0"),
             Option("friction_neg", "friction for v_rel < 0 (default the odd extension)"),
             Option("friction_name", "a name for the friction law"),
             Option("M", "the N-DOF family: mass matrix (array, or a string like [[1,0],[0,1]])"),
             Option("C", "the N-DOF family: damping matrix (default 0)"),
             Option("K", "the N-DOF family: stiffness matrix"),
             Option("normal", "the N-DOF family: index of the normal coordinate (the penetration)"),
             Option("tangential", "the N-DOF family: index of the tangential coordinate (along the belt)")),
    defaults={"t_end": 300.0, "key_parameters": ("mu", "P")},
    source=SOURCE,
)

__all__ = ["MODE_COUPLING"]
