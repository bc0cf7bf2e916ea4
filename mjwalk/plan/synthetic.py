"""A synthetic WalkPath made without the planner: alternating footprints along a straight line or
a circular arc, the pelvis between them swaying towards the stance foot.

For tests, benchmarks and training data that need a known, regular walk (the gait-pose model's
training walks, the leg synthesis' checks); world frame, metres, seconds, yaw from +x CCW.
"""

from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike
from scipy.interpolate import PchipInterpolator

from mjwalk.conventions import SAMPLE_RATE_HZ
from mjwalk.errors import MjwalkError
from mjwalk.plan.walkpath import PathStep, WalkPath


def synthetic_walk(
    n_steps: int = 8,
    step_len: float = 0.65,
    width: float = 0.18,
    step_time: float = 0.55,
    sway: float = 0.03,
    radius: float | None = None,
    start: ArrayLike = (0.0, 0.0, 0.0),
    hold: float = 0.25,
) -> WalkPath:
    """A walk of ``n_steps`` steps from standing, without planning, sampled as planned walks are
    (:data:`~mjwalk.conventions.SAMPLE_RATE_HZ`).

    Args:
        n_steps: steps after the standing start (>= 1); the first is a half step.
        step_len: distance between successive footprints along the line or arc, metres.
        width: step width (distance of the footprints across the line), metres.
        step_time: duration of a step, seconds.
        sway: sideways pelvis excursion towards the stance foot, metres (half a sine per step).
        radius: None for a straight walk, else the radius (m) of a left arc (negative: right).
        start: (x, y, heading) of the start: metres, radians from +x.
        hold: seconds the final pose is held after the last step (0: the walk ends with it).

    Returns:
        the WalkPath: the first stance foot is the right one; ``meta["planner"]`` is
        ``"synthetic"``.
    """
    fps = SAMPLE_RATE_HZ
    if n_steps < 1 or step_time <= 0 or hold < 0:
        raise MjwalkError(
            f"synthetic_walk: need n_steps >= 1, step_time > 0 and hold >= 0, got "
            f"{n_steps}, {step_time}, {hold}"
        )
    x0, y0, h0 = (float(v) for v in np.asarray(start, float))

    def centre(s):
        s = np.asarray(s, float)
        if radius is None:
            p = np.stack([s, np.zeros_like(s)], -1)
            h = np.zeros_like(s)
        else:
            p = radius * np.stack([np.sin(s / radius), 1 - np.cos(s / radius)], -1)
            h = s / radius
        c, si = np.cos(h0), np.sin(h0)
        p = p @ np.array([[c, si], [-si, c]]) + [x0, y0]
        return p, h + h0

    # footprint arc positions: f0 = 0 (right, initial stance), f_k = (k - 0.5) L
    f = np.array([0.0] + [(k - 0.5) * step_len for k in range(1, n_steps + 1)])
    sides = ["right"] + ["left" if k % 2 else "right" for k in range(1, n_steps + 1)]

    def footprint(k):
        p, h = centre(f[k])
        lat = (0.5 if sides[k] == "left" else -0.5) * width
        n = np.array([-np.sin(h), np.cos(h)])
        return np.array([*(p + lat * n), h])

    bounds = np.round(np.arange(n_steps + 1) * step_time * fps).astype(int)
    n_hold = round(hold * fps)
    n = bounds[-1] + n_hold + 1
    t = np.arange(n) / fps
    # pelvis arc length at step starts: midway between the two feet (a quarter step at first)
    sp = [0.0] + [
        0.5 * (f[i - 1] + f[i]) if i > 1 else 0.25 * step_len for i in range(1, n_steps + 1)
    ]
    if n_hold:
        knots_t, knots_s = np.r_[t[bounds], t[-1]], np.r_[sp, sp[-1]]
    else:
        knots_t, knots_s = t[bounds], np.asarray(sp)
    s_of_t = PchipInterpolator(knots_t, knots_s)(t)
    p, h = centre(s_of_t)
    lat = np.zeros(n)
    steps = []
    for i in range(n_steps):
        a, b = bounds[i], bounds[i + 1]
        phi = (np.arange(a, b + 1) - a) / (b - a)
        stance_left = sides[i] == "left"
        lat[a : b + 1] = sway * (1 if stance_left else -1) * np.sin(np.pi * phi)
        steps.append(
            PathStep(
                side=sides[i + 1],
                start=int(a),
                end=int(b),
                foot=footprint(i + 1),
                stance=footprint(i),
            )
        )
    xy = p + lat[:, None] * np.stack([-np.sin(h), np.cos(h)], -1)
    return WalkPath(t=t, xy=xy, yaw=h, steps=steps, meta={"planner": "synthetic"})
