"""The frictional impact oscillator of Lancioni, Lenci & Galvanetto declared as the model ``impact-oscillator``.

A bar on a moving belt (their eq. 1) with Coulomb friction μ or any velocity law F(v)
(``friction``/``friction_neg`` options, its parameters by name), parameter set 1 of Sec. 3
(Leine, Brogliato & Nijmeijer 2002) with g = 10 m/s².  Hopf parameter: μ for Coulomb friction,
else the ``parameter`` option (default the law's first parameter).  The Hopf point is that of the
slip equilibrium, :func:`landau.verify.lancioni.slip.slip_hopf`.
"""

from __future__ import annotations

from dataclasses import replace

from landau.errors import InputError
from landau.models import LawKind, Model, Option, Parameter, Setup

SOURCE = "Lancioni, Lenci & Galvanetto, Sec. 3, set 1 (Leine, Brogliato & Nijmeijer 2002)"
#: the mechanical parameters' domains and meanings (their defaults are set 1, slip.SET1)
_MECHANICAL = {"m1": ("positive", "kg", "mass of the bar"), "m2": ("positive", "kg", "mass of the frame"),
               "l": ("positive", "m", "length of the bar"), "k_y": ("nonnegative", "N/m", "vertical stiffness"),
               "k_phi": ("nonnegative", "N m", "rotational stiffness"),
               "c_y": ("nonnegative", "N s/m", "vertical damping"),
               "c_phi": ("nonnegative", "N m s", "rotational damping"),
               "phi0": ("real", "rad", "rest angle of the rotational spring"),
               "y0": ("real", "m", "rest position of the vertical spring"),
               "g": ("nonnegative", "m/s^2", "gravitational acceleration")}
#: the Coulomb coefficient used by a simulation when none is given (above the Hopf point 0.40978)
MU_SIMULATE = 0.42


def friction_law(setup: Setup, params: dict):
    """The friction law of the setup (Coulomb μ, or the ``friction`` option), its values removed from ``params``."""
    from landau.laws.velocity import coulomb, law_from_options

    return law_from_options(setup.option("friction"), setup.option("friction_neg"), setup.option("friction_name"),
                            coulomb(), params)


def _declare(setup: Setup) -> tuple[Parameter, ...]:
    from landau.verify.lancioni.slip import SET1

    mech = tuple(Parameter(n, float(SET1[n]), unit, dom, meaning, SOURCE)
                 for n, (dom, unit, meaning) in _MECHANICAL.items())
    from landau.laws.velocity import declared_names

    own = tuple(Parameter(n, setup.params.get(n), "1", "real", "a parameter of the friction law", "the user's law")
                for n in declared_names(setup.option("friction"), setup.option("friction_neg")))
    if setup.option("friction") is None:   # Coulomb: mu is the friction coefficient
        own = (Parameter("mu", 0.4, "1", "nonnegative", "Coulomb friction coefficient", SOURCE),)
    return (*mech, *own,
            Parameter("v_belt", -1.0, "m/s", "nonzero", "belt velocity (< 0: positive slip, the direction with the "
                      "Hopf point)", SOURCE),
            Parameter("eN", 0.0, "1", "nonnegative", "normal restitution coefficient of the impacts", SOURCE))


def _hopf_parameter(setup: Setup) -> str | None:
    parameter = setup.option("parameter")
    if parameter is not None:
        return str(parameter)
    if setup.option("friction") is None:
        return "mu"
    from landau.laws.velocity import declared_names

    names = declared_names(setup.option("friction"), setup.option("friction_neg"))
    given = [n for n in setup.params if n in names]   # the law's first parameter, in the order given
    return given[0] if given else (names[0] if names else None)


