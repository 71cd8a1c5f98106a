"""Derivative tensors with the Hopf parameter kept apart: an entry c₀ + c₁p + … has atoms c₀, c₁, ….

:class:`~landau.derivation.jets.Jets` writes every derivative at the equilibrium as an opaque atom,
except an entry that contains the Hopf parameter p, which it keeps as written (p must stay visible:
the characteristic polynomial det(λE − J) = P(λ) + p Q(λ) and the unfolding ∂J/∂p need it).  For
the plain spring–block that entry is −k; a normal load that follows the spring (γ_LD) makes it
−k(1 − γ_LD μ_ss), and the Linker–Dieterich state response (α_LD) puts k into the state row as well,
dφ₁/dt ∋ α_LD γ_LD k u/(σ_ss ∂μ/∂φ₁) (Linker & Dieterich 1992).  Kept as written, those entries
carry the whole steady state (logarithms of V, fractions) into the determinant, whose ring is then
no longer a polynomial ring over the atoms.  :class:`ParameterJets` writes each such entry that is
polynomial in p as Σₘ cₘ pᵐ with every coefficient cₘ = (1/m!) ∂ᵐ/∂pᵐ at p = 0 an atom of its own
(named ``<entry>_k``, ``<entry>_k2``, … for m ≥ 1), so the determinant stays polynomial in the atoms,
λ and p; an entry not polynomial in p is kept as written, as before.

References
----------
Putelat, T., Dawes, J. H. P. & Willis, J. R. (2010), J. Mech. Phys. Solids 58(1), 27–53, eqs (7)–(8).
Linker, M. F. & Dieterich, J. H. (1992), J. Geophys. Res. 97(B4), 4923–4940.
"""

from __future__ import annotations

import sympy as sp

from landau.derivation.jets import Jets, _is_simple


class ParameterJets(Jets):
    """:class:`~landau.derivation.jets.Jets` with the entries polynomial in the Hopf parameter p
    written as Σₘ cₘ pᵐ, each coefficient cₘ an atom (see the module docstring).

    Parameters
    ----------
    system : DynamicalSystem
        The system E·ẏ = f(y; p).
    """

    def _atom(self, name: str, value: sp.Expr) -> sp.Expr:
        p = self.system.parameter
        if value == 0 or _is_simple(value) or p not in value.free_symbols or not value.is_polynomial(p):
            return super()._atom(name, value)
        out = sp.Integer(0)
        coef, m = value, 0
        while coef != 0:
            c = coef.subs(p, 0) / sp.factorial(m)
            if c != 0:
                out += super()._atom(name if m == 0 else f"{name}_{p.name}{m if m > 1 else ''}", c) * p ** m
            coef, m = sp.diff(coef, p), m + 1
        return out


__all__ = ["ParameterJets"]
