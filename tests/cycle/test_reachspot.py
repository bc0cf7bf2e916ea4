"""mjwalk.cycle.reachspot: a reach task from a clear stand turns to the target and reaches it
from where the walk ended (no step), and the start's home defaults to where the operator
stands."""

from __future__ import annotations

import numpy as np

from mjwalk.cycle.context import context_of
from mjwalk.cycle.reaching import ReachPace, default_timing
from mjwalk.cycle.reachspot import ReachStart, reach_task


def test_a_reach_start_stands_at_home_unless_told():
    start = ReachStart(1.0, 2.0, 0.5)
    assert (start.facing, start.held, start.home) == (None, None, None)


def test_a_clear_reach_turns_and_reaches_from_the_walks_end(scenes_dir):
    ctx = context_of(scenes_dir / "assembly_station.toml")
    st = ctx.workplace.station("stand_rack2")
    task = next(t for t in ctx.spec.tasks if t.kind == "pick" and t.site == "rack2_screw1")
    x, y = float(st.pos[0]), float(st.pos[1])
    r = reach_task(
        ctx, task, ReachStart(x, y, st.yaw, st.yaw), ReachPace(0.4, 30.0, default_timing)
    )
    assert r.error < 0.01 and r.distance == np.inf and r.step_back == 0.0
    assert (r.x, r.y) == (x, y) and r.width is None
    root = ctx.jointmap.root
    np.testing.assert_allclose(r.turn[-1, root : root + 2], (x, y))
    assert r.turn_time == len(r.turn) / 30.0
    np.testing.assert_allclose(r.frames[-1], r.turn[-1])  # back in the turn's last pose
