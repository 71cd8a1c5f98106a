"""The Dieterich law with n independent state variables (the benchmark's family): k_c, ω_c and Λ of the
derivation against an independent computation written here.

μ = a_v + a ln(v/V_*) + Σᵢ bᵢ ln(V_* φᵢ/Lᵢ), dφᵢ/dt = 1 − vφᵢ/Lᵢ on the spring–block
M ẍ = −k(x − Vt) − σ μ (Putelat et al. 2010, eqs 1–3, with n state variables).  The independent
route: the Jacobian of that vector field written out by hand in (X, u = Ẋ, φ…), the Hopf point as
the stiffness where an eigenvalue pair crosses the imaginary axis (bisection on the largest real
part, then Newton on det(iωI − A(k)) = 0 at 30 digits), and Λ = 2 Re c₁ from Kuznetsov's
projection formula (Kuznetsov 2004, §3.5, eq. 3.20) with the second and third derivatives of the
same vector field written out by hand, the critical mode normalised to q_X = 1 and ⟨p, q⟩ = 1
(landau's convention: Putelat et al. 2010, eq. 20; :mod:`landau.derivation.hopf`).

Tolerance 1e-9 relative: every value :meth:`Derivation.evaluate` returns is accurate to 1e-10
(its documented guarantee, :data:`landau.derivation.precision.REL_GOOD`); the independent values are
good to ~1e-25 (30 digits, a simple root of a well-conditioned 2×2 system).
"""

from __future__ import annotations

import mpmath
import numpy as np
import pytest

from landau.derivation.multiscale import derive
from landau.laws import FrictionLaw
from landau.systems.system import SpringBlock

V0 = 1e-5
REL = 1e-9


def _law(n: int) -> FrictionLaw:
    """The benchmark's n-state Dieterich law (benchmarks/sections_engine.py)."""
    mu = "a_v + a*log(v/V_s) + " + " + ".join(f"b{i}*log(V_s*phi{i}/L{i})" for i in range(1, n + 1))
    params = {}
    for i in range(1, n + 1):
        params[f"b{i}"] = 0.06 / n * (1 + 0.1 * i)
        params[f"L{i}"] = 1e-6 * 3.0 ** (i - 1)
    rates = {f"phi{i}": f"1 - v*phi{i}/L{i}" for i in range(1, n + 1)}
    return FrictionLaw.from_strings(f"dieterich-{n}", mu, rates, params)


