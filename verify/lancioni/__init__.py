"""Frictional impact oscillator of Lancioni, Lenci & Galvanetto (windscreen-wiper hopping).

* :mod:`landau.verify.lancioni.contact` — one frictional unilateral contact on the hybrid engine
  (free flight / slip± / stick, Poisson impact law with Coulomb friction — impulse equations
  derived in its docstring —, chattering, Painlevé detection);
* :mod:`landau.verify.lancioni.model` — eq. (1): the two-mass bar on a moving belt;
* :mod:`landau.verify.lancioni.kernels` — its regimes' fields (and the slip ODE's) generated and
  compiled once per machine, integrated by the compiled DOP853
  (:class:`~landau.verify.hybrid.dop853.CompiledDOP853`, the default of every analysis here);
* :mod:`landau.verify.lancioni.slip` — the smooth slip mode as a ``DynamicalSystem`` and its
  Hopf point through :func:`landau.derivation.general.hopf_normal_form`;
* :mod:`landau.verify.lancioni.analysis` — slip cycles, lift-off, stick onset, free-flight onset,
  Painlevé onset, simulated Hopf point;
* :mod:`landau.verify.lancioni.period_adding` — the e_N = 0 detached branch near μ = 0.38957 (why
  eq. (1) has no period-adding cascade);
* :mod:`landau.verify.lancioni.diagrams` — bifurcation diagrams in μ and the sinusoidal belt runs;
* :mod:`landau.verify.lancioni.declaration` — the model ``impact-oscillator`` (``landau hopf impact-oscillator``).

Friction.  The paper's Coulomb coefficient μ is the default; every model, analysis and
command also takes a velocity-dependent friction coefficient law
(:class:`landau.laws.velocity.VelocityFriction`, ``friction=``; ``--friction`` on the command
line), with its bifurcation parameter (``parameter=``, default the law's first).

Results against the paper (g = 10 m/s², belt v = −1 m/s — the direction with the Hopf point)
--------------------------------------------------------------------------------------------
=====================================  ==============  ===========================================
quantity                               paper           this toolkit
=====================================  ==============  ===========================================
set 1 Hopf μ_c (engine)                0.40977         0.4097782 (supercritical, Λ = −116.3,
                                                       ω_c = 33.68 rad/s); 5th digit: see scenes
set 1 Hopf by hybrid simulation        —               0.40976 (growth-rate zero, ±0.002)
set 1 lift-off (end of slip cycle)     0.40983         0.4098280
set 1 detached branch end (e_N = 0)    0.38957 (acc.)  0.3895691098 (no period-adding cascade in
                                                       eq. (1), nor with a stick tolerance; see
                                                       period_adding)
set 1 e_N = 0.2 detached orbit         bouncing        pure bouncing (flight + impacts), μ ≤ 0.4099
set 1 Painlevé / motion change         ≈ 0.6450        0.64681 (slip reaches D₊ = 0: PainleveError)
set 2 Hopf μ_c                         0.353           0.3530929 (supercritical)
set 2 stick appears                    ≈ 0.360         0.3602370
set 2 free flight from                 ≈ 0.453         0.44986 (0.7 % lower: unprinted belt speed,
                                                       |v| = 0.991 gives 0.4530)
Fig. 6 v = sin(πt/2)                   hop at 0.5      hopping in every v < 0 half period at 0.5,
                                       none at 0.3     no flight at 0.3
=====================================  ==============  ===========================================
"""
