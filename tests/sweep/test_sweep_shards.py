"""Shards of a sweep (a SLURM job array, independent machines) and their merge; the memory budget.

The reference of every comparison is the unsharded run of the same sweep, computed here: a shard
computes the same chunks, so its points must equal the direct run's bit for bit.
"""

import json

import numpy as np
import pytest

pytest.importorskip("xarray")

import landau  # noqa: E402
from landau.analyses.sweep import merge  # noqa: E402
from landau.analyses.sweep_budget import (  # noqa: E402
    BYTES_PER_POINT,
    MEMORY_FRACTION,
    machine_memory,
    memory_estimate,
    parse_memory,
)
from landau.analyses.sweep_engine import make_grid, parse_shard  # noqa: E402
from landau.analyses.sweep_files import shard_path  # noqa: E402
from landau.cli import main  # noqa: E402
from landau.errors import InputError  # noqa: E402

# a = 0.06 > b: velocity strengthening, no Hopf point (Putelat et al. 2010 Sec. 2): two statuses
GRID = {"V": [1e-6, 1e-5, 1e-4, 1e-3], "a": [0.02, 0.0349, 0.06]}
OPTIONS = {"chunk_size": 5}   # 12 points: chunks of 5, 5, 2; shard 1/2 takes chunks 0 and 2, shard 2/2 chunk 1


def _open(path):
    import xarray as xr

    with xr.open_dataset(path) as ds:
        return ds.load()


def _same(a, b):
    """Every variable equal bit for bit (NaN where NaN), the same statuses and messages."""
    assert set(a.data_vars) == set(b.data_vars)
    for name in a.data_vars:
        x, y = a[name].values, b[name].values
        assert x.shape == y.shape, name
        if x.dtype.kind == "f":
            assert np.array_equal(x, y, equal_nan=True), name
        else:
            assert (x.astype(str) == y.astype(str)).all(), name


@pytest.fixture(scope="module")
def files(tmp_path_factory):
    d = tmp_path_factory.mktemp("shards")
    direct = d / "direct.nc"
    landau.sweep("hopf", GRID, law="dieterich", workers=1, progress=False, options=OPTIONS, out=direct)
    for i in (1, 2):
        landau.sweep("hopf", GRID, law="dieterich", workers=1, progress=False, options=OPTIONS,
                     out=d / "map.nc", shard=(i, 2))
    return d


def test_shard_files_named_and_disjoint(files):
    one, two = _open(files / "map.shard-1-of-2.nc"), _open(files / "map.shard-2-of-2.nc")
    assert one.attrs["shard"] == "1/2" and two.attrs["shard"] == "2/2"
    # chunks 0 and 2 (flat points 0-4 and 10-11) and chunk 1 (points 5-9)
    assert one.attrs["shard_points"] == 7 and two.attrs["shard_points"] == 5
    done1 = (one.status.values != "pending").reshape(-1)
    done2 = (two.status.values != "pending").reshape(-1)
    assert np.flatnonzero(done1).tolist() == [0, 1, 2, 3, 4, 10, 11]
    assert np.flatnonzero(done2).tolist() == [5, 6, 7, 8, 9]


def test_merged_equals_direct_bit_for_bit(files, tmp_path):
    direct = _open(files / "direct.nc")
    assert set(np.unique(direct.status.values.astype(str))) == {"ok", "no-hopf"}
    ds, report = merge([files / "map.shard-2-of-2.nc", files / "map.shard-1-of-2.nc"], tmp_path / "merged.nc")
    _same(ds, direct)
    _same(_open(tmp_path / "merged.nc"), direct)
    assert report["pending"] == 0 and report["missing_shards"] == []
    assert [(f["shard"], f["points"], f["pending"]) for f in report["files"]] == [("2/2", 5, 0), ("1/2", 7, 0)]
    assert "shard" not in _open(tmp_path / "merged.nc").attrs


def test_merge_reports_a_missing_shard_and_resumes(files, tmp_path):
    ds, report = merge([files / "map.shard-1-of-2.nc"], tmp_path / "part.nc")
    assert report["missing_shards"] == [2] and report["pending"] == 5
    # the merged file is resumed by the unsharded run: only the missing shard's 5 points computed
    full, counts = landau.sweep("hopf", GRID, law="dieterich", workers=1, progress=False, options=OPTIONS,
                                out=tmp_path / "part.nc", return_counts=True)
    assert counts["computed"] == 5 and counts["reused"] == 7
    _same(full, _open(files / "direct.nc"))


