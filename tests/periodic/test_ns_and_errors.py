"""Neimark–Sacker detection (and a neutral saddle rejected), the end reasons, errors and the outputs."""

from __future__ import annotations

import numpy as np
import pytest
from cycle_systems import stuart_landau

from landau.errors import InputError, IntegratorError
from landau.periodic import CycleProblem, CycleStart, continue_cycles


def _product(transverse: str, omega_t: float = 0.7) -> CycleProblem:
    """A unit cycle (x, y), period 2π, times a transverse pair (u, v) whose linear part at 0 gives the
    nontrivial multipliers in closed form: "focus" e^{(μ ± iΩ)2π} (a Neimark–Sacker at μ = 0),
    "saddle" e^{(μ ± 1)2π} (product 1 at μ = 0: a neutral saddle, no bifurcation)."""

    def rhs(y, mu):
        x, yy, u, v = y
        r2 = x * x + yy * yy
        if transverse == "focus":
            du, dv = mu * u - omega_t * v - u * (u * u + v * v), omega_t * u + mu * v - v * (u * u + v * v)
        else:
            du, dv = (mu + 1) * u - u ** 3, (mu - 1) * v - v ** 3
        return np.array([x * (1 - r2) - yy, yy * (1 - r2) + x, du, dv])

    def jac(y, mu, h=1e-6):
        y = np.asarray(y, dtype=float)
        cols = [(rhs(y + h * e.reshape((4,) + (1,) * (y.ndim - 1)), mu)
                 - rhs(y - h * e.reshape((4,) + (1,) * (y.ndim - 1)), mu)) / (2 * h) for e in np.eye(4)]
        return np.stack(cols, axis=1)

    return CycleProblem(f"cycle-x-{transverse}", ("x", "y", "u", "v"), "mu", rhs, jac)


def _unit_cycle(mu: float) -> CycleStart:
    t = np.linspace(0, 2 * np.pi, 60, endpoint=False)
    return CycleStart(t, np.array([np.cos(t), np.sin(t), 0 * t, 0 * t]), 2 * np.pi, mu)


def test_neimark_sacker_located_with_its_closed_form_multipliers():
    br = continue_cycles(_product("focus"), _unit_cycle(-0.3), steps=12, ds=0.1, ntst=20)
    ns = br.points("NS")
    assert len(ns) == 1 and abs(ns[0].parameter) < 1e-9
    mu = ns[0].multipliers
    pair = mu[np.abs(mu.imag) > 1e-3]
    # the pair e^{±iΩT}, Ω = 0.7, T = 2π
    expected = np.exp(2j * np.pi * 0.7 * np.array([1, -1]))
    np.testing.assert_allclose(np.sort_complex(pair), np.sort_complex(expected), atol=1e-8)
    assert br.stable[ns[0].index] and not br.stable[ns[0].index + 1]


def test_neutral_saddle_is_not_reported_as_neimark_sacker():
    br = continue_cycles(_product("saddle"), _unit_cycle(-0.3), steps=8, ds=0.1, ntst=20)
    assert min(br.parameter) < 0 < max(br.parameter)
    assert not br.points("NS")


def test_end_reasons_keep_the_branch_and_strict_raises_with_it():
    pr = stuart_landau()
    br = continue_cycles(pr, steps=50, ds=0.05, ntst=16, max_period=2.0)     # T = 2π/1.3 ≈ 4.8 > 2
    assert br.end.name == "MAX_PERIOD" and len(br) >= 1 and "max_period" in br.message
    with pytest.raises(IntegratorError, match="max_period") as err:
        continue_cycles(pr, steps=50, ds=0.05, ntst=16, max_period=2.0, strict=True)
    assert len(err.value.branch) == len(br)
    # continued back towards the Hopf point the cycle collapses
    t = np.linspace(0, 2 * np.pi / 1.3, 40, endpoint=False)
    start = CycleStart(t, 0.5 * np.array([np.cos(1.3 * t), np.sin(1.3 * t)]), 2 * np.pi / 1.3, 0.25)
    back = continue_cycles(pr, start, steps=200, ds=0.05, ntst=16, direction=-1)
    assert back.end.name == "COLLAPSE" and min(back.parameter) < 0.01 and "Hopf" in back.message


def test_bad_input_is_an_input_error():
    pr = stuart_landau()
    with pytest.raises(InputError, match="direction"):
        continue_cycles(pr, direction=0)
    with pytest.raises(InputError, match="no start"):
        continue_cycles(CycleProblem("p", ("a", "b"), "q", pr.rhs, pr.jac))
    with pytest.raises(InputError, match="increasing"):
        CycleStart(np.array([0.0, 1.0, 0.5, 2.0]), np.zeros((2, 4)), 1.0, 0.0)
    with pytest.raises(InputError, match="period"):
        CycleStart(np.arange(5.0), np.zeros((2, 5)), -1.0, 0.0)
    with pytest.raises(InputError, match="3 states"):
        continue_cycles(pr, CycleStart(np.arange(5.0), np.zeros((3, 5)), 5.0, 0.1))


def test_first_cycle_failure_is_an_integrator_error():
    pr = stuart_landau()
    # a guess at μ < 0, where no cycle exists: Newton cannot converge at fixed μ
    t = np.linspace(0, 5, 30, endpoint=False)
    with pytest.raises(IntegratorError, match="first cycle") as err:
        continue_cycles(pr, CycleStart(t, np.array([np.cos(t), np.sin(t)]), 5.0, -1.0, exact=False), ntst=16)
    assert err.value.branch.end.name == "FIRST_POINT"


def test_dataset_and_cycle_outputs():
    br = continue_cycles(stuart_landau(), steps=5, ds=0.05, ntst=16)
    ds = br.to_dataset()
    assert ds.sizes["point"] == 6 and ds.sizes["state"] == 2 and ds.sizes["multiplier"] == 2
    assert ds.attrs["route"] == "hopf" and ds.attrs["end_reason"] == "STEPS" and ds.attrs["ntst"] == 16
    np.testing.assert_allclose(ds["amplitude"].values, br.amplitude)
    t, Y = br.cycle(3)
    assert t[0] == 0 and abs(t[-1] - br.period[3]) < 1e-12 and Y.shape == (2, t.size)
    np.testing.assert_allclose(Y[:, 0], Y[:, -1])
