"""The regime map of the dilatant spring–block over (eps_dil, t_drain) by ``landau sweep``, and its
boundary against single calls.

At V = 1e-6 m/s the plain aging-law block (σ = 20, σ̄ = 15) is subcritical; dilatancy with fast drainage
makes its Hopf bifurcation supercritical, and slower drainage (larger t_f) subcritical again.  The sweep
maps the criticality; on each row of ε the sign change of Λ between two t_f of the grid is interpolated
(linear in ln t_f) and compared with the boundary that single calls (:func:`predict`, the engine of
``landau hopf``) locate by bisection: the single-call boundary lies in the sweep's cell, and the
interpolated one within 5 % of it (the cell is a factor 1.45 wide in t_f; Λ is smooth in ln t_f there).
"""

from __future__ import annotations

import functools

import numpy as np
import pytest

import landau
from landau.derivation.multiscale import derive
from landau.systems.system import SpringBlock

V = 1e-6
FIXED = {"sigma": 20.0, "p_inf": 5.0, "beta": 1e-3}
EPS = [1e-4, 2e-4, 4e-4]
T_DRAIN = list(np.geomspace(2.0, 40.0, 9))


@functools.lru_cache(maxsize=1)
def _single():
    return derive(SpringBlock("dieterich", ("eps_dil",)))


def _Lambda(eps, tf):
    """Λ of one call (the derivation ``landau hopf spring-block`` and ``landau derive`` evaluate)."""
    return float(np.ravel(_single().evaluate(np.array([V]), {**FIXED, "eps_dil": eps, "t_drain": tf},
                                             ["Lambda"])["Lambda"])[0])


def test_regime_map_and_its_boundary_against_single_calls():
    ds = landau.sweep("hopf", {"eps_dil": EPS, "t_drain": T_DRAIN}, law="dieterich", params={"V": V, **FIXED},
                      workers=1, progress=False)
    assert ds.Lambda.dims == ("eps_dil", "t_drain")
    assert set(np.ravel(ds.status.values)) == {"ok"}
    crit = ds.criticality.values
    lam = ds.Lambda.values
    assert np.array_equal(crit == "supercritical", lam < 0)
    lt = np.log(T_DRAIN)
    for i, eps in enumerate(EPS):
        flips = np.flatnonzero(np.diff(np.sign(lam[i])) != 0)
        assert len(flips) == 1 and crit[i, 0] == "supercritical" and crit[i, -1] == "subcritical"
        j = int(flips[0])
        # the sweep's points equal single calls
        for jj in (j, j + 1):
            assert lam[i, jj] == pytest.approx(_Lambda(eps, T_DRAIN[jj]), rel=1e-9)
        t_interp = np.exp(lt[j] - lam[i, j] * (lt[j + 1] - lt[j]) / (lam[i, j + 1] - lam[i, j]))
        lo, hi = T_DRAIN[j], T_DRAIN[j + 1]
        for _ in range(16):    # the cell's width 1.45 to 6e-6 in ln t_f
            mid = np.sqrt(lo * hi)
            lo, hi = (mid, hi) if _Lambda(eps, mid) < 0 else (lo, mid)
        t_single = np.sqrt(lo * hi)
        assert T_DRAIN[j] < t_single < T_DRAIN[j + 1]
        assert t_interp == pytest.approx(t_single, rel=0.05)
