"""The mode-coupling (flutter) model of Hoffmann, Fischer, Begley & Gaul (2002) simulated non-smoothly.

:mod:`~landau.verify.modecoupling.nonsmooth` (the hybrid model: unilateral contact, stick and slip,
compiled), :mod:`~landau.verify.modecoupling.run` (the model's ``simulate``) and
:mod:`~landau.verify.modecoupling.check` (the amplitude check near the flutter onset).
"""
