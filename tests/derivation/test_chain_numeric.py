"""The chain's numeric route (one block's law jets, sparse solves): equal to the symbolic route where
both run, its Hopf point against a bisection of a Jacobian assembled in the test, Λ of identical
blocks against the single block, the law jets against their closed forms, and the route's choices."""

from __future__ import annotations

import numpy as np
import pytest

from landau.analyses.chain import chain_hopf
from landau.errors import InputError, NonSimpleHopfError
from landau.laws import get_law
from landau.laws.local_jets import law_jets
from landau.support.blas_threads import one_blas_thread
from landau.systems.chain import SpringBlockChain

# Putelat et al. (2010) Table 1 (the dieterich law's defaults)
A_, B_, L_ = 0.0349, 0.0489, 9e-7


def uneven(n: int, kc: float = 3e4, quasi_static: bool = False) -> dict:
    """Blocks of different masses and loads (no tie between blocks in the critical mode)."""
    over = {"k_coupling": kc, **{f"M_{i}": 0.8 + 0.3 * np.sin(1.7 * i) ** 2 for i in range(1, n + 1)},
            **{f"sigma_{i}": 9.0 + 2.5 * np.cos(0.9 * i) ** 2 for i in range(1, n + 1)}}
    if quasi_static:
        over["M_1"] = 0.0
    return over


FIELDS = ("p_c", "omega_c", "Lambda", "chi", "C", "l1")


def assert_same(num, sym, rel):
    assert num.extra["route"] == "numeric" and sym.extra["route"] == "symbolic"
    assert num.normalise == sym.normalise
    for name in FIELDS:
        assert getattr(num, name) == pytest.approx(getattr(sym, name), rel=rel), name
    assert num.dlambda_dp == pytest.approx(sym.dlambda_dp, rel=rel)
    assert num.c1 == pytest.approx(sym.c1, rel=rel)
    assert np.allclose(num.extra["mode_shape"], sym.extra["mode_shape"], rtol=0, atol=1e-10)


@pytest.mark.parametrize("n, quasi_static", [(2, False), (3, False), (2, True)])
def test_the_numeric_route_equals_the_symbolic_route(n, quasi_static):
    # the symbolic route works at 50 digits: float64 LU solves agree to ~1e-13 (1e-10 asked)
    chain, over = SpringBlockChain("dieterich", n), uneven(n, quasi_static=quasi_static)
    assert_same(chain_hopf(chain, over, route="numeric"), chain_hopf(chain, over, route="symbolic"), 1e-10)


@pytest.mark.slow
@pytest.mark.parametrize("n", [4, 5, 6, 8])
def test_the_numeric_route_equals_the_symbolic_route_up_to_eight_blocks(n):
    chain, over = SpringBlockChain("dieterich", n), uneven(n)
    assert_same(chain_hopf(chain, over, route="numeric"), chain_hopf(chain, over, route="symbolic"), 1e-10)


def test_a_two_state_law_on_both_routes():
    # the law jets of a law with two states (mixed derivatives in φ₁, φ₂ and v)
    chain, over = SpringBlockChain("two-state-dieterich", 2), {"k_coupling": 3e4, "M_2": 0.7}
    assert_same(chain_hopf(chain, over, route="numeric"), chain_hopf(chain, over, route="symbolic"), 1e-10)


@pytest.mark.slow
@pytest.mark.parametrize("law", ["ruina", "spinodal", "modified-dieterich", "nanoscale", "micron-scale"])
def test_every_built_in_law_on_both_routes(law):
    chain, over = SpringBlockChain(law, 2), {"k_coupling": 3e4, "M_2": 0.7}
    assert_same(chain_hopf(chain, over, route="numeric"), chain_hopf(chain, over, route="symbolic"), 1e-10)


