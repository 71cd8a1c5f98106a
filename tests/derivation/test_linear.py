"""Linear stability of steady sliding (Putelat et al. 2010, eqs 7, 8, 30, 31, 41–43, Sec. 4.1)."""

import math

import mpmath
import numpy as np
import pytest
import sympy as sp

from landau.analyses.transition import extrema, velocity_weakening_ranges
from landau.derivation.linear import NO_HOPF_STABLE, HopfLine
from landau.derivation.multiscale import Derivation
from landau.errors import InputError
from landau.laws import TABLE1, get_law, v
from landau.systems.system import M, SpringBlock, V, sigma

a, b, L, V_s = (TABLE1[n].symbol for n in ("a", "b", "L", "V_s"))
c = sp.Symbol("c", positive=True)


def _paper_G_derivatives(law):
    """F = σμ and G = −rate with their first derivatives at the steady state (paper notation)."""
    phi = law.states[0]
    ss = {phi: law.steady_state_closed_form[0].subs(v, V), v: V}
    F = sigma * law.mu
    G = -law.rates[0]
    d = lambda e, x: sp.diff(e, x).subs(ss)
    mu_ss = (sigma * law.mu).subs(phi, law.steady_state_closed_form[0])
    return d(F, v), d(F, phi), d(G, v), d(G, phi), sp.diff(mu_ss, v).subs(v, V)


@pytest.mark.parametrize("name", ["dieterich", "ruina"])
def test_kc_and_omega_equal_eqs_30_and_8(name):
    hl = HopfLine(SpringBlock(get_law(name)))
    eq30 = sigma * (b - a) / L * (1 + M * V ** 2 / (L * a * sigma))          # eq. (30)
    assert sp.simplify(hl.kc_expr - eq30) == 0
    F_V, F_phi, G_V, G_phi, Fss_prime = _paper_G_derivatives(get_law(name))
    eq8 = -G_phi ** 2 * Fss_prime / F_V                                       # eq. (8)
    assert sp.simplify(hl.omega2_expr - eq8) == 0
    eq7 = (F_phi * G_V - F_V * G_phi) * (1 + M * G_phi / F_V)                 # eq. (7)
    assert sp.simplify(hl.kc_expr - eq7) == 0


def test_modified_dieterich_kc_and_omega2_equal_eqs_42_43():
    hl = HopfLine(SpringBlock(get_law("modified-dieterich")))
    Vm = (b / a - 1) * V_s / c                                                # eq. (41)
    eq42 = (a * c * sigma / L) * (Vm - V) * (1 + M * V ** 2 / (a * sigma * L)) / (V_s + c * V)
    # eq. (43) read as ω_c² with the last term carrying a factor V (the print drops both)
    eq43 = (V / L) ** 2 * (b / a - 1 - (b * c / a) * V / (V_s + c * V))
    assert sp.simplify(hl.kc_expr - eq42) == 0
    assert sp.simplify(hl.omega2_expr - eq43) == 0


def test_v_hat_eq31():
    p = SpringBlock(get_law("dieterich")).resolve()
    v_hat = math.sqrt(p["a"] * p["sigma"] * p["L"] / p["M"])
    assert v_hat == pytest.approx(5.55e-4, rel=2e-3)   # eq. (31); the paper rounds to 5.6e-4


def test_spinodal_hopf_exactly_between_the_extrema_sec41():
    block = SpringBlock(get_law("spinodal"))
    ex = extrema(Derivation(block), None, 1e-12, 1.0)
    assert [e.kind for e in ex] == ["maximum", "minimum"]
    V_M, V_m = ex[0].V, ex[1].V
    assert V_M == pytest.approx(2.493e-8, rel=5e-4)     # Sec. 4.1: V_M = 2.493e-8 m/s
    assert V_m == pytest.approx(4.052e-4, rel=5e-4)     # Sec. 4.1: V_m = 4.052e-4 m/s
    (rng,) = velocity_weakening_ranges(Derivation(block), None, 1e-12, 1.0)
    assert (rng.lo, rng.hi) == (V_M, V_m)
    hl = HopfLine(block)
    inside = np.logspace(np.log10(V_M) + 1e-6, np.log10(V_m) - 1e-6, 200)
    kc, _ = hl.evaluate(inside)
    assert np.all(kc > 0)
    outside = np.concatenate([np.logspace(-11, np.log10(V_M) - 1e-6, 50), np.logspace(np.log10(V_m) + 1e-6, 0, 50)])
    kc_out, _ = hl.evaluate(outside)
    assert np.all(np.isnan(kc_out))
    # k_c -> 0 at both ends: it changes sign exactly at the extrema (closed form evaluated just inside)
    assert hl.evaluate([V_M * (1 + 1e-6), V_m * (1 - 1e-6)])[0] == pytest.approx([0, 0], abs=1.0)


