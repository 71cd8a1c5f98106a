"""First-order normal-form coefficients of the bifurcations of cycles (Kuznetsov, Govaerts & Doedel 2005)."""

from __future__ import annotations

from typing import Any

from landau.periodic.problem import CycleProblem


def coefficient(problem: CycleProblem, kind: str, point: Any) -> tuple[float | None, str]:
    """The normal-form coefficient of a located special point, and a one-line message."""
    return None, f"{kind}: normal-form coefficient not computed"
