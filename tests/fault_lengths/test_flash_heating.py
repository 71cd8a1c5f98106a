"""Flash heating as a law modifier (Rice 2006; Beeler, Tullis & Goldsby 2008): ``dieterich+flash``.

Independent routes written here, in numpy, from the law as typed by hand (not from landau's
engine): the steady-state friction of eq. (1) of :mod:`landau.laws.flash`; the spring–block's
Jacobian with hand-derived partial derivatives, whose eigenvalues are bisected in k for k_c; and
Kuznetsov's (2004, eq. 3.20) first Lyapunov coefficient l₁ from finite-difference multilinear forms
of that Jacobian, with the amplitude constant of the normal form, C = 2|q_X| sqrt(|dReλ/dk| / |Re c₁|),
compared with landau's C = 2 sqrt(2 Γ̄/|Λ|) (which contains Λ).
"""

from __future__ import annotations

import contextlib
import io
import json

import numpy as np
import pytest

from landau.cli.app import main
from landau.errors import InputError
from landau.laws import flash_heating, get_law
from landau.verify.springblock.checks import predict

#: away from every default: another f_w, V_w, load, mass, a, b, L
P = dict(a_v=0.55, a=0.011, b=0.016, L=2e-6, V_s=1e-6, f_w=0.15, V_w=0.03, sigma=20.0, M=0.5)
LAW_KEYS = ("a_v", "a", "b", "L", "V_s", "f_w", "V_w")
BLOCK = {k: P[k] for k in ("sigma", "M")}
#: V ~ V_w (the weakening sets in) and V = 10 V_w (the high-rate branch, Rice's V_w/V form)
VS = (0.05, 0.3)


def mu_lv(p, w):
    return p["a_v"] + (p["a"] - p["b"]) * np.log(w / p["V_s"])


def mu_hand(p, v, phi):
    """Eq. (2) of landau.laws.flash for the Dieterich law, typed by hand: v_phi = L/phi."""
    w = p["L"] / phi
    return (p["a_v"] + p["a"] * np.log(v / p["V_s"]) + p["b"] * np.log(p["V_s"] * phi / p["L"])
            - (mu_lv(p, w) - p["f_w"]) * w / (w + p["V_w"]))


def mu_ss_eq1(p, V):
    """Eq. (1): f_w + (f_LV - f_w) V_w/(V + V_w)."""
    return p["f_w"] + (mu_lv(p, V) - p["f_w"]) * p["V_w"] / (V + p["V_w"])


def law():
    return get_law("dieterich+flash").with_defaults(**{k: P[k] for k in LAW_KEYS})


def test_steady_state_is_eq1_and_the_direct_effect_is_a():
    """μ_ss of the modified law is eq. (1) to round-off; for V ≫ V_w it approaches Rice's (2006)
    f_w + (f_LV − f_w) V_w/V with relative difference (of the weakened part) V_w/V; the direct effect
    V ∂μ/∂v at fixed state is a, unchanged."""
    lw = law()
    pars = {k: P[k] for k in LAW_KEYS}
    Vs = np.array([1e-6, 1e-3, 0.03, 0.3, 3.0])
    phi = lw.steady_state_values(Vs, pars)[0]
    np.testing.assert_allclose(phi, P["L"] / Vs, rtol=1e-14)
    got = np.array([mu_hand(P, V, ph) for V, ph in zip(Vs, phi, strict=True)])
    np.testing.assert_allclose(got, mu_ss_eq1(P, Vs), rtol=1e-13)
    import sympy as sp

    mu_ss = sp.lambdify([lw.v, *(q.symbol for q in lw.parameters)], lw.mu_ss())
    np.testing.assert_allclose([mu_ss(V, *(pars[q.name] for q in lw.parameters)) for V in Vs], mu_ss_eq1(P, Vs),
                               rtol=1e-13)
    # Rice (2006): the weakened part (mu_ss - f_w) -> (f_LV - f_w) V_w/V, relative difference V_w/(V + V_w)
    V = 3.0
    rice = (mu_lv(P, V) - P["f_w"]) * P["V_w"] / V
    assert (mu_ss_eq1(P, V) - P["f_w"]) / rice - 1 == pytest.approx(-P["V_w"] / (V + P["V_w"]), rel=1e-12, abs=0)
    # direct effect: central difference in ln v at fixed phi (mu is linear in ln v at fixed phi: exact)
    h = 1e-3
    for V, ph in zip(Vs, phi, strict=True):
        d = (mu_hand(P, V * np.exp(h), ph) - mu_hand(P, V * np.exp(-h), ph)) / (2 * h)
        assert d == pytest.approx(P["a"], rel=1e-9, abs=0)


