"""The (V, η) regime map: each point simulated at k = 1.003 k_c of its own (V, η), beside the
amplitude equation's prediction there.

The prediction columns equal single ``landau hopf`` calls (the same function: to the last bit).  Just
above k_c the simulation tells the two kinds of Hopf point apart by hysteresis (Putelat et al. 2010,
Sec. 5 and Fig. 12): a supercritical point slides steadily from both starts; a subcritical one is
bistable where the quintic amplitude equation puts a fold of cycles k_fold beyond the simulated
stiffness (the bistable window k_c < k < k_fold), and steady where k_fold lies below it.  Points
whose fold lies within a factor 2 of the simulated stiffness, or with no fold predicted (Λ and Λ₅
of one sign: outside the quintic truncation), are left unjudged.
"""

from __future__ import annotations

import json

import numpy as np
import pytest

import landau

R = 1.003   # k / k_c, the default of the regime task without k


def _hopf(V, eta, capsys):
    from landau.cli import main

    assert main(["hopf", "spring-block", "dieterich", "--V", repr(V), "--param", f"eta={eta!r}", "--json"]) == 0
    return json.loads(capsys.readouterr().out)


def _expected(crit: str, k_fold: float, k_c: float) -> str | None:
    if crit == "supercritical":
        return "steady"
    window = k_fold / k_c - 1 if np.isfinite(k_fold) else np.nan
    if not np.isfinite(window):
        return None
    if window > 2 * (R - 1):
        return "bistable"
    if window < (R - 1) / 2:
        return "steady"
    return None


def _check_map(ds, capsys):
    judged = {"supercritical": 0, "subcritical": 0}
    for i, V in enumerate(ds.V.values):
        for j, eta in enumerate(ds.eta.values):
            if str(ds.status.values[i, j]) != "ok":
                continue
            doc = _hopf(float(V), float(eta), capsys)
            crit = str(ds.criticality.values[i, j])
            assert crit == doc["criticality"], (V, eta)
            assert float(ds.k_c.values[i, j]) == doc["p_c"], (V, eta)
            assert float(ds.k.values[i, j]) == R * doc["p_c"]
            want = _expected(crit, float(ds.k_fold.values[i, j]), doc["p_c"])
            if want is None:
                continue
            assert str(ds.regime.values[i, j]) == want, (V, eta, crit)
            judged[crit] += 1
    return judged


def test_a_small_v_eta_map_agrees_with_the_prediction(capsys):
    ds = landau.sweep("regime", {"V": [8e-5, 5e-4], "eta": [0.0, 300.0]}, law="dieterich", workers=1, progress=False)
    assert set(ds.status.values.ravel()) == {"ok"}
    assert _check_map(ds, capsys) == {"supercritical": 3, "subcritical": 1}


def _command_line_map(tmp_path, capsys, V, eta):
    from landau.cli import main

    out = tmp_path / "v_eta.nc"
    assert main(["sweep", "regime", "spring-block", "dieterich", "--grid", V, "--grid", eta,
                 "--workers", "1", "--out", str(out), "--json"]) == 0
    capsys.readouterr()
    import xarray as xr

    with xr.open_dataset(out) as ds:
        ds = ds.load()
    return _check_map(ds, capsys)


def test_the_v_eta_map_of_the_command_line(tmp_path, capsys):
    """The command line's map on the small map's corners (log and linear ranges of ``--grid``): each
    point agrees with its single ``landau hopf`` call and with the prediction, both kinds present."""
    judged = _command_line_map(tmp_path, capsys, "V=8e-5:5e-4:2:log", "eta=0:300:2")
    assert judged == {"supercritical": 3, "subcritical": 1}, judged


@pytest.mark.slow
def test_the_v_eta_map_of_the_command_line_12_by_7(tmp_path, capsys):
    judged = _command_line_map(tmp_path, capsys, "V=1e-5:1e-3:12:log", "eta=0:300:7")
    assert judged["supercritical"] >= 70 and judged["subcritical"] >= 3, judged
