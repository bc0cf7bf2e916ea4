"""The 120 Hz pelvis path and the steps of a walk laid out from its footfalls.

:func:`mjwalk.plan.levelcross.cross_walk` places a crossing's footfalls (where each foot lands,
at what height, how long each step takes and which way it faces); :func:`footfall_walk` walks
them: feet alternate, each foot half the step width beside its footfall's walking line; the
pelvis moves at even speed between the double-support instants, at the middle of the two feet;
its height is the mean height of the surfaces under the two feet and its heading the step's,
both eased (smoothstep) through each step. All steps at once, in NumPy (the same arithmetic,
element by element, as a loop over the steps: the samples are equal bit for bit). Metres,
seconds, radians; heights world (the steps' above ``floor_z``).
"""

from __future__ import annotations

import numpy as np

from mjwalk.conventions import SAMPLE_RATE_HZ, other_side
from mjwalk.plan.walkpath import PathStep


def footfall_walk(
    lay: tuple, feet: dict, side: str, start: tuple, turn: tuple, floor_z: float
) -> tuple[np.ndarray, np.ndarray, np.ndarray, list[PathStep]]:
    """Walk a sequence of footfalls (module docstring).

    Args:
        lay: (points (k, 2) world xy of the footfalls on the walking line, heights (k,) world z
            of the surfaces under them, times (k,) the steps' durations in s, headings (k,) the
            feet's, across (k, 2) the unit vectors left of each step's heading, the step
            width in metres).
        feet: {"left", "right"}: (foot pose (3,) world x, y, yaw; world z) where each foot
            stands before the first step.
        side: the first step's swinging foot, "left" or "right".
        start: (pelvis xy (2,), pelvis world z, pelvis heading) before the first step.
        turn: (was (k,) the heading each step turns from, the number of turning steps, the
            heading the steps after them keep), radians.
        floor_z: the floor's world height, metres.

    Returns:
        (xy (n, 2), z (n,) world, yaw (n,)) at :data:`~mjwalk.conventions.SAMPLE_RATE_HZ`
        from the start on, and the steps (heights above ``floor_z``).
    """
    points, heights, times, headings, across, width = lay
    was, turns, yaw = turn
    k = len(times)
    other = other_side(side)
    lead = 1.0 if side == "left" else -1.0  # the left foot left of the walking line
    sign = np.where(np.arange(k) % 2 == 0, lead, -lead)
    foot = np.column_stack([points + (sign * 0.5 * width)[:, None] * across, headings])
    fz = np.asarray(heights, dtype=float)
    before = np.vstack([np.asarray(feet[other][0], dtype=float)[None, :3], foot[:-1]])
    before_z = np.concatenate([[float(feet[other][1])], fz[:-1]])
    end_xy = 0.5 * (foot[:, :2] + before[:, :2])
    end_z = 0.5 * (fz + before_z)
    m = np.array([max(1, round(dt * SAMPLE_RATE_HZ)) for dt in times], dtype=np.int64)
    first = np.cumsum(m) - m  # each step's first sample after the start
    # each step starts at the last sample of the one before (start + 1.0 * (end - start))
    sx, sy, sz = float(start[0][0]), float(start[0][1]), float(start[1])
    starts = np.empty((k, 3))
    for j in range(k):
        starts[j] = sx, sy, sz
        ex, ey = float(end_xy[j, 0]), float(end_xy[j, 1])
        sx, sy, sz = sx + (ex - sx), sy + (ey - sy), sz + (float(end_z[j]) - sz)
    which = np.repeat(np.arange(k), m)
    mm = m[which]
    u = (np.arange(len(which)) - first[which] + 1) / mm
    ease = u * u * (3 - 2 * u)
    s0 = starts[which]
    xy = s0[:, :2] + u[:, None] * (end_xy[which] - s0[:, :2])
    z = s0[:, 2] + ease * (end_z[which] - s0[:, 2])
    turning = np.arange(k) <= turns
    w, h = np.asarray(was, dtype=float)[which], np.asarray(headings, dtype=float)[which]
    yaws = np.where(turning[which], w + ease * (h - w), yaw)
    n = np.concatenate([[0], np.cumsum(m)])
    steps = [
        PathStep(
            side if j % 2 == 0 else other, int(n[j]), int(n[j + 1]), foot[j].copy(),
            before[j].copy(), foot_z=float(fz[j]) - floor_z, stance_z=float(before_z[j]) - floor_z,
        )
        for j in range(k)
    ]  # fmt: skip
    xy = np.vstack([np.asarray(start[0], dtype=float)[None, :], xy])
    z = np.concatenate([[float(start[1])], z])
    return xy, z, np.concatenate([[float(start[2])], yaws]), steps
