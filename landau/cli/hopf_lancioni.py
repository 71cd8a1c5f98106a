"""``landau hopf impact-oscillator``: the Hopf point of the slip equilibrium of the frictional impact
oscillator of Lancioni, Lenci & Galvanetto, with the paper's Coulomb friction or your own law.

``landau hopf impact-oscillator [--friction EXPR [--friction-neg EXPR]] [--parameter NAME]
[--param NAME=VALUE ...] [--json]``

* without ``--friction``: plain Coulomb friction, bifurcation parameter μ (the paper's Hopf
  point, μ_c = 0.40978 for set 1 with g = 10 m/s²);
* ``--friction EXPR``: a friction coefficient F(v) for positive sliding velocity ``v`` (odd
  extension for v < 0 unless ``--friction-neg``), its parameters by ``--param``; the
  bifurcation parameter is ``--parameter`` (a law or mechanical parameter), default the law's
  first parameter;
* ``--param``: also the mechanical parameters (m1, m2, l, k_y, k_phi, c_y, c_phi, phi0, y0, g;
  default set 1) and the belt velocity ``v_belt`` (m/s, default −1: positive slip, the
  direction with the Hopf point).

The result carries c₁ and the Landau coefficient from the landau engine
(:func:`landau.derivation.general.hopf_normal_form`), hence the criticality.
"""

from __future__ import annotations

from dataclasses import replace

from landau.cli.common import parse_params, velocity_law_from_args
from landau.cli.hopf import register
from landau.derivation.hopf import HopfResult
from landau.errors import InputError

#: --param names besides the mechanical ones and the law's
EXTRA = ("v_belt",)


def impact_oscillator_hopf(args) -> HopfResult:
    """The Hopf point of the impact oscillator's slip equilibrium for the command-line arguments.

    Parameters
    ----------
    args : argparse.Namespace
        ``friction``, ``friction_neg``, ``friction_name``, ``param`` and optionally ``parameter``.

    Returns
    -------
    HopfResult
        With the friction law's expression, the belt velocity and the bifurcation parameter in
        ``extra``.

    Raises
    ------
    InputError
        Rate-and-state options, unknown parameters, a law that cannot be used.

    References
    ----------
    Lancioni, G., Lenci, S. & Galvanetto, U., the frictional impact oscillator, eq. (1) and
    Sec. 3 (Hopf point of the slip equilibrium).
    """
    from landau.laws.velocity import coulomb
    from landau.verify.lancioni import slip as S

    if args.law is not None or args.mu is not None or args.state or args.V is not None:
        raise InputError("landau hopf impact-oscillator: give the friction as --friction EXPR (or the Coulomb "
                         "coefficient as --param mu=VALUE); LAW, --mu, --state and --V are for the spring-block")
    params = parse_params(args.param)
    user = getattr(args, "friction", None) is not None
    law = velocity_law_from_args(args, coulomb(), params)
    v = params.pop("v_belt", -1.0)
    unknown = sorted(set(params) - set(S.PARAM_NAMES))
    if unknown:
        raise InputError(f"impact-oscillator: unknown parameter(s) {', '.join(unknown)} (known: the law's "
                         f"{', '.join(p.name for p in law.parameters) or 'none'}, {', '.join(S.PARAM_NAMES)}, "
                         f"{', '.join(EXTRA)})")
    if v >= 0:
        raise InputError(f"impact-oscillator: v_belt must be < 0 (positive slip, the belt direction with the Hopf "
                         f"point), got {v!r}")
    parameter = getattr(args, "parameter", None)
    friction = law if user or parameter not in (None, "mu") else None
    if friction is None:  # the paper's Coulomb friction, bifurcation parameter mu
        h = S.slip_hopf(params)
    else:
        h = S.slip_hopf(params, friction=friction, parameter=parameter, v=v)
    extra = {**h.extra, "friction": law.name, "friction_positive": str(law.positive),
             "friction_negative": str(law.branch(-1)), "v_belt": v}
    return replace(h, extra=extra)


register("impact-oscillator", "frictional impact oscillator (Lancioni, Lenci & Galvanetto): slip equilibrium; "
         "parameter mu, or a parameter of --friction")(impact_oscillator_hopf)
