"""The Python API as a newcomer calls it: parameters as keywords, a vector where one velocity is meant."""

from __future__ import annotations

import numpy as np
import pytest

import landau
from landau.errors import InputError


@pytest.fixture(scope="module")
def d():
    return landau.derive("ruina")


def test_evaluate_takes_parameters_as_keywords(d):
    by_kw = d.evaluate([1e-4, 1e-3], M=0.5, names=["kc", "Lambda"])
    by_dict = d.evaluate([1e-4, 1e-3], {"M": 0.5}, ["kc", "Lambda"])
    for n in ("kc", "Lambda"):
        np.testing.assert_array_equal(by_kw[n], by_dict[n])
    # and the keyword is used: eq. (7) of Putelat et al. (2010) for the Ruina law depends on M
    assert by_kw["kc"][1] != d.evaluate([1e-3], names=["kc"])["kc"][0]
    kc, _ = d.hopf.evaluate([1e-4, 1e-3], M=0.5)
    np.testing.assert_allclose(kc, by_kw["kc"], rtol=1e-10)
    (pt,) = d.points(1e-4, M=0.5)
    assert pt.kc == pytest.approx(by_kw["kc"][0], rel=1e-12)


@pytest.mark.parametrize("call, needle", [
    (lambda d: d.evaluate(1e-4, {"M": 1.0}, M=2.0), "'M' is given twice"),
    (lambda d: d.evaluate(1e-4, Mass=2.0), "unknown parameter 'Mass'"),
    (lambda d: d.hopf.point([1e-4, 1e-3]), "V must be one velocity (a number), got 2 value(s)"),
    (lambda d: d.hopf.require(np.array([1e-4, 1e-3])), "for several velocities use points(V)"),
    (lambda d: d.evaluate_mp([1e-4], {}, ["Lambda"]), "V must be one velocity"),
    (lambda d: d.points([[1e-4, 1e-3]]), "1-D sequence of velocities"),
    (lambda d: d.points("fast"), "sequence of numbers"),
])
def test_bad_arguments_are_named(d, call, needle):
    with pytest.raises(InputError) as err:
        call(d)
    assert needle in str(err.value)


def test_bautin_point_refuses_a_vector():
    from landau.analyses.bautin import bautin_point

    with pytest.raises(InputError, match="one velocity"):
        bautin_point(landau.derive("modified-dieterich"), [1.1e-3])


def test_check_refuses_a_vector_velocity_by_name():
    # was: a raw TypeError (float() of a list) from inside check()
    import landau

    with pytest.raises(InputError, match="V must be one velocity"):
        landau.check("dieterich", V=[1e-4, 1e-3])


def test_check_no_hopf_names_the_velocity_weakening_range(capsys):
    # was: "law 'dieterich' has no Hopf point at V = 0.0001 m/s" without the range that `derive` prints
    import landau
    from landau.errors import NoHopfError

    with pytest.raises(NoHopfError, match="velocity strengthening"):
        landau.check("dieterich", V=1e-4, params={"b": 0.01})
    from landau.cli import main

    code = main(["verify", "dieterich", "--V", "1e-4", "--param", "b=0.01"])
    assert code != 0 and "velocity strengthening" in capsys.readouterr().err
