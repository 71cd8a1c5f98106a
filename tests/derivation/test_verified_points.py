"""Every returned point is verified before it is returned: a generalised-Hopf point has l₁ = 0
to the accuracy of its location, a Hopf point a crossing pair ±iω; a scan grid that lands on
the Hopf point takes it; a DAE's algebraic row may stand anywhere; a ``normalise`` state outside
the critical mode is refused by name."""

from __future__ import annotations

import sys
from pathlib import Path

import pytest
import sympy as sp

from landau.analyses.continuation import _HopfTracker, _locate_gh, generalised_hopf
from landau.derivation.general import hopf_normal_form
from landau.errors import InputError, NoHopfError
from landau.systems.system import DynamicalSystem

sys.path.insert(0, str(Path(__file__).parent))
from test_matcont_bk import CO, CO_PARAMS  # noqa: E402  (BifurcationKit's CO-oxidation model)


@pytest.fixture(scope="module")
def co_start():
    return hopf_normal_form(CO, {**CO_PARAMS, "k": 0.4}, (1.0505, 1.0520))


def test_generalised_hopf_follows_the_curve(co_start):
    # was: k = 0.2332 with l1 = 0.84, l2 = -746.2 (a Newton jump from k = 0.4 to 0.2 changed branch);
    # the point on the Hopf curve followed by pseudo-arclength (hopf_curve) is k = 0.23249, q2 = 0.89132
    gh = generalised_hopf(CO, CO_PARAMS, "k", (0.4, 0.2), (1.0505, 1.0520))
    assert gh.p2 == pytest.approx(0.2324873542, rel=1e-8)
    assert gh.p1 == pytest.approx(0.8913189808, rel=1e-8)
    assert abs(gh.hopf.l1) < 1e-10
    assert gh.l2 == pytest.approx(-776.90, rel=1e-4)


def test_a_located_point_that_is_not_generalised_hopf_is_refused(co_start):
    # the old route: one bisection between the bracket's ends, Newton from the last point found
    tracker = _HopfTracker(CO, {**CO_PARAMS, "k": 0.4}, "k", co_start, 40, "taylor")
    with pytest.raises(NoHopfError, match="not a generalised-Hopf point"):
        _locate_gh(CO, tracker, 0.4, 0.2, False)


def test_no_sign_change_is_named():
    with pytest.raises(NoHopfError, match="does not change sign"):
        generalised_hopf(CO, CO_PARAMS, "k", (0.4, 0.3), (1.0505, 1.0520), l2=False)


# --- Brusselator: Hopf point at b = 1 + a² exactly ----------------------------------------------
x, y, z, a, b, mu = sp.symbols("x y z a b mu", real=True)
BRUSSELATOR = DynamicalSystem("brusselator", (x, y), (a - (b + 1)*x + x**2*y, b*x - x**2*y), (1, 1), b, (a, b / a))


@pytest.mark.parametrize("bracket", [(1.8, 2.2), (1.5, 2.0), (2.0, 2.5)])
def test_scan_grid_on_the_hopf_point(bracket):
    # (1.8, 2.2): the grid's point 2.0 is the Hopf point (was: raw ValueError from brentq);
    # (1.5, 2.0): the bracket's end is (was: "no Hopf crossing")
    ref = hopf_normal_form(BRUSSELATOR, {"a": 1.0}, (1.93, 2.11))
    res = hopf_normal_form(BRUSSELATOR, {"a": 1.0}, bracket)
    assert res.p_c == pytest.approx(2.0, abs=1e-14)          # 1 + a²
    assert res.omega_c == pytest.approx(1.0, rel=1e-14)      # ω² = a²
    assert res.l1 == pytest.approx(ref.l1, rel=1e-12)


# --- DAEs: the algebraic row anywhere; the normalised state ---------------------------------------
_F = (mu*x - y - x*z, x + mu*y - y*z)
_G = z - x**2 - y**2
ODE = DynamicalSystem("ode", (x, y), tuple(f.subs(z, x**2 + y**2) for f in _F), (1, 1), mu, (0, 0))


@pytest.mark.parametrize("order", ["first", "middle", "last"])
def test_dae_algebraic_row_anywhere(order):
    ref = hopf_normal_form(ODE, {}, (-0.5, 0.4))
    states, rhs, mass, norm = {
        "first": ((z, x, y), (_G, *_F), (0, 1, 1), 1),
        "middle": ((x, z, y), (_F[0], _G, _F[1]), (1, 0, 1), 0),
        "last": ((x, y, z), (*_F, _G), (1, 1, 0), 0),
    }[order]
    dae = DynamicalSystem("dae", states, rhs, mass, mu, (0, 0, 0), normalise=norm)
    res = hopf_normal_form(dae, {}, (-0.5, 0.4))
    assert abs(res.p_c) < 1e-12 and res.omega_c == pytest.approx(1.0, rel=1e-12)
    assert res.l1 == pytest.approx(ref.l1, rel=1e-12) and ref.l1 == pytest.approx(-2.0, rel=1e-12)
    assert res.Lambda == pytest.approx(ref.Lambda, rel=1e-12)


