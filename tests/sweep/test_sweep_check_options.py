"""The check sweep's own quantity eps2 = |k − k_c|/k_c: refused up front where it is one value for every
point (as ``landau verify`` refuses it), a point of its own where it is swept, and a run whose every point
failed says why on stderr (it exited 1 with nothing there)."""

from __future__ import annotations

import json

import pytest

pytest.importorskip("xarray")

from landau.cli import main  # noqa: E402


def test_an_eps2_outside_the_checks_domain_is_refused_up_front_with_exit_2(tmp_path, capsys):
    # before: 2 points `failed`, exit 1, nothing on stderr; `landau verify --eps2 0.7` exits 2
    argv = ["sweep", "check", "spring-block", "dieterich", "--grid", "V=1e-4,2e-4", "--eps2", "0.7",
            "--out", str(tmp_path / "c.nc"), "--json"]
    assert main(argv) == 2
    out, err = capsys.readouterr()
    assert json.loads(out) == {"error": "eps2 must be in (0, 0.5), got 0.7", "kind": "InputError", "exit_code": 2}
    assert err.strip() == "landau: error: eps2 must be in (0, 0.5), got 0.7"
    assert not (tmp_path / "c.nc").exists()
    assert main(argv[:-1]) == 2     # and without --json the same line
    assert capsys.readouterr().err.strip() == "landau: error: eps2 must be in (0, 0.5), got 0.7"


def test_a_swept_eps2_is_an_axis_each_point_failing_alone_and_the_failed_run_says_why(tmp_path, capsys):
    import xarray as xr

    # before: an internal ValueError ("variables {'eps2'} are found in both data_vars and coords")
    argv = ["sweep", "check", "spring-block", "dieterich", "--grid", "eps2=0.7,0.8", "--grid", "V=1e-4",
            "--out", str(tmp_path / "c.nc")]
    assert main(argv) == 1
    out, err = capsys.readouterr()
    assert "status: failed: 2" in out
    assert err.strip() == ("landau: every computed point failed (2); the first: InputError: check: "
                           "eps2 = |k - k_c|/k_c must be in (0, 0.5), got 0.7")
    with xr.open_dataset(tmp_path / "c.nc") as ds:
        assert list(ds.eps2.values) == [0.7, 0.8] and "eps2" not in ds.data_vars
        assert [m for m in ds.message.values.ravel()] == [
            f"InputError: check: eps2 = |k - k_c|/k_c must be in (0, 0.5), got {e}" for e in (0.7, 0.8)]


def test_eps2_alone_is_a_grid(tmp_path, capsys):
    # before: "a sweep needs at least one --grid axis" (the axis was dropped before the check of names)
    argv = ["sweep", "check", "spring-block", "dieterich", "--grid", "eps2=0.6", "--out", str(tmp_path / "c.nc"),
            "--json"]
    assert main(argv) == 1
    doc = json.loads(capsys.readouterr().out)
    assert doc["status"] == {"failed": 1} and doc["dims"] == {"eps2": 1}