def assembled_jacobian(k, V, Ms, sigmas, kc):
    """ẏ = J y at steady sliding, y = (X_i, u_i, φ_i): aging law μ = a ln(v/V_s) + a_v + b ln(V_s φ/L),
    dφ/dt = 1 − φv/L (φ_ss = L/V): μ_v = a/V, μ_φ = bV/L, ∂rate/∂v = −1/V, ∂rate/∂φ = −V/L."""
    n = len(Ms)
    J = np.zeros((3 * n, 3 * n))
    for i in range(n):
        x, u, f = 3 * i, 3 * i + 1, 3 * i + 2
        J[x, u] = 1.0
        nb = [j for j in (i - 1, i + 1) if 0 <= j < n]
        J[u, x] = -(k + kc * len(nb)) / Ms[i]
        for j in nb:
            J[u, 3 * j] = kc / Ms[i]
        J[u, u] = -sigmas[i] * A_ / V / Ms[i]
        J[u, f] = -sigmas[i] * B_ * V / L_ / Ms[i]
        J[f, u] = -1.0 / V
        J[f, f] = -V / L_
    return J


def test_fifty_blocks_against_a_bisection_of_the_assembled_jacobian():
    n, V, kc = 50, 1e-4, 3e4
    over = uneven(n, kc)
    Ms = [over[f"M_{i}"] for i in range(1, n + 1)]
    sigmas = [over[f"sigma_{i}"] for i in range(1, n + 1)]

    def rightmost(k):
        with one_blas_thread():
            return np.max(np.linalg.eigvals(assembled_jacobian(k, V, Ms, sigmas, kc)).real)

    # the first crossing as k decreases: a geometric scan, then bisection on the sign of max Re λ
    ks = np.geomspace(1e7, 1e4, 61)
    i = next(i for i in range(len(ks) - 1) if rightmost(ks[i]) < 0 <= rightmost(ks[i + 1]))
    hi, lo = ks[i], ks[i + 1]
    while hi - lo > 1e-13 * hi:
        mid = 0.5 * (hi + lo)
        hi, lo = (hi, mid) if rightmost(mid) >= 0 else (mid, lo)
    r = chain_hopf(SpringBlockChain("dieterich", n), {"V": V, **over})
    assert r.extra["route"] == "numeric"
    # max Re λ is resolved to ~eps‖J‖ = 1e-11, |dRe λ/dk| ≈ 1e-4: the bisection holds k_c to ~1e-12
    assert r.p_c == pytest.approx(lo, rel=1e-10)
    lam = np.linalg.eigvals(assembled_jacobian(lo, V, Ms, sigmas, kc))
    assert r.omega_c == pytest.approx(abs(lam[np.argmax(lam.real)].imag), rel=1e-9)


def test_identical_blocks_have_the_single_block_landau_coefficient_at_fifty_blocks():
    # the in-phase subspace of identical blocks is invariant (the coupling springs are not stretched)
    # and is the single block: its Λ, χ, C from the general engine on the one-block system
    over = {"V": 2e-4, "k_coupling": 5e4}
    r = chain_hopf(SpringBlockChain("dieterich", 50), over)
    one = chain_hopf(SpringBlockChain("dieterich", 1), {"V": 2e-4}, route="symbolic")
    assert r.extra["route"] == "numeric" and r.extra["mode"] == "in-phase"
    for name in ("p_c", "omega_c", "Lambda", "chi", "C"):
        assert getattr(r, name) == pytest.approx(getattr(one, name), rel=1e-10), name


def test_the_law_jets_are_the_dieterich_derivatives():
    # μ = a_v + a ln(v/V_s) + b ln(V_s φ/L), dφ/dt = 1 − vφ/L at (V, φ = L/V)
    law = get_law("dieterich")
    p = {q.name: q.default for q in law.parameters}
    a, b, L = p["a"], p["b"], p["L"]
    V = 1e-4
    phi = L / V
    D = law_jets(law, V, [phi], p, 3)
    assert D[1] == pytest.approx(np.array([[a / V, b / phi], [-phi / L, -V / L]]), rel=1e-14)
    assert D[2][0] == pytest.approx(np.array([[-a / V ** 2, 0], [0, -b / phi ** 2]]), rel=1e-14)
    assert D[2][1] == pytest.approx(np.array([[0, -1 / L], [-1 / L, 0]]), rel=1e-14)
    assert D[3][0][0, 0, 0] == pytest.approx(2 * a / V ** 3, rel=1e-14)
    assert D[3][0][1, 1, 1] == pytest.approx(2 * b / phi ** 3, rel=1e-14)
    assert np.count_nonzero(D[3][1]) == 0


def test_the_route_is_chosen_by_the_number_of_blocks():
    assert chain_hopf(SpringBlockChain("dieterich", 3), {}).extra["route"] == "symbolic"
    assert chain_hopf(SpringBlockChain("dieterich", 4), {}).extra["route"] == "numeric"


