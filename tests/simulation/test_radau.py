"""The compiled order-5 Radau IIA (landau.verify.hybrid.radau) against closed forms.

Hairer & Wanner (1996), *Solving ODEs II*, Sec. IV.8: the simplified Newton iteration in the
eigenbasis of A⁻¹ (one real and one complex n × n system).  Checked against closed-form
solutions (decay, harmonic oscillator and its zero crossings, a stiff linear system through
the matrix exponential), on the Fig. 3 stick–slip cycle of Putelat et al. (2010) against the
period found by shooting, and as plain Python (``NUMBA_DISABLE_JIT=1``) against the compiled run.
"""

from __future__ import annotations

import json
import os
import subprocess
import sys

import numpy as np
import pytest
import scipy.linalg
import sympy as sp

from landau.codegen.kernels import generate_kernel
from landau.errors import InputError
from landau.verify.hybrid.radau import (
    A_RADAU,
    ALPHA_SPLIT,
    BETA_SPLIT,
    GAMMA_SPLIT,
    MU_REAL,
    VINV,
    radau_core,
    split_coefficients,
)


def _run(kernel, y0, t_end, rtol, ev_idx=-1, ev_dir=0, ev_stop=0, max_steps=10 ** 6, rec_cap=0):
    y0 = np.asarray(y0, dtype=float)
    n = len(y0)
    buf, dirs = np.empty((20, n + 1)), np.zeros(20)
    return radau_core(kernel.fun, kernel.jac, 0.0, y0, t_end, kernel.p, rtol, np.full(n, rtol), 1e-4, np.inf,
                      max_steps, ev_idx, 0.0, ev_dir, ev_stop, rec_cap, A_RADAU, VINV, buf, dirs), dirs


@pytest.fixture(scope="module")
def oscillator():
    x, v = sp.symbols("x v")
    return generate_kernel([x, v], [v, -4 * x], [], [], name="radau_oscillator_omega2")


def test_split_coefficients_match_the_closed_forms():
    """γ = 3 + 3^{2/3} − 3^{1/3}, α ± iβ = 3 − (3^{2/3} − 3^{1/3})/2 ± i(3^{7/6} + 3^{5/6})/2
    (Hairer & Wanner 1996, IV.8), and T·Λ·T⁻¹ = A⁻¹ to rounding."""
    T, TI, g, a, b = split_coefficients(A_RADAU)
    assert g == pytest.approx(MU_REAL, rel=1e-14) and g == GAMMA_SPLIT
    assert a == pytest.approx(3 - (3 ** (2 / 3) - 3 ** (1 / 3)) / 2, rel=1e-13) and a == ALPHA_SPLIT
    assert b == pytest.approx((3 ** (7 / 6) + 3 ** (5 / 6)) / 2, rel=1e-13) and b == BETA_SPLIT
    lam = np.array([[g, 0, 0], [0, a, -b], [0, b, a]])
    assert np.allclose(T @ lam @ TI, np.linalg.inv(A_RADAU), rtol=0, atol=1e-12)
    with pytest.raises(InputError, match="3 x 3"):
        split_coefficients(np.eye(2))


def test_decay_matches_exp_and_outputs_are_owned():
    """y' = −k y on three components: y(5) = e^{−5k} y0; the returned arrays share no memory with
    the inputs and stay unchanged after a second run."""
    y = sp.symbols("y0:3")
    rates = (1, 3, 7)
    k = generate_kernel(list(y), [-r * yi for r, yi in zip(rates, y, strict=True)], [], [], name="radau_decay3")
    y0 = np.array([1.0, 2.0, -1.0])
    (st, t, yend, cnt, ev_t, ev_y, rec_t, rec_y, h, Q), _ = _run(k, y0, 5.0, 1e-10, rec_cap=50)
    assert st == 0 and t == 5.0
    # rtol 1e-10 per step over ~100 steps: global error ≲ 1e-9 (measured below 1e-10)
    assert np.max(np.abs(yend - np.exp(-5.0 * np.array(rates)) * y0)) < 1e-9
    assert cnt[5] == 0          # no Newton failure on a linear problem
    assert len(rec_t) == 50 and rec_t[0] == 0.0 and np.array_equal(rec_y[0], y0)
    assert np.allclose(rec_y[1:], np.exp(-np.outer(rec_t[1:], rates)) * y0, rtol=1e-8, atol=1e-12)
    assert y0.tolist() == [1.0, 2.0, -1.0]
    keep = yend.copy(), rec_y.copy()
    assert not np.shares_memory(yend, y0) and not np.shares_memory(rec_y, yend)
    _run(k, 2 * y0, 1.0, 1e-6, rec_cap=50)
    assert np.array_equal(yend, keep[0]) and np.array_equal(rec_y, keep[1])


