"""Scenes for Galvanetto (2004), J. Sound Vib. 276, 121–139.

``value`` is the located bifurcation parameter.  Where the paper gives an interval
instead of a number (Figs 8, 9, 15) the published value is the interval's midpoint and the
tolerance its relative half-width, so ``agrees`` means "inside the printed interval".
``lo``/``hi`` bound the search (Brent's method on the scene's test function, see
:mod:`landau.verify.galvanetto.bifurcations`); ``lo = hi = 0`` (the default) derives the search
interval from the model (the law's weakening velocity, the Hopf point, the preceding bifurcation,
the periodic windows of the map's attractor), so the scenes also run at parameters away from the
paper's (``--param``).
"""

from __future__ import annotations

from landau.scenes import Scene, register
from landau.verify.galvanetto import bifurcations as B

SRC = "Galvanetto 2004, J. Sound Vib. 276:121-139"


def _half_digit(value: float, decimals: int) -> float:
    """Relative tolerance of a value printed with ``decimals`` decimals (half a unit)."""
    return 0.5 * 10.0 ** (-decimals) / value


def _interval(lo: float, hi: float) -> tuple[float, float]:
    mid = 0.5 * (lo + hi)
    return mid, 0.5 * (hi - lo) / mid


def _bracket(p: dict):
    """The scene's (lo, hi), or None (derived from the model) when both are 0; ``lo = 0`` with a
    given ``hi`` searches (hi/1000, hi) (the parameters searched are positive)."""
    lo, hi = p["lo"], p["hi"]
    if lo == 0 and hi == 0:
        return None
    return (hi * 1e-3 if lo == 0 else lo, hi)


def _doc(loc: B.Located, **extra) -> dict:
    return {"value": loc.value, "residual": loc.residual, "evaluations": loc.evaluations, **loc.details, **extra}


def _one_block(kind):
    def compute(p):
        loc = B.one_block_sliding(kind, p["gamma"], p["delta"], p["c"], bracket=_bracket(p))
        return _doc(loc)
    return compute


register(Scene(
    name="galvanetto2004/one-block-type-II", parameter="V", units="dimensionless",
    source=f"{SRC}, Sec. 4.1, Fig. 7 (V≈1.241; reproduced with δ=0.2, the printed δ=0 gives ≈0.642)",
    compute=_one_block("II"), defaults={"gamma": 3.0, "delta": 0.2, "c": 0.0, "lo": 0.0, "hi": 0.0},
    published=1.241, tolerance=_half_digit(1.241, 3),
    description="one block: the slip phase (r<0) ends exactly at the left end of the stick interval"))

register(Scene(
    name="galvanetto2004/one-block-type-I", parameter="V", units="dimensionless",
    source=f"{SRC}, Sec. 4.1, Fig. 7(c) (V≈10.801; reproduced with δ=0.2, printed δ=0 gives ≈4.424)",
    compute=_one_block("I"), defaults={"gamma": 3.0, "delta": 0.2, "c": 0.0, "lo": 0.0, "hi": 0.0},
    published=10.801, tolerance=_half_digit(10.801, 3),
    description="one block: the slip phase with r>0 ends exactly at the right end of the stick interval"))


def _c1(p):
    h = B.hopf_c1_normal_form(p["V"], p["gamma"], p["delta"])
    return {"value": h.p_c, "closed_form": B.hopf_c1(p["V"], p["gamma"], p["delta"]),
            "formula": "c1 = F_k'(-V) = gamma(1-delta)/(1+gamma V)^2", "omega_c": h.omega_c,
            "Lambda": h.Lambda, "criticality": h.criticality, "C": h.C,
            "engine": "landau.derivation.general.hopf_normal_form on the smooth slip field"}


register(Scene(
    name="galvanetto2004/one-block-c1", parameter="c", units="dimensionless",
    source=f"{SRC}, Sec. 4.2, Fig. 10(b) (subcritical Hopf at c=c1; no number printed)",
    compute=_c1, defaults={"V": 0.5, "gamma": 3.0, "delta": 0.0},
    description="damped one block: Hopf point of the slip equilibrium (closed form) and its criticality"))


def _c2(p):
    loc = B.nonsmooth_fold_c2(p["V"], p["gamma"], p["delta"], bracket=_bracket(p))
    return _doc(loc)


register(Scene(
    name="galvanetto2004/one-block-c2", parameter="c", units="dimensionless",
    source=f"{SRC}, Sec. 4.2, Fig. 10(c) (non-smooth fold; no number printed)",
    compute=_c2, defaults={"V": 0.5, "gamma": 3.0, "delta": 0.0, "lo": 0.0, "hi": 0.0},
    description="damped one block: the unstable slip cycle touches the stick line at the stick end "
                "(lo=hi=0: searched above the Hopf point c1)"))


