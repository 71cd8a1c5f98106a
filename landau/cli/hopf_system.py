"""``landau hopf system``: the Hopf point of any smooth system E·ẏ = f(y; p) written on the command line.

``landau hopf system --rhs NAME=EXPR ... --parameter P [--param NAME=VALUE ...]
(--equilibrium NAME=EXPR ... | --guess NAME=VALUE ...) --bracket LO:HI [--mass NAME=EXPR ...] [--json]``

* ``--rhs``: one per state, in order: the state's name and its right-hand side f_i, parsed by the
  friction laws' whitelist parser (numbers, the declared names, + − * / ^ **, log, exp, sqrt,
  sin, cos, tanh, …; anything else is refused, naming the token);
* ``--parameter``: the Hopf parameter p; ``--param``: every other name the expressions use;
* ``--equilibrium``: the equilibrium of each state as an expression of the parameters and p, or
  ``--guess``: a starting value of each state for Newton's method (states left out start at 0);
* ``--bracket LO:HI``: the interval of p holding one Hopf point (``--bracket=-1:1`` when LO is
  negative);
* ``--mass``: diagonal mass entries E_ii (default 1; 0 makes the row algebraic).

The result is that of :func:`landau.derivation.general.hopf_normal_form` (``p_c``, ``omega_c``,
``Lambda``, ``l1``, ``criticality``, …), the JSON of ``landau hopf``.  Example (the Brusselator,
Hopf point b_c = 1 + a², ω_c = a):

    landau hopf system --rhs "x=a - (b + 1)*x + x^2*y" --rhs "y=b*x - x^2*y" --parameter b
        --param a=1.5 --equilibrium x=a --equilibrium y=b/a --bracket 2:4
"""

from __future__ import annotations

import math

from landau.cli.common import parse_floats, parse_params, split_assignment
from landau.cli.hopf import register
from landau.errors import InputError


def add_arguments(p) -> None:
    """The options of ``landau hopf system`` (added to the ``landau hopf`` parser)."""
    p.add_argument("--rhs", action="append", default=[], metavar="NAME=EXPR",
                   help="system: a state and its right-hand side dNAME/dt (repeatable, in order)")
    p.add_argument("--equilibrium", action="append", default=[], metavar="NAME=EXPR",
                   help="system: the equilibrium of a state as an expression of the parameters (repeatable)")
    p.add_argument("--guess", action="append", default=[], metavar="NAME=VALUE",
                   help="system: instead of --equilibrium, a starting value of a state for Newton's method")
    p.add_argument("--mass", action="append", default=[], metavar="NAME=EXPR",
                   help="system: the mass entry E_ii of a state (default 1; 0: an algebraic row)")
    p.add_argument("--bracket", default=None, metavar="LO:HI",
                   help="system: interval of the Hopf parameter holding one Hopf point (--bracket=-1:1 if LO < 0)")


def parse_bracket(text: str | None, what: str = "--bracket") -> tuple[float, float]:
    """``LO:HI`` (either may be negative) as two finite, different floats, in increasing order."""
    if text is None:
        raise InputError(f"{what} LO:HI is required (the interval of the Hopf parameter to search)")
    head, sep, tail = str(text).rpartition(":")
    if not sep or not head.strip() or not tail.strip():
        raise InputError(f"{what}: expected LO:HI, got {text!r}")
    lo, hi = parse_floats(head, what), parse_floats(tail, what)
    if len(lo) != 1 or len(hi) != 1:
        raise InputError(f"{what}: expected LO:HI with one number on each side, got {text!r}")
    a, b = lo[0], hi[0]
    if not (math.isfinite(a) and math.isfinite(b)) or a >= b:
        raise InputError(f"{what}: need LO < HI, both finite, got {text!r}")
    return a, b


def _assignments(items, option: str, what: str) -> dict[str, str]:
    out: dict[str, str] = {}
    for item in items:
        name, val = split_assignment(item, option, what, out)
        if not name:
            raise InputError(f"{option} {item!r}: the name before '=' is empty")
        out[name] = val
    return out


#: options of the other models that a system does not take
_FOREIGN = (("law", "a law name"), ("mu", "--mu"), ("state", "--state"), ("friction", "--friction"),
            ("V", "--V"), ("kinetic", "--kinetic"), ("kinetic_pos", "--kinetic-pos"), ("blocks", "--blocks"))


def system_from_args(args):
    """(DynamicalSystem, parameter values, bracket) from the ``landau hopf system`` arguments."""
    from landau.systems.system import DynamicalSystem

    for attr, label in _FOREIGN:
        val = getattr(args, attr, None)
        if val not in (None, [], False):
            raise InputError(f"landau hopf system: {label} belongs to another model; write the system with --rhs")
    if not args.rhs:
        raise InputError("landau hopf system: give the right-hand side with --rhs NAME=EXPR (one per state)")
    if not getattr(args, "parameter", None):
        raise InputError("landau hopf system: name the Hopf parameter with --parameter NAME")
    rhs = _assignments(args.rhs, "--rhs", "EXPR")
    eq = _assignments(args.equilibrium, "--equilibrium", "EXPR") if args.equilibrium else None
    guess = None
    if args.guess:
        guess = {}
        for name, val in _assignments(args.guess, "--guess", "VALUE").items():
            vals = parse_floats(val, f"--guess {name}")
            if len(vals) != 1 or not math.isfinite(vals[0]):
                raise InputError(f"--guess {name}: expected one finite number, got {val!r}")
            guess[name] = vals[0]
    if eq is None and guess is None:
        raise InputError("landau hopf system: give the equilibrium (--equilibrium NAME=EXPR for every state) "
                         "or a guess of it (--guess NAME=VALUE)")
    if eq is not None and guess is not None:
        raise InputError("landau hopf system: give --equilibrium or --guess, not both")
    mass = _assignments(args.mass, "--mass", "EXPR") if args.mass else None
    params = parse_params(args.param, reserved={})
    bracket = parse_bracket(args.bracket)
    system = DynamicalSystem.from_strings(rhs, args.parameter, params, equilibrium=eq, guess=guess, mass=mass,
                                          name="system")
    unused = sorted(set(params) - {s.name for s in system.parameters})
    if unused:
        raise InputError(f"--param {unused[0]}: no expression uses it")
    return system, params, bracket


@register("system", "any smooth system E dy/dt = f(y; p) given by --rhs, --parameter, --param, --bracket")
def system_hopf(args):
    """The Hopf point of the system written with ``--rhs`` (:func:`landau.derivation.general.hopf_normal_form`)."""
    from landau.derivation.general import hopf_normal_form

    system, params, bracket = system_from_args(args)
    return hopf_normal_form(system, params, bracket)
