"""Double-double arithmetic compiled with numba: a value is an unevaluated sum hi + lo of two
float64 numbers with |lo| ≤ ulp(hi)/2, about 32 significant digits (unit round-off 2⁻¹⁰⁶).

Built on the error-free transformations TwoSum (Knuth 1969), FastTwoSum (Dekker 1971) and
TwoProd by Veltkamp–Dekker splitting (Dekker 1971; no fused multiply–add needed), with the
accurate double-double sum and product analysed by Joldes, Muller & Popescu (2017),
"Tight and rigorous error bounds for basic building blocks of double-word arithmetic",
ACM TOMS 44(2), 15: relative error ≤ 3u² (sum, Algorithm 6) and ≤ 7u² (product,
Algorithm 12), u = 2⁻⁵³.  Division and square root follow Hida, Li & Bailey's QD library
(2001, "Algorithms for quad-double precision floating point arithmetic"); exp by argument
reduction k·ln 2 + r, r/2⁹, a Taylor series of expm1 and nine squarings of 1 + expm1;
log by one Newton step on exp from the float64 logarithm (the step squares the float64 error).

Every function takes and returns the parts (hi, lo) as separate floats (numba passes them in
registers); the interpreter :func:`landau.codegen.bounded.run_dd` calls them.  The error of each function,
relative to its result, is below the units of :data:`UNITS` (arithmetic), :data:`UNIT_FUNC`
(exp, log, pow, asinh: about 2⁻¹⁰⁰ measured against 50-digit mpmath, allowed 2⁻⁹⁶).
The compilation must keep IEEE semantics: never ``fastmath`` (it would re-associate the
error-free transformations away).
"""

from __future__ import annotations

import math
from fractions import Fraction

import numba as nb

#: relative error of the double-double sum and product, ≥ the proven 3u², 7u² (u = 2⁻⁵³)
UNIT = 2.0 ** -103
#: relative error of division and square root (Hida, Li & Bailey's algorithms; measured ≤ 4u²)
UNIT_DIV = 2.0 ** -102
#: relative error (of the result, or absolute where the result is near 0: see the generator) of
#: exp, log, the power x^y and asinh as implemented here
UNIT_FUNC = 2.0 ** -96

_SPLIT = 134217729.0            # 2^27 + 1 (Veltkamp)
_jit = nb.njit(cache=True, error_model="numpy", nogil=True)


def dd_const(x) -> tuple[float, float]:
    """The double-double nearest (to 2⁻¹⁰⁶ relative) a rational (``Fraction``, int) or an mpmath number."""
    if isinstance(x, (int, Fraction)):
        fx = Fraction(x)
        hi = float(fx)
        return hi, float(fx - Fraction(hi))
    import mpmath

    with mpmath.workdps(40):
        hi = float(x)
        return hi, float(x - mpmath.mpf(hi))


LN2_HI, LN2_LO = 0.6931471805599453, 2.3190468138462996e-17
_INV_FACT = tuple(dd_const(Fraction(1, math.factorial(n))) for n in range(2, 10))
_IF_HI = tuple(c[0] for c in _INV_FACT)
_IF_LO = tuple(c[1] for c in _INV_FACT)
#: asinh x = Σ (−1)ᵏ (2k)!/(4ᵏ (k!)² (2k+1)) x^(2k+1), used for |x| < 1/64 (10 terms: < 2⁻¹¹⁰)
_ASINH = tuple(dd_const(Fraction((-1) ** k * math.factorial(2 * k), 4 ** k * math.factorial(k) ** 2 * (2 * k + 1)))
               for k in range(10))
_AS_HI = tuple(c[0] for c in _ASINH)
_AS_LO = tuple(c[1] for c in _ASINH)


@_jit
def two_sum(a, b):
    s = a + b
    bb = s - a
    return s, (a - (s - bb)) + (b - bb)


@_jit
def fast_two_sum(a, b):          # |a| ≥ |b| (or a = 0)
    s = a + b
    return s, b - (s - a)


@_jit
def split(a):
    c = _SPLIT * a
    hi = c - (c - a)
    return hi, a - hi


@_jit
def two_prod(a, b):
    p = a * b
    ah, al = split(a)
    bh, bl = split(b)
    return p, ((ah * bh - p) + ah * bl + al * bh) + al * bl


@_jit
def dd_add(ah, al, bh, bl):
    s, e = two_sum(ah, bh)
    t, f = two_sum(al, bl)
    e += t
    s, e = fast_two_sum(s, e)
    e += f
    return fast_two_sum(s, e)


@_jit
def dd_add_d(ah, al, b):
    s, e = two_sum(ah, b)
    e += al
    return fast_two_sum(s, e)


@_jit
def dd_mul(ah, al, bh, bl):
    p, e = two_prod(ah, bh)
    e += ah * bl + al * bh
    return fast_two_sum(p, e)


@_jit
def dd_mul_d(ah, al, b):
    p, e = two_prod(ah, b)
    e += al * b
    return fast_two_sum(p, e)


