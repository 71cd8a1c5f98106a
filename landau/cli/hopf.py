"""Hopf point of a model's steady state, with its first Lyapunov coefficient and criticality.

``landau hopf MODEL [law options] [--param NAME=VALUE ...] [model options] [--json]``

MODEL is any registered model that offers a Hopf analysis (:func:`landau.models.get`; ``landau
hopf --help`` lists them): the command turns its arguments into the model's setup — the friction
law of the kind the model takes, the parameter values, the model's own options — and calls the
model's Hopf analysis.  The result is a :class:`~landau.derivation.hopf.HopfResult`, which prints its
amplitude equation and criticality.  The built-in models:

* ``spring-block`` — the spring–block of Putelat, Dawes & Willis (2010) with a rate-and-state
  law (built-in name, or ``--mu``/``--state``), at driving velocity ``--V``: the bifurcation
  parameter is the stiffness k.
* ``spring-block-chain`` — N such blocks (``--blocks N``, up to 100) coupled by ``k_coupling``: the
  first Hopf point as k decreases, with the critical mode shape; ``--route`` symbolic (the general
  engine at 50 digits, up to 12 blocks), numeric (float64 sparse solves from one block's law jets) or
  auto (symbolic up to 3 blocks); the route taken is printed and in the JSON (``route``).
* ``impact-oscillator``, ``galvanetto-one-block`` — with ``--friction EXPR`` / ``--kinetic EXPR``.
* ``system`` — any smooth system written with ``--rhs NAME=EXPR``.
* ``mode-coupling`` — friction-induced flutter of Hoffmann et al. (2002): ``--param`` m, k1, k2,
  alpha1, alpha2 (the spring angles, in degrees), kH, kNL, P, c1, c2, v0 in SI units, ``--contact``
  linear, cubic or hertz; or an N-DOF structure (``--mass-matrix``, ``--stiffness-matrix``,
  ``--damping-matrix``, ``--normal``, ``--tangential``).  The bifurcation parameter is mu (or
  ``--parameter``); undamped, the result is the mode-coupling collision (``kind``).

``landau hopf spring-block --patch H --shear-modulus G --param sigma=PA`` analyses a fault patch of
size H as a block of unit area: k from the patch (π μ′/H, Rice & Ruina 1983), its critical size and
whether its steady sliding is unstable (docs/models/nucleation.md).
"""

from __future__ import annotations

from landau.cli.common import add_friction_arguments, add_law_arguments
from landau.cli.model_args import add_model_options, add_patch_options, setup_from_args
from landau.errors import InputError


def configure(p) -> None:
    from landau.models import offering

    p.add_argument("model", help="the mechanical model (" + ", ".join(offering("hopf")) + ")")
    add_law_arguments(p)
    add_friction_arguments(p)
    p.add_argument("--V", default=None, help="spring-block: driving velocity in m/s (default 1e-4); galvanetto: the "
                                              "belt velocity")
    add_model_options(p)
    add_patch_options(p)


def run(args) -> dict:
    from landau.models import get

    model = get(args.model)
    if model.hopf is None:
        from landau.models import offering

        raise InputError(f"landau hopf: the model {model.name!r} has no Hopf analysis (models that do: "
                         f"{', '.join(offering('hopf'))})")
    res = model.hopf(setup_from_args(model, args, "landau hopf"))
    doc = {"model": args.model}
    doc.update(res.as_dict() if hasattr(res, "as_dict") else {"result": repr(res)})
    doc["text"] = str(res)
    if doc.get("route"):
        doc["text"] += f"\nroute: {doc['route']}"
    if "k_patch" in doc:
        from landau.analyses.fault_patch import patch_text

        doc["text"] += patch_text(doc)
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
