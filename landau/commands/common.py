"""Argument helpers shared by the sub-commands: velocities, --param, inline laws."""

from __future__ import annotations

import argparse
import math
from typing import Sequence

from landau.errors import InputError
from landau.system import SpringBlock
from landau.laws import BUILTIN, FrictionLaw, get_law

SYSTEM_PARAMS = ("M", "g", "sigma")


def add_law_arguments(p: argparse.ArgumentParser) -> None:
    p.add_argument("law", nargs="?", default=None,
                   help=f"built-in law ({', '.join(BUILTIN)}) or, with --mu, a name for an inline law")
    p.add_argument("--mu", default=None, help="inline friction coefficient, e.g. 'a_v + a*log(v/V_s) + b*log(V_s*phi/L)'")
    p.add_argument("--state", action="append", default=[], metavar="NAME=RATE",
                   help="inline state variable and its rate dNAME/dt (repeatable), e.g. phi='1 - v*phi/L'")
    p.add_argument("--param", action="append", default=[], metavar="NAME=VALUE",
                   help="law or system parameter (M, g, sigma, a, b, L, ...); repeatable")


def parse_params(items: Sequence[str]) -> dict[str, float]:
    out: dict[str, float] = {}
    for item in items:
        if "=" not in item:
            raise InputError(f"--param {item!r}: expected NAME=VALUE")
        name, val = item.split("=", 1)
        name = name.strip()
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
    lo, hi = (parse_floats(s, what)[0] for s in text.split(":", 1))
    if not (0 < lo < hi):
        raise InputError(f"{what}: need 0 < LO < HI, got {lo!r}:{hi!r}")
    return lo, hi


def resolve_law(args) -> tuple[FrictionLaw, dict[str, float]]:
    """The law named or declared on the command line, and the remaining --param overrides."""
    params = parse_params(args.param)
    if args.mu is not None or args.state:
        if args.mu is None or not args.state:
            raise InputError("an inline law needs both --mu and at least one --state NAME=RATE")
        states = {}
        for item in args.state:
            if "=" not in item:
                raise InputError(f"--state {item!r}: expected NAME=RATE")
            name, rate = item.split("=", 1)
            states[name.strip()] = rate
        law_params = {k: v for k, v in params.items() if k not in SYSTEM_PARAMS}
        law = FrictionLaw.from_strings(args.law or "inline", args.mu, states, law_params)
        return law, {k: v for k, v in params.items() if k in SYSTEM_PARAMS}
    if args.law is None:
        raise InputError(f"name a law ({', '.join(BUILTIN)}) or give --mu and --state")
    return get_law(args.law), params


def block_and_params(args) -> tuple[SpringBlock, dict[str, float]]:
    law, overrides = resolve_law(args)
    block = SpringBlock(law)
    return block, block.resolve(overrides)


def fmt(x: float, width: int = 12) -> str:
    if x is None or (isinstance(x, float) and not math.isfinite(x)):
        return "-".rjust(width)
    return f"{x:{width}.6g}"
