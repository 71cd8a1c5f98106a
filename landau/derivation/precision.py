"""The precision routes of :meth:`landau.derivation.multiscale.Derivation.evaluate`: every returned value
accurate to :data:`REL_GOOD` (relative) or settled by a slower, more precise route.

Each route returns a :class:`Raw` (k_c, ω_c², the requested coefficients, the points still in
doubt, the points where Λ vanishes identically); :func:`refine_mpmath` settles the doubtful
points and :func:`finish` assembles the table.

* :func:`exact_rational_route` — laws whose derivatives at steady sliding are rational in V
  (Dieterich, Ruina, modified Dieterich): every point from the exactly cancelled form
  (:mod:`landau.derivation.rational`), with a proven error bound or an exact evaluation.
* :func:`screened_route` — a closed-form Hopf line: float64 (numpy, vectorised in blocks on
  threads), screened by the same code in float32; the suspects again in long double (x87,
  eps 1.1e-19); what is still doubtful from the exactly cancelled form where it exists.
* :func:`bounded_route` — a closed-form Hopf line in float64 with a running error bound
  (:mod:`landau.codegen.bounded`), double-double where it does not certify (the default for
  batches of :data:`BOUNDED_MIN` points or more, :data:`BOUNDED_MIN_SIGN` for a sign scan).
* a Hopf line found numerically (several state variables): the routes of
  :mod:`landau.derivation.precision_numeric`.
* :func:`refine_mpmath` — the points in doubt after a route: 50 and 80 digits, and up to 550
  until two successive precisions agree (:func:`evaluate_mp_checked`).

Round-off grows with the unit round-off times the condition number at every precision: a
float32 value off by δ₃₂ means a float64 value off by about δ₃₂·2⁻²⁹ (measured up to 200×
more, hence the screen's threshold :data:`REL_SCREEN`), and a long double value ~2000× better
than float64 (Higham 2002, *Accuracy and Stability of Numerical Algorithms*, Sec. 1.12).
"""

from __future__ import annotations

import logging
import math
import os
import warnings
from concurrent.futures import ThreadPoolExecutor
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any, Mapping, Sequence

import mpmath
import numpy as np

from landau.derivation.coefficients import DERIVED, CoefficientTable, _with_bases
from landau.errors import NoHopfError, SingularPointError

if TYPE_CHECKING:
    from landau.derivation.multiscale import Derivation

logger = logging.getLogger(__name__)