def test_modified_dieterich_vm_eq41():
    block = SpringBlock(get_law("modified-dieterich"))
    for cval in (1e-4, 3e-4, 1e-3):
        p = block.resolve({"c": cval})
        ex = [e for e in extrema(Derivation(block), p, 1e-9, 10.0) if e.kind == "minimum"]
        assert ex[0].V == pytest.approx((p["b"] / p["a"] - 1) * p["V_s"] / cval, rel=1e-10)


def test_velocity_strengthening_reports_no_hopf():
    pt = HopfLine(SpringBlock(get_law("spinodal"))).point(1e-2)
    assert pt.status == "no-hopf" and pt.reason == NO_HOPF_STABLE and math.isnan(pt.kc)


@pytest.mark.parametrize("name", ["dieterich", "spinodal", "nanoscale"])
def test_n_state_route_agrees_with_closed_form(name):
    hl = HopfLine(SpringBlock(get_law(name)))
    Vs = [3e-6, 3e-5, 2e-4]
    k1, w1 = hl.evaluate(Vs)
    k2, w2 = hl.evaluate(Vs, method="polynomial")
    assert k2 == pytest.approx(k1, rel=1e-10)
    assert w2 == pytest.approx(w1, rel=1e-10)


def _eigenvalues(block, V0, k, dps=40):
    """Eigenvalues of E⁻¹J of the numeric Jacobian at (V0, k), in mpmath (float eig loses ~8 digits
    here: the matrix entries span 10 decades)."""
    sysm = block.system
    p = block.resolve()
    vals = {s: p[s.name] for s in sysm.parameters if s.name in p}
    vals.update({V: V0, sysm.parameter: k})
    at = dict(zip(sysm.states, [0, 0] + [e.subs(vals) for e in sysm.equilibrium[2:]], strict=True))
    J = sp.Matrix(sysm.rhs).jacobian(sysm.states).subs(at).subs(vals)
    E = [sp.sympify(m).subs(vals) for m in sysm.mass]
    with mpmath.workdps(dps):
        A = mpmath.matrix([[mpmath.mpf(str(sp.N(J[i, j] / E[i], dps + 5))) for j in range(J.shape[1])]
                           for i in range(J.shape[0])])
        return [complex(z) for z in mpmath.eig(A, left=False, right=False)]


def test_two_state_hopf_is_a_pure_imaginary_pair_of_the_numeric_jacobian():
    block = SpringBlock(get_law("two-state-dieterich"))
    hl = HopfLine(block)
    for V0 in (1e-5, 1e-4):
        kc, om = (float(x[0]) for x in hl.evaluate([V0]))
        lam = _eigenvalues(block, V0, kc)
        crit = min(lam, key=lambda z: abs(z.real) + abs(abs(z.imag) - om))
        assert abs(crit.real) < 1e-12 * om                   # on the axis at k_c ...
        assert abs(crit.imag) == pytest.approx(om, rel=1e-12)  # ... at ±iω_c
        assert all(z.real < 0 for z in lam if abs(abs(z.imag) - om) > 1e-6 * om)
        # just above k_c every eigenvalue is stable, just below the pair is unstable
        assert max(z.real for z in _eigenvalues(block, V0, kc * (1 + 1e-4))) < 0
        assert max(z.real for z in _eigenvalues(block, V0, kc * (1 - 1e-4))) > 0


def test_bad_parameters_are_named():
    block = SpringBlock(get_law("dieterich"))
    with pytest.raises(InputError, match="unknown parameter 'q'"):
        block.resolve({"q": 1})
    with pytest.raises(InputError, match="'L' must be > 0"):
        block.resolve({"L": -1})
    with pytest.raises(InputError, match="V must be > 0"):
        HopfLine(block).points([0.0])
