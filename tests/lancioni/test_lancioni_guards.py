"""The compiled guards of eq. (1) (verify/lancioni/kernels.py, verify/hybrid/guarded.py).

* each regime's generated guard vector against the Python guards of the contact model (numpy,
  the contact algebra of verify/hybrid/contact.py) for Coulomb friction, a user's law and the
  sinusoidal belt, with the γ_T-minimum section of the period-adding analysis: the same formulas
  in another order, equal to rounding (1e-10 relative: the stick forces divide by det G);
* a run whose guards are screened inside the compiled loop against the same run with the guards
  evaluated in Python (``Mode.guard_kernel`` removed): the loop only decides which steps the
  Python scan sees, so the events and the final state are the same, and a recorded run keeps
  the same samples;
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
    # the event times: located by the same Python guards on the same steps' dense output
    assert np.max(np.abs([e.t - f.t for e, f in zip(a.events, b.events, strict=True)])) <= opts.xtol
    assert a.nsteps == b.nsteps
    assert a.y_final == pytest.approx(b.y_final, rel=1e-9, abs=1e-12)


@pytest.mark.parametrize("max_samples, samples", [(200_000, 8), (300, 4)], ids=["all-samples", "thinned"])
def test_the_compiled_loop_records_what_the_python_scan_records(max_samples, samples):
    # recorded runs (figures, ``landau simulate impact-oscillator``): the quiet steps' samples come
    # from the compiled loop, thinned past ``max_samples`` as the per-step record is
    cm = build(0.40, 0.2)
    y0 = np.array([0.38, 0.929, 0.0, 0.0])
    mode = cm.initial_mode(0.0, y0)
    opts = default_options(1e-6, record=True, max_samples=max_samples, samples=samples)
    a = simulate(cm.model, mode, y0, (0.0, 4.0), STEPPER, opts)
    b = simulate(_python_guards(cm.model), mode, y0, (0.0, 4.0), STEPPER, opts)
    (ta, ya, ma), (tb, yb, mb) = a.trajectory(), b.trajectory()
    assert len(ta) > 100 and (len(ta) <= 2 * max_samples)
    assert np.array_equal(ta, tb) and np.array_equal(ya, yb) and ma == mb
    assert [s.mode for s in a.segments] == [s.mode for s in b.segments]
    assert [(e.t, e.guard) for e in a.events] == [(e.t, e.guard) for e in b.events]


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
