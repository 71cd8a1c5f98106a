"""A per-point callable on the sweep engine (map_points): the loops of the figure scripts and of
the transition scans.  Same numbers on 1 and 2 local processes; an exception ends the loop as a
plain loop would; an object that cannot be pickled travels by reference."""

from __future__ import annotations

import math
import os
from functools import partial

import numpy as np
import pytest

from landau.analyses.sweep_points import _SHARED, Shared, map_points
from landau.errors import NoHopfError


def _point(a: float, b: float, scale: float = 1.0) -> dict:
    # a closed form per point, and a list whose length depends on the point
    return {"s": scale * math.sin(a) * b, "pid": float(os.getpid()), "roots": [a * k for k in range(int(b))]}


def _failing(a: float) -> dict:
    if a > 1.5:
        raise NoHopfError(f"no Hopf point at a = {a:g}")
    return {"a": a}


def _by_reference(ref, a: float) -> dict:
    return {"y": ref.get()(a)}


def test_points_equal_the_closed_form_and_do_not_depend_on_the_workers():
    grid = {"a": np.linspace(0.1, 2.0, 7), "b": [1.0, 3.0]}
    one = map_points(partial(_point, scale=2.0), grid, workers=1)
    two = map_points(partial(_point, scale=2.0), grid, workers=2, chunk_size=2)
    assert len(one) == 14
    for k, (a, b) in enumerate((a, b) for a in grid["a"] for b in grid["b"]):   # C order
        assert one[k]["s"] == 2.0 * math.sin(a) * b
        n = int(b)
        assert list(one[k]["roots"][:n]) == [a * j for j in range(n)]
        assert np.all(np.isnan(one[k]["roots"][n:]))   # padded to the longest list
        assert two[k]["s"] == one[k]["s"]
        assert np.array_equal(two[k]["roots"], one[k]["roots"], equal_nan=True)
    # one worker: this process; two: the first chunk here (it loads what the rest needs), the others
    # in the forked workers
    assert {p["pid"] for p in one} == {float(os.getpid())}
    assert len({p["pid"] for p in two} - {float(os.getpid())}) >= 1


@pytest.mark.parametrize("workers", [1, 2])
def test_an_exception_ends_the_loop_with_its_type_and_message(workers):
    with pytest.raises(NoHopfError, match="no Hopf point at a = 1.9"):
        map_points(_failing, {"a": [0.5, 1.0, 1.9, 1.2]}, workers=workers)


def test_an_object_that_cannot_be_pickled_travels_by_reference():
    fn = lambda a: 3.0 * a  # noqa: E731 - a lambda cannot be pickled
    with Shared(fn) as ref:
        got = map_points(_by_reference, {"a": [1.0, 2.0, 3.0, 4.0]}, fixed={"ref": ref}, workers=2)
        token = ref.token
    assert [g["y"] for g in got] == [3.0, 6.0, 9.0, 12.0]
    assert token not in _SHARED   # forgotten when the loop is over
    # elsewhere (a process that did not inherit it) it is rebuilt from its recipe, or refused by name
    other = Shared(fn, rebuild=partial(float, 7.0))
    other.release()
    assert other.get() == 7.0
    orphan = Shared(fn)
    orphan.release()
    with pytest.raises(Exception, match="cannot be rebuilt"):
        orphan.get()


def test_workers_of_the_figures_and_of_transition_are_checked(tmp_path, capsys):
    from landau.cli import main
    from landau.paper_figures import using_workers, workers

    assert workers() == (os.cpu_count() or 1)
    with using_workers(3):
        assert workers() == 3
    assert workers() == (os.cpu_count() or 1)
    assert main(["figures", "putelat2010", "--only", "fig5", "--workers", "0", "--out", str(tmp_path)]) == 2
    assert "--workers must be >= 1" in capsys.readouterr().err
    assert not any(tmp_path.iterdir())
