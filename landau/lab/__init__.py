"""Laboratory friction data to a verdict: units, protocols, fits and what the fit says about a rig."""
