"""The check and simulate tasks of landau.sweep, and the landau sweep command line."""

import json

import numpy as np
import pytest

pytest.importorskip("xarray")

import landau  # noqa: E402
from landau.cli import main  # noqa: E402


def test_check_sweep_over_two_velocities_gives_both_verdicts():
    ds = landau.sweep("check", {"V": [1e-5, 1e-4]}, law="dieterich", workers=1, progress=False)
    # at V = 1e-5 m/s the predicted slip-rate swing exceeds V at eps2 = 1e-3 (Putelat et al. 2010: the
    # subcritical cycle there is a stick-slip one), at 1e-4 the cycle is weakly nonlinear
    assert list(ds.verdict.values) == ["outside-validity", "agrees"]
    assert list(ds.status.values) == ["outside-validity", "ok"]
    assert "reverse the slip" in str(ds.message.values[0])
    direct = landau.check("dieterich", V=1e-4, eps2=1e-3, bistability=False)  # the same check, called alone
    pt = ds.sel(V=1e-4)
    assert float(pt.rel_error) == direct.rel_error and float(pt.p) == direct.p
    assert float(pt.eps2_max_valid) == direct.eps2_max_valid


# the old implementation of the ω-sweep (its own process pool, continuation chunks of 2 with one
# warm-up point) gave these section points, bit for bit, on this grid
OMEGAS = [21.6, 21.65, 21.7, 21.75, 21.8]
OLD_SECTION = {21.8: ("-0x1.626d97657965fp-8", "-0x1.0ba54e540692ap-8"),
               21.75: ("-0x1.5bf32eface948p-8", "-0x1.046ef8537a84ap-8"),
               21.7: ("-0x1.f970168b29d27p-9", "-0x1.5476aecebd810p-8"),
               21.65: ("-0x1.e96a9e3ac52b7p-9", "-0x1.4c480e9d004bdp-8"),
               21.6: ("-0x1.43c2ebf5cfbecp-8", "-0x1.d954087f2c1f2p-9")}
OPTIONS = {"n_first": 30, "n_step": 10, "n_keep": 6, "rtol": 1e-7, "overlap": 1, "direction": "down", "chunk_size": 2}


def test_simulate_sweep_of_the_forced_oscillator_reproduces_the_omega_sweep(tmp_path):
    from landau.verify.skurativskyi.analysis import continuation

    ds = landau.sweep("simulate", {"omega": OMEGAS}, model="forced-oscillator", workers=1, progress=False,
                      options=OPTIONS, out=tmp_path / "om.nc")
    for w, (x0, x1) in OLD_SECTION.items():
        pt = ds.sel(omega=w)
        assert float(pt.impacts_per_period) == 1.5  # Fig. 3 of Skurativskyi et al. (2019): 3 impacts / 2 periods
        assert [float(pt.x_section[0]), float(pt.x_section[1])] == [float.fromhex(x0), float.fromhex(x1)]
    # the first chunk (21.8, 21.75) is a plain continuation from rest: the serial route gives the same
    serial = continuation([21.8, 21.75], None, 30, 10, 6, rtol=1e-7)
    assert np.array_equal(ds.sel(omega=21.75).x_section.values, serial[1].x_section)
    # interrupted after the second point of the third chunk (21.6 pending): resumed from the stored y_end
    import netCDF4

    from landau.analyses.sweep_store import seal

    with netCDF4.Dataset(tmp_path / "om.nc", "a") as nc:   # as the interrupted run writes it: sealed
        nc.variables["status"][list(OMEGAS).index(21.6)] = "pending"
        seal(nc, nc.variables["status"].shape)
    again, counts = landau.sweep("simulate", {"omega": OMEGAS}, model="forced-oscillator", workers=1,
                                 progress=False, options=OPTIONS, out=tmp_path / "om.nc", return_counts=True)
    assert counts["computed"] == 1 and counts["reused"] == 4
    assert np.array_equal(again.x_section.values, ds.x_section.values, equal_nan=True)
    png = tmp_path / "omega.png"
    assert main(["plot", "--sweep", str(tmp_path / "om.nc"), "--out", str(png)]) == 0
    assert png.stat().st_size > 1000


