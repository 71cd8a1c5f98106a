"""The Hopf point of a Hopf line without closed form, with error bounds: W = ω_c², k_c and ω_c
from the Hopf polynomial H(W) and p(W) = −Re(P Q̄)(W)/|Q|²(W) (:mod:`landau.derivation.hopf_polynomial`),
whose coefficients come from the bounded kernels of :mod:`landau.codegen.bounded` (values and
absolute error bounds, in float64 or double-double).

What the coefficient formulas of a several-state law need as inputs is (ω_c, k_c) at the root;
their error moves the coefficients by |∂y/∂ω|e_ω + |∂y/∂k|e_k, which the kernels add to their
own bound once these errors are known.  So this module gives, for every point:

* :func:`f64_point` — the float64 root W (found by :mod:`landau.derivation.hopf_roots`) with the
  first-order bound on its distance to the exact root of the exact polynomial,

      |W − W*| ≤ e₁ + |H″| e₁²/|H′|,   e₁ = (|Ĥ(W)| + γ₂d Σᵢ|cᵢ||W|^(d−i) + Σᵢ eᵢ|W|^(d−i)) / |H′(W)|,

  Ĥ(W) the Horner value, γₙ = nu/(1 − nu) its rounding (Higham 2002, *Accuracy and Stability
  of Numerical Algorithms*, 2nd ed., eq. 5.3), eᵢ the coefficients' bounds; a Newton–Kantorovich
  style estimate, refused (∞) where the second-order term is not small (near a double root,
  |H″|e₁/|H′| > 1/10).  Then p(W) with |p′|e_W, the coefficients' bounds and the rounding of
  both polynomials and the division; ω = √W with e_W/(2ω).
* :func:`dd_point` — the same in double-double (u → 2⁻¹⁰³ of :mod:`landau.codegen.ddarith`),
  after two Newton steps W ← W − Ĥ(W)/H′(W) with Ĥ in double-double and H′ in float64 (each
  step multiplies the error by |1 − H′/Ĥ′| ~ 1e-16: from the float64 root to ~1e-32); refused
  where the steps moved W by more than 1e-12 relative (they may have found another root).

Coefficient arrays are (terms, points), highest power first, as ``sympy.Poly.all_coeffs``.
"""

from __future__ import annotations

import math

import numba as nb
import numpy as np

from landau.codegen import ddarith

_jit = nb.njit(cache=True, error_model="numpy", nogil=True)
U = 2.0 ** -53
_INF = math.inf
#: the second-order term of the root's bound, relative to the first, above which it is refused
_KANTOROVICH = 0.1
#: the largest relative move of the Newton steps from the float64 root (accurate to ~1e-15) that is
#: taken as converging to that root; beyond it the bound is refused (it might be another root's)
_MOVE = 1e-12


@_jit
def _gamma(n, u):
    return n * u / (1.0 - n * u)


@_jit
def _horner64(c, e, j, W):
    """(value, derivative, second derivative, Σ|cᵢ||W|^(d−i), Σ eᵢ|W|^(d−i)) at point j."""
    h = c[0, j]
    d1 = 0.0
    d2 = 0.0
    a = abs(c[0, j])
    ea = e[0, j]
    aw = abs(W)
    for i in range(1, c.shape[0]):
        d2 = d2 * W + 2.0 * d1
        d1 = d1 * W + h
        h = h * W + c[i, j]
        a = a * aw + abs(c[i, j])
        ea = ea * aw + e[i, j]
    return h, d1, d2, a, ea


@_jit
def _root_bound(r, d1, d2):
    """|W − W*| from the residual bound r, H′ and H″ (∞ where the estimate is not first order)."""
    if not (abs(d1) > 0.0):
        return _INF
    e1 = r / abs(d1)
    second = abs(d2) * e1 / abs(d1)
    if not (second <= _KANTOROVICH):
        return _INF
    return e1 * (1.0 + second)


@_jit
def f64_point(C, EC, R, ER, S, ES, W, out):
    """Float64 (ω, e_ω, k, e_k) of every point into out (4 × points) from its root W (NaN: none).

    C, R, S: coefficients of H, Re(P Q̄) and |Q|² in W (terms × points); EC, ER, ES their bounds."""
    dH = C.shape[0] - 1
    gH = _gamma(2 * dH, U)
    gR = _gamma(2 * (R.shape[0] - 1) + 1, U)
    gS = _gamma(2 * (S.shape[0] - 1) + 1, U)
    for j in range(W.size):
        x = W[j]
        if not (x > 0.0):
            out[0, j], out[1, j], out[2, j], out[3, j] = math.nan, 0.0, math.nan, 0.0
            continue
        h, d1, d2, a, ea = _horner64(C, EC, j, x)
        eW = _root_bound(abs(h) + gH * a + ea, d1, d2)
        re, re1, _, ra, rea = _horner64(R, ER, j, x)
        q2, q21, _, sa, sea = _horner64(S, ES, j, x)
        e_re = gR * ra + rea + abs(re1) * eW
        e_q2 = gS * sa + sea + abs(q21) * eW
        k = -re / q2
        if not (e_q2 <= _KANTOROVICH * abs(q2)) or not (eW <= _KANTOROVICH * x):
            ek = _INF
            ew = _INF
        else:
            ek = (e_re + abs(k) * e_q2) / abs(q2) * (1.0 + e_q2 / abs(q2)) / (1.0 - e_q2 / abs(q2)) + U * abs(k)
            w = math.sqrt(x)
            ew = eW / (2.0 * w) * (1.0 + eW / x) + U * w
        out[0, j], out[1, j], out[2, j], out[3, j] = math.sqrt(x), ew, k, ek


