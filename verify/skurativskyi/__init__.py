"""Verifier IV: the harmonically forced impacting oscillator with regularised dry friction
and Hertz contact of Skurativskyi, Kudra, Witkowski & Awrejcewicz (2019), Nonlinear Dyn.
98:1795–1806 (seed 002; notes §4).

Modules: :mod:`.model` (eq. 1, parameters of Sec. 2), :mod:`.rk` (compiled Dormand–Prince
5(4) with exact contact switching), :mod:`.simulate` (runs, engine model), :mod:`.approx`
(Sec. 5 approximate solutions), :mod:`.analysis` (impact counting, first detachment,
sweeps, grazing, Lyapunov exponent, Tsallis q), :mod:`.sweep` (parallel / dask sweeps
streamed to disk), :mod:`.scenes`.
"""