# ---------------------------------------------------------------------------------------------
# the spring-block, assembled here: y = (X, u, phi), X' = u, M u' = -k X - sigma (mu(V+u, phi) - mu_ss(V)),
# phi' = 1 - (V + u) phi / L  (Putelat, Dawes & Willis 2010, eq. 4)
# ---------------------------------------------------------------------------------------------
def field(p, V, k, y):
    X, u, phi = y
    return np.array([u, (-k * X - p["sigma"] * (mu_hand(p, V + u, phi) - mu_ss_eq1(p, V))) / p["M"],
                     1 - (V + u) * phi / p["L"]], dtype=complex)


def jacobian(p, V, k, y):
    """The Jacobian with the partial derivatives of μ derived by hand:
    μ_v = a/v, μ_φ = b/φ − W'(φ), W = (f_LV(L/φ) − f_w) s, s = L/(L + V_w φ)."""
    X, u, phi = y
    v = V + u
    s = p["L"] / (p["L"] + p["V_w"] * phi)
    ds = -p["L"] * p["V_w"] / (p["L"] + p["V_w"] * phi) ** 2
    dW = -(p["a"] - p["b"]) / phi * s + (mu_lv(p, p["L"] / phi) - p["f_w"]) * ds
    mu_v, mu_phi = p["a"] / v, p["b"] / phi - dW
    M, sg, L = p["M"], p["sigma"], p["L"]
    return np.array([[0, 1, 0],
                     [-k / M, -sg * mu_v / M, -sg * mu_phi / M],
                     [0, -phi / L, -v / L]], dtype=complex)


def y0(p, V):
    return np.array([0.0, 0.0, p["L"] / V], dtype=complex)


def growth(p, V, k):
    return np.linalg.eigvals(jacobian(p, V, k, y0(p, V))).real.max()


def k_c_bisected(p, V):
    """k_c by bisection of the largest real part of the eigenvalues (unstable below k_c)."""
    lo, hi = 1.0, 1e14
    assert growth(p, V, lo) > 0 > growth(p, V, hi)
    for _ in range(200):
        mid = np.sqrt(lo * hi)
        if growth(p, V, mid) > 0:
            lo = mid
        else:
            hi = mid
        if hi / lo - 1 < 1e-15:
            break
    return 0.5 * (lo + hi)


def test_kc_against_the_bisected_jacobian():
    """k_c and ω_c of ``dieterich+flash`` (landau's derivation) against the eigenvalues of the Jacobian
    assembled here, at V ~ V_w and V = 10 V_w; and flash heating raises k_c above the plain law's at both
    (the steady state weakens faster than ln V there)."""
    lw = law()
    plain = get_law("dieterich").with_defaults(**{k: P[k] for k in LAW_KEYS if k not in ("f_w", "V_w")})
    for V in VS:
        res = predict(lw, V, BLOCK)
        kc = k_c_bisected(P, V)
        # bisection to 1e-15; the Jacobian's entries are exact formulas: agreement to round-off of eig
        assert res.p_c == pytest.approx(kc, rel=1e-9, abs=0)
        lam = np.linalg.eigvals(jacobian(P, V, kc, y0(P, V)))
        assert res.omega_c == pytest.approx(np.abs(lam.imag).max(), rel=1e-9)
        assert res.p_c > 1.2 * predict(plain, V, BLOCK).p_c