#: accuracy every returned value must have (relative)
REL_GOOD = 1e-10
#: doubtful points from which deriving the exactly cancelled form beats mpmath point by point
RATIONAL_MIN = 500
#: points from which the exactly cancelled form (~0.2 s to derive per parameter set) beats the
#: general formula for all of them (float64 + float32 screen + long double pass)
RATIONAL_DIRECT = 100_000
#: points per block of the vectorised evaluation (working set of a formula stays in cache)
BLOCK = 16_384
#: threads for the blocks (numpy's elementwise loops release the GIL)
WORKERS = max(1, min(8, os.cpu_count() or 1))
#: float32 vs float64 disagreement above which float64 may miss REL_GOOD.  The eps ratio is
#: ~5e8, but float32's error saturates where float64's does not: on 20,000 log-spaced points of
#: the spinodal law's range (M = default and 1e-7 kg) 2e-4 let one float64 value off by 1.2e-10
#: through; at 2e-5 the worst value passed is off by 1e-11 (nanoscale, micron-scale: ≤ 1e-12)
REL_SCREEN = 2e-5
#: digits of the successive mpmath evaluations that decide whether a tiny value is genuine
MP_LADDER = (50, 80, 120, 200, 330, 550)
#: further digits for a point with a parameter (or V) beyond 1e±EXTREME: the terms of a coefficient
#: then cancel over as many orders as the parameter has (Λ ∝ M = 1e-308 lies 315 orders below
#: its terms), more than the 550 digits of :data:`MP_LADDER` can settle to 1e-20
MP_LADDER_EXTREME = (900, 1500)
EXTREME = 100
#: extended precision available (x86 80-bit long double: eps 1.1e-19, ~1000x float64)
EXTENDED = np.finfo(np.longdouble).eps < 1e-18
#: how much closer to the exact value the long double evaluation is than float64, at least.
#: Not the 2048 of the unit round-offs: the printed formulas carry float64 literals (rational
#: constants such as 1/3), whose rounding long double does not remove; measured 60–300 at the
#: low-velocity end of the Dieterich and Ruina laws (1000-point tests against 50 digits), where
#: 512 let long double values off by 2e-10 through.  16 keeps a factor ≥ 4 below that.
EXT_GAIN = 16.0
#: the same gain where only a sign is needed: the smallest measured (60); a sign is taken as
#: certain where the long double value's error so estimated is below half its size
SIGN_GAIN = 60.0
#: points settled by mpmath in one call from which the cost (~1 ms a point) deserves a warning
MP_WARN = 2_000
#: relative error bound below which a value of the bounded kernels is certified: half of
#: :data:`REL_GOOD`, a margin for the rounding of the bound itself and for the second-order
#: terms it leaves out
REL_BOUND = 0.5 * REL_GOOD
#: points from which a batch takes the bounded route: below, the numpy route (float32 screen, long
#: double) costs less than the one-time compilation of the interpreters (~3–5 CPU-s per machine,
#: then loaded from numba's disk cache) that a single command would otherwise pay
BOUNDED_MIN = 1_000
#: the same for a batch that asks only for signs (a sign scan, ``sign_only``): the numpy route
#: settles a sign in long double for almost every point, about 1 µs a point more than the warm
#: interpreters (a 1300-point scan of Λ: 2.5–4.8 ms against 1.7–3.2 ms, five built-in laws),
#: while their first compilation costs ~8 CPU-s (float64 and double-double, measured on a cold
#: ``landau figures putelat2010``, whose 37 sign scans of 1000–1300 points paid it)
BOUNDED_MIN_SIGN = 100_000
#: points through the bounded kernels in this process: all of them (float64), those again in
#: double-double, and those left in doubt after it (read by the benchmark and the tests)
BOUNDED_STATS = {"f64": 0, "dd": 0, "left": 0}

_warned: set[tuple[str, str]] = set()


def warn_once(key: tuple[str, str], message: str) -> None:
    """``warnings.warn(message)`` once per process for ``key`` (law, cause)."""
    if key not in _warned:
        _warned.add(key)
        warnings.warn(message, RuntimeWarning, stacklevel=4)


@dataclass
class Raw:
    """What a route computed: ``values`` ("kc", "W" = ω_c², and the coefficients), the points
    whose values are not yet proven to :data:`REL_GOOD` (``doubtful``), and the points where Λ
    vanishes identically (``degenerate``)."""

    values: dict[str, np.ndarray]
    doubtful: np.ndarray
    degenerate: np.ndarray


def agree(x: np.ndarray, y: np.ndarray, rel: float) -> np.ndarray:
    """|x − y| ≤ rel·|y| elementwise, both finite; two NaNs agree (no Hopf point in either
    precision), and two equal infinities.  A finite value never agrees with an infinite one
    (|x − ∞| ≤ rel·∞ would hold: a float32 overflow must not pass a float64 value unscreened)."""
    with np.errstate(all="ignore"):
        d = np.abs(x - y)
        # d = ∞ only where one value is infinite and the other is not (equal infinities give NaN)
        return ((d <= rel * np.abs(y)) & (d != np.inf)) | (x == y) | (np.isnan(x) & np.isnan(y))


def sign_settled(x64: np.ndarray, x80: np.ndarray) -> np.ndarray:
    """Where the extended-precision value is certain in sign: non-zero, and its error — the
    float64 error |x64 − x80| scaled down by :data:`SIGN_GAIN` — below half its size."""
    with np.errstate(all="ignore"):
        return (x80 != 0) & np.isfinite(x80) & (np.abs(x64 - x80) <= 0.5 * SIGN_GAIN * np.abs(x80))


