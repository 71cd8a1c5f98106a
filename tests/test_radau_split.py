"""The order-5 Radau IIA with its Newton system in the eigenbasis of A⁻¹ (``method="radau5t"``).

Hairer & Wanner (1996), *Solving ODEs II*, Sec. IV.8: one real and one complex n × n system per
Newton iteration instead of the 3n × 3n one.  Checked against closed-form solutions and, on the
Fig. 3 stick–slip cycle of Putelat et al. (2010), against the default untransformed core.
"""

from __future__ import annotations

import numpy as np
import pytest
import scipy.linalg
import sympy as sp

from landau.codegen.kernels import generate_kernel
from landau.verify.hybrid.collocation import split_coefficients
from landau.verify.hybrid.fastcall import addresses, radau_split_at
from landau.verify.hybrid.radau import (A_RADAU, ALPHA_SPLIT, BETA_SPLIT, GAMMA_SPLIT, MU_REAL, T_SPLIT, TI_SPLIT,
                                        VINV)


def _run(kernel, y0, t_end, rtol, ev_idx=-1, ev_dir=0, ev_stop=0):
    af, aj = addresses(kernel.fun, kernel.jac)
    y0 = np.asarray(y0, dtype=float)
    n = len(y0)
    buf, dirs = np.empty((20, n + 1)), np.zeros(20)
    return radau_split_at(af, aj, 0.0, y0, t_end, kernel.p, rtol, np.full(n, rtol), 1e-4, np.inf, 10 ** 6, ev_idx,
                          0.0, ev_dir, ev_stop, 0, A_RADAU, VINV, T_SPLIT, TI_SPLIT, GAMMA_SPLIT, ALPHA_SPLIT,
                          BETA_SPLIT, buf, dirs), dirs


def test_split_coefficients_match_the_closed_forms():
    """γ = 3 + 3^{2/3} − 3^{1/3}, α ± iβ = 3 − (3^{2/3} − 3^{1/3})/2 ± i(3^{7/6} + 3^{5/6})/2
    (Hairer & Wanner 1996, IV.8), and T·Λ·T⁻¹ = A⁻¹ to rounding."""
    T, TI, g, a, b = split_coefficients(A_RADAU)
    assert g == pytest.approx(MU_REAL, rel=1e-14)
    assert a == pytest.approx(3 - (3 ** (2 / 3) - 3 ** (1 / 3)) / 2, rel=1e-13)
    assert b == pytest.approx((3 ** (7 / 6) + 3 ** (5 / 6)) / 2, rel=1e-13)
    lam = np.array([[g, 0, 0], [0, a, -b], [0, b, a]])
    assert np.allclose(T @ lam @ TI, np.linalg.inv(A_RADAU), rtol=0, atol=1e-12)


def test_decay_matches_exp():
    """y' = −y on three components (the constant-size path): y(5) = e^{−5} y0."""
    y = sp.symbols("y0:3")
    k = generate_kernel(list(y), [-yi for yi in y], [], [], name="split_decay3")
    y0 = np.array([1.0, 2.0, -1.0])
    (st, t, yend, cnt, *_), _ = _run(k, y0, 5.0, 1e-10)
    assert st == 0 and t == 5.0
    # rtol 1e-10 per step over ~100 steps: global error ≲ 1e-9 (measured below 1e-10)
    assert np.max(np.abs(yend - np.exp(-5.0) * y0)) < 1e-9
    assert cnt[5] == 0          # no Newton failure on a linear problem


def test_harmonic_oscillator_and_its_crossings():
    """x'' = −4x from (1, 0) (two states: the general-size path): x = cos 2t, and the downward
    crossings of x = 0 at t = π/4 + jπ located on the collocation cubic."""
    x, v = sp.symbols("x v")
    k = generate_kernel([x, v], [v, -4 * x], [], [], name="split_oscillator_omega2")
    (st, t, yend, cnt, *_), _ = _run(k, [1.0, 0.0], 10.0, 1e-10)
    assert st == 0
    assert np.allclose(yend, [np.cos(20.0), -2 * np.sin(20.0)], rtol=0, atol=1e-8)
    (st, t, yend, cnt, ev_t, ev_y, *_), dirs = _run(k, [1.0, 0.0], 10.0, 1e-10, ev_idx=0, ev_dir=-1, ev_stop=2)
    assert st == 1 and len(ev_t) == 3
    assert np.allclose(ev_t, np.pi / 4 + np.pi / 2 * np.arange(3), rtol=0, atol=1e-8)
    assert list(dirs[:3]) == [-1, 1, -1]
    assert np.allclose(ev_y[:, 0], 0.0, atol=1e-10)


def test_stiff_linear_system_matches_expm():
    """y' = My with eigenvalues −1, −10³, −10⁵ (non-normal M = S·diag·S⁻¹): y(2) = e^{2M} y0
    (scipy.linalg.expm); the stiffness ratio 10⁵ is what the implicit method is for."""
    S = np.array([[1.0, 0.5, 0.2], [0.0, 1.0, 0.3], [0.1, 0.0, 1.0]])
    M = S @ np.diag([-1.0, -1e3, -1e5]) @ np.linalg.inv(S)
    y = sp.symbols("y0:3")
    Ms = sp.Matrix(M.tolist())
    rhs = list(Ms * sp.Matrix(y))
    k = generate_kernel(list(y), rhs, [], [], name="split_stiff_linear3")
    y0 = np.array([1.0, -1.0, 2.0])
    (st, t, yend, cnt, *_), _ = _run(k, y0, 2.0, 1e-9)
    assert st == 0
    exact = scipy.linalg.expm(2.0 * M) @ y0
    assert np.max(np.abs(yend - exact)) < 1e-8
    # the steps follow the slow mode, not the fast one (explicit stability would need ~10⁵ steps)
    assert cnt[0] < 500


def test_fig3_period_agrees_with_radau5():
    """The period of the Fig. 3 cycle (Putelat et al. 2010) from the downward returns to w = 0,
    with the transformed and the default core at rtol 1e-10: agreement to the integration
    tolerance (1e-8 of the period; measured 4e-15, the shooting itself is done at 1e-11)."""
    from landau.verify.springblock.simulate import W_INDEX, choose_method, integrate
    from landau.verify.springblock.workprecision import fig3_cycle, fig3_model

    model = fig3_model()
    orbit = fig3_cycle(model)
    y0 = np.insert(orbit.z, W_INDEX, 0.0)
    kw = dict(rtol=1e-10, event_index=W_INDEX, event_direction=-1, stop_after=2)
    a = integrate(model, y0, (0.0, 3 * orbit.period), method="radau5", **kw)
    b = integrate(model, y0, (0.0, 3 * orbit.period), method="radau5t", **kw)
    ta, tb = a.event_t[a.event_dir < 0], b.event_t[b.event_dir < 0]
    assert b.status == "terminal event" and len(tb) == 2
    assert np.allclose(tb, ta, rtol=1e-8, atol=0)
    assert abs(tb[0] - orbit.period) < 1e-8 * orbit.period
    # same method, same controller: the step counts agree within a few per cent
    assert abs(a.steps - b.steps) <= 0.05 * a.steps
    assert choose_method(1e-4, True) == "radau5t"
