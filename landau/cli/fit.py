"""Fit a friction law's parameters to a laboratory record (velocity steps, slide-hold-slide) by least squares.

Reads a CSV of time (or load-point displacement), load-point velocity (or displacement) and
friction: landau's columns ``t``, ``x_lp``, ``V_lp``, ``mu`` (units in brackets, SI otherwise), or
rsfmodel's with ``--format rsfmodel``, or any other with ``--column NAME=COLUMN`` and ``--unit
NAME=UNIT``.  Fits the quasi-static spring–slider per unit normal stress with the law given
(``--law dieterich``, or ``--mu``/``--state`` for your own) and the stiffness ``--k`` (e.g.
``1e-3/um``), and reports each parameter with its standard error, the correlation matrix and the
residual; ``--mcmc STEPS`` adds a posterior by emcee, its chains saved with ``--chains FILE.npz``.
"""

from __future__ import annotations

from landau.errors import InputError


def configure(p) -> None:
    p.add_argument("data", help="the CSV record")
    p.add_argument("--law", default=None, help="built-in law (landau laws lists them), or the name of an inline law")
    p.add_argument("--mu", default=None,
                   help="inline friction coefficient, e.g. 'a_v + a*log(v/V_s) + b*log(V_s*phi/L)'")
    p.add_argument("--state", action="append", default=[], metavar="NAME=RATE",
                   help="inline state variable and its rate dNAME/dt (repeatable), e.g. phi='1 - v*phi/L'")
    p.add_argument("--format", default="landau", choices=["landau", "rsfmodel"], help="the record's column layout")
    p.add_argument("--column", action="append", default=[], metavar="NAME=COLUMN",
                   help="the file's column for landau's t, x_lp, V_lp or mu (repeatable)")
    p.add_argument("--unit", action="append", default=[], metavar="NAME=UNIT",
                   help="the unit of a column (s, um, um/s, ...; repeatable)")
    p.add_argument("--k", default=None, metavar="K", help="stiffness k' = k/sigma, e.g. 1e-3/um (a bare number: 1/m)")
    p.add_argument("--fit-k", action="store_true", help="fit the stiffness too (--k is its starting value)")
    p.add_argument("--trend", action="store_true", help="fit a linear trend of friction in load-point displacement")
    p.add_argument("--free", default=None, metavar="NAMES",
                   help="comma-separated parameters to fit (default: all of the law's but V_s)")
    p.add_argument("--param", action="append", default=[], metavar="NAME=VALUE",
                   help="starting or fixed value of a parameter, e.g. L=10um, V_s=1um/s (repeatable)")
    p.add_argument("--mcmc", type=int, default=None, metavar="STEPS", help="emcee steps per walker (default: no MCMC)")
    p.add_argument("--walkers", type=int, default=None, help="emcee walkers (default max(4q, 16))")
    p.add_argument("--burn", type=int, default=None, help="steps dropped as burn-in (default half)")
    p.add_argument("--seed", type=int, default=None, help="seed of the MCMC (default 0)")
    p.add_argument("--chains", default=None, metavar="FILE", help="save the MCMC chains to FILE (.npz)")


def _pairs(items, option: str) -> dict[str, str]:
    from landau.cli.common import split_assignment

    out: dict[str, str] = {}
    for item in items:
        name, val = split_assignment(item, option, "VALUE", out)
        out[name] = val.strip()
    return out


def _law(args, params: dict[str, float]):
    from landau.lab.fit import STIFFNESS, TREND
    from landau.laws import FrictionLaw, get_law

    if args.mu is not None or args.state:
        if args.mu is None or not args.state:
            raise InputError("an inline law needs both --mu and at least one --state NAME=RATE")
        states = _pairs(args.state, "--state")
        own = {n: v for n, v in params.items() if n not in (STIFFNESS, TREND)}
        return FrictionLaw.from_strings(args.law or "inline", args.mu, states, own)
    if args.law is None:
        raise InputError("name a law with --law (landau laws lists them), or give --mu and --state")
    return get_law(args.law)


def run(args) -> dict:
    from landau.lab.data import read_csv
    from landau.lab.fit import fit
    from landau.lab.units import KINDS, parse_value

    params = {n: parse_value(v, tuple(KINDS), f"--param {n}")[0] for n, v in _pairs(args.param, "--param").items()}
    law = _law(args, params)
    data = read_csv(args.data, columns=_pairs(args.column, "--column"), units=_pairs(args.unit, "--unit"),
                    format=args.format)
    k = parse_value(args.k, "inverse length", "--k")[0] if args.k is not None else None
    free = None
    if args.free is not None:
        free = [s.strip() for s in args.free.split(",") if s.strip()]
        if not free:
            raise InputError("--free: no parameter named")
    if args.chains is not None and not args.mcmc:
        raise InputError("--chains needs --mcmc STEPS")
    if args.mcmc is not None and args.mcmc < 2:
        raise InputError(f"--mcmc must be at least 2 steps, got {args.mcmc}")
    res = fit(data, law, free=free, params=params, k=k, fit_k=args.fit_k, trend=args.trend, mcmc=args.mcmc or 0,
              walkers=args.walkers, burn=args.burn, seed=args.seed or 0, chains=args.chains)
    doc = res.to_dict()
    doc["data"] = {"file": args.data, "samples": len(data), "t_end_s": float(data.t[-1] - data.t[0])}
    doc["units"] = "SI: lengths m, velocities m/s, k and trend 1/m"
    return doc


def render(doc: dict) -> str:
    lines = [f"law {doc['law']}, {doc['data']['samples']} samples ({doc['units']})"]
    for n, e in doc["fitted"].items():
        se = "not determined" if e["standard_error"] is None else f"{e['standard_error']:.3g}"
        lines.append(f"  {n:>8} = {e['value']:.10g} ± {se}")
    if doc["fixed"]:
        lines.append("  fixed: " + ", ".join(f"{n}={v:g}" for n, v in doc["fixed"].items()))
    names = doc["correlation"]["names"]
    lines.append("  correlation: " + "  ".join(f"{n:>8}" for n in names))
    for n, row in zip(names, doc["correlation"]["matrix"], strict=True):
        lines.append(f"  {n:>11}: " + "  ".join("       -" if x is None else f"{x:8.3f}" for x in row))
    lines.append(f"  rms residual {doc['rms_residual']:.3g}; {doc['nfev']} forward runs; {doc['message']}")
    if doc["mcmc"]:
        m = doc["mcmc"]
        lines.append(f"  MCMC: {m['draws']} draws, acceptance {m['acceptance']:.2f}"
                     + (f", chains in {m['chains']}" if m["chains"] else ""))
        for n in names:
            lines.append(f"    {n:>8}: mean {m['mean'][n]:.6g}, std {m['std'][n]:.3g}")
    return "\n".join(lines)
