"""Transition velocity V*, codimension-two points, critical residual strength c* (Putelat et al. 2010).

Parameter set: Table 1 (L = 0.9e-6 m, V_* = 1e-6 m/s,
M = 1.2 kg, σ = 11.772 N).  Published numbers are printed with 3–4 digits: 0.5 %
tolerance unless stated (half a unit of the last printed digit or better).
"""

from __future__ import annotations

import io
import json
import math
from contextlib import redirect_stdout

import numpy as np
import pytest

from landau.analyses.transition import (
    codim2_points,
    critical_parameter,
    extrema,
    transition_curve,
    velocity_weakening_ranges,
)
from landau.derivation.multiscale import Derivation
from landau.errors import InputError
from landau.laws import FrictionLaw, get_law
from landau.systems.system import SpringBlock

T1 = dict(a=0.0349, b=0.0489, L=0.9e-6, V_s=1e-6, M=1.2, sigma=11.772)
PRINTED = 5e-3  # 0.5 %: the values are printed with 3-4 significant digits


def rel(x, y):
    return abs(x - y) / abs(y)


_cache: dict[str, Derivation] = {}


def D(name: str) -> Derivation:
    if name not in _cache:
        _cache[name] = Derivation(SpringBlock(get_law(name)))
    return _cache[name]


# --- Dieterich law (Sec. 3.2, Fig. 5b, eq. 34) -------------------------------------
def test_dieterich_codim2_point_fig5b_and_eq34():
    pts = codim2_points(D("dieterich"), 1e-9, 1e-1)
    assert len(pts) == 1
    pt = pts[0]
    # Fig. 5(b): the saddle-node line meets the Hopf line at k ≈ 2.08e5 N/m
    assert rel(pt.kc, 2.08e5) < PRINTED
    # eq. (34) read with V̂ (not the printed √V̂): V_D* = sqrt((−3a + 2 sqrt(a(3a+b)))/(3a+4b)) V̂,
    # V̂ = sqrt(aσL/M) (eq. 31).  Both are exact, so they agree to the root-finder's precision.
    a, b, L, Mm, s = T1["a"], T1["b"], T1["L"], T1["M"], T1["sigma"]
    Vhat = math.sqrt(a * s * L / Mm)
    VD = math.sqrt((-3 * a + 2 * math.sqrt(a * (3 * a + b))) / (3 * a + 4 * b)) * Vhat
    assert rel(pt.V, VD) < 1e-9
    # (33): Λ_D > 0 as V → 0 (subcritical), < 0 as V → ∞
    assert (pt.sign_below, pt.sign_above) == (1, -1)
    # the published velocity 2.31e-5 m/s (Fig. 5 caption) is NOT reproduced (it depends only on gL): V* ≈ 2.07e-4
    assert rel(pt.V, 2.31e-5) > 1.0


def test_dieterich_without_inertia_has_no_transition():
    # eq. (33): Λ_D ≡ 0 for M = 0 — round-off noise must not be reported as codimension-two points
    assert codim2_points(D("dieterich"), 1e-9, 1e-1, {"M": 0.0}) == []


def test_ruina_is_supercritical_everywhere():
    d = D("ruina")
    assert codim2_points(d, 1e-9, 1e-1) == []
    lam = d.evaluate(np.logspace(-9, -1, 400), {}, ["Lambda"])["Lambda"]
    assert np.all(lam < 0)


