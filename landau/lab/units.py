"""Unit-aware values of the laboratory: ``"1um/s"``, ``"1e-3/um"``, ``"10um"``, ``"100s"``; SI inside.

Friction laboratories report velocities in µm/s, displacements and memory lengths in µm and the
machine stiffness per unit normal stress, k′ = k/σ, in 1/µm (Marone 1998; rsfmodel and PyRSF
take their inputs in these units).  A value here is a number followed, with or without a space,
by a unit built from one length or time unit over another:

* length: ``m``, ``mm``, ``um`` (also ``µm``, ``μm``), ``nm``;
* time: ``s``, ``ms``, ``us``, ``min``, ``h``;
* velocity: a length over a time (``um/s``, ``mm/s``, ``m/s``, ``nm/s``, ``um/min``…);
* stiffness per unit normal stress: ``1/`` or ``/`` and a length (``1/um``, ``/um``, ``1/m``);
* stiffness: a force over a length (``N/m``, ``kN/m``, ``MN/m``, ``N/um``).

:func:`parse_value` returns the value in SI (m, s, m/s, 1/m, N/m) after checking that its unit
has the kind asked for; a bare number is in the ``default`` unit given (the preset's,
:mod:`landau.lab.preset`).  Every malformed or mismatched value is an
:class:`~landau.errors.InputError` naming the value, the option and what was expected.
:func:`to_unit` converts back from SI for output.

References
----------
Marone, C. (1998), Laboratory-derived friction laws and their application to seismic faulting,
Annu. Rev. Earth Planet. Sci. 26, 643–696.
"""

from __future__ import annotations

import math
import re
from fractions import Fraction

from landau.errors import InputError

#: lengths in metres (exact fractions: 10um is 1e-05 m to the last bit, 10/10**6 correctly rounded)
LENGTHS = {"m": Fraction(1), "mm": Fraction(1, 10**3), "um": Fraction(1, 10**6), "µm": Fraction(1, 10**6),
           "μm": Fraction(1, 10**6), "nm": Fraction(1, 10**9)}
#: times in seconds
TIMES = {"s": Fraction(1), "ms": Fraction(1, 10**3), "us": Fraction(1, 10**6), "min": Fraction(60),
         "h": Fraction(3600)}
#: forces in newtons
FORCES = {"N": Fraction(1), "kN": Fraction(10**3), "MN": Fraction(10**6)}

#: the kinds of value, their SI unit and examples of their units (for the error messages)
KINDS = {
    "length": ("m", "um, mm, m"),
    "time": ("s", "s, ms, min, h"),
    "velocity": ("m/s", "um/s, mm/s, m/s"),
    "inverse length": ("1/m", "1/um, 1/mm, 1/m"),
    "stiffness": ("N/m", "N/m, kN/m, N/um"),
    "number": ("1", "no unit"),
}

_NUMBER = re.compile(r"^\s*([+-]?(?:\d+\.?\d*|\.\d+)(?:[eE][+-]?\d+)?)\s*(.*?)\s*$")


def unit_kind(unit: str) -> tuple[str, Fraction]:
    """(kind, factor to SI) of a unit string (``"um/s"`` → ("velocity", 1e-6)).

    Raises
    ------
    InputError
        An unknown unit (the message lists the known ones).
    """
    u = unit.strip().replace(" ", "")
    if u in ("", "1"):
        return "number", Fraction(1)
    if u in LENGTHS:
        return "length", LENGTHS[u]
    if u in TIMES:
        return "time", TIMES[u]
    num, sep, den = u.partition("/")
    if sep and "/" not in den:
        if num in ("", "1") and den in LENGTHS:
            return "inverse length", 1 / LENGTHS[den]
        if num in LENGTHS and den in TIMES:
            return "velocity", LENGTHS[num] / TIMES[den]
        if num in FORCES and den in LENGTHS:
            return "stiffness", FORCES[num] / LENGTHS[den]
    raise InputError(f"unknown unit {unit!r} (lengths {', '.join(LENGTHS)}; times {', '.join(TIMES)}; velocities "
                     "as length/time, e.g. um/s; stiffness per unit normal stress as 1/length, e.g. 1/um; "
                     "stiffness as N/m)")


def split_value(text: str, what: str) -> tuple[float, str]:
    """(number, unit text) of ``"10um/s"``; InputError naming ``what`` when it is not a number and a unit."""
    if not isinstance(text, str):
        text = repr(text) if isinstance(text, (int, float)) else str(text)
    m = _NUMBER.match(text)
    if m is None:
        raise InputError(f"{what}: {text.strip()!r} is not a number with an optional unit (e.g. '10um/s')")
    x = float(m.group(1))
    if not math.isfinite(x):
        raise InputError(f"{what}: {text.strip()!r} is not finite")
    return x, m.group(2)


def parse_value(text: str | float, kind: str | tuple[str, ...], what: str, default: str = "") -> tuple[float, str]:
    """The SI value and the kind of ``text`` (``"1e-3/um"`` → (1000.0, "inverse length")).

    Parameters
    ----------
    text : str or float
        A number with an optional unit; a float is a bare number.
    kind : str or tuple of str
        The kind(s) of :data:`KINDS` accepted.
    what : str
        The option or field, for the error messages (``"--k"``).
    default : str
        The unit of a bare number (``""``: SI of the first kind).

    Raises
    ------
    InputError
        Not a number, an unknown unit, or a unit of another kind (the message names the value,
        ``what`` and the units expected).
    """
    kinds = (kind,) if isinstance(kind, str) else tuple(kind)
    x, unit = (float(text), "") if isinstance(text, (int, float)) and not isinstance(text, bool) else \
        split_value(str(text), what)
    if not math.isfinite(x):
        raise InputError(f"{what}: {text!r} is not finite")
    if not unit:
        if not default:
            return x, kinds[0]
        unit = default
    try:
        got, factor = unit_kind(unit)
    except InputError as exc:
        raise InputError(f"{what}: {str(text).strip()!r}: {exc}") from None
    if got not in kinds:
        want = " or ".join(f"{_article(k)} {k} ({KINDS[k][1]})" for k in kinds)
        raise InputError(f"{what}: {str(text).strip()!r} is {_article(got)} {got}, expected {want}")
    return _scaled(x, factor), got


def _article(word: str) -> str:
    return "an" if word[0] in "aeiou" else "a"


def _scaled(x: float, factor: Fraction) -> float:
    """x·factor correctly rounded where factor is 1/10ⁿ or 10ⁿ (one rounding: x·p/q)."""
    return x * factor.numerator / factor.denominator


def to_unit(value, unit: str):
    """An SI value (or array) in ``unit`` (``to_unit(1e-6, "um/s")`` → 1.0)."""
    f = unit_kind(unit)[1]
    return value * f.denominator / f.numerator


__all__ = ["FORCES", "KINDS", "LENGTHS", "TIMES", "parse_value", "split_value", "to_unit", "unit_kind"]