def test_cli_sweep_json_and_resume(tmp_path, capsys):
    out = tmp_path / "kc.nc"
    argv = ["sweep", "hopf", "spring-block", "dieterich", "--grid", "V=1e-6:1e-3:4:log", "--grid", "a=0.02,0.06",
            "--workers", "1", "--out", str(out), "--json"]
    assert main(argv) == 0
    doc = json.loads(capsys.readouterr().out)
    assert doc["computed"] == 8 and doc["reused"] == 0 and doc["dims"] == {"V": 4, "a": 2}
    assert doc["status"] == {"no-hopf": 4, "ok": 4}
    assert main(argv) == 0
    doc = json.loads(capsys.readouterr().out)
    assert doc["computed"] == 0 and doc["reused"] == 8


@pytest.mark.parametrize("args, what", [
    (["--grid", "V=1:2", "--out", "x.nc"], "LO:HI:N"),
    (["--grid", "V=1e-4", "--out", "x.txt"], "netCDF"),
    (["--grid", "V=1e-4"], "--out"),
    (["--out", "x.nc"], "--grid"),
    (["--grid", "V=1e-4", "--grid", "V=1e-3", "--out", "x.nc"], "twice"),
    (["--grid", "V=1e-4", "--dask", "local:0", "--out", "x.nc"], "local:N"),
    (["--grid", "V=a,b", "--out", "x.nc"], "not a number"),
])
def test_cli_sweep_bad_input_one_line_exit_2(tmp_path, capsys, monkeypatch, args, what):
    monkeypatch.chdir(tmp_path)
    assert main(["sweep", "hopf", "spring-block", "dieterich", *args]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and what in err


def test_hopf_sweep_of_another_model_point_by_point_equals_landau_hopf(capsys):
    # Galvanetto (2004) one block: c_1 = F_k'(-V), the engine's Λ; the sweep calls the same analysis
    ds = landau.sweep("hopf", {"V": [0.3, 0.5], "gamma": [2.0, 3.0]}, model="galvanetto-one-block", workers=1,
                      progress=False)
    assert (ds.status == "ok").all()
    assert main(["hopf", "galvanetto-one-block", "--V", "0.5", "--param", "gamma=3.0", "--json"]) == 0
    doc = json.loads(capsys.readouterr().out)
    pt = ds.sel(V=0.5, gamma=3.0)
    for name in ("p_c", "omega_c", "Lambda", "C"):
        assert float(pt[name]) == doc[name], name
    assert str(pt.criticality.values) == doc["criticality"]


def test_scene_sweep_equals_the_scene_and_its_published_value_at_the_defaults():
    from landau.scenes import get_scene, run_scene

    name = "skurativskyi2019/static-equilibrium"
    kI = get_scene(name).defaults["kI"]
    ds = landau.sweep("scene", {"kI": [0.5 * kI, kI, 2 * kI]}, model=name, workers=1, progress=False)
    assert ds.value.attrs["units"] == "m" and ds.attrs["scene_parameter"] == "X0"
    at = ds.sel(kI=kI)
    assert float(at.value) == run_scene(name)["value"]
    # Skurativskyi et al. (2019) Sec. 5: X0 = -2.0807e-3 m at the identified parameters
    assert str(at.agrees.values) == "true" and float(at.published) == -2.0807e-3
    # a stiffer obstacle holds the cart closer to it: X0 moves towards x_I = -2.086e-3 m
    assert float(ds.value.sel(kI=2 * kI)) < float(at.value) < float(ds.value.sel(kI=0.5 * kI))
    assert list(ds.agrees.values[[0, 2]]) == ["", ""]  # other parameters: compared, not judged
    # on 2 local processes (the first chunk in this process, the others in the forked workers): the same
    two = landau.sweep("scene", {"kI": [0.5 * kI, kI, 2 * kI]}, model=name, workers=2, progress=False)
    assert two.value.values.tolist() == ds.value.values.tolist()
