"""The compiled guards of eq. (1) (verify/lancioni/kernels.py, verify/hybrid/guarded.py).

* each regime's generated guard vector against the Python guards of the contact model (numpy,
  the contact algebra of verify/hybrid/contact.py) for Coulomb friction, a user's law and the
  sinusoidal belt, with the γ_T-minimum section of the period-adding analysis: the same formulas
  in another order, equal to rounding (1e-10 relative: the stick forces divide by det G);
* a run whose guards are screened and whose events are located inside compiled code against the
  same run with the guards evaluated in Python (``Mode.guard_kernel`` removed): the same events,
  at times that agree to rounding, and a recorded run keeps the same samples; every compiled
  root of a Fig. 2 run against the Python root on the same bracket (xtol + rounding);
* the routes without compiled guards: a section without a symbolic form, the stick tolerance,
  another belt;
* the scan test of a disarmed section (verify/hybrid/locate.py ``_quiet_guards``).
"""

import dataclasses

import numpy as np
import pytest

from landau.laws.velocity import VelocityFriction
from landau.verify.hybrid import HybridModel, simulate
from landau.verify.hybrid.contact import Section
from landau.verify.hybrid.dop853 import CompiledDOP853
from landau.verify.hybrid.locate import _quiet_guards
from landau.verify.lancioni import period_adding as PA
from landau.verify.lancioni.contact import default_options
from landau.verify.lancioni.model import PHI_ZERO_UP, PHIDOT_MAX, SineBelt, build
from landau.verify.lancioni.slip import SET1

LAW = VelocityFriction.from_strings("mine", "mu*(1 + alpha*exp(-v/v0))", params={"mu": 0.3, "alpha": 0.3, "v0": 0.5})
MODES = ("flight", "slip+", "slip-", "stick")
STEPPER = CompiledDOP853(1e-10, 1e-12)


def _states(n=12, seed=5):
    rng = np.random.default_rng(seed)
    for _ in range(n):
        yield rng.uniform(0, 3), np.array([0.4, 0.92, 0.0, 0.0]) + rng.normal(size=4) * [0.2, 0.05, 2.0, 0.5]


@pytest.mark.parametrize("kw", [dict(mu=0.4), dict(friction=LAW), dict(mu=0.5, belt=SineBelt())],
                         ids=["coulomb", "user-law", "sine-belt"])
def test_guard_kernels_equal_the_python_guards(kw):
    cm = build(**kw, sections=(PHIDOT_MAX, PHI_ZERO_UP, PA._gT_min_section(SET1)))
    for mode in MODES:
        m = cm.model.mode(mode)
        gk = m.guard_kernel()
        out = np.empty(len(m.guards))
        for t, y in _states():
            gk.fun(t, y, gk.p, out)
            ref = np.array([float(g.fun(t, y)) for g in m.guards])
            assert out == pytest.approx(ref, rel=1e-10, abs=1e-10), (mode, t, y)


def _python_guards(model):
    return HybridModel({k: dataclasses.replace(m, guard_kernel=None) for k, m in model.modes.items()}, model.name)


@pytest.mark.parametrize("mu, eN, belt", [(0.40, 0.2, None), (0.38957, 0.0, None), (0.5, 0.0, SineBelt())],
                         ids=["bouncing", "stick-slip", "sine-belt"])
def test_compiled_guards_give_the_events_of_the_python_guards(mu, eN, belt):
    cm = build(mu, eN, belt=belt)
    y0 = np.array([0.38, 0.929, 0.0, 0.0])
    mode = cm.initial_mode(0.0, y0)
    opts = default_options(1e-6, record=False)
    a = simulate(cm.model, mode, y0, (0.0, 6.0), STEPPER, opts)
    b = simulate(_python_guards(cm.model), mode, y0, (0.0, 6.0), STEPPER, opts)
    assert len(a.events) > 10
    assert [(e.guard, e.from_mode, e.to_mode, e.kind) for e in a.events] == \
           [(e.guard, e.from_mode, e.to_mode, e.kind) for e in b.events]
    # the event times: each root is refined on the same step's dense output by the compiled guard
    # (to xtol, test below) instead of the Python guard, which moves it by rounding; the later
    # phases start from states moved by that much, so the runs agree to far below their
    # integration tolerance (rtol 1e-10 per step; measured: 5e-11 s at most, at the short
    # bounces of the e_N = 0.2 run, whose slopes are small)
    assert np.max(np.abs([e.t - f.t for e, f in zip(a.events, b.events, strict=True)])) <= 1e-9
    assert abs(a.nsteps - b.nsteps) <= 0.01 * b.nsteps
    assert a.y_final == pytest.approx(b.y_final, rel=1e-9, abs=1e-12)


