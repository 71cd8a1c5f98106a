"""Mechanical systems as data: E(p)·ẏ = f(y; p), the spring–block and any smooth system."""
