"""Every sensitivity ∂q/∂p (q: k_c, ω_c, Γ̄, Ω̄, Λ, χ, C; p: every parameter) against a centred
finite difference on random parameter sets (fixed seed).

The difference is taken on the quantities evaluated with mpmath at 50 digits
(``Derivation.evaluate_mp``), with the relative step h = 1e-7 and the divisor the difference of
the two float64 abscissae actually used (so the step is exact): the truncation error is
h²/6 · x²q‴/q′ ≈ 1e-15 relative, the rounding 1e-50/h; for a law whose steady state is solved
numerically, the float64 steady state adds 1e-16/h = 1e-9.  All well below the 1e-6 asserted.
The compiled sensitivities are float64: an exact zero (ω_c does not depend on σ) comes out as the
rounding of the chain rule's terms, ~1e-16 of q/p, hence the absolute floor 1e-12·|q/p|.
"""

import mpmath
import numpy as np
import pytest

import landau
from landau.derivation.sensitivity import SENSITIVE, parameters
from landau.laws import FrictionLaw
from landau.systems.system import SpringBlock

H = 1e-7


def one_state(rng):
    a = rng.uniform(0.005, 0.03)
    return {"a_v": rng.uniform(0.3, 0.8), "a": a, "b": a * rng.uniform(1.1, 2.5), "L": 10 ** rng.uniform(-6, -4),
            "V_s": 10 ** rng.uniform(-7, -5), "M": rng.uniform(0.5, 5.0), "sigma": rng.uniform(5.0, 50.0)}


def two_state(rng):
    a = rng.uniform(0.005, 0.03)
    return {"a_v": rng.uniform(0.3, 0.8), "a": a, "b1": a * rng.uniform(0.8, 1.5), "b2": a * rng.uniform(0.3, 1.0),
            "L1": 10 ** rng.uniform(-6, -5), "L2": 10 ** rng.uniform(-5, -4), "V_s": 10 ** rng.uniform(-7, -5),
            "M": rng.uniform(0.5, 5.0), "sigma": rng.uniform(5.0, 50.0)}


def atan_law():
    p = {"a_v": 0.369, "a": 0.0349, "b": 0.0489, "L": 9e-7, "V_s": 1e-6, "c": 0.1}
    return FrictionLaw.from_strings("atan-state", "a_v + a*log(v/V_s) + b*log(V_s*phi/L)",
                                    {"phi": "1 - v*phi/L - c*atan(V_s*phi/L)"}, p)


def atan_state(rng):
    return {**one_state(rng), "c": rng.uniform(0.05, 0.3)}


def check_against_fd(d, p, V):
    names = [("kc" if q == "k_c" else q) for q in SENSITIVE]
    res = d.sensitivities(V, p, SENSITIVE)
    assert all(np.isfinite(np.ravel(res["value"][q])[0]) for q in SENSITIVE), "draw without a Hopf point"
    for x in parameters(d):
        x0 = V if x == "V" else p[x]
        xp, xm = float(x0 * (1 + H)), float(x0 * (1 - H))

        def at(xv, x=x):
            if x == "V":
                return d.evaluate_mp(xv, p, names, dps=50)
            return d.evaluate_mp(V, {**p, x: xv}, names, dps=50)
        up, down = at(xp), at(xm)
        with mpmath.workdps(50):
            step = mpmath.mpf(xp) - mpmath.mpf(xm)
            for q, n in zip(SENSITIVE, names, strict=True):
                fd = float((up[n] - down[n]) / step)
                got = float(np.ravel(res[q][x])[0])
                scale = abs(float(np.ravel(res["value"][q])[0]) / x0)
                assert abs(got - fd) <= 1e-6 * abs(fd) + 1e-12 * scale, (q, x, got, fd)


def draws(law_draw, n, seed):
    rng = np.random.default_rng(seed)
    return [(law_draw(rng), 10 ** rng.uniform(-6, -3)) for _ in range(n)]


@pytest.mark.parametrize("law", ["dieterich", "ruina"])
def test_every_sensitivity_against_finite_differences_one_state(law):
    d = landau.derive(law)
    for p, V in draws(one_state, 3, 20261202):
        check_against_fd(d, p, V)


def test_every_sensitivity_against_finite_differences_numeric_hopf_line():
    # two state variables: k_c and ω_c are roots of the Hopf polynomial (implicit differentiation)
    d = landau.derive("two-state-dieterich")
    for p, V in draws(two_state, 1, 7):
        check_against_fd(d, p, V)


def test_every_sensitivity_against_finite_differences_numeric_steady_state():
    # dφ/dt = 1 − vφ/L − c·atan(V_sφ/L): φ₀ has no closed form (implicit function theorem)
    d = landau.derive(SpringBlock(atan_law()))
    for p, V in draws(atan_state, 2, 11):
        check_against_fd(d, p, V)


def test_float64_vectorised_route_against_the_50_digit_route():
    # the float64 programs over arrays of parameters (one draw per element), against the 50-digit
    # route: 1e-6 relative or 1e-8 of |q/p| (a near-cancelling sensitivity keeps its absolute accuracy)
    d = landau.derive("dieterich")
    sets = draws(one_state, 4, 99)
    arrays = {k: np.array([p[k] for p, _ in sets]) for k in sets[0][0]}
    Vs = np.array([V for _, V in sets])
    fast = d.sensitivities(Vs, arrays, SENSITIVE, method="float64")
    for i, (p, V) in enumerate(sets):
        slow = d.sensitivities(V, p, SENSITIVE, method="mpmath")
        for q in SENSITIVE:
            for x in parameters(d):
                scale = abs(float(slow["value"][q]) / (V if x == "V" else p[x]))
                want = float(slow[q][x])
                assert abs(fast[q][x][i] - want) <= 1e-6 * abs(want) + 1e-8 * scale, (q, x)
