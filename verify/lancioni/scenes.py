"""Scenes for Lancioni, Lenci & Galvanetto, the frictional impact oscillator (Sec. 3).

Parameters (all scenes): m1, m2, l, k_y, k_phi, c_y, c_phi, phi0, y0, g — the paper's set 1
with g = 10 m/s² (the printed Hopf values need g = 10; g = 9.81 gives
μ_c ≈ 0.40986).  The Hopf and lift-off scenes use the direction with the Hopf point
(positive slip, belt v = −1 m/s; see verify.lancioni.slip).

Tolerances.  ``lancioni/hopf``: 4 significant digits (relative
half-unit 1.2e-4).  The engine gives μ_c = 0.4097782, whose 5-digit rounding is 0.40978,
one unit above the printed 0.40977 (printed value = truncation; the paper located it from
simulations, its Fig. 2(b) resolves ~1e-5).  ``lancioni/lift-off``: half a unit of the
printed 5th digit.  ``lancioni/period-adding``: the printed accumulation point 0.38957, half a unit
of its 5th digit (the model has no cascade steps; see verify/lancioni/period_adding.py).
"""

from __future__ import annotations

from landau.scenes import Scene, register
from landau.verify.lancioni.slip import SET1, SET2

SRC = "Lancioni, Lenci & Galvanetto, frictional impact oscillator, Sec. 3"


def _half_digit(value: float, decimals: int) -> float:
    return 0.5 * 10.0 ** (-decimals) / value


def _params(p):
    return {k: p[k] for k in SET1}


def _hopf(p):
    from landau.verify.lancioni.slip import slip_hopf
    h = slip_hopf(_params(p), bracket=(p["lo"], p["hi"]) if p["hi"] > p["lo"] else None, s=1)
    return {"value": h.p_c, "omega_c": h.omega_c, "Lambda": h.Lambda, "chi": h.chi, "C": h.C,
            "criticality": h.criticality, "phi_e": h.equilibrium[0], "dRe_lambda_dmu": h.dlambda_dp.real,
            "belt_direction": "v < 0 (positive slip, g_T > 0); v > 0 has no Hopf point",
            "convention": "dA/dT = a(mu-mu_c)A + b A|A|^2, phi-component of the critical mode = 1, "
                          "Lambda = 2 Re b < 0 supercritical, max|phi-phi_e| ~ C sqrt(mu-mu_c)"}


register(Scene(
    name="lancioni/hopf", parameter="mu", units="dimensionless",
    source=f"{SRC}: Hopf bifurcation of the slip equilibrium at mu = 0.40977 (set 1, Fig. 2(b)); "
           "set 2 (m1=0.4, k_phi=25): 0.353 (Fig. 4(b)); reproduced with g = 10 m/s^2",
    compute=_hopf, defaults={**SET1, "lo": 0.0, "hi": 0.0}, published=0.40977, tolerance=_half_digit(0.4098, 4),
    description="slip-mode ODE (eq. 1 with g_N = 0) through landau.derivation.general.hopf_normal_form "
                "(lo = hi = 0: the mu interval is found by scanning the model)"))


def _lift_off(p):
    from landau.verify.lancioni.analysis import lift_off_mu
    m, cyc = lift_off_mu(_params(p))
    return {"value": m, "amplitude_phi": cyc.amplitude, "period": cyc.period, "phidot_max": cyc.phidot_max,
            "method": "shooting on the slip ODE's cycle; min lambda_N along it = 0"}


register(Scene(
    name="lancioni/lift-off", parameter="mu", units="dimensionless",
    source=f"{SRC}: 'At mu = 0.40983 the slip periodic branch disappears' (set 1, Fig. 2(b))",
    compute=_lift_off, defaults=dict(SET1), published=0.40983, tolerance=_half_digit(0.40983, 5),
    description="end of the slip periodic branch: the normal force of the slip cycle reaches 0"))


def _stick(p):
    from landau.verify.lancioni.analysis import stick_onset_mu
    m, cyc = stick_onset_mu(_params(p), v=p["v"])
    return {"value": m, "phidot_max": cyc.phidot_max, "amplitude_phi": cyc.amplitude}


register(Scene(
    name="lancioni/stick-onset", parameter="mu", units="dimensionless",
    source=f"{SRC}: set 2 'for 0.360 < mu < 0.453 the periodic oscillation involves also the stick mode' (Fig. 4)",
    compute=_stick, defaults={**SET2, "v": -1.0}, published=0.360, tolerance=_half_digit(0.360, 3),
    description="the slip cycle first touches g_T = 0 (belt |v| = 1 m/s)"))


def _period_adding(p):
    from landau.verify.lancioni.period_adding import period_adding_steps
    res = period_adding_steps(_params(p), n_steps=int(p["n_steps"]))
    return {"value": res.accumulation, "steps": list(res.steps),
            "periods_seen": sorted({per for _, per in res.periods}),
            "stick_free_multiplier": res.multiplier, "first_miss_slope": res.first_miss_slope,
            "method": res.method,
            "note": "value = end of the detached stick orbit (every stick phase ends at the same point P, "
                    "so this is where a cascade would accumulate); eq. (1) has no period-adding steps "
                    "(border collision with an unstable stick-free orbit; a stick tolerance only shifts "
                    "the end linearly) - see verify/lancioni/period_adding.py"}


register(Scene(
    name="lancioni/period-adding", parameter="mu", units="dimensionless",
    source=f"{SRC}: e_N = 0 period-adding cascade accumulating at mu = 0.38957; first step at 0.38965 (Fig. 2(c))",
    compute=_period_adding, defaults={**SET1, "n_steps": 3}, published=0.38957, tolerance=_half_digit(0.38957, 5),
    description="end of the e_N = 0 detached stick orbit (the cascade's accumulation point); steps: none in eq. (1)"))


def _flight(p):
    from landau.verify.lancioni.analysis import flight_onset_mu
    r = flight_onset_mu(_params(p), bracket=(p["lo"], p["hi"]) if p["hi"] > p["lo"] else None)
    return {"value": r.mu, "bracket": list(r.bracket), "lamN_min_at_lo": r.lamN_min_below,
            "note": "bisection on lift-off along the stick-slip attractor (bracket width 1e-5)"}


register(Scene(
    name="lancioni/free-flight", parameter="mu", units="dimensionless",
    source=f"{SRC}: set 2 'for mu > 0.453 a more complex free flight-slip-stick-slip motion takes place' (Fig. 4)",
    compute=_flight, defaults={**SET2, "lo": 0.0, "hi": 0.0}, published=0.453, tolerance=_half_digit(0.453, 3),
    explained="the paper does not print the constant belt speed; its stick onset 0.360 allows |v| in "
              "[0.954, 1.016] m/s, over which the flight onset runs from 0.466 to 0.444; |v| = 0.991 gives 0.4530 "
              "with the other two set-2 values, |v| = 1 (kept) gives 0.44986 (docs/findings.md, Lancioni et al.; "
              "landau.verify.lancioni.analysis.flight_onset_mu)",
    known_value=0.44986, known_tolerance=5e-5,     # the bisection's bracket, 1e-5 in mu
    description="free flight first appears on the stick-slip attractor (e_N = 0, belt v = -1; lo = hi = 0: "
                "the mu window starts at the computed stick onset and widens until the attractor flies)"))
