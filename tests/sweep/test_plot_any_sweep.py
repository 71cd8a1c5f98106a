"""``landau plot --sweep`` draws any sweep: a hopf sweep's k_c and Λ over its axes (the generic figure),
a model's own figure where it declares one (the regime map over (V, k))."""

from __future__ import annotations

import json

import landau
from landau.cli import main


def test_a_hopf_sweep_over_v_and_eta_is_drawn(tmp_path, capsys):
    out = tmp_path / "v_eta.nc"
    landau.sweep("hopf", {"V": [1e-5, 1e-4, 1e-3], "eta": [0.0, 200.0]}, law="dieterich", out=out, workers=1,
                 progress=False)
    png = tmp_path / "v_eta.png"
    assert main(["plot", "--sweep", str(out), "--out", str(png), "--json"]) == 0
    doc = json.loads(capsys.readouterr().out)
    assert doc["kind"] == "sweep-lines" and doc["x"] == "V" and doc["variables"][:2] == ["k_c", "Lambda"]
    assert png.stat().st_size > 10_000


def test_a_file_that_is_not_a_sweep_is_refused(tmp_path, capsys):
    bad = tmp_path / "x.nc"
    bad.write_bytes(b"not netcdf")
    assert main(["plot", "--sweep", str(bad), "--out", str(tmp_path / "x.png"), "--json"]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and "not a netCDF sweep file" in err[0]
