"""Sliding bifurcations and the Hopf / non-smooth fold points of the one-block model, Galvanetto
(2004) Sec. 4.1–4.2: type I/II sliding in V (:func:`one_block_sliding`), the Hopf point c₁ of the
damped slip field (:func:`hopf_c1`, :func:`hopf_c1_normal_form`) and the non-smooth fold c₂ where
its unstable cycle touches the stick line (:func:`nonsmooth_fold_c2`).
"""

from __future__ import annotations

import numpy as np

from landau.errors import InputError
from landau.laws.kinetic import KineticFriction, resolve_kinetic_law
from landau.verify.galvanetto.maps import MapUndefined, default_stepper, one_block_cycle
from landau.verify.galvanetto.model import _make_rhs, one_block
from landau.verify.galvanetto.periodic import _locate, _margins, _velocity_scale, scan_bracket
from landau.verify.hybrid import Status
from landau.verify.hybrid.analysis import Located

# ----------------------------------------------------------------- one block (Sec. 4.1, 4.2)

def one_block_sliding(kind: str, gamma: float | None = None, delta: float | None = None, c: float = 0.0,
                      bracket: tuple[float, float] | None = None, stepper=None, *,
                      law: KineticFriction | None = None) -> Located:
    """Type II (``kind="II"``) or type I (``"I"``) sliding point of the one block, in V.

    The cycle starts at the end of the stick interval (X = F_s − cV, Ẋ = V).  Type II:
    the first return to r = 0 (from r < 0) happens at K = X + cV = −F_s.  Type I: the
    return from r > 0 happens at K = +F_s.  Paper (δ misprinted as 0; δ = 0.2 reproduces them):
    1.241, 10.801.

    Parameters
    ----------
    kind : "II" or "I".
    gamma, delta : parameters of the default law, eq. (7) (defaults γ = 3, δ = 0.2).
    c : viscous damping.
    bracket : search interval in V; default derived from the law: the test function is
        scanned on a logarithmic grid of V from 0.01 to 10⁴ times the law's weakening velocity
        (:meth:`KineticFriction.weakening_velocity`, 1/γ for eq. (7)) — type I from the type II
        point upward, as the r > 0 slip phase is born there.
    stepper : mode integrator (default DOP853, rtol 1e-11).
    law : the kinetic law (default eq. (7) with ``gamma``, ``delta``).

    Returns
    -------
    Located

    References
    ----------
    U. Galvanetto, J. Sound Vib. 276 (2004) 121–139, Sec. 4.1, Fig. 7.
    """
    if kind not in ("II", "I"):
        raise InputError(f"one_block_sliding: kind must be 'II' or 'I', not {kind!r}")
    law = resolve_kinetic_law(law, gamma, delta, default_delta=0.2)
    side = "n" if kind == "II" else "p"

    def H(V):
        p = one_block(V, c=c, law=law)
        sol = one_block_cycle(p, stepper, stop=lambda ev: ev.guard == "r1=0" and ev.from_mode == side)
        if sol.status is not Status.STOPPED:
            return 1.0  # never reaches r = 0 from that side: still before the bifurcation
        return _margins(p, sol.events, side)[-1]

    if bracket is None:
        vs = _velocity_scale(law)
        start = 0.01 * vs if kind == "II" else one_block_sliding("II", c=c, stepper=stepper, law=law).value
        grid = start * 10.0 ** (np.arange(0, 1 + 8 * np.log10(1e4 * vs / start)) / 8)
        bracket = scan_bracket(H, grid, f"one-block type {kind} sliding")
    V, res, n, sec = _locate(H, bracket)
    return Located(f"one-block-type-{kind}", "V", V, res, n, sec,
                   {"gamma": law.gamma, "delta": law.delta, "c": c, "bracket": tuple(map(float, bracket))})


# ----------------------------------------------------------------- damped one block (Sec. 4.2)

def hopf_c1(V: float = 0.5, gamma: float | None = None, delta: float | None = None, law=None) -> float:
    """c₁ = F_k'(−V): the linearised slip field u'' + (c − F_k'(−V))u' + u = 0 about the
    equilibrium X = F_k(−V) loses its damping.  ``law`` is the kinetic law (default Galvanetto's
    eq. (7) with ``gamma`` = 3, ``delta`` = 0, where c₁ = γ(1 − δ)/(1 + γV)²); the slope is that
    of its r < 0 branch, differentiated symbolically."""
    from landau.verify.galvanetto.smooth import kinetic_law
    return float(kinetic_law(gamma, delta, law).dneg(-V))


