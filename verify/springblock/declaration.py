"""The spring–block family declared as models: ``spring-block`` and ``spring-block-chain``.

* ``spring-block`` — the block on a driven spring with a rate-and-state law, Putelat, Dawes &
  Willis (2010), eq. (4), with the optional terms of :mod:`landau.systems.springblock_terms`
  (radiation damping η, Rice 1993; variable normal stress γ_LD and the state response α_LD,
  Linker & Dieterich 1992).  Hopf parameter: the stiffness k.  Sweep tasks: ``hopf`` (vectorised
  over a chunk), ``check`` (:func:`landau.check`), ``regime`` (direct simulation from both sides).
* ``spring-block-chain`` — N such blocks coupled by ``k_coupling`` (Burridge & Knopoff 1967),
  :func:`landau.analyses.chain.chain_hopf`.  Hopf parameter: k.

Each parameter is declared once here, with its default, unit, domain and source; the defaults are
those of the law (:mod:`landau.laws`) and of :class:`~landau.systems.system.SpringBlock`.

References
----------
Putelat, T., Dawes, J. H. P. & Willis, J. R. (2010), Regimes of frictional sliding of a spring–block
system, J. Mech. Phys. Solids 58(1), 27–53.
Burridge, R. & Knopoff, L. (1967), Model and theoretical seismicity, Bull. Seismol. Soc. Am. 57(3), 341–371.
"""

from __future__ import annotations

from landau.derivation.coefficients import CONVENTION
from landau.errors import InputError
from landau.models import LawKind, Model, Option, Parameter, Setup
from landau.systems.chain import MAX_BLOCKS

#: the driving velocity used where none is given (m/s), as ``landau hopf`` and ``landau simulate`` do
V_DEFAULT = 1e-4
PUTELAT = "Putelat et al. (2010), Sec. 3"


def _law(setup: Setup):
    from landau.laws import get_law

    return setup.law if setup.law is not None else get_law("dieterich")


def law_parameters(law) -> tuple[Parameter, ...]:
    """The law's constants as model parameters (their defaults, units and sources)."""
    return tuple(Parameter(p.name, None if p.default is None else float(p.default), p.units or "1",
                           "positive" if p.positive else "real", p.description, p.source)
                 for p in law.parameters)


def _term_parameters() -> tuple[Parameter, ...]:
    from landau.systems.springblock_terms import TERMS

    out = []
    for name, t in TERMS.items():
        out.append(Parameter(name, 0.0, t.unit, "nonnegative" if t.nonnegative else "real", t.meaning, t.source))
        # a term's further parameters (a drainage time, a storage coefficient), with their defaults
        out += [Parameter(q.symbol.name, float(q.default), q.unit, q.domain, q.meaning, t.source)
                for q in t.parameters]
    return tuple(out)


def _block_parameters(setup: Setup) -> tuple[Parameter, ...]:
    from landau.systems.system import G_DEFAULT, M_DEFAULT

    law = _law(setup)
    return (
        Parameter("V", V_DEFAULT, "m/s", "positive", "driving (load-point) velocity", PUTELAT),
        Parameter("k", None, "N/m", "positive", "spring stiffness (the Hopf parameter)", PUTELAT),
        *law_parameters(law),
        Parameter("M", M_DEFAULT, "kg", "nonnegative", "block mass (0: quasi-static)", PUTELAT),
        Parameter("g", G_DEFAULT, "m/s^2", "positive", "gravitational acceleration", PUTELAT),
        Parameter("sigma", M_DEFAULT * G_DEFAULT, "N", "positive", "normal load (default M g)", PUTELAT),
        *_term_parameters(),
    )


def spring_block_hopf(setup: Setup):
    """The Hopf point of the spring–block at one point (:func:`landau.verify.springblock.checks.predict`);
    at a degenerate point (Λ = 0) the next order from the general engine (l₂, Λ₅); with the ``patch``
    option, a fault patch's stiffness and verdict (:mod:`landau.analyses.fault_patch`)."""
    from landau.analyses.fault_patch import patch_stiffness_of, with_patch

    law = _law(setup)
    params = dict(setup.params)
    if "k" in params:
        raise InputError("spring-block: k is the bifurcation parameter (its critical value k_c is computed), it "
                         "cannot be given")
    k_patch = patch_stiffness_of(setup)
    if k_patch is not None:
        return with_patch(_block_hopf(law, params), setup, k_patch)
    return _block_hopf(law, params)


