"""The compiled DOP853 stepper and the engine's compiled quiet runs.

* The dense output is DOP853's continuous extension of order 7 (Hairer, Nørsett & Wanner,
  *Solving ODEs I*, II.6): checked against the closed-form harmonic oscillator, its error
  inside a fixed step falls like h⁸.
* Quiet steps of a mode whose guards are affine run in one compiled call
  (``DOP853Solver.run_quiet``); the test is the engine's dense-output scan test, so the
  events are those of the same stepper scanning every step on the same dense output
  (``EngineOptions(screen=False)``) — to the last bit, since the steps are the same — and,
  as the steps are scipy's, those of scipy's DOP853 to rounding.
* The Galvanetto (2004) models declare their guards as affine forms (of the state and, for the
  velocity extrema, the field) and their modes' fields as generated kernels: both checked
  against the Python guards and right-hand sides.
"""

from __future__ import annotations

import numpy as np
import pytest
import sympy as sp

from landau.codegen.kernels import generate_kernel
from landau.verify.galvanetto.maps import gsp_start, model_for
from landau.verify.galvanetto.model import build_model, one_block, two_blocks
from landau.verify.hybrid import EngineOptions, ScipyStepper, simulate
from landau.verify.hybrid.dop853 import CompiledDOP853

_x, _v = sp.symbols("x v")


def _first_step_dense_error(h: float) -> float:
    """Max error of the dense output inside one fixed step of x'' = -x from (1, 0)."""
    k = generate_kernel([_x, _v], [_v, -_x], name="harmonic")
    s = CompiledDOP853(rtol=0.5, atol=0.5, first_step=h, max_step=h)(k, 0.0, [1.0, 0.0], 10.0)
    assert s.step() is None and s.t == pytest.approx(h, rel=1e-15)
    ts = np.linspace(0.0, h, 41)
    y = s.dense_output()(ts)
    # the dense output interpolates the step ends (to rounding)
    np.testing.assert_allclose(y[:, 0], [1.0, 0.0], rtol=0, atol=1e-15)
    np.testing.assert_allclose(y[:, -1], s.y, rtol=0, atol=1e-15)
    return float(np.max(np.abs(y - np.array([np.cos(ts), -np.sin(ts)]))))


def test_dense_output_is_scipys_and_converges_like_h8():
    e1, e2 = _first_step_dense_error(0.8), _first_step_dense_error(0.4)
    # O(h⁸) local error of the order-7 interpolant: halving h divides it by 256 (≥ 120 leaves
    # room for the next term at h = 0.8)
    assert e1 / e2 > 120
    # the same interpolant as scipy's DOP853 on the same step
    k = generate_kernel([_x, _v], [_v, -_x], name="harmonic")
    ours = CompiledDOP853(rtol=0.5, atol=0.5, first_step=0.4, max_step=0.4)(k, 0.0, [1.0, 0.0], 10.0)
    ref = ScipyStepper("DOP853", 0.5, 0.5, max_step=0.4, first_step=0.4)(k, 0.0, np.array([1.0, 0.0]), 10.0)
    ours.step(), ref.step()
    ts = np.linspace(0.0, 0.4, 9)
    np.testing.assert_allclose(ours.dense_output()(ts), ref.dense_output()(ts), rtol=0, atol=1e-15)


def test_a_mode_without_kernel_runs_on_scipys_dop853():
    from scipy.integrate import DOP853

    s = CompiledDOP853(1e-8, 1e-10)(lambda t, y: -y, 0.0, np.array([1.0]), 1.0)
    assert isinstance(s, DOP853)


def _events(sol):
    return [(e.guard, e.from_mode, e.to_mode, e.kind) for e in sol.events]