def _multilinear(p, V, kc, scale, h=1e-3):
    """Second and third derivative tensors of the field at steady sliding from fourth-order central
    differences of the hand-derived Jacobian, in the scaled coordinates y = y0 + diag(scale) z with
    ``scale`` the variables' natural sizes (truncation ~h^4 = 1e-12, round-off ~eps/h^2 = 1e-10, relative)."""
    base = y0(p, V)
    n = 3

    def d1(fun, j):
        e = np.zeros(n)
        e[j] = h
        return (-fun(2 * e) + 8 * fun(e) - 8 * fun(-e) + fun(-2 * e)) / (12 * h)

    J = lambda z: jacobian(p, V, kc, base + scale * z).real
    H = np.zeros((n, n, n))              # H[i, a, b] = d^2 f_i / dy_a dy_b = (1/scale_b) dJ_ia/dz_b
    T = np.zeros((n, n, n, n))           # T[i, a, b, c] = (1/(scale_b scale_c)) d^2 J_ia/dz_b dz_c
    for b in range(n):
        H[:, :, b] = d1(J, b) / scale[b]
        for c in range(n):
            T[:, :, b, c] = d1(lambda z, c=c: d1(lambda w: J(z + w), c), b) / (scale[b] * scale[c])
    return H, T


def kuznetsov(p, V):
    """(l1, c1, q, dRe λ/dk) of Kuznetsov (2004), eq. (3.20), at k_c, in the coordinates (X, u, φ)."""
    kc = k_c_bisected(p, V)
    A = jacobian(p, V, kc, y0(p, V)).real
    lam, vecs = np.linalg.eig(A)
    i = int(np.argmax(lam.imag))
    om = lam[i].imag
    q = vecs[:, i] / np.linalg.norm(vecs[:, i])
    lamT, vecsT = np.linalg.eig(A.T)
    pv = vecsT[:, int(np.argmin(np.abs(lamT + 1j * om)))]
    pv = pv / np.vdot(pv, q).conj()        # <p, q> = conj(p) . q = 1
    scale = np.array([p["L"], V, p["L"] / V])
    H, T = _multilinear(p, V, kc, scale)
    B = lambda x, y: np.einsum("iab,a,b->i", H, x, y)
    C = lambda x, y, z: np.einsum("iabc,a,b,c->i", T, x, y, z)
    inner = lambda a, b: np.vdot(a, b)
    h20 = np.linalg.solve(2j * om * np.eye(3) - A, B(q, q))      # (2iω − A) h20 = B(q, q)
    h11 = np.linalg.solve(-A, B(q, q.conj()))                    # −A h11 = B(q, q̄)
    g21 = inner(pv, C(q, q, q.conj())) + inner(pv, B(q.conj(), h20)) + 2 * inner(pv, B(q, h11))
    c1 = g21 / 2
    dk = kc * 1e-4          # central difference: truncation ~(dk/kc)^2 = 1e-8, round-off eps omega/(Gamma_bar dk)
    dre = (growth(p, V, kc + dk) - growth(p, V, kc - dk)) / (2 * dk)
    return c1.real / om, c1, q, dre, kc


@pytest.mark.parametrize("V", VS)
def test_lambda_against_kuznetsov_l1(V):
    """landau's l₁ and its amplitude constant C (from Λ and Γ̄) against Kuznetsov's l₁ and the normal
    form's amplitude computed here; the criticality is the sign of l₁."""
    res = predict(law(), V, BLOCK)
    l1, c1, q, dre, kc = kuznetsov(P, V)
    # the multilinear forms by finite differences: ~1e-8 relative (docstring of _multilinear)
    assert res.l1 == pytest.approx(l1, rel=1e-6, abs=0)
    assert res.Gamma_bar == pytest.approx(-dre, rel=1e-6, abs=0)
    C_here = 2 * abs(q[0]) * np.sqrt(abs(dre) / abs(c1.real))
    assert res.C == pytest.approx(C_here, rel=1e-6, abs=0)
    assert res.criticality == ("supercritical" if l1 < 0 else "subcritical")


