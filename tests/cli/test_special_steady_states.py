"""Steady states without an elementary closed form, checked against an independent route.

Two laws whose steady state sympy cannot write with the law's own functions:

* dφ/dt = 1 − vφ/L − c·log(1 + V_sφ/L): sympy solves it with LambertW, whose argument
  v·exp((V_s + v)/(V_s c))/(V_s c) overflows float64 for v ≳ 7e-5 m/s at c = 0.1 — the steady state
  is solved numerically instead;
* dφ/dt = 1 − vφ/L − c·atan(V_sφ/L): no closed form at all.

The reference here shares nothing with the engine: the steady state by mpmath's Newton solver at
40 digits; the Hopf point from the Routh–Hurwitz condition a₂a₁ = a₀ of the 3×3 Jacobian's
characteristic polynomial (affine in k, so k_c solves a linear equation and ω_c² = a₁); the
Landau coefficient from Kuznetsov's (2004, eq. 3.20) first Lyapunov coefficient with the
multilinear forms B, C taken as finite derivatives (mpmath.diff, polarisation) of the vector
field E⁻¹f, converted to landau's normalisation (critical mode's slip component 1):
Λ = 2 Re c₁ for that mode (Putelat et al. 2010, eq. 20).  Both routes are converged far beyond
float64, and the engine promises 1e-10 relative, hence the 1e-8 tolerance.
"""

from __future__ import annotations

import json

import mpmath
import pytest

from landau.cli import main

MU = "a_v + a*log(v/V_s) + b*log(V_s*phi/L)"
RATES = {
    "lambertw": ("1 - v*phi/L - c*log(1 + V_s*phi/L)", lambda x: mpmath.log(1 + x)),
    "atan": ("1 - v*phi/L - c*atan(V_s*phi/L)", mpmath.atan),
}
#: Table 1 of Putelat et al. (2010), the default spring–block (M = 1.2 kg, σ = M g) and c = 3,
#: large enough that the c-term moves k_c by 7 % at V = 1e-4 m/s
P = dict(a_v=0.369, a=0.0349, b=0.0489, L=0.9e-6, V_s=1e-6, M=1.2, sigma=1.2 * 9.81, c=3.0)


def run(capsys, *argv):
    code = main(list(argv))
    out, err = capsys.readouterr()
    return code, out, err


def law_args(kind: str) -> list[str]:
    return ["--mu", MU, "--state", f"phi={RATES[kind][0]}", "--param", f"c={P['c']}"]


def reference(kind: str, V: float) -> tuple[float, float, float]:
    """(k_c, ω_c, Λ) by the independent route described in the module docstring."""
    g = RATES[kind][1]
    with mpmath.workdps(40):
        a_v, a, b, L, Vs, M, s, c = (mpmath.mpf(P[k]) for k in ("a_v", "a", "b", "L", "V_s", "M", "sigma", "c"))
        V = mpmath.mpf(V)
        mu = lambda vv, ph: a_v + a * mpmath.log(vv / Vs) + b * mpmath.log(Vs * ph / L)
        rate = lambda vv, ph: 1 - vv * ph / L - c * g(Vs * ph / L)
        phi0 = mpmath.findroot(lambda ph: rate(V, ph), L / V)
        assert phi0 > 0 and abs(rate(V, phi0)) < mpmath.mpf(10) ** -35

        def field(y, k):  # E⁻¹ f for y = (X, u, φ − φ0): Putelat et al. (2010), eq. (4)
            X, u, dph = y
            return [u, (-k * X - s * (mu(V + u, phi0 + dph) - mu(V, phi0))) / M, rate(V + u, phi0 + dph)]

        def jac(k):
            cols = []
            for j in range(3):
                e = [0, 0, 0]
                e[j] = 1
                cols.append([mpmath.diff(lambda t, e=e, i=i: field([t * x for x in e], k)[i], 0) for i in range(3)])
            return mpmath.matrix([[cols[j][i] for j in range(3)] for i in range(3)])

        def char(A):  # det(λ − A) = λ³ + a2 λ² + a1 λ + a0
            a2 = -(A[0, 0] + A[1, 1] + A[2, 2])
            a1 = sum(A[i, i] * A[j, j] - A[i, j] * A[j, i] for i in range(3) for j in range(i + 1, 3))
            det = (A[0, 0] * (A[1, 1] * A[2, 2] - A[1, 2] * A[2, 1]) - A[0, 1] * (A[1, 0] * A[2, 2] - A[1, 2] * A[2, 0])
                   + A[0, 2] * (A[1, 0] * A[2, 1] - A[1, 1] * A[2, 0]))   # expanded: A is singular at k = 0
            return a2, a1, -det

        a2, a1_0, a0_0 = char(jac(0))
        _, a1_1, a0_1 = char(jac(1))
        kc = (a0_0 - a2 * a1_0) / (a2 * (a1_1 - a1_0) - (a0_1 - a0_0))
        A = jac(kc)
        W = char(A)[1]
        assert W > 0 and kc > 0
        om = mpmath.sqrt(W)
        # critical modes: A q = iω q with q_X = 1, Aᵀ p = −iω p with <p, q> = p̄·q = 1
        ev, vr = mpmath.eig(A)
        i = min(range(3), key=lambda j: abs(ev[j] - 1j * om))
        q = [vr[r, i] / vr[0, i] for r in range(3)]
        evl, vl = mpmath.eig(A.T)
        i = min(range(3), key=lambda j: abs(evl[j] + 1j * om))
        p = [vl[r, i] for r in range(3)]
        norm = sum(mpmath.conj(p[r]) * q[r] for r in range(3))
        p = [z / mpmath.conj(norm) for z in p]
        dot = lambda x, y: sum(mpmath.conj(x[r]) * y[r] for r in range(3))

        def D(x, order):  # the order-th derivative of E⁻¹f along x (complex x: analytic continuation)
            return [mpmath.diff(lambda t, r=r: field([t * z for z in x], kc)[r], 0, order) for r in range(3)]

        add = lambda x, y, sgn=1: [x[r] + sgn * y[r] for r in range(3)]
        B = lambda x, y: [(u - w) / 4 for u, w in zip(D(add(x, y), 2), D(add(x, y, -1), 2), strict=True)]
        C_xxy = lambda x, y: [(u - w - 2 * z) / 6
                              for u, w, z in zip(D(add(x, y), 3), D(add(x, y, -1), 3), D(y, 3), strict=True)]
        qb = [mpmath.conj(z) for z in q]
        I3 = mpmath.eye(3)
        solve = lambda Mx, r: list(mpmath.lu_solve(Mx, mpmath.matrix(r)))
        h11 = solve(A, B(q, qb))                   # A⁻¹ B(q, q̄)
        h20 = solve(2j * om * I3 - A, B(q, q))      # (2iω − A)⁻¹ B(q, q)
        c1 = (dot(p, C_xxy(q, qb)) - 2 * dot(p, B(q, h11)) + dot(p, B(qb, h20))) / 2
        return float(kc), float(om), float(2 * mpmath.re(c1))


