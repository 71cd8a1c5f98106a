"""The periodicity defect (:mod:`landau.periodic.defect`): resolved cycles pass, an unresolved one fails.

* Rössler (a = b = 0.2): a stable cycle at c = 2.5 and the unstable period-1 cycle at c = 5.7
  (multiplier −2.40) are cycles of the field: the closure of one Radau period (rtol 1e-10) is at the
  integrator's and the collocation's error, far below 1e-6.
* The quasi-static two-state block with β₂ = −0.84 (Gu et al. 1984 read with the other sign; see
  tests/springblock/test_cascade_gu1984.py): continued at ntst 80 from its Hopf point through the
  fold, the branch reaches cycles near κ = 0.145 whose slip spike (v up to e¹⁰) the mesh does not
  resolve. Newton's method converged on them, but one period integrated from the first node misses
  it by a tenth of its scale and strays from it by more (measured: closure 0.18, path 1.1): the check says so.
"""

from __future__ import annotations

import numpy as np
import pytest
from cycle_systems import rossler, simulated_cycle

from landau.errors import InputError
from landau.periodic import CycleProblem, HopfStart, continue_cycles
from landau.periodic.defect import periodicity_defect


def test_resolved_cycles_stable_and_unstable_pass():
    pr = rossler()
    br = continue_cycles(pr, simulated_cycle(pr, 2.5, [1.0, 1.0, 0.0]), steps=100, ds=0.1, ntst=60)
    assert br.parameter[-1] == 5.7
    first, last = periodicity_defect(br, 0), periodicity_defect(br, -1)
    assert first.ok and last.ok
    assert first.closure < 1e-7 and last.closure < 1e-7 and last.path < 1e-6
    assert last.amplification == pytest.approx(2.4039535, rel=1e-6)      # the unstable cycle's |μ|


def _gu_other_sign() -> CycleProblem:
    b1, b2, rho = 1.0, -0.84, 0.048

    def rhs(y, k):
        x, t1, t2 = y[0], y[1], y[2]
        v = np.exp(x)
        d1, d2 = -v * (t1 + (1 + b1) * x), -(v / rho) * (t2 + b2 * x)
        return np.array([k * (1 - v) - d1 - d2, d1, d2])

    def jac(y, k):
        x, t1, t2 = np.broadcast_arrays(y[0], y[1], y[2])
        v = np.exp(x)
        d1x, d1t = -v * (t1 + (1 + b1) * x) - v * (1 + b1), -v
        d2x, d2t = -(v / rho) * (t2 + b2 * x) - (v / rho) * b2, -v / rho
        o = np.zeros_like(x)
        return np.array([[-k * v - d1x - d2x, -d1t, -d2t], [d1x, d1t, o], [d2x, o, d2t]])

    J0 = jac(np.zeros(3), 0.0)
    # the Hopf point of the linearisation at the steady state (x, θ₁, θ₂) = 0: κ_c with Re λ = 0
    from scipy.optimize import brentq
    kc = brentq(lambda k: np.max(np.linalg.eigvals(J0 - np.diag([k, 0, 0])).real), 0.1, 0.2, xtol=1e-14)
    lam, vec = np.linalg.eig(jac(np.zeros(3), kc))
    i = int(np.argmax(lam.imag))
    hopf = HopfStart(kc, np.zeros(3), float(lam[i].imag), vec[:, i] / vec[0, i], amplitude=1.0, side=-1)
    return CycleProblem("gu-other-sign", ("x", "th1", "th2"), "kappa", rhs, jac, hopf=hopf,
                        parameter_range=(0.01, 0.2))


def test_an_unresolved_relaxation_cycle_is_caught():
    br = continue_cycles(_gu_other_sign(), steps=105, ds=0.01, ds_max=0.5, ntst=80, max_period=2000)
    i = int(np.argmin(np.abs(np.asarray(br.parameter) - 0.145)))
    assert abs(br.parameter[i] - 0.145) < 5e-3
    d = periodicity_defect(br, i)
    assert not d.ok and d.closure > 1e-2 and d.path > 0.1 and "NOT a cycle" in str(d)
    # near the Hopf point the same branch's cycles are resolved
    assert periodicity_defect(br, 5).ok


def test_bad_arguments_are_named():
    pr = rossler()
    br = continue_cycles(pr, simulated_cycle(pr, 2.5, [1.0, 1.0, 0.0]), steps=2, ds=0.1)
    with pytest.raises(InputError, match="cycle 10 is not on the branch"):
        periodicity_defect(br, 10)
    with pytest.raises(InputError, match="rtol and tol must be positive"):
        periodicity_defect(br, 0, tol=0.0)
