"""Where the stick–slip Hopf bifurcation changes nature: V*(p), the critical p*, and V_m(p).

Putelat et al. (2010), Secs 3.2, 4.2 and 5.  On the Hopf line k = k_c(V) > 0 the Landau
coefficient Λ(V) (eq. 21) decides the criticality (Λ < 0 supercritical).  A velocity V*
where Λ changes sign is a codimension-two point (Bautin point) of the (V, k) plane —
eq. (34) for the Dieterich law, the zero of P₇ (eq. 45) for the modified Dieterich law
(39), V_l*, V_h* of Figs 15–18.  The ends of a velocity-weakening range, where
k_c → 0 at an extremum of μ_ss (V_M, V_m), are *not* codimension-two points even though
Γ and Λ vanish there too.

* :func:`velocity_weakening_ranges` — the extrema of μ_ss(V) (eq. 40/41 for law 39)
  and the ranges where dμ_ss/dV < 0, found by a sign scan of dμ_ss/dV on a log grid and
  refined with brentq.
* :func:`codim2_points` — every sign change of Λ on the Hopf line in [lo, hi]: a log
  grid plus points clustered geometrically towards each extremum (the subcritical band
  just below V_m can be very narrow), refined with brentq on the compiled Λ (the engine
  switches to 50-digit mpmath where ω_c² is ill-conditioned, near V_m); each bracket is
  confirmed with a 50-digit evaluation, so round-off noise of a coefficient that vanishes
  identically (Dieterich with M = 0) is never reported as a transition.
* :func:`critical_parameter` — the value p* of a law parameter at which a codimension-two
  point reaches an extremum of μ_ss and disappears (c* of Sec. 4.2): generically, the
  root in p of the sign of Λ just inside the extremum, Λ(V_m(p)(1 − η); p), η = 1e-10,
  evaluated with 50 digits.  Since Λ ∝ (V − V_m)·P(V) near V_m, this is the root of
  P(V_m(p)) — for law (39) exactly the paper's condition P₇[V_m(c*)] = 0.
* :func:`transition_curve` — V*(p) and k_c(V*(p)) over a range of p, ending at p*.

Finding (law 39, Table 1): for small c (c ≲ 1e-4) there are three codimension-two
points, not one: besides V* ∝ 1/c (Fig. 13b) the Dieterich-like point near 2e-4 m/s and a
low one at V ≈ a²cσL/((b − a)V_* M) ≈ 0.77c m/s (the balance of the two lowest-order
terms of P₇); the lower two merge and disappear between c ≈ 8e-5 and 1.2e-4.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any, Mapping, Sequence

import mpmath
import numpy as np
from scipy.optimize import brentq

from landau.analyses.codim2 import SPRING_BLOCK_PARAMETERS, GeneralisedHopfPoint
from landau.derivation.multiscale import Derivation
from landau.errors import InputError, NoHopfError

#: relative distance from an extremum of μ_ss where Λ's sign "at the extremum" is read (critical_parameter)
EDGE_ETA = 1e-10
#: closest relative approach to an extremum when scanning for sign changes of Λ
_CLUSTER_MIN = 1e-10
#: digits of the confirming evaluation
_DPS = 50


# --------------------------------------------------------------------------------------
# results
@dataclass(frozen=True)
class Extremum:
    """An extremum of the steady-state friction coefficient μ_ss(V) (k_c = 0 there)."""

    V: float
    kind: str  # "minimum" (V_m, weakening below / strengthening above) or "maximum" (V_M)
    mu: float

    def __repr__(self) -> str:
        return f"Extremum({self.kind} of mu_ss at V={self.V:.6g} m/s, mu_ss={self.mu:.6g})"


@dataclass(frozen=True)
class WeakeningRange:
    """A velocity range where dμ_ss/dV < 0.  ``lo_extremum``/``hi_extremum`` tell whether
    an end is an extremum of μ_ss (k_c → 0 there) or just the end of the scanned interval."""

    lo: float
    hi: float
    lo_extremum: bool
    hi_extremum: bool

    def __contains__(self, V: float) -> bool:
        return self.lo <= V <= self.hi

    def __repr__(self) -> str:
        lo = f"{self.lo:.6g}" + (" (V_M)" if self.lo_extremum else " (scan end)")
        hi = f"{self.hi:.6g}" + (" (V_m)" if self.hi_extremum else " (scan end)")
        return f"WeakeningRange({lo} .. {hi} m/s)"


@dataclass(frozen=True)
class CriticalValue:
    """p* where a codimension-two point meets the extremum ``V_ext`` of μ_ss and disappears."""

    name: str
    value: float
    V_ext: float
    end: str  # "upper" (V_m, the minimum of μ_ss) or "lower" (V_M, the maximum)

    def as_dict(self) -> dict[str, Any]:
        return {"name": self.name, "value": self.value, "V_ext": self.V_ext, "end": self.end}

    def __repr__(self) -> str:
        return f"CriticalValue({self.name}*={self.value:.8g}, V_ext={self.V_ext:.8g} m/s at the {self.end} end)"


@dataclass(frozen=True)
class TransitionRow:
    value: float
    V_star: float
    kc: float
    omega_c: float
    V_ext: float  # the extremum V_m(p) that closes the range containing V*

    @property
    def k_c(self) -> float:
        """The critical stiffness k_c(V*) (N/m) (the field ``kc``)."""
        return self.kc


@dataclass(frozen=True)
class TransitionCurve:
    """V*(p), k_c(V*(p)) over p (Fig. 13b, Fig. 14a), with the critical values p*."""

    name: str
    rows: tuple[TransitionRow, ...]
    critical: tuple[CriticalValue, ...]
    values: tuple[float, ...]  # the p grid that was scanned

    @property
    def critical_value(self) -> float | None:
        ups = [c for c in self.critical if c.end == "upper"] or list(self.critical)
        return ups[0].value if ups else None

    def as_dict(self) -> dict[str, Any]:
        return {"critical_value": self.critical_value,
                "critical_values": [c.as_dict() for c in self.critical],
                "curve": [{self.name: r.value, "V_star": r.V_star, "k_c": r.kc, "kc": r.kc, "omega_c": r.omega_c,
                           "V_ext": r.V_ext} for r in self.rows]}

    def __repr__(self) -> str:
        cv = self.critical_value
        return (f"TransitionCurve({self.name}: {len(self.rows)} points over {len(self.values)} values, "
                f"critical {self.name}*={'none' if cv is None else f'{cv:.6g}'})")


# --------------------------------------------------------------------------------------
# velocity-weakening ranges
def _dmu(d: Derivation):
    """Compiled (μ_ss, dμ_ss/dV) (vectorised) for the block of ``d``; InputError when the law
    has no closed-form steady state."""
    return d.hopf._compiled_mu


def extrema(d: Derivation, params: Mapping[str, float] | None = None, lo: float = 1e-12, hi: float = 1e2,
            per_decade: int = 60) -> list[Extremum]:
    """Every extremum of μ_ss(V) in [lo, hi] (brentq on dμ_ss/dV in log V)."""
    if not (0 < lo < hi):
        raise InputError(f"velocity range must satisfy 0 < lo < hi, got {lo!r}:{hi!r}")
    p = d.block.resolve(params)
    fmu, fdmu = _dmu(d)
    n = max(int(per_decade * math.log10(hi / lo)), 16)
    Vs = np.logspace(math.log10(lo), math.log10(hi), n)
    vals = d.block.argvals(Vs, p)
    g = np.asarray(fdmu(*vals), dtype=float) * Vs  # V dμ/dV: O(a) scale over decades

    def gs(logV: float) -> float:
        V0 = math.exp(logV)
        return float(fdmu(*d.block.argvals(np.float64(V0), p))) * V0

    out = []
    for i in range(n - 1):
        if not (np.isfinite(g[i]) and np.isfinite(g[i + 1])) or g[i] * g[i + 1] >= 0:
            continue
        xa, xb = math.log(Vs[i]), math.log(Vs[i + 1])
        if gs(xa) * gs(xb) >= 0:  # a grid end sitting on the extremum itself: round-off sign
            continue
        r = brentq(gs, xa, xb, xtol=1e-15, rtol=8.9e-16, maxiter=200)
        Ve = math.exp(r)
        mu = float(fmu(*d.block.argvals(np.float64(Ve), p)))
        out.append(Extremum(Ve, "minimum" if g[i] < 0 else "maximum", mu))
    return out


def velocity_weakening_ranges(d: Derivation, params: Mapping[str, float] | None = None,
                              lo: float = 1e-12, hi: float = 1e2) -> list[WeakeningRange]:
    """The ranges of [lo, hi] where μ_ss decreases (dμ_ss/dV < 0), ends at extrema refined.

    Raises :class:`InputError` when the law has no velocity-weakening branch in [lo, hi]
    (steady sliding is then linearly stable for every stiffness)."""
    ranges = _weakening(d, params, lo, hi)
    if not ranges:
        raise InputError(f"law {d.block.law.name!r} has no velocity-weakening branch (dmu_ss/dV < 0) "
                         f"in [{lo:g}, {hi:g}] m/s: steady sliding is stable for every stiffness, "
                         "there is no Hopf bifurcation")
    return ranges


def _weakening(d: Derivation, params, lo: float, hi: float) -> list[WeakeningRange]:
    p = d.block.resolve(params)
    fmu, fdmu = _dmu(d)
    ext = extrema(d, p, lo, hi)
    edges = [lo, *[e.V for e in ext], hi]
    out = []
    for a, b in zip(edges[:-1], edges[1:], strict=True):
        mid = math.sqrt(a * b)
        s = float(fdmu(*d.block.argvals(np.float64(mid), p)))
        if np.isfinite(s) and s < 0:
            out.append(WeakeningRange(a, b, a != lo, b != hi))
    return out


# --------------------------------------------------------------------------------------
# codimension-two points
def _lam(d: Derivation, p: Mapping[str, float], V0: float) -> float:
    """Λ for a root bracket: only its sign matters (mpmath only where the sign is uncertain)."""
    return float(d.evaluate(np.array([V0]), p, ["Lambda"], sign_only=True)["Lambda"][0])


def _lam_mp(d: Derivation, p: Mapping[str, float], V0) -> mpmath.mpf | None:
    try:
        return d.evaluate_mp(V0, p, ["Lambda"], dps=_DPS)["Lambda"]
    except NoHopfError:
        return None


def _confirmed(d: Derivation, p, Va: float, la: float, Vb: float, lb: float) -> bool:
    """Both bracket values confirmed in sign and size at 50 digits — round-off noise of an
    identically vanishing Λ fails this.  The scan's values are certain in sign, with an error
    below a tenth of their size (``sign_only``), hence the 0.2 relative tolerance."""
    for V0, lf in ((Va, la), (Vb, lb)):
        lm = _lam_mp(d, p, V0)
        if lm is None or lm == 0 or abs(float(lm) - lf) > 0.2 * abs(float(lm)):
            return False
    return True


def _scan_grid(lo: float, hi: float, ext: Sequence[Extremum], per_decade: int) -> np.ndarray:
    n = max(int(per_decade * math.log10(hi / lo)), 32)
    grid = np.logspace(math.log10(lo), math.log10(hi), n)
    cluster = 10.0 ** -np.linspace(1.0, -math.log10(_CLUSTER_MIN), 30)
    extra = []
    for e in ext:
        # stay clear of the extremum itself: k_c changes sign there
        grid = grid[np.abs(grid / e.V - 1.0) > 1e-3]
        extra += [e.V * (1 - cluster), e.V * (1 + cluster)]
    if extra:
        grid = np.concatenate([grid, *extra])
    grid = grid[(grid >= lo) & (grid <= hi)]
    return np.unique(grid)


def codim2_points(derivation: Derivation, lo: float, hi: float,
                  params: Mapping[str, float] | None = None, *, per_decade: int = 200) -> list[GeneralisedHopfPoint]:
    """Every velocity in [lo, hi] where Λ changes sign on the Hopf line (k_c > 0).

    Not the ends of a velocity-weakening range (k_c → 0 there).  Roots are refined with
    brentq to ~1e-15 relative in V on the compiled Λ (50-digit mpmath near V_m); each
    sign change is confirmed at 50 digits before it is reported.  Each point is a
    :class:`~landau.analyses.codim2.GeneralisedHopfPoint` with p₁ = k_c, p₂ = V and the signs of Λ
    below and above (:func:`landau.analyses.bautin.bautin_point` adds Λ₅, l₂ and the fold of cycles)."""
    if not (np.isfinite(lo) and np.isfinite(hi) and 0 < lo < hi):
        raise InputError(f"codim2: need 0 < LO < HI (m/s), got {lo!r}:{hi!r}")
    d = derivation
    p = d.block.resolve(params)
    # widened a little so that an extremum sitting on LO or HI is still found (and avoided)
    ext = extrema(d, p, lo / 1.01, hi * 1.01) if d.hopf.closed_form is not None else []
    Vs = _scan_grid(lo, hi, ext, per_decade)
    # a sign scan: values uncertain beyond 1e-10 but certain in sign are not sent to mpmath
    res = d.evaluate(Vs, p, ["Lambda"], sign_only=True)
    kc, lam = res["kc"], res["Lambda"]
    ok = np.isfinite(kc) & (kc > 0) & np.isfinite(lam)
    out: list[GeneralisedHopfPoint] = []
    for i in range(len(Vs) - 1):
        if not (ok[i] and ok[i + 1]) or lam[i] * lam[i + 1] >= 0:
            continue
        Va, Vb = float(Vs[i]), float(Vs[i + 1])
        if not _confirmed(d, p, Va, float(lam[i]), Vb, float(lam[i + 1])):
            continue
        r = brentq(lambda x: _lam(d, p, math.exp(x)), math.log(Va), math.log(Vb),
                   xtol=1e-16, rtol=8.9e-16, maxiter=300)
        Vr = math.exp(r)
        at = d.evaluate(np.array([Vr]), p, ["kc", "omega_c"])
        out.append(GeneralisedHopfPoint(d.block.law.name, SPRING_BLOCK_PARAMETERS, float(at["kc"][0]), Vr,
                                        float(at["omega_c"][0]), sign_below=int(np.sign(lam[i])),
                                        sign_above=int(np.sign(lam[i + 1]))))
    return out


# --------------------------------------------------------------------------------------
# continuation in a law parameter
def _check_param(d: Derivation, name: str) -> None:
    names = [s.name for s in d.block.args[1:]]
    if name not in names:
        raise InputError(f"law {d.block.law.name!r} has no parameter {name!r} (known: {', '.join(names)})")


def edge_sign_function(d: Derivation, params: Mapping[str, float], ext: Extremum, inside: int) -> float:
    """Λ(V_ext(1 + inside·η)) / η at 50 digits (η = EDGE_ETA): the slope of Λ at the extremum,
    read from inside the weakening range (inside = −1 below V_m, +1 above V_M)."""
    with mpmath.workdps(_DPS):
        V0 = mpmath.mpf(ext.V) * (1 + inside * mpmath.mpf(EDGE_ETA))
        lm = _lam_mp(d, params, V0)
    if lm is None:
        raise NoHopfError(f"no Hopf point just inside the extremum V = {ext.V:g} m/s")
    return float(lm) / EDGE_ETA


def _edge_values(d: Derivation, params, lo: float, hi: float) -> dict[str, tuple[Extremum, float]]:
    """{'upper'/'lower': (extremum, edge slope of Λ)} for the extremum-ends of the weakening ranges."""
    out: dict[str, tuple[Extremum, float]] = {}
    ranges = _weakening(d, params, lo, hi)
    for r in ranges:
        if r.hi_extremum and "upper" not in out:
            e = Extremum(r.hi, "minimum", float("nan"))
            out["upper"] = (e, edge_sign_function(d, params, e, -1))
        if r.lo_extremum and "lower" not in out:
            e = Extremum(r.lo, "maximum", float("nan"))
            out["lower"] = (e, edge_sign_function(d, params, e, +1))
    return out


def _grid(lo: float, hi: float, n: int) -> np.ndarray:
    if lo > 0 and hi / lo >= 10:
        return np.logspace(math.log10(lo), math.log10(hi), n)
    return np.linspace(lo, hi, n)


def _sweep(d: Derivation, name: str, lo: float, hi: float, params, n: int) -> tuple[dict, np.ndarray]:
    """Checked arguments of a sweep in the law parameter ``name``: the fixed parameters and the grid."""
    _check_param(d, name)
    if not (lo < hi):
        raise InputError(f"--vary {name}: need LO < HI, got {lo!r}:{hi!r}")
    return dict(params or {}), _grid(lo, hi, n)


def _shared(d: Derivation):
    """``d`` as a :class:`~landau.analyses.sweep_points.Shared` reference: local workers inherit it,
    other executors rebuild it from the law's declaration."""
    from functools import partial

    from landau.analyses.sweep_points import Shared
    from landau.analyses.sweep_tasks import LawSpec

    try:
        recipe = partial(_rebuild, LawSpec.of(d.block.law), tuple(d.block.terms))
    except Exception:  # noqa: BLE001 - a law without a declaration: local processes only
        recipe = None
    return Shared(d, recipe)


