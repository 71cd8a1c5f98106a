"""Code generation: symbolic results as compiled, vectorised functions and simulation kernels."""
