"""Bifurcations of cycles along a branch: test functions, and their location by a secant on the arclength.

At every point of a branch the test functions are (Kuznetsov 2004, Sect. 10.3; Doedel et al. 1991)

* fold of cycles (LPC): ψ_LPC = dp/ds, the parameter component of the unit tangent;
* period doubling (PD): ψ_PD = det(I + M) = Π_i (1 + μ_i), real, zero when a multiplier is −1;
* Neimark–Sacker (NS): ψ_NS = Π_{i<j} (μ_i μ_j − 1) over the nontrivial multipliers (the
  bialternate product; real, since the multipliers come in conjugate pairs), zero when two
  multipliers have product 1 — a complex pair on the unit circle (NS), or a real pair μ, 1/μ
  (a *neutral saddle*, not a bifurcation: rejected after location, where the crossing pair is real);
* branch point (BP): a sign change of the determinant of the bordered Jacobian [F_u; τᵀ] without
  a sign change of ψ_LPC.

A sign change between two points is located by the Illinois variant of regula falsi on the step
length s from the earlier point (each trial a corrector solve on the hyperplane ⟨u − u₀ − sτ₀, τ₀⟩ = 0),
to |Δs| below ``tol`` — on a smooth ψ this converges superlinearly.
"""

from __future__ import annotations

from typing import Callable

import numpy as np

from landau.periodic.floquet import Multipliers

KINDS = ("LPC", "PD", "NS")


def test_values(tangent_p: float, mu: Multipliers) -> dict[str, float]:
    """ψ_LPC, ψ_PD and ψ_NS at one point (see the module docstring)."""
    pd = float(np.prod(1.0 + mu.all).real)
    rest = mu.nontrivial
    ns = 1.0
    for i in range(rest.size):
        for j in range(i + 1, rest.size):
            ns *= rest[i] * rest[j] - 1.0
    return {"LPC": float(tangent_p), "PD": pd, "NS": float(np.real(ns))}


def changes(before: dict[str, float], after: dict[str, float]) -> list[str]:
    """The test functions whose sign changed between two points."""
    return [k for k in KINDS if np.sign(before[k]) * np.sign(after[k]) < 0]


def is_neimark_sacker(mu: Multipliers, tol: float = 1e-3) -> bool:
    """True if a complex pair (|Im μ| > tol) lies on the unit circle within tol (not a neutral saddle)."""
    rest = mu.nontrivial
    near = np.abs(np.abs(rest) - 1.0) < max(tol, 10 * float(np.min(np.abs(np.abs(rest) - 1.0))))
    return bool(np.any(near & (np.abs(rest.imag) > tol)))


def locate(psi: Callable[[float], float], s0: float, s1: float, f0: float, f1: float, *,
           tol: float = 1e-10, maxit: int = 60) -> float:
    """The root s of ψ(s) in [s0, s1] where ψ(s0) = f0 and ψ(s1) = f1 have opposite signs (Illinois)."""
    a, b, fa, fb = s0, s1, f0, f1
    s = b
    for _ in range(maxit):
        s = b - fb * (b - a) / (fb - fa)
        fs = psi(s)
        if fs == 0.0:
            return s
        if np.sign(fs) != np.sign(fb):   # the root lies between b and s
            a, fa = b, fb
        else:                            # between a and s: halve the retained value (Illinois)
            fa /= 2
        b, fb = s, fs
        if abs(b - a) < tol * max(1.0, abs(s)):
            return s
    return s
