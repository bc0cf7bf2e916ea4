"""mjwalk.cycle.reaching: a one-handed reach ends on its target and comes back to where it
started, its hold lasts the pace's hold, and the reference adult's timing."""

from __future__ import annotations

import numpy as np
import pytest

from mjwalk.cycle.context import context_of
from mjwalk.cycle.poses import standing_pose
from mjwalk.cycle.reaching import (
    ReachPace,
    blend_dir,
    blend_dirs,
    default_timing,
    reach_frames,
    time_factor,
)
from mjwalk.cycle.targets import approach_offset, reach_target


def test_blend_dirs_gives_blend_dirs_numbers_row_by_row():
    """The batch gives exactly what blend_dir gives for each blend, with one start or one
    start per row (the reach's approach and hand turn use both)."""
    rng = np.random.default_rng(8)
    starts = rng.normal(size=(500, 3))
    starts /= np.linalg.norm(starts, axis=1, keepdims=True)
    b = starts[0]
    taus = rng.uniform(0.0, 1.0, 500)
    taus[:2] = [0.0, 1.0]
    alone = np.array([blend_dir(a, b, float(t)) for a, t in zip(starts, taus, strict=True)])
    assert np.array_equal(blend_dirs(starts, b, taus), alone)
    one = np.array([blend_dir(starts[1], b, t) for t in taus])
    assert np.array_equal(blend_dirs(starts[1], b, taus), one)


def test_blend_dir_runs_between_unit_vectors():
    a, b = np.array([1.0, 0.0, 0.0]), np.array([0.0, 1.0, 0.0])
    np.testing.assert_allclose(blend_dir(a, b, 0.0), a)
    np.testing.assert_allclose(blend_dir(a, b, 1.0), b)
    np.testing.assert_allclose(blend_dir(a, b, 0.5), np.array([1.0, 1.0, 0.0]) / np.sqrt(2.0))


def test_the_reference_adults_time_factor_is_one():
    assert time_factor(None) == 1.0 and time_factor(default_timing) == 1.0
    reach, back = default_timing(0.4)
    assert 0.0 < back < reach  # a return (MTM-1 case E) is quicker than a reach (case B)
    assert time_factor(lambda d: (2.0 * reach, 2.0 * default_timing(d)[1])) == pytest.approx(2.0)


def test_a_reach_ends_on_its_target_and_holds_for_the_pace(scenes_dir):
    ctx = context_of(scenes_dir / "assembly_station.toml")
    st = ctx.workplace.station("stand_rack2")
    x, y = float(st.pos[0]), float(st.pos[1])
    site = ctx.workplace.station("rack2_screw1").pos
    q0 = standing_pose(ctx, x, y, st.yaw)
    target = reach_target("pick", site, x, y)
    approach = approach_offset("pick", site, x, y, st.yaw)
    frames, error, res = reach_frames(ctx, q0, target, approach, ReachPace(0.4, 30.0))
    assert error < 0.01 and frames.shape[1] == ctx.model.nq
    np.testing.assert_allclose(frames[-1], q0)  # back to the standing pose
    still = np.flatnonzero(np.abs(np.diff(frames, axis=0)).max(axis=1) < 1e-12)
    assert len(still) == round(0.4 * 30.0)  # the hold's repeated frames
    shorter, _, _ = reach_frames(ctx, q0, target, approach, ReachPace(0.0, 30.0))
    assert len(frames) - len(shorter) == round(0.4 * 30.0)
    assert res.directions.shape[1:] == (3, 3)
