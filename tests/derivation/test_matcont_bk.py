"""The general engine against published BifurcationKit values (BifurcationKit.jl test suite).

Every number below is copied from the BifurcationKit.jl repository (github.com/bifurcationkit/
BifurcationKit.jl, commit ed4b14eef65b60fd1612e6914fa669f44fac3d81); the file and line are
given with each.  Conventions: BifurcationKit's Hopf normal form is ż = (iω + a·δp) z + b z|z|²
with ⟨ζ, ζ⟩ = 1, ⟨ζ*, ζ⟩ = 1 (Kuznetsov's normalisation) and its ζ the eigenvector of −iω, so
its (a, b) are the complex conjugates of landau's ``dlambda_dp`` and Kuznetsov's ``c1``; its
printed ``l1`` is Re c₁ (not divided by ω as MatCont does).  BifurcationKit locates points by
bisection on the eigenvalues, so its normal-form numbers carry the error of that location; the
tolerances are the ones its own tests use for the same numbers.
"""

from __future__ import annotations

import math

import pytest
import sympy as sp

from landau.analyses.continuation import equilibrium_branch, hopf_curve
from landau.systems.system import DynamicalSystem

BK = "BifurcationKit.jl"


# --- extended Lorenz-84 model -------------------------------------------------------------------------
# test/hopf_codim_2/lorenz84.jl lines 7-16 (vector field), 30 (parameters), 42 (initial guess)
X, Y, Z, U = sp.symbols("X Y Z U", real=True)
alpha, beta, gamma, delta, G, F, T = sp.symbols("alpha beta gamma delta G F T", real=True)
LORENZ84 = DynamicalSystem(
    "lorenz84-extended", (X, Y, Z, U),
    (-Y**2 - Z**2 - alpha*X + alpha*F - gamma*U**2, X*Y - beta*X*Z - Y + G, beta*X*Y + X*Z - Z,
     -delta*U + gamma*U*X + T),
    (1, 1, 1, 1), F,
    tuple(sp.Float(v) for v in (2.9787004394953343, -0.03868302503393752, 0.058232737694740085,
                                -0.02105288273117459)))
LORENZ84_PARAMS = dict(alpha=0.25, beta=1.0, G=0.25, delta=1.04, gamma=0.987, T=0.04)


@pytest.fixture(scope="module")
def lorenz_branch():
    # BifurcationKit continues in F from F = 3 over [-1.5, 3] (lines 32-55)
    return equilibrium_branch(LORENZ84, LORENZ84_PARAMS, (-1.5, 3.0), start=3.0, direction=-1)


def test_lorenz84_hopf_points_inside_bifurcationkit_intervals(lorenz_branch):
    # lorenz84.jl lines 62-64: the bisection intervals of the Hopf points special points 2-4
    intervals = [(2.859863413561998, 2.859897757930758), (2.467211879219629, 2.467246154619121),
                 (1.619657484413436, 1.6196654620692468)]
    found = sorted((h.p_c for h in lorenz_branch.hopf), reverse=True)
    assert len(found) == 3
    for p, (a, b) in zip(found, intervals, strict=True):
        assert a <= p <= b, (p, a, b)


def test_lorenz84_hopf_points_found_with_another_pair_unstable(lorenz_branch):
    # at two of the three Hopf points another eigenvalue is already unstable on both sides, so the
    # largest real part never changes sign there: the crossing pair must be followed
    import numpy as np

    from landau.derivation.general import NumericSystem

    num = NumericSystem(LORENZ84, LORENZ84_PARAMS)
    others = 0
    for h in lorenz_branch.hopf:
        lam = num.eigenvalues(h.equilibrium, h.p_c)
        crossing = np.argmin(np.abs(lam - 1j * h.omega_c))
        rest = np.delete(lam, crossing)
        rest = rest[np.abs(rest + 1j * h.omega_c) > 1e-6]  # drop the conjugate
        others += bool(np.any(rest.real > 1e-9))
    assert others >= 1
    # and the frequency is the imaginary part of a pair on the axis (closed check of the point)
    for h in lorenz_branch.hopf:
        lam = num.eigenvalues(h.equilibrium, h.p_c)
        assert np.min(np.abs(lam - 1j * h.omega_c)) < 1e-9 * h.omega_c


