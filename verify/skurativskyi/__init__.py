"""Verifier IV: the harmonically forced impacting oscillator with regularised dry friction
and Hertz contact of Skurativskyi, Kudra, Witkowski & Awrejcewicz (2019), Nonlinear Dyn.
98:1795–1806.

Modules: :mod:`.model` (eq. 1, parameters of Sec. 2, the friction law), :mod:`.friction` (the
friction term compiled from a law as C callbacks), :mod:`.field` (eq. 1 compiled once for
every law), :mod:`.rk` (compiled Dormand–Prince
5(4) with exact contact switching; the mixed path hands stick steps to :mod:`.sdirk`, an
L-stable SDIRK4), :mod:`.simulate` (runs, engine model), :mod:`.approx` (Sec. 5 approximate
solutions), :mod:`.analysis` (impact counting, first detachment, sweeps, Lyapunov exponent,
Tsallis q), :mod:`.grazing` (grazing margins of continued orbits: the Fig. 3b cascade),
:mod:`.sweep` (parallel / dask sweeps streamed to disk), :mod:`.scenes`.
"""
