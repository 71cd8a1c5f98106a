"""The model ``system``: any smooth system E·ẏ = f(y; p) written as strings, declared as a model.

Its equations are options (``rhs``, ``equilibrium`` or ``guess``, ``mass``; the Hopf parameter
``parameter`` and the search interval ``bracket``), parsed by the whitelist parser of
:meth:`landau.systems.system.DynamicalSystem.from_strings`; its parameters are the names its
expressions use, declared with the values given (``--param NAME=VALUE``), any of which can be swept.
The Hopf point is :func:`landau.derivation.general.hopf_normal_form` (Kuznetsov 2004, Sec. 3.5).

References
----------
Kuznetsov, Y. A. (2004), *Elements of Applied Bifurcation Theory*, 3rd ed., Springer.
"""

from __future__ import annotations

from typing import Any, Mapping

from landau.errors import InputError
from landau.models import LawKind, Model, Option, Parameter, Setup

#: systems built from the same strings, reused (the sweep calls the Hopf analysis point by point)
_SYSTEMS: dict[tuple, Any] = {}


def _frozen(mp: Mapping[str, Any] | None) -> tuple:
    return () if not mp else tuple((str(k), str(v)) for k, v in mp.items())


def system_of(setup: Setup):
    """The :class:`~landau.systems.system.DynamicalSystem` of the setup's options (cached by its strings)."""
    from landau.systems.system import DynamicalSystem

    rhs = setup.option("rhs")
    if not rhs:
        raise InputError("system: give the right-hand side (--rhs NAME=EXPR, one per state; options={'rhs': {...}})")
    parameter = setup.option("parameter")
    if not parameter:
        raise InputError("system: name the Hopf parameter (--parameter NAME; options={'parameter': NAME})")
    eq, guess, mass = setup.option("equilibrium"), setup.option("guess"), setup.option("mass")
    if eq is None and guess is None:
        raise InputError("system: give the equilibrium (--equilibrium NAME=EXPR for every state) or a guess of it "
                         "(--guess NAME=VALUE)")
    if eq is not None and guess is not None:
        raise InputError("system: give --equilibrium or --guess, not both")
    names = tuple(sorted(setup.params))
    key = (_frozen(rhs), str(parameter), _frozen(eq), _frozen(guess), _frozen(mass), names)
    if key not in _SYSTEMS:
        system = DynamicalSystem.from_strings(dict(rhs), str(parameter), {n: 1.0 for n in names}, equilibrium=eq,
                                              guess=guess, mass=mass, name="system")
        unused = sorted(set(names) - {s.name for s in system.parameters})
        if unused:
            raise InputError(f"--param {unused[0]}: no expression of the system uses it")
        _SYSTEMS[key] = system
    return _SYSTEMS[key]


def _used_names(setup: Setup) -> set[str]:
    """The names the system's expressions use besides its states (its parameters and the Hopf parameter)."""
    from landau.laws.parse import referenced_names

    rhs = setup.option("rhs") or {}
    names: set[str] = set()
    for what in ("rhs", "equilibrium", "mass"):
        for state, text in (setup.option(what) or {}).items():
            names |= referenced_names(str(text), what=f"{what} {state}")
    return names - set(rhs)


def _declare(setup: Setup) -> tuple[Parameter, ...]:
    parameter = setup.option("parameter")
    given = dict(setup.params)
    names = (_used_names(setup) | set(given)) - {parameter}
    out = [Parameter(n, given.get(n), "1", "real", "a parameter of the system's expressions", "the user's system")
           for n in sorted(names)]
    if parameter:
        out.append(Parameter(str(parameter), None, "1", "real", "the Hopf parameter", "the user's system"))
    return tuple(out)


def system_hopf(setup: Setup):
    """The Hopf point of the system of the setup's options in ``bracket``."""
    from landau.derivation.general import hopf_normal_form

    bracket = setup.option("bracket")
    if bracket is None:
        raise InputError("system: give the interval of the Hopf parameter holding one Hopf point (--bracket LO:HI; "
                         "options={'bracket': (lo, hi)})")
    system = system_of(setup)
    if system.parameter.name in setup.params:
        raise InputError(f"system: {system.parameter.name!r} is the Hopf parameter: its critical value is computed, "
                         "it cannot be given or swept")
    return hopf_normal_form(system, dict(setup.params), _bracket(bracket))


