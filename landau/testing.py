"""Assertions for a user's own test suite (pytest or unittest).

Example — a CI test for your own law::

    from landau.laws import FrictionLaw
    from landau.testing import assert_prediction

    MY_LAW = FrictionLaw.from_strings("my-law", mu="a_v + a*log(v/V_s) + b*log(V_s*phi/L)",
                                      state={"phi": "1 - v*phi/L"})

    def test_amplitude_equation_matches_simulation():
        assert_prediction(MY_LAW, V=1e-4, eps2=1e-3)
"""

from __future__ import annotations

from typing import Any, Mapping, Sequence

from landau.analyses.checking import CheckResult, Verdict, check


def assert_prediction(target: Any, V: float | None = None, eps2: float | Sequence[float] = 1e-3,
                      params: Mapping[str, float] | None = None, **kwargs: Any) -> CheckResult:
    """Assert that the amplitude equation of ``target`` agrees with a direct simulation.

    Parameters
    ----------
    target, V, eps2, params, **kwargs
        As for :func:`landau.check`.

    Returns
    -------
    CheckResult
        The check, when it agrees.

    Raises
    ------
    AssertionError
        With the prediction, the simulated value, the relative error, the fitted exponent of the error
        in ε² and its value extrapolated to ε² → 0 (the contract of :func:`landau.check`), and the
        verdict's advice (the largest valid ε² outside the range of validity, the resolvable range
        when the simulation cannot resolve the cycle).
    """
    result = check(target, V, eps2, params, **kwargs)
    if result.verdict is not Verdict.AGREES:
        lines = [f"prediction not confirmed by simulation: {result.verdict.value}",
                 f"  {result.summary()}",
                 f"  fitted exponent of the error in eps2: {_num(result.exponent, '.3f')} (the theory: 1); "
                 f"extrapolated error at eps2 -> 0: {_num(result.extrapolated_error, '+.3%')}",
                 f"  {result.verdict.message}"]
        if result.eps2_max_valid is not None and result.verdict is Verdict.OUTSIDE_VALIDITY:
            lines.append(f"  largest valid eps2: {result.eps2_max_valid:.3g}")
        raise AssertionError("\n".join(lines))
    return result


def _num(x: float | None, spec: str) -> str:
    return "not measured" if x is None else format(x, spec)
