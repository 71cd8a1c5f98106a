"""landau.support.memo.FloatMemo: one computation per value among the last ``size``, keyed by float."""

from __future__ import annotations

import pytest

from landau.support.memo import FloatMemo


def test_each_value_is_computed_once_and_the_memo_stays_bounded():
    calls: list[float] = []

    def square(x: float) -> float:
        calls.append(x)
        return x * x

    memo = FloatMemo(square, 3)
    assert [memo(2), memo(2.0), memo(3)] == [4.0, 4.0, 9.0]
    assert calls == [2.0, 3.0]                    # 2 and 2.0 are one key
    memo(4)
    memo(5)                                       # the fourth value: the memo starts again
    memo(2)
    assert calls == [2.0, 3.0, 4.0, 5.0, 2.0]
    assert len(memo._values) <= 3


def test_a_size_below_one_is_refused():
    with pytest.raises(ValueError, match="size must be at least 1"):
        FloatMemo(float, 0)
