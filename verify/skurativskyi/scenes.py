"""Scenes for Skurativskyi, Kudra, Witkowski & Awrejcewicz (2019), Nonlinear Dyn. 98:1795–1806.

Published values carry the tolerance of their printed digits (half a unit of the last
digit); the first detachment is printed as an interval (14.0, 14.1) rad/s: published =
midpoint, tolerance = relative half-width, so ``agrees`` means "inside the interval".
"""

from __future__ import annotations

from landau.scenes import Scene, register
from landau.verify.skurativskyi import approx
from landau.verify.skurativskyi.model import PAPER, Params

SRC = "Skurativskyi et al. 2019, Nonlinear Dyn. 98:1795-1806"


def _half_digit(value: float, decimals: int) -> float:
    return 0.5 * 10.0 ** (-decimals) / abs(value)


def _params(p: dict) -> Params:
    return PAPER.with_(**{k: v for k, v in p.items() if k in Params.names()})


_STATIC = {k: getattr(PAPER, k) for k in ("m", "k", "kI", "xI", "n1")}
_FORMULA = {k: getattr(PAPER, k) for k in ("m", "m0e", "k", "c", "kI", "xI", "n1")}
_ALL = {k: getattr(PAPER, k) for k in Params.names() if k != "omega"}


def _static(p):
    return {"value": approx.static_equilibrium(_params(p)),
            "equation": "k X0 + k_I (X0 - x_I)^n1 = 0 (Sec. 5)"}


register(Scene(
    name="skurativskyi2019/static-equilibrium", parameter="X0", units="m",
    source=f"{SRC}, Sec. 5 (X0 = -2.0807e-3 m)", compute=_static, defaults=_STATIC,
    published=-2.0807e-3, tolerance=_half_digit(2.0807, 4) ,
    description="static equilibrium of the cart pressed on the obstacle (m does not enter; listed as issued)"))


def _glin(p):
    q = _params(p)
    return {"value": approx.grazing_linear(q), "X0": approx.static_equilibrium(q),
            "equation": "x_I = X0 - m0e w^2 / sqrt((w c)^2 + Delta^2), Delta = k + 1.5 k_I sqrt(X0 - x_I) - m w^2"}


register(Scene(
    name="skurativskyi2019/grazing-linear", parameter="omega", units="rad/s",
    source=f"{SRC}, Sec. 5, after eq. (4) (15.657 rad/s)", compute=_glin, defaults=_FORMULA,
    published=15.657, tolerance=_half_digit(15.657, 3),
    description="first grazing estimated from the linearised solution (4)"))


def _gharm(p):
    q = _params(p)
    br = approx.grazing_harmonic_branches(q)
    return {"value": approx.grazing_harmonic(q), "branches": br,
            "sign_choice": "x_I = X0 + A with A = x_I - X0 < 0 and cos(alpha) = -sqrt(1 - sin^2 alpha) "
                           "reproduces the printed value; cos(alpha) > 0 has no root"}


register(Scene(
    name="skurativskyi2019/grazing-harmonic", parameter="omega", units="rad/s",
    source=f"{SRC}, Sec. 5, eqs (5)-(6) (12.789 rad/s)", compute=_gharm, defaults=_FORMULA,
    published=12.789, tolerance=_half_digit(12.789, 3),
    description="first grazing estimated from the harmonic-balance solution (5)"))


def _detachment_window(q: Params) -> tuple[float, float]:
    # The two first-grazing estimates of Sec. 5 (harmonic balance, linearisation about X0) come
    # from the model alone and bound the first detachment (12.79 < 14.05 < 15.66 for the paper's
    # set); 10 % beyond each covers their error.
    est = (approx.grazing_harmonic(q), approx.grazing_linear(q))
    return 0.9 * min(est), 1.1 * max(est)


def _detach(p):
    from landau.verify.skurativskyi.analysis import first_detachment
    q = _params(p)
    lo, hi = (p["lo"], p["hi"]) if p["hi"] > p["lo"] else _detachment_window(q)
    loc = first_detachment(lo, hi, p["tol"], q, rtol=p["rtol"])
    return {"value": loc.value, "lo": loc.lo, "hi": loc.hi, "runs": loc.evaluations, "window": [lo, hi]}


register(Scene(
    name="skurativskyi2019/first-detachment", parameter="omega", units="rad/s",
    source=f"{SRC}, Sec. 5, Fig. 8 (permanent contact at 14, one impact per period at 14.1 rad/s)",
    compute=_detach, defaults={**_ALL, "lo": 0.0, "hi": 0.0, "tol": 1e-3, "rtol": 1e-8},
    published=14.05, tolerance=0.05 / 14.05,
    description="first detachment from the obstacle (impact adding starts), located by bisection on "
                "simulations from rest (60 periods transient, 20 observed); lo = hi = 0: the window runs "
                "from 0.9x the harmonic-balance to 1.1x the linearised grazing estimate"))


#: the window whose lower edge is the first grazing of the cascade (Sec. 4, Fig. 3b): the up-sweep
#: leaves the chaotic band onto a period-7 orbit with 14 impacts per 7 forcing periods
_CASCADE_PERIOD, _CASCADE_IMPACTS = 7, 14


