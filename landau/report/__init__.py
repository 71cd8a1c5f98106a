"""Presentation primitives: LaTeX printing, tables for terminals and notebooks, plots.

They know nothing of a derivation; what a derivation prints is composed in :mod:`landau.derivation.latex`."""
