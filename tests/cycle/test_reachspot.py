"""mjwalk.cycle.reachspot: a reach task from a clear stand turns to the target and reaches it
from where the walk ended (no step), and the start's home defaults to where the operator
stands."""

from __future__ import annotations

import numpy as np
import pytest

from mjwalk.cycle.context import context_of
from mjwalk.cycle.reaching import ReachPace, default_timing
from mjwalk.cycle.reachspot import ReachStart, reach_task
from mjwalk.cycle.seeding import run_generator
from mjwalk.cycle.simulate import simulate_cycle, simulate_cycles
from mjwalk.cycle.tiptoe import max_rise


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


def test_a_short_operator_rises_on_the_toes_for_the_top_shelf(scenes_dir):
    """Run 18 of 40 of the shelving station (seed 1; a 1.53 m operator) touched
    ``rack1_shelf_top`` with the left forearm and fingers picking from the top shelf and the
    right placing on it (109 contact frames, up to 16 mm deep): the shoulder (0.818 H = 1.25 m)
    is too low for the arm to come over the board's front edge (1.52 m) from any spot, with or
    without the approach from out of the board. On the toes
    (:func:`~mjwalk.cycle.tiptoe.tiptoe_pose`, at most the rise of 90 % of the plantar flexion
    range: 7.3 cm at 1.53 m) the hand comes over the edge: no contact, every hand on its target
    within 1 cm, the heels lifted only for the top shelf."""
    ctx = context_of(scenes_dir / "shelving_station.toml")
    # run 18 of the batch (simulate_cycles draws run k from run_generator(seed, k))
    r = simulate_cycle(ctx, run_generator(1, 18), run=18, keep_timeline=True)
    assert r.operator is not None and r.operator.stature == pytest.approx(1.53, abs=0.005)
    assert r.collisions == [], (len(r.collisions), r.collisions[:2])
    assert max(a.hand_error for a in r.arms) < 0.01
    # the pelvis rises above standing height only during the two top-shelf reaches, by no more
    # than the heel rise allows
    tl = r.timeline
    z = tl.qpos[:, tl.jointmap.root + 2]
    stand = z[0]
    up = np.flatnonzero(z > stand + 0.005) / tl.fps
    high = [t for t in r.tasks if t.site == "rack1_high"]
    assert len(up) > 0
    assert all(any(t.start <= s <= t.end for t in high) for s in up)
    assert z.max() - stand <= max_rise(1.53) + 1e-9
