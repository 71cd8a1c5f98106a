"""Infrastructure every stage uses: atomic files, the disk caches, deadlines for symbolic work, progress,
and complex numbers as pairs over any real field."""