# --- modified Dieterich law (39), Sec. 4.2, Fig. 13 -----------------------------------
def test_modified_dieterich_V_star_and_V_m():
    d = D("modified-dieterich")
    (pt,) = codim2_points(d, 1e-9, 1e-1, {"c": 3e-4})
    assert rel(pt.V, 1.109e-3) < PRINTED            # Sec. 4.2: V* ≈ 1.109e-3 m/s at c = 3e-4
    assert (pt.sign_below, pt.sign_above) == (-1, 1)  # supercritical below V*, subcritical above
    (ext,) = extrema(d, {"c": 3e-4}, 1e-9, 1e-1)
    assert ext.kind == "minimum"
    assert rel(ext.V, 1.337e-3) < PRINTED           # Sec. 4.2: V_m ≈ 1.337e-3
    # eq. (41): V_m = (b/a − 1) V_*/c exactly — the extremum finder to ~1e-12
    assert rel(ext.V, (T1["b"] / T1["a"] - 1) * T1["V_s"] / 3e-4) < 1e-12
    # the root is refined to full precision: Λ changes sign across V*(1 ± 1e-12)
    lam = d.evaluate(np.array([pt.V * (1 - 1e-12), pt.V * (1 + 1e-12)]), {"c": 3e-4}, ["Lambda"])["Lambda"]
    assert lam[0] < 0 < lam[1]
    # k_c(V*) of eq. (42)
    a, L, Vs, Mm, s, c = T1["a"], T1["L"], T1["V_s"], T1["M"], T1["sigma"], 3e-4
    kc42 = (a * c * s / L) * (ext.V - pt.V) * (1 + Mm * pt.V ** 2 / (a * s * L)) / (Vs + c * pt.V)
    assert rel(pt.kc, kc42) < 1e-9


def _paper_cubic_bounds():
    """Sec. 4.2: cubic a6 c*^6 + a4 c*^4 + a2 c*^2 + a0 = 0 (coefficients printed after Fig. 13)."""
    a, b, L, Vs, Mm, s = T1["a"], T1["b"], T1["L"], T1["V_s"], T1["M"], T1["sigma"]
    a0 = b * (b - a) ** 6 * (2 * b - a) * Vs ** 7 * L ** 2 * Mm ** 3
    a2 = a ** 3 * b * (b - a) ** 4 * (3 * b - 2 * a) * s * Vs ** 5 * L ** 3 * Mm ** 2
    a4 = a ** 6 * b * (b - 2 * a) * (b - a) ** 2 * s ** 2 * Vs ** 3 * L ** 4 * Mm
    a6 = -a ** 10 * b * s ** 3 * Vs * L ** 5
    upper = (a0 / -a4) ** 0.25   # balance a4 c^4 ~ a0
    lower = (a2 / -a6) ** 0.25   # balance a6 c^6 ~ a2 c^2
    roots = np.roots([a6, a4, a2, a0])
    c_cubic = math.sqrt(max(r.real for r in roots if abs(r.imag) < 1e-30 and r.real > 0))
    # the closed-form bounds printed after Fig. 14 are the same balances
    lo_f = ((b - a) ** 4 * (3 * b - 2 * a) * Mm ** 2 * Vs ** 4 / (a ** 7 * s ** 2 * L ** 2)) ** 0.25
    up_f = ((b - a) ** 4 * (2 * b - a) * Mm ** 2 * Vs ** 4 / (a ** 6 * (2 * a - b) * s ** 2 * L ** 2)) ** 0.25
    assert rel(lower, lo_f) < 1e-12 and rel(upper, up_f) < 1e-12
    return lower, upper, c_cubic


def test_critical_residual_strength_c_star():
    d = D("modified-dieterich")
    (cs,) = critical_parameter(d, "c", 1e-4, 2e-3)
    assert cs.end == "upper"
    assert rel(cs.value, 9.02e-4) < PRINTED          # Sec. 4.2/6: c* ≈ 9.02e-4
    assert rel(cs.V_ext, 4.447e-4) < PRINTED         # V_m(c*) ≈ 4.447e-4 m/s
    lower, upper, c_cubic = _paper_cubic_bounds()
    assert rel(lower, 8.80e-4) < PRINTED and rel(upper, 9.52e-4) < PRINTED
    assert lower <= cs.value <= upper
    # independent route: the paper's cubic in c*^2 (from P7[V_m(c*)] = 0) vs the generic
    # edge-slope root (η = 1e-10 bias ⇒ agreement to ~1e-8)
    assert rel(cs.value, c_cubic) < 1e-7


