"""Friction laws declared symbolically (μ(v, φ…), dφ/dt), with defaults and provenance.

Built-in laws (CLI names): ``dieterich``, ``ruina``, ``spinodal``,
``modified-dieterich``, ``nanoscale``, ``micron-scale`` (Putelat et al. 2010) and
``two-state-dieterich``.  A new law: :meth:`FrictionLaw.from_strings` or the
:class:`FrictionLaw` constructor.

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
        One of :data:`BUILTIN` (``landau laws`` lists them), e.g. ``"dieterich"``, ``"ruina"``.

    Returns
    -------
    FrictionLaw
        The law, with its parameters' published defaults.

    Raises
    ------
    InputError
        An unknown name (with a "did you mean" suggestion).

    References
    ----------
    Putelat, T., Dawes, J. H. P. & Willis, J. R. (2010), "Regimes of frictional sliding of a
    spring–block system", J. Mech. Phys. Solids 58(1), 27–53, Table 1 (the laws, parameters).
    """
    if not isinstance(name, str) or name not in BUILTIN:
        import difflib

        close = difflib.get_close_matches(str(name), list(BUILTIN), n=1, cutoff=0.6)
        hint = f" (did you mean {close[0]!r}?)" if close else ""
        raise InputError(f"unknown law {name!r}{hint}; built-in: {', '.join(BUILTIN)}")
    return BUILTIN[name]()


__all__ = ["FrictionLaw", "Parameter", "TABLE1", "BUILTIN", "get_law", "v", "Law", "VelocityFriction", "coulomb",
           "regularised_coulomb", "BUILTIN_VELOCITY"]
