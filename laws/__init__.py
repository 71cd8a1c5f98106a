"""Friction laws declared symbolically (μ(v, φ…), dφ/dt), with defaults and provenance.

Built-in laws (CLI names): ``dieterich``, ``ruina``, ``spinodal``,
``modified-dieterich``, ``nanoscale``, ``micron-scale`` (Putelat et al. 2010) and
``two-state-dieterich``.  A new law: :meth:`FrictionLaw.from_strings` or the
:class:`FrictionLaw` constructor.  A law modifier makes a new law from a law: flash heating,
:func:`flash_heating` (Rice 2006), named on the command line as a suffix, ``dieterich+flash``.

Velocity-only friction (:class:`VelocityFriction`, on the same :class:`Law` base): the plain
Coulomb law of the frictional impact oscillator of Lancioni, Lenci & Galvanetto
(:func:`coulomb`), the regularised Coulomb resistance of Skurativskyi et al. (2019)
(:func:`regularised_coulomb`), or your own (:meth:`VelocityFriction.from_strings`).
"""

from __future__ import annotations

from typing import Callable

from landau.errors import InputError
from landau.laws import putelat2010 as _p
from landau.laws.base import Law
from landau.laws.law import TABLE1, FrictionLaw, Parameter, v
from landau.laws.velocity import BUILTIN_VELOCITY, VelocityFriction, coulomb, regularised_coulomb

BUILTIN: dict[str, Callable[[], FrictionLaw]] = {
    "dieterich": _p.dieterich,
    "ruina": _p.ruina,
    "spinodal": _p.spinodal,
    "modified-dieterich": _p.modified_dieterich,
    "nanoscale": _p.nanoscale,
    "micron-scale": _p.micron_scale,
    "two-state-dieterich": _p.two_state_dieterich,
}


def get_law(name: str) -> FrictionLaw:
    """A built-in law by its CLI name.

    Parameters
    ----------
    name : str
        One of :data:`BUILTIN` (``landau laws`` lists them), e.g. ``"dieterich"``, ``"ruina"``, possibly
        with modifiers as suffixes (``"dieterich+flash"``, :mod:`landau.laws.flash`).

    Returns
    -------
    FrictionLaw
        The law, with its parameters' published defaults.

    Raises
    ------
    InputError
        An unknown name (with a "did you mean" suggestion) or modifier.

    References
    ----------
    Putelat, T., Dawes, J. H. P. & Willis, J. R. (2010), "Regimes of frictional sliding of a
    spring–block system", J. Mech. Phys. Solids 58(1), 27–53, Table 1 (the laws, parameters).
    """
    if isinstance(name, str) and "+" in name and name.split("+", 1)[0] in BUILTIN:
        from landau.laws.flash import apply_modifiers, split_name

        base, mods = split_name(name)
        return apply_modifiers(BUILTIN[base](), mods)
    if not isinstance(name, str) or name not in BUILTIN:
        import difflib

        close = difflib.get_close_matches(str(name), list(BUILTIN), n=1, cutoff=0.6)
        hint = f" (did you mean {close[0]!r}?)" if close else ""
        raise InputError(f"unknown law {name!r}{hint}; built-in: {', '.join(BUILTIN)}")
    return BUILTIN[name]()


def is_law_name(name: object) -> bool:
    """Whether ``name`` names a built-in law, possibly with known modifiers (``"dieterich+flash"``).

    Parameters
    ----------
    name : object
        A candidate name.

    Returns
    -------
    bool
        True for a name of :data:`BUILTIN` followed by ``+`` suffixes of known modifiers.
    """
    if not isinstance(name, str):
        return False
    from landau.laws.flash import MODIFIERS, split_name

    base, mods = split_name(name)
    return base in BUILTIN and all(m in MODIFIERS for m in mods)


def flash_heating(law: FrictionLaw | str, **kw) -> FrictionLaw:
    """``law`` with flash heating above the weakening slip rate V_w (Rice 2006; Beeler, Tullis & Goldsby 2008).

    Parameters
    ----------
    law : FrictionLaw or str
        A rate-and-state law or a built-in law's name.
    **kw
        ``f_w``, ``V_w``, ``state`` of :func:`landau.laws.flash.flash_heating`.

    Returns
    -------
    FrictionLaw
        The law ``<name>+flash`` (its steady-state friction f_w + (f_LV − f_w) V_w/(V + V_w)).
    """
    from landau.laws.flash import flash_heating as _fh

    return _fh(get_law(law) if isinstance(law, str) else law, **kw)


__all__ = ["is_law_name", "flash_heating",
           "FrictionLaw", "Parameter", "TABLE1", "BUILTIN", "get_law", "v", "Law", "VelocityFriction", "coulomb",
           "regularised_coulomb", "BUILTIN_VELOCITY"]