def test_merge_refuses_another_sweep(files, tmp_path):
    other = tmp_path / "other.nc"
    landau.sweep("hopf", GRID, law="dieterich", workers=1, progress=False, options=OPTIONS, out=other,
                 params={"L": 2e-5}, shard=(2, 2))
    with pytest.raises(InputError, match="another sweep.*fixed_parameters differs"):
        merge([files / "map.shard-1-of-2.nc", tmp_path / "other.shard-2-of-2.nc"], tmp_path / "m.nc")
    grid = {"V": [1e-6, 1e-5, 1e-4, 2e-3], "a": GRID["a"]}
    landau.sweep("hopf", grid, law="dieterich", workers=1, progress=False, options=OPTIONS,
                 out=tmp_path / "g.nc", shard=(2, 2))
    with pytest.raises(InputError, match="the grid of V differs"):
        merge([files / "map.shard-1-of-2.nc", tmp_path / "g.shard-2-of-2.nc"], tmp_path / "m.nc")
    with pytest.raises(InputError, match="given twice"):
        merge([files / "map.shard-1-of-2.nc", files / "map.shard-1-of-2.nc"], tmp_path / "m.nc")
    with pytest.raises(InputError, match="one of the shards"):
        merge([files / "map.shard-1-of-2.nc"], files / "map.shard-1-of-2.nc")
    assert not (tmp_path / "m.nc").exists()


@pytest.mark.parametrize("n, sizes", [(3, [4, 4, 4]), (4, [4, 2, 2, 4])])
def test_n_shards_cover_the_grid_once(tmp_path, n, sizes):
    """The chunk composition does not depend on N: with 3 or 4 shards the union is again the direct run,
    bit for bit (every N-th chunk of 2 points, the 6 chunks of the 12-point grid)."""
    direct = landau.sweep("hopf", GRID, law="dieterich", workers=1, progress=False, options={"chunk_size": 2})
    for i in range(1, n + 1):
        landau.sweep("hopf", GRID, law="dieterich", workers=1, progress=False, options={"chunk_size": 2},
                     out=tmp_path / "s.nc", shard=f"{i}/{n}")
    ds, report = merge([tmp_path / f"s.shard-{i}-of-{n}.nc" for i in range(1, n + 1)])
    assert sorted(f["points"] for f in report["files"]) == sorted(sizes)
    _same(ds, direct)


def test_continuation_shards_merge_to_the_direct_run(tmp_path):
    """A continuation in omega (the forced oscillator, Skurativskyi et al. 2019): each chunk starts
    from its own warm-up points, so a shard's chunks are the direct run's; the per-point lists
    (Poincaré points) are joined at the direct run's width."""
    grid = {"omega": [21.6, 21.65, 21.7, 21.75, 21.8]}
    opts = {"n_first": 30, "n_step": 10, "n_keep": 6, "rtol": 1e-7, "overlap": 1, "direction": "down",
            "chunk_size": 2}
    direct = landau.sweep("simulate", grid, model="forced-oscillator", workers=1, progress=False, options=opts,
                          out=tmp_path / "d.nc")
    assert (direct.status == "ok").all() and direct.x_section.ndim == 2
    for i in (1, 2):
        landau.sweep("simulate", grid, model="forced-oscillator", workers=1, progress=False, options=opts,
                     out=tmp_path / "om.nc", shard=(i, 2))
    ds, report = merge([tmp_path / "om.shard-1-of-2.nc", tmp_path / "om.shard-2-of-2.nc"], tmp_path / "om.nc")
    assert [f["points"] for f in report["files"]] == [3, 2] and report["pending"] == 0
    _same(_open(tmp_path / "om.nc"), _open(tmp_path / "d.nc"))


def test_cli_shard_and_merge(files, tmp_path, capsys):
    base = ["sweep", "hopf", "spring-block", "dieterich", "--grid", "V=1e-6,1e-5,1e-4,1e-3",
            "--grid", "a=0.02,0.0349,0.06", "--chunk-size", "5", "--workers", "1", "--out", str(tmp_path / "c.nc")]
    for i in (1, 2):
        assert main([*base, "--shard", f"{i}/2", "--json"]) == 0
        doc = json.loads(capsys.readouterr().out)
        assert doc["out"] == str(tmp_path / f"c.shard-{i}-of-2.nc") and doc["shard"] == f"{i}/2"
        assert doc["computed"] == (7, 5)[i - 1]
    shards = [str(tmp_path / f"c.shard-{i}-of-2.nc") for i in (1, 2)]
    assert main(["sweep-merge", str(tmp_path / "c.nc"), *shards, "--json"]) == 0
    doc = json.loads(capsys.readouterr().out)
    assert doc["pending"] == 0 and doc["points"] == 12
    _same(_open(tmp_path / "c.nc"), _open(files / "direct.nc"))
    # one shard missing: the file is written, the exit code says it is incomplete
    assert main(["sweep-merge", str(tmp_path / "half.nc"), shards[0]]) == 1
    assert "shard 2/2 missing" in capsys.readouterr().out
    for bad in (["--shard", "3/2"], ["--shard", "0/2"], ["--shard", "1-2"]):
        assert main([*base, *bad]) == 2
        err = capsys.readouterr().err
        assert "--shard" in err and "Traceback" not in err
    assert main(["sweep-merge", str(tmp_path / "m.nc"), str(tmp_path / "nope.nc")]) == 2
    assert "no such file" in capsys.readouterr().err


