"""Unit-aware values (landau.lab.units) and the presets (landau.lab.preset): good strings to their SI
value (exact where the decimal value is: 10um is the double nearest 1e-5), bad ones a named InputError."""

from __future__ import annotations

import pytest

from landau.errors import InputError
from landau.lab.preset import LAB, SI, get_preset
from landau.lab.units import parse_value, to_unit


@pytest.mark.parametrize("text, kind, si", [
    ("1um/s", "velocity", 1e-6),
    ("10 um/s", "velocity", 1e-5),
    ("3um/min", "velocity", 5e-8),
    ("2.5mm/s", "velocity", 2.5e-3),
    ("1e-3/um", "inverse length", 1e3),
    ("1e-3 1/um", "inverse length", 1e3),
    ("0.5/mm", "inverse length", 500.0),
    ("10um", "length", 1e-5),
    ("10µm", "length", 1e-5),
    ("2min", "time", 120.0),
    ("2e4N/m", "stiffness", 2e4),
    ("3kN/m", "stiffness", 3e3),
    ("7", "velocity", 7.0),            # a bare number is SI without a default unit
])
def test_good_values_in_si(text, kind, si):
    x, got = parse_value(text, kind, "--x")
    assert got == kind
    assert x == si           # exact: one correctly rounded multiplication or division by a power of ten


def test_a_bare_number_takes_the_default_unit_and_output_converts_back():
    assert parse_value("10", "velocity", "--V", "um/s")[0] == 1e-5
    assert parse_value(10.0, "length", "L", "um")[0] == 1e-5
    assert to_unit(1e-5, "um") == 10.0
    assert to_unit(1e3, "1/um") == 1e-3


@pytest.mark.parametrize("text, kind, words", [
    ("1um", "velocity", ["'1um'", "is a length", "expected a velocity"]),
    ("10um/s", "length", ["'10um/s'", "is a velocity", "expected a length"]),
    ("1e-3/kg", "inverse length", ["'1e-3/kg'", "unknown unit '/kg'"]),
    ("1 furlong/s", "velocity", ["unknown unit 'furlong/s'"]),
    ("um/s", "velocity", ["'um/s' is not a number"]),
    ("", "velocity", ["'' is not a number"]),
    ("nan um/s", "velocity", ["is not a number"]),
    ("1e999um/s", "velocity", ["not finite"]),
    ("1um/s/s", "velocity", ["unknown unit 'um/s/s'"]),
])
def test_bad_values_are_named_input_errors(text, kind, words):
    with pytest.raises(InputError) as exc:
        parse_value(text, kind, "--V")
    msg = str(exc.value)
    assert msg.startswith("--V: ")
    for w in words:
        assert w in msg


def test_the_stiffness_of_a_preset():
    # per unit normal stress k' in 1/um: k = k' sigma; the lab preset has sigma = 1
    assert LAB.stiffness_value("1e-3/um", 1.0) == 1e3
    assert LAB.stiffness_value("1e-3", 1.0) == 1e3          # bare: 1/um
    assert SI.stiffness_value("1e-3/um", 11.772) == pytest.approx(11772.0, rel=1e-15)
    assert SI.stiffness_value("2e4", 11.772) == 2e4         # bare: N/m
    with pytest.raises(InputError, match="--k: '1um/s' is a velocity"):
        LAB.stiffness_value("1um/s", 1.0)
    with pytest.raises(InputError, match="must be > 0"):
        LAB.stiffness_value("-1/um", 1.0)
    with pytest.raises(InputError, match="unknown preset 'lib'"):
        get_preset("lib")


def test_the_lab_preset_is_quasi_static_per_unit_normal_stress():
    assert dict(LAB.block) == {"M": 0.0, "eta": 0.0, "sigma": 1.0}
    assert (LAB.length, LAB.velocity, LAB.stiffness) == ("um", "um/s", "1/um")
    assert LAB.parameter_value("10", "m", "L") == 1e-5
    assert LAB.parameter_value("1", "m/s", "V_s") == 1e-6
    assert LAB.parameter_value("0.005", "", "a") == 0.005
    with pytest.raises(InputError, match="L: '10um/s' is a velocity"):
        LAB.parameter_value("10um/s", "m", "L")
