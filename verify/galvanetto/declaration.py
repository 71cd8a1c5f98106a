"""The stick–slip models of Galvanetto (2004) as models: ``galvanetto-one-block`` and ``galvanetto-two-blocks``.

Dimensionless blocks on a belt moving at V (Galvanetto 2004, eq. 1), kinetic friction eq. (7)
(parameters γ, δ) or the user's law of the relative velocity r = Ẋ − V (``kinetic`` option, the
r < 0 branch; ``kinetic_pos`` the r > 0 one, default the odd reflection), with its own
parameters.  The one block's steady sliding loses stability in the damping c at c₁ = F_k'(−V):
its Hopf analysis is :func:`landau.verify.galvanetto.bifurcations.hopf_c1_normal_form`.

References
----------
Galvanetto, U. (2004), Sliding bifurcations in the dynamics of mechanical systems with dry friction —
remarks for engineers and applied scientists, J. Sound Vib. 276, 121–139.
"""

from __future__ import annotations

import math

import numpy as np

from landau.errors import InputError, NoHopfError
from landau.models import LawKind, Model, Option, Parameter, Setup

SOURCE = "Galvanetto (2004), eqs (1), (7)"
#: the belt velocity of the one block's Hopf analysis where none is given
V_HOPF = 0.5


def _own_names(setup: Setup) -> set[str]:
    """The parameter names of the user's kinetic law (besides r, gamma, delta)."""
    from landau.laws.parse import referenced_names

    kinetic, kinetic_pos = setup.option("kinetic"), setup.option("kinetic_pos")
    if kinetic is None:
        return set()
    own = referenced_names(kinetic, what="--kinetic") | (
        referenced_names(kinetic_pos, what="--kinetic-pos") if kinetic_pos is not None else set())
    return own - {"r", "gamma", "delta"}


def _declare(setup: Setup, blocks: int) -> tuple[Parameter, ...]:
    out = [Parameter("V", 0.25 if blocks == 2 else V_HOPF, "1", "positive", "belt velocity (dimensionless)", SOURCE),
           Parameter("gamma", 3.0, "1", "real", "decay rate of the kinetic law eq. (7)", SOURCE),
           Parameter("delta", 0.0, "1", "real", "asymptotic friction level of eq. (7)", SOURCE),
           Parameter("c", None if blocks == 1 else 0.0, "1", "nonnegative", "damping (the one block's Hopf "
                     "parameter)", SOURCE)]
    if blocks == 2:
        out += [Parameter("alpha", 1.2, "1", "nonnegative", "stiffness of the spring between the blocks", SOURCE),
                Parameter("beta", 1.3, "1", "positive", "block 2's static friction level", SOURCE)]
    out += [Parameter(n, None, "1", "real", "a parameter of the kinetic law", "the user's law")
            for n in sorted(_own_names(setup))]
    return tuple(out)


def kinetic_law(setup: Setup, params: dict):
    """The kinetic law of the setup (eq. 7 or the ``kinetic`` option) with its values taken from ``params``."""
    from landau.laws.kinetic import KineticFriction

    kinetic, kinetic_pos = setup.option("kinetic"), setup.option("kinetic_pos")
    if kinetic_pos is not None and kinetic is None:
        raise InputError("galvanetto: --kinetic-pos needs --kinetic (the r < 0 branch)")
    own = _own_names(setup)
    g, d = params.pop("gamma", 3.0), params.pop("delta", 0.0)
    extra = {k: params.pop(k) for k in list(params) if k in own}
    if kinetic is None:
        return KineticFriction(g, d)
    return KineticFriction.from_expression(kinetic, kinetic_pos, gamma=g, delta=d,
                                           names=("--kinetic", "--kinetic-pos"), **extra)


