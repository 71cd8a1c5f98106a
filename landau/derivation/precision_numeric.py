"""The precision routes of a Hopf line without closed form (laws with several state variables, or a
steady state solved numerically), used by :meth:`landau.derivation.multiscale.Derivation.evaluate`
as the closed-form routes of :mod:`landau.derivation.precision` are: every returned value accurate
to :data:`~landau.derivation.precision.REL_GOOD` or left doubtful for
:func:`~landau.derivation.precision.refine_mpmath`.

* :func:`bounded_numeric_route` — batches of :data:`~landau.derivation.precision.BOUNDED_MIN`
  points or more (:data:`~landau.derivation.precision.BOUNDED_MIN_SIGN` for a sign scan): the
  Hopf polynomial's coefficients and the coefficients (Λ, …) by the bounded kernels of
  :mod:`landau.codegen.bounded`, (ω_c, k_c) with error bounds from
  :mod:`landau.codegen.bounded_hopf`, double-double where float64 does not certify.
* :func:`numeric_hopf_route` — smaller batches: (k_c, ω_c) polished in long double
  (:func:`polish_extended`), the coefficients in float64 screened by long double there.
"""

from __future__ import annotations

import logging
from typing import TYPE_CHECKING, Sequence

import numpy as np

from landau.derivation import precision
from landau.derivation.precision import (
    BOUNDED_STATS,
    EXTENDED,
    REL_BOUND,
    REL_GOOD,
    Raw,
    _no_extended,
    _varying,
    agree,
    bounded_kernels,
    raw,
    sign_settled,
)

if TYPE_CHECKING:
    from landau.derivation.multiscale import Derivation

logger = logging.getLogger(__name__)

#: relative error of the numerically solved (k_c, ω_c) polished in long double (:func:`polish_extended`),
#: at which the small-batch route screens the coefficients: measured ≤ 1.0e-18 against 40 digits
#: (the two-state Dieterich law, 400 log-spaced points from 1e-8 to 0.1 m/s; the 3- and 5-state
#: Dieterich laws of the derivation benchmark, 150 points each; float64 roots: ≤ 2.2e-15); ten
#: times that
INPUT_REL_EXT = 1e-17