def _no_extended(law: str, n: int) -> None:
    warn_once((law, "no long double"), (
        f"{law}: numpy's long double has no more precision than float64 on this platform, so {n} point(s) "
        "that float64 may not give to 1e-10 are re-evaluated with mpmath (about 1 ms each); on an x86-64 "
        "machine they are settled in 80-bit long double instead"))


# --- vectorised evaluation in one precision ------------------------------------------------
def raw(d: "Derivation", vals, shape, bases, dtype, kc=None, om=None) -> dict[str, np.ndarray]:
    """k_c, ω_c² and the coefficients ``bases`` in one precision (``dtype``), atoms shared.

    With ``kc``, ``om`` given (a numeric Hopf line) only the coefficients are evaluated there.
    Large batches go through in blocks of :data:`BLOCK` points on :data:`WORKERS` threads: the
    formulas are long chains of elementwise operations; blocks that fit in cache run them
    faster and numpy releases the GIL inside each operation."""
    size = int(np.prod(shape))
    if size <= BLOCK:
        return _raw_block(d, vals, shape, bases, dtype, kc, om)
    flat = [np.ravel(v) for v in vals]
    kcf = None if kc is None else np.ravel(kc)
    omf = None if om is None else np.ravel(om)
    _raw_block(d, [v[:1] for v in flat], (1,), bases, dtype, None if kcf is None else kcf[:1],
               None if omf is None else omf[:1])          # compile once, outside the threads

    def block(i: int) -> tuple[slice, dict[str, np.ndarray]]:
        sl = slice(i, min(i + BLOCK, size))
        return sl, _raw_block(d, [v[sl] for v in flat], (sl.stop - sl.start,), bases, dtype,
                              None if kcf is None else kcf[sl], None if omf is None else omf[sl])

    out: dict[str, np.ndarray] = {}
    with ThreadPoolExecutor(max_workers=WORKERS) as pool:
        for sl, part in pool.map(block, range(0, size, BLOCK)):
            for key, val in part.items():
                out.setdefault(key, np.empty(size, dtype=val.dtype))[sl] = val
    return {key: val.reshape(shape) for key, val in out.items()}


def _raw_block(d: "Derivation", vals, shape, bases, dtype, kc=None, om=None) -> dict[str, np.ndarray]:
    formulas = [d._compiled_formula(n) for n in bases]
    hopf: tuple[Any, ...] = d.hopf._compiled_closed if kc is None else ()
    atoms = d._atom_table.evaluate(sorted(set().union(*(f.atom_syms for f in [*formulas, *hopf])), key=str), *vals)
    res: dict[str, np.ndarray] = {}
    if kc is None:
        fk, fW = hopf
        res["kc"] = np.asarray(fk.call_with_atoms(atoms, *vals), dtype=dtype) * np.ones(shape, dtype)
        res["W"] = np.asarray(fW.call_with_atoms(atoms, *vals), dtype=dtype) * np.ones(shape, dtype)
        with np.errstate(all="ignore"):
            om = np.sqrt(np.where(res["W"] > 0, res["W"], np.nan))
        kc = res["kc"]
    for n, f in zip(bases, formulas, strict=True):
        res[n] = np.asarray(f.call_with_atoms(atoms, om, kc, *vals), dtype=dtype) * np.ones(shape, dtype)
    return res


# --- the routes ------------------------------------------------------------------------------
def rational_forms(d: "Derivation", bases, params):
    """The exactly cancelled forms (:func:`landau.derivation.rational.rational_forms`) for these
    parameters, cached on the derivation; None when the law's derivatives at steady state are
    not rational in V."""
    from landau.derivation.rational import rational_forms as build

    key = (tuple(bases), tuple(sorted(params.items())))
    if key not in d._rational_cache:
        d._rational_cache[key] = build(d, bases, params)
    return d._rational_cache[key]


def has_rational(d: "Derivation", bases, params) -> bool:
    """Whether the exactly cancelled forms for these parameters were built already."""
    return (tuple(bases), tuple(sorted(params.items()))) in d._rational_cache


