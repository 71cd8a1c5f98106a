"""Named errors. Anything a user can cause is an :class:`InputError` (CLI exit code 2)."""

from __future__ import annotations


class LandauError(Exception):
    """Base class of every error the toolkit raises on purpose."""


class InputError(LandauError, ValueError):
    """Bad input: unknown symbol, parameter out of domain, malformed expression, ..."""


class ParseError(InputError):
    """A friction-law string contains a token outside the whitelist."""


class DomainError(InputError):
    """A law is not real, finite or positive where it must be: μ and the rates on v > 0,
    states > 0, and the steady state (which must exist, be positive and be stable)."""


class NoSteadySlidingError(InputError):
    """The system has no steady sliding state at the requested point (e.g. a normal load that
    grows with the spring force faster than friction can hold it: γ_LD μ_ss ≥ 1)."""


class OutputError(InputError):
    """A result cannot be written where asked (a folder, a missing or read-only place, a full disk)."""


class BudgetError(LandauError):
    """A symbolic computation exceeded its time budget; the message says what to do instead."""


class NoHopfError(LandauError):
    """The requested point has no Hopf bifurcation (e.g. velocity strengthening)."""


class NonSimpleHopfError(LandauError):
    """Several complex pairs cross the imaginary axis together (a double, non-simple Hopf point,
    e.g. identical uncoupled oscillators): there is a crossing, but no single-mode amplitude equation."""


class SingularPointError(InputError):
    """The law's derivatives are singular (or undefined) at the requested point."""


class IntegratorError(LandauError):
    """A numerical integration failed; carries the time and state where it happened."""

    def __init__(self, message: str, t: float | None = None, state=None):
        detail = message
        if t is not None:
            detail += f" (at t = {t!r}"
            if state is not None:
                detail += f", state = {list(map(float, state))!r}"
            detail += ")"
        super().__init__(detail)
        self.t = t
        self.state = state