def test_compiled_roots_agree_with_the_python_roots_on_a_fig2_run(monkeypatch):
    # the first two points of Fig. 2's detached branch (e_N = 0; impacts, lift-off, stick onset,
    # stops and the φ̇-maximum section): every root the engine refines in compiled code
    # (DOP853Solver.kernel_root, bisection) is refined again on the same bracket and dense output
    # by the Python route (Brent on the Python guard, locate.root_new_side).  Both end on the new
    # side within xtol + 4 eps·t of their guard's root (Brent's tolerance; the bisection's is
    # xtol), and the two guards' roots differ by the rounding of the guard formulas (~4 eps on
    # terms of order 1, e.g. y − l cos φ) over the guard's slope.
    from landau.verify.hybrid.dop853 import DOP853Solver
    from landau.verify.hybrid.locate import guard_on_dense, root_new_side
    from landau.verify.lancioni import diagrams as D

    built = []

    def build_and_keep(*a, **kw):
        built.append(build(*a, **kw))
        return built[-1]

    compiled = DOP853Solver.kernel_root
    pairs = []

    def both(self, gk, j, n_guards, lo, hi, xtol):
        r = compiled(self, gk, j, n_guards, lo, hi, xtol)
        (guard,) = {m.guards[j] for cm in built for m in cm.model.modes.values()
                    if m.guard_kernel is not None and m.guard_kernel() is gk}
        gs = guard_on_dense(guard.fun, self.dense_output())
        pairs.append((r, root_new_side(gs, lo, hi, xtol), abs(gs(hi) - gs(lo)) / (hi - lo), xtol, guard.name))
        return r

    monkeypatch.setattr(D, "build", build_and_keep)
    monkeypatch.setattr(DOP853Solver, "kernel_root", both)
    D.diagram([0.4099, 0.405], np.array([0.38, 0.929, 0.0, 0.0]), None, eN=0.0, t_transient=10.0, t_keep=3.0)
    assert len(pairs) > 200 and {"impact", "lift-off", "slip+ onset", "phidot-max"} <= {p[-1] for p in pairs}
    eps = np.finfo(float).eps
    for r, rp, slope, xtol, name in pairs:
        assert abs(r - rp) <= 2 * (xtol + 4 * eps * abs(r)) + 4 * eps / slope, (name, r, rp)


@pytest.mark.parametrize("max_samples, samples", [(200_000, 8), (300, 4)], ids=["all-samples", "thinned"])
def test_the_compiled_loop_records_what_the_python_scan_records(max_samples, samples, monkeypatch):
    # recorded runs (figures, ``landau simulate impact-oscillator``): the quiet steps' samples come
    # from the compiled loop, thinned past ``max_samples`` as the per-step record is.  With the
    # events located by the Python guards (a stepper without ``kernel_root``) the loop only decides
    # which steps the Python scan sees: the same samples to the last bit
    from landau.verify.hybrid.dop853 import DOP853Solver

    cm = build(0.40, 0.2)
    y0 = np.array([0.38, 0.929, 0.0, 0.0])
    mode = cm.initial_mode(0.0, y0)
    opts = default_options(1e-6, record=True, max_samples=max_samples, samples=samples)
    c = simulate(cm.model, mode, y0, (0.0, 4.0), STEPPER, opts)
    b = simulate(_python_guards(cm.model), mode, y0, (0.0, 4.0), STEPPER, opts)
    with monkeypatch.context() as mp:
        mp.delattr(DOP853Solver, "kernel_root")
        a = simulate(cm.model, mode, y0, (0.0, 4.0), STEPPER, opts)
    (ta, ya, ma), (tb, yb, mb) = a.trajectory(), b.trajectory()
    assert len(ta) > 100 and (len(ta) <= 2 * max_samples)
    assert np.array_equal(ta, tb) and np.array_equal(ya, yb) and ma == mb
    assert [s.mode for s in a.segments] == [s.mode for s in b.segments]
    assert [(e.t, e.guard) for e in a.events] == [(e.t, e.guard) for e in b.events]
    # with the roots in compiled code: the same record, the events moved by rounding (test above)
    assert len(c.trajectory()[0]) == len(tb) and [s.mode for s in c.segments] == [s.mode for s in b.segments]
    assert [e.guard for e in c.events] == [e.guard for e in b.events]
    assert np.max(np.abs([e.t - f.t for e, f in zip(c.events, b.events, strict=True)])) <= 1e-9


def test_models_without_compiled_guards():
    # a section whose function is not symbolic: the modes' guards stay in Python
    plain = Section("phi-max", lambda t, y, acc: y[2])
    # the stick tolerance's stop guard (a min/max of the stick forces) has no compiled form
    assert all(m.guard_kernel is None for m in build(0.4, stick_tol=1e-3).model.modes.values())
    assert all(m.guard_kernel is None for m in build(0.4, sections=(plain,)).model.modes.values())
    # a symbolic form that sympy cannot take: no kernel (decided when it is built)
    odd = Section("odd", lambda t, y, acc: np.sin(y[0]), symbolic=lambda t, y, acc: np.sin(y[0]))
    assert all(m.guard_kernel() is None for m in build(0.4, sections=(odd,)).model.modes.values())

    class Ramp:
        def __call__(self, t):
            return -1.0 + 0.0 * np.asarray(t, float)

        def rate(self, t):
            return 0.0 * np.asarray(t, float)
    assert all(m.guard_kernel is None for m in build(0.4, belt=Ramp()).model.modes.values())


def test_a_disarmed_section_is_quiet_while_it_stays_below_atol():
    m, atol = 2, 1e-13
    vals = np.array([[-0.3, -0.2, -0.1, -0.3, -0.2, -0.3, -0.2]])  # m samples, the end, the two widened sets

    def quiet(v, state):
        g, dec, st = np.array([-0.4]), np.array([False]), np.array([state])
        return _quiet_guards(v, m, g, dec, st, atol, 2.0), g[0], st[0]
    # disarmed: quiet, the value advanced to the step end, still disarmed
    assert quiet(vals, -1) == (True, -0.1, -1)
    # a sample that may be above atol (its widened value): the scan must arm it
    up = vals.copy()
    up[0, 4] = 1e-12
    assert quiet(up, -1)[0] is False
    # an end value above atol
    end = vals.copy()
    end[0, 2] = 1e-3
    assert quiet(end, -1)[0] is False
    # an armed guard with negative samples is a crossing, never quiet
    assert quiet(vals, 1)[0] is False
