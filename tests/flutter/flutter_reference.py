"""Independent reference computations for the flutter tests, written from the equations of
Hoffmann et al. (2002) and Kuznetsov (2004) without landau's assembly or engine.

* :func:`assembled` — M, C, K_eff of the 2-DOF model by hand (equilibrium by scipy's fsolve);
* :func:`bisect_threshold` — the first μ where max Re λ of [[0, I], [−M⁻¹K, −M⁻¹C]] turns positive,
  by plain bisection;
* :func:`kuznetsov_l1` — Kuznetsov's invariant formula for c₁ (2004, eq. 3.20) on the first-order
  system, with the contact's derivatives N'', N''' by hand, and dλ/dμ by a five-point stencil.
"""

from __future__ import annotations

import math

import numpy as np
import scipy.optimize


def stiffness(k1, k2, a1_deg, a2_deg):
    a1, a2 = math.radians(a1_deg), math.radians(a2_deg)
    return (k1 * math.cos(a1) ** 2 + k2 * math.cos(a2) ** 2,
            k1 * math.sin(a1) * math.cos(a1) - k2 * math.sin(a2) * math.cos(a2),
            k1 * math.sin(a1) ** 2 + k2 * math.sin(a2) ** 2)


def contact(kind, kH, kNL, y):
    """(N, N', N'', N''') at penetration y."""
    if kind == "linear":
        return kH * y, kH, 0.0, 0.0
    if kind == "cubic":
        return kH * y + kNL * y**3, kH + 3 * kNL * y**2, 6 * kNL * y, 6 * kNL
    return kH * y**1.5, 1.5 * kH * y**0.5, 0.75 * kH * y**-0.5, -0.375 * kH * y**-1.5


def equilibrium(p, mu, kind):
    k11, k12, k22 = stiffness(p["k1"], p["k2"], p["alpha1"], p["alpha2"])

    def F(z):
        x, y = z
        N = contact(kind, p["kH"], p["kNL"], abs(y))[0]
        return [k11 * x + k12 * y - mu * N, k12 * x + k22 * y - p["P"] + N]

    y_lin = p["P"] / (k22 + p["kH"])
    sol = scipy.optimize.fsolve(F, [0.0, y_lin], xtol=1e-15, full_output=True)
    return sol[0]


def first_order(p, mu, kind):
    """A of ż = A z, z = (x, y, ẋ, ẏ) − equilibrium, and the equilibrium's y."""
    k11, k12, k22 = stiffness(p["k1"], p["k2"], p["alpha1"], p["alpha2"])
    _, y = equilibrium(p, mu, kind)
    _, kN, _, _ = contact(kind, p["kH"], p["kNL"], y)
    m = p["m"]
    K = np.array([[k11, k12 - mu * kN], [k12, k22 + kN]])
    C = np.diag([p["c1"], p["c2"]])
    A = np.zeros((4, 4))
    A[:2, 2:] = np.eye(2)
    A[2:, :2] = -K / m
    A[2:, 2:] = -C / m
    return A, y


def bisect_threshold(growth, lo, hi, tol=1e-14):
    """Plain bisection on the sign of ``growth`` (negative at lo, positive at hi)."""
    assert growth(lo) < 0 < growth(hi)
    while hi - lo > tol * max(1.0, abs(hi)):
        mid = 0.5 * (lo + hi)
        if growth(mid) > 0:
            hi = mid
        else:
            lo = mid
    return 0.5 * (lo + hi)


def scan_bisect(growth, lo, hi, n=400):
    grid = np.linspace(lo, hi, n + 1)
    g = [growth(x) for x in grid]
    for i in range(n):
        if g[i] < 0 < g[i + 1]:
            return bisect_threshold(growth, grid[i], grid[i + 1])
    raise AssertionError("no threshold in the bracket")


def damped_threshold(p, kind, lo=0.0, hi=2.0):
    def growth(mu):
        return float(np.max(np.linalg.eigvals(first_order(p, mu, kind)[0]).real))

    return scan_bisect(growth, lo, hi)


def critical_eigenvalue(p, mu, kind, omega):
    lam = np.linalg.eigvals(first_order(p, mu, kind)[0])
    return lam[np.argmin(np.abs(lam - 1j * omega))]


def kuznetsov_l1(p, mu_c, kind):
    """(Λ, C, |q_y/q_x|, l₁) at the Hopf point μ_c by Kuznetsov's formula (landau's convention for Λ, C)."""
    A, y = first_order(p, mu_c, kind)
    _, _, N2, N3 = contact(kind, p["kH"], p["kNL"], y)
    m = p["m"]
    # the nonlinear terms only act through N(y): f = ... + (μ e_ẋ − e_ẏ) N(y)/m
    d = np.array([0.0, 0.0, mu_c / m, -1.0 / m])

    def B(a, b):
        return d * N2 * a[1] * b[1]

    def Cm(a, b, c):
        return d * N3 * a[1] * b[1] * c[1]

    lam, vec = np.linalg.eig(A)
    j = int(np.argmax(lam.imag * (np.abs(lam.real) < 1e-6 * np.abs(lam))))
    omega = lam[j].imag
    q = vec[:, j] / np.linalg.norm(vec[:, j])
    lamT, vecT = np.linalg.eig(A.T)
    k = int(np.argmin(np.abs(lamT + 1j * omega)))
    pv = vecT[:, k]
    pv = pv / np.vdot(pv, q).conj()          # <p, q> = p̄ᵀ q = 1
    assert abs(np.vdot(pv, q) - 1) < 1e-12
    I4 = np.eye(4)
    h11 = np.linalg.solve(A, B(q, q.conj()))
    h20 = np.linalg.solve(2j * omega * I4 - A, B(q, q))
    c1 = (0.5 * np.vdot(pv, Cm(q, q, q.conj())) - np.vdot(pv, B(q, h11)) + 0.5 * np.vdot(pv, B(q.conj(), h20)))
    # a = dλ/dμ by a five-point stencil of the hand-assembled matrices (equilibrium moved with μ)
    h = 1e-4 * mu_c
    lam_at = [critical_eigenvalue(p, mu_c + s * h, kind, omega) for s in (-2, -1, 1, 2)]
    a = (lam_at[0] - 8 * lam_at[1] + 8 * lam_at[2] - lam_at[3]) / (12 * h)
    qx = abs(q[0])
    Lambda = 2 * c1.real / qx**2
    C = 2 * qx * math.sqrt(abs(a.real) / abs(c1.real))
    return Lambda, C, abs(q[1] / q[0]), c1.real / omega
