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
# # Reproduce a paper figure
#
# Fig. 5(a) of Putelat, Dawes & Willis (2010), J. Mech. Phys. Solids 58, 27–53: the Landau
# coefficient Λ(V) of the Ruina and Dieterich laws, and the Dieterich codimension-two point
# where Λ changes sign on the Hopf line (the paper's Fig. 5b prints k_c ≈ 2.08e5 N/m there).
# The same script runs from the command line: `landau figures putelat2010 --only fig5`.

# %%
import tempfile
from pathlib import Path

import matplotlib.pyplot as plt
import numpy as np

from landau.paper_figures.putelat2010 import fig5

# %%
data = fig5.data()
codim2 = data["codim2"]
codim2

# %%
# one sign change of the Dieterich Λ in 1e-7..1e-2 m/s, at k_c ≈ 2.08e5 N/m (Fig. 5b; the
# paper prints three digits, so agreement to 0.5 %); the Ruina Λ stays negative
assert len(codim2) == 1 and abs(codim2[0].k_c / 2.08e5 - 1) < 5e-3, codim2
assert np.all(data["Lambda_R"][np.isfinite(data["Lambda_R"])] < 0)

# %% [markdown]
# The figure as the script draws it (written to a file), and the same data in a notebook plot.

# %%
out = Path(tempfile.mkdtemp())
paths = fig5.make(out)
assert all(Path(p).stat().st_size > 0 for p in paths)
paths

# %%
fig, ax = plt.subplots(figsize=(6, 4))
V = data["V"]
for key, style, label in (("Lambda_R", "-", "Ruina"), ("Lambda_D", "--", "Dieterich")):
    ax.plot(V, data[key], "k" + style, label=label)
ax.plot([c.V for c in codim2], [0.0] * len(codim2), "ko", label="codimension-two point")
ax.set_xscale("log")
ax.set_yscale("symlog", linthresh=1e6)
ax.set_xlabel("V [m/s]")
ax.set_ylabel("Λ [1/(m² s)]")
ax.legend(fontsize="small")
fig.tight_layout()