def polish_extended(d: "Derivation", lvals, kc80: np.ndarray,
                    om80: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """(k_c, ω_c, polished) in long double from a float64 root: two Newton steps W ← W − H(W)/H′(W)
    on the Hopf polynomial (:mod:`landau.derivation.hopf_polynomial`), its coefficients evaluated
    in long double, then k_c = −Re(P Q̄)/|Q|² at that W.  Each step squares the relative error of
    a simple root, so W is then as accurate as its long double coefficients make it (measured
    against 40 digits: :data:`INPUT_REL_EXT`).  ``polished`` is False (the float64 values are
    returned) where there is no Hopf point, and where the steps moved W by more than 1e-12
    relative or left it non-positive — not a simple root within the float64 root's error (near a
    double root of H)."""
    ld = np.longdouble
    coeffs, fre, fq2 = d.hopf._compiled_poly
    syms = sorted(set().union(*(f.atom_syms for f in [*coeffs, fre, fq2])), key=str)
    atoms = d._atom_table.evaluate(syms, *lvals)
    cs = [np.asarray(c.call_with_atoms(atoms, *lvals), dtype=ld) for c in coeffs]
    W = W64 = om80 * om80
    with np.errstate(all="ignore"):
        for _ in range(2):
            h, dh = cs[0] * np.ones_like(W), np.zeros_like(W)
            for c in cs[1:]:
                dh = dh * W + h
                h = h * W + c
            W = np.where(np.isfinite(W) & (dh != 0), W - h / dh, W)
        k = -(np.asarray(fre.call_with_atoms(atoms, W, *lvals), dtype=ld)
              / np.asarray(fq2.call_with_atoms(atoms, W, *lvals), dtype=ld))
        ok = np.isfinite(kc80) & np.isfinite(k) & (W > 0) & (np.abs(W - W64) <= ld(1e-12) * W64)
        return np.where(ok, k, kc80), np.where(ok, np.sqrt(np.where(ok, W, 1)), om80), ok


def numeric_hopf_route(d: "Derivation", Vs, vals, shape, bases, p, sign_only: bool) -> Raw:
    """A Hopf line without closed form (several state variables), for batches too small for the
    bounded kernels (:func:`~landau.derivation.precision.takes_bounded`): k_c and ω_c solved numerically
    (:meth:`landau.derivation.linear.HopfLine.numeric_at`) and polished in long double
    (:func:`polish_extended`), the coefficients in float64 at the rounded polished point, screened
    by the same formulas in long double at the polished point.

    Guarantee: a coefficient is kept where float64 and long double agree to
    :data:`~landau.derivation.precision.REL_GOOD` and where the error of its inputs (k_c, ω_c),
    each off by up to :data:`INPUT_REL_EXT`, moves it by less than half of that; elsewhere the
    point is doubtful (:func:`~landau.derivation.precision.refine_mpmath`), except with
    ``sign_only`` where the long double value is certain in sign and larger than twice that
    movement.  The long double value is returned where kept.  The second condition is needed
    because float64 and long double evaluated at the same rounded inputs agree even where Λ
    amplifies their error a millionfold (the two-state Dieterich law near V = 3e-6 m/s:
    |d ln Λ/d ln k_c| ~ 1e6); the polish makes that error ~2000 times smaller than a float64
    root's, so only points more sensitive than ~1e6 are left to mpmath (with float64 roots: ~1e3)."""
    kc, om = d.hopf.numeric_at(vals)
    kc, om = kc.reshape(shape), om.reshape(shape)
    doubtful = np.zeros(shape, dtype=bool)
    if EXTENDED and bases:
        ld = np.longdouble
        lvals = [v.astype(ld) for v in vals]
        kc80, om80, polished = polish_extended(d, lvals, kc.astype(ld), om.astype(ld))
        values = {"kc": kc80.astype(float), "W": (om80 * om80).astype(float)}
        values.update(raw(d, vals, shape, bases, np.float64, values["kc"], om80.astype(float)))
        ext = raw(d, lvals, shape, bases, ld, kc80, om80)
        # the coefficients again with k_c and ω_c each moved by their error bound: a first-order
        # estimate of what the inputs' error does to each (in long double, so that the formula's
        # own round-off does not mask it)
        bump = ld(1) + ld(INPUT_REL_EXT)
        moved_k = raw(d, lvals, shape, bases, ld, kc80 * bump, om80)
        moved_w = raw(d, lvals, shape, bases, ld, kc80, om80 * bump)
        for n in bases:
            x80 = ext[n].astype(float)
            with np.errstate(invalid="ignore"):
                moved = (np.abs((moved_k[n] - ext[n]).astype(float))
                         + np.abs((moved_w[n] - ext[n]).astype(float)))
                sensitive = ~(moved <= 0.5 * REL_GOOD * np.abs(x80))
            off = ~agree(values[n], x80, REL_GOOD) | (sensitive & np.isfinite(x80))
            if sign_only:
                off &= ~(sign_settled(values[n], x80) & (np.abs(x80) > 2 * moved))
            values[n] = np.where(off, values[n], x80)
            doubtful |= off
        doubtful |= ~polished        # the screen's input error is not known there: 50 digits
    else:
        values = {"kc": kc, "W": om ** 2}
        values.update(raw(d, vals, shape, bases, np.float64, kc, om))
        if bases:
            doubtful[...] = True
            _no_extended(d.block.law.name, int(np.sum(np.isfinite(values["kc"]))))
    doubtful &= np.isfinite(values["kc"])
    return Raw(values, doubtful, np.zeros(shape, dtype=bool))


def hopf_coefficient_kernels(d: "Derivation", varying: tuple[bool, ...]):
    """The bounded kernels of the coefficients of the Hopf polynomial H(W), of Re(P Q̄)(W) and of
    |Q|²(W) (:mod:`landau.derivation.hopf_polynomial`), highest power first, for a Hopf line without
    closed form: (kernels, number of terms of each); None where an operation has no bounded form."""
    import sympy as sp

    from landau.codegen.bounded import BoundedKernels, Unsupported, linearise
    from landau.derivation.linear import W

    cache = d.__dict__.setdefault("_bounded_hopf", {})
    if varying not in cache:
        H, re, q2 = d.hopf._hopf_polys
        polys = [H.all_coeffs(), sp.Poly(re, W).all_coeffs(), sp.Poly(q2, W).all_coeffs()]
        try:
            prog = linearise([c for cs in polys for c in cs], d.args, varying, d.jets.atoms)
            cache[varying] = (BoundedKernels(prog), tuple(len(cs) for cs in polys))
        except Unsupported as exc:
            logger.debug("%s: no bounded Hopf polynomial (%s)", d.block.law.name, exc)
            cache[varying] = None
    return cache[varying]


def _split(a: np.ndarray, sizes: Sequence[int]) -> list[np.ndarray]:
    return np.split(a, np.cumsum(sizes)[:-1], axis=0)


def _polyval(c: np.ndarray, x: np.ndarray) -> np.ndarray:
    """Σᵢ c[i] x^(d−i) per column (Horner), c: terms × points."""
    out = c[0].copy()
    for ci in c[1:]:
        out = out * x + ci
    return out


def bounded_numeric_route(d: "Derivation", Vs, vals, shape, bases, p, sign_only: bool) -> Raw | None:
    """A Hopf line without closed form (several state variables) in float64 with error bounds,
    the points they do not certify to :data:`~landau.derivation.precision.REL_BOUND` in
    double-double; the default for batches of :data:`~landau.derivation.precision.BOUNDED_MIN`
    points or more (:data:`~landau.derivation.precision.BOUNDED_MIN_SIGN` for a sign scan).

    1. The coefficients of H(W), Re(P Q̄)(W) and |Q|²(W) with the float64 bounded kernels.
    2. The stiffest root W of every point (:func:`landau.derivation.hopf_roots.stiffest`), and
       ω_c, k_c with bounds on their distance to the exact root
       (:func:`landau.codegen.bounded_hopf.f64_point`).
    3. The coefficients (Λ, …) at (ω_c, k_c) with the float64 bounded kernels, the errors of
       ω_c and k_c among their inputs' errors: a point where the formula amplifies them (the
       two-state Dieterich law near V = 3e-6 m/s: |d ln Λ/d ln k_c| ~ 1e6) is not certified.
    4. The points not certified: steps 1–3 in double-double, with two Newton steps on the root
       (:func:`landau.codegen.bounded_hopf.dd_point`), so that ω_c and k_c are off by ~1e-30.
    5. What is still in doubt (a double root, Λ ≡ 0, a zero of Λ closer than ~1e-20) is left
       to :func:`~landau.derivation.precision.refine_mpmath`.

    None (another route is taken) where an operation has no bounded form, and for batches too small
    for it (:func:`~landau.derivation.precision.takes_bounded`)."""
    size = int(np.prod(shape))
    if not precision.takes_bounded(size, sign_only) or not bases:   # before the imports: no numba for a small batch
        return None
    from landau.codegen.bounded_hopf import hopf_dd, hopf_f64
    from landau.derivation.hopf_roots import stiffest

    varying = _varying(vals)
    hk = hopf_coefficient_kernels(d, varying)
    kern = bounded_kernels(d, bases, varying)
    if hk is None or kern is None or not (kern.dd_ok and hk[0].dd_ok):
        return None
    coef, sizes = hk
    X = np.stack([np.ravel(x) for x, var in zip(vals, varying, strict=True) if var]) if any(varying) \
        else np.empty((0, size))
    Q = np.array([0.0 if var else float(np.ravel(x)[0]) for x, var in zip(vals, varying, strict=True)])
    # 1–2: the Hopf point with its bounds, in float64
    cv, _, ce = coef.f64_parts(X, Q)
    (C, R, S), (EC, ER, ES) = _split(cv, sizes), _split(ce, sizes)
    with np.errstate(all="ignore"):
        _, W0 = stiffest(C.T, lambda Wr, rows: -_polyval(R[:, rows], Wr) / _polyval(S[:, rows], Wr), 1e-9)
    hp = hopf_f64(C, EC, R, ER, S, ES, W0)
    has = np.isfinite(hp[2])
    # 3: the coefficients at (ω_c, k_c), their errors among the inputs'
    Xf = np.vstack([hp[0][None], hp[2][None], X])
    EXf = np.zeros_like(Xf)
    EXf[0], EXf[1] = hp[1], hp[3]
    Qf = np.concatenate([[0.0, 0.0], Q])            # the formulas' arguments: ω, k, then the law's
    out, rb = kern.f64(np.where(np.isfinite(Xf), Xf, 1.0), Qf, EXf)
    kc, om = hp[2].copy(), hp[0].copy()
    with np.errstate(invalid="ignore", divide="ignore"):
        rin = np.maximum(hp[1] / om, hp[3] / np.abs(kc))
    flag = has & ~((rb[0] <= REL_BOUND) & (rin <= REL_BOUND))
    BOUNDED_STATS["f64"] += size
    # 4: the rest in double-double
    if flag.any():
        idx = np.flatnonzero(flag)
        _, _, ch, cl, cde = coef.dd_parts(X[:, idx], Q)
        parts = [tuple(_split(a, sizes)[i] for a in (ch, cl, cde)) for i in range(3)]
        hq = hopf_dd(parts[0], parts[1], parts[2], W0[idx])
        Xd = np.vstack([hq[0][None], hq[3][None], X[:, idx]])
        XLd = np.zeros_like(Xd)
        XLd[0], XLd[1] = hq[1], hq[4]
        EXd = np.zeros_like(Xd)
        EXd[0], EXd[1] = hq[2], hq[5]
        ok = np.isfinite(Xd).all(axis=0)
        out2, rb2 = kern.dd(np.where(ok, Xd, 1.0), Qf, np.where(ok, XLd, 0.0), EXd)
        out[:, idx], rb[0, idx] = out2, rb2[0]
        kc[idx], om[idx] = hq[3] + hq[4], hq[0] + hq[1]
        with np.errstate(invalid="ignore", divide="ignore"):
            rin2 = np.maximum(hq[2] / np.abs(hq[0]), hq[5] / np.abs(hq[3]))
        flag[idx] = ~((rb2[0] <= REL_BOUND) & (rin2 <= REL_BOUND) & ok)
        BOUNDED_STATS["dd"] += idx.size
    BOUNDED_STATS["left"] += int(flag.sum())
    if sign_only:
        flag &= ~(rb[0] < 1.0)
    values = {"kc": np.where(has, kc, np.nan).reshape(shape), "W": np.where(has, om * om, np.nan).reshape(shape)}
    values.update({n: np.where(has, out[j], np.nan).reshape(shape) for j, n in enumerate(bases)})
    return Raw(values, flag.reshape(shape), np.zeros(shape, dtype=bool))