def _rebuild(spec, terms: tuple[str, ...]) -> Derivation:
    from landau.systems.system import SpringBlock

    return Derivation(SpringBlock(spec.build(), terms))


def _edge_point(_ref, _base: dict, _name: str, _vrange: tuple[float, float], **point: float) -> dict[str, float]:
    """One value of the grid of :func:`critical_parameter`: the edge slopes of Λ (:func:`_edge_values`)."""
    d = _ref.get()
    prm = d.block.resolve({**_base, _name: point[_name]})
    ev = _edge_values(d, prm, *_vrange)
    out: dict[str, float] = {}
    for end in ("upper", "lower"):
        e = ev.get(end)
        out[f"{end}_found"] = 0.0 if e is None else 1.0
        out[f"{end}_V"] = math.nan if e is None else e[0].V
        out[f"{end}_slope"] = math.nan if e is None else e[1]
    return out


def critical_parameter(derivation: Derivation, name: str, lo: float, hi: float,
                       params: Mapping[str, float] | None = None, *, n: int = 24,
                       V_range: tuple[float, float] = (1e-12, 1e2), workers: int | None = 1,
                       executor=None) -> list[CriticalValue]:
    """Every p* in [lo, hi] where a codimension-two point meets an extremum of μ_ss (c* of Sec. 4.2).

    Generic: the roots in p of the edge slope of Λ at each extremum end (see
    :func:`edge_sign_function`), bracketed on an ``n``-point grid (independent points, run on the
    sweep engine: ``workers`` local processes or ``executor``, same numbers for any) and refined
    with brentq (a sequential root search, in this process)."""
    from landau.analyses.sweep_points import map_points

    d = derivation
    base, ps = _sweep(d, name, lo, hi, params, n)
    with _shared(d) as ref:
        pts = map_points(_edge_point, {name: ps}, workers=workers, executor=executor,
                         fixed={"_ref": ref, "_base": base, "_name": name, "_vrange": tuple(V_range)})
    table = []
    for pt in pts:
        table.append({end: (Extremum(float(pt[f"{end}_V"]), "minimum" if end == "upper" else "maximum",
                                     float("nan")), float(pt[f"{end}_slope"]))
                      for end in ("upper", "lower") if pt[f"{end}_found"] == 1.0})
    out: list[CriticalValue] = []
    for end in ("upper", "lower"):
        for i in range(len(ps) - 1):
            a, b = table[i].get(end), table[i + 1].get(end)
            if a is None or b is None or a[1] * b[1] >= 0:
                continue

            def f(x: float, end: str = end) -> float:
                prm = d.block.resolve({**base, name: x})
                ev = _edge_values(d, prm, *V_range).get(end)
                if ev is None:
                    raise NoHopfError(f"the {end} extremum disappeared at {name} = {x:g}")
                return ev[1]

            root = brentq(f, float(ps[i]), float(ps[i + 1]), xtol=1e-14 * abs(ps[i]), rtol=1e-13, maxiter=200)
            prm = d.block.resolve({**base, name: root})
            ev = _edge_values(d, prm, *V_range)[end]
            out.append(CriticalValue(name, root, ev[0].V, end))
    return sorted(out, key=lambda c: c.value)


