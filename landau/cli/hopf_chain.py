"""``landau hopf spring-block-chain LAW --blocks N``: the first Hopf point of a chain of spring–blocks as k decreases.

``landau hopf spring-block-chain LAW --blocks N [--V V] [--param NAME=VALUE ...] [--bracket LO:HI] [--json]``

Block i (``--param M_i=…``, ``--param sigma_i=…``, default M_i = 1.2 kg, σ_i = M_i g) is pulled
by a spring k to the load point and coupled to its neighbours by ``--param k_coupling=…`` (N/m,
free ends); the law (built-in name, or ``--mu``/``--state``) and its parameters are shared.  The
result is the general engine's amplitude equation at the first crossing met as k decreases, with
the critical mode shape (the slips X_i, largest 1) — :func:`landau.analyses.chain.chain_hopf`.
"""

from __future__ import annotations

from landau.cli.common import parse_params, parse_velocities, resolve_law
from landau.cli.hopf import register
from landau.errors import InputError


def add_arguments(p) -> None:
    """The options of ``landau hopf spring-block-chain`` (added to the ``landau hopf`` parser)."""
    p.add_argument("--blocks", default=None, metavar="N",
                   help="spring-block-chain: the number of blocks (1 to 12)")


@register("spring-block-chain", "N spring-blocks coupled by k_coupling (Burridge-Knopoff with a rate-and-state "
                                "law); parameter k at --V")
def chain_hopf_cli(args):
    """The chain's Hopf point for the command-line arguments."""
    from landau.analyses.chain import chain_hopf
    from landau.cli.hopf_system import parse_bracket
    from landau.systems.chain import SpringBlockChain

    for attr, label in (("friction", "--friction"), ("rhs", "--rhs"), ("equilibrium", "--equilibrium"),
                        ("guess", "--guess"), ("mass", "--mass"), ("kinetic", "--kinetic")):
        if getattr(args, attr, None) not in (None, []):
            raise InputError(f"landau hopf spring-block-chain: {label} belongs to another model")
    if getattr(args, "parameter", None) not in (None, "k"):
        raise InputError("landau hopf spring-block-chain: the bifurcation parameter is the stiffness k "
                         f"(got --parameter {args.parameter})")
    if args.blocks is None:
        raise InputError("landau hopf spring-block-chain: give the number of blocks with --blocks N")
    try:
        n = int(args.blocks)
    except ValueError:
        raise InputError(f"--blocks: {args.blocks!r} is not an integer") from None
    law, overrides = resolve_law(args)
    overrides.update({k: v for k, v in parse_params(args.param, reserved={}).items() if k not in overrides})
    for name in ("k", "V"):
        if name in overrides:
            raise InputError(f"--param {name}: " + ("k is the bifurcation parameter: its critical value is computed"
                                                    if name == "k" else "give the driving velocity with --V"))
    Vs = parse_velocities(args.V if args.V is not None else "1e-4")
    if len(Vs) != 1:
        raise InputError("landau hopf spring-block-chain: give one driving velocity --V")
    bracket = parse_bracket(args.bracket) if args.bracket is not None else None
    return chain_hopf(SpringBlockChain(law, n), {**overrides, "V": Vs[0]}, bracket)
