"""A walk laid out from its footfalls (mjwalk.plan.footfallwalk): the same samples, bit for bit,
as a loop over the steps (the loop mjwalk.plan.levelcross.cross_walk ran until levelcost47)."""

from __future__ import annotations

import numpy as np
import pytest

from mjwalk.conventions import SAMPLE_RATE_HZ
from mjwalk.plan.footfallwalk import footfall_walk
from mjwalk.plan.walkpath import PathStep


def _loop(lay, feet, side, start, turn, floor_z):
    """The step loop, one step at a time (the reference)."""
    points, heights, times, headings, across, width = lay
    was, turns, yaw = turn
    feet = dict(feet)
    xs, zs, yaws = [start[0][None, :]], [np.array([start[1]])], [np.array([start[2]])]
    steps, n = [], 0
    for k, dt in enumerate(times):
        sign = 1.0 if side == "left" else -1.0
        foot = np.array([*(points[k] + sign * 0.5 * width * across[k]), headings[k]])
        fz = float(heights[k])
        other = "right" if side == "left" else "left"
        stance, sz = feet[other]
        feet[side] = (foot, fz)
        end_xy = 0.5 * (feet["left"][0][:2] + feet["right"][0][:2])
        end_z = 0.5 * (feet["left"][1] + feet["right"][1])
        m = max(1, round(dt * SAMPLE_RATE_HZ))
        u = np.arange(1, m + 1) / m
        ease = u * u * (3 - 2 * u)
        start_xy, start_z = xs[-1][-1], zs[-1][-1]
        xs.append(start_xy + np.outer(u, end_xy - start_xy))
        zs.append(start_z + ease * (end_z - start_z))
        yaws.append(was[k] + ease * (headings[k] - was[k]) if k <= turns else np.full(m, yaw))
        steps.append(
            PathStep(side, n, n + m, foot, np.array(stance, dtype=float),
                     foot_z=fz - floor_z, stance_z=float(sz) - floor_z)
        )  # fmt: skip
        n += m
        side = other
    return np.concatenate(xs), np.concatenate(zs), np.concatenate(yaws), steps


@pytest.mark.parametrize("seed", range(40))
def test_footfall_walk_equals_the_step_loop_bit_for_bit(seed):
    rng = np.random.default_rng(seed)
    k = int(rng.integers(1, 16))
    heads = np.cumsum(rng.uniform(-1.0, 1.0, k)) + rng.uniform(-4.0, 4.0)
    across = np.stack([-np.sin(heads), np.cos(heads)], axis=1)
    heights = rng.choice([0.0, 0.17, 0.34, 1.02], k) + rng.normal(0, 0.01, k)
    lay = (
        rng.uniform(-5.0, 5.0, (k, 2)), heights, rng.uniform(0.3, 0.9, k), heads, across,
        float(rng.uniform(0.08, 0.15)),
    )  # fmt: skip
    feet = {
        "left": (rng.uniform(-5.0, 5.0, 3), float(rng.uniform(0.0, 1.0))),
        "right": (rng.uniform(-5.0, 5.0, 3), float(rng.uniform(0.0, 1.0))),
    }
    side = "left" if seed % 2 else "right"
    start = (rng.uniform(-5.0, 5.0, 2), 0.5 * (feet["left"][1] + feet["right"][1]), heads[0] - 0.3)
    turn = (np.concatenate([[start[2]], heads[:-1]]), int(rng.integers(-1, k)), float(heads[-1]))
    floor_z = float(rng.uniform(-0.1, 0.1))
    got, want = (
        footfall_walk(lay, feet, side, start, turn, floor_z),
        _loop(lay, feet, side, start, turn, floor_z),
    )
    for a, b in zip(got[:3], want[:3], strict=True):
        assert a.shape == b.shape and np.array_equal(a, b)
    assert len(got[3]) == len(want[3])
    for p, q in zip(got[3], want[3], strict=True):
        assert (p.side, p.start, p.end, p.foot_z, p.stance_z) == (
            q.side, q.start, q.end, q.foot_z, q.stance_z,
        )  # fmt: skip
        assert np.array_equal(p.foot, q.foot) and np.array_equal(p.stance, q.stance)
