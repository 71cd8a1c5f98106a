"""Hopf point of a model's steady state, with its first Lyapunov coefficient and criticality.

``landau hopf MODEL [law options] [--param NAME=VALUE ...] [--json]``

Each model registers how to find its Hopf point (:data:`MODELS`, filled by the models'
own modules): the result is a :class:`~landau.derivation.hopf.HopfResult`, which prints its amplitude
equation and criticality.  Models:

* ``spring-block`` — the spring–block of Putelat, Dawes & Willis (2010) with a rate-and-state
  law (built-in name, or ``--mu``/``--state``), at driving velocity ``--V``: the bifurcation
  parameter is the stiffness k.
* ``spring-block-chain`` — N such blocks (``--blocks N``) coupled by ``k_coupling``: the first Hopf
  point as k decreases, with the critical mode shape (:mod:`landau.cli.hopf_chain`).
* ``system`` — any smooth system written with ``--rhs NAME=EXPR`` (:mod:`landau.cli.hopf_system`).
"""

from __future__ import annotations

from typing import Callable

from landau.cli.common import add_friction_arguments, add_law_arguments, block_and_params, parse_velocities
from landau.errors import InputError

#: model name -> (one-line description, function(args) -> HopfResult)
MODELS: dict[str, tuple[str, Callable]] = {}


def register(name: str, description: str):
    """Register ``fn(args) -> HopfResult`` as the Hopf analysis of model ``name``."""
    def deco(fn):
        MODELS[name] = (description, fn)
        return fn
    return deco


@register("spring-block", "spring–block with a rate-and-state law (Putelat et al. 2010); parameter k at --V")
def _spring_block(args):
    from landau.verify.springblock.checks import predict

    if args.friction is not None:
        raise InputError("landau hopf spring-block: the spring-block takes a rate-and-state law (LAW or "
                         "--mu/--state), not --friction")
    if getattr(args, "parameter", None) not in (None, "k"):
        raise InputError("landau hopf spring-block: the bifurcation parameter is the stiffness k "
                         f"(got --parameter {args.parameter})")
    block, params = block_and_params(args)
    Vs = parse_velocities(args.V if args.V is not None else "1e-4")
    if len(Vs) != 1:
        raise InputError("landau hopf: give one driving velocity --V")
    res = predict(block.law, Vs[0], params)
    if res.criticality == "degenerate":
        res = _next_order(block, Vs[0], params, res)
    return res


def _next_order(block, V: float, params, res):
    """At a degenerate point (Λ = 0) the next order from the general engine: l₂, Λ₅ and whether
    the point is degenerate at every order computed (:mod:`landau.derivation.degenerate`)."""
    from dataclasses import replace

    from landau.derivation.general import hopf_normal_form

    gen = hopf_normal_form(block.system, {**params, "V": V}, (0.9 * res.p_c, 1.1 * res.p_c))
    if gen.criticality != "degenerate":
        return res
    keys = ("Lambda_bound", "l2_bound", "criticality_next_order", "degenerate_at_every_order_computed")
    return replace(res, Lambda5=gen.Lambda5, l2=gen.l2,
                   extra={**res.extra, **{k: gen.extra[k] for k in keys if k in gen.extra}})


def _load_models() -> None:
    # the other models register themselves when their analysis modules are imported
    import importlib

    for mod in ("landau.cli.hopf_galvanetto", "landau.cli.hopf_lancioni", "landau.cli.hopf_system",
                "landau.cli.hopf_chain"):
        try:
            importlib.import_module(mod)
        except ModuleNotFoundError as exc:
            if exc.name != mod:
                raise


def configure(p) -> None:
    from landau.cli import hopf_chain, hopf_system

    p.add_argument("model", help="the mechanical model (spring-block, spring-block-chain, galvanetto-one-block, "
                                 "impact-oscillator, system)")
    add_law_arguments(p)
    add_friction_arguments(p)
    p.add_argument("--V", default=None, help="spring-block: driving velocity in m/s (default 1e-4)")
    p.add_argument("--kinetic", default=None, metavar="EXPR",
                   help="galvanetto-one-block: kinetic friction for r = Xdot - V < 0 in r, gamma, delta")
    p.add_argument("--kinetic-pos", default=None, metavar="EXPR",
                   help="galvanetto-one-block: the r > 0 branch (default the odd reflection of --kinetic)")
    p.add_argument("--parameter", default=None, metavar="NAME",
                   help="impact-oscillator: the bifurcation parameter "
                        "(default mu, or the first parameter of --friction); system: the Hopf parameter")
    hopf_system.add_arguments(p)
    hopf_chain.add_arguments(p)


def run(args) -> dict:
    _load_models()
    if args.model not in MODELS:
        raise InputError(f"landau hopf: unknown model {args.model!r}; known: {', '.join(MODELS)}")
    res = MODELS[args.model][1](args)
    doc = {"model": args.model}
    doc.update(res.as_dict() if hasattr(res, "as_dict") else {"result": repr(res)})
    doc["text"] = str(res)
    if doc.get("degenerate_at_every_order_computed"):
        doc["text"] += ("\nLambda and Lambda5 are 0 within their round-off bounds ("
                        f"{doc.get('Lambda_bound', 0.0):.1e}, {doc.get('l2_bound', 0.0):.1e}): "
                        "degenerate at every order computed")
    elif doc.get("criticality_next_order"):
        doc["text"] += (f"\nLambda is 0 within its round-off bound: the fifth order decides, "
                        f"{doc['criticality_next_order']} (l2 = {doc.get('l2', 0.0):.6g})")
    return doc


def render(doc: dict) -> str:
    return doc.get("text") or repr(doc)
