"""How speed varies along a walk: slower in curves, speeding up from and slowing down to a stand.

Two measures of a horizontal pelvis path (n, 2) in metres sampled at ``fps`` Hz, used to compare
planned walks with captured ones (``benchmarks/bench_pace.py``, tests of the planner):

- :func:`curve_speed_ratio`: the speed where the walk turns over the speed where it runs
  straight. People slow down in curves (Vieilledent et al. 2001, Hicheur et al. 2005: the
  speed of walking falls with the path's curvature; their laws' figures were not checked here,
  so the reference is again the capture: 0.91 of the straight speed in a 90 deg turn).
- :func:`start_stop_distances`: the distance from setting off to reaching 90 % of the walk's
  steady speed, and from last being at 90 % of it to standing. Studies of gait initiation put
  the transition to steady gait between the end of the first step (Lepers et al. 1995, as a
  review of gait initiation cites it) and about three steps (Mann, Hagy, White & Liddell, "The
  initiation of gait", J Bone Joint Surg Am 61:232-239, 1979: "approximately three steps");
  those figures were not checked against the papers here, so the capture mjwalk has is the
  reference the planner is checked against (``benchmarks/bench_pace.py``: 0.62 m, about one
  step, to speed up; 0.25 m to stop).

Both average the speed over a window first: the pelvis speeds up and slows down within every
step, and the within-step swing is no change of pace.
"""

from __future__ import annotations

import numpy as np
from scipy.ndimage import uniform_filter1d

__all__ = ["MOVING_SPEED", "STEP_WINDOW", "curve_speed_ratio", "start_stop_distances"]

#: Speed (m/s) above which the pelvis counts as moving (standing sway is far slower).
MOVING_SPEED = 0.1
#: Averaging window (s) of :func:`start_stop_distances`: one step at 113 steps/min (the
#: reference cadence of :mod:`mjwalk.gait.walker`), which removes the within-step speed swing.
STEP_WINDOW = 60.0 / 113.0


def curve_speed_ratio(xy: np.ndarray, fps: float) -> float:
    """Speed ratio of curved to straight walking.

    Median speed where the stride-averaged (1 s) direction of travel turns faster than
    30 deg/s over the median where it turns slower than 5 deg/s, among samples at >= 60 % of
    the walk's 95th-percentile stride-averaged speed (steady walking, not setting off or
    stopping).

    Args:
        xy: (n, 2) horizontal pelvis path, metres.
        fps: sampling rate, Hz.

    Returns:
        The ratio; nan when either set has fewer than 5 samples.
    """
    n = max(1, round(fps))
    s = uniform_filter1d(np.asarray(xy, dtype=float), n, axis=0, mode="nearest")
    v = np.gradient(s, axis=0) * fps
    speed = np.hypot(*v.T)
    turn = np.abs(uniform_filter1d(np.gradient(np.unwrap(np.arctan2(v[:, 1], v[:, 0]))) * fps, n))
    steady = speed >= 0.6 * np.percentile(speed, 95)
    curve, straight = steady & (turn > np.radians(30)), steady & (turn < np.radians(5))
    if curve.sum() < 5 or straight.sum() < 5:
        return float("nan")
    return float(np.median(speed[curve]) / np.median(speed[straight]))


def start_stop_distances(xy: np.ndarray, fps: float, window: float = STEP_WINDOW):
    """Speed-up and slow-down distances of a walk from standing to standing.

    Metres walked from the first sample moving faster than :data:`MOVING_SPEED` to the first
    at 90 % of the steady speed (the median over the middle third of the moving samples), and
    from the last at 90 % of it to the last moving sample, speed averaged over ``window``.

    Args:
        xy: (n, 2) horizontal pelvis path, metres.
        fps: sampling rate, Hz.
        window: averaging window, seconds.

    Returns:
        (speed-up distance m, slow-down distance m, steady speed m/s); None when the walk
        moves for less than two seconds.
    """
    n = max(1, round(fps * window))
    s = uniform_filter1d(np.asarray(xy, dtype=float), n, axis=0, mode="nearest")
    v = np.hypot(*np.gradient(s, axis=0).T) * fps
    moving = np.flatnonzero(v > MOVING_SPEED)
    if len(moving) < 2 * fps:
        return None
    a, b = int(moving[0]), int(moving[-1])
    third = (b - a) // 3
    steady = float(np.median(v[a + third : b - third + 1]))
    up = a + int(np.argmax(v[a:] >= 0.9 * steady))
    down = b - int(np.argmax(v[b::-1] >= 0.9 * steady))
    walked = np.concatenate([[0.0], np.cumsum(np.hypot(*np.diff(s, axis=0).T))])
    return float(walked[up] - walked[a]), float(walked[b] - walked[down]), steady
