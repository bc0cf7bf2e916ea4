"""The shared bounded memo (mjwalk.boundedmemo): the cycle's caches and the level planner's."""

from __future__ import annotations

import pytest

from mjwalk.boundedmemo import Memo
from mjwalk.cycle import memo as cycle_memo


def test_memo_with_its_own_maker_makes_each_key_once_and_drops_the_oldest():
    made = []
    memo = Memo(lambda k: made.append(k) or k * 10, limit=2)
    assert memo.get(1) == 10 and memo.get(1) == 10 and made == [1]
    memo.get(2)
    memo.get(3)  # no room for three: 1, the oldest, goes
    assert 1 not in memo and 2 in memo and 3 in memo and len(memo) == 2


def test_a_maker_per_call_is_used_only_for_a_key_not_kept():
    memo: Memo[str, int] = Memo(limit=3)
    assert memo.get("a", lambda: 1) == 1
    assert memo.get("a", lambda: 2) == 1  # kept: the key names what the value depends on
    with pytest.raises(TypeError):
        memo.get("b")  # no maker at all


def test_the_cycle_names_the_same_memo():
    assert cycle_memo.Memo is Memo


def test_a_cleared_memo_makes_its_values_again():
    made = []
    memo = Memo(lambda k: made.append(k) or k, limit=4)
    memo.get(1)
    memo.clear()
    assert len(memo) == 0 and 1 not in memo
    assert memo.get(1) == 1 and made == [1, 1]
