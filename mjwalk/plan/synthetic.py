"""A synthetic WalkPath made without the planner: alternating footprints along a straight line or
a circular arc, the pelvis between them swaying towards the stance foot.

For tests, benchmarks and training data that need a known, regular walk (the gait-pose model's
training walks, the leg synthesis' checks); world frame, metres, seconds, yaw from +x CCW.
"""

from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike
from scipy.interpolate import PchipInterpolator

from mjwalk.conventions import DEFAULT_STATURE, SAMPLE_RATE_HZ
from mjwalk.errors import MjwalkError
from mjwalk.gait.stairs import StairGeometry, stair_gait
from mjwalk.gait.walker import Walker
from mjwalk.plan.levelcross import flight_setback
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


def synthetic_stair_walk(
    riser: float = 0.17,
    tread: float = 0.28,
    n: int = 6,
    direction: str = "up",
    step_time: float | None = None,
    width: float = 0.18,
    start: ArrayLike = (0.0, 0.0, 0.0),
    stature: float = DEFAULT_STATURE,
) -> WalkPath:
    """A step-over-step walk up or down a straight stair of ``n`` risers, without planning:
    from standing on the floor (up) or the top landing (down) with the stance foot half a tread
    before the first riser, every step lands on the next tread's centre; a last step brings the
    trailing foot beside it on the landing half a tread past the last riser. The feet stand as
    the level planner puts them (:func:`mjwalk.plan.levelcross.flight_setback`: each foot
    centred on its tread, the feet on the level before and after the flight a gap off the riser
    they face). The walk carries its heights
    (``WalkPath.z``, ``PathStep.foot_z``/``stance_z``).

    Args:
        riser: rise per step, metres.
        tread: going per step, metres.
        n: risers (>= 1).
        direction: "up" or "down".
        step_time: seconds per step; default the reference adult's on that stair
            (:func:`mjwalk.gait.stairs.stair_gait`: 0.58 s up, 0.46 s down).
        width: step width, metres.
        start: (x, y, heading): the first riser's edge line crosses the heading ``tread / 2``
            ahead of this point (the centre of the tread the walk starts on), metres, radians.
        stature: the walker's stature, metres (its foot's lengths place the footprints).

    Returns:
        the WalkPath; ``meta["stair"]`` holds riser, tread, n, direction and the first riser's
        distance along the heading from ``start``; ``meta["edges"]`` the risers' edge lines
        (as :meth:`mjwalk.plan.levelroute.Crossing.riser_lines` gives them).
    """
    if n < 1 or direction not in ("up", "down") or riser <= 0 or tread <= 0:
        raise MjwalkError(
            f"synthetic_stair_walk: need n >= 1, direction 'up' or 'down', riser and tread > 0, "
            f"got {n}, {direction!r}, {riser}, {tread}"
        )
    if step_time is None:
        stair = StairGeometry(riser, tread)
        step_time = stair_gait(Walker(), stair, "up" if direction == "up" else "down").step_time
    fps = SAMPLE_RATE_HZ
    x0, y0, h0 = (float(v) for v in np.asarray(start, float))
    fwd, left = np.array([np.cos(h0), np.sin(h0)]), np.array([-np.sin(h0), np.cos(h0)])
    top = n * riser

    def height(s):  # the surface height at distance s along the heading
        k = np.clip(np.floor((np.asarray(s, float) - 0.5 * tread) / tread) + 1, 0, n)
        return k * riser if direction == "up" else top - k * riser

    # footprint k on tread k (0: the start tread); the last one beside footprint n
    s_f = np.r_[np.arange(n + 1) * tread, n * tread]
    sides = ["right"] + ["left" if k % 2 else "right" for k in range(1, n + 2)]
    back = flight_setback(s_f, np.arange(n + 1) * tread, direction == "up", stature)

    def footprint(k):
        lat = (0.5 if sides[k] == "left" else -0.5) * width
        along = s_f[k] - back[k]
        return np.array([*(np.array([x0, y0]) + along * fwd + lat * left), h0])

    n_steps = n + 1
    bounds = np.round(np.arange(n_steps + 1) * step_time * fps).astype(int)
    n_hold = round(0.25 * fps)  # the final pose held a quarter second, as synthetic_walk's
    m = bounds[-1] + n_hold + 1
    t = np.arange(m) / fps
    sp = _pelvis_knots(s_f, back)
    knots_t, knots_s = t[bounds], np.asarray(sp)
    if n_hold:
        knots_t, knots_s = np.r_[knots_t, t[-1]], np.r_[knots_s, knots_s[-1]]
    s_of_t = PchipInterpolator(knots_t, knots_s)(t)
    steps = [
        PathStep(
            side=sides[i + 1],
            start=int(bounds[i]),
            end=int(bounds[i + 1]),
            foot=footprint(i + 1),
            stance=footprint(i),
            foot_z=float(height(s_f[i + 1])),
            stance_z=float(height(s_f[i])),
        )
        for i in range(n_steps)
    ]
    xy = np.array([x0, y0]) + s_of_t[:, None] * fwd
    up = 1.0 if direction == "up" else -1.0  # the axis up the stair
    edges = [
        {"xy": [float(v) for v in np.array([x0, y0]) + (i + 0.5) * tread * fwd],
         "normal": [float(v) for v in up * fwd],
         "low": float(height((i + 1.0 if up < 0 else i) * tread)),
         "high": float(height((i if up < 0 else i + 1.0) * tread)), "half_width": 0.0}
        for i in range(n)
    ]  # fmt: skip
    meta = {
        "planner": "synthetic",
        "stair": {"riser": riser, "tread": tread, "n": n, "direction": direction,
                  "first_riser": 0.5 * tread},
        "edges": edges,
    }  # fmt: skip
    return WalkPath(t=t, xy=xy, yaw=np.full(m, h0), steps=steps, meta=meta, z=height(s_of_t))