def test_harmonic_oscillator_and_its_crossings(oscillator):
    """x'' = −4x from (1, 0) (two states): x = cos 2t, and the crossings of x = 0 at
    t = π/4 + jπ/2 located on the collocation cubic; the run stops at the second downward one."""
    (st, t, yend, cnt, *_), _ = _run(oscillator, [1.0, 0.0], 10.0, 1e-10)
    assert st == 0
    assert np.allclose(yend, [np.cos(20.0), -2 * np.sin(20.0)], rtol=0, atol=1e-8)
    (st, t, yend, cnt, ev_t, ev_y, *_), dirs = _run(oscillator, [1.0, 0.0], 10.0, 1e-10, ev_idx=0, ev_dir=-1,
                                                    ev_stop=2)
    assert st == 1 and len(ev_t) == 3 and cnt[6] == 3
    # measured 5e-14 s; a crossing on the wrong step or a wrong dense output is off by ≥ 1e-4 s
    assert np.allclose(ev_t, np.pi / 4 + np.pi / 2 * np.arange(3), rtol=0, atol=1e-9)
    assert list(dirs[:3]) == [-1, 1, -1]
    assert np.allclose(ev_y[:, 0], 0.0, atol=1e-10)
    assert np.allclose(ev_y[:, 1], [-2.0, 2.0, -2.0], rtol=0, atol=2e-9)     # ẋ = −2 sin 2t
    assert ev_t[-1] <= t < ev_t[-1] + 0.1                                      # stopped at that step


def test_status_codes(oscillator):
    (st, t, y, cnt, *_), _ = _run(oscillator, [np.nan, 0.0], 1.0, 1e-8, max_steps=100)
    assert (st, t, cnt[0] + cnt[1]) == (-3, 0.0, 0)             # non-finite start: no step
    (st, t, y, cnt, *_), _ = _run(oscillator, [1.0, 0.0], 100.0, 1e-8, max_steps=5)
    assert (st, cnt[0] + cnt[1]) == (-2, 5) and 0.0 < t < 100.0  # step budget
    (st, t, y, cnt, *_), _ = _run(oscillator, [1.0, 0.0], 1.0, 1e-8)
    assert (st, t) == (0, 1.0)                                   # the end is hit exactly
    assert abs(y[0] - np.cos(2.0)) < 4e-8                        # measured 1e-11


def test_stiff_linear_system_matches_expm():
    """y' = My with eigenvalues −1, −10³, −10⁵ (non-normal M = S·diag·S⁻¹): y(2) = e^{2M} y0
    (scipy.linalg.expm); the stiffness ratio 10⁵ is what the implicit method is for."""
    S = np.array([[1.0, 0.5, 0.2], [0.0, 1.0, 0.3], [0.1, 0.0, 1.0]])
    M = S @ np.diag([-1.0, -1e3, -1e5]) @ np.linalg.inv(S)
    y = sp.symbols("y0:3")
    rhs = list(sp.Matrix(M.tolist()) * sp.Matrix(y))
    k = generate_kernel(list(y), rhs, [], [], name="radau_stiff_linear3")
    y0 = np.array([1.0, -1.0, 2.0])
    (st, t, yend, cnt, *_), _ = _run(k, y0, 2.0, 1e-9)
    assert st == 0
    assert np.max(np.abs(yend - scipy.linalg.expm(2.0 * M) @ y0)) < 1e-8
    # the steps follow the slow mode, not the fast one (explicit stability would need ~10⁵ steps)
    assert cnt[0] < 500


def test_only_its_own_coefficients_and_method_name_are_accepted(oscillator):
    with pytest.raises(InputError, match="AR"):
        radau_core(oscillator.fun, oscillator.jac, 0.0, np.array([1.0, 0.0]), 1.0, oscillator.p, 1e-6,
                   np.full(2, 1e-6), 1e-3, np.inf, 100, -1, 0.0, 0, 0, 0, 2 * A_RADAU, VINV)
    from landau.verify.springblock.simulate import integrate
    from landau.verify.springblock.workprecision import fig3_model

    model = fig3_model()
    for name in ("radau9", "rodas4", "auto", "radau5t"):
        with pytest.raises(InputError, match=f"got '{name}'"):
            integrate(model, model.perturbed(1e-7), (0.0, 1.0), method=name)


