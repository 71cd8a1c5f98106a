"""Analyses built on the derivation: amplitudes, generalised-Hopf points and folds of cycles,
transition velocities, regime diagrams, continuation, and the check by direct simulation."""
