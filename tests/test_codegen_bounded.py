"""The compiled Λ(V) kernel with round-off bounds (landau.bounded) and the values it proves.

Every reference is an independent 50-digit mpmath evaluation of the same formulas
(``Derivation.evaluate_mp``) or a closed form evaluated in mpmath; the tolerance 1e-10 is the
accuracy ``Derivation.evaluate`` promises for every returned value.
"""

import mpmath
import numpy as np
import pytest
import sympy as sp

from landau.errors import NoHopfError
from landau.bounded import EXTENDED, BoundedKernel, evaluate_proven
from landau.laws import get_law
from landau.multiscale import derive
from landau.system import SpringBlock
from vw_ranges import LAWS, vw_range

GENERAL = ("spinodal", "nanoscale", "micron-scale")   # laws not rational in V: the compiled route


@pytest.fixture(autouse=True)
def _bounded_route_on_small_grids(monkeypatch):
    # Derivation.evaluate compiles the bounded program only for large grids (or when it is
    # cached); these tests check that program's values on small grids, so they always take it
    import landau.multiscale

    monkeypatch.setattr(landau.multiscale, "BOUNDED_MIN_POINTS", 0)


def _cancelling(x):
    """((1 + x) − 1)/x, exactly 1, kept unsimplified (float64 loses ~|log10 x| digits)."""
    diff = sp.Add(sp.Add(sp.Integer(1), x, evaluate=False), sp.Integer(-1), evaluate=False)
    return sp.Mul(diff, sp.Pow(x, -1, evaluate=False), evaluate=False)


def _rel_err(got, want) -> float:
    with mpmath.workdps(50):
        return float(abs(mpmath.mpf(float(got)) - want) / abs(want))


def _velocities(name: str, n_range: int, n_edge: int) -> np.ndarray:
    """Log-spaced points over the velocity-weakening range and points approaching each end
    that is an extremum of μ_ss (relative distance 1e-8 … 1e-2, where k_c, Γ, Λ → 0/0)."""
    lo, hi, ends = vw_range(name)
    inner = np.logspace(np.log10(lo * (1 + 1e-8) if lo in ends else lo),
                        np.log10(hi * (1 - 1e-8) if hi in ends else hi), n_range)
    edge = [e * (1 + s * np.logspace(-8, -2, n_edge)) for e in ends for s in (-1, 1)]
    return np.concatenate([inner, *edge]) if edge else inner


def _worst(d, Vs, params=None) -> tuple[float, int]:
    """Largest relative error of k_c and Λ against 50 digits over the points with a Hopf point."""
    got = d.evaluate(Vs, params or {}, ["kc", "Lambda"])
    worst, checked = 0.0, 0
    for i, V0 in enumerate(Vs):
        if not np.isfinite(got["kc"][i]):
            continue
        ref = d.evaluate_mp(float(V0), params or {}, ["Lambda"], dps=50)
        worst = max(worst, _rel_err(got["kc"][i], ref["kc"]), _rel_err(got["Lambda"][i], ref["Lambda"]))
        checked += 1
    return worst, checked


def test_bound_covers_the_error_of_a_cancellation():
    # ((1 + x) − 1)/x = 1: the bound must report the lost digits and cover the error
    x = sp.Symbol("x")
    k = BoundedKernel([_cancelling(x), sp.exp(x) * sp.log(1 + x)], [x])
    xs = np.array([1e-3, 1e-7, 3e-9, 1e-12])
    V, R = k(xs)
    for i, x0 in enumerate(xs):
        err0 = abs(V[0, i] - 1.0)
        assert err0 <= R[0, i] * 1.0001
        with mpmath.workdps(40):
            ref = mpmath.exp(mpmath.mpf(x0)) * mpmath.log(1 + mpmath.mpf(x0))
            assert _rel_err(V[1, i], ref) <= R[1, i] * 1.0001
    assert R[0, 3] > 1e-6          # 12 digits cancelled: not proven to 1e-10
    if EXTENDED:
        Ve, Re = k.extended(xs)
        assert np.all(Re[0] < R[0] / 1000)       # 11 more bits: bound ~2000x smaller
        assert np.all(np.abs(Ve[0].astype(float) - 1.0) <= Re[0] * 1.0001 + 1e-16)