def test_fig3_period_agrees_with_shooting():
    """The period of the Fig. 3 cycle (Putelat et al. 2010) from the downward returns to w = 0 at
    rtol 1e-10 agrees with the period found by shooting at rtol 1e-11 to 1e-8 of the period
    (measured 4e-15: the returns are located on the collocation cubic of the same method)."""
    from landau.verify.hybrid.result import Status
    from landau.verify.springblock.simulate import W_INDEX, integrate
    from landau.verify.springblock.workprecision import fig3_cycle, fig3_model

    model = fig3_model()
    orbit = fig3_cycle(model)
    y0 = np.insert(orbit.z, W_INDEX, 0.0)
    run = integrate(model, y0, (0.0, 3 * orbit.period), rtol=1e-10, event_index=W_INDEX, event_direction=-1,
                    stop_after=2)
    td = run.event_t[run.event_dir < 0]
    assert run.status is Status.STOPPED and len(td) == 2
    assert abs(td[0] - orbit.period) < 1e-8 * orbit.period
    assert abs(td[1] - 2 * orbit.period) < 2e-8 * orbit.period
    assert run.success and len(run.events) == len(run.event_t)


_SHORT_RUN = """
import json, sys, warnings
import numpy as np
warnings.simplefilter("always")
from landau.verify.springblock.simulate import W_INDEX, integrate
from landau.verify.springblock.workprecision import fig3_model
model = fig3_model()
run = integrate(model, model.perturbed(1e-6), (0.0, {t_end}), rtol=1e-8, event_index=W_INDEX)
print(json.dumps({{"y": run.y_final.tolist(), "steps": run.nsteps, "t": run.t_final}}))
"""


def test_runs_as_plain_python_and_agrees_with_the_compiled_run():
    """With NUMBA_DISABLE_JIT=1 the integrator and the kernels run as Python (a warning says so)
    and give the compiled run's result: the same steps, states equal to rounding (the compiled
    code and Python evaluate exp/log through different libraries; rtol 1e-8 per step)."""
    code = _SHORT_RUN.format(t_end=0.2)      # about a hundred steps and a crossing of w = 0
    env = dict(os.environ)
    compiled = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, env=env, timeout=600)
    assert compiled.returncode == 0, compiled.stderr
    env["NUMBA_DISABLE_JIT"] = "1"
    plain = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, env=env, timeout=600)
    assert plain.returncode == 0, plain.stderr
    assert "NUMBA_DISABLE_JIT" in plain.stderr and plain.stderr.count("runs as plain Python") == 1
    a = json.loads(compiled.stdout.strip().splitlines()[-1])
    b = json.loads(plain.stdout.strip().splitlines()[-1])
    assert a["steps"] > 20 and a["steps"] == b["steps"] and a["t"] == b["t"]
    assert np.allclose(a["y"], b["y"], rtol=1e-10, atol=1e-12)


@pytest.mark.skipif(os.environ.get("NUMBA_DISABLE_JIT") == "1", reason="no compiler: nothing to build")
def test_nothing_compiles_at_import():
    """Importing the integrator and the spring–block simulation compiles no numba function."""
    code = ("import landau.verify.springblock.simulate, landau.verify.hybrid.radau as R\n"
            "import landau.verify.hybrid.crossing as C, landau.verify.hybrid.radau_linalg as L\n"
            "fs = [R._radau_loop, L.lu, L.solve, L.stage_jacobians, C.cubic_crossing, R._crossings]\n"
            "print(sum(len(f.signatures) for f in fs))\n")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=300)
    assert out.returncode == 0, out.stderr
    assert out.stdout.strip() == "0"


def test_reuse_policy_keeps_the_jacobian_and_the_factors_on_a_smooth_problem():
    """Hairer's reuse policy (radau5): on the pendulum x'' = −sin x from (1, 0) over t ∈ [0, 10]
    the simplified Newton iteration contracts fast, so J is kept over many steps (radau5's θ ≤ THET)
    and the two LU factors survive the steps whose size the controller holds (ratio in [1, 1.2]);
    a core that recomputes J and both factors every step has njev = steps and nlu = 2·steps.
    The solution stays within tolerance of scipy's DOP853 at rtol = atol = 1e-12 (an explicit
    method: an independent route)."""
    from scipy.integrate import solve_ivp

    x, v = sp.symbols("x v")
    k = generate_kernel([x, v], [v, -sp.sin(x)], [], [], name="radau_pendulum")
    (st, t, yend, cnt, *_), _ = _run(k, [1.0, 0.0], 10.0, 1e-8)
    steps, njev, nlu = int(cnt[0]), int(cnt[3]), int(cnt[4])
    assert st == 0 and t == 10.0
    # measured 256 steps, 13 Jacobians and 212 factorisations (106 real + 106 complex) on this machine
    assert njev < steps / 4 and nlu < steps
    ref = solve_ivp(lambda _t, y: [y[1], -np.sin(y[0])], (0.0, 10.0), [1.0, 0.0], method="DOP853", rtol=1e-12,
                    atol=1e-12).y[:, -1]
    # rtol 1e-8 per step over ~250 steps: global error ≲ 1e-8 (measured 1.3e-10)
    assert np.max(np.abs(yend - ref)) < 1e-8
