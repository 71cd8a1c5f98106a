"""Sweeps of the spring–block's Hopf point (Putelat et al. 2010): executors, samples, resuming."""

import json
from concurrent.futures import Executor, Future

import numpy as np
import pytest

pytest.importorskip("xarray")

import landau  # noqa: E402
from landau.cli import main  # noqa: E402
from landau.errors import InputError  # noqa: E402

GRID = {"V": [1e-6, 1e-5, 1e-4, 1e-3], "a": [0.02, 0.0349, 0.06]}  # a = 0.06 > b: no Hopf point


def _same(a, b):
    """Identical datasets: every variable equal bit for bit (NaN where NaN), the same statuses."""
    assert set(a.data_vars) == set(b.data_vars)
    for name in a.data_vars:
        x, y = a[name].values, b[name].values
        if x.dtype.kind == "f":
            assert np.array_equal(x, y, equal_nan=True), name
        else:
            assert (x == y).all(), name


@pytest.fixture(scope="module")
def serial():
    return landau.sweep("hopf", GRID, law="dieterich", workers=1, progress=False, options={"chunk_size": 5})


def test_hopf_sweep_processes_and_dask_identical(serial):
    from distributed import Client, LocalCluster

    two = landau.sweep("hopf", GRID, law="dieterich", workers=2, progress=False, options={"chunk_size": 5})
    _same(serial, two)
    with LocalCluster(n_workers=2, processes=False, dashboard_address=None) as cluster, Client(cluster) as client:
        remote = landau.sweep("hopf", GRID, law="dieterich", executor=client.get_executor(), progress=False,
                              options={"chunk_size": 5})
    _same(serial, remote)


def test_hopf_sweep_labels_and_statuses(serial):
    ds = serial
    assert ds.kc.dims == ("V", "a") and ds.V.attrs["units"] == "m/s" and ds.kc.attrs["units"] == "N/m"
    assert ds.attrs["model"] == "spring-block" and ds.attrs["law"] == "dieterich"
    assert ds.attrs["convention"] == "putelat2010" and ds.attrs["landau_version"] == landau.__version__
    assert "dphi/dt" in ds.attrs["law_declaration"]
    # a > b: velocity strengthening, steady sliding never loses stability (Putelat et al. 2010 Sec. 2)
    assert (ds.status.sel(a=0.06) == "no-hopf").all() and np.isnan(ds.kc.sel(a=0.06)).all()
    assert (ds.status.sel(a=0.02) == "ok").all()
    assert set(np.unique(ds.criticality.sel(a=0.0349).values)) <= {"subcritical", "supercritical"}


@pytest.mark.parametrize("V, a", [(1e-5, 0.02), (1e-3, 0.0349)])
def test_hopf_sweep_sample_points_equal_landau_hopf(serial, capsys, V, a):
    assert main(["hopf", "spring-block", "dieterich", "--V", repr(V), "--param", f"a={a!r}", "--json"]) == 0
    doc = json.loads(capsys.readouterr().out)
    pt = serial.sel(V=V, a=a)
    assert str(pt.criticality.values) == doc["criticality"]
    # the same formulas, evaluated in a batch and alone: equal within evaluate()'s guaranteed 1e-10 relative
    for name in ("p_c", "kc", "omega_c", "Lambda", "chi", "C", "dRe_lambda_dp", "dIm_lambda_dp"):
        assert float(pt[name]) == pytest.approx(doc[name], rel=1e-10), name


class _Interrupting(Executor):
    """Runs each chunk at submit; raises KeyboardInterrupt (a Ctrl-C) at the ``after``-th submit."""

    def __init__(self, after):
        self.after, self.n = after, 0

    def submit(self, fn, *args, **kwargs):
        self.n += 1
        if self.n == self.after:
            raise KeyboardInterrupt
        f = Future()
        f.set_result(fn(*args, **kwargs))
        return f


def test_interrupted_sweep_resumes_computing_only_the_rest(tmp_path, serial):
    out = tmp_path / "kc.nc"
    with pytest.raises(KeyboardInterrupt):
        landau.sweep("hopf", GRID, law="dieterich", executor=_Interrupting(after=2), workers=1, out=out,
                     progress=False, options={"chunk_size": 5})
    import xarray as xr

    with xr.open_dataset(out) as part:
        assert int((part.status != "pending").sum()) == 5  # the first chunk was kept
    ds, counts = landau.sweep("hopf", GRID, law="dieterich", workers=1, out=out, progress=False,
                              options={"chunk_size": 5}, return_counts=True)
    assert counts == {"computed": 7, "reused": 5, "failed": 0, "kept_failed": 0}
    _same(serial.drop_attrs(), ds.drop_attrs())
    with xr.open_dataset(out) as stored:
        assert stored.attrs["computed"] == 7 and stored.attrs["reused"] == 5
    with pytest.raises(InputError, match="different sweep"):
        landau.sweep("hopf", {"V": [1e-5]}, law="dieterich", workers=1, out=out, progress=False)