@pytest.mark.parametrize("name", ["spinodal", "nanoscale"])
def test_bound_covers_the_actual_float64_error_of_lambda(name):
    """The first-order bound of every output is at least its actual error (50-digit reference),
    and it is sharp enough to prove most points of the range without refinement."""
    from landau.linear import w

    d = derive(SpringBlock(get_law(name)), ["Lambda"])
    d.coefficient("Lambda")
    kc, W = d.hopf.closed_form
    k = BoundedKernel([kc, W, d.coefficient("Lambda").formula], d.args,
                      {**d.jets.atoms, w: sp.sqrt(W), d.k: kc})
    Vs = _velocities(name, 60, 8)
    vals = d.block.argvals(Vs, d.block.resolve())
    V, R = k(*vals)
    checked = 0
    for i, V0 in enumerate(Vs):
        try:
            ref = d.evaluate_mp(float(V0), {}, ["Lambda"], dps=50)
        except NoHopfError:          # beyond an extremum of μ_ss
            continue
        checked += 1
        with mpmath.workdps(50):
            W0 = ref["omega_c"] ** 2
        for j, want in enumerate((ref["kc"], W0, ref["Lambda"])):
            assert _rel_err(V[j, i], want) <= R[j, i] * 1.0001 + 1e-300, (V0, j)
    assert checked >= 60
    # proven without refinement: most points of the nanoscale law; the spinodal law's low
    # velocities (ω_c² → 0, terms ∝ 1/ω_c² cancel in Λ) genuinely lose ~1e-10 in float64
    inner = R[2][:60]          # the points of the range (the rest approach the extrema)
    assert np.mean(inner <= 1e-10) > {"spinodal": 0.3, "nanoscale": 0.9}[name], np.mean(inner <= 1e-10)


@pytest.mark.parametrize("name", LAWS)
def test_lambda_within_1e_10_near_extrema(name):
    """k_c and Λ within 1e-10 of 50 digits over the range and within 1e-8 of the extrema of μ_ss."""
    d = derive(SpringBlock(get_law(name)), ["Lambda"])
    worst, checked = _worst(d, _velocities(name, 25, 6))
    assert checked >= 25
    assert worst <= 1e-10, worst


@pytest.mark.parametrize("name", GENERAL)
def test_lambda_within_1e_10_at_tiny_mass(name):
    """M = 1e-7 kg: ω_c² large, the inertia-free limit of the formulas (terms ∝ M cancel)."""
    d = derive(SpringBlock(get_law(name)), ["Lambda"])
    worst, checked = _worst(d, _velocities(name, 25, 0), {"M": 1e-7})
    assert checked >= 15
    assert worst <= 1e-10, worst


def test_sign_only_keeps_proven_signs():
    d = derive(SpringBlock(get_law("spinodal")), ["Lambda"])
    Vs = _velocities("spinodal", 50, 5)
    full = d.evaluate(Vs, {}, ["Lambda"])["Lambda"]
    signs = d.evaluate(Vs, {}, ["Lambda"], sign_only=True)["Lambda"]
    ok = np.isfinite(full)
    assert np.array_equal(np.sign(full[ok]), np.sign(signs[ok]))


def test_evaluate_proven_reports_unproven_points():
    x = sp.Symbol("x")
    k = BoundedKernel([sp.Integer(1) + x, _cancelling(x)], [x])
    V, bad = evaluate_proven(k, [np.array([0.5, 1e-14])], 1e-10)
    assert not bad[0].any()
    assert bad[1, 1] and not bad[1, 0]


@pytest.mark.slow
@pytest.mark.parametrize("name", LAWS)
def test_lambda_1000_points_within_1e_10(name):
    """The benchmark's criterion: 1000 points (including 200 approaching the extrema of μ_ss)."""
    d = derive(SpringBlock(get_law(name)), ["Lambda"])
    ends = vw_range(name)[2]
    n_edge = 50
    worst, checked = _worst(d, _velocities(name, 1000 - 2 * n_edge * len(ends), n_edge))
    assert checked >= 800
    assert worst <= 1e-10, worst


def test_machine_code_cached_on_disk(tmp_path, monkeypatch):
    """The compiled loop is stored under the cache directory and reloaded from it: same values."""
    from landau import cache

    monkeypatch.setenv("LANDAU_CACHE_DIR", str(tmp_path))
    cache.set_enabled(True)
    try:
        x = sp.Symbol("x")
        expr = sp.asinh(x) * sp.exp(x) + x ** 3
        first = BoundedKernel([expr], [x])(np.array([0.5, 2.0]))
        stored = list((tmp_path / "kernels").glob("bounded_*.o"))
        assert len(stored) == 1
        again = BoundedKernel([expr], [x])(np.array([0.5, 2.0]))      # a new engine: loads the object file
        assert np.array_equal(first[0], again[0]) and np.array_equal(first[1], again[1])
        with mpmath.workdps(30):
            ref = mpmath.asinh(2) * mpmath.exp(2) + 8
        assert _rel_err(first[0][0, 1], ref) <= first[1][0, 1] * 1.0001 + 1e-16
    finally:
        cache.set_enabled(None)
