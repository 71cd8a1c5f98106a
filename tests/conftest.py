"""Test-suite settings shared by every test module."""

import os


def pytest_configure(config):
    # the suite tests derivations, not the user's disk cache: no test reads or writes it unless it
    # turns the cache on for itself, in a temporary directory (tests/cli/test_latex.py)
    os.environ["LANDAU_CACHE"] = "off"