def _slip_inputs(setup: Setup):
    """``(params, friction, parameter, v, law)`` of the slip mode: the mechanical parameters, the friction
    law (None: the paper's Coulomb μ), the bifurcation parameter, the belt velocity and the law named."""
    from landau.verify.lancioni import slip as S

    params = dict(setup.params)
    parameter = setup.option("parameter")
    params.pop("eN", None)
    user = setup.option("friction") is not None
    law = friction_law(setup, params)
    v = params.pop("v_belt", -1.0)
    unknown = sorted(set(params) - set(S.PARAM_NAMES))
    if unknown:
        raise InputError(f"impact-oscillator: unknown parameter(s) {', '.join(unknown)} (known: the law's "
                         f"{', '.join(p.name for p in law.parameters) or 'none'}, {', '.join(S.PARAM_NAMES)}, v_belt)")
    if v >= 0:
        raise InputError(f"impact-oscillator: v_belt must be < 0 (positive slip, the belt direction with the Hopf "
                         f"point), got {v!r}")
    friction = law if user or parameter not in (None, "mu") else None
    return params, friction, parameter, v, law


def impact_oscillator_hopf(setup: Setup):
    """The Hopf point of the slip equilibrium (:func:`landau.verify.lancioni.slip.slip_hopf`), with the
    friction law's expression and the belt velocity in ``extra``."""
    from landau.verify.lancioni import slip as S

    params, friction, parameter, v, law = _slip_inputs(setup)
    try:
        if friction is None:  # the paper's Coulomb friction, bifurcation parameter mu
            h = S.slip_hopf(params)
        else:
            h = S.slip_hopf(params, friction=friction, parameter=parameter, v=v)
    except (OverflowError, ZeroDivisionError, FloatingPointError) as exc:
        raise InputError(f"impact-oscillator: the slip equilibrium's Hopf analysis leaves the float64 range with "
                         f"law {law.name!r} ({exc}): bring the law's parameters nearer their physical scale") from None
    extra = {**h.extra, "friction": law.name, "friction_positive": str(law.positive),
             "friction_negative": str(law.branch(-1)), "v_belt": v}
    return replace(h, extra=extra)


def impact_oscillator_cycles(setup: Setup):
    """The cycles of the smooth slip mode (contact closed, g_T > 0: :func:`landau.verify.lancioni.slip.slip_system`)
    from its Hopf point; a cycle is the oscillator's motion only while the contact stays closed and the
    bar slips one way (no impact, no stick): the branch says nothing past either."""
    from landau.analyses.cycle_problems import cycle_problem
    from landau.verify.lancioni import slip as S

    result = impact_oscillator_hopf(setup)
    params, friction, parameter, v, _ = _slip_inputs(setup)
    if friction is None:
        system, values = S.slip_system(1), S.resolve(params)
    else:
        system = S.slip_system(1, friction, S.hopf_parameter(friction, parameter))
        values = S.slip_values(params, 1, friction, v)
    return cycle_problem(system, values, result, name="impact-oscillator slip mode")


def _simulate(setup: Setup, **kw):
    from landau.verify.lancioni.run import simulate

    return simulate(setup, **kw)


IMPACT_OSCILLATOR = Model(
    name="impact-oscillator",
    description="frictional impact oscillator (Lancioni, Lenci & Galvanetto): slip equilibrium; parameter mu, or a "
                "parameter of --friction",
    law_kind=LawKind.VELOCITY,
    declare=_declare,
    hopf_parameter=_hopf_parameter,
    hopf=impact_oscillator_hopf,
    simulate=_simulate,
    cycles=impact_oscillator_cycles,
    options=(Option("friction", "friction F(v) for sliding velocity v > 0"),
             Option("friction_neg", "friction for v < 0 (default the odd extension)"),
             Option("friction_name", "a name for the friction law"),
             Option("parameter", "the bifurcation parameter (default mu, or the law's first parameter)")),
    defaults={"t_end": 10.0, "key_parameters": ("mu", "v_belt")},
    source=SOURCE,
)

__all__ = ["IMPACT_OSCILLATOR", "friction_law", "impact_oscillator_cycles", "impact_oscillator_hopf"]