def one_block_hopf(setup: Setup):
    """The damped one block's Hopf point c₁ = F_k'(−V) with its normal form, for the setup's law."""
    import difflib

    from landau.verify.galvanetto.bifurcations import hopf_c1, hopf_c1_normal_form

    params = dict(setup.params)
    own = _own_names(setup)
    if "c" in params and "c" not in own:   # (a law that uses c is refused by the law itself: c is the damping)
        raise InputError("galvanetto-one-block: c is the bifurcation parameter (its critical value c1 is computed), "
                         "it cannot be given or swept")
    known = ["V", "gamma", "delta", *sorted(own)]
    unknown = sorted(set(params) - set(known) - {"c"})
    if unknown:
        close = difflib.get_close_matches(unknown[0], known, n=1)
        raise InputError(f"galvanetto-one-block: unknown parameter(s) {', '.join(unknown)} (known: {', '.join(known)})"
                         + (f"; did you mean {close[0]!r}?" if close else ""))
    V = float(params.pop("V", V_HOPF))
    if not (math.isfinite(V) and V > 0):
        raise InputError(f"galvanetto-one-block: belt velocity V must be finite and > 0, got {V!r}")
    g, d = params.get("gamma", 3.0), params.get("delta", 0.0)
    law = kinetic_law(setup, params)
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


def one_block_cycles(setup: Setup):
    """The cycles of the damped one block's smooth slip field (r = Ẋ − V < 0,
    :func:`landau.verify.galvanetto.smooth.damped_slip_system`) in the damping c from c₁; a cycle is the
    block's motion only while it slips (max Ẋ < V): the branch says nothing past the first stick."""
    from landau.analyses.cycle_problems import cycle_problem
    from landau.verify.galvanetto.smooth import damped_slip_system

    result = one_block_hopf(setup)
    params = dict(setup.params)
    V = float(params.pop("V", V_HOPF))
    system = damped_slip_system(V, law=kinetic_law(setup, params))
    return cycle_problem(system, {**system.defaults, "V": V}, result, parameter_range=(0.0, np.inf))


def _simulate_one(setup: Setup, **kw):
    from landau.verify.galvanetto.run import simulate_one_block

    return simulate_one_block(setup, **kw)


def _simulate_two(setup: Setup, **kw):
    from landau.verify.galvanetto.run import simulate_two_blocks

    return simulate_two_blocks(setup, **kw)


_KINETIC_OPTIONS = (Option("kinetic", "kinetic friction for r = Xdot - V < 0 in r, gamma, delta"),
                    Option("kinetic_pos", "the r > 0 branch (default the odd reflection of the r < 0 one)"))

GALVANETTO_ONE_BLOCK = Model(
    name="galvanetto-one-block",
    description="damped one block on a belt (Galvanetto 2004); parameter c, kinetic law eq. (7) or --kinetic EXPR",
    law_kind=LawKind.KINETIC,
    declare=lambda setup: _declare(setup, 1),
    hopf_parameter="c",
    hopf=one_block_hopf,
    cycles=one_block_cycles,
    simulate=_simulate_one,
    options=_KINETIC_OPTIONS,
    # simulate_options: settings of the simulation only (hopf: add the damped block's Hopf point)
    defaults={"t_end": 60.0, "key_parameters": ("V", "c"), "simulate_options": ("hopf",)},
    source=SOURCE,
)

GALVANETTO_TWO_BLOCKS = Model(
    name="galvanetto-two-blocks",
    description="two coupled blocks on a belt (Galvanetto 2004), kinetic law eq. (7) or --kinetic EXPR",
    law_kind=LawKind.KINETIC,
    declare=lambda setup: _declare(setup, 2),
    simulate=_simulate_two,
    options=_KINETIC_OPTIONS,
    defaults={"t_end": 60.0, "key_parameters": ("V", "alpha", "beta")},
    source=SOURCE,
)

__all__ = ["GALVANETTO_ONE_BLOCK", "GALVANETTO_TWO_BLOCKS", "kinetic_law", "one_block_cycles", "one_block_hopf"]