def test_transition_curve_is_the_same_on_two_worker_processes():
    # the values of c are independent points on the sweep engine: 2 local processes give the
    # numbers of this process, bit for bit (and c* of Sec. 4.2)
    one = transition_curve(D("modified-dieterich"), "c", 1e-4, 2e-3, n=6, workers=1)
    two = transition_curve(D("modified-dieterich"), "c", 1e-4, 2e-3, n=6, workers=2)
    assert repr(two.as_dict()) == repr(one.as_dict())
    assert rel(two.critical_value, 9.02e-4) < PRINTED
    assert len(two.rows) > 6


def test_V_star_curve_fig13b():
    d = D("modified-dieterich")
    curve = transition_curve(d, "c", 1e-6, 2e-3, n=16)
    cstar = curve.critical_value
    assert cstar is not None and rel(cstar, 9.02e-4) < PRINTED
    # the branch that ends on V_m: the largest V* at each c (for small c the Dieterich-like
    # pair of codimension-two points at lower V also exists, see transition.py docs)
    top: dict[float, tuple[float, float]] = {}
    for r in curve.rows:
        if r.kc > 0 and (r.value not in top or r.V_star > top[r.value][0]):
            top[r.value] = (r.V_star, r.V_ext)
    cs = np.array(sorted(top))
    assert np.all(cs < cstar) and len(cs) >= 12
    Vst = np.array([top[c][0] for c in cs])
    Vm = np.array([top[c][1] for c in cs])
    assert np.all(Vst < Vm)                            # V* < V_m(c) for all c < c*
    # V* ∝ 1/c for small c: log-log slope −1 within 1 %
    small = cs < 2e-5
    slope = np.polyfit(np.log(cs[small]), np.log(Vst[small]), 1)[0]
    assert abs(slope + 1) < 0.01
    # no codimension-two point above c* (Fig. 13b: V* undefined)
    assert codim2_points(d, 1e-9, 1e-1, {"c": 1.2 * cstar}) == []


def test_velocity_weakening_range_errors():
    strengthening = FrictionLaw.from_strings("vs", mu="a_v + a*log(v/V_s) + b*log(V_s*phi/L)",
                                             state={"phi": "1 - v*phi/L"}, params={"b": 0.01})
    d = Derivation(SpringBlock(strengthening))
    with pytest.raises(InputError, match="no velocity-weakening"):
        velocity_weakening_ranges(d)
    assert codim2_points(d, 1e-9, 1e-1) == []
    with pytest.raises(InputError):
        codim2_points(d, 1e-3, 1e-5)


# --- spinodal law (37)-(38), Sec. 4, Figs 8-10 ---------------------------------------
def test_spinodal_c_crit_sec41():
    a, b, L, Vs, Mm, s = T1["a"], T1["b"], T1["L"], T1["V_s"], T1["M"], T1["sigma"]
    c_crit = (b / a - 1) * Vs / math.sqrt(L * a * s / Mm)
    assert rel(c_crit, 7.2e-4) < PRINTED
    # meaning: at c_crit the minimum V_m of μ_ss sits at V̂ (eq. 31) — checked with the
    # extremum finder on the full law (V_m ≈ (1 + 1/R)(b/a − 1)V_*/c, R = 100 ⇒ 1 %)
    ext = [e for e in extrema(D("spinodal"), {"c": c_crit}) if e.kind == "minimum"]
    assert len(ext) == 1 and rel(ext[0].V, math.sqrt(a * s * L / Mm)) < 0.015
    # Sec. 4.1 prints V_M = 2.493e-8 and V_m = 4.052e-4 for c = 1e-3
    ranges = velocity_weakening_ranges(D("spinodal"), {"c": 1e-3})
    assert len(ranges) == 1 and ranges[0].lo_extremum and ranges[0].hi_extremum
    assert rel(ranges[0].lo, 2.493e-8) < PRINTED and rel(ranges[0].hi, 4.052e-4) < PRINTED


def _lambda_on_range(d, params, n=600):
    (r,) = velocity_weakening_ranges(d, params)
    t = np.linspace(1e-6, 1 - 1e-6, n)
    Vs = np.exp(np.log(r.lo) + t * (np.log(r.hi) - np.log(r.lo)))
    return Vs, d.evaluate(Vs, params, ["Lambda"])["Lambda"], r


