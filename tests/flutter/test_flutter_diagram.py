"""The stability diagram against the closed-form eigenvalues of the undamped 2-DOF model.

Undamped, λ² = −s/m with s the roots of s² − (k₁₁ + k₂₂ + k_H)s + k₁₁(k₂₂ + k_H) − k₁₂(k₁₂ − μk_H) = 0
(Hoffmann et al. 2002): the diagram's eigenvalues must be those to 1e-10 relative (float64 eigenvalues
of a 4×4 matrix away from the collision), and unstable exactly beyond the closed-form μ_c.
"""

from __future__ import annotations

import csv
import math

import numpy as np
import pytest

from landau.analyses.flutter import hoffmann_threshold
from landau.analyses.flutter_diagram import stability_diagram
from landau.errors import InputError
from landau.systems.mode_coupling import HOFFMANN_DEFAULTS as D
from landau.systems.mode_coupling import ModeCoupling, hoffmann_stiffness


def _closed_form(mu):
    k11, k12, k22 = hoffmann_stiffness(D["k1"], D["k2"], D["alpha1"], D["alpha2"])
    tr, det = k11 + k22 + D["kH"], k11 * (k22 + D["kH"]) - k12 * (k12 - mu * D["kH"])
    s = np.roots([1.0, -tr, det]).astype(complex)
    lam = np.concatenate([np.sqrt(-s / D["m"]), -np.sqrt(-s / D["m"])])
    return lam


def test_diagram_is_the_closed_form_and_unstable_beyond_mu_c(tmp_path):
    mc = ModeCoupling.hoffmann2002(contact="linear", c1=0.0, c2=0.0)
    values = np.linspace(0.0, 1.0, 200)
    dia = stability_diagram(mc, values)
    mu_c, _ = hoffmann_threshold(D["m"], D["k1"], D["k2"], D["alpha1"], D["alpha2"], D["kH"])
    assert dia.eigenvalues.shape == (200, 2)
    for mu, row in zip(values, dia.eigenvalues, strict=True):
        ref = _closed_form(mu)
        upper = ref[np.argsort(-ref.imag)][:2]
        upper = upper[np.lexsort((upper.real, np.round(upper.imag / np.abs(upper).max(), 9)))]
        assert row == pytest.approx(upper, rel=1e-10, abs=1e-10 * np.abs(ref).max())
    np.testing.assert_array_equal(dia.unstable(), values > mu_c)
    path = dia.write_csv(tmp_path / "diagram.csv")
    rows = list(csv.reader(path.open()))
    assert rows[0] == ["mu", "re_1", "im_1", "f_hz_1", "re_2", "im_2", "f_hz_2"]
    assert len(rows) == 201
    assert float(rows[1][2]) == pytest.approx(dia.frequencies[0, 0], rel=1e-15)
    assert float(rows[1][3]) == pytest.approx(dia.frequencies[0, 0] / (2 * math.pi), rel=1e-15)
    fig = dia.save_figure(tmp_path / "diagram.png", threshold=mu_c)
    assert fig.stat().st_size > 1000


def test_diagram_in_another_parameter_and_bad_values():
    mc = ModeCoupling.hoffmann2002(contact="linear", c1=0.0, c2=0.0, mu=0.7)
    # in kH at mu = 0.7: the diagram at kH = 2e4 is the mu-diagram's point at mu = 0.7
    dia = stability_diagram(mc, [2e4], parameter="kH")
    ref = stability_diagram(ModeCoupling.hoffmann2002(contact="linear", c1=0.0, c2=0.0), [0.7])
    assert dia.eigenvalues == pytest.approx(ref.eigenvalues, rel=1e-14)
    with pytest.raises(InputError, match="finite"):
        stability_diagram(mc, [0.1, float("nan")])
    with pytest.raises(InputError, match="unknown parameter"):
        stability_diagram(mc, [0.1], parameter="q")
