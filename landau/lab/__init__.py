"""Laboratory friction data to a verdict: the lab's units and protocols, fitting a law to lab data, and what
the fit says about a rig."""