def _cascade_grazing_derived(q: Params, rtol: float, step: float, tol: float):
    """Up-sweep from the first detachment (a grazing of an impacting orbit needs impacts; below it the
    attractor from rest stays in contact, Sec. 5) to the first period-7 orbit with 14 impacts whose lower
    edge is a grazing: each window the sweep enters is handed to the grazing locator, and one whose
    orbit ends without a maximum touching x_I (straight-line zero of the margin away from the bracket:
    a fold or crisis window inside the chaotic band) is passed over — the sweep resumes from its orbit."""
    import time

    from landau.verify.skurativskyi.analysis import first_detachment, sweep_to_window
    from landau.verify.skurativskyi.grazing import locate_grazing_margin
    t0, c0 = time.perf_counter(), time.process_time()
    d = first_detachment(*_detachment_window(q), 0.02, q, rtol=rtol)
    E = sweep_to_window(d.lo, _CASCADE_PERIOD, _CASCADE_IMPACTS, q, rtol, step=step)
    start, points, periods, passed, t_sweep, c_sweep = E.start, E.points, E.periods, [], 0.0, 0.0
    while True:
        t_sweep, c_sweep = time.perf_counter() - t0, time.process_time() - c0
        G = locate_grazing_margin(E.orbit_omega, E.gone_omega, E.y_orbit, tol, q, rtol)
        if G.root_at_bracket(max(2e-4, 2 * tol)):
            break
        passed.append({"orbit_omega": E.orbit_omega, "gone_omega": E.gone_omega, "value": G.value,
                       "linear_root": G.extrapolated})
        E = sweep_to_window(E.orbit_omega, _CASCADE_PERIOD, _CASCADE_IMPACTS, q, rtol, step=step,
                            n_first=50, y0=E.y_orbit, stop=2.0 * d.lo)
        points, periods = points + E.points, periods + E.periods
    window = {"orbit_omega": E.orbit_omega, "gone_omega": E.gone_omega, "entered_from_period": E.gone_period,
              "sweep_start": start, "first_detachment": [d.lo, d.hi], "sweep_points": points,
              "sweep_periods": periods, "passed_over": passed, "search_seconds": t_sweep,
              "search_cpu_seconds": c_sweep}
    return G, E.y_orbit, window


def _first_cascade_grazing(p):
    from landau.errors import InputError
    from landau.verify.skurativskyi.analysis import continuation
    from landau.verify.skurativskyi.grazing import locate_grazing_margin
    q = _params(p)
    hi, lo = p["orbit_omega"], p["gone_omega"]
    out = {}
    if hi > 0 and lo > 0:                 # given bracket: the orbit at orbit_omega, reached from rest just above
        y = continuation([hi + 0.003, hi], None, 300, 60, 7, q, p["rtol"])[-1].y_end
        G = locate_grazing_margin(hi, lo, y, p["tol"], q, p["rtol"])
    elif hi == 0 and lo == 0:             # derived bracket: the up-sweep enters the window
        if not (p["step"] > 0 and p["tol"] > 0):
            raise InputError(f"step and tol must be > 0 (got {p['step']}, {p['tol']})")
        G, y, out["window"] = _cascade_grazing_derived(q, p["rtol"], p["step"], p["tol"])
    else:
        raise InputError("give both orbit_omega and gone_omega (a bracket of the window's edge), or neither "
                         "(0: derived by an up-sweep from the first detachment)")
    return {"value": G.value, "lo": G.lo, "hi": G.hi, "linear_root": G.extrapolated, "period": G.period,
            "impacts": G.impacts, "kind": G.kind, "runs": G.evaluations, **out, "y_orbit": [float(v) for v in y]}


register(Scene(
    name="skurativskyi2019/first-cascade-grazing", parameter="omega", units="rad/s",
    source=f"{SRC}, Sec. 4, Fig. 3b (grazing cascade f = 20.59, 20.8586, 21.5085, 23.0702 rad/s)",
    compute=_first_cascade_grazing,
    defaults={**_ALL, "orbit_omega": 0.0, "gone_omega": 0.0, "step": 0.0025, "tol": 1e-4, "rtol": 1e-8},
    published=20.59, tolerance=0.015 / 20.59,
    settings=frozenset({"orbit_omega", "gone_omega", "step", "tol", "rtol"}),
    description="first grazing of the cascade: the up-sweep attractor leaves the chaotic band at the lower "
                "edge of the period-7 window (14 impacts), where a free-flight maximum of x touches x_I; "
                "bisection on the impact count of the continued orbit, cross-checked by the zero of the "
                "grazing margin (verify.skurativskyi.grazing).  orbit_omega = gone_omega = 0: the bracket is "
                "derived by continuing the attractor upward from the first detachment (grid of multiples of "
                "step, strides along settled periodic orbits) to the first period-7 orbit with 14 impacts "
                "whose lower edge is a grazing (windows ending otherwise are passed over); orbit_omega = "
                "the first such grid point, gone_omega = one step below.  Tolerance 0.015 rad/s: "
                "20.59 is printed to +-0.005 and located points move by ~0.01 rad/s with the integration "
                "tolerance (at rtol 1e-6)"))
