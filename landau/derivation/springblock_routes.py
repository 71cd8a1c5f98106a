"""The Hopf point of a spring–block with the Linker–Dieterich state response, by the general engine.

With ``alpha_ld`` the stiffness k enters the state rate as well as the force (dσ/dt = −γ_LD k u).
The symbolic multiple-scales route (:mod:`landau.derivation.multiscale`, ``landau derive``) takes it
(:class:`~landau.derivation.parameter_jets.ParameterJets`); ``landau hopf spring-block``,
``predict`` and ``landau verify`` locate the point here instead, with the general Fredholm engine
(:func:`landau.derivation.general.hopf_normal_form`: numeric jets, its own root finder) on the same
:class:`~landau.systems.system.DynamicalSystem`, bracketed around the k_c of the same block without
``alpha_ld`` (closed form) — a route independent of the symbolic one, against which the tests check
it.  Both give the spring–block convention: the critical mode normalised with slip component X = 1,
dλ/dk = −Γ̄ + iΩ̄.

References
----------
Putelat, T., Dawes, J. H. P. & Willis, J. R. (2010), J. Mech. Phys. Solids 58(1), 27–53, eq. (20).
Linker, M. F. & Dieterich, J. H. (1992), J. Geophys. Res. 97(B4), 4923–4940.
"""

from __future__ import annotations

from typing import Mapping

import numpy as np

from landau.errors import NoHopfError

#: the general route's bracket: k_c(α_LD = 0) divided and multiplied by this factor
BRACKET_FACTOR = 20.0


def hopf_point(block, V: float, params: Mapping[str, float]):
    """The Hopf point of ``block`` (with ``alpha_ld``) at driving velocity V by the general engine.

    Parameters
    ----------
    block : SpringBlock
        With the term ``alpha_ld``.
    V : float
        Driving velocity, m/s.
    params : mapping
        Resolved parameters (:meth:`SpringBlock.resolve`).

    Returns
    -------
    HopfResult
        In the spring–block convention (:func:`landau.derivation.hopf.spring_block_result`).

    Raises
    ------
    NoHopfError
        No Hopf point within a factor :data:`BRACKET_FACTOR` of k_c(α_LD = 0).
    """
    from landau.derivation.general import hopf_normal_form
    from landau.derivation.hopf import spring_block_result
    from landau.derivation.linear import HopfLine
    from landau.systems.springblock_terms import TERMS
    from landau.systems.system import SpringBlock

    # the start: the Hopf line without the terms that put k in the state rates
    rate_terms = {t for t in block.terms if TERMS[t].stiffness_in_rates}
    plain = SpringBlock(block.law, tuple(t for t in block.terms if t not in rate_terms))
    guess = float(np.ravel(HopfLine(plain).evaluate(np.array([float(V)]),
                                                    {k: v for k, v in params.items() if k not in rate_terms})[0])[0])
    if not (np.isfinite(guess) and guess > 0):
        guess = None
    block.argvals(float(V), params)                     # the law's and the terms' checks at steady sliding
    values = {k: v for k, v in params.items() if k in {s.name for s in block.system.parameters}}
    values["V"] = float(V)
    if guess is None:
        raise NoHopfError(f"law {block.law.name!r} with {', '.join(block.terms)}: no Hopf point located at "
                          f"V = {V:g} m/s (none without {', '.join(sorted(rate_terms))} to start from)")
    res = hopf_normal_form(block.system, values, (guess / BRACKET_FACTOR, guess * BRACKET_FACTOR))
    a = res.dlambda_dp
    out = spring_block_result(block.law.name, float(V), res.p_c, res.omega_c, -a.real, a.imag, res.Lambda,
                              res.chi, params={k: float(v) for k, v in params.items()}, l1=res.l1, c1=res.c1)
    return block.name_terms(out)