def _pelvis_knots(s_f: np.ndarray, back: np.ndarray) -> list[float]:
    """The pelvis's distance along a synthetic stair walk's heading standing before its first
    step, at each later step's start and at its end: midway between the two feet, as
    :func:`synthetic_walk`'s (whose first step is a half step, so its midway is a quarter
    step; here the first step is a whole tread: a quarter tread put the first step off a
    landing 7 cm nearer above its lifting foot than the flight's steps, knee 100.1 against
    95.5-95.7 deg down at 1.75 m).

    Up and down, midway between the footprints (the points under the ankles, set back from
    the treads' centres), as the level planner's walks put it
    (:func:`mjwalk.plan.footfallwalk.footfall_walk`): midway between the treads' centres put
    it the setback (6.65 cm at 1.75 m) ahead of the planner's at every foot contact, up the
    swing thigh less flexed (hip peak 51.8 deg against the planner's 55.2, hip47d), down
    the swing knee less flexed (descent47).

    Args:
        s_f: (k,) the footprints' tread centres along the heading, metres (the last two: the
            last tread's and the foot closing beside it).
        back: (k,) their setbacks, metres (:func:`mjwalk.plan.levelcross.flight_setback`).

    Returns:
        (k,) distances along the heading, metres.
    """
    s_p = s_f - back
    sp = [float(s_p[0])] + [0.5 * (s_p[i - 1] + s_p[i]) for i in range(1, len(s_f) - 1)]
    return [*sp, float(s_p[-1])]


def synthetic_ramp_walk(
    angle: float,
    n_steps: int = 6,
    step_len: float = 0.6,
    step_time: float = 0.55,
    start: ArrayLike = (0.0, 0.0, 0.0),
) -> WalkPath:
    """A straight walk (:func:`synthetic_walk`) on a ramp rising along the heading from the
    start: the ground's height is ``tan(angle)`` times the distance along the heading.

    Args:
        angle: the ramp's slope, radians (+ up along the heading, - down).
        n_steps: steps.
        step_len: distance between successive footprints, metres.
        step_time: seconds per step.
        start: (x, y, heading), metres and radians; the ramp's height is 0 there.

    Returns:
        the WalkPath with its heights.
    """
    walk = synthetic_walk(n_steps=n_steps, step_len=step_len, step_time=step_time, start=start)
    x0, y0, h0 = (float(v) for v in np.asarray(start, float))
    fwd = np.array([np.cos(h0), np.sin(h0)])

    def height(p):
        return np.tan(angle) * ((np.asarray(p, float)[..., :2] - [x0, y0]) @ fwd)

    walk.z = height(walk.xy)
    for s in walk.steps:
        s.foot_z, s.stance_z = float(height(s.foot)), float(height(s.stance))
    walk.meta["ramp"] = {"angle": angle}
    return walk
