"""From a system to its Hopf point and amplitude equation: jets, the linear problem, the Fredholm
condition, the multiple-scales coefficients, the independent Lyapunov route and the result type."""
