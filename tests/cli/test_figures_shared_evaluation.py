"""The figures' shared evaluations: one evaluation per (law, grid, parameters), same numbers."""

from __future__ import annotations

import numpy as np

from landau.derivation.multiscale import Derivation
from landau.laws import get_law
from landau.paper_figures.putelat2010._common import SharedDerivation, fresh
from landau.systems.system import SpringBlock

V = np.logspace(-7, -2, 60)


def _counting(monkeypatch) -> list:
    """Record the names of every evaluation that reaches the engine (Derivation.evaluate)."""
    calls: list = []
    engine = Derivation.evaluate

    def counted(self, Vs, params=None, names=("kc", "omega_c", "Gamma_bar", "Lambda"), method="auto",
                sign_only=False):
        calls.append(tuple(names))
        return engine(self, Vs, params, names, method, sign_only)

    monkeypatch.setattr(Derivation, "evaluate", counted)
    return calls


def test_shared_values_agree_with_a_plain_derivation():
    d = fresh("dieterich")
    assert isinstance(d, SharedDerivation)
    plain = Derivation(SpringBlock(get_law("dieterich")))
    shared = d.evaluate(V, {}, ["kc", "Gamma_bar", "Lambda"])
    for name in ("kc", "Gamma_bar", "Lambda"):
        ref = plain.evaluate(V, {}, [name])[name]
        # each value is within 1e-10 of the 50-digit value (Derivation.evaluate's promise), so two
        # evaluations that asked for different names agree to 2e-10
        assert np.allclose(shared[name], ref, rtol=2e-10, atol=0), name


def test_a_grid_is_evaluated_once_per_name(monkeypatch):
    d = fresh("dieterich")
    calls = _counting(monkeypatch)
    first = d.evaluate(V, {}, ["Gamma_bar", "Lambda"])
    again = d.evaluate(V, {"M": 1.2}, ["Lambda"])            # the default M: the same parameters
    assert len(calls) == 1
    assert np.array_equal(first["Lambda"], again["Lambda"], equal_nan=True)
    d.evaluate(V, {}, ["Lambda", "chi"])                      # only the new name reaches the engine
    assert calls[-1] == ("chi",)
    d.evaluate(V, {"M": 0.0}, ["kc"])                         # other parameters: a new evaluation
    d.evaluate(V[:-1], {}, ["Lambda"])                        # another grid: a new evaluation
    assert len(calls) == 4


def test_returned_arrays_are_copies_and_sign_scans_pass_through(monkeypatch):
    d = fresh("dieterich")
    a = d.evaluate(V, {}, ["Lambda"])
    a["Lambda"][:] = 0.0
    assert np.all(d.evaluate(V, {}, ["Lambda"])["Lambda"] != 0.0)
    calls = _counting(monkeypatch)
    d.evaluate(V, {}, ["Lambda"], sign_only=True)
    d.evaluate(V, {}, ["Lambda"], sign_only=True)
    assert len(calls) == 2
