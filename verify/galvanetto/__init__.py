"""Galvanetto (2004) one- and two-block stick–slip models on the hybrid engine.

* :mod:`landau.verify.galvanetto.model` — the models (modes, guards, Filippov transitions);
* :mod:`landau.verify.galvanetto.maps` — the event map d_{k+1} = f(d_k) (Sec. 2.2), one-block cycle;
* :mod:`landau.verify.galvanetto.bifurcations` — locators of the sliding bifurcations (Sec. 4);
* :mod:`landau.verify.galvanetto.analysis` — map curves, bifurcation diagrams, trajectories;
* :mod:`landau.verify.galvanetto.smooth` — the damped one block's smooth slip field for the
  landau (Hopf) engine;
* :mod:`landau.verify.galvanetto.scenes` — the published points as scenes.

Every entry point takes the kinetic friction as a law object, ``law=``
(:class:`landau.laws.kinetic.KineticFriction`: Galvanetto's eq. (7) by default, or a user's
two-branch law from :meth:`~landau.laws.kinetic.KineticFriction.from_expression`); ``gamma``/``delta``
remain as shortcuts for eq. (7).  The locators derive their search intervals from the model:
the law's weakening velocity for the sliding points in V, the Hopf point c₁ for c₂, a β scan for
the discontinuous fold and, from it upward, the period doubling, border collision and crisis.

Findings (located values; DOP853 rtol 1e-11, converged to < 1e-8 against rtol 1e-12)
-------------------------------------------------------------------------------------
* One block, γ = 3, c = 0 (Sec. 4.1): with δ = 0.2 type II at V = 1.2409307 and type I
  at V = 10.801144 (paper 1.241, 10.801); with the printed δ = 0 they are 0.6419889 and
  4.4238333.  The printed δ = 0 is a misprint for this example.
* Two blocks α = 1.2, β = 1.3, γ = 3, δ = 0: type II at V = 0.18285366 (on the period-2
  map orbit; block 1's slip–stick reaches K₁ = −1), type I at V = 0.73501455 (period-1;
  block 1's landing from r₁ > 0 reaches K₁ = +1, after which the map is undefined).
* Fig. 12 (V = 0.25): discontinuous fold β = 1.7216799, period doubling 1.7231390,
  border collision 1.7235674 (paper 1.7217, 1.7231, 1.7236).  At the fold the slopes are
  > 1 and in (−1, 0) — the paper's case (3).  The kink of f is block 1 grazing its
  sticking region (max r₁ = 0 at K₁ = 1) in its first slip phase with both blocks slipping.
  The chaotic attractor dies in a boundary crisis (f²(d_k) = unstable period-1 point) at
  β = 1.7287054; the paper has only a β-axis tick label 1.7280 there.
* Fig. 15: β* = 1.7653142 (paper: 1.7652 < β* < 1.7656).  The computation shows that the
  short stick phase involved is **block 1's** (it exists for β > β*, vanishing like
  sqrt(β − β*)), not block 2's as the paper's text says.
* Multi-sliding (Fig. 16): γ = 10.752697 (paper 10.75265; |Δ| = 4.7e-5 < 1e-4).
* Damped one block, V = 0.5: Hopf c₁ = γ/(1 + γV)² = 0.48, subcritical (ℓ₁ = 3a₃/8 > 0,
  checked by the unstable cycle's amplitude in simulation); non-smooth fold c₂ = 0.65544176.
"""
