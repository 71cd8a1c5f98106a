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
# # A non-smooth model: Galvanetto's stick–slip block
#
# A block on a belt moving at speed V, held by a unit spring, with the kinetic friction law
# F_k(r) = (1 − δ)/(1 − γr) + δ for a slip rate r < 0 (and its mirror image for r > 0), static
# friction F_s = 1 while stuck (Galvanetto 2004, J. Sound Vib. 276, eqs 4a, 7).  The block
# sticks, slips and sticks again: a hybrid system with modes "s" (stick), "n" (r < 0) and
# "p" (r > 0), simulated by the toolkit's event-driven engine.

# %%
import matplotlib.pyplot as plt
import numpy as np

from landau.verify.galvanetto.analysis import trajectory
from landau.verify.galvanetto.bifurcations import hopf_c1, hopf_c1_normal_form
from landau.verify.galvanetto.model import one_block

# %% [markdown]
# ## A stick–slip cycle
# Start at the end of the stick interval (spring force = F_s, block moving with the belt) and
# record the hybrid trajectory: time series and phase portrait.

# %%
p = one_block(V=0.5, gamma=3.0, delta=0.2)
t, y, run = trajectory(p, "n", [1.0, p.V], t_end=30.0)
modes = sorted({e.to_mode for e in run.events})
len(run.events), modes

# %%
# the block comes back to stick (mode "s") and the spring force there never exceeds F_s = 1
assert "s" in modes
stuck = np.isclose(y[1], p.V)
assert np.all(np.abs(y[0][stuck]) <= 1.0 + 1e-9)
# every stick phase ends at the same point (spring force F_s), so the motion is periodic:
# the times between successive ends of stick agree to the integration tolerance
period = np.diff([e.t for e in run.events if e.to_mode == "n"])
assert len(period) >= 2 and np.ptp(period) < 1e-6 * period[0], period
period[0]

# %%
fig, (a1, a2) = plt.subplots(1, 2, figsize=(9, 3.4))
a1.plot(t, y[0], lw=1)
a1.set_xlabel("t")
a1.set_ylabel("X")
a2.plot(y[0], y[1], lw=1)
a2.axhline(p.V, color="0.5", ls=":", label="stick: dX/dt = V")
a2.set_xlabel("X")
a2.set_ylabel("dX/dt")
a2.legend(fontsize="small")
fig.tight_layout()

# %% [markdown]
# ## The smooth part, through the Hopf engine
# With viscous damping c the slipping block has a Hopf point at c₁ = F_k'(−V) =
# γ(1 − δ)/(1 + γV)² (closed form, ω = 1).  The general engine locates it numerically and gives
# its criticality: Λ > 0, subcritical — an unstable cycle exists for c > c₁.

# %%
hopf = hopf_c1_normal_form(V=0.5, gamma=3.0, delta=0.0)
hopf

# %%
assert abs(hopf.p_c - hopf_c1(0.5, 3.0, 0.0)) < 1e-12 * hopf.p_c
assert abs(hopf.omega_c - 1) < 1e-12 and hopf.Lambda > 0
plt.close("all")
