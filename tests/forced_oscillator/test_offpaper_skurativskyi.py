"""Skurativskyi, Kudra, Witkowski & Awrejcewicz (2019) scenes away from the paper's parameter set.

The search intervals come from the model (contact resonance sqrt(k_lin/m) for the grazing estimates;
the two grazing estimates for the first detachment; an up-sweep from the first detachment for the first
grazing of the cascade), so these sets move the answers away from the printed numbers; each is checked
against an independent computation.
"""

import mpmath
import pytest

from landau.scenes import run_scene


def _static_equilibrium(p):
    """X₀ from k X₀ + k_I (X₀ − x_I)^{n₁} = 0 at the working precision (the cart pressed on the obstacle)."""
    return mpmath.findroot(lambda X: p["k"] * X + p["kI"] * (X - p["xI"]) ** p["n1"],
                           (p["xI"] * (1 - mpmath.mpf(10) ** -12), mpmath.mpf(0)), solver="anderson")


# other obstacle positions and a softer contact: X0 − x_I, k_lin and the contact resonance all move
OFF_PAPER = [{"xI": -0.003}, {"kI": 5e7, "c": 10.0}]


@pytest.mark.parametrize("params", OFF_PAPER)
def test_grazing_harmonic_off_paper_against_mpmath(params):
    """Harmonic-balance grazing estimate, eqs (5)–(6), written again at 40 digits: with the trough
    x_I = X₀ + A (A = x_I − X₀ < 0) the contact force vanishes, so eq. (5) reads
    −mAω² + k x_I = m₀eω² cos α, sin α = cAω/(m₀eω²), cos α = −sqrt(1 − sin²α) (the branch that
    reproduces the printed 12.789).  X₀ from k X₀ + k_I (X₀ − x_I)^{n₁} = 0.  The scene's brentq stops
    at xtol 1e-13 rad/s: 1e-10 relative leaves room for the double-precision X₀."""
    doc = run_scene("skurativskyi2019/grazing-harmonic", params)
    p = {k: mpmath.mpf(v) for k, v in doc["params"].items()}
    with mpmath.workdps(40):
        X0 = _static_equilibrium(p)
        A = p["xI"] - X0

        def residual(w):
            F = p["m0e"] * w ** 2
            cos_a = -mpmath.sqrt(1 - (p["c"] * A * w / F) ** 2)
            return -p["m"] * A * w ** 2 + p["k"] * p["xI"] - F * cos_a
        ref = mpmath.findroot(residual, mpmath.mpf(doc["value"]))
    assert doc["value"] == pytest.approx(float(ref), rel=1e-10)
    # the estimate lies below the contact resonance, where the search runs
    k_lin = p["k"] + p["n1"] * p["kI"] * (X0 - p["xI"]) ** (p["n1"] - 1)
    assert doc["value"] < float(mpmath.sqrt(k_lin / p["m"]))


@pytest.mark.slow
@pytest.mark.parametrize("params", OFF_PAPER)
def test_first_detachment_off_paper(params):
    """First detachment away from the paper: the bisection window is [0.9 min, 1.1 max] of the two
    grazing estimates of the same parameters (not the printed (14.0, 14.1)), the located ω lies in it
    with a 1e-3 bracket, and a re-run with other integration settings (rtol 1e-10 instead of 1e-8,
    100 transient periods instead of 60) agrees 0.02 rad/s either side: contact kept below, lost above.
    (scipy's LSODA, Radau and BDF all stop on this stiff, non-smooth model — Hertz damping ∝ |ẋ|^0.187,
    friction regularised over 1e-6 m/s — so the reference is the project's own integrator.)"""
    from landau.verify.skurativskyi.analysis import detaches
    from landau.verify.skurativskyi.model import PAPER

    doc = run_scene("skurativskyi2019/first-detachment", params)
    est = (run_scene("skurativskyi2019/grazing-harmonic", params)["value"],
           run_scene("skurativskyi2019/grazing-linear", params)["value"])
    assert doc["window"] == pytest.approx([0.9 * min(est), 1.1 * max(est)], rel=1e-12)
    assert doc["window"][0] < doc["lo"] < doc["hi"] < doc["window"][1] and doc["hi"] - doc["lo"] <= 1e-3
    q = PAPER.with_(**params)
    assert not detaches(doc["value"] - 0.02, q, n_transient=100, rtol=1e-10)
    assert detaches(doc["value"] + 0.02, q, n_transient=100, rtol=1e-10)