def test_parse_shard_and_path():
    assert parse_shard("3/8") == (3, 8) and parse_shard((1, 1)) == (1, 1) and parse_shard(None) is None
    for bad in ("9/8", "0/8", "a/b", "3", (1.0, 2), (True, 2)):
        with pytest.raises(InputError, match="shard"):
            parse_shard(bad)
    assert shard_path("runs/map.nc", (3, 8)).as_posix() == "runs/map.shard-3-of-8.nc"


# ---------------------------------------------------------------------------------------------
# the memory budget
# ---------------------------------------------------------------------------------------------
def test_big_grid_refused_before_any_work(tmp_path):
    """3000 x 3000 points (9e6): in memory about 4.4 GiB at BYTES_PER_POINT, refused under a 1 GiB
    budget at once; written to a file about 0.27 GiB (STORED_BYTES_PER_POINT and the blocks), refused
    under 100 MiB; no file is written and nothing allocated (the refusal takes well under a second,
    where the table alone would take seconds to allocate)."""
    import time

    from landau.analyses.sweep_budget import STORED_BYTES_PER_POINT, STORED_OVERHEAD

    grid = {"V": "1e-6:1e-3:3000:log", "a": "0.01:0.04:3000"}
    t0 = time.perf_counter()
    with pytest.raises(InputError, match=r"9000000 points, about 4\.\d+ GiB .*budget of 1 GiB"):
        landau.sweep("hopf", grid, law="dieterich", workers=1, progress=False, max_memory="1G")
    with pytest.raises(InputError, match=r"9000000 points, about 0\.267 GiB .*budget of 0\.0977 GiB"):
        landau.sweep("hopf", grid, law="dieterich", workers=1, progress=False, out=tmp_path / "big.nc",
                     max_memory="100M")
    assert time.perf_counter() - t0 < 5.0
    assert not list(tmp_path.iterdir())
    assert memory_estimate(make_grid(grid)) == 9_000_000 * (BYTES_PER_POINT + 16)
    assert memory_estimate(make_grid(grid), stored=True) == 9_000_000 * STORED_BYTES_PER_POINT + STORED_OVERHEAD


def test_default_budget_is_a_fraction_of_the_machine(monkeypatch, tmp_path):
    """The default budget is MEMORY_FRACTION of the machine's memory: a machine of 8 GiB refuses the
    3000 x 3000 grid (4.4 GiB > 4 GiB) and accepts a small one."""
    import landau.analyses.sweep_budget as budget

    monkeypatch.setattr(budget, "machine_memory", lambda: 8 << 30)
    with pytest.raises(InputError, match=r"budget of 4 GiB \(0.5 of this machine's 8 GiB\)"):
        landau.sweep("hopf", {"V": "1e-6:1e-3:3000:log", "a": "0.01:0.04:3000"}, law="dieterich",
                     workers=1, progress=False)
    assert MEMORY_FRACTION == 0.5
    ds = landau.sweep("hopf", GRID, law="dieterich", workers=1, progress=False)
    assert int((ds.status == "ok").sum()) == 8
    total = machine_memory()
    assert total is None or total > 1 << 28   # a real machine has more than 256 MiB


def test_cli_max_memory(capsys, tmp_path, monkeypatch):
    import landau.cli.sweep as command

    def no_cluster(args):
        raise AssertionError("the cluster was started before the grid was refused")

    monkeypatch.setattr(command, "_executor", no_cluster)
    argv = ["sweep", "hopf", "spring-block", "dieterich", "--grid", "V=1e-6:1e-3:3000:log",
            "--grid", "a=0.01:0.04:3000", "--out", str(tmp_path / "big.nc"), "--dask", "local:2",
            "--max-memory", "100M"]
    assert main(argv) == 2
    err = capsys.readouterr().err
    assert "9000000 points" in err and "--max-memory" in err and "Traceback" not in err
    assert not list(tmp_path.iterdir())
    assert main([*argv[:-1], "lots"]) == 2
    assert "--max-memory 'lots'" in capsys.readouterr().err


def test_parse_memory():
    assert parse_memory("8G") == 8 << 30 and parse_memory("500M") == 500 << 20 and parse_memory(4096) == 4096
    assert parse_memory("2.5GB") == int(2.5 * (1 << 30)) and parse_memory("1GiB") == 1 << 30
    for bad in ("0", "-1G", "many", "nanG", True):
        with pytest.raises(InputError, match="--max-memory"):
            parse_memory(bad)
