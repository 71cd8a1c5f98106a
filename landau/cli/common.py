"""Argument helpers shared by the sub-commands: velocities, --param, inline laws."""

from __future__ import annotations

import argparse
import math
from typing import Mapping, Sequence

from landau.errors import InputError
from landau.laws import BUILTIN, FrictionLaw, get_law
from landau.systems.system import SpringBlock


def _system_params() -> tuple[str, ...]:
    from landau.systems.springblock_terms import TERMS, parameters

    return ("M", "g", "sigma", *(name for name, *_ in parameters(tuple(TERMS))))


def add_law_arguments(p: argparse.ArgumentParser) -> None:
    p.add_argument("law", nargs="?", default=None,
                   help=f"built-in law ({', '.join(BUILTIN)}), with modifiers as suffixes (dieterich+flash: "
                        "flash heating), or, with --mu, a name for an inline law")
    p.add_argument("--mu", default=None,
                   help="inline friction coefficient, e.g. 'a_v + a*log(v/V_s) + b*log(V_s*phi/L)'")
    p.add_argument("--state", action="append", default=[], metavar="NAME=RATE",
                   help="inline state variable and its rate dNAME/dt (repeatable), e.g. phi='1 - v*phi/L'")
    p.add_argument("--param", action="append", default=[], metavar="NAME=VALUE",
                   help="law or system parameter (M, g, sigma, a, b, L, ...); repeatable")


#: --param names that are not parameters, and what to do instead
NOT_PARAMS = {
    "V": "V is the driving velocity: give it with --V (comma-separated values in m/s)",
    "k": "k is the bifurcation parameter: its critical value k_c is computed, not given",
    "v": "v is the slip rate, the variable of the friction law, not a parameter",
}


def split_assignment(item: str, option: str, rhs: str, seen) -> tuple[str, str]:
    """``NAME=RHS`` of a repeatable option split at the first '=' (name stripped); InputError
    when there is no '=' or the name is already in ``seen``."""
    if "=" not in item:
        raise InputError(f"{option} {item!r}: expected NAME={rhs}")
    name, val = item.split("=", 1)
    name = name.strip()
    if name in seen:
        raise InputError(f"{option} {name} is given twice")
    return name, val


def parse_params(items: Sequence[str], reserved: Mapping[str, str] = NOT_PARAMS) -> dict[str, float]:
    """``--param NAME=VALUE`` items as finite floats; a name in ``reserved`` (default: the spring–block
    commands' V, k and v) is an InputError with its explanation."""
    out: dict[str, float] = {}
    for item in items:
        name, val = split_assignment(item, "--param", "VALUE", out)
        if name in reserved:
            raise InputError(f"--param {name}: {reserved[name]}")
        try:
            x = float(val)
        except ValueError:
            raise InputError(f"--param {name}: {val!r} is not a number") from None
        if not math.isfinite(x):
            raise InputError(f"--param {name}: value must be finite")
        out[name] = x
    return out


def parse_floats(text: str, what: str = "--V") -> list[float]:
    vals = []
    for tok in str(text).split(","):
        tok = tok.strip()
        if not tok:
            continue
        try:
            x = float(tok)
        except ValueError:
            raise InputError(f"{what}: {tok!r} is not a number") from None
        vals.append(x)
    if not vals:
        raise InputError(f"{what}: no values given")
    return vals


#: the widest LO:HI range accepted (beyond it powers of the values overflow or underflow float64)
RANGE_BOUNDS = (1e-20, 1e20)


def parse_velocities(text: str | None) -> list[float]:
    if text is None:
        raise InputError("--V is required (driving velocity in m/s, comma-separated)")
    vals = parse_floats(text, "--V")
    for x in vals:
        if not math.isfinite(x) or x <= 0:
            raise InputError(f"--V: driving velocity must be > 0 m/s, got {x!r}")
    return vals


