"""A CI test for your own friction law: the amplitude equation must match a direct simulation."""
from landau.laws import FrictionLaw
from landau.testing import assert_prediction

MY_LAW = FrictionLaw.from_strings(
    "my-ruina", mu="a_v + a*log(v/V_s) + b*log(V_s*phi/L)", state={"phi": "-(v*phi/L)*log(v*phi/L)"})


def test_my_law_amplitude_equation_holds():
    assert_prediction(MY_LAW, V=1e-3, eps2=1e-3)   # supercritical: error falls like eps2, to ~0