def test_flash_law_through_the_command_line():
    """``landau hopf spring-block dieterich+flash`` is the Python result; an unknown modifier and a law the
    modifier cannot take are exit 2 with one line."""
    argv = ["hopf", "spring-block", "dieterich+flash", "--V", "0.05",
            *[x for k, v in P.items() for x in ("--param", f"{k}={v!r}")], "--json"]
    out = io.StringIO()
    with contextlib.redirect_stdout(out):
        assert main(argv) == 0
    doc = json.loads(out.getvalue())
    assert doc["p_c"] == pytest.approx(k_c_bisected(P, 0.05), rel=1e-9)
    for bad, words in ((["hopf", "spring-block", "dieterich+foo", "--json"], "unknown law modifier 'foo'"),
                       (["hopf", "spring-block", "spinodal+flash", "--json"], "no unique positive inverse")):
        out = io.StringIO()
        with contextlib.redirect_stdout(out):
            assert main(bad) == 2
        err = json.loads(out.getvalue())["error"]
        assert words in err and "\n" not in err


def test_modifier_errors_are_named():
    with pytest.raises(InputError, match="already has a parameter 'f_w'"):
        flash_heating(law())
    with pytest.raises(InputError, match="V_w must be finite and > 0"):
        flash_heating("dieterich", V_w=-1.0)
    with pytest.raises(InputError, match="no state 'psi'"):
        flash_heating("dieterich", state="psi")
    two = flash_heating("two-state-dieterich", state="phi2")
    assert two.name == "two-state-dieterich+flash" and {"f_w", "V_w"} <= set(two.defaults())


def test_derive_latex_sweep_and_simulate_take_the_modified_law(tmp_path):
    """No other change: ``landau derive`` (its own multiple-scales route) and ``landau sweep hopf`` give
    the numbers of ``landau hopf`` (the same bisected k_c), ``--latex`` writes the law with V_w, and
    ``landau simulate`` runs it."""
    import xarray as xr

    par = [x for k, v in P.items() for x in ("--param", f"{k}={v!r}")]

    def run(argv):
        out = io.StringIO()
        with contextlib.redirect_stdout(out):
            assert main(argv) == 0
        return out.getvalue()

    d = json.loads(run(["derive", "dieterich+flash", "--V", "0.05,0.3", *par, "--json"]))
    for pt, V in zip(d["points"], VS, strict=True):
        res = predict(law(), V, BLOCK)
        assert pt["k_c"] == pytest.approx(k_c_bisected(P, V), rel=1e-9, abs=0)
        assert pt["Lambda"] == pytest.approx(res.Lambda, rel=1e-9, abs=0)
    tex = tmp_path / "flash.tex"
    run(["derive", "dieterich+flash", "--V", "0.05", *par, "--quantities", "k_c,Lambda", "--latex", str(tex)])
    assert "V_{w}" in tex.read_text()
    nc = tmp_path / "flash.nc"
    run(["sweep", "hopf", "spring-block", "dieterich+flash", "--grid", "V=0.05,0.3", *par, "--out", str(nc), "--json"])
    with xr.open_dataset(nc) as ds:
        np.testing.assert_allclose(ds.k_c.values, [k_c_bisected(P, V) for V in VS], rtol=1e-9)
    sim = json.loads(run(["simulate", "spring-block", "dieterich+flash", "--V", "0.05", "--k", "2e9", *par,
                          "--t-end", "1e-3", "--json"]))
    assert sim["status"] == "finished" and sim["parameters"]["V_w"] == P["V_w"]