def single_block_kc(V: float = 1e-4, M: float = 1.2, sigma: float = 1.2 * 9.81) -> float:
    """Putelat et al. (2010) eq. (30), aging law: k_c = σ(b − a)/L · (1 + M V²/(σ a L))."""
    return sigma * (B_ - A_) / L_ * (1 + M * V ** 2 / (sigma * A_ * L_))


@pytest.mark.parametrize("kc, stalls", [(1.0, False), (1e-2, True)])
def test_weakly_coupled_identical_blocks_on_the_numeric_route(kc, stalls):
    # the other modes cross at k_c − 2k_coupling(1 − cos(jπ/N)): within 1e-7 of k_c at k_coupling =
    # 1e-2, where Newton's iteration stalls at its round-off floor (reported; auto then takes the
    # symbolic route) and still finds the in-phase crossing at the single block's k_c
    r = chain_hopf(SpringBlockChain("dieterich", 4), {"k_coupling": kc}, route="numeric")
    assert r.p_c == pytest.approx(single_block_kc(), rel=1e-12)
    assert r.extra["mode"] == "in-phase"
    assert (r.extra["newton_floor"] > 1e-10) is stalls


@pytest.mark.slow
def test_auto_takes_the_symbolic_route_where_newton_stalls():
    r = chain_hopf(SpringBlockChain("dieterich", 4), {"k_coupling": 1e-2})
    assert r.extra["route"] == "symbolic" and r.p_c == pytest.approx(single_block_kc(), rel=1e-12)


def test_uncoupled_identical_blocks_are_a_double_crossing_on_the_numeric_route():
    with pytest.raises(NonSimpleHopfError, match=r"4 complex pairs cross .* together at k = 189062\.9"):
        chain_hopf(SpringBlockChain("dieterich", 4), {"k_coupling": 0.0}, route="numeric")


@pytest.mark.parametrize("n", [2, 30])
def test_identical_quasi_static_blocks_are_degenerate_on_the_numeric_route(n):
    # identical quasi-static aging-law blocks: the in-phase mode is the single block's centre
    # (Λ = Λ₅ = 0, tests/derivation/test_degenerate.py), at the single block's k_c = σ(b − a)/L
    over = {"k_coupling": 2e4, **{f"M_{i}": 0.0 for i in range(1, n + 1)}}
    r = chain_hopf(SpringBlockChain("dieterich", n), over, route="numeric")
    assert r.p_c == pytest.approx(11.772 * (B_ - A_) / L_, rel=1e-12)
    assert r.Lambda == 0.0 and r.Lambda5 == 0.0 and r.criticality == "degenerate"
    assert r.extra["mode"] == "in-phase" and r.extra["degenerate_at_every_order_computed"] is True


@pytest.mark.parametrize("quasi_static", [False, True])
def test_the_fifth_order_equals_kuznetsovs_projection_route(quasi_static):
    # l₂ = Re c₂ (⟨q, q⟩ = 1) by the sparse Fredholm recursion against Kuznetsov's projection
    # formulas at 40 digits (landau.derivation.lyapunov, through second_lyapunov): another route
    chain, over = SpringBlockChain("dieterich", 2), uneven(2, quasi_static=quasi_static)
    num = chain_hopf(chain, over, route="numeric", l2=True)
    sym = chain_hopf(chain, over, route="symbolic", l2=True)
    assert num.l2 == pytest.approx(sym.l2, rel=1e-10)
    # Λ₅ = 2 Re c with q_n = 1, l₂ = Re c/⟨q, q⟩², and ⟨q, q⟩ = Λ/(2 Re c₁) from the same result
    qq = num.Lambda / (2 * num.c1.real)
    assert num.Lambda5 == pytest.approx(2 * sym.l2 * qq ** 2, rel=1e-10)


@pytest.mark.parametrize("blocks, route, message", [
    (2, "fast", "route must be one of"),
    (13, "symbolic", "at most 12 blocks"),
    (101, "numeric", "number of blocks"),
])
def test_bad_route(blocks, route, message):
    with pytest.raises(InputError, match=message):
        chain_hopf(SpringBlockChain("dieterich", blocks), {}, route=route)