@pytest.mark.slow
@pytest.mark.parametrize("params", [{"xI": -0.0021}, {"k": 1500.0}])
def test_first_cascade_grazing_off_paper_is_a_located_grazing(params):
    """The cascade scene derives its bracket from the model: an up-sweep from the first detachment
    to the first period-7 orbit with 14 impacts whose lower edge is a grazing (at k = 1500 the sweep
    first meets a period-7 window inside the chaotic band, at 21.0025, whose orbit ends without
    grazing — the straight-line zero of its margin lies 0.26 rad/s away —, and passes over it).  Checked independently
    at rtol 1e-10 instead of 1e-8, continuing the returned orbit
    (``y_orbit``): 1e-3 rad/s above the located point it is still the period-7 orbit with 14 impacts,
    1e-3 below it is gone (1e-3 is 10 bisection tolerances and twice the largest shift of this edge
    measured between integration tolerances, 5e-4 from rtol 1e-7 to 1e-8); and the free-flight margin
    x_I − max x of that orbit, sampled at rtol 1e-10 at 1e-4 and 2e-4 above the bracket, extrapolates
    linearly to zero at the located point within the bisection tolerance 1e-4 rad/s (measured 3e-5:
    the margin grows by ~45 µm per 1e-3 rad/s and bends over within ~5e-4 of the edge, so the samples
    stay close): a maximum touches x = x_I there — a grazing, not a fold or a crisis, where the orbit
    would end with a finite margin."""
    import numpy as np

    from landau.verify.skurativskyi.analysis import attractor, section_period
    from landau.verify.skurativskyi.grazing import maxima
    from landau.verify.skurativskyi.model import PAPER

    doc = run_scene("skurativskyi2019/first-cascade-grazing", params)
    win = doc["window"]
    assert (doc["period"], doc["impacts"], doc["kind"]) == (7, 14, "impact added")
    assert win["gone_omega"] <= doc["lo"] < doc["hi"] <= win["orbit_omega"]
    assert doc["hi"] - doc["lo"] <= doc["params"]["tol"]
    assert win["orbit_omega"] - win["gone_omega"] == pytest.approx(doc["params"]["step"], rel=1e-9)
    assert win["entered_from_period"] == 0            # the up-sweep leaves a chaotic band there
    # the sweep started below the first detachment it located (in contact, no grazing possible)
    assert win["sweep_start"] <= win["first_detachment"][0] < win["orbit_omega"]

    q = PAPER.with_(**params)
    y = np.array(doc["y_orbit"])
    d = 1e-3

    def orbit7(w):
        a = attractor(w, y, 150, 84, q, rtol=1e-10)
        return a, section_period(a, 1e-6, 24) == 7 and round(a.impacts_per_period * 7) == 14

    above, kept = orbit7(doc["hi"] + d)
    assert kept
    assert not orbit7(doc["lo"] - d)[1]
    g = []
    for w in (doc["hi"] + 1e-4, doc["hi"] + 2e-4):
        m = maxima(w, attractor(w, above.y_end, 100, 7, q, rtol=1e-10).y_end, 7, 200, params=q, rtol=1e-10)
        assert m.impacts_per_period * 7 == pytest.approx(14)
        g.append(m.margin)
    assert 0 < g[0] < g[1]                          # the free maximum approaches x_I towards the edge
    root = doc["hi"] + 1e-4 - g[0] * 1e-4 / (g[1] - g[0])
    assert root == pytest.approx(doc["value"], abs=1e-4), (g, root)


def test_scene_parameters_named_k_or_v_are_accepted_on_the_command_line(capsys):
    """``landau scene run`` takes a scene's own parameter names, including the spring stiffness k of
    this oscillator (reserved as the bifurcation parameter only in the spring–block commands).
    Independent: the linearised grazing condition x_I = X₀ − m₀eω²/sqrt((ωc)² + Δ²),
    Δ = k + n₁k_I(X₀ − x_I)^{n₁−1} − mω², evaluated at the returned ω with a 40-digit X₀ (to 1e-10 of
    X₀ − x_I, the scene's brentq stops at 1e-13 rad/s)."""
    import json

    from landau.cli import main

    code = main(["scene", "run", "skurativskyi2019/grazing-linear", "--param", "k=1500", "--json"])
    doc = json.loads(capsys.readouterr().out)
    assert code == 0 and doc["params"]["k"] == 1500.0
    p = {k: mpmath.mpf(v) for k, v in doc["params"].items()}
    w = mpmath.mpf(doc["value"])
    with mpmath.workdps(40):
        X0 = _static_equilibrium(p)
        delta = p["k"] + p["n1"] * p["kI"] * (X0 - p["xI"]) ** (p["n1"] - 1) - p["m"] * w ** 2
        trough = X0 - p["m0e"] * w ** 2 / mpmath.sqrt((w * p["c"]) ** 2 + delta ** 2)
    assert float(trough - p["xI"]) == pytest.approx(0.0, abs=1e-10 * float(X0 - p["xI"]))
