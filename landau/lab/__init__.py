"""From laboratory data to a verdict: the lab's units, protocols, measurements, fits and rig verdicts.

Friction laboratories drive a sample at a load-point velocity history — velocity steps and
slide-hold-slide tests (Dieterich 1979; Ruina 1983; Marone 1998) — and read the friction
coefficient against the load-point displacement.  This package speaks their conventions:

* :mod:`landau.lab.units` — unit-aware values (``"1um/s"``, ``"1e-3/um"``, ``"10um"``), SI inside;
* :mod:`landau.lab.preset` — the ``lab`` preset: the quasi-static spring–slider (M = 0, η = 0)
  per unit normal stress, k′ = k/σ in 1/µm, velocities in µm/s, displacements in µm;
* :mod:`landau.lab.protocols` — velocity-step, slide-hold-slide and velocity-history builders,
  and their run (:func:`~landau.lab.protocols.run_protocol`);
* :mod:`landau.lab.measure` — Δμ_ss, the direct-effect peak, healing Δμ_peak against hold time
  and its slope per decade, relaxation during a hold (peaks on the dense solution);
* :mod:`landau.lab.figure` — friction against load-point displacement, the lab's plot;
* :mod:`landau.lab.data`, :mod:`landau.lab.forward`, :mod:`landau.lab.fit` — a record read (landau's
  columns, rsfmodel's, or a mapping), the compiled quasi-static forward model with its exact forward
  sensitivities, and the least-squares fit (standard errors, correlations, an emcee posterior);
* :mod:`landau.lab.verdict` — the fitted law carried to a rig: k_c, ω_c, Λ, the criticality, their
  uncertainties, P(unstable) and P(subcritical).

References
----------
Dieterich, J. H. (1979), Modeling of rock friction 1, J. Geophys. Res. 84, 2161–2168.
Ruina, A. (1983), Slip instability and state variable friction laws, J. Geophys. Res. 88, 10359–10370.
Marone, C. (1998), Laboratory-derived friction laws and their application to seismic faulting,
Annu. Rev. Earth Planet. Sci. 26, 643–696.
"""