def _two_block(kind, period):
    def compute(p):
        br = _bracket(p)
        loc = B.two_block_sliding(kind, p["alpha"], p["beta"], p["gamma"], p["delta"], bracket=br,
                                  period=period if br is not None else None)
        return _doc(loc)
    return compute


_mid, _tol = _interval(0.18, 0.19)
register(Scene(
    name="galvanetto2004/two-block-type-II", parameter="V", units="dimensionless",
    source=f"{SRC}, Sec. 4.1, Fig. 8 (type II between V=0.18 and V=0.19)",
    compute=_two_block("II", 2), defaults={"alpha": 1.2, "beta": 1.3, "gamma": 3.0, "delta": 0.0, "lo": 0.0, "hi": 0.0},
    published=_mid, tolerance=_tol, description="two blocks, period-2 orbit of the map; published = interval midpoint"))

_mid, _tol = _interval(0.725, 0.740)
register(Scene(
    name="galvanetto2004/two-block-type-I", parameter="V", units="dimensionless",
    source=f"{SRC}, Sec. 4.1, Fig. 9 (type I for 0.725 < V < 0.740)",
    compute=_two_block("I", 1), defaults={"alpha": 1.2, "beta": 1.3, "gamma": 3.0, "delta": 0.0, "lo": 0.0, "hi": 0.0},
    published=_mid, tolerance=_tol, description="two blocks, period-1 orbit of the map; published = interval midpoint"))


def _beta_scene(fn):
    def compute(p):
        loc = fn(bracket=_bracket(p), V=p["V"], alpha=p["alpha"], gamma=p["gamma"], delta=p["delta"])
        return _doc(loc)
    return compute


_fig12 = {"V": 0.25, "alpha": 1.2, "gamma": 3.0, "delta": 0.0}


def _register_beta(name: str, fn, figure: str, published: float, tolerance: float, description: str) -> None:
    """A scene of the Fig. 12 family (parameter β at Fig. 12's V, α, law; derived search interval)."""
    register(Scene(
        name=f"galvanetto2004/{name}", parameter="beta", units="dimensionless", source=f"{SRC}, Sec. 4.2, {figure}",
        compute=_beta_scene(fn), defaults={**_fig12, "lo": 0.0, "hi": 0.0},
        published=published, tolerance=tolerance, description=description))


_register_beta("fold", B.discontinuous_fold, "Figs 12-13 (discontinuous fold, beta≈1.7217)",
               1.7217, _half_digit(1.7217, 4), "a fixed point of the map sits at its slope discontinuity")
_register_beta("period-doubling", B.period_doubling, "Fig. 12 (period doubling, beta≈1.7231)",
               1.7231, _half_digit(1.7231, 4), "slope of the map at the stable fixed point reaches -1")
_register_beta("border-collision", B.border_collision,
               "Figs 12, 14 (border collision period 2 -> chaos, beta≈1.7236)",
               1.7236, _half_digit(1.7236, 4), "the period-2 orbit reaches the slope discontinuity of the map")
_register_beta("grazing-sliding", B.grazing_sliding, "Fig. 15 (1.7652 < beta* < 1.7656)",
               *_interval(1.7652, 1.7656),
               "period-2 attractor: a slip phase of block 1 grazes its sticking region (the paper's text "
               "says block 2; the computation shows block 1's short stick phase); lo=hi=0: searched upward "
               "from the border collision for a period-2 orbit through the map's kink")


def _multi(p):
    loc = B.multi_sliding(bracket=_bracket(p), V=p["V"], alpha=p["alpha"], beta=p["beta"], delta=p["delta"],
                          gamma=p["gamma"] or None, d0=p["d0"])
    return _doc(loc)


register(Scene(
    name="galvanetto2004/multi-sliding", parameter="gamma", units="dimensionless",
    source=f"{SRC}, Sec. 4.3, Fig. 16 (gamma≈10.75265; the figure at gamma=10.756 from d≈0.1969494)",
    compute=_multi, defaults={"V": 0.05, "alpha": 1.2, "beta": 2.0, "delta": 0.0, "gamma": 0.0, "d0": 0.0,
                              "lo": 0.0, "hi": 0.0},
    published=10.75265, tolerance=1e-4 / 10.75265,
    # the start of the search (gamma, d0) and its bracket steer the computation, not the model
    settings=frozenset({"gamma", "d0", "lo", "hi"}),
    description="a stick phase of block 2 touches K2 = -beta: a slip phase with r2>0 is born.  gamma = 0 and "
                "lo = hi = 0: the start is derived from the model (periodic windows of the map's attractor from "
                "d0, the middle of the map's domain, scanned in gamma over the law's weakening velocity 10V..V, "
                "lowest period first); gamma > 0: the periodic attractor at gamma from d0 is followed in gamma "
                "(the figure's start: --param gamma=10.756 --param d0=0.1969494)"))
