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
# # Friction-induced flutter: a brake-squeal onset, linear and nonlinear
#
# The 2-DOF model of Hoffmann, Fischer, Allgaier & Gaul (2002, Mech. Res. Commun. 29): a mass on a
# belt held by two inclined springs and pressed on through a contact.  Friction couples its two
# modes; above μ_c they merge into a flutter.  We draw the stability diagram (complex eigenvalue
# analysis), check μ_c against its closed form, then add damping and get what complex eigenvalue
# analysis cannot say: whether the squeal starts gently (supercritical) or suddenly (subcritical),
# and how loud it is.  The parameter values are illustrative (`HOFFMANN_DEFAULTS`).

# %%
import numpy as np

from landau.analyses.flutter import destabilisation_paradox, flutter_hopf, hoffmann_threshold
from landau.analyses.flutter_diagram import stability_diagram
from landau.systems.mode_coupling import HOFFMANN_DEFAULTS as D
from landau.systems.mode_coupling import ModeCoupling

# %% [markdown]
# ## The undamped model: a mode-coupling collision

# %%
undamped = ModeCoupling.hoffmann2002(contact="linear", c1=0.0, c2=0.0)
diagram = stability_diagram(undamped, np.linspace(0.0, 1.0, 200))
collision = flutter_hopf(undamped)
collision

# %%
# the discriminant of the 2x2 eigenproblem vanishes at the closed-form mu_c
mu_c, omega_c = hoffmann_threshold(D["m"], D["k1"], D["k2"], D["alpha1"], D["alpha2"], D["kH"])
assert collision.kind == "mode-coupling"
assert abs(collision.p_c - mu_c) < 1e-10 * mu_c and abs(collision.omega_c - omega_c) < 1e-10 * omega_c
# the diagram is unstable exactly beyond mu_c
assert np.array_equal(diagram.unstable(), diagram.values > mu_c)
fig = diagram.figure(threshold=mu_c)
fig

# %% [markdown]
# ## With damping: the Hopf point and the squeal's amplitude

# %%
squeal = flutter_hopf(ModeCoupling.hoffmann2002())    # cubic (hardening) contact, c1 = 2, c2 = 0.5
squeal

# %%
assert str(squeal.criticality) == "supercritical"
print(f"squeal at {squeal.omega_c / (2 * np.pi):.2f} Hz above mu_c = {squeal.p_c:.6f}; "
      f"amplitudes per sqrt(mu - mu_c): x {squeal.extra['C_x']:.4g} m, y {squeal.extra['C_y']:.4g} m")

# %% [markdown]
# A ten times stiffer cubic term (or a Hertz contact) turns the onset subcritical: a sudden, loud
# squeal with hysteresis — the quadratic term of N about the pressed state y* decides with the cubic.

# %%
stiff = flutter_hopf(ModeCoupling.hoffmann2002(kNL=5.0e9))
assert str(stiff.criticality) == "subcritical" and stiff.Lambda > 0
stiff

# %% [markdown]
# ## The destabilisation paradox (Hoffmann & Gaul 2003)
# Non-proportional damping (c1 ≠ c2) that vanishes leaves a threshold below the undamped one.

# %%
paradox = destabilisation_paradox(ModeCoupling.hoffmann2002(contact="linear"), scales=[1.0, 1e-2, 1e-4])
assert paradox.limit < 0.95 * paradox.p_c_undamped
print(f"mu_c(c -> 0) = {paradox.limit:.5f} < mu_c(c = 0) = {paradox.p_c_undamped:.5f}")
