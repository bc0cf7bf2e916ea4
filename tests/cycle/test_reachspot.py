"""mjwalk.cycle.reachspot: a reach task from a clear stand turns to the target and reaches it
from where the walk ended (no step), and the start's home defaults to where the operator
stands."""

from __future__ import annotations

import numpy as np

from mjwalk.cycle.context import context_of
from mjwalk.cycle.reaching import ReachPace, default_timing
from mjwalk.cycle.reachspot import ReachStart, reach_task
from mjwalk.cycle.simulate import simulate_cycles


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


def test_short_operators_reach_onto_the_top_shelf_over_its_edge(scenes_dir):
    """Runs 11 and 27 of 40 of the shelving station (seed 0; 1.71 and 1.59 m operators) touched
    ``rack1_shelf_top`` with the forearm and palm (26 and 40 contact frames, up to 11 mm deep)
    picking from and placing on the top shelf (1.52 m): the part lies 0.2 m back on the board,
    the pre-grasp point 0.15 m back was over the board, and the reach model brought the forearm
    up through its front edge; from no spot was the reach clear. With the pre-grasp point out of
    the board (:func:`~mjwalk.cycle.targets.edge_back`) the hand comes over the edge: no
    contact, every hand on its target within 1 cm."""
    res = simulate_cycles(scenes_dir / "shelving_station.toml", runs=40, seed=0, only=[11, 27])
    assert [r.run for r in res] == [11, 27]
    for r in res:
        assert r.operator is not None and r.operator.stature < 1.75
        assert r.collisions == [], (r.run, len(r.collisions), r.collisions[:2])
        assert max(a.hand_error for a in r.arms) < 0.01