def exact_rational_route(d: "Derivation", Vs, shape, bases, forms) -> Raw:
    """Every point from the exactly cancelled form (``forms``, see :func:`rational_forms`).

    Used for ``method="rational"``, and by ``"auto"`` for a closed-form Hopf line with scalar
    parameters when the batch has ≥ :data:`RATIONAL_DIRECT` points or the form exists already.
    Guarantee: each value carries a proven float64 error bound ≤ :data:`REL_GOOD` or is computed
    exactly in ℚ and rounded once; Λ ≡ 0 (Dieterich at M = 0) is exactly 0 and flagged."""
    values = forms.evaluate(np.broadcast_to(Vs, shape), bases, REL_GOOD)
    degenerate = np.full(shape, "Lambda" in forms and forms["Lambda"].identically_zero)
    return Raw(values, np.zeros(shape, dtype=bool), degenerate)


def settle_exactly(d: "Derivation", Vs, shape, bases, p, exact: bool, values: dict[str, np.ndarray],
                   doubtful: np.ndarray, rest: np.ndarray) -> Raw:
    """The doubtful points ``rest`` (a valid Hopf point, only the coefficients in doubt) settled from
    the exactly cancelled rational form, where the law has one and it is worth deriving (at least
    :data:`RATIONAL_MIN` of them, or a form already derived); the points whose Λ is identically zero
    there are marked degenerate. The others stay doubtful for mpmath."""
    degenerate = np.zeros(shape, dtype=bool)
    if bases and exact and (rest.sum() >= RATIONAL_MIN or (rest.any() and has_rational(d, bases, p))):
        forms = rational_forms(d, bases, p)
        if forms is not None:
            sub = forms.evaluate(np.broadcast_to(Vs, shape)[rest], bases, REL_GOOD)
            for n in bases:
                values[n][rest] = sub[n]
            doubtful &= ~rest
            degenerate = rest & bool("Lambda" in forms and forms["Lambda"].identically_zero)
    return Raw(values, doubtful, degenerate)


def screened_route(d: "Derivation", Vs, vals, shape, bases, p, exact: bool, sign_only: bool) -> Raw:
    """A closed-form Hopf line: float64, screened by float32, suspects again in long double.

    Used by ``method="general"`` and by ``"auto"`` below :data:`RATIONAL_DIRECT` points.  A value
    is kept where float64 and float32 agree to :data:`REL_SCREEN` (float64 then within ~1e-12);
    a suspect keeps its float64 value where long double agrees with it to :data:`REL_GOOD`, takes
    the long double value where that is good to REL_GOOD (float64–long double gap below
    REL_GOOD·:data:`EXT_GAIN`), and is otherwise doubtful.  With ``exact`` (scalar parameters)
    doubtful points of a law rational in V are taken from the exactly cancelled form when there
    are ≥ :data:`RATIONAL_MIN` of them or the form exists; the rest go to :func:`refine_mpmath`.
    ``sign_only``: a suspect whose long double value is certain in sign is not doubtful."""
    law = d.block.law.name
    # arrays also at one point (shape ()): the suspects are written back into them in place
    values = {key: np.array(val) for key, val in raw(d, vals, shape, bases, np.float64).items()}
    with np.errstate(over="ignore"):    # a value beyond float32's range: a suspect, settled below
        r32 = raw(d, [v.astype(np.float32) for v in vals], shape, bases, np.float32)
    suspect = np.zeros(shape, dtype=bool)
    for key in values:
        suspect |= ~agree(values[key], r32[key].astype(float), REL_SCREEN)
    bad = {key: suspect.copy() for key in values}
    if suspect.any() and not EXTENDED:
        _no_extended(law, int(suspect.sum()))
    elif suspect.any():
        sub = [v[suspect].astype(np.longdouble) for v in vals]
        ext = raw(d, sub, sub[0].shape, bases, np.longdouble)
        for key in values:
            with np.errstate(over="ignore"):
                x64, x80 = values[key][suspect], ext[key].astype(float)
            values[key][suspect] = np.where(agree(x64, x80, REL_GOOD), x64, x80)
            bad[key][suspect] = ~agree(x64, x80, REL_GOOD * EXT_GAIN)
            if sign_only:
                bad[key][suspect] &= ~sign_settled(x64, x80)
    doubtful = np.zeros(shape, dtype=bool)
    for key in values:
        doubtful |= bad[key]
    rest = doubtful & ~(bad["kc"] | bad["W"]) & (values["kc"] > 0) & (values["W"] > 0)
    return settle_exactly(d, Vs, shape, bases, p, exact, values, doubtful, rest)


