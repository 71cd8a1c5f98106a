"""landau fit on the command line: rsfmodel's velocity step fitted after a column mapping, and every
bad record refused with exit 2 and one line naming what is wrong.

The record is rsfmodel's README example (Leeman et al., rsfmodel, examples/velocity_step_one_state.py:
μ₀ = 0.6, a = 0.005, b = 0.01, D_c = 10 µm, k = 1e-3/µm, 1 → 10 µm/s at t = 10 s, 100 Hz for 40 s),
written in the columns of rsfmodel's results (time, loadpoint_displacement, slider_velocity,
friction, states, and the model's loadpoint_velocity), in its units (s, µm, µm/s).
"""

import csv
import json
import subprocess
import sys

import numpy as np
import pytest

from landau.cli import main
from landau.lab.data import read_csv
from landau.lab.fit import fit
from landau.lab.forward import forward_model
from landau.laws import get_law

TRUE = dict(a_v=0.6, a=0.005, b=0.01, L=10e-6, V_s=1e-6)
RSF_COLUMNS = ["time", "loadpoint_displacement", "slider_velocity", "friction", "states", "loadpoint_velocity"]


def _rsfmodel_rows():
    t = np.arange(0, 40.01, 0.01)
    V = np.ones_like(t)
    V[10 * 100:] = 10.0                      # um/s, as rsfmodel's example
    run = forward_model(get_law("dieterich"), ()).run(t, V * 1e-6, TRUE, 1e3, rtol=1e-12)
    x = np.concatenate([[0.0], np.cumsum(V[:-1] * np.diff(t))])   # rsfmodel's _calculateDisplacement
    return np.column_stack([t, x, run.v * 1e6, run.mu, run.states[0], V])


def _write(path, header, rows):
    with open(path, "w", newline="") as fh:
        w = csv.writer(fh)
        w.writerow(header)
        w.writerows(rows)
    return path


@pytest.fixture(scope="module")
def rsf_csv(tmp_path_factory):
    return _write(tmp_path_factory.mktemp("rsf") / "velocity_step.csv", RSF_COLUMNS, _rsfmodel_rows())


def _landau(*args, capsys=None):
    """(exit code, stdout, stderr) of ``landau ARGS``: in this process with ``capsys``, else a child."""
    if capsys is not None:
        capsys.readouterr()
        code = main([str(a) for a in args])
        out, err = capsys.readouterr()
        return code, out, err
    p = subprocess.run([sys.executable, "-m", "landau", *map(str, args)], capture_output=True, text=True, timeout=300)
    return p.returncode, p.stdout, p.stderr


def test_rsfmodel_record_fitted_after_mapping(rsf_csv, capsys):
    code, out, err = _landau("fit", rsf_csv, "--law", "dieterich", "--format", "rsfmodel", "--k", "1e-3/um",
                             "--param", "a=0.004", "--param", "b=0.012", "--param", "L=8um", "--json", capsys=capsys)
    assert code == 0, err
    doc = json.loads(out)
    for n, v in TRUE.items():
        got = doc["fitted"][n]["value"] if n in doc["fitted"] else doc["fixed"][n]
        assert abs(got / v - 1) < 1e-6, n
    assert doc["data"]["samples"] == 4001


def test_renamed_columns_mapped_one_by_one(tmp_path):
    rows = _rsfmodel_rows()
    path = _write(tmp_path / "renamed.csv", ["Time (s)", "LP disp", "v", "Mu", "theta", "LP velocity"], rows)
    data = read_csv(path, columns={"t": "Time (s)", "V_lp": "LP velocity", "mu": "Mu"}, units={"V_lp": "um/s"})
    assert data.V_lp[0] == pytest.approx(1e-6, rel=1e-15)
    res = fit(data, "dieterich", k=1e3, params={"a": 0.004, "b": 0.012, "L": 8e-6})
    assert abs(res.params["L"] / 10e-6 - 1) < 1e-6


def test_landau_columns_with_units_in_brackets(tmp_path):
    rows = _rsfmodel_rows()
    path = _write(tmp_path / "own.csv", ["t [s]", "x_lp [um]", "mu"], rows[:, [0, 1, 3]])
    data = read_csv(path)
    # the velocity from the displacement: (x[i+1] - x[i]) / dt, 1 um/s then 10 um/s from t = 10 s
    assert data.V_lp[999] == pytest.approx(1e-6, rel=1e-9) and data.V_lp[1000] == pytest.approx(1e-5, rel=1e-9)


def _one_error_line(code, out, err):
    assert code == 2, (code, err)
    lines = err.strip().splitlines()
    assert len(lines) == 1 and "Traceback" not in err, err
    return lines[0]


def test_missing_column(tmp_path, capsys):
    path = _write(tmp_path / "nomu.csv", ["t", "V_lp"], [[0, 1e-6], [1, 1e-6], [2, 1e-6]])
    line = _one_error_line(*_landau("fit", path, "--law", "dieterich", "--k", "1e3", capsys=capsys))
    assert "no column 'mu'" in line


def test_non_monotonic_time(tmp_path, capsys):
    path = _write(tmp_path / "back.csv", ["t", "V_lp", "mu"], [[0, 1e-6, 0.6], [1, 1e-6, 0.6], [0.5, 1e-6, 0.6]])
    line = _one_error_line(*_landau("fit", path, "--law", "dieterich", "--k", "1e3", capsys=capsys))
    assert "not strictly increasing at line 4" in line


def test_nan_row(tmp_path, capsys):
    path = _write(tmp_path / "nan.csv", ["t", "V_lp", "mu"], [[0, 1e-6, 0.6], [1, 1e-6, "nan"], [2, 1e-6, 0.6]])
    line = _one_error_line(*_landau("fit", path, "--law", "dieterich", "--k", "1e3", capsys=capsys))
    assert "line 3" in line and "'mu'" in line and "nan" in line


def test_unknown_law(rsf_csv, capsys):
    line = _one_error_line(*_landau("fit", rsf_csv, "--law", "dieterick", "--format", "rsfmodel", "--k", "1e3",
                                    capsys=capsys))
    assert "unknown law 'dieterick'" in line and "did you mean 'dieterich'" in line


@pytest.mark.parametrize("args, words", [
    (["--k", "1e-3/furlong"], "unknown unit '/furlong'"),
    ([], "stiffness k'"),
    (["--k", "1e3", "--free", "a,q"], "cannot fit 'q'"),
    (["--k", "1e3", "--unit", "V_lp=parsec/s"], "unknown unit 'parsec/s'"),
    (["--k", "1e3", "--chains", "c.npz"], "--chains needs --mcmc"),
])
def test_other_bad_input(rsf_csv, args, words, capsys):
    line = _one_error_line(*_landau("fit", rsf_csv, "--law", "dieterich", "--format", "rsfmodel", *args, capsys=capsys))
    assert words in line, line


def test_json_error_document(tmp_path, capsys):
    path = _write(tmp_path / "nomu.csv", ["t", "V_lp"], [[0, 1e-6], [1, 1e-6], [2, 1e-6]])
    code, out, _ = _landau("fit", path, "--law", "dieterich", "--k", "1e3", "--json", capsys=capsys)
    assert code == 2 and json.loads(out)["exit_code"] == 2
