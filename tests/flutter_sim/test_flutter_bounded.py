"""Every non-smooth mode-coupling run is bounded and ends with a named outcome; the command line's contract."""

import json

import numpy as np
import pytest

from landau.cli import main
from landau.errors import InputError
from landau.verify.hybrid import Status
from landau.verify.modecoupling.nonsmooth import Contact, Structure, hoffmann_structure, sliding_equilibrium
from landau.verify.modecoupling.run import bounded_run


def _start(s):
    y0 = sliding_equilibrium(s)
    y0[0] += 1e-3
    return y0


def test_step_budget_and_wall_clock():
    s = hoffmann_structure(mu=0.9)
    sol = bounded_run(s, _start(s), 1e4, max_steps=50)
    assert sol.status is Status.MAX_STEPS and sol.nsteps == 50 and not sol.success
    # a wall-clock budget far below the run's cost: tested at the first logged extremum, after ~1 period
    sol = bounded_run(s, _start(s), 1e6, wall_s=1e-6)
    assert sol.status is Status.WALL_TIME and not sol.success and sol.t_final < 20.0
    assert "wall-clock" in sol.message


def test_softening_contact_collapse_is_named():
    # kNL < 0: N'(delta) = 0 at delta_max = sqrt(kH / (3 |kNL|)); the growing flutter reaches it
    s = hoffmann_structure(mu=1.0, contact="cubic", kNL=-0.4)
    assert s.contact.delta_max == pytest.approx(np.sqrt(1.0 / 1.2), rel=1e-15)
    sol = bounded_run(s, _start(s), 2000.0)
    assert sol.status is Status.STOPPED and sol.final_mode == "collapse"
    assert sol.y_final[1] == pytest.approx(s.contact.delta_max, abs=1e-9)


def test_bad_contact_laws_are_named():
    with pytest.raises(InputError, match="kH"):
        Contact("linear", -1.0)
    with pytest.raises(InputError, match="contact law"):
        Contact("quartic", 1.0)
    with pytest.raises(InputError, match="cubic"):
        Contact("linear", 1.0, 0.5)


@pytest.mark.parametrize("bad,words", [
    (dict(v0=0.0), "v0"),
    (dict(normal=0, tangential=0), "differ"),
    (dict(M=np.array([[1.0, 2.0], [2.0, 1.0]])), "positive definite"),
    (dict(K=np.eye(3)), "same size"),
])
def test_bad_structures_are_named(bad, words):
    kw = dict(M=np.eye(2), C=np.zeros((2, 2)), K=np.eye(2), normal=1, tangential=0, preload=1.0, v0=1.0,
              contact=Contact("linear", 1.0), mu=0.5)
    with pytest.raises(InputError, match=words):
        Structure(**{**kw, **bad})


def test_cli_simulate(tmp_path, capsys):
    out = tmp_path / "run.csv"
    assert main(["simulate", "mode-coupling", "--t-end", "240", "--out", str(out), "--json"]) == 0
    doc = json.loads(capsys.readouterr().out)
    assert doc["status"] == "finished" and doc["state_names"] == ["x", "y", "xdot", "ydot"]
    assert doc["events"] > 0 and out.read_text().startswith("t [s],x [m],y [m],xdot [m/s],ydot [m/s]")
    assert main(["simulate", "mode-coupling", "--max-steps", "20", "--json"]) == 1
    assert json.loads(capsys.readouterr().out)["status"] == "max-steps"


@pytest.mark.parametrize("args,words", [
    (["--contact", "cubicle"], "invalid choice"),
    (["--param", "m=-1"], "'m'"),
    (["--param", "zeta=1"], "zeta"),
    (["--param", "P=-1"], "preload"),
])
def test_cli_bad_input(args, words, capsys):
    assert main(["simulate", "mode-coupling", *args, "--json"]) == 2
    io = capsys.readouterr()
    assert words in json.loads(io.out)["error"] and "Traceback" not in io.err


def test_matrix_family_embeds_the_two_dof_model():
    # the 2-DOF model written as a 3-DOF structure (normal coordinate 0, tangential 2, a decoupled
    # oscillator at 1 left at rest): the same run to the integration tolerance, events included
    import landau

    two = hoffmann_structure(mu=0.9)
    perm = [1, 2, 0]             # 3-DOF coordinate i holds 2-DOF coordinate perm[i] (2: the extra one)
    M, C, K = np.eye(3), np.zeros((3, 3)), np.zeros((3, 3))
    for i, a in enumerate(perm):
        for j, b in enumerate(perm):
            if a < 2 and b < 2:
                C[i, j], K[i, j] = two.C[a, b], two.K[a, b]
    C[1, 1], K[1, 1] = 0.1, 2.0
    opts = {"mass_matrix": M.tolist(), "damping_matrix": str(C.tolist()), "stiffness_matrix": K, "normal": 0,
            "tangential": 2, "contact": "linear"}
    contact = {"kH": 1.0, "kNL": 0.0, "P": 1.0, "v0": 1.0, "mu": 0.9}
    three = landau.simulate("mode-coupling", params=contact, options=opts, t_end=235.0)
    # hoffmann_structure's values through the model's parameters
    ref = landau.simulate("mode-coupling", params={**contact, "m": 1.0, "k1": 1.0, "k2": 0.5, "alpha1": 30.0,
                                                   "alpha2": 60.0, "c1": 0.02, "c2": 0.04},
                          options={"contact": "linear"}, t_end=235.0)
    assert three.state_names == ("x0", "x1", "x2", "xdot0", "xdot1", "xdot2")
    np.testing.assert_allclose(three.y_final[[2, 0, 5, 3]], ref.y_final, atol=1e-6)
    assert three.y_final[1] == 0.0 and three.y_final[4] == 0.0
    assert [e.guard for e in three.events if e.kind == "switch"] == [e.guard for e in ref.events if e.kind == "switch"]