def hopf_c1_normal_form(V: float = 0.5, gamma: float | None = None, delta: float | None = None, law=None):
    """The damped one block's Hopf point c₁ located by the landau engine (:mod:`landau.derivation.general`) on
    the smooth slip field of the kinetic law ``law`` (default eq. (7) with ``gamma``, ``delta``),
    with its amplitude equation: Λ > 0 means subcritical (an unstable cycle for c > c₁ whose
    displacement amplitude is C·sqrt(c − c₁))."""
    from landau.derivation.general import hopf_normal_form
    from landau.verify.galvanetto.smooth import damped_slip_system, kinetic_law

    law = kinetic_law(gamma, delta, law)
    c1 = hopf_c1(V, law=law)
    return hopf_normal_form(damped_slip_system(V, law=law), {"V": V, "gamma": law.gamma, "delta": law.delta},
                            (0.5 * c1, 1.5 * c1))


def nonsmooth_fold_c2(V: float = 0.5, gamma: float | None = None, delta: float | None = None,
                      bracket: tuple[float, float] | None = None, stepper=None, *,
                      law: KineticFriction | None = None) -> Located:
    """c₂: the unstable cycle of the smooth slip field touches the stick line Ẋ = V at the
    stick end X = F_s − cV (Fig. 10c), where stick–slip and slip–stick transitions merge.

    The unstable cycle attracts in *backward* time, so from the stick end (X = F_s − cV,
    Ẋ = V, a velocity maximum of the slip field) the r < 0 slip field is integrated backward
    to its previous velocity maximum: H(c) = r there.  c < c₂: the point lies outside the
    cycle, the backward orbit shrinks onto it, H < 0; c > c₂: inside, H > 0.  H is smooth
    and bounded (the backward orbit never leaves the cycle's neighbourhood).

    Parameters
    ----------
    V : belt velocity.
    gamma, delta : parameters of the default law, eq. (7) (defaults γ = 3, δ = 0).
    bracket : search interval in c; default derived from the Hopf point c₁ = F_k'(−V) (the
        unstable cycle is born there): H is scanned on a logarithmic grid of c − c₁ from
        10⁻⁴ c₁ to 10² c₁.
    stepper : mode integrator (default DOP853, rtol 1e-11).
    law : the kinetic law (default eq. (7) with ``gamma``, ``delta``).

    Returns
    -------
    Located

    Raises
    ------
    NoHopfError
        c₁ ≤ 0: the law does not weaken at r = −V, steady sliding has no Hopf point.

    References
    ----------
    U. Galvanetto, J. Sound Vib. 276 (2004) 121–139, Sec. 4.2, Fig. 10.
    """
    from landau.errors import NoHopfError
    from landau.verify.hybrid import Guard, HybridModel, Mode, simulate
    from landau.verify.hybrid.simulate import EngineOptions
    law = resolve_kinetic_law(law, gamma, delta)
    c1 = hopf_c1(V, law=law)
    if not c1 > 0:
        raise NoHopfError(f"F_k'(-V) = {c1:.6g} <= 0 at V = {V:g}: no Hopf point c1 > 0 for {law!r}")
    st = stepper or default_stepper()

    def H(c):
        slip = _make_rhs(one_block(V, c=c, law=law), "n")   # the r < 0 slip field of the model
        back = lambda t, y: -slip(t, y)
        model = HybridModel.from_modes(Mode("slip-back", back, (Guard("vmax", lambda t, y: -slip(t, y)[1]),)))
        sol = simulate(model, "slip-back", [1.0 - c * V, V], (0.0, 100.0), st, EngineOptions(record=False),
                       stop=lambda ev: ev.guard == "vmax")
        if sol.status is not Status.STOPPED:
            raise MapUndefined("no velocity maximum in backward time")
        return float(sol.y_final[1] - V)

    if bracket is None:
        bracket = scan_bracket(H, c1 * (1.0 + 10.0 ** (np.arange(-16, 9) / 4)), "non-smooth fold c2")
    c, res, n, sec = _locate(H, bracket)
    return Located("one-block-c2", "c", c, res, n, sec, {"c1": c1, "bracket": tuple(map(float, bracket))})
