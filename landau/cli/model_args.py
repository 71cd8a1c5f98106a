"""From command-line arguments to a model's setup: the law of the kind the model takes, its parameters, its options.

One function for every command that runs a registered model (:func:`setup_from_args`): it reads the
model's declaration (:class:`landau.models.Model`: its law kind, its options, its Hopf parameter)
and refuses an option that belongs to another model, naming it.  The options of every model are
added to a parser once (:func:`add_model_options`); their values are converted by option name.
"""

from __future__ import annotations

import math
from typing import Any

from landau.cli.common import NOT_PARAMS, parse_floats, parse_params, parse_velocities, resolve_law, split_assignment
from landau.errors import InputError
from landau.models import LawKind, Model, Setup


def add_model_options(p) -> None:
    """The model-specific options (``--kinetic``, ``--parameter``, ``--rhs`` …, ``--blocks``) on parser ``p``."""
    p.add_argument("--kinetic", default=None, metavar="EXPR",
                   help="galvanetto models: kinetic friction for r = Xdot - V < 0 in r, gamma, delta")
    p.add_argument("--kinetic-pos", default=None, metavar="EXPR",
                   help="galvanetto models: the r > 0 branch (default the odd reflection of --kinetic)")
    p.add_argument("--parameter", default=None, metavar="NAME",
                   help="impact-oscillator, mode-coupling: the bifurcation parameter (default mu, or the first "
                        "parameter of --friction); system: the Hopf parameter")
    p.add_argument("--rhs", action="append", default=[], metavar="NAME=EXPR",
                   help="system: a state and its right-hand side dNAME/dt (repeatable, in order)")
    p.add_argument("--equilibrium", action="append", default=[], metavar="NAME=EXPR",
                   help="system: the equilibrium of a state as an expression of the parameters (repeatable)")
    p.add_argument("--guess", action="append", default=[], metavar="NAME=VALUE",
                   help="system: instead of --equilibrium, a starting value of a state for Newton's method")
    p.add_argument("--mass", action="append", default=[], metavar="NAME=EXPR",
                   help="system: the mass entry E_ii of a state (default 1; 0: an algebraic row)")
    p.add_argument("--bracket", default=None, metavar="LO:HI",
                   help="system, spring-block-chain, mode-coupling: interval of the Hopf parameter to search "
                        "(--bracket=-1:1 if LO < 0)")
    p.add_argument("--blocks", default=None, metavar="N", help="spring-block-chain: the number of blocks (1 to 100)")
    p.add_argument("--route", default=None, choices=("auto", "symbolic", "numeric"),
                   help="spring-block-chain: symbolic (the general engine, 50 digits, up to 12 blocks), numeric "
                        "(float64 sparse solves from one block's law jets) or auto (by the number of blocks)")
    p.add_argument("--contact", default=None, choices=("linear", "cubic", "hertz"),
                   help="mode-coupling: the normal contact law N(y) (default cubic: kH*y + kNL*y^3)")
    for name, what in (("mass", "M"), ("damping", "C"), ("stiffness", "K")):
        p.add_argument(f"--{name}-matrix", default=None, metavar="[[..],[..]]",
                       help=f"mode-coupling: the structure's {name} matrix {what} of an N-DOF system (JSON rows)")
    p.add_argument("--normal", default=None, metavar="INDEX",
                   help="mode-coupling with matrices: index of the normal coordinate (the penetration; default 1)")
    p.add_argument("--tangential", default=None, metavar="INDEX",
                   help="mode-coupling with matrices: index of the tangential coordinate (default 0)")


def add_elastic_arguments(p) -> None:
    """The elastic medium and geometry of a fault (``landau nucleation``, ``landau hopf spring-block --patch``)."""
    from landau.analyses.nucleation import GEOMETRIES

    p.add_argument("--shear-modulus", default=None, metavar="PA", help="the shear modulus G in Pa")
    p.add_argument("--density", default=None, metavar="KG_M3",
                   help="the density rho in kg/m^3 (with --shear-speed: G = rho c_s^2)")
    p.add_argument("--shear-speed", default=None, metavar="M_S", help="the shear-wave speed c_s in m/s")
    p.add_argument("--poisson", default=None, metavar="NU", help="Poisson's ratio nu (inplane and circular)")
    p.add_argument("--geometry", default=None, metavar="NAME",
                   help=f"the fault's geometry: {', '.join(GEOMETRIES)} (default antiplane)")


def add_patch_options(p) -> None:
    """``--patch H`` and the elastic medium (:func:`add_elastic_arguments`) for ``landau hopf``."""
    p.add_argument("--patch", default=None, metavar="H",
                   help="spring-block: analyse a fault patch of size H in m (k from the patch, sigma in Pa)")
    add_elastic_arguments(p)


def one_number(text, what: str) -> float:
    """One finite number from the command line, else an InputError naming ``what``."""
    vals = parse_floats(text, what)
    if len(vals) != 1 or not math.isfinite(vals[0]):
        raise InputError(f"{what}: expected one finite number, got {text!r}")
    return vals[0]


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