def test_lorenz84_fold(lorenz_branch):
    import mpmath
    import numpy as np

    from landau.derivation.general import NumericSystem

    assert len(lorenz_branch.folds) == 1
    fold = lorenz_branch.folds[0]
    # independent: f = 0 and det J = 0 solved together at 30 digits from the nearest branch point
    num = NumericSystem(LORENZ84, LORENZ84_PARAMS)
    y0 = lorenz_branch.y[int(np.argmin(np.abs(lorenz_branch.p - fold)))]
    with mpmath.workdps(30):
        def eqs(*v):
            f, J, _ = num.first(list(v[:4]), v[4], False)
            return list(f) + [mpmath.det(J)]
        exact = float(mpmath.findroot(eqs, [mpmath.mpf(c) for c in y0] + [mpmath.mpf(fold)])[4])
    assert fold == pytest.approx(exact, abs=1e-14)
    # lorenz84.jl line 65: the fold (special point 5) lies in (1.546648372620807, 1.5466483727182652)
    # by BifurcationKit's bisection; its points carry its Newton tolerance, and the exact fold is
    # 2.3e-11 below the interval: agreement to 1e-10 (6e-11 relative)
    a, b = 1.546648372620807, 1.5466483727182652
    assert a - 1e-10 <= fold <= b + 1e-10


def test_lorenz84_generalised_hopf_frequency(lorenz_branch):
    # lorenz84.jl lines 287-300: the Hopf curve from special point 3 (F ≈ 2.4672) continued in T has
    # a GH point; line 314: its ω ≈ 0.6903636672622595 (atol 1e-5 there)
    h = min(lorenz_branch.hopf, key=lambda r: abs(r.p_c - 2.4672))
    curve = hopf_curve(LORENZ84, LORENZ84_PARAMS, "T", (0.03, 0.07), h, steps=8, l2=False)
    assert len(curve.generalised_hopf) == 1
    # the curve turns back in T (at T ≈ 0.058) inside the range: pseudo-arclength passes the turn
    import numpy as np

    assert curve.p2.max() < 0.065 and np.any(np.diff(curve.p2) > 0) and np.any(np.diff(curve.p2) < 0)
    gh = curve.generalised_hopf[0]
    assert gh.omega == pytest.approx(0.6903636672622595, abs=1e-5)
    assert abs(gh.hopf.l1) < 1e-10


def test_lorenz84_generalised_hopf_l2(lorenz_branch):
    # lorenz84.jl line 315: l2 ≈ 0.15555332623343107 (atol 1e-3).  BifurcationKit prints Re c₂
    # (NormalForms.jl: l2 = real(G32)/12), and so does landau's HopfResult.l2.
    h = min(lorenz_branch.hopf, key=lambda r: abs(r.p_c - 2.4672))
    curve = hopf_curve(LORENZ84, LORENZ84_PARAMS, "T", (0.03, 0.07), h, steps=8, l2=True)
    gh = curve.generalised_hopf[0]
    assert gh.l2 == pytest.approx(0.15555332623343107, abs=1e-3)


# --- CO oxidation (Bykov) model ----------------------------------------------------------------------
# test/fold_codim_2/codim2.jl lines 7-16 (vector field), 19-20 (parameters, initial guess)
x, y, s = sp.symbols("x y s", real=True)
q1, q2, q3, q4, q5, q6, k = sp.symbols("q1:7 k", real=True)
_z = 1 - x - y - s
CO = DynamicalSystem("co-oxidation", (x, y, s),
                     (2*q1*_z**2 - 2*q5*x**2 - q3*x*y, q2*_z - q6*y - q3*x*y, q4*_z - k*q4*s),
                     (1, 1, 1), q2, (sp.Float(0.07), sp.Float(0.2), sp.Integer(5)))
