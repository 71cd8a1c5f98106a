"""A function of one float, remembered for the last values asked.

Continuations revisit their parameter values: the corrector evaluates at the predicted value
several times, a finite difference at p ± h and the point itself. :class:`FloatMemo` keeps
f(x) by ``float(x)``, at most ``size`` values (all forgotten when one more is asked: the values a
continuation needs are the last few, and a clear is cheaper than an order to keep).
"""

from __future__ import annotations

from typing import Callable, Generic, TypeVar

T = TypeVar("T")


class FloatMemo(Generic[T]):
    """``memo(x)`` = ``fn(float(x))``, computed once per value among the last ``size`` kept."""

    def __init__(self, fn: Callable[[float], T], size: int) -> None:
        if size < 1:
            raise ValueError(f"FloatMemo: size must be at least 1, got {size}")
        self.fn = fn
        self.size = size
        self._values: dict[float, T] = {}

    def __call__(self, x: float) -> T:
        key = float(x)
        if key not in self._values:
            if len(self._values) >= self.size:
                self._values.clear()
            self._values[key] = self.fn(key)
        return self._values[key]


__all__ = ["FloatMemo"]
