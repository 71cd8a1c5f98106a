"""Locators for the sliding bifurcations of Galvanetto (2004), Sec. 4.

Each locator reduces the bifurcation to a scalar *test function* H(parameter) that
changes sign at the bifurcation and finds its root with Brent's method (xtol 1e-12 in the
parameter).  H is evaluated on the steady state: the stick–slip cycle of the one block
(determined by the stick end) or a periodic point of the event map f (found by a secant
iteration warm-started from the previous parameter value).

Test functions (r = Ẋ − V, K the spring force, F_s the static level):

* type II sliding: a slip phase with r < 0 ends (r = 0) exactly at the left end of the
  sticking interval: H = min over r = 0 events from r < 0 of (K + F_s);
* type I sliding: a slip phase with r > 0 ends exactly at the right end: H = min over
  r = 0 events from r > 0 of (F_s − K); past it the orbit has no stick phase there, so H
  is continued by a *virtual* orbit that sticks anyway (``stick{i}:p``);
* grazing of the sticking region by a slip phase (the kink of f): the maximum of r in
  that phase, with the stick guard made transparent so that the maximum is a smooth
  function (the virtual orbit continues on the same slip branch through r = 0);
* multi-sliding: the minimum of K₂ + β over a stick phase of block 2 (transparent guard);
* fold / border collision of the map: fⁿ(d_k) − d_k = 0 at the kink d_k(β);
* period doubling: f'(d*) + 1 = 0 at the fixed point (central differences with Richardson
  extrapolation).

Without a ``bracket`` every locator derives its search interval from the model, never from a
published value: the law's weakening velocity (sliding points in V), the Hopf point c₁ (c₂), a β
scan from equal static levels (the fold) and, upward from each bifurcation, the next one of the
Fig. 12 sequence and the grazing-sliding (the next period-2 orbit through the kink), and for the
multi-sliding the periodic windows of the map's attractor in a γ scan over the law's weakening
velocity (10·V down to V), whose orbits are followed in γ.  When the test function does not change
sign there, :class:`NoBifurcationError` names the range searched.

The locators live in modules of one idea each and are gathered here:
:mod:`~landau.verify.galvanetto.periodic` (periodic points, scans and root searches),
:mod:`~landau.verify.galvanetto.one_block` (one block: sliding, Hopf c₁, non-smooth fold c₂),
:mod:`~landau.verify.galvanetto.two_block` (two blocks: sliding, the kink, the Fig. 12 sequence,
the grazing-sliding) and :mod:`~landau.verify.galvanetto.multisliding`.
"""

from landau.verify.galvanetto.multisliding import (  # noqa: F401
                                                   MS_SCAN_DECADE,
                                                   MS_SCAN_STEP,
                                                   MS_TRANSIENT,
                                                   _multi_sliding_range,
                                                   multi_sliding,
)
from landau.verify.galvanetto.one_block import hopf_c1, hopf_c1_normal_form, nonsmooth_fold_c2, one_block_sliding  # noqa: F401
from landau.verify.galvanetto.periodic import (  # noqa: F401
                                                   SCAN_RTOL,
                                                   XTOL,
                                                   NoBifurcationError,
                                                   PeriodicPoint,
                                                   attractor,
                                                   map_slope,
                                                   orbit_events,
                                                   periodic_point,
                                                   scan_bracket,
)
from landau.verify.galvanetto.two_block import (  # noqa: F401
                                                   GRAZE1,
                                                   border_collision,
                                                   boundary_crisis,
                                                   discontinuous_fold,
                                                   fig12_params,
                                                   fixed_point_beside_kink,
                                                   grazing_sliding,
                                                   kink,
                                                   kink_function,
                                                   period_doubling,
                                                   two_block_sliding,
)
from landau.verify.hybrid.analysis import Located  # noqa: F401

__all__ = ["Located", "NoBifurcationError", "PeriodicPoint", "attractor", "border_collision", "boundary_crisis",
           "discontinuous_fold", "fig12_params", "fixed_point_beside_kink", "grazing_sliding", "hopf_c1",
           "hopf_c1_normal_form", "kink", "kink_function", "map_slope", "multi_sliding", "nonsmooth_fold_c2",
           "one_block_sliding", "orbit_events", "period_doubling", "periodic_point", "scan_bracket",
           "two_block_sliding"]