def bounded_kernels(d: "Derivation", bases, varying: tuple[bool, ...]):
    """The running-error-bound kernels (:mod:`landau.codegen.bounded`) of k_c, ω_c² (closed form)
    and the coefficients ``bases`` for this pattern of varying arguments, made once per
    derivation; None where an operation has no bounded form."""
    from landau.codegen.bounded import BoundedKernels, Unsupported, linearise
    from landau.derivation.linear import w

    cf = d.hopf.closed_form
    closed = cf is not None
    key = (tuple(bases), varying, closed)
    cache = d.__dict__.setdefault("_bounded", {})
    if key not in cache:
        formulas = [d.coefficient(n).formula for n in bases]
        try:
            if cf is not None:
                kc, W = cf
                prog = linearise([kc, W, *formulas], d.args, varying, d.jets.atoms,
                                 given={w: ("sqrt", 1), d.k: ("same", 0)})
                prog.gate = (prog.outs[0], prog.outs[1])
            else:
                prog = linearise(formulas, [w, d.k, *d.args], (True, True, *varying), d.jets.atoms)
            cache[key] = BoundedKernels(prog)
        except Unsupported as exc:
            logger.debug("%s: no bounded kernel (%s)", d.block.law.name, exc)
            cache[key] = None
    return cache[key]


def _varying(inputs) -> tuple[bool, ...]:
    """Which arguments vary over the points (a scalar broadcast to the shape has zero strides)."""
    return tuple(np.ndim(x) > 0 and any(np.asarray(x).strides) and np.size(x) > 1 for x in inputs)


def _run_bounded(kern, inputs: Sequence[np.ndarray], size: int, sign_only: bool):
    """Values (outputs × points), the relative bounds (2 × points) and the points still in doubt:
    float64 with its running bound, the points above :data:`REL_BOUND` again in double-double."""
    varying = _varying(inputs)
    X = np.stack([np.ravel(x) for x, var in zip(inputs, varying, strict=True) if var]) if any(varying) \
        else np.empty((0, size))
    Q = np.array([0.0 if var else float(np.ravel(x)[0]) for x, var in zip(inputs, varying, strict=True)])
    out, rb = kern.f64(X, Q)
    flag = ~(rb[0] <= REL_BOUND)
    if flag.any() and kern.dd_ok:
        idx = np.flatnonzero(flag)
        out2, rb2 = kern.dd(X[:, idx], Q)
        out[:, idx], rb[:, idx] = out2, rb2
        flag[idx] = ~(rb2[0] <= REL_BOUND)
        BOUNDED_STATS["dd"] += idx.size
    BOUNDED_STATS["f64"] += size
    BOUNDED_STATS["left"] += int(flag.sum())
    if sign_only:
        flag &= ~(rb[0] < 1.0)
    return out, rb, flag


def takes_bounded(size: int, sign_only: bool) -> bool:
    """Whether a batch of ``size`` points takes the bounded kernels: from :data:`BOUNDED_MIN`
    points, from :data:`BOUNDED_MIN_SIGN` where only signs are asked for."""
    return size >= (BOUNDED_MIN_SIGN if sign_only else BOUNDED_MIN)