def test_spinodal_lambda_signs_figs_8_to_10():
    d = D("spinodal")
    # Fig. 8(d): c = 1e-3, Λ ≤ 0 on all of (V_M, V_m)
    _, lam, _ = _lambda_on_range(d, {"c": 1e-3})
    assert np.all(lam <= 0)
    assert codim2_points(d, 1e-9, 1e-1, {"c": 1e-3}) == []
    # Figs 9(b), 10(d): c = 3e-4, Λ > 0 in a narrow band just below V_m ...
    (pt,) = codim2_points(d, 1e-9, 1e-1, {"c": 3e-4})
    Vs, lam, r = _lambda_on_range(d, {"c": 3e-4})
    assert (pt.sign_below, pt.sign_above) == (-1, 1)
    assert np.all(lam[Vs > pt.V] > 0) and np.all(lam[Vs < pt.V] <= 0)
    assert math.log10(r.hi / pt.V) < 0.1 * math.log10(r.hi / r.lo)  # the band is < 10 % of the range (log)
    # ... and Λ ≤ 0 everywhere without inertia (Fig. 10d)
    _, lam0, _ = _lambda_on_range(d, {"c": 3e-4, "M": 0.0})
    assert np.all(lam0 <= 0)
    assert codim2_points(d, 1e-9, 1e-1, {"c": 3e-4, "M": 0.0}) == []


def test_spinodal_transition_only_below_critical_c():
    # Figs 9-10: the transition velocity exists for c = 3e-4, not for c = 1e-3; the critical c
    # of the full spinodal law lies between, close to the c* ≈ 9.02e-4 of its approximation (39)
    (cs,) = critical_parameter(D("spinodal"), "c", 2e-4, 2e-3, n=12)
    assert 3e-4 < cs.value < 1e-3
    assert rel(cs.value, 9.02e-4) < 0.02


# --- Sec. 5: nanoscale (48) and micron-scale (50) laws ------------------------------
def test_nanoscale_two_transitions_fig15_16():
    pts = codim2_points(D("nanoscale"), 1e-9, 1e-1)
    assert len(pts) == 2
    assert rel(pts[0].V, 6.24e-6) < PRINTED and rel(pts[1].V, 3.41e-4) < PRINTED
    # Fig. 16 caption also prints log10(V*/V_*) ≈ 0.7953 and 2.533
    assert abs(math.log10(pts[0].V / 1e-6) - 0.7953) < 2e-3
    assert abs(math.log10(pts[1].V / 1e-6) - 2.533) < 2e-3
    assert [(p.sign_below, p.sign_above) for p in pts] == [(1, -1), (-1, 1)]


def test_micron_scale_two_transitions_fig17_18():
    pts = codim2_points(D("micron-scale"), 1e-9, 1e-1, {"c": 1.4e-2})
    assert len(pts) == 2
    assert rel(pts[0].V, 1.039e-5) < PRINTED and rel(pts[1].V, 2.07e-4) < PRINTED
    # Fig. 18 caption: log10(V*/V_*) ≈ 1.01679 and 2.3179 (more digits than the velocities)
    assert abs(math.log10(pts[0].V / 1e-6) - 1.01679) < 2e-4
    assert abs(math.log10(pts[1].V / 1e-6) - 2.3179) < 2e-4


# --- CLI --------------------------------------------------------------------------
def test_cli_transition_json():
    from landau.cli import main

    buf = io.StringIO()
    with redirect_stdout(buf):
        code = main(["transition", "modified-dieterich", "--vary", "c=1e-4:2e-3", "--points", "6", "--json"])
    assert code == 0
    doc = json.loads(buf.getvalue())
    assert rel(doc["critical_value"], 9.02e-4) < PRINTED
    assert all({"c", "V_star", "kc"} <= set(r) for r in doc["curve"])
    assert any(r["kc"] > 0 for r in doc["curve"])


