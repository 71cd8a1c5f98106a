"""``landau hopf galvanetto-one-block``: the damped one block's Hopf point with any kinetic law.

The steady sliding equilibrium of the one block (Galvanetto 2004, eq. (4a)) loses stability in
the damping c at c₁ = F_k'(−V); the landau engine gives the criticality and the amplitude
equation on the smooth slip field (:func:`landau.verify.galvanetto.bifurcations.hopf_c1_normal_form`).
The kinetic law is eq. (7) or the user's ``--kinetic EXPR`` (r < 0 branch in r, gamma, delta and
any parameter of its own; ``--kinetic-pos`` the r > 0 branch); ``--param gamma=... --param
delta=...`` and ``--param NAME=VALUE`` for the law's own (e.g. ``eta`` in
``'(1 - delta)/(1 - gamma*r)**2 + delta - eta*r'``), ``--V`` the belt velocity (default 0.5).
"""

from __future__ import annotations

import math

import numpy as np

from landau.cli.common import parse_params
from landau.cli.hopf import register
from landau.errors import InputError, NoHopfError


@register("galvanetto-one-block", "damped one block on a belt (Galvanetto 2004); parameter c, kinetic law "
                                  "eq. (7) or --kinetic EXPR")
def _galvanetto_one_block(args):
    from landau.laws.kinetic import KineticFriction
    from landau.verify.galvanetto.bifurcations import hopf_c1, hopf_c1_normal_form

    if getattr(args, "friction", None) is not None:
        raise InputError("landau hopf galvanetto-one-block: give the kinetic law as --kinetic EXPR (the r < 0 "
                         "branch in r = Xdot - V), not --friction")
    if getattr(args, "parameter", None) not in (None, "c"):
        raise InputError(f"landau hopf galvanetto-one-block: the bifurcation parameter is the damping c "
                         f"(got --parameter {args.parameter})")
    over = parse_params(args.param)
    kinetic, kinetic_pos = getattr(args, "kinetic", None), getattr(args, "kinetic_pos", None)
    if kinetic_pos is not None and kinetic is None:
        raise InputError("galvanetto-one-block: --kinetic-pos needs --kinetic (the r < 0 branch)")
    # a user's law may have parameters of its own (--param eta=0.05 for '... - eta*r')
    own = set()
    if kinetic is not None:
        from landau.laws.parse import referenced_names

        own = referenced_names(kinetic, what="--kinetic") | (
            referenced_names(kinetic_pos, what="--kinetic-pos") if kinetic_pos is not None else set())
    unknown = sorted(set(over) - {"gamma", "delta"} - own)
    if unknown:
        raise InputError(f"galvanetto-one-block: unknown parameter(s) {', '.join(unknown)} (known: "
                         + ", ".join(["gamma", "delta", *sorted(own - {"r", "gamma", "delta"})]) + ")")
    g, d = over.pop("gamma", 3.0), over.pop("delta", 0.0)
    law = (KineticFriction(g, d) if kinetic is None
           else KineticFriction.from_expression(kinetic, kinetic_pos, gamma=g, delta=d,
                                                names=("--kinetic", "--kinetic-pos"), **over))
    try:
        V = float(args.V) if args.V is not None else 0.5
    except ValueError:
        raise InputError(f"--V: {args.V!r} is not a number") from None
    if not (math.isfinite(V) and V > 0):
        raise InputError(f"galvanetto-one-block: belt velocity V must be finite and > 0, got {V!r}")
    where = f"at V = {V:g} with gamma = {g:g}, delta = {d:g}"
    with np.errstate(all="raise"):
        try:
            c1 = hopf_c1(V, law=law)
        except (OverflowError, ZeroDivisionError, FloatingPointError) as exc:
            raise InputError(f"galvanetto-one-block: F_k'(-V) leaves the float64 range {where} ({exc}): bring V "
                             "and the law's parameters nearer their physical scale") from None
    if not math.isfinite(c1):
        raise InputError(f"galvanetto-one-block: F_k'(-V) = {c1} {where}: the kinetic law is not differentiable "
                         f"at steady sliding, r = -V, or leaves the float64 range ({law!r})")
    if c1 == 0 and law.dneg(-V * (1 - 1e-6)) != 0:
        raise InputError(f"galvanetto-one-block: F_k'(-V) underflows to 0 {where} (its exact value is below "
                         "float64's smallest number): bring V and the law's parameters nearer their physical scale")
    if not c1 > 0:
        raise NoHopfError(f"galvanetto-one-block: F_k'(-V) = {c1:.6g} <= 0 at V = {V:g}: steady sliding is "
                          f"stable for every damping c >= 0 ({law!r})")
    try:
        return hopf_c1_normal_form(V, law=law)
    except (OverflowError, ZeroDivisionError, FloatingPointError) as exc:
        raise InputError(f"galvanetto-one-block: the normal form leaves the float64 range {where} ({exc}): "
                         "bring V and the law's parameters nearer their physical scale") from None