def bounded_route(d: "Derivation", Vs, vals, shape, bases, p, exact: bool, sign_only: bool) -> Raw | None:
    """A closed-form Hopf line in float64 with a running error bound, the points it does not
    certify to :data:`REL_BOUND` in compiled double-double (:mod:`landau.codegen.bounded`).

    The default route of ``method="auto"``.  What the double-double bound still leaves in
    doubt (near a zero of a coefficient closer than ~1e-21 relative, Λ ≡ 0) is taken from
    the exactly cancelled form where it exists and is worth it (as in :func:`screened_route`),
    else by :func:`refine_mpmath`.  None (another route is taken) where the formulas use an
    operation without a bounded form, and for batches too small for it (:func:`takes_bounded`)."""
    if not takes_bounded(int(np.prod(shape)), sign_only):
        return None
    varying = _varying(vals)
    kern = bounded_kernels(d, bases, varying)
    if kern is None:
        return None
    size = int(np.prod(shape))
    out, rb, flag = _run_bounded(kern, vals, size, sign_only)
    values = {"kc": out[0].reshape(shape), "W": out[1].reshape(shape)}
    values.update({n: out[2 + j].reshape(shape) for j, n in enumerate(bases)})
    doubtful = flag.reshape(shape)
    rest = doubtful & (rb[1] <= REL_BOUND).reshape(shape) & (values["kc"] > 0) & (values["W"] > 0)
    return settle_exactly(d, Vs, shape, bases, p, exact, values, doubtful, rest)


# --- mpmath ----------------------------------------------------------------------------------
def evaluate_mp_checked(d: "Derivation", V0: float, point: Mapping[str, float], names,
                        sign_estimate: Mapping[str, float] | None = None) -> tuple[dict, bool]:
    """Values at 50 digits, or more where needed.  A coefficient whose values at two
    successive precisions (50, 80, 120, 200, 330, 550 digits) agree to 1e-20 relative is
    settled at the finer one: a tiny but genuine value (e.g. Λ ∝ M at M = 1e-50) is
    cancellation-free once the precision exceeds the orders it lies below its terms.  A
    coefficient that never settles is round-off of an identically vanishing quantity
    (its value keeps shrinking with the precision): it is returned as 0 and flagged.

    ``sign_estimate`` (a sign scan's float values at this point): round-off grows with the
    unit round-off times the same condition number at every precision, so a 50-digit value
    h whose float estimate f (unit round-off ≥ 5e-20) is off by |h − f| is itself off by
    about |h − f|·1e-30.  Where |h − f| ≤ 1e20·|h| (f non-zero) that is below 1e-10·|h|:
    the sign is certain and the 50-digit values are returned without climbing the ladder.
    Round-off of a quantity that vanishes identically, or a genuine value far below its
    terms (|h − f| ~ 1e34·|h|), still climbs it."""
    ladder = MP_LADDER
    if any(x != 0 and abs(math.log10(abs(x))) > EXTREME for x in (V0, *point.values())):
        ladder = ladder + MP_LADDER_EXTREME
    hi = d.evaluate_mp(V0, point, names, dps=ladder[0])
    if sign_estimate is not None and all(
            n in DERIVED or (hi[n] != 0 and sign_estimate.get(n, 0.0) != 0
                             and abs(hi[n] - sign_estimate.get(n, float("nan"))) <= 1e20 * abs(hi[n]))
            for n in names):
        return dict(hi), False
    ref = d.evaluate_mp(V0, point, names, dps=ladder[1])
    degenerate = False
    res = dict(hi)
    tol = mpmath.mpf("1e-20")
    for n in names:
        if n in DERIVED or abs(hi[n] - ref[n]) <= tol * abs(ref[n]):
            continue
        prev, settled = ref[n], None
        for dps in ladder[2:]:
            cur = d.evaluate_mp(V0, point, [n], dps=dps)[n]
            if abs(cur - prev) <= tol * abs(cur):
                settled = cur
                break
            prev = cur
        if settled is not None:
            res[n] = settled
        else:
            res[n] = mpmath.mpf(0)
            degenerate = degenerate or n == "Lambda"
    if "C" in res:      # from the settled Γ̄ and Λ (the 50-digit C used the 50-digit Λ)
        lam = res["Lambda"]
        res["C"] = mpmath.inf if degenerate or lam == 0 else 2 * mpmath.sqrt(2 * res["Gamma_bar"] / abs(lam))
    return res, degenerate