@pytest.mark.parametrize("kind", sorted(RATES))
def test_derive_matches_an_independent_route(capsys, kind):
    code, out, err = run(capsys, "derive", kind, *law_args(kind), "--V", "1e-4,1e-3", "--json")
    assert code == 0, err
    for pt in json.loads(out)["points"]:
        kc, om, lam = reference(kind, pt["V"])
        assert pt["status"] == "ok"
        assert pt["kc"] == pytest.approx(kc, rel=1e-8)
        assert pt["omega_c"] == pytest.approx(om, rel=1e-8)
        assert pt["Lambda"] == pytest.approx(lam, rel=1e-8)


def test_the_lambertw_law_is_solved_numerically_not_compiled():
    from landau.laws import FrictionLaw

    law = FrictionLaw.from_strings("lw", MU, {"phi": RATES["lambertw"][0]}, {"c": 3.0})
    assert law.steady_state_closed_form is None       # sympy's LambertW form is not used
    phi = law.steady_state_values([1e-4, 1e-3], {**P})[0]
    for V, x in zip((1e-4, 1e-3), phi, strict=True):
        assert 1 - V * x / P["L"] - 3.0 * mpmath.log(1 + P["V_s"] * x / P["L"]) == pytest.approx(0, abs=1e-12)


@pytest.mark.parametrize("kind", sorted(RATES))
def test_codim2_text_and_json(capsys, kind):
    code, out, err = run(capsys, "derive", kind, *law_args(kind), "--codim2", "1e-6:1e-2")
    assert code == 0, err
    assert "Lambda5" in out and "subcritical / supercritical" in out and "fold of cycles" in out
    code, out, err = run(capsys, "derive", kind, *law_args(kind), "--codim2", "1e-6:1e-2", "--json")
    (pt,) = json.loads(out)["codim2"]
    # a sign change of Λ between the two velocities checked against the reference above
    assert 1e-4 < pt["V"] < 1e-3 and pt["Lambda5"] < 0 and pt["l2"] < 0
    assert pt["sign_below"] == 1 and pt["sign_above"] == -1


@pytest.mark.parametrize("kind", sorted(RATES))
def test_transition_runs(capsys, kind):
    code, out, err = run(capsys, "transition", kind, *law_args(kind), "--vary", "c=1:3", "--points", "3",
                         "--V-range", "1e-6:1e-2", "--json")
    assert code == 0, err
    doc = json.loads(out)
    assert [r["c"] for r in doc["curve"]] == pytest.approx([1.0, 2.0, 3.0])
    # at c = 3 the transition velocity is the codimension-two point of --codim2
    code, out, _ = run(capsys, "derive", kind, *law_args(kind), "--codim2", "1e-6:1e-2", "--json")
    assert doc["curve"][-1]["V_star"] == pytest.approx(json.loads(out)["codim2"][0]["V"], rel=1e-9)


def test_bautin_points_from_python():
    from landau.analyses.bautin import bautin_points
    from landau.derivation.multiscale import Derivation
    from landau.laws import FrictionLaw
    from landau.systems.system import SpringBlock

    law = FrictionLaw.from_strings("atan", MU, {"phi": RATES["atan"][0]}, {"c": 3.0})
    (pt,) = bautin_points(Derivation(SpringBlock(law)), 1e-6, 1e-2)
    # Λ changes sign between V = 1e-4 (subcritical) and 1e-3 m/s (supercritical), see above
    assert 1e-4 < pt.V < 1e-3 and pt.Lambda5 < 0 and pt.fold_side == -1


def test_latex_says_why_the_hopf_line_is_numerical(capsys, tmp_path):
    out = tmp_path / "atan.tex"
    code, _, err = run(capsys, "derive", "atan", *law_args("atan"), "--quantities", "kc,omega_c",
                       "--latex", str(out))
    assert code == 0, err
    text = out.read_text()
    # one state variable: the Hopf line is numerical because the steady state is, not "n > 1 states"
    assert "it depends on the steady state, which has no closed form" in text
    assert "n>1" not in text and "state variables)" not in text