def _curve_point(_ref, _base: dict, _name: str, _vrange: tuple[float, float], **point: float) -> dict[str, Any]:
    """One value of :func:`transition_curve`: its codimension-two points and the extremum closing each range."""
    d = _ref.get()
    prm = d.block.resolve({**_base, _name: point[_name]})
    ranges = _weakening(d, prm, *_vrange)
    rows = []
    if ranges:
        for pt in codim2_points(d, ranges[0].lo, ranges[-1].hi, prm, per_decade=120):
            rng = next((r for r in ranges if pt.V in r), None)
            V_ext = rng.hi if (rng is not None and rng.hi_extremum) else float("nan")
            rows.append((pt.V, pt.kc, pt.omega_c, V_ext))
    cols = list(zip(*rows, strict=True)) if rows else [(), (), (), ()]
    return {"rows": float(len(rows)), "V_star": cols[0], "kc": cols[1], "omega_c": cols[2], "V_ext": cols[3]}


def transition_curve(derivation: Derivation, name: str, lo: float, hi: float,
                     params: Mapping[str, float] | None = None, *, n: int = 40,
                     V_range: tuple[float, float] = (1e-12, 1e2), workers: int | None = 1,
                     executor=None) -> TransitionCurve:
    """V*(p) (every codimension-two point) and k_c(V*) on an ``n``-point grid of p in [lo, hi],
    plus the critical values p* where a branch ends on an extremum of μ_ss (there V* = V_m(p*),
    k_c = 0; that end point closes the curve).

    The values of p are independent points, run on the sweep engine (``workers`` local processes
    — 1: this process; None: one per CPU — or any ``executor``); the numbers do not depend on it."""
    from landau.analyses.sweep_points import map_points

    d = derivation
    base, ps = _sweep(d, name, lo, hi, params, n)
    crit = critical_parameter(d, name, lo, hi, base, n=max(n // 2, 8), V_range=V_range, workers=workers,
                              executor=executor)
    values = sorted({*map(float, ps), *(c.value for c in crit)})
    ends = {c.value for c in crit}
    inner = [pv for pv in values if pv not in ends]
    found: dict[float, dict[str, Any]] = {}
    if inner:
        with _shared(d) as ref:
            pts = map_points(_curve_point, {name: inner}, workers=workers, executor=executor,
                             fixed={"_ref": ref, "_base": base, "_name": name, "_vrange": tuple(V_range)})
        found = dict(zip(inner, pts, strict=True))
    rows: list[TransitionRow] = []
    for pv in values:
        for c in crit:
            if c.value == pv:
                rows.append(TransitionRow(pv, c.V_ext, 0.0, float("nan"), c.V_ext))
        if pv in ends:
            continue
        pt = found[pv]
        for j in range(int(pt["rows"])):
            rows.append(TransitionRow(pv, float(pt["V_star"][j]), float(pt["kc"][j]), float(pt["omega_c"][j]),
                                      float(pt["V_ext"][j])))
    return TransitionCurve(name, tuple(rows), tuple(crit), tuple(map(float, ps)))
