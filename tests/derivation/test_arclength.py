"""The pseudo-arclength engine (landau.analyses.arclength) on branches with closed forms."""

import math

import numpy as np
import pytest

from landau.analyses.arclength import CorrectorError, StepControl, continue_branch, newton_corrector, tangent


def circle(u):
    # G(x, λ) = x² + λ² − 1: a closed branch with folds in λ at (0, ±1)
    x, lam = u
    return np.array([x * x + lam * lam - 1.0]), np.array([[2 * x, 2 * lam]]), None


def test_circle_points_lie_on_the_branch_and_folds_are_refined():
    br = continue_branch(circle, np.array([1.0, 0.0]), StepControl(h0=0.1, h_max=0.2, h_min=1e-8),
                         orient=np.array([0.0, 1.0]), tol=1e-12, max_points=80)
    u = np.array([p.u for p in br.points])
    assert np.max(np.abs(np.hypot(u[:, 0], u[:, 1]) - 1)) < 1e-12
    # once round: the turning points in λ at λ = +1 and λ = −1, in that order
    assert len(br.folds) >= 2
    lam = [f.point.u[1] for f in br.folds[:2]]
    # bisection of the arclength to h/2¹²: |λ − (±1)| ≈ s²/2 with s ≤ 0.2/4096
    assert lam[0] == pytest.approx(1.0, abs=1e-8) and lam[1] == pytest.approx(-1.0, abs=1e-8)
    assert br.stopped == "point limit"


def test_stop_reason_and_step_growth():
    seen = []
    br = continue_branch(circle, np.array([1.0, 0.0]), StepControl(h0=0.01, h_max=0.05, h_min=1e-8),
                         orient=np.array([0.0, 1.0]), stop=lambda p: "half" if p.u[0] < 0 else None,
                         on_point=seen.append)
    assert br.stopped == "half" and br.points[-1].u[0] < 0 <= br.points[-2].u[0]
    assert len(seen) == len(br.points)
    # the step h is the chord's projection on the tangent: on the unit circle chord = h / cos(θ/2), θ ≈ h
    steps = np.linalg.norm(np.diff([p.u for p in br.points], axis=0), axis=1)
    assert steps.max() <= 0.05 / math.cos(0.026) and steps[0] == pytest.approx(0.01, rel=1e-4)
    assert steps[1] == pytest.approx(0.013, rel=1e-4)   # three Newton steps or fewer: h grows by 1.3


def test_tangent_is_the_unit_null_vector_oriented_by_the_previous_one():
    DG = np.array([[2.0, 1.0]])
    t = tangent(DG, np.array([-1.0, 1.0]))
    assert DG @ t == pytest.approx([0.0], abs=1e-15)
    # null vector ±(1, −2)/√5, turned to have a positive product with (−1, 1)
    assert t == pytest.approx([-1 / math.sqrt(5), 2 / math.sqrt(5)], rel=1e-14)
    assert tangent(DG) @ t == pytest.approx(1.0, rel=1e-14) or tangent(DG) @ t == pytest.approx(-1.0, rel=1e-14)


def test_corrector_fails_cleanly():
    with pytest.raises(CorrectorError):
        newton_corrector(lambda u: (np.array([np.nan]), np.array([[1.0, 0.0]]), None), np.zeros(2),
                         np.array([0.0, 1.0]), 1e-10)
    # no solution on the line λ = 2 (circle of radius 1): Newton cannot converge
    with pytest.raises(CorrectorError):
        newton_corrector(circle, np.array([0.5, 2.0]), np.array([0.0, 1.0]), 1e-12)


def test_step_underflow_is_reported():
    def never(u):
        return np.array([np.nan]), np.array([[1.0, 0.0]]), None

    br = continue_branch(lambda u: circle(u) if np.allclose(u, [1, 0]) else never(u), np.array([1.0, 0.0]),
                         StepControl(h0=0.1, h_max=0.1, h_min=1e-3))
    assert br.stopped.startswith("step size underflow") and len(br.points) == 1