def refine_mpmath(d: "Derivation", out: dict[str, np.ndarray], vals, where: np.ndarray, extra: Sequence[str],
                  sign_only: bool) -> None:
    """The points ``where`` re-evaluated with mpmath (:meth:`Derivation._evaluate_mp_checked`),
    in place in ``out``.

    Used after every route for the points it left doubtful (cancellation near an extremum of
    μ_ss, inertia-free limits, Λ ≡ 0).  Guarantee: values at 50 digits or at the precision
    where two successive ladder steps agree; an identically vanishing Λ is 0 and flagged.
    With ``sign_only`` the route's float estimates let a certain sign stop at 50 digits."""
    idx_all = np.argwhere(where)
    if len(idx_all) >= MP_WARN:
        warn_once((d.block.law.name, "mpmath"), (
            f"{d.block.law.name}: {len(idx_all)} point(s) lose more than 1e-10 to round-off in float64 and long "
            "double (cancellation near an extremum of mu_ss or in an inertia-free limit) and are re-evaluated "
            "with mpmath (about 1 ms each); fewer points in that region, or method='rational' for a law "
            "rational in V, avoid it"))
    elif len(idx_all):
        logger.debug("%s: 50-digit evaluation at %d points", d.block.law.name, len(idx_all))
    for idx in map(tuple, idx_all):
        point = {s.name: float(vals[i + 1][idx]) for i, s in enumerate(d.args[1:])}
        estimate = {n: float(out[n][idx]) for n in extra if n in out} if sign_only else None
        try:
            mp, degenerate = d._evaluate_mp_checked(float(vals[0][idx]), point, extra, estimate)
        except NoHopfError:
            # the float route's Hopf point was round-off (k_c or ω_c² of either sign within its
            # error, at the end of a velocity-weakening range): at 50 digits there is none
            for n in ("kc", "omega_c", *extra):
                if n not in DERIVED:
                    out[n][idx] = np.nan
            out["degenerate"][idx] = False
            continue
        for n in ("kc", "omega_c", *extra):
            if n not in DERIVED:
                out[n][idx] = float(mp[n])
        out["degenerate"][idx] = degenerate


#: smallest normal float64: a value below it (or 0) may be an underflow of a representable quotient
TINY = float(np.finfo(float).tiny)
#: largest float64
HUGE = float(np.finfo(float).max)


def _extreme_params(point: Mapping[str, float]) -> str:
    """The point's parameters far from unity (|log10| ≥ 30), else all of them, as ``a = 1, b = 2``."""
    far = {k: v for k, v in point.items() if v != 0 and abs(np.log10(abs(v))) >= 30}
    return ", ".join(f"{k} = {v:g}" for k, v in (far or point).items())


def _point(d: "Derivation", vals, idx) -> tuple[float, dict[str, float]]:
    return float(vals[0][idx]), {s.name: float(vals[i + 1][idx]) for i, s in enumerate(d.args[1:])}


