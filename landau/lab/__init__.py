"""Laboratory friction experiments: the lab's units and protocols, and fitting a law to lab data."""
