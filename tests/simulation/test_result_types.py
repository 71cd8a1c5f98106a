"""One located-point type and one sweep result for every model (verify/hybrid/analysis.py).

The bisection of the forced oscillator's locators (Skurativskyi et al. 2019) and the root searches
of the stick–slip locators (Galvanetto 2004) return the same :class:`Located`; the generic
warm-started sweep and the forced oscillator's ω-sweep return the same :class:`SweepResult`.
The names they had before stay importable, and the renamed fields readable, for one release.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from landau.verify.hybrid.analysis import Located, SweepResult, sweep


def test_every_model_names_the_same_types():
    from landau.verify.galvanetto import bifurcations
    from landau.verify.skurativskyi import analysis
    from landau.verify.skurativskyi import sweep as fo_sweep

    assert bifurcations.Located is Located and analysis.Located is Located
    assert fo_sweep.SweepResult is SweepResult


def test_bisection_returns_the_bracket_and_counts_its_runs():
    # pred(ω) = ω² > 2 on [1, 2] to 1e-6: the bracket halves until its width is ≤ 1e-6, i.e.
    # ceil(log2(1 / 1e-6)) = 20 halvings, plus the two end evaluations; it holds √2 (closed form)
    from landau.verify.skurativskyi.analysis import bisect

    loc = bisect(lambda w: w * w > 2.0, 1.0, 2.0, 1e-6, "square root")
    assert loc.name == "square root" and loc.parameter == "omega"
    assert loc.lo < math.sqrt(2.0) < loc.hi and loc.hi - loc.lo <= 1e-6
    assert loc.value == 0.5 * (loc.lo + loc.hi)
    assert loc.evaluations == 2 + math.ceil(math.log2(1.0 / 1e-6))
    assert math.isnan(loc.residual)
    # the bracket keeps lo on the side of the starting lo, also when it is the larger end
    rev = bisect(lambda w: w * w > 2.0, 2.0, 1.0, 1e-6, "square root")
    assert rev.hi < math.sqrt(2.0) < rev.lo
    assert "omega ∈ [" in repr(loc) and "|H|" not in repr(loc)


def test_a_root_search_gives_value_and_residual():
    loc = Located("fold", "V", 1.25, 3e-14, 12, 0.5, {"d": 0.1})
    assert (loc.value, loc.residual, loc.evaluations, loc.details["d"]) == (1.25, 3e-14, 12, 0.1)
    assert math.isnan(loc.lo) and math.isnan(loc.hi)
    assert repr(loc) == "Located(fold: V = 1.25, |H| = 3e-14, 12 evaluations, 0.50 s)"


def test_sweep_records_failures_and_keeps_going():
    from landau.errors import LandauError

    def fn(q, warm):
        if q == 2.0:
            raise LandauError("no attractor")
        return q + warm

    res = sweep(fn, [1.0, 2.0, 3.0], warm=0.0)
    np.testing.assert_array_equal(res.params, [1.0, 2.0, 3.0])
    assert res.values == [1.0, None, 4.0]          # 3 + the last good output 1
    assert res.failures == {2.0: "no attractor"} and res.direction is None and res.out is None


def test_renamed_names_and_fields_warn_and_still_work():
    from landau.verify.galvanetto import periodic

    with pytest.warns(DeprecationWarning, match="bifurcations or landau.verify.hybrid.analysis"):
        assert periodic.Located is Located
    with pytest.raises(AttributeError):
        periodic.NoSuchName  # noqa: B018
    loc = Located("grazing", "omega", 20.6, math.nan, 9, lo=20.59, hi=20.61)
    with pytest.warns(DeprecationWarning, match="Located.name"):
        assert loc.what == "grazing"
    res = SweepResult(np.array([21.8, 21.75]), ("a", "b"), direction="down", out="sweep.nc")
    with pytest.warns(DeprecationWarning, match="SweepResult.values"):
        assert res.attractors == ("a", "b")
    with pytest.warns(DeprecationWarning, match="SweepResult.params"):
        assert list(res.omegas) == [21.8, 21.75]
    assert repr(res) == "SweepResult(down, 2 points, 0 failures, out='sweep.nc')"


def test_the_former_run_names_warn_and_are_the_new_classes():
    import landau.verify.springblock as springblock
    from landau.verify.skurativskyi import simulate as forced
    from landau.verify.springblock import simulate as radau

    for module, new in ((springblock, radau.RadauRecord), (radau, radau.RadauRecord),
                        (forced, forced.ForcedRun)):
        with pytest.warns(DeprecationWarning, match=f"{module.__name__}.Run is deprecated: use {new.__name__}"):
            assert module.Run is new
        with pytest.raises(AttributeError):
            module.NoSuchName  # noqa: B018
    with pytest.warns(DeprecationWarning, match="use ForcedRun"):
        from landau.verify.skurativskyi.simulate import Run  # noqa: F401