def test_normalise_outside_the_critical_mode_is_refused_by_name():
    # z = x² + y² has no linear part: the critical mode's z component is 0 (was: ZeroDivisionError)
    dae = DynamicalSystem("dae", (z, x, y), (_G, *_F), (0, 1, 1), mu, (0, 0, 0), normalise=0)
    with pytest.raises(InputError, match=r"'z' .* no component .* one of x, y"):
        hopf_normal_form(dae, {}, (-0.5, 0.4))


@pytest.mark.parametrize("bad", [3, -1, "z", 1.5])
def test_normalise_must_be_a_state_index(bad):
    dae = DynamicalSystem("dae", (x, y, z), (*_F, _G), (1, 1, 0), mu, (0, 0, 0), normalise=bad)
    with pytest.raises(InputError, match="normalise must be the index"):
        hopf_normal_form(dae, {}, (-0.5, 0.4))


# --- folds ------------------------------------------------------------------------------------------
_yf, _pf = sp.symbols("yf pf", real=True)


def test_fold_is_verified():
    from landau.analyses.continuation import equilibrium_branch

    # f = p − y²: the branch y = ±sqrt(p) turns back at the fold p = 0, where ∂f/∂y = −2y = 0
    fold = DynamicalSystem("fold", (_yf,), (_pf - _yf**2,), (1,), _pf, (sp.sqrt(_pf),))
    br = equilibrium_branch(fold, {}, (-0.5, 1.0), start=1.0, direction=-1, locate_hopf=False)
    assert len(br.folds) == 1 and abs(br.folds[0]) < 1e-12


def test_a_point_that_is_not_a_fold_is_refused():
    import numpy as np

    from landau.analyses.continuation import _refine_fold
    from landau.derivation.general import NumericSystem
    from landau.errors import SingularPointError

    # f = p − y has no fold: the extremum of p between two points is an end, where ∂f/∂y = −1
    line = DynamicalSystem("line", (_yf,), (_pf - _yf,), (1,), _pf, (_pf,))
    num = NumericSystem(line, {})
    with pytest.raises(SingularPointError, match="fails its check"):
        _refine_fold(num, np.array([[0.2], [0.3], [0.4]]), np.array([0.2, 0.3, 0.4]), 2)


def test_lorenz84_fold_where_the_jacobian_is_singular():
    # Lorenz (1984) with alpha = 0.25, beta = 4, G = 0.5: the branch from F = 0 turns at two folds.  The
    # first was reported at F = 1.1177295 (the branch point after the fold: the bracket missed the
    # extremum); the fold solves f = 0, det ∂f/∂y = 0 (solved here independently by scipy's fsolve)
    import numpy as np
    import scipy.optimize

    from landau.analyses.continuation import equilibrium_branch

    X, Y, Z = sp.symbols("X Y Z", real=True)
    al, be, F, G = sp.symbols("alpha beta F G", real=True)
    rhs = (-Y**2 - Z**2 - al*X + al*F, X*Y - be*X*Z - Y + G, be*X*Y + X*Z - Z)
    lor = DynamicalSystem("lorenz84", (X, Y, Z), rhs, (1, 1, 1), F, (sp.Float(1.0), sp.Float(0.5), sp.Float(0.5)))
    par = {"alpha": 0.25, "beta": 4.0, "G": 0.5}
    br = equilibrium_branch(lor, par, (0.0, 2.0), start=0.0, locate_hopf=False)
    vals = {al: 0.25, be: 4.0, G: 0.5}
    f = sp.lambdify([X, Y, Z, F], [e.subs(vals) for e in rhs])
    detJ = sp.lambdify([X, Y, Z, F], sp.Matrix(rhs).jacobian([X, Y, Z]).subs(vals).det())
    refs = []
    for guess in ([0.0856, 0.4796, 0.1795, 1.1345], [0.453, 0.0763, 0.2529, 0.7321]):
        sol = scipy.optimize.fsolve(lambda u: [*f(*u), detJ(*u)], guess, xtol=1e-14)
        refs.append(sol[3])
    assert np.allclose(sorted(br.folds), sorted(refs), rtol=1e-9, atol=0)