def test_hopf_sweep_bad_input():
    with pytest.raises(InputError, match="bifurcation parameter"):
        landau.sweep("hopf", {"k": [1.0]}, law="dieterich", params={"V": 1e-4}, progress=False)
    with pytest.raises(InputError, match="unknown parameter"):
        landau.sweep("hopf", {"V": [1e-4], "zeta": [1.0]}, law="dieterich", progress=False)
    with pytest.raises(InputError, match="unknown sweep task"):
        landau.sweep("hopff", {"V": [1e-4]}, law="dieterich", progress=False)


def test_velocity_only_sweep_uses_one_route_and_equals_landau_hopf():
    from landau.laws import get_law
    from landau.verify.springblock.checks import predict

    Vs = [1e-6, 3e-5, 1e-3]
    a = landau.sweep("hopf", {"V": Vs}, law="dieterich", workers=1, progress=False)
    b = landau.sweep("hopf", {"V": Vs}, law="dieterich", workers=1, progress=False, options={"chunk_size": 1})
    _same(a, b)  # the route does not depend on how the grid is cut
    for V in Vs:
        pr = predict(get_law("dieterich"), V)
        assert float(a.kc.sel(V=V)) == pytest.approx(pr.p_c, rel=1e-10)
        assert float(a.Lambda.sel(V=V)) == pytest.approx(pr.Lambda, rel=1e-10)


def test_a_failed_point_is_tried_again_on_a_rerun(tmp_path, serial):

    out = tmp_path / "kc.nc"
    landau.sweep("hopf", GRID, law="dieterich", workers=1, out=out, progress=False, options={"chunk_size": 5})
    import netCDF4

    from landau.analyses.sweep_store import seal

    with netCDF4.Dataset(out, "a") as nc:   # as a run whose worker died at that point writes it: sealed
        nc.variables["status"][0, 0] = "failed"
        nc.variables["message"][0, 0] = "BrokenProcessPool: A process in the process pool was terminated abruptly"
        seal(nc, nc.variables["status"].shape)
    again, counts = landau.sweep("hopf", GRID, law="dieterich", workers=1, out=out, progress=False,
                                 options={"chunk_size": 5}, return_counts=True)
    assert counts["computed"] == 1 and counts["reused"] == 11
    _same(serial.drop_attrs(), again.drop_attrs())


def test_a_declared_law_sweeps_like_the_same_built_in_law():
    from landau.laws import FrictionLaw

    # the Dieterich law of Putelat et al. (2010) eqs (26)+(28), declared from strings under another name
    mine = FrictionLaw.from_strings("my-dieterich", "a_v + a*log(v/V_s) + b*log(V_s*phi/L)", {"phi": "1 - v*phi/L"})
    Vs = [1e-5, 1e-4]
    a = landau.sweep("hopf", {"V": Vs}, law=mine, workers=1, progress=False)
    b = landau.sweep("hopf", {"V": Vs}, law="dieterich", workers=1, progress=False)
    assert a.attrs["law"] == "my-dieterich" and "dphi/dt" in a.attrs["law_declaration"]
    for name in ("kc", "omega_c", "Lambda", "C"):
        assert np.allclose(a[name].values, b[name].values, rtol=1e-10, atol=0), name


def test_a_two_state_law_sweeps_over_a_parameter_as_one_chunk_equal_to_40_digits():
    """A (V, b₂) sweep of the two-state Dieterich law: its chunks go through the vectorised route
    (array-valued parameters on a Hopf line without closed form; they were evaluated point by point),
    cut into chunks or not the same numbers, each within 1e-10 of a 40-digit evaluation at its point."""
    from landau.derivation.multiscale import derive
    from landau.laws import get_law
    from landau.systems.system import SpringBlock

    grid = {"V": [1e-7, 3e-6, 1e-4], "b2": [0.010, 0.0189]}
    one = landau.sweep("hopf", grid, law="two-state-dieterich", workers=1, progress=False)
    cut = landau.sweep("hopf", grid, law="two-state-dieterich", workers=1, progress=False, options={"chunk_size": 1})
    _same(one, cut)
    d = derive(SpringBlock(get_law("two-state-dieterich")), ["Lambda"])
    for V in grid["V"]:
        for b2 in grid["b2"]:
            want = d.evaluate_mp(V, {"b2": b2}, ["kc", "Lambda"], dps=40)
            for name, key in (("kc", "kc"), ("Lambda", "Lambda")):
                got = float(one[name].sel(V=V, b2=b2))
                assert abs(got - want[key]) <= 1e-10 * abs(want[key]), (V, b2, name, got, float(want[key]))