def parse_range(text: str, what: str) -> tuple[float, float]:
    if ":" not in text:
        raise InputError(f"{what}: expected LO:HI, got {text!r}")
    parts = [parse_floats(s, what) for s in text.split(":", 1)]
    if any(len(p) != 1 for p in parts):
        raise InputError(f"{what}: expected LO:HI with one number on each side, got {text!r}")
    lo, hi = parts[0][0], parts[1][0]
    if not (math.isfinite(lo) and math.isfinite(hi) and 0 < lo < hi):
        raise InputError(f"{what}: need 0 < LO < HI, both finite, got {lo!r}:{hi!r}")
    if lo < RANGE_BOUNDS[0] or hi > RANGE_BOUNDS[1]:
        raise InputError(f"{what}: {lo:g}:{hi:g} leaves the range {RANGE_BOUNDS[0]:g}:{RANGE_BOUNDS[1]:g} where "
                         "the computation stays within floating-point range")
    return lo, hi


def resolve_law(args) -> tuple[FrictionLaw, dict[str, float]]:
    """The law named or declared on the command line, and the remaining --param overrides."""
    params = parse_params(args.param)
    if args.mu is not None or args.state:
        if args.mu is None or not args.state:
            raise InputError("an inline law needs both --mu and at least one --state NAME=RATE")
        states: dict[str, str] = {}
        for item in args.state:
            name, rate = split_assignment(item, "--state", "RATE", states)
            states[name] = rate
        system_params = _system_params()
        law_params = {k: v for k, v in params.items() if k not in system_params}
        if args.law is not None and (not args.law.strip() or len(args.law) > 100):
            raise InputError("the inline law's name must be 1 to 100 characters")
        law = FrictionLaw.from_strings(args.law or "inline", args.mu, states, law_params)
        return law, {k: v for k, v in params.items() if k in system_params}
    if args.law is None:
        raise InputError(f"name a law ({', '.join(BUILTIN)}) or give --mu and --state")
    return get_law(args.law), params


def block_and_params(args) -> tuple[SpringBlock, dict[str, float]]:
    law, overrides = resolve_law(args)
    block = SpringBlock.for_params(law, overrides)   # the optional terms given (eta, gamma_ld, alpha_ld)
    return block, block.resolve(overrides)


def fmt(x: float, width: int = 12) -> str:
    if x is None or (isinstance(x, float) and not math.isfinite(x)):
        return "-".rjust(width)
    return f"{x:{width}.6g}"


# ---------------------------------------------------------------------------------------------
# velocity-only friction laws (impact oscillator, forced oscillator): --friction EXPR
def add_friction_arguments(p: argparse.ArgumentParser) -> None:
    """``--friction EXPR`` (F for positive sliding velocity ``v``), ``--friction-neg EXPR``
    (for v < 0; default the odd extension) and ``--friction-name NAME``."""
    p.add_argument("--friction", default=None, metavar="EXPR",
                   help="your velocity-dependent friction for sliding velocity v > 0 (impact and forced "
                        "oscillators), e.g. 'mu_k + (mu_s - mu_k)*exp(-v/v_s)'; its parameters by --param")
    p.add_argument("--friction-neg", default=None, metavar="EXPR",
                   help="the friction for v < 0 (default: the odd extension -F(-v))")
    p.add_argument("--friction-name", default="user-friction", metavar="NAME", help="a name for --friction")


def velocity_law_from_args(args, default, params: dict[str, float], *, quantity: str = "coefficient"):
    """The model's friction law: ``default`` (a :class:`~landau.laws.velocity.VelocityFriction`)
    with any --param values of its parameters, or the law declared by --friction.

    Parameters
    ----------
    args : argparse.Namespace
        With ``friction``, ``friction_neg``, ``friction_name``.
    default : VelocityFriction
        The model's published law.
    params : dict
        The --param values; the law's own are removed from it (the rest are the model's).
    quantity : {"coefficient", "force"}
        What the model expects the law to give.

    Returns
    -------
    VelocityFriction
    """
    from landau.laws.velocity import law_from_options

    return law_from_options(getattr(args, "friction", None), getattr(args, "friction_neg", None),
                            getattr(args, "friction_name", None), default, params, quantity=quantity)
