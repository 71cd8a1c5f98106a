"""One name for the spring–block's critical stiffness: ``k_c``, with ``kc`` its deprecated alias.

Every JSON document that carries ``kc`` carries ``k_c`` with the same value (and ``p_c`` of
``landau hopf`` equals both); Python reads ``k_c`` wherever it reads ``kc``; ``evaluate`` takes
either name and answers under the name asked for.
"""

from __future__ import annotations

import json

import numpy as np
import pytest

from landau.cli import main
from landau.derivation.coefficients import CoefficientTable, with_canonical_names
from landau.laws import get_law
from landau.systems.system import SpringBlock
from landau.verify.springblock.checks import predict

# eq. (30) of Putelat et al. (2010), Dieterich at V = 1e-5 m/s: sigma (b - a)/L (1 + M V^2/(L a sigma))
_S, _A, _B, _L, _M = 1.2 * 9.81, 0.0349, 0.0489, 0.9e-6, 1.2


def _kc_closed(V: float) -> float:
    return _S * (_B - _A) / _L * (1 + _M * V ** 2 / (_L * _A * _S))


def _json(capsys, *argv) -> dict:
    code = main([*argv, "--json"])
    out, _ = capsys.readouterr()
    assert code == 0
    return json.loads(out)


def test_linear_json_carries_k_c_beside_kc(capsys):
    doc = _json(capsys, "linear", "dieterich", "--V", "1e-5")
    pt = doc["points"][0]
    assert pt["k_c"] == pt["kc"] == pytest.approx(_kc_closed(1e-5), rel=1e-12)
    assert doc["units"]["k_c"] == doc["units"]["kc"] == "N/m"


def test_derive_json_carries_k_c_and_accepts_it_as_a_quantity(capsys):
    old = _json(capsys, "derive", "dieterich", "--V", "1e-5", "--quantities", "kc,Lambda")
    new = _json(capsys, "derive", "dieterich", "--V", "1e-5", "--quantities", "k_c,Lambda")
    for doc in (old, new):
        pt = doc["points"][0]
        assert pt["k_c"] == pt["kc"] == pytest.approx(_kc_closed(1e-5), rel=1e-12)
        assert doc["units"]["k_c"] == "N/m"
    assert new["points"][0]["Lambda"] == old["points"][0]["Lambda"]


def test_derive_text_shows_the_stiffness_once(capsys):
    assert main(["derive", "dieterich", "--V", "1e-5", "--quantities", "k_c"]) == 0
    out = capsys.readouterr().out
    header = next(line for line in out.splitlines() if line.lstrip().startswith("V [m/s]"))
    assert header.split()[2:] == ["k_c", "criticality"]   # one column under k_c, whichever name was asked for
    row = out.splitlines()[out.splitlines().index(header) + 1].split()
    assert float(row[1]) == pytest.approx(_kc_closed(1e-5), rel=1e-5)


def test_hopf_spring_block_json_p_c_k_c_kc_agree(capsys):
    doc = _json(capsys, "hopf", "spring-block", "dieterich", "--V", "1e-5")
    assert doc["p_c"] == doc["k_c"] == doc["kc"] == pytest.approx(_kc_closed(1e-5), rel=1e-12)


def test_verify_json_carries_k_c(capsys):
    doc = _json(capsys, "verify", "ruina", "--V", "1e-4", "--eps2", "1e-3")
    pt = doc["points"][0]
    assert pt["k_c"] == pt["kc"] and np.isfinite(pt["k_c"])
    assert doc["units"]["k_c"] == "N/m"


def test_python_k_c_everywhere():
    import landau

    law = get_law("dieterich")
    r = predict(law, 1e-5)
    assert r.k_c == r.kc == r.p_c == pytest.approx(_kc_closed(1e-5), rel=1e-12)
    assert r["k_c"] == r["kc"] == r.k_c
    d = landau.derive(SpringBlock(law), ["k_c", "Lambda"])
    new = d.evaluate([1e-5, 1e-4], names=["k_c", "Lambda"])
    old = d.evaluate([1e-5, 1e-4], names=["kc", "Lambda"])
    assert "k_c" in new and "kc" not in new         # under the name asked for
    assert "kc" in old and "k_c" not in old
    np.testing.assert_array_equal(new["k_c"], old["kc"])
    np.testing.assert_array_equal(new["kc"], old["k_c"])   # either name reads either table
    assert new["k_c"][0] == pytest.approx(_kc_closed(1e-5), rel=1e-12)
    assert list(new.columns()["criticality"]) == list(old.columns()["criticality"])
    pt = d.points([1e-5])[0]
    assert pt.k_c == pt.kc == new["k_c"][0]
    hp = d.hopf.points([1e-5])[0]                  # the linear HopfPoint
    assert hp.k_c == hp.kc == hp.as_dict()["k_c"] == hp.as_dict()["kc"]


def test_with_canonical_names_and_table_alias():
    assert list(with_canonical_names({"V": 1.0, "kc": 2.0, "C": 3.0})) == ["V", "kc", "k_c", "C"]
    assert with_canonical_names({"kc": 2.0, "k_c": 5.0})["k_c"] == 5.0
    t = CoefficientTable({"kc": np.array([1.0])})
    assert t["k_c"][0] == 1.0
    with pytest.raises(KeyError):
        t["Lambda"]


def test_sweep_dataset_carries_k_c():
    pytest.importorskip("xarray")
    import landau

    ds = landau.sweep("hopf", {"V": [1e-5, 1e-4]}, model="spring-block", law="dieterich")
    np.testing.assert_array_equal(ds["k_c"].values, ds["kc"].values)
    assert ds["k_c"].values[0] == pytest.approx(_kc_closed(1e-5), rel=1e-12)