def test_compiled_quiet_run_logs_the_dense_scan_events_two_blocks():
    """One step of the two-block event map (eight switching events, Galvanetto 2004 Sec. 2.2)."""
    p = two_blocks(0.25, beta=1.722)
    mode, y0 = gsp_start(p, -0.3)
    run = lambda stepper, opts: simulate(model_for(p), mode, y0, (0.0, 300.0), stepper, opts,
                                         stop=lambda ev: ev.to_mode == "ss")
    st = CompiledDOP853(1e-10, 1e-12, max_step=1.0)
    fast = run(st, EngineOptions(record=False))
    scan = run(st, EngineOptions(record=False, screen=False))
    same = run(ScipyStepper("DOP853", 1e-10, 1e-12, max_step=1.0), EngineOptions(record=False, screen=False))
    ref = run(ScipyStepper("DOP853", 1e-12, 1e-14), EngineOptions(record=False))
    assert len(fast.events) == 8
    assert _events(fast) == _events(scan) == _events(same) == _events(ref)
    # same steps, same dense output, same scan: the same event times to the last bit
    assert [e.t for e in fast.events] == [e.t for e in scan.events]
    assert fast.nsteps == scan.nsteps
    # scipy's DOP853 at the same tolerances takes the same steps: event times to rounding
    np.testing.assert_allclose([e.t for e in fast.events], [e.t for e in same.events], rtol=0, atol=1e-12)
    # against scipy's DOP853 at rtol 1e-12: within the integration tolerance
    np.testing.assert_allclose([e.t for e in fast.events], [e.t for e in ref.events], rtol=0, atol=1e-7)


def test_compiled_quiet_run_one_block_event_time():
    """Slip→stick time of the one-block cycle (Galvanetto 2004, Fig. 7a: γ = 3, δ = 0.2, V = 1)."""
    p = one_block(1.0, gamma=3.0, delta=0.2)
    run = lambda stepper, opts=EngineOptions(record=False): simulate(
        model_for(p), "n", np.array([1.0, 1.0]), (0.0, 50.0), stepper, opts, stop=lambda ev: ev.to_mode == "s")
    st = CompiledDOP853(1e-12, 1e-14)
    fast = run(st)
    scan = run(st, EngineOptions(record=False, screen=False))
    ref = run(ScipyStepper("DOP853", 1e-13, 1e-15))
    assert _events(fast) == _events(scan) == _events(ref)
    # the compiled quiet run takes the steps the per-step scan takes: the same event time exactly
    assert fast.t_final == scan.t_final and fast.nsteps == scan.nsteps
    assert abs(fast.t_final - ref.t_final) < 1e-11
    assert fast.nsteps > 10              # many steps, taken in the compiled loop


@pytest.mark.parametrize("p", [one_block(0.7, gamma=2.0, delta=0.2, c=0.3),
                               two_blocks(0.25, alpha=1.2, beta=1.722, delta=0.1).with_(c=0.2)])
def test_galvanetto_affine_guards_and_kernels_match_the_python_model(p):
    rng = np.random.default_rng(1)
    model = build_model(p, sections=True)
    n = 2 * p.n
    for mode in model.modes.values():
        Y = rng.normal(size=(n, 5))
        Y[p.n:] = p.V + 0.05 * rng.normal(size=(p.n, 5))   # slip velocities near the belt's
        k = mode.kernel()
        F = np.column_stack([mode.rhs(0.0, y) for y in Y.T])
        for g in mode.guards:
            assert g.affine is not None
            w, b, *u = g.affine      # the r-extrema (rmax, rmin) are ± a component of the field
            expect = np.asarray(w) @ Y + b + (np.asarray(u[0]) @ F if u else 0.0)
            np.testing.assert_allclose(expect, g.fun(0.0, Y), rtol=0, atol=1e-13)
        for y in Y.T:
            np.testing.assert_allclose(k(0.0, y), mode.rhs(0.0, y), rtol=1e-14, atol=1e-14)


def test_the_first_field_value_comes_from_the_loops_cfunc_without_compiling_the_kernels_dispatcher():
    """f(t0, y0) of a compiled DOP853 run is evaluated by the cfunc its loops call: the kernel's own
    numba dispatcher, which nothing else of the run calls, is never compiled (one build per kernel
    saved on a first run)."""
    q = sp.Symbol("q")
    k = generate_kernel([_x, _v], [_v, -q * _x - _v ** 3 / 4], [q], [2.5], name="cubic-damped")
    s = CompiledDOP853(rtol=1e-8, atol=1e-10)(k, 0.0, [0.6, -0.8], 5.0)
    # closed form: (v, -q x - v³/4) at (0.6, -0.8), q = 2.5
    np.testing.assert_allclose(s.f, [-0.8, -2.5 * 0.6 + 0.8 ** 3 / 4], rtol=1e-15, atol=0)
    assert len(k.fun.signatures) == 0
