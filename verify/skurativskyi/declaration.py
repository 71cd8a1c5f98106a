"""The forced cart with Hertz contact of Skurativskyi, Kudra, Witkowski & Awrejcewicz (2019), declared as
the model ``forced-oscillator``.

A cart on a belt driven by an unbalanced rotor at frequency ω, hitting an obstacle through a Hertz
contact, with the paper's regularised Coulomb friction (c, T, eps) or any velocity law F(v) [N]
(``friction`` option).  Identified parameters of their Table 1.  Sweep task ``simulate``: the
attractor by continuation in ω (:mod:`landau.verify.skurativskyi.sweep`).

References
----------
Skurativskyi, S., Kudra, G., Witkowski, K. & Awrejcewicz, J. (2019), Bifurcation phenomena and
statistical regularities in dynamics of forced impacting oscillator, Nonlinear Dyn. 98, 1795–1806.
"""

from __future__ import annotations

from landau.models import LawKind, Model, Option, Parameter, Setup

SOURCE = "Skurativskyi et al. (2019), Table 1"
#: the mechanical parameters: domain, unit, meaning (defaults: the identified values of Params)
_MECHANICAL = {"m": ("positive", "kg", "mass of the cart"), "m0e": ("nonnegative", "kg m", "rotor unbalance m0 e"),
               "n1": ("positive", "1", "exponent of the Hertz contact"), "n2": ("positive", "1", "damping exponent"),
               "n3": ("positive", "1", "damping exponent of the velocity"),
               "k": ("positive", "N/m", "spring stiffness"), "kI": ("positive", "N/m^n1", "contact stiffness"),
               "b": ("nonnegative", "s/m", "contact damping"), "xI": ("real", "m", "position of the obstacle"),
               "omega": ("positive", "rad/s", "forcing frequency")}


def _declare(setup: Setup) -> tuple[Parameter, ...]:
    from landau.laws.velocity import declared_names, regularised_coulomb
    from landau.verify.skurativskyi.model import Params

    base = Params()
    mech = tuple(Parameter(n, float(getattr(base, n)), unit, dom, meaning, SOURCE)
                 for n, (dom, unit, meaning) in _MECHANICAL.items())
    if setup.option("friction") is None:   # the paper's regularised Coulomb law (c, T, eps)
        own = tuple(Parameter(p.name, None if p.default is None else float(p.default), p.units or "1",
                              "positive" if p.positive else "real", p.description, p.source or SOURCE)
                    for p in regularised_coulomb().parameters)
    else:
        own = tuple(Parameter(n, setup.params.get(n), "1", "real", "a parameter of the friction law", "the user's law")
                    for n in declared_names(setup.option("friction"), setup.option("friction_neg")))
    return (*mech, *own)


def _simulate_task(task, model, law, fixed, options):
    from landau.verify.skurativskyi.sweep import make_task

    return make_task(task, model, law, fixed, options)


def _plot_simulate(ds, fig) -> dict:
    from landau.verify.skurativskyi.sweep import plot_diagram

    plot_diagram(ds, fig)
    return {"kind": "bifurcation-diagram"}


def _simulate(setup: Setup, **kw):
    from landau.verify.skurativskyi.run import simulate

    return simulate(setup, **kw)


FORCED_OSCILLATOR = Model(
    name="forced-oscillator",
    description="forced cart with Hertz contact (Skurativskyi et al. 2019), regularised Coulomb friction or --friction",
    law_kind=LawKind.VELOCITY,
    declare=_declare,
    simulate=_simulate,
    tasks={"simulate": _simulate_task},
    options=(Option("friction", "friction force F_R(v) [N] for sliding velocity v > 0"),
             Option("friction_neg", "the friction for v < 0 (default the odd extension)"),
             Option("friction_name", "a name for the friction law")),
    defaults={"t_end": 10.0, "key_parameters": ("omega",)},
    plots={"simulate": _plot_simulate},
    source=SOURCE,
)

__all__ = ["FORCED_OSCILLATOR"]
