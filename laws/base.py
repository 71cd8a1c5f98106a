"""What every friction law of the library shares: named parameters with defaults and provenance.

Two kinds of law derive from :class:`Law`:

* :class:`~landau.laws.law.FrictionLaw` — rate-and-state friction μ(v, φ₁…φₙ) with state
  evolution dφᵢ/dt (Putelat, Dawes & Willis 2010; Dieterich 1979; Ruina 1983);
* :class:`~landau.laws.velocity.VelocityFriction` — friction that depends on the sliding
  velocity only, set-valued (Coulomb) or regularised at zero velocity (the impact oscillator
  of Lancioni, Lenci & Galvanetto; the forced cart of Skurativskyi et al. 2019);

and the two-branch kinetic law of Galvanetto (2004),
:class:`~landau.laws.kinetic.KineticFriction`.  Each is data: sympy expressions over named
symbols and :class:`~landau.laws.law.Parameter` objects; derivatives come from sympy and
numeric functions are generated from the expressions, never typed again.
"""

from __future__ import annotations

from landau.errors import InputError


class Law:
    """Base of the friction laws: a ``name``, ``parameters`` (a tuple of
    :class:`~landau.laws.law.Parameter`), a ``source`` and a :meth:`latex` form.

    Subclasses are frozen dataclasses that declare those fields; this class adds what is
    computed from them alone.

    Parameters
    ----------
    name : str
        Short name (CLI name of a built-in law).
    parameters : tuple of Parameter
        Named constants with defaults, units and provenance.
    source : str
        Paper and equation the law comes from.
    """

    name: str
    parameters: tuple
    source: str

    def defaults(self) -> dict[str, float]:
        """The parameters' default values.

        Returns
        -------
        dict of str to float
            By parameter name (parameters without a default are left out).
        """
        return {p.name: p.default for p in self.parameters if p.default is not None}

    def parameter(self, name: str):
        """The declared parameter ``name``.

        Parameters
        ----------
        name : str
            A parameter of this law.

        Returns
        -------
        Parameter

        Raises
        ------
        InputError
            The law has no such parameter.
        """
        for p in self.parameters:
            if p.name == name:
                return p
        raise InputError(f"law {self.name!r} has no parameter {name!r} "
                         f"(known: {', '.join(p.name for p in self.parameters) or 'none'})")

    def with_defaults(self, **values: float):
        """A copy with some parameter defaults changed.

        Parameters
        ----------
        **values : float
            New defaults by parameter name.

        Returns
        -------
        Law
            A new law of the same kind; this one is unchanged.

        Raises
        ------
        InputError
            A name that is not a parameter of the law.
        """
        import dataclasses

        from landau.laws.law import Parameter

        values = dict(values)
        new = []
        for p in self.parameters:
            if p.name in values:
                new.append(Parameter(p.name, float(values.pop(p.name)), p.units, p.source, p.description, p.positive))
            else:
                new.append(p)
        if values:
            raise InputError(f"law {self.name!r} has no parameter(s) {', '.join(sorted(values))}")
        # every concrete law is a dataclass; the abstract base is not
        return dataclasses.replace(self, parameters=tuple(new))  # type: ignore[type-var]

    def latex(self) -> str:  # pragma: no cover - every subclass defines it
        """The law as one line of LaTeX.

        Returns
        -------
        str
        """
        raise NotImplementedError

    def _repr_latex_(self) -> str:
        return f"${self.latex()}$"