def rescue_range(d: "Derivation", out: dict[str, np.ndarray], vals, where: np.ndarray, extra: Sequence[str]) -> None:
    """The points ``where`` (a float64 value overflowed, underflowed to 0 or came out NaN
    although the exact value may be representable: k_c = 1.6e304 at σ = 1e300, C = 2e-112 at
    M = 1e200 where Γ̄ = 1e-413 underflows) evaluated with mpmath, whose exponent is unbounded
    (a scaled form), in place in ``out``; derived quantities (C) from the mpmath values too.

    Where mpmath finds no Hopf point the point keeps NaN (no Hopf point).  A value whose exact
    magnitude exceeds float64's range raises :class:`~landau.errors.DomainError` naming the
    quantity, the velocity and the parameters; a value that mpmath cannot give either raises
    :class:`~landau.errors.SingularPointError` (the law is singular there)."""
    from landau.errors import DomainError, NoHopfError

    law = d.block.law.name
    for idx in map(tuple, np.argwhere(where)):
        V0, point = _point(d, vals, idx)
        try:
            mp, degenerate = d._evaluate_mp_checked(V0, point, list(extra))
        except NoHopfError:
            for n in ("kc", "omega_c", *extra):
                out[n][idx] = np.nan
            continue
        for n in ("kc", "omega_c", *extra):
            x = mp[n]
            if n == "C" and degenerate:
                out[n][idx] = np.inf
                continue
            if not mpmath.isfinite(x):
                raise SingularPointError(
                    f"{law}: {n} is not finite at V = {V0:g} m/s although a Hopf point exists there: the "
                    "law's derivatives are singular at this steady state")
            if abs(x) > HUGE:
                raise DomainError(
                    f"{law}: {n} = {mpmath.nstr(x, 6)} {_unit(n)}at V = {V0:g} m/s lies beyond the float64 range "
                    f"(|x| ≤ {HUGE:.3g}) for {_extreme_params(point)}: bring the parameters nearer to their "
                    "physical scale")
            out[n][idx] = float(x)
        out["degenerate"][idx] = degenerate


def _unit(name: str) -> str:
    from landau.derivation.coefficients import UNITS

    return f"{UNITS[name]} " if name in UNITS else ""


def finish(d: "Derivation", Vs, vals, r: Raw, names, bases, sign_only: bool,
           params: dict[str, Any]) -> CoefficientTable:
    """The table of a route's values: NaN where there is no Hopf point, doubtful points from
    :func:`refine_mpmath`, C composed from Γ̄ and Λ.

    Every value returned is finite where a Hopf point exists (only C is infinite, where Λ
    vanishes identically, flagged ``degenerate``): a float64 overflow, an underflow to 0 of
    k_c or ω_c², a NaN from ∞ − ∞, and a C whose Γ̄ or Λ left the normal float64 range are
    evaluated again with mpmath (:func:`rescue_range`); a value beyond float64's range raises
    :class:`~landau.errors.DomainError`, a singular one :class:`~landau.errors.SingularPointError`."""
    shape = r.doubtful.shape
    kc, W_c = r.values["kc"], r.values["W"]
    with np.errstate(all="ignore"):
        ok = (kc > 0) & (W_c > 0) & np.isfinite(kc) & np.isfinite(W_c)
        if d.hopf.closed_form is not None:   # NaN, ±inf or 0 from a closed form: a float64 range problem
            lost = ~np.isfinite(kc) | ~np.isfinite(W_c) | (kc == 0) | (W_c == 0)
        else:                                # the numeric Hopf line gives NaN where there is none
            lost = np.isinf(kc) | np.isinf(W_c)
        out: dict[str, np.ndarray] = {"V": Vs * np.ones(shape), "kc": np.where(ok, kc, np.nan),
                                      "omega_c": np.sqrt(np.where(ok, W_c, np.nan))}
    for n in bases:
        out[n] = np.array(r.values[n], dtype=float)
    out["degenerate"] = r.degenerate & ok
    extra = [n for n in _with_bases(names) if n not in ("kc", "omega_c")]
    refine_mpmath(d, out, vals, r.doubtful & ok & ~lost, extra, sign_only)
    if "C" in names:
        with np.errstate(all="ignore"):
            out["C"] = 2 * np.sqrt(2 * out["Gamma_bar"] / np.abs(out["Lambda"]))
            # a quotient of values outside the normal range (Γ̄ = 1e-413 underflowed at M = 1e200)
            lost |= ok & ~out["degenerate"] & (
                (np.abs(out["Gamma_bar"]) < TINY) | (np.abs(out["Lambda"]) < TINY)
                | ~np.isfinite(out["C"]) | (out["C"] == 0))
    for n in bases:
        lost |= ok & ~np.isfinite(out[n])
    if lost.any():
        for n in extra:
            out.setdefault(n, np.full(shape, np.nan))
        rescue_range(d, out, vals, lost, extra)
    return CoefficientTable(out, law=d.block.law.name, params=params)
