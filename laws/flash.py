"""Flash heating as a law modifier: a new rate-and-state law from any law of the library.

Flash heating of the asperity contacts (Rice 2006; Beeler, Tullis & Goldsby 2008) weakens
friction above a weakening slip rate V_w: the steady-state friction falls from the low-speed
law's value f_LV(V) towards a weakened value f_w, as

    f_ss(V) = f_w + (f_LV(V) − f_w) V_w / V                        (V > V_w; Rice 2006)

and is f_LV(V) below V_w.  :func:`flash_heating` uses the smooth form that joins the two
branches (it tends to Rice's high-speed form for V ≫ V_w and to f_LV for V ≪ V_w, without the
kink at V = V_w that no derivative of the amplitude equation survives):

    f_ss(V) = f_w + (f_LV(V) − f_w) V_w / (V + V_w).               (1)

**Where the weakening enters.**  Flash heating depends on the lifetime of a contact, D/V at
steady sliding (Rice 2006; Beeler et al. 2008), which is what the state variable measures: the
weakening is written as a function of the *state* and not of the slip rate, so the direct
effect ∂μ/∂ln v at fixed state (a) is unchanged and only the evolution to the new steady state
carries the weakening.  With v_φ(φ) the slip rate at which the chosen state φ is steady
(the inverse of φ_ss(v); v_φ = L/φ for the Dieterich and Ruina laws), the modified law is

    μ_fh(v, φ) = μ(v, φ) − (μ_ss(v_φ) − f_w) · v_φ / (v_φ + V_w),  (2)

with the state rates unchanged.  At steady sliding v_φ = v and (2) is (1); for v_φ ≪ V_w the
law is the original one.  Parameters: ``f_w`` (the weakened friction coefficient, 1) and
``V_w`` (the weakening slip rate, m/s).  Defaults f_w = 0.1, V_w = 0.1 m/s, the orders of
magnitude Rice (2006) gives for rocks (V_w ~ 0.1 m/s, f_w ~ 0.1–0.2).

The modified law is an ordinary :class:`~landau.laws.FrictionLaw` (data: sympy expressions), so
``derive``, its LaTeX, ``landau hopf``, ``landau.check``, ``landau simulate`` and ``landau sweep``
take it without any other change.  On the command line a modifier is a suffix of the law's
name: ``dieterich+flash`` (:func:`apply_modifiers`).

Validity: the law must have a closed-form steady state whose chosen state is invertible in v
with a positive inverse (every built-in law but the spinodal one, whose state is bounded by 1
and gives no slip rate above its bound); for a law of several states the first state carries
the weakening unless ``state=`` names another.

References
----------
Rice, J. R. (2006), Heating and weakening of faults during earthquake slip, J. Geophys. Res.
111, B05311.
Beeler, N. M., Tullis, T. E. & Goldsby, D. L. (2008), Constitutive relationships and physical
basis of fault strength due to flash heating, J. Geophys. Res. 113, B01401.
"""

from __future__ import annotations

import sympy as sp

from landau.errors import InputError
from landau.laws.law import FrictionLaw, Parameter, v

#: the suffix that names the modifier on the command line (``dieterich+flash``)
SUFFIX = "flash"
#: the modifier's parameters, with their defaults and sources
F_W = Parameter("f_w", 0.1, "", "Rice 2006, Sec. 3 (f_w ~ 0.1-0.2 for rocks)", "weakened friction coefficient f_w")
V_W = Parameter("V_w", 0.1, "m/s", "Rice 2006, Sec. 3 (V_w ~ 0.1 m/s for rocks)", "flash-weakening slip rate V_w")


def _state_slip_rate(law: FrictionLaw, state: sp.Symbol, phi_ss: sp.Expr) -> sp.Expr:
    """v_φ: the positive slip rate at which ``state`` has the value φ at steady state (the
    inverse of φ_ss(v)); an InputError naming the law when there is no unique positive one."""
    try:
        sols = sp.solve(sp.Eq(state, phi_ss), v, dict=False)
    except (NotImplementedError, ValueError, TypeError):
        sols = []
    good = [sp.simplify(s) for s in sols if sp.simplify(s).is_positive]
    if len(good) != 1:
        raise InputError(f"flash heating: the steady state {state} = {phi_ss} of law {law.name!r} has no unique "
                         "positive inverse in the slip rate v (needed to write the weakening as a function of the "
                         "state); the modifier takes laws whose state is a contact lifetime (dieterich, ruina, ...)")
    return good[0]