@pytest.mark.parametrize("argv", [["transition", "modified-dieterich"],
                                  ["transition", "modified-dieterich", "--vary", "q=1:2"],
                                  ["transition", "modified-dieterich", "--vary", "c=2e-3:1e-4"],
                                  ["transition", "modified-dieterich", "--vary", "c=-1:1"],
                                  ["transition", "modified-dieterich", "--vary", "c=1e-4:2e-3", "--workers", "0"]])
def test_cli_transition_bad_input(argv, capsys):
    from landau.cli import main

    assert main(argv) == 2
    assert "error" in capsys.readouterr().err


# --- regime diagram (Fig. 14a) -----------------------------------------------------
def test_regime_diagram_split_and_quasi_static_comparison():
    from landau.analyses.regimes import regime_diagram

    d = D("spinodal")
    V = np.logspace(-7.5, math.log10(1.35e-3), 300)
    g = regime_diagram(d, V, {"c": 3e-4})
    (pt,) = g.codim2
    sub = np.isfinite(g.subcritical)
    assert np.all(V[sub] > pt.V) and np.any(sub)           # subcritical only above V*
    assert np.all(np.isfinite(g.supercritical[np.isfinite(g.kc) & (V < pt.V)]))
    # inertial boundary Mω_c² below the Hopf line at the transition point: creep domain (Sec. 4.2)
    i = int(np.argmin(np.abs(V - pt.V)))
    assert g.inertial_boundary[i] < g.kc[i]
    g0 = regime_diagram(d, V, {"c": 3e-4, "M": 0.0})
    assert not np.any(np.isfinite(g0.subcritical)) and g0.codim2 == ()
    assert np.all(g0.inertial_boundary[np.isfinite(g0.kc)] == 0.0)


def test_codim2_sign_scan_does_not_fall_back_to_mpmath(monkeypatch):
    # the scan needs only the sign of Lambda: points near V_m that are doubtful beyond 1e-10 but
    # certain in sign are settled in extended precision, not by the 50/80-digit route
    from landau.analyses import transition as tr

    calls = []
    orig = Derivation._evaluate_mp_checked

    def counted(self, *args, **kw):
        calls.append(args[0])
        return orig(self, *args, **kw)

    monkeypatch.setattr(Derivation, "_evaluate_mp_checked", counted)
    d = Derivation(SpringBlock(get_law("micron-scale")))
    pts = codim2_points(d, 1e-9, 1e-1)
    assert calls == []
    # the two transitions of the micron-scale law (Putelat et al. 2010, Fig. 17) as computed at
    # full accuracy (README: 1.0395e-5 and 2.0794e-4 m/s)
    assert len(pts) == 2 and all(rel(p.V, v) < 1e-4 for p, v in zip(pts, (1.0395e-5, 2.0794e-4), strict=True))
    # the same scan at full accuracy does need the 50/80-digit route (so the count above can fail),
    # and the sign-only values agree in sign with those accurate values everywhere
    p = d.block.resolve(None)
    ext = extrema(d, p, 1e-9 / 1.01, 1e-1 * 1.01)
    grid = tr._scan_grid(1e-9, 1e-1, ext, 200)
    fast = d.evaluate(grid, p, ["Lambda"], sign_only=True)["Lambda"]
    assert calls == []
    # the float32-screen + long double route ("general") settles its doubtful points there (so the
    # count above can fail); the default route of a batch this size (float64 with an error bound,
    # double-double where the bound is too wide) certifies them without it
    full = d.evaluate(grid, p, ["Lambda"], method="general")["Lambda"]
    assert len(calls) > 0
    n_general = len(calls)
    bounded = d.evaluate(grid, p, ["Lambda"])["Lambda"]
    assert len(calls) == n_general
    both = np.isfinite(full) & np.isfinite(bounded)
    assert np.all(np.abs(bounded[both] - full[both]) <= 1e-10 * np.abs(full[both]))
    finite = np.isfinite(full)
    assert np.array_equal(np.sign(fast[finite]), np.sign(full[finite]))