def _bracket(value) -> tuple[float, float]:
    """The Hopf parameter's interval from ``(lo, hi)`` or the command line's ``"LO:HI"``."""
    parts = value.split(":") if isinstance(value, str) else value
    try:
        lo, hi = (float(v) for v in parts)
    except (TypeError, ValueError):
        raise InputError(f"system: bracket must be two numbers, (lo, hi) or 'LO:HI', got {value!r}") from None
    return lo, hi


def system_cycles(setup: Setup):
    """The system's cycles in its Hopf parameter from the Hopf point in ``bracket`` (:func:`system_hopf`):
    ẏ = E⁻¹ f(y; p) with E invertible, measured on the state the amplitude equation is normalised on."""
    from landau.analyses.cycle_problems import cycle_problem

    result = system_hopf(setup)
    system = system_of(setup)
    y0 = result.equilibrium
    unknowns = {e.name: float(v) for e, v in zip(system.equilibrium, y0, strict=True) if e in system.unknowns}
    return cycle_problem(system, dict(setup.params), result, unknowns=unknowns)


def _simulation_setup(setup: Setup) -> Setup:
    """The setup as the simulation reads it: the Hopf parameter is a value like the others there (default
    the first parameter given), and a system without an equilibrium starts from a guess of 0."""
    from dataclasses import replace

    opts = dict(setup.options)
    params = dict(setup.params)
    if not opts.get("parameter"):
        if params:
            opts["parameter"] = next(iter(params))
        else:   # a system without parameters: a placeholder Hopf parameter no expression uses
            opts["parameter"], params["no_parameter"] = "no_parameter", 0.0
    if opts.get("equilibrium") is None and opts.get("guess") is None:
        opts["guess"] = {}
    return replace(setup, params=params, options=opts)


def system_simulate(setup: Setup, *, t_end=None, y0=None, history=None, t_eval=None, max_steps=None,
                    sections=False):
    """A run of the system of the setup's options with the compiled Radau IIA
    (:func:`landau.analyses.system_simulation.simulate_system`); every parameter value given, the
    Hopf parameter's included."""
    from dataclasses import replace

    from landau.analyses.system_simulation import simulate_system
    from landau.verify.hybrid.run_inputs import end_time, initial_state, no_history

    no_history(history, "system")
    if sections:
        raise InputError("system: a Poincare section is not defined for a user system")
    setup = _simulation_setup(setup)
    hp = str(setup.option("parameter"))
    if hp not in setup.params:
        raise InputError(f"system: give the value of {hp!r} to simulate at (--param {hp}=VALUE)")
    rest = {k: v for k, v in setup.params.items() if k != hp}
    system = system_of(replace(setup, params=rest))
    T = end_time(t_end, SYSTEM.defaults["t_end"])
    kw = {} if max_steps is None else {"max_steps": int(max_steps)}
    start = None if y0 is None else initial_state(y0, [s.name for s in system.states])
    sim = simulate_system(system, dict(setup.params), T, start, t_eval=t_eval, **kw)
    units = {"t": "1", **{s.name: "1" for s in system.states}}   # the user's own units
    return replace(sim, units=units, parameters={k: float(v) for k, v in setup.params.items()},
                   notes=(*sim.notes, "compiled Radau IIA (rtol 1e-8) on the system written with --rhs"))


SYSTEM = Model(
    name="system",
    description="any smooth system E dy/dt = f(y; p) given by --rhs, --parameter, --param, --bracket",
    law_kind=LawKind.NONE,
    declare=_declare,
    hopf_parameter=lambda setup: setup.option("parameter"),
    hopf=system_hopf,
    simulate=system_simulate,
    cycles=system_cycles,
    options=(Option("rhs", "a state and its right-hand side dNAME/dt (NAME=EXPR, repeatable, in order)"),
             Option("equilibrium", "the equilibrium of a state as an expression of the parameters (NAME=EXPR)"),
             Option("guess", "instead of the equilibrium, a starting value of a state for Newton's method"),
             Option("mass", "the mass entry E_ii of a state (default 1; 0: an algebraic row)"),
             Option("parameter", "the Hopf parameter"),
             Option("bracket", "interval LO:HI of the Hopf parameter holding one Hopf point")),
    defaults={"t_end": 100.0},
    source="Kuznetsov (2004), Sec. 3.5 (the normal form)",
)

__all__ = ["SYSTEM", "system_cycles", "system_hopf", "system_of"]