def _block_hopf(law, params: dict):
    """The block's Hopf point (:func:`spring_block_hopf` without the patch)."""
    from dataclasses import replace

    from landau.derivation.general import hopf_normal_form
    from landau.systems.system import SpringBlock
    from landau.verify.springblock.checks import predict

    V = float(params.pop("V", V_DEFAULT))
    SPRING_BLOCK.parameter("V").check(V, "spring-block")
    block = SpringBlock.for_params(law, params)
    resolved = block.resolve(params)
    res = predict(law, V, resolved)
    if res.criticality != "degenerate":
        return res
    gen = hopf_normal_form(block.system, {**resolved, "V": V}, (0.9 * res.p_c, 1.1 * res.p_c))
    if gen.criticality != "degenerate":
        return res
    keys = ("Lambda_bound", "l2_bound", "criticality_next_order", "degenerate_at_every_order_computed")
    return replace(res, Lambda5=gen.Lambda5, l2=gen.l2,
                   extra={**res.extra, **{k: gen.extra[k] for k in keys if k in gen.extra}})


def spring_block_cycles(setup: Setup):
    """The spring–block's cycles in k (:class:`~landau.periodic.problem.CycleProblem`) from its Hopf point:
    eq. (4) of Putelat et al. (2010) with every optional term given (radiation damping η …), any law
    and any number of states; the amplitude is the slip X's half swing (the amplitude equation's C).
    A quasi-static block (M = 0) is a differential-algebraic system: refused with an InputError."""
    import numpy as np

    from landau.analyses.cycle_problems import cycle_problem
    from landau.systems.system import SpringBlock

    law = _law(setup)
    result = spring_block_hopf(setup)
    params = dict(setup.params)
    V = float(params.pop("V", V_DEFAULT))
    block = SpringBlock.for_params(law, params)
    resolved = {**block.resolve(params), "V": V}
    unknowns = {}
    if block.system.unknowns:   # the steady state with no closed form, solved numerically
        vals = block.argvals(V, resolved)
        unknowns = {s.name: float(np.ravel(x)[0]) for s, x in zip(block.args, vals, strict=True) if s in block.phi0}
    return cycle_problem(block.system, resolved, result, unknowns=unknowns, parameter_range=(0.0, np.inf))


def _hopf_task(task, model, law, fixed, options):
    from landau.analyses.sweep_tasks import SpringBlockHopf

    return SpringBlockHopf("hopf", model, law, fixed, options, chunk_size=int(dict(options).get("chunk_size", 4096)),
                           method=str(dict(options).get("method", "auto")))


def _check_task(task, model, law, fixed, options):
    from landau.analyses.sweep_tasks import SpringBlockCheck

    return SpringBlockCheck("check", model, law, fixed, options, chunk_size=1)


def _simulate(setup: Setup, **kw):
    from landau.verify.springblock.run import simulate

    return simulate(setup, **kw)


def _regime_task(task, model, law, fixed, options):
    from landau.verify.springblock.regime_map import make_task

    return make_task(task, model, law, fixed, options)


def plot_regime_sweep(ds, fig) -> dict:
    """A ``regime`` sweep over (V, k) as the regime map with the amplitude equation's boundaries on top
    (k_c(V), the fold of cycles, V*: :func:`landau.analyses.regime_overlay.regime_overlay`); over other
    axes the generic figure of its numbers."""
    import numpy as np

    from landau.analyses.regime_overlay import regime_overlay
    from landau.verify.springblock.regime_map import plot_regime_map

    if set(ds.status.dims) != {"V", "k"}:
        from landau.report.sweep_figure import plot_any_sweep

        return plot_any_sweep(ds, fig)
    overlay = regime_overlay(ds)
    plot_regime_map(ds, fig.subplots(), overlay=overlay)
    vals, counts = np.unique(ds.regime.values.astype(str), return_counts=True)
    doc: dict = {"kind": "regime-map", "regimes": {str(v): int(c) for v, c in zip(vals, counts, strict=True)}}
    if overlay is not None:
        # the codimension-two velocities drawn, as landau derive --codim2 gives them
        doc["V_star"] = [float(v) for v in overlay["V_star"]]
        doc["fold_points"] = int(np.isfinite(overlay["k_fold"]).sum())
    return doc


def _patch_options():
    from landau.analyses.fault_patch import OPTIONS

    return OPTIONS


SPRING_BLOCK = Model(
    name="spring-block",
    description="spring-block with a rate-and-state law (Putelat et al. 2010); parameter k at --V",
    law_kind=LawKind.RATE_AND_STATE,
    declare=_block_parameters,
    hopf_parameter="k",
    hopf=spring_block_hopf,
    simulate=_simulate,
    cycles=spring_block_cycles,
    tasks={"hopf": _hopf_task, "check": _check_task, "regime": _regime_task},
    options=_patch_options(),
    # "presets": the conventions its load-point histories take (landau.lab.preset: si, lab)
    defaults={"V": V_DEFAULT, "t_end": 20.0, "key_parameters": ("V", "k"), "history": True, "presets": ("si", "lab")},
    convention="putelat2010",
    convention_description=CONVENTION,
    plots={"regime": plot_regime_sweep},
    source="Putelat, Dawes & Willis (2010), eq. (4); Rice (1993); Linker & Dieterich (1992)",
    default_law="dieterich",
)