@_jit
def _horner_dd(ch, cl, ce, j, wh, wl):
    """Double-double Horner at W = wh + wl: (hi, lo, H′ in float64, H″ in float64,
    Σ|cᵢ||W|^(d−i), Σ eᵢ|W|^(d−i)); the float64 parts by :func:`_horner64` on the high parts,
    the two sums raised by 4u for their own rounding."""
    hh, hl = ch[0, j], cl[0, j]
    for i in range(1, ch.shape[0]):
        ph, pl = ddarith.dd_mul(hh, hl, wh, wl)
        hh, hl = ddarith.dd_add(ph, pl, ch[i, j], cl[i, j])
    _, d1, d2, a, ea = _horner64(ch, ce, j, wh)
    return hh, hl, d1, d2, a * (1.0 + 4 * U), ea * (1.0 + 4 * U)


@_jit
def dd_point(CH, CL, CE, RH, RL, RE, SH, SL, SE, W, out):
    """Double-double (ω hi, ω lo, e_ω, k hi, k lo, e_k) of every point into out (6 × points),
    from its float64 root W (NaN: none), after two Newton steps in double-double.

    CH, CL, CE: high and low parts and bounds of the coefficients of H (RH… of Re(P Q̄), SH… of
    |Q|²), terms × points."""
    UD, UV = ddarith.UNIT, ddarith.UNIT_DIV
    dH = CH.shape[0] - 1
    gH = _gamma(2 * dH + 2, UD)
    gR = _gamma(2 * (RH.shape[0] - 1) + 2, UD)
    gS = _gamma(2 * (SH.shape[0] - 1) + 2, UD)
    for j in range(W.size):
        wh, wl = W[j], 0.0
        if not (wh > 0.0):
            for q in range(6):
                out[q, j] = math.nan if q in (0, 3) else 0.0
            continue
        for _ in range(2):
            hh, hl, d1, _d2, _a, _ea = _horner_dd(CH, CL, CE, j, wh, wl)
            if d1 != 0.0:
                wh, wl = ddarith.dd_add_d(wh, wl, -(hh + hl) / d1)
        hh, hl, d1, d2, a, ea = _horner_dd(CH, CL, CE, j, wh, wl)
        eW = _root_bound(abs(hh + hl) * (1.0 + 2 * U) + gH * a + ea, d1, d2)
        rh, rl, r1, _, ra, rea = _horner_dd(RH, RL, RE, j, wh, wl)
        qh, ql, q1, _, sa, sea = _horner_dd(SH, SL, SE, j, wh, wl)
        e_re = gR * ra + rea + abs(r1) * eW * (1.0 + 4 * U)
        e_q2 = gS * sa + sea + abs(q1) * eW * (1.0 + 4 * U)
        kh, kl = ddarith.dd_div(rh, rl, qh, ql)
        kh, kl = -kh, -kl
        omh, oml = ddarith.dd_sqrt(wh, wl)
        ak, aq = abs(kh), abs(qh)
        moved = abs((wh - W[j]) + wl) > _MOVE * W[j]     # Newton left the float64 root: another root?
        if moved or not (e_q2 <= _KANTOROVICH * aq) or not (eW <= _KANTOROVICH * wh):
            ek = _INF
            ew = _INF
        else:
            ek = ((e_re + ak * e_q2) / aq * (1.0 + e_q2 / aq) / (1.0 - e_q2 / aq) + UV * ak) * (1.0 + 4 * U)
            ew = (eW / (2.0 * omh) * (1.0 + eW / wh) + UV * omh) * (1.0 + 4 * U)
        out[0, j], out[1, j], out[2, j] = omh, oml, ew
        out[3, j], out[4, j], out[5, j] = kh, kl, ek


def _c(a) -> np.ndarray:
    return np.ascontiguousarray(a, dtype=float)


def hopf_f64(C, EC, R, ER, S, ES, W) -> np.ndarray:
    """(ω, e_ω, k, e_k) × points in float64 (see :func:`f64_point`)."""
    out = np.empty((4, np.size(W)))
    f64_point(_c(C), _c(EC), _c(R), _c(ER), _c(S), _c(ES), _c(W), out)
    return out


def hopf_dd(parts_H, parts_R, parts_S, W) -> np.ndarray:
    """(ω hi, ω lo, e_ω, k hi, k lo, e_k) × points in double-double (see :func:`dd_point`);
    each ``parts_*`` is (high parts, low parts, bounds) of a polynomial's coefficients."""
    out = np.empty((6, np.size(W)))
    (CH, CL, CE), (RH, RL, RE), (SH, SL, SE) = parts_H, parts_R, parts_S
    dd_point(_c(CH), _c(CL), _c(CE), _c(RH), _c(RL), _c(RE), _c(SH), _c(SL), _c(SE), _c(W), out)
    return out
