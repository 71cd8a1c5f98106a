"""The regime task: the spring–block by direct simulation from both sides, against the amplitude equation."""

import json

import pytest

pytest.importorskip("xarray")

import landau  # noqa: E402
from landau.cli import main  # noqa: E402


def test_regime_sweep_agrees_with_the_hopf_line_and_its_criticality(tmp_path, capsys):
    from landau.verify.springblock.checks import predict

    pr = predict(landau.laws.get_law("dieterich"), 1e-4)
    assert pr.criticality == "subcritical"  # Λ > 0 at this velocity (Putelat et al. 2010, Fig. 12)
    ks = [0.8 * pr.p_c, 1.003 * pr.p_c, 1.2 * pr.p_c]
    out = tmp_path / "map.nc"
    ds = landau.sweep("regime", {"V": [1e-4], "k": ks}, law="dieterich", workers=1, progress=False, out=out)
    reg = list(ds.regime.sel(V=1e-4).values)
    # below k_c steady sliding is linearly unstable: a cycle; well above it, stable and alone; just above
    # a subcritical k_c the unstable cycle separates steady sliding from the large cycle: bistable
    assert reg[0] in ("stick-slip", "small-cycle") and reg[2] == "steady" and reg[1] == "bistable"
    assert (ds.status == "ok").all()
    png = tmp_path / "map.png"
    assert main(["plot", "--sweep", str(out), "--out", str(png), "--json"]) == 0
    doc = json.loads(capsys.readouterr().out)
    assert png.stat().st_size > 1000 and doc["points"] == 3 and doc["regimes"]["bistable"] == 1


def test_plot_sweep_draws_another_task_as_lines(tmp_path, capsys):
    """A sweep without a figure of its model's own (a hopf sweep) is drawn as its numbers over its axes."""
    out = tmp_path / "kc.nc"
    landau.sweep("hopf", {"V": [1e-4, 2e-4]}, law="dieterich", workers=1, progress=False, out=out)
    assert main(["plot", "--sweep", str(out), "--out", str(tmp_path / "x.png")]) == 0
    assert "k_c, Lambda, C of the spring-block sweep against V (2 points)" in capsys.readouterr().out
