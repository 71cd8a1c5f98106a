"""Friction-induced flutter (mode-coupling instability) of a structure in sliding contact.

* :mod:`landau.verify.modecoupling.declaration` — the model ``mode-coupling`` (Hoffmann et al. 2002's
  2-DOF model, or any N-DOF structure given by its matrices), its Hopf (or mode-coupling) analysis;
* :mod:`~landau.verify.modecoupling.nonsmooth` — the hybrid model simulated: unilateral contact,
  stick and slip, compiled;
* :mod:`~landau.verify.modecoupling.run` — the model's ``simulate``;
* :mod:`~landau.verify.modecoupling.check` — the amplitude check near the flutter onset.

References
----------
Hoffmann, N., Fischer, M., Allgaier, R. & Gaul, L. (2002), Mech. Res. Commun. 29, 197–205.
Hoffmann, N. & Gaul, L. (2003), Z. Angew. Math. Mech. 83, 524–534.
"""