@_jit
def dd_div(ah, al, bh, bl):
    q1 = ah / bh
    ph, pl = dd_mul_d(bh, bl, q1)
    rh, rl = dd_add(ah, al, -ph, -pl)
    q2 = rh / bh
    ph, pl = dd_mul_d(bh, bl, q2)
    rh, rl = dd_add(rh, rl, -ph, -pl)
    q3 = rh / bh
    q1, q2 = fast_two_sum(q1, q2)
    return dd_add_d(q1, q2, q3)


@_jit
def dd_recip(ah, al):
    return dd_div(1.0, 0.0, ah, al)


@_jit
def dd_sqrt(ah, al):
    if not ah > 0.0:
        return math.sqrt(ah), 0.0          # 0 → 0, negative or NaN → NaN
    x = 1.0 / math.sqrt(ah)
    ax = ah * x
    ph, pl = two_prod(ax, ax)
    dh, dl = dd_add(ah, al, -ph, -pl)
    return two_sum(ax, dh * x * 0.5)


@_jit
def dd_powi(ah, al, n):
    """(hi, lo)ⁿ for an integer n ≥ 1, by binary powering."""
    rh, rl = 1.0, 0.0
    bh, bl = ah, al
    while n > 0:
        if n & 1:
            rh, rl = dd_mul(rh, rl, bh, bl)
        n >>= 1
        if n:
            bh, bl = dd_mul(bh, bl, bh, bl)
    return rh, rl


@_jit
def dd_exp(ah, al):
    if ah > 709.78:
        return math.inf, 0.0
    if ah < -745.2:
        return 0.0, 0.0
    if ah != ah:
        return ah, 0.0
    k = math.floor(ah / LN2_HI + 0.5)
    ph, pl = dd_mul_d(LN2_HI, LN2_LO, k)
    rh, rl = dd_add(ah, al, -ph, -pl)
    rh *= 1.0 / 512.0
    rl *= 1.0 / 512.0
    # expm1(r) = r + r²(1/2! + r(1/3! + … + r/9!)), |r| ≤ 6.8e-4: the first term left out,
    # r¹⁰/10!, is below 2e-35 of r
    sh, sl = _IF_HI[7], _IF_LO[7]
    for j in range(6, -1, -1):
        sh, sl = dd_mul(sh, sl, rh, rl)
        sh, sl = dd_add(sh, sl, _IF_HI[j], _IF_LO[j])
    sh, sl = dd_mul(sh, sl, rh, rl)
    sh, sl = dd_mul(sh, sl, rh, rl)
    sh, sl = dd_add(sh, sl, rh, rl)
    for _ in range(9):                     # expm1(2r) = 2 expm1(r) + expm1(r)²
        qh, ql = dd_mul(sh, sl, sh, sl)
        sh, sl = dd_add(2.0 * sh, 2.0 * sl, qh, ql)
    sh, sl = dd_add_d(sh, sl, 1.0)
    if k > 1000.0:                         # 2^k in two steps (2^k alone would overflow)
        return math.ldexp(math.ldexp(sh, 1000), int(k) - 1000), math.ldexp(math.ldexp(sl, 1000), int(k) - 1000)
    if k < -1000.0:
        return math.ldexp(math.ldexp(sh, -1000), int(k) + 1000), math.ldexp(math.ldexp(sl, -1000), int(k) + 1000)
    return math.ldexp(sh, int(k)), math.ldexp(sl, int(k))


@_jit
def dd_log(ah, al):
    if not ah > 0.0 or ah == math.inf:
        return math.log(ah) if ah >= 0.0 else math.nan, 0.0
    x = math.log(ah)
    eh, el = dd_exp(-x, 0.0)
    th, tl = dd_mul(ah, al, eh, el)
    th, tl = dd_add_d(th, tl, -1.0)       # a·e^(−x) − 1 ≈ a − e^x relative: the Newton correction
    return dd_add_d(th, tl, x)


@_jit
def dd_pow(ah, al, yh, yl):
    """a^y = exp(y log a), a > 0."""
    lh, ll = dd_log(ah, al)
    th, tl = dd_mul(lh, ll, yh, yl)
    return dd_exp(th, tl)


@_jit
def dd_asinh(ah, al):
    neg = ah < 0.0
    if neg:
        ah, al = -ah, -al
    if ah > 1e150:                         # asinh x = log 2x + O(x⁻²)
        rh, rl = dd_log(ah, al)
        rh, rl = dd_add(rh, rl, LN2_HI, LN2_LO)
    elif ah < 0.015625:                    # the series: log(x + √(x²+1)) would cancel near 1
        qh, ql = dd_mul(ah, al, ah, al)
        rh, rl = _AS_HI[9], _AS_LO[9]
        for k in range(8, -1, -1):
            rh, rl = dd_mul(rh, rl, qh, ql)
            rh, rl = dd_add(rh, rl, _AS_HI[k], _AS_LO[k])
        rh, rl = dd_mul(rh, rl, ah, al)
    else:
        qh, ql = dd_mul(ah, al, ah, al)
        qh, ql = dd_add_d(qh, ql, 1.0)
        qh, ql = dd_sqrt(qh, ql)
        qh, ql = dd_add(qh, ql, ah, al)
        rh, rl = dd_log(qh, ql)
    if neg:
        return -rh, -rl
    return rh, rl

