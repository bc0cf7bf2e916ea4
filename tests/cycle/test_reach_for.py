"""mjwalk.cycle.actions.reach_for: a reach's hold is drawn at the operator's pace, and its
perform turns, reaches and returns with the hand on the target."""

from __future__ import annotations

import numpy as np
import pytest

from mjwalk.cycle.actions.base import CycleRun, CycleState
from mjwalk.cycle.actions.reach_for import Reach
from mjwalk.cycle.context import context_of
from mjwalk.cycle.handling import task_factor
from mjwalk.cycle.poses import standing_pose
from mjwalk.cycle.types import TASK_KINDS, Task
from mjwalk.gait.walker import Walker


def _run(ctx, walker=None, seed=7) -> CycleRun:
    rng = np.random.default_rng(seed)
    return CycleRun(ctx, walker, 30.0, rng, np.random.default_rng(seed), rng, np.zeros(3))


@pytest.mark.parametrize("duration", [None, 1.5])
def test_the_hold_is_the_tasks_at_the_operators_pace_times_a_drawn_factor(duration):
    kind = TASK_KINDS["fasten"]
    walker = Walker(stature=1.75, speed=1.0, cadence=100.0)
    reach = Reach(Task("fasten", site="s", duration=duration), kind, 0)
    state = CycleState(0.0, 0.0, 0.0, "a", (0.0, 0.0), np.zeros(3))
    hold, factor = reach.plan(_run(None, walker), state)  # type: ignore[arg-type]
    assert factor == task_factor(np.random.default_rng(7))  # the handling stream's first draw
    base = kind.default_hold if duration is None else duration
    assert hold == pytest.approx(base * factor / walker.pace)


def test_a_pick_turns_and_ends_on_its_target(scenes_dir):
    ctx = context_of(scenes_dir / "assembly_station.toml")
    task = next(t for t in ctx.spec.tasks if t.kind == "pick" and t.site == "rack2_screw1")
    st = ctx.workplace.station("stand_rack2")
    x, y = float(st.pos[0]), float(st.pos[1])
    state = CycleState(x, y, st.yaw, "stand_rack2", (x, y), standing_pose(ctx, x, y, st.yaw))
    reach = Reach(task, TASK_KINDS["pick"], 4)
    done = reach.perform(_run(ctx), state, (0.4, 1.0))
    (turn, dt), (frames, seconds) = done.pieces
    assert dt == pytest.approx(len(turn) / 30.0) and seconds == pytest.approx(len(frames) / 30.0)
    assert done.record.task == 4 and done.record.hand == "left"
    assert done.record.hand_error < 0.01
    assert done.state.grip is None  # one hand: nothing held between the palms
