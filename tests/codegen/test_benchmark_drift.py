"""The speed figures of ``docs/performance.md`` cannot drift unseen: a quick subset of the benchmarks
is rerun and compared with the committed results it was generated from.

Absolute CPU figures depend on the machine and its load, so the comparison is between same-run
ratios: Λ(V) of the engine (``Derivation.evaluate``, best repeated call and first call) over
``sympy.lambdify(cse=True)`` of the same expression compiled by ``numba.vectorize``, both timed in
this process on the same points
(``benchmarks/sections_engine.py::lambda_row``, the function the benchmark itself runs), on as many
points as the recorded run (2e5 for ``--quick`` results, 1e6 otherwise).  A ratio that falls below
half of the recorded one is a regression of more than 2×; the message names the results file and
the commit it was measured at.  Behind ``slow``: each law costs a few CPU seconds.
"""

from __future__ import annotations

import json
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
RESULTS = ROOT / "benchmarks" / "results"
#: the largest slowdown of a same-run ratio that is not called a regression
DRIFT = 2.0


def _recorded() -> tuple[str, dict, dict[str, dict]]:
    """(file name, machine, rows by law) of the newest results file with Λ(V) rows."""
    found = []
    for path in RESULTS.glob("results-*.json"):
        res = json.loads(path.read_text(encoding="utf-8"))
        rows = res.get("raw", {}).get("lambda")
        if rows:
            found.append((res.get("machine", {}).get("date", ""), path.name, res["machine"], rows))
    assert found, f"no results file in {RESULTS} holds the Λ(V) section"
    _, name, machine, rows = max(found)
    return name, machine, {r["law"]: r for r in rows}


def _lambda_row(law: str, n_points: int) -> dict:
    sys.path.insert(0, str(ROOT / "benchmarks"))
    from sections_engine import lambda_row

    return lambda_row(law, n_points, accuracy=False)


def _check(law: str) -> None:
    name, machine, rows = _recorded()
    was = rows[law]
    now = _lambda_row(law, was.get("points", 200_000 if name.startswith("results-quick") else 1_000_000))
    where = f"{name} (commit {machine.get('commit') or 'not recorded'}, {machine.get('date', 'undated')})"
    for what in ("engine pts/s", "first call pts/s"):
        ratio_was = was[what] / was["numba-lambdify pts/s"]
        ratio_now = now[what] / now["numba-lambdify pts/s"]
        assert ratio_now >= ratio_was / DRIFT, (
            f"Λ(V) {law}: {what} / numba-lambdify is {ratio_now:.3g} in this run, {ratio_was:.3g} in {where}: "
            f"a regression of {ratio_was / ratio_now:.1f}× (more than {DRIFT:g}×)")


@pytest.mark.slow
@pytest.mark.parametrize("law", ["dieterich", "ruina", "spinodal", "modified-dieterich", "nanoscale", "micron-scale"])
def test_lambda_throughput_has_not_drifted(law):
    _check(law)
