"""ISO 11226:2000 (Ergonomics -- Evaluation of static working postures): trunk inclination and
upper-arm elevation held as static postures, against the standard's acceptable holding times.

Step 1 of the standard: trunk inclination 0-20 deg and upper-arm elevation 0-20 deg are
acceptable; beyond 60 deg (trunk without support, upper arm) not acceptable; in 20-60 deg the
posture is acceptable only as long as the maximum acceptable holding time (step 2, the
standard's Figures 2 and 3: from 4 min at 20 deg to 1 min at 60 deg for the trunk, from 3 min at
20 deg to 1 min at 60 deg for the upper arm, linear in between). Postures held less than 4 s are
not static (the standard's scope). The holding-time curves are transcribed from the figures'
end points, not from the standard's text (not reachable, checked 2026-12-01: only its title
pages are in the reference stores). One independent public implementation found uses the same
end points (trunk 240 s at 20 deg to 60 s at 60 deg, upper arm 180 s to 60 s, linear); the
straight line between the end points is an approximation of the figures' curves, NOT verified.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

#: Static postures are those held at least this long (s) (ISO 11226, scope).
STATIC_S = 4.0
#: (angle deg, maximum acceptable holding time s) at the ends of the 20-60 deg zone.
TRUNK_HOLD = ((20.0, 240.0), (60.0, 60.0))
ARM_HOLD = ((20.0, 180.0), (60.0, 60.0))
ACCEPTABLE_DEG, LIMIT_DEG = 20.0, 60.0


def max_holding_time(angle: float, curve=TRUNK_HOLD) -> float:
    """The maximum acceptable holding time at an angle, linear between the curve's end points.

    Args:
        angle: trunk inclination or upper-arm elevation, degrees.
        curve: ((a0, t0), (a1, t1)): :data:`TRUNK_HOLD` or :data:`ARM_HOLD` (deg, s).

    Returns:
        Seconds: inf below ``a0`` (20 deg), 0 above ``a1`` (60 deg).
    """
    (a0, t0), (a1, t1) = curve
    if angle < a0:
        return float("inf")
    if angle > a1:
        return 0.0
    return float(np.interp(angle, [a0, a1], [t0, t1]))


@dataclass
class Holding:
    """The worst static holding of one body part in a motion: the longest run (s) of frames in
    the 20-60 deg zone or beyond, its peak angle (deg), the acceptable time at that angle (s),
    and ``acceptable``."""

    part: str
    held: float
    angle: float
    limit: float
    acceptable: bool


def _runs(mask: np.ndarray) -> list[tuple[int, int]]:
    """[start, end) runs of True in a boolean array."""
    m = np.concatenate([[False], mask, [False]]).astype(np.int8)
    d = np.diff(m)
    return list(zip(np.flatnonzero(d == 1), np.flatnonzero(d == -1), strict=True))


def holding(angle: np.ndarray, fps: float, part: str, curve) -> Holding:
    """The worst static holding of a body part: every run of at least :data:`STATIC_S` above
    20 deg is held against the holding time at its peak angle; the worst run (highest ratio of
    held to acceptable time) is returned.

    Args:
        angle: (F,) angles, degrees.
        fps: their frame rate, frames/s.
        part: the body part's name (kept in the result).
        curve: the holding-time curve (:data:`TRUNK_HOLD` or :data:`ARM_HOLD`).

    Returns:
        The :class:`Holding` (``held`` 0 and acceptable when no run is static).
    """
    worst = Holding(part, 0.0, 0.0, float("inf"), True)
    worst_ratio = 0.0
    for s, e in _runs(np.asarray(angle) > ACCEPTABLE_DEG):
        held = (e - s) / fps
        if held < STATIC_S:
            continue
        peak = float(np.max(angle[s:e]))
        limit = max_holding_time(peak, curve)
        ratio = held / limit if limit > 0 else float("inf")
        if ratio >= worst_ratio:
            worst_ratio = ratio
            worst = Holding(part, float(held), peak, float(limit), bool(held <= limit))
    return worst
