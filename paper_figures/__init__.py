"""Scripts that regenerate the source papers' figures from the toolkit.

Each sub-package (one per paper) exposes ``FIGURES``: an ordered mapping from a figure
name (``"fig8"``) to a function ``make(out_dir: Path) -> list[Path]`` that computes only
what that figure plots and writes its PNG(s) atomically.
"""
