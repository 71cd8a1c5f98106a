"""The forced oscillator of Skurativskyi, Kudra, Witkowski & Awrejcewicz (2019) without numba's
compiler (``NUMBA_DISABLE_JIT=1``): the event-driven loop, its SDIRK4 stick stepper, the field
and a friction law's generated functions run as plain Python (one warning says so) and give
the compiled run's result."""

from __future__ import annotations

import json
import os
import subprocess
import sys

import numpy as np

#: a short run of eq. (1) with the paper's law and with a user's law (tanh-regularised dry
#: friction), three forcing periods from rest: impacts on the obstacle, detachments and
#: stick phases on it (ω = 15: steps of both the DOPRI5 and the SDIRK4 stepper)
_SHORT_RUN = """
import json, warnings
warnings.simplefilter("always")
from landau.laws.velocity import VelocityFriction
from landau.verify.skurativskyi.model import Params
from landau.verify.skurativskyi.simulate import run
user = VelocityFriction.from_strings("tanh-dry", "c*v + T*tanh(v/e)",
                                     params={"c": 6.6511, "T": 0.63133, "e": 1e-5}, quantity="force")
out = {}
for name, prm in (("paper", Params(omega=15.0)), ("user", Params(omega=15.0, friction=user))):
    r = run(prm, 3)
    out[name] = {"t": r.t_final, "y": r.y_final.tolist(), "impacts": r.impacts.tolist(),
                 "detachments": r.detachments.tolist(), "steps": r.nsteps, "stiff": r.nstiff,
                 "strobe": r.strobe_y.tolist()}
print(json.dumps(out))
"""


def _run(disable_jit: bool) -> subprocess.CompletedProcess:
    env = dict(os.environ)
    env.pop("NUMBA_DISABLE_JIT", None)
    if disable_jit:
        env["NUMBA_DISABLE_JIT"] = "1"
    out = subprocess.run([sys.executable, "-c", _SHORT_RUN], capture_output=True, text=True, env=env, timeout=600)
    assert out.returncode == 0, out.stderr
    return out


def test_runs_as_plain_python_and_agrees_with_the_compiled_run():
    """Under NUMBA_DISABLE_JIT=1 the run is plain Python (one warning names the cause) and agrees
    with the compiled run: the same floating-point operations in the same order, so the same
    steps, stick steps, impacts and detachments, and states equal to far below the integration
    tolerance (rtol 1e-8 per step; only sin and pow may round differently in numpy and in
    the compiled code's math library)."""
    plain = _run(True)
    compiled = _run(False)
    assert plain.stderr.count("NUMBA_DISABLE_JIT is set") == 1
    assert "forced oscillator" in plain.stderr and "runs as plain Python" not in compiled.stderr
    a = json.loads(compiled.stdout.strip().splitlines()[-1])
    b = json.loads(plain.stdout.strip().splitlines()[-1])
    for law in ("paper", "user"):
        x, y = a[law], b[law]
        assert x["t"] == y["t"] == 3 * (2 * np.pi / 15.0)     # t_end = 3 periods, as run() computes it
        assert x["steps"] == y["steps"] and x["stiff"] == y["stiff"] and x["stiff"] > 0
        assert len(x["impacts"]) == len(y["impacts"]) >= 3 and len(x["detachments"]) == len(y["detachments"])
        assert np.allclose(x["impacts"], y["impacts"], rtol=0, atol=1e-12)
        assert np.allclose(x["detachments"], y["detachments"], rtol=0, atol=1e-12)
        # atol: the run's own absolute tolerances (rtol·1e-4 m, rtol·1e-2 m/s) times 1e-2
        assert np.allclose(x["y"], y["y"], rtol=1e-10, atol=1e-14)
        assert np.allclose(x["strobe"], y["strobe"], rtol=1e-10, atol=1e-14)
    # the two laws are different computations (the check above could not pass by accident)
    assert a["paper"]["y"] != a["user"]["y"]