class _Independent:
    """ẏ = F(y) = E⁻¹f(y) of the n-state spring–block at steady sliding, by hand (mpmath numbers)."""

    def __init__(self, n: int, p: dict):
        self.n = n
        self.M, self.sig, self.a = (mpmath.mpf(p[k]) for k in ("M", "sigma", "a"))
        self.b = [mpmath.mpf(p[f"b{i}"]) for i in range(1, n + 1)]
        self.L = [mpmath.mpf(p[f"L{i}"]) for i in range(1, n + 1)]
        self.V = mpmath.mpf(V0)
        self.phi = [L / self.V for L in self.L]          # steady state φᵢ = Lᵢ/V

    def jacobian(self, k):
        """A = E⁻¹ ∂f/∂y in (X, u, φ₁…φₙ)."""
        n, M, sig, V = self.n, self.M, self.sig, self.V
        A = mpmath.zeros(n + 2, n + 2)
        A[0, 1] = 1
        A[1, 0] = -k / M
        A[1, 1] = -sig * self.a / (V * M)                               # −σ ∂μ/∂v / M
        for i in range(n):
            A[1, 2 + i] = -sig * self.b[i] / (self.phi[i] * M)           # −σ ∂μ/∂φᵢ / M
            A[2 + i, 1] = -self.phi[i] / self.L[i]                        # ∂Rᵢ/∂v
            A[2 + i, 2 + i] = -V / self.L[i]                              # ∂Rᵢ/∂φᵢ
        return A

    def B(self, x, y):
        """Second derivative of F: ∂²μ/∂v² = −a/v², ∂²μ/∂φᵢ² = −bᵢ/φᵢ², ∂²Rᵢ/∂v∂φᵢ = −1/Lᵢ."""
        out = mpmath.zeros(self.n + 2, 1)
        s = -self.a / self.V ** 2 * x[1] * y[1]
        for i in range(self.n):
            s += -self.b[i] / self.phi[i] ** 2 * x[2 + i] * y[2 + i]
            out[2 + i] = -(x[1] * y[2 + i] + x[2 + i] * y[1]) / self.L[i]
        out[1] = -self.sig * s / self.M
        return out

    def C(self, x, y, z):
        """Third derivative of F: ∂³μ/∂v³ = 2a/v³, ∂³μ/∂φᵢ³ = 2bᵢ/φᵢ³ (the rates are bilinear)."""
        out = mpmath.zeros(self.n + 2, 1)
        s = 2 * self.a / self.V ** 3 * x[1] * y[1] * z[1]
        for i in range(self.n):
            s += 2 * self.b[i] / self.phi[i] ** 3 * x[2 + i] * y[2 + i] * z[2 + i]
        out[1] = -self.sig * s / self.M
        return out

    def hopf_point(self):
        """(k_c, ω_c): the largest stiffness where an eigenvalue pair crosses the imaginary axis."""
        def growth(k):
            ev = np.linalg.eigvals(np.array(self.jacobian(mpmath.mpf(k)).tolist(), dtype=float))
            return ev[np.argmax(ev.real)]

        hi = 1.0
        while growth(hi).real > 0:
            hi *= 2
        k = hi
        while growth(k).real < 0 and k > 1e-12:
            k /= 2
        lo = k            # unstable at lo, stable at hi: the crossing lies between
        for _ in range(200):
            mid = 0.5 * (lo + hi)
            lo, hi = (mid, hi) if growth(mid).real > 0 else (lo, mid)
            if hi - lo <= 1e-14 * hi:
                break
        om = abs(growth(hi).imag)
        n = self.n + 2

        def eqs(k, om):
            d = mpmath.det(mpmath.mpc(0, om) * mpmath.eye(n) - self.jacobian(k))
            return [d.real, d.imag]

        with mpmath.workdps(30):
            k, om = mpmath.findroot(eqs, (mpmath.mpf(hi), mpmath.mpf(om)))
        return k, om

    def lam(self, k, om):
        """Λ = 2 Re c₁ with q_X = 1, ⟨p, q⟩ = p̄ᵀq = 1 (Kuznetsov 2004, eq. 3.20)."""
        n = self.n + 2
        A = self.jacobian(k)
        iw = mpmath.mpc(0, om)
        R = A - iw * mpmath.eye(n)
        q_rest = mpmath.lu_solve(R[1:, 1:], -R[1:, 0])           # (A − iω)q = 0, q_X = 1
        q = mpmath.matrix([1] + [q_rest[i] for i in range(n - 1)])
        S = A.T + iw * mpmath.eye(n)                              # Aᵀp = −iωp, p_u = 1
        keep = [0] + list(range(2, n))
        p_rest = mpmath.lu_solve(mpmath.matrix([[S[r, c] for c in keep] for r in keep]),
                                 mpmath.matrix([-S[r, 1] for r in keep]))
        p = mpmath.matrix(n, 1)
        p[1] = 1
        for j, r in enumerate(keep):
            p[r] = p_rest[j]
        dot = lambda a, b: sum(mpmath.conj(a[i]) * b[i] for i in range(n))
        p = p / mpmath.conj(dot(p, q))
        qb = mpmath.matrix([mpmath.conj(x) for x in q])
        W0 = mpmath.lu_solve(A, self.B(q, qb))
        W2 = mpmath.lu_solve(2 * iw * mpmath.eye(n) - A, self.B(q, q))
        c1 = dot(p, self.C(q, q, qb)) / 2 - dot(p, self.B(q, W0)) + dot(p, self.B(qb, W2)) / 2
        return 2 * c1.real


def _check(n: int) -> None:
    block = SpringBlock(_law(n))
    d = derive(block, ["kc", "omega_c", "Lambda"])
    got = d.evaluate([V0], {}, ["kc", "omega_c", "Lambda"])
    ref = _Independent(n, block.resolve())
    with mpmath.workdps(30):
        kc, om = ref.hopf_point()
        lam = ref.lam(kc, om)
    for name, want in (("kc", kc), ("omega_c", om), ("Lambda", lam)):
        assert float(got[name][0]) == pytest.approx(float(want), rel=REL), (n, name)


def test_three_states_against_the_eigenvalue_crossing_and_kuznetsov():
    _check(3)


@pytest.mark.slow
def test_eight_states_against_the_eigenvalue_crossing_and_kuznetsov():
    _check(8)
