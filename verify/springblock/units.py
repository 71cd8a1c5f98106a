"""The units of a rate-and-state law's state variables, by dimensional analysis.

A law declares units for its parameters (``Parameter.units``: ``"m"``, ``"m/s"``, ``""``…) but
not for its states φᵢ.  They follow from two requirements: μ(v, φ) is dimensionless and
dφᵢ/dt has the units of φᵢ per second.  :func:`infer_state_units` tries the usual candidates
(s, 1, m, m/s, 1/s, s/m) for each state and keeps the one under which both hold — checked
numerically: rescaling the metre and the second by random factors must leave μ unchanged and
scale each rate by [φᵢ]/s.  For the aging law of Dieterich (dφ/dt = 1 − vφ/L) that is φ in s.
"""

from __future__ import annotations

import itertools
import math
import re

import numpy as np

#: candidate units of a state: (exponent of m, exponent of s) → text
CANDIDATES = {(0, 1): "s", (0, 0): "1", (1, 0): "m", (1, -1): "m/s", (0, -1): "1/s", (-1, 1): "s/m"}

_TOKEN = re.compile(r"^(m|s|1)(?:\^|\*\*)?(-?\d+)?$")


def parse_units(text: str) -> tuple[int, int] | None:
    """Exponents (m, s) of a unit string made of m, s and 1 with ``*``, ``/`` and integer powers
    (``"m/s"`` → (1, −1), ``""`` → (0, 0)); None for anything else (e.g. ``"Pa"``)."""
    text = (text or "").replace(" ", "")
    if text in ("", "1", "-"):
        return (0, 0)
    num, _, den = text.partition("/")
    out = [0, 0]
    for part, sign in ((num, 1), (den, -1)):
        if not part:
            continue
        for tok in part.split("*") if "**" not in part else [part]:
            m = _TOKEN.match(tok)
            if m is None:
                return None
            e = int(m.group(2) or 1) * sign
            if m.group(1) == "m":
                out[0] += e
            elif m.group(1) == "s":
                out[1] += e
    return (out[0], out[1])


def infer_state_units(law) -> dict[str, str]:
    """State name → unit (``"s"``, ``"1"``, ``"m"``, …) for the states whose unit the law's
    parameter units determine; states left out when none or several candidates fit.

    Parameters
    ----------
    law : FrictionLaw

    Returns
    -------
    dict of str to str
    """
    import sympy as sp

    from landau.laws.law import v as v_slip

    dims = {}
    for prm in law.parameters:
        d = parse_units(prm.units)
        if d is None:
            return {}
        dims[prm.symbol] = (d, float(prm.default))
    ns = len(law.states)
    if ns == 0 or ns > 3:
        return {}
    syms = [v_slip, *law.states, *dims]
    try:
        mu = sp.lambdify(syms, law.mu, "math")
        rates = [sp.lambdify(syms, r, "math") for r in law.rates]
    except Exception:   # noqa: BLE001 - a law lambdify cannot print: no units, never a failure
        return {}
    rng = np.random.default_rng(12345)
    # a point near steady sliding at V = 1e-4 m/s: φ of the order of L/V where the law has an L
    L = next((val for s, (d, val) in dims.items() if d == (1, 0)), 1e-6)
    V = 1e-4
    base = [L / V * (1.7 + 0.3 * i) for i in range(ns)]   # off steady sliding: no rate is ~0
    fits = []
    for combo in itertools.product(list(CANDIDATES), repeat=ns):
        ok = True
        for _ in range(3):
            am, as_ = np.exp(rng.uniform(-2, 2, 2))
            phis = base

            def scaled(factor_m, factor_s, phis=phis, combo=combo):
                args = [V * factor_m / factor_s]
                args += [ph * factor_m ** c[0] * factor_s ** c[1] for ph, c in zip(phis, combo, strict=True)]
                args += [val * factor_m ** d[0] * factor_s ** d[1] for d, val in dims.values()]
                return args

            try:
                a0, a1 = scaled(1.0, 1.0), scaled(am, as_)
                if not math.isclose(mu(*a0), mu(*a1), rel_tol=1e-9, abs_tol=1e-12):
                    ok = False
                    break
                for r, c in zip(rates, combo, strict=True):
                    r0, r1 = r(*a0), r(*a1)
                    want = r0 * am ** c[0] * as_ ** (c[1] - 1)
                    if not math.isclose(r1, want, rel_tol=1e-9, abs_tol=1e-300):
                        ok = False
                        break
            except (ValueError, ZeroDivisionError, OverflowError, TypeError):
                ok = False
            if not ok:
                break
        if ok:
            fits.append(combo)
    if len(fits) != 1:
        return {}
    return {s.name: CANDIDATES[c] for s, c in zip(law.states, fits[0], strict=True)}