def flash_heating(law: FrictionLaw, *, f_w: float | None = None, V_w: float | None = None,
                  state: str | None = None) -> FrictionLaw:
    """The law ``law`` with flash weakening above ``V_w``, eq. (2) of the module docstring.

    Parameters
    ----------
    law : FrictionLaw
        Any rate-and-state law with a closed-form steady state.
    f_w : float, optional
        The weakened friction coefficient (default :data:`F_W`, 0.1).
    V_w : float, optional
        The weakening slip rate in m/s (default :data:`V_W`, 0.1 m/s).
    state : str, optional
        The state that carries the weakening (default the first).

    Returns
    -------
    FrictionLaw
        Named ``<law>+flash``, with the parameters of ``law`` and ``f_w``, ``V_w``; its steady
        states are those of ``law``, its steady-state friction eq. (1).

    Raises
    ------
    InputError
        Not a rate-and-state law, a law that already has ``f_w`` or ``V_w``, no closed-form
        steady state, a state that is not invertible, or a bad ``f_w``/``V_w``.
    """
    if not isinstance(law, FrictionLaw):
        raise InputError(f"flash heating modifies a rate-and-state law (a FrictionLaw), got {type(law).__name__}")
    names = {p.name for p in law.parameters}
    for p in (F_W, V_W):
        if p.name in names:
            raise InputError(f"flash heating: law {law.name!r} already has a parameter {p.name!r}")
    ss = law.steady_state_closed_form
    if ss is None:
        raise InputError(f"flash heating: law {law.name!r} has no closed-form steady state (eq. (2) needs mu_ss)")
    idx = 0
    if state is not None:
        idx = next((i for i, s in enumerate(law.states) if s.name == state), -1)
        if idx < 0:
            raise InputError(f"flash heating: law {law.name!r} has no state {state!r} "
                             f"(states: {', '.join(s.name for s in law.states)})")
    phi = law.states[idx]
    v_phi = _state_slip_rate(law, phi, ss[idx])
    mu_ss = law.mu.subs(dict(zip(law.states, ss, strict=True)))
    fw, Vw = F_W.symbol, V_W.symbol
    # eq. (2): the weakening evaluated at the state's own slip rate v_phi (the contact lifetime)
    weakening = (mu_ss.subs(v, v_phi) - fw) * v_phi / (v_phi + Vw)
    params = [*law.parameters,
              F_W if f_w is None else Parameter("f_w", _positive(f_w, "f_w"), "", "user", F_W.description),
              V_W if V_w is None else Parameter("V_w", _positive(V_w, "V_w"), "m/s", "user", V_W.description)]
    return FrictionLaw(
        f"{law.name}+{SUFFIX}", law.mu - weakening, law.states, law.rates, tuple(params),
        source=f"{law.source}; flash heating after Rice 2006 and Beeler, Tullis & Goldsby 2008",
        description=f"{law.description or law.name} with flash heating above V_w", steady_state=tuple(ss),
    )


def _positive(x, name: str) -> float:
    try:
        val = float(x)
    except (TypeError, ValueError):
        raise InputError(f"flash heating: {name} must be a number, got {x!r}") from None
    if not val > 0 or val == float("inf"):
        raise InputError(f"flash heating: {name} must be finite and > 0, got {x!r}")
    return val


#: the modifiers by their command-line suffix
MODIFIERS = {SUFFIX: flash_heating}


def split_name(name: str) -> tuple[str, list[str]]:
    """``"dieterich+flash"`` as the base name and the modifiers' suffixes, ``("dieterich", ["flash"])``."""
    base, *mods = str(name).split("+")
    return base, mods


def apply_modifiers(law: FrictionLaw, suffixes: list[str]) -> FrictionLaw:
    """``law`` with the modifiers named by ``suffixes`` applied in order; an unknown suffix is an InputError."""
    for m in suffixes:
        if m not in MODIFIERS:
            raise InputError(f"unknown law modifier {m!r} in {law.name}+{m} (modifiers: "
                             f"{', '.join('+' + k for k in MODIFIERS)})")
        law = MODIFIERS[m](law)
    return law
