"""The cycle's memo (mjwalk.cycle.memo) and the context's caches built on it."""

from __future__ import annotations

import dataclasses

import pytest

from mjwalk.cycle.memo import Memo


def test_memo_makes_each_key_once_and_drops_the_oldest():
    made = []
    memo = Memo(lambda k: made.append(k) or k * 10, limit=2)
    assert memo.get(1) == 10 and memo.get(1) == 10
    assert made == [1]  # kept: made once
    memo.get(2)
    memo.get(3)  # no room for three: 1, the oldest, goes
    assert 1 not in memo and 2 in memo and 3 in memo and len(memo) == 2
    assert memo.get(1) == 10 and made == [1, 2, 3, 1]


def test_unbounded_memo_keeps_everything():
    memo = Memo(str)
    for k in range(100):
        memo.get(k)
    assert len(memo) == 100


def test_context_is_frozen_and_shares_its_caches_with_operators(scenes_dir):
    from mjwalk.cycle.context import operator_context, prepare
    from mjwalk.cycle.spec import load_cycle_spec
    from mjwalk.gait.walker import Walker

    ctx = prepare(load_cycle_spec(scenes_dir / "assembly_station.toml"))
    with pytest.raises(dataclasses.FrozenInstanceError):
        ctx.turn_rate = 2.0  # type: ignore[misc]
    step = ctx.step_model.pace().step_length
    zone = ctx.zone(1, ctx.spec.stature, step)
    # the key's rounded figures make the zone: a tenth of a millimetre asks for the same one
    assert ctx.zone(1, ctx.spec.stature + 1e-4, step) is zone
    tall = operator_context(ctx, Walker(stature=1.90))
    assert tall.model is not ctx.model and tall.scratch() is not ctx.scratch()
    assert tall.scratch() is tall.scratch()  # one scratch MjData per model and thread
    # an operator of the cycle's own stature works in the cycle's humanoid and its MjData
    same = operator_context(ctx, Walker(stature=ctx.spec.stature, cadence=100.0))
    assert same is not ctx and same.model is ctx.model and same.scratch() is ctx.scratch()
    import threading

    other: list = []
    worker = threading.Thread(target=lambda: other.append(operator_context(ctx, Walker(1.90))))
    worker.start()
    worker.join()
    assert other[0].model is tall.model and other[0].scratch() is not tall.scratch()
    assert tall.zones is ctx.zones and tall.planners is ctx.planners and tall.routes is ctx.routes
    assert tall.zone(1, ctx.spec.stature, step) is zone
