# ---
# jupyter:
#   jupytext:
#     text_representation:
#       extension: .py
#       format_name: percent
#   kernelspec:
#     display_name: Python 3
#     language: python
#     name: python3
# ---

# %% [markdown]
# # Models, simulations and maps
#
# Every mechanical model of landau is one registered object (`landau.models`): its parameters
# with defaults, units, domains and sources, the friction law it takes and what it offers.  This
# notebook walks through a user system written as strings, a chain of spring–blocks, a load-point
# history and a (V, η) map — each checked against a closed form.

# %%
import numpy as np

import landau
import landau.models

print(landau.models.names())
m = landau.models.get("spring-block")
print(m.offered(), [(p.name, p.default, p.unit) for p in m.parameters()][:4])

# %% [markdown]
# ## A user system from strings
#
# The Brusselator, ẋ = a − (b + 1)x + x²y, ẏ = bx − x²y, loses stability at b_c = 1 + a² with
# frequency ω_c = a (Nicolis & Prigogine 1977).  Its Hopf point through the model `system`, then
# a run just past it with the compiled Radau IIA:

# %%
opts = {"rhs": {"x": "a - (b + 1)*x + x^2*y", "y": "b*x - x^2*y"}, "parameter": "b",
        "equilibrium": {"x": "a", "y": "b/a"}, "bracket": (2.0, 5.0)}
h = landau.models.get("system").hopf(landau.models.Setup(None, {"a": 1.5}, opts))
print(h.p_c, h.omega_c, h.criticality)
assert abs(h.p_c - (1 + 1.5**2)) < 1e-10 and abs(h.omega_c - 1.5) < 1e-10

run = landau.simulate("system", params={"a": 1.5, "b": 3.3}, options=opts, t_end=200.0)
x = run.y[0]
print(f"x oscillates between {x[run.t > 150].min():.4f} and {x[run.t > 150].max():.4f}")

# %% [markdown]
# ## A chain of spring–blocks
#
# Two identical blocks with the Dieterich law, weakly coupled: the in-phase mode moves both blocks
# together, so its Hopf point is the single block's k_c (Putelat et al. 2010, eq. 30).

# %%
law = landau.laws.get_law("dieterich")
single = landau.models.get("spring-block").hopf(landau.models.Setup(law, {"V": 1e-4}))
chain = landau.models.get("spring-block-chain").hopf(
    landau.models.Setup(law, {"V": 1e-4, "k_coupling": 1e5}, {"blocks": 2}))
print(single.p_c, chain.p_c, chain.extra.get("mode"))
assert abs(chain.p_c / single.p_c - 1) < 1e-9

# %% [markdown]
# ## A load-point history
#
# A velocity step from 1 to 10 µm/s: the friction coefficient settles at
# μ_ss(V₂) = μ_ss(V₁) + (a − b) ln(V₂/V₁) (Dieterich 1979).  The series on a uniform grid:

# %%
p = law.defaults()
step = landau.simulate("spring-block", "dieterich", history="1e-6@0,1e-5@20", t_end=200.0, dt=1.0)
mu = step.y[list(step.state_names).index("mu")]
dmu = mu[-1] - mu[0]
print(f"delta mu_ss = {dmu:.6f}, (a - b) ln 10 = {(p['a'] - p['b']) * np.log(10):.6f}")
assert abs(dmu - (p["a"] - p["b"]) * np.log(10)) < 1e-6
fig = step.plot()

# %% [markdown]
# ## A (V, η) map
#
# Radiation damping η (Rice 1993) moves the codimension-two velocity V* where the Hopf
# bifurcation turns from subcritical to supercritical.  Any declared parameter is a sweep axis:

# %%
ds = landau.sweep("hopf", {"V": np.logspace(-5, -3, 9), "eta": [0.0, 100.0, 300.0]}, law="dieterich",
                  workers=1, progress=False)
print(ds.criticality.values)
assert ds.criticality.values[0, 0] == "subcritical" and ds.criticality.values[0, 2] == "supercritical"
