"""Theory curves of Putelat, Dawes & Willis (2010), J. Mech. Phys. Solids — regenerated.

``landau figures putelat2010 [--only fig8] [--out DIR]``.  One module per figure; each
computes only what it plots (the k_c panels never build cubic-order derivatives).  AUTO
branches (saddle-node lines, bifurcation diagrams) are not drawn here.
"""

from __future__ import annotations

from collections import OrderedDict

from landau.paper_figures.putelat2010 import fig4, fig5, fig8, fig9, fig10, fig13, fig14, fig15, fig17

FIGURES = OrderedDict([
    ("fig4", fig4.make), ("fig5", fig5.make), ("fig8", fig8.make), ("fig9", fig9.make),
    ("fig10", fig10.make), ("fig13", fig13.make), ("fig14", fig14.make), ("fig15", fig15.make),
    ("fig17", fig17.make),
])