def _guesses(items) -> dict[str, float]:
    out = {}
    for name, val in _assignments(items, "--guess", "VALUE").items():
        vals = parse_floats(val, f"--guess {name}")
        if len(vals) != 1 or not math.isfinite(vals[0]):
            raise InputError(f"--guess {name}: expected one finite number, got {val!r}")
        out[name] = vals[0]
    return out


#: how each model option's command-line value becomes the option's value
_CONVERT = {
    "rhs": lambda v: _assignments(v, "--rhs", "EXPR"),
    "equilibrium": lambda v: _assignments(v, "--equilibrium", "EXPR"),
    "mass": lambda v: _assignments(v, "--mass", "EXPR"),
    "guess": _guesses,
    "bracket": parse_bracket,
    "patch": lambda v: one_number(v, "--patch"),
    "shear_modulus": lambda v: one_number(v, "--shear-modulus"),
    "density": lambda v: one_number(v, "--density"),
    "shear_speed": lambda v: one_number(v, "--shear-speed"),
    "poisson": lambda v: one_number(v, "--poisson"),
}
def convert_option(name: str, value):
    """An option's command-line value as the model takes it (NAME=EXPR lists as mappings, LO:HI as a pair)."""
    return _CONVERT[name](value) if name in _CONVERT else value


#: the option attributes of the parsers, with their spelling (for "belongs to another model")
_OPTION_FLAGS = {"friction": "--friction", "friction_neg": "--friction-neg", "kinetic": "--kinetic",
                 "kinetic_pos": "--kinetic-pos", "parameter": "--parameter", "rhs": "--rhs",
                 "equilibrium": "--equilibrium", "guess": "--guess", "mass": "--mass", "bracket": "--bracket",
                 "blocks": "--blocks", "patch": "--patch", "shear_modulus": "--shear-modulus",
                 "density": "--density", "shear_speed": "--shear-speed", "poisson": "--poisson",
                 "geometry": "--geometry", "contact": "--contact", "mass_matrix": "--mass-matrix",
                 "damping_matrix": "--damping-matrix", "stiffness_matrix": "--stiffness-matrix", "normal": "--normal",
                 "tangential": "--tangential", "route": "--route"}
#: the law options of each law kind
_LAW_OPTIONS = {LawKind.VELOCITY: ("friction", "friction_neg", "friction_name"),
                LawKind.KINETIC: ("kinetic", "kinetic_pos")}


def _given(args, attr: str) -> bool:
    return getattr(args, attr, None) not in (None, [], False)


def model_options(model: Model, args, command: str) -> dict[str, Any]:
    """The model's options from ``args``; an option of another model is an InputError naming it."""
    takes = {o.name for o in model.options} | set(_LAW_OPTIONS.get(model.law_kind, ()))
    out: dict[str, Any] = {}
    for attr, flag in _OPTION_FLAGS.items():
        if not _given(args, attr):
            continue
        val = getattr(args, attr)
        if attr not in takes:
            if attr == "parameter" and val == model.bifurcation_parameter():
                continue   # naming the model's own bifurcation parameter is harmless
            if attr == "parameter" and model.hopf_parameter is not None:
                raise InputError(f"{command} {model.name}: the bifurcation parameter is "
                                 f"{model.bifurcation_parameter()} (got --parameter {val})")
            raise InputError(f"{command} {model.name}: {flag} belongs to another model")
        out[attr] = _CONVERT[attr](val) if attr in _CONVERT else val
    if "friction" in out or "friction_neg" in out:
        out["friction_name"] = getattr(args, "friction_name", None) or "user-friction"
    return out


def setup_from_args(model: Model, args, command: str) -> Setup:
    """The :class:`~landau.models.Setup` of ``model`` from the parsed arguments of ``command``.

    Raises
    ------
    InputError
        A law of a kind the model does not take, an option of another model, a bad value.
    """
    options = model_options(model, args, command)
    law_given = _given(args, "law") or _given(args, "mu") or _given(args, "state")
    law = None
    if model.law_kind is LawKind.RATE_AND_STATE:
        law, params = resolve_law(args)
        everything = parse_params(args.param)
        params.update({k: v for k, v in everything.items()
                       if k not in params and k not in {p.name for p in law.parameters}})
    else:
        if law_given:
            raise InputError(f"{command} {model.name}: LAW, --mu and --state (a rate-and-state law) belong to another "
                             f"model; {_law_words(model)}")
        params = parse_params(args.param, {} if model.law_kind is LawKind.NONE else NOT_PARAMS)
    declared_V = any(p.name == "V" for p in model.parameters(Setup(law, {}, options)))
    if _given(args, "V"):
        if not declared_V:
            raise InputError(f"{command} {model.name}: --V belongs to another model (this one has no driving "
                             "velocity V)")
        Vs = parse_velocities(args.V)
        if len(Vs) != 1:
            raise InputError(f"{command}: give one driving velocity --V")
        params["V"] = Vs[0]
    return Setup(law, params, options)


def _law_words(model: Model) -> str:
    return {LawKind.VELOCITY: "give its friction as --friction EXPR",
            LawKind.KINETIC: "give its kinetic law as --kinetic EXPR",
            LawKind.NONE: "write its equations with --rhs"}.get(model.law_kind, "")


__all__ = ["add_elastic_arguments", "add_patch_options", "one_number", "add_model_options", "convert_option",
           "model_options", "parse_bracket", "setup_from_args"]
