"""The amplitude equation's boundaries on a regime map: the fold of cycles and the codimension-two velocities."""

import json

import numpy as np
import pytest

xr = pytest.importorskip("xarray")

from landau.cli import main  # noqa: E402

#: law (39) of Putelat et al. (2010) at c = 3e-4, over the gallery map's velocity range (docs/sweeps.md)
LAW, C, V_LO, V_HI = "modified-dieterich", 3e-4, 1e-7, 3e-3


def _map(V, k=(1e5, 2e5, 4e5)):
    """A regime map's Dataset without the simulations (the overlay reads only the law, the fixed
    parameters and the axes)."""
    reg = np.full((len(V), len(k)), "steady", dtype=object)
    return xr.Dataset({"regime": (("V", "k"), reg), "status": (("V", "k"), np.full(reg.shape, "ok", dtype=object))},
                      coords={"V": np.asarray(V, dtype=float), "k": np.asarray(k, dtype=float)},
                      attrs={"task": "regime", "model": "spring-block", "law": LAW,
                             "fixed_parameters": json.dumps({"c": C})})


@pytest.fixture(scope="module")
def overlay():
    from landau.analyses.regime_overlay import regime_overlay

    V = np.geomspace(V_LO, V_HI, 40)      # the gallery map's axis
    return V, regime_overlay(_map(V), n_fold=120)


def test_fold_curve_equals_the_quintic_amplitude_equation_at_the_map_velocities(overlay):
    from landau.analyses.bautin import spring_block_fold
    from landau.derivation.multiscale import Derivation
    from landau.laws import get_law
    from landau.systems.system import SpringBlock

    V, ov = overlay
    assert set(V) <= set(ov["V_fold"])                 # evaluated at every column of the map
    d = Derivation(SpringBlock(get_law(LAW)))
    drawn = dict(zip(ov["V_fold"], ov["k_fold"], strict=True))
    # where Λ < 0 < Λ₅ below V* (a fold below k_c) and where Λ > 0 > Λ₅ above it, and where there is none
    for Vi in (V[30], V[32], V[33], V[20]):
        f = spring_block_fold(d, float(Vi), {"c": C})
        if f is None:
            assert np.isnan(drawn[Vi])
        else:
            assert drawn[Vi] == pytest.approx(f.p_fold, rel=1e-12)
    assert np.isfinite(ov["k_fold"]).sum() >= 4 and np.isnan(drawn[V[20]])
    # the sides of V*: above it (Λ > 0 > Λ₅) the fold bounds the bistable window above k_c, below it
    # (Λ < 0 < Λ₅) the stable small cycle meets an unstable one below k_c
    kc = ov["kc_fold"]
    fin = np.isfinite(ov["k_fold"])
    above = fin & (ov["V_fold"] > ov["V_star"][0])
    assert above.any() and (ov["k_fold"][above] > kc[above]).all()
    assert (ov["k_fold"][fin & ~above] < kc[fin & ~above]).all()

def test_codimension_two_velocity_equals_landau_derive(overlay, capsys):
    _, ov = overlay
    assert main(["derive", LAW, "--param", f"c={C}", "--codim2", f"{V_LO}:{V_HI}", "--json"]) == 0
    doc = json.loads(capsys.readouterr().out)
    assert len(ov["V_star"]) == len(doc["codim2"]) == 1
    assert ov["V_star"][0] == pytest.approx(doc["codim2"][0]["V"], rel=1e-12)
    assert ov["kc_star"][0] == pytest.approx(doc["codim2"][0]["kc"], rel=1e-12)


def test_the_plot_draws_the_overlay_with_a_legend_entry_for_each_mark(overlay, tmp_path, capsys):
    from matplotlib.figure import Figure

    from landau.verify.springblock.regime_map import plot_regime_map

    V, ov = overlay
    ds = _map(V)
    ax = plot_regime_map(ds, Figure().subplots(), overlay=ov)
    lines = {ln.get_label(): ln for ln in ax.get_lines()}
    fold = next(ln for lab, ln in lines.items() if lab.startswith("fold of cycles"))
    np.testing.assert_array_equal(fold.get_xdata(), ov["V_fold"])
    np.testing.assert_array_equal(fold.get_ydata(), ov["k_fold"])
    star = next(ln for lab, ln in lines.items() if lab.startswith("V*"))
    assert star.get_xdata()[0] == ov["V_star"][0]
    legend = [t.get_text() for t in ax.get_legend().get_texts()]
    assert any(t.startswith("fold of cycles") for t in legend) and any(t.startswith("V*") for t in legend)
    # the command line: the same V* in its JSON document
    nc = tmp_path / "map.nc"
    ds.to_netcdf(nc)
    assert main(["plot", "--sweep", str(nc), "--out", str(tmp_path / "map.png"), "--json"]) == 0
    doc = json.loads(capsys.readouterr().out)
    assert doc["V_star"] == pytest.approx(list(ov["V_star"]), rel=1e-15) and doc["fold_points"] > 0


def test_simulated_bistable_window_ends_at_the_predicted_fold():
    """Dieterich law at V = 1.5e-4 m/s, subcritical (V < V* = 2.07e-4 m/s): the quintic amplitude
    equation puts the fold 0.27 % of k_c above k_c; direct simulation from both sides finds the
    bistable window ending there.  The truncation's relative error is O(V* − V) (module
    :mod:`landau.analyses.bautin`): at 20 % inside the window the point is bistable, at 20 % beyond
    the fold only steady sliding remains."""
    import landau
    from landau.analyses.bautin import spring_block_fold
    from landau.derivation.multiscale import Derivation
    from landau.systems.system import SpringBlock

    V = 1.5e-4
    f = spring_block_fold(Derivation(SpringBlock(landau.laws.get_law("dieterich"))), V)
    width = f.p_fold - f.p_c
    assert 0 < width / f.p_c < 0.01
    ks = [f.p_c + 0.8 * width, f.p_c + 1.2 * width]
    ds = landau.sweep("regime", {"V": [V], "k": ks}, law="dieterich", workers=1, progress=False)
    assert list(ds.regime.values[0]) == ["bistable", "steady"]
