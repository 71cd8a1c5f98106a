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
# # Your friction law in five minutes
#
# Declare a rate-and-state law, derive the amplitude equation of its stick–slip (Hopf)
# bifurcation, get LaTeX for a paper, check the prediction against a direct simulation of the
# full model, and plot the coefficients.  Open this file in Jupyter with jupytext, or run it as
# a script.

# %%
import numpy as np

from landau import SpringBlock, derive
from landau.laws import FrictionLaw

# %% [markdown]
# ## 1. Declare
# μ(v, φ) and dφ/dt as strings (parsed safely, never evaluated).  Here: Ruina's slip law.
# The names a_v, a, b, L, V_s take the values of Table 1 of Putelat, Dawes & Willis (2010).

# %%
law = FrictionLaw.from_strings(
    "my-slip-law",
    mu="a_v + a*log(v/V_s) + b*log(V_s*phi/L)",
    state={"phi": "-(v*phi/L)*log(v*phi/L)"},
)
law

# %% [markdown]
# ## 2. Derive
# `derive` is lazy: it builds only what the requested coefficients need.  `evaluate` is
# vectorised over V and returns a table (a dict of arrays that also shows as a table, converts
# to a pandas DataFrame and plots itself).

# %%
d = derive(SpringBlock(law), ["k_c", "omega_c", "Lambda", "C"])
d

# %%
table = d.evaluate([1e-5, 1e-4, 1e-3], None, ["k_c", "omega_c", "Lambda", "C"])
table

# %% [markdown]
# The slip law is supercritical (Λ < 0) at every velocity: a small stable stick–slip cycle is
# born as the stiffness k drops below k_c.

# %%
assert np.all(table["Lambda"] < 0)
d.points([1e-4, 1e-3])

# %% [markdown]
# ## 3. LaTeX
# Closed forms for the paper.  (The full document, every coefficient, is one command:
# `landau derive --mu ... --state ... --latex my-law.tex`.)

# %%
print(law.latex())
print(d.coefficient("k_c").latex())

# %% [markdown]
# ## 4. Check against a direct simulation
# At k = k_c(1 − ε²) the full (stiff, nonlinear) model is integrated until it settles on its
# limit cycle, and the cycle's amplitude is compared with C·sqrt(k_c − k).  The error of a
# correct leading-order prediction falls like ε².

# %%
import landau

V = 1e-4
checks = [landau.check(law, V, eps2) for eps2 in (1e-3, 4e-4, 1.6e-4)]
checks[0]

# %%
from landau.report.display import ResultList

# a list of results shows as one table
ResultList(checks, columns=["eps2", "amplitude_predicted", "amplitude_simulated", "rel_error", "verdict"])

# %%
eps2s = np.array([c.eps2 for c in checks])
rel = np.abs([c.rel_error for c in checks])
exponent = np.polyfit(np.log(eps2s), np.log(rel), 1)[0]
# every check agrees (each measures its ε² and ε²/4: the error falls like ε² and extrapolates
# to ≈ 0, eq. 23 of Putelat et al. 2010 being a leading-order prediction), and across the three
# the error shrinks like ε² too (a fitted exponent near 1)
assert all(c.agrees for c in checks) and 0.8 < exponent < 1.2, (rel, exponent)
exponent

# %% [markdown]
# In your own CI, one line does the same: `landau.testing.assert_prediction(law, V=1e-4,
# eps2=1e-3)` raises a readable assertion error when the prediction fails.

# %% [markdown]
# ## 5. Plot

# %%
from landau.plotting import plot_check

plot_check(checks, title=f"{law.name}, V = {V:g} m/s")

# %% [markdown]
# The coefficients against V, with the supercritical (Λ < 0) range shaded.  Each plotting call
# shows its figure once, whether it ends the cell or is assigned (`fig = d.plot(...)`).

# %%
d.plot((1e-7, 1e-2), n=120)
