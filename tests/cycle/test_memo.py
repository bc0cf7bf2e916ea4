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
    # one scratch MjData per model layout and thread: every stature's humanoid has the sizes
    assert tall.model is not ctx.model and tall.scratch() is ctx.scratch()
    assert tall.scratch() is tall.scratch()
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


def test_scratch_data_are_kept_per_layout_bounded_and_let_dropped_models_go(monkeypatch):
    """The scratch MjData of each model layout and thread (cycle.context._scratch_of): the same
    for models of one size signature, kept for at most SCRATCH's limit of layouts, and a dropped
    layout's model is freed (an MjData holds its model, so a weak-keyed cache never dropped
    any); a model with mocap bodies has its own."""
    import gc
    import weakref

    import mujoco

    from mjwalk.cycle import context
    from mjwalk.cycle.memo import ScratchData

    monkeypatch.setattr(context, "SCRATCH", ScratchData(2))

    def xml(n: int, size: float = 1.0) -> str:
        geoms = "".join(f'<geom size="{size}" pos="{k} 0 0"/>' for k in range(n))
        return f"<mujoco><worldbody>{geoms}</worldbody></mujoco>"

    first = mujoco.MjModel.from_xml_string(xml(1))
    data = context._scratch_of(first)
    assert context._scratch_of(first) is data and data.model is not None
    # another model of the same sizes (other numbers) shares it; other sizes do not
    assert context._scratch_of(mujoco.MjModel.from_xml_string(xml(1, 2.0))) is data
    gone = weakref.ref(first)
    del first, data
    kept = [mujoco.MjModel.from_xml_string(xml(n)) for n in (2, 3)]
    assert context._scratch_of(kept[0]) is not context._scratch_of(kept[1])
    gc.collect()
    assert gone() is None
    assert len(context.SCRATCH) == 2
    mocap = '<mujoco><worldbody><body mocap="true"><geom size="1"/></body></worldbody></mujoco>'
    a, b = (mujoco.MjModel.from_xml_string(mocap) for _ in range(2))
    assert context._scratch_of(a) is not context._scratch_of(b)


@pytest.mark.slow
def test_a_cycle_does_not_depend_on_the_scratch_data_it_gets(scenes_dir, monkeypatch):
    """A run's poses, part tracks, contacts and ergonomics are the same whichever scratch MjData
    its context gets: a used one (another run's state in it) or a new one with junk in every
    field the kinematics do not set. (The bounded scratch cache of 5c4f3dc was reverted for a
    frames/track fingerprint line that changed once; in later runs 5c4f3dc's fingerprint
    equalled its base's.)"""
    import mujoco
    import numpy as np

    from mjwalk.cycle import context
    from mjwalk.cycle.simulate import prepare, simulate_cycle
    from mjwalk.cycle.spec import load_cycle_spec

    ctx = prepare(load_cycle_spec(scenes_dir / "assembly_station.toml"))
    simulate_cycle(ctx, 5)  # the shared scratch now holds another run's state
    used = simulate_cycle(ctx, 1, keep_timeline=True)
    rng = np.random.default_rng(0)

    def junk(model: mujoco.MjModel) -> mujoco.MjData:
        data = mujoco.MjData(model)
        for name in ("qpos", "qvel", "act", "ctrl", "qacc_warmstart", "mocap_pos", "xpos"):
            field = getattr(data, name)
            field[...] = rng.normal(size=field.shape)
        return data

    monkeypatch.setattr(context, "_scratch_of", junk)
    fresh = simulate_cycle(prepare(load_cycle_spec(scenes_dir / "assembly_station.toml")), 1,
                           keep_timeline=True)  # fmt: skip
    tu, tf = used.timeline, fresh.timeline
    assert tu is not None and tf is not None and np.array_equal(tu.qpos, tf.qpos)
    assert [repr(c) for c in used.collisions] == [repr(c) for c in fresh.collisions]
    assert repr(used.ergonomics) == repr(fresh.ergonomics)
    assert len(tu.parts) == len(tf.parts) > 0
    for a, b in zip(tu.parts, tf.parts, strict=True):
        assert a.geom == b.geom and np.array_equal(a.pos, b.pos) and np.array_equal(a.mat, b.mat)


def test_scratch_data_is_per_layout_and_thread():
    """ScratchData (the clearance checks' MjData): one MjData for models of one layout, another
    for another layout, and another thread gets its own."""
    import threading

    import mujoco

    from mjwalk.cycle.memo import ScratchData, data_layout

    def model(size: float) -> mujoco.MjModel:
        return mujoco.MjModel.from_xml_string(
            f'<mujoco><worldbody><body><freejoint/><geom size="{size}"/></body></worldbody>'
            "</mujoco>"
        )

    one, same, other = model(0.1), model(0.2), model(0.1)
    bigger = mujoco.MjModel.from_xml_string(
        '<mujoco><worldbody><body><freejoint/><geom size="0.1"/></body>'
        '<body><freejoint/><geom size="0.1"/></body></worldbody></mujoco>'
    )
    assert data_layout(one) == data_layout(same) != data_layout(bigger)
    scratch = ScratchData(4)
    d = scratch.of(one)
    assert scratch.of(same) is d and scratch.of(other) is d
    assert scratch.of(bigger) is not d
    seen = []
    t = threading.Thread(target=lambda: seen.append(scratch.of(one)))
    t.start()
    t.join()
    assert seen[0] is not d