# ---------------------------------------------------------------------------------------------
# the chain
# ---------------------------------------------------------------------------------------------


def chain_blocks(setup: Setup) -> int:
    """The number of blocks of the chain (the ``blocks`` option), checked."""
    n = setup.option("blocks")
    if n is None:
        raise InputError("spring-block-chain: give the number of blocks (--blocks N, options={'blocks': N})")
    try:
        n = int(n)
    except (TypeError, ValueError):
        raise InputError(f"--blocks: {n!r} is not an integer") from None
    if not 1 <= n <= MAX_BLOCKS:
        raise InputError(f"--blocks: the chain takes 1 to {MAX_BLOCKS} blocks, got {n}")
    return n


def _chain_parameters(setup: Setup) -> tuple[Parameter, ...]:
    from landau.systems.chain import K_COUPLING_DEFAULT
    from landau.systems.system import G_DEFAULT, M_DEFAULT

    law = _law(setup)
    n = chain_blocks(setup) if setup.option("blocks") is not None else 1
    blocks = []
    for i in range(1, n + 1):
        blocks += [Parameter(f"M_{i}", M_DEFAULT, "kg", "nonnegative", f"mass of block {i}", PUTELAT),
                   Parameter(f"sigma_{i}", M_DEFAULT * G_DEFAULT, "N", "positive",
                             f"normal load of block {i} (default: the single block's sigma)", PUTELAT)]
    return (
        Parameter("V", V_DEFAULT, "m/s", "positive", "driving (load-point) velocity", PUTELAT),
        Parameter("k", None, "N/m", "positive", "stiffness of each block's spring to the load point (Hopf parameter)",
                  PUTELAT),
        *law_parameters(law),
        Parameter("k_coupling", K_COUPLING_DEFAULT, "N/m", "nonnegative", "stiffness of the springs between "
                  "neighbouring blocks", "Burridge & Knopoff (1967)"),
        Parameter("g", G_DEFAULT, "m/s^2", "positive", "gravitational acceleration", PUTELAT),
        *blocks,
    )


def chain_hopf_setup(setup: Setup):
    """The chain's first Hopf point as k decreases (:func:`landau.analyses.chain.chain_hopf`)."""
    from landau.analyses.chain import chain_hopf
    from landau.systems.chain import SpringBlockChain

    params = dict(setup.params)
    if "k" in params:
        raise InputError("spring-block-chain: k is the bifurcation parameter: its critical value is computed")
    params.setdefault("V", V_DEFAULT)
    bracket = setup.option("bracket")
    return chain_hopf(SpringBlockChain(_law(setup), chain_blocks(setup)), params,
                      None if bracket is None else tuple(bracket), route=setup.option("route") or "auto")


def chain_cycles(setup: Setup):
    """The chain's cycles in k from its first Hopf point (:func:`chain_hopf_setup`), measured on the slip
    of the block that moves most in the critical mode (the amplitude equation's normalisation)."""
    import numpy as np

    from landau.analyses.cycle_problems import cycle_problem
    from landau.systems.chain import SpringBlockChain

    result = chain_hopf_setup(setup)
    chain = SpringBlockChain(_law(setup), chain_blocks(setup))
    params = {"V": V_DEFAULT, **dict(setup.params)}
    resolved = chain.resolve(params)
    system = chain.system
    y_eq = chain.equilibrium_values(resolved)
    unknowns = {u.name: float(y_eq[2 + j]) for j, u in enumerate(system.unknowns)}
    return cycle_problem(system, resolved, result, unknowns=unknowns, parameter_range=(0.0, np.inf))


SPRING_BLOCK_CHAIN = Model(
    name="spring-block-chain",
    description="N spring-blocks coupled by k_coupling (Burridge-Knopoff with a rate-and-state law); "
                "parameter k at --V",
    law_kind=LawKind.RATE_AND_STATE,
    declare=_chain_parameters,
    hopf_parameter="k",
    hopf=chain_hopf_setup,
    cycles=chain_cycles,
    options=(Option("blocks", f"the number of blocks (1 to {MAX_BLOCKS})"),
             Option("bracket", "stiffnesses LO:HI (N/m) to search for the first crossing"),
             Option("route", "auto, symbolic (the general engine, up to 12 blocks) or numeric (sparse, float64)")),
    defaults={"V": V_DEFAULT},
    source="Burridge & Knopoff (1967); Putelat et al. (2010), eq. (4) per block",
    default_law="dieterich",
)

__all__ = ["SPRING_BLOCK", "SPRING_BLOCK_CHAIN", "V_DEFAULT", "chain_blocks", "chain_cycles", "law_parameters",
           "spring_block_cycles"]