CO_PARAMS = dict(q1=2.5, q3=10.0, q4=0.0675, q5=1.0, q6=0.1, k=0.4)


@pytest.fixture(scope="module")
def co_hopf():
    # BifurcationKit continues q2 from 2.0 on both sides over [0.6, 2.5] (lines 24-30)
    branch = equilibrium_branch(CO, CO_PARAMS, (0.6, 2.5), start=2.0, direction=0)
    return sorted(branch.hopf, key=lambda h: h.p_c)


def test_co_two_hopf_points_and_first_lyapunov(co_hopf):
    assert len(co_hopf) == 2
    low, high = co_hopf
    # codim2.jl line 38: Re b = 1.070259e+01 (rtol 1e-3) at the upper Hopf point; line 41: Re b =
    # 4.332247 (rtol 1e-2) at the lower one.  b is Kuznetsov's c₁ (BifurcationKit's l1 = Re c₁).
    assert high.c1.real == pytest.approx(1.070259e+01, rel=1e-3)
    assert low.c1.real == pytest.approx(4.332247, rel=1e-2)
    assert high.l1 == pytest.approx(high.c1.real / high.omega_c, rel=1e-12)  # MatCont's l₁ = Re c₁/ω


def test_co_hopf_normal_form_coefficients(co_hopf):
    low = co_hopf[0]
    # codim2.jl lines 94-95: a ≈ 2.546719962189168 + 1.6474887797814664im,
    # b ≈ 4.3536804635557855 + 15.441272421860365im (complex conjugates of landau's a and c₁, see the
    # module docstring).  The point is 1e-3 from a fold, where the coefficients move fast; the same
    # file checks Re b at this point only to rtol 1e-2 (line 41): so do we.
    a_bk = complex(2.546719962189168, 1.6474887797814664)
    b_bk = complex(4.3536804635557855, 15.441272421860365)
    assert low.dlambda_dp.conjugate() == pytest.approx(a_bk, rel=1e-2)
    assert low.c1.conjugate() == pytest.approx(b_bk, rel=1e-2)


# --- Stuart–Landau oscillator with quintic term -------------------------------------------------------
# test/normal_forms/testNF.jl lines 370-380 (vector field Fsl2), 419 (parameters), 439-440 (nf.a ≈ 1,
# nf.b/2 ≈ −c3 + iμ, atol 1e-14)
u1, u2, r = sp.symbols("u1 u2 r", real=True)
mu_, nu_, c3_, c5_ = sp.symbols("mu nu c3 c5", real=True)
_ua = u1**2 + u2**2
STUART_LANDAU = DynamicalSystem(
    "stuart-landau", (u1, u2),
    (r*u1 - nu_*u2 - _ua*(c3_*u1 - mu_*u2) - c5_*_ua**2*u1, r*u2 + nu_*u1 - _ua*(c3_*u2 + mu_*u1) - c5_*_ua**2*u2),
    (1, 1), r, (0, 0))


def test_stuart_landau_normal_form():
    from landau.derivation.general import hopf_normal_form

    par = dict(mu=0.132, nu=1.0, c3=1.123, c5=0.2)
    h = hopf_normal_form(STUART_LANDAU, par, (-0.3, 0.1))
    assert abs(h.p_c) < 1e-40
    assert h.dlambda_dp.conjugate() == pytest.approx(1.0, abs=1e-14)
    b_bk = 2 * complex(-par["c3"], par["mu"])
    assert abs(h.c1.conjugate() - b_bk) < 1e-14
    assert h.l1 == pytest.approx(-2 * par["c3"] / par["nu"], rel=1e-14)
    assert math.isclose(h.omega_c, par["nu"], rel_tol=1e-14)
