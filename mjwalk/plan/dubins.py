"""Shortest paths of bounded curvature between two poses (Dubins 1957).

Dubins ("On curves of minimal length with a constraint on average curvature, and with
prescribed initial and terminal positions and tangents", Am J Math 79:497-516, 1957) showed
that the shortest path of curvature at most 1/r from a pose to a pose is one of six words of
arcs (L, R: turning left or right at radius r) and straight runs (S): LSL, RSR, LSR, RSL, RLR,
LRL. :func:`word_lengths` gives a word's three segments in closed form (Shkel & Lumelsky 2001,
"Classification of the Dubins set", Robot Auton Syst 34:179-202; the formulas as LaValle 2006,
"Planning Algorithms" §15.3.1, gives them, quoted from memory: :func:`dubins_paths` traces each
word and keeps only those that end at the goal pose); :func:`dubins_paths` gives the words that
join two poses as sampled paths, shortest first. :mod:`mjwalk.plan.turnin` walks them into a
flight. Metres, radians (world frame, yaw from +x CCW).
"""

from __future__ import annotations

import math

import numpy as np

#: The six words (Dubins 1957), in :func:`word_lengths`' numbering.
WORDS = ("LSL", "RSR", "LSR", "RSL", "RLR", "LRL")
#: Spacing (m) of the points a path is sampled at, at most (as
#: :func:`mjwalk.plan.guide.guide_is_clear` checks a path: 5 cm).
SPACING = 0.05
#: How far (m, rad) a traced word's end may miss the goal pose (rounding only).
END_TOLERANCE = (1e-3, 1e-6)


def _mod(a: float) -> float:
    return a % (2.0 * math.pi)


def word_lengths(word: int, d: float, alpha: float, beta: float) -> tuple[float, ...] | None:
    """The segments of Dubins word ``word`` from heading ``alpha`` at the origin to heading
    ``beta`` at (d, 0), all in turning radii (a turn's in radians).

    Args:
        word: 0-5, the word's index in :data:`WORDS`.
        d: the distance between the two points, in turning radii.
        alpha: the start heading against the line between them, radians.
        beta: the end heading against that line, radians.

    Returns:
        (t, p, q), or None where the word does not join the two poses.
    """
    sa, ca, sb, cb = math.sin(alpha), math.cos(alpha), math.sin(beta), math.cos(beta)
    cab = math.cos(alpha - beta)
    if word in (0, 1):  # LSL, RSR
        sign = 1.0 if word == 0 else -1.0
        tmp = 2.0 + d * d - 2.0 * cab + 2.0 * sign * d * (sa - sb)
        if tmp < 0.0:
            return None
        if word == 0:
            th = math.atan2(cb - ca, d + sa - sb)
            return _mod(th - alpha), math.sqrt(tmp), _mod(beta - th)
        th = math.atan2(ca - cb, d - sa + sb)
        return _mod(alpha - th), math.sqrt(tmp), _mod(th - beta)
    if word == 2:  # LSR
        tmp = -2.0 + d * d + 2.0 * cab + 2.0 * d * (sa + sb)
        if tmp < 0.0:
            return None
        p = math.sqrt(tmp)
        th = math.atan2(-ca - cb, d + sa + sb) - math.atan2(-2.0, p)
        return _mod(th - alpha), p, _mod(th - beta)
    if word == 3:  # RSL
        tmp = d * d - 2.0 + 2.0 * cab - 2.0 * d * (sa + sb)
        if tmp < 0.0:
            return None
        p = math.sqrt(tmp)
        th = math.atan2(ca + cb, d - sa - sb) - math.atan2(2.0, p)
        return _mod(alpha - th), p, _mod(beta - th)
    sign = 1.0 if word == 4 else -1.0  # RLR, LRL
    tmp = (6.0 - d * d + 2.0 * cab + 2.0 * sign * d * (sa - sb)) / 8.0
    if abs(tmp) > 1.0:
        return None
    p = _mod(2.0 * math.pi - math.acos(tmp))
    if word == 4:
        t = _mod(alpha - math.atan2(ca - cb, d - sa + sb) + p / 2.0)
        return t, p, _mod(alpha - beta - t + p)
    t = _mod(-alpha - math.atan2(ca - cb, d + sa - sb) + p / 2.0)
    return t, p, _mod(beta - alpha - t + p)


def _trace(start: np.ndarray, yaw: float, word: str, lengths, radius: float) -> tuple:
    """The points (m, every :data:`SPACING` or closer, the start and end included) and the
    end heading (radians, unwrapped from ``yaw``) of a word from ``start`` heading ``yaw``."""
    pts = [np.asarray(start, dtype=float)[None, :]]
    x, y = float(start[0]), float(start[1])
    for kind, seg in zip(word, lengths, strict=True):
        u = np.arange(1, max(1, math.ceil(seg * radius / SPACING)) + 1)
        u = u / u[-1] * seg
        if kind == "S":
            xs, ys = x + radius * u * math.cos(yaw), y + radius * u * math.sin(yaw)
        else:
            sign = 1.0 if kind == "L" else -1.0
            cx, cy = x - sign * radius * math.sin(yaw), y + sign * radius * math.cos(yaw)
            xs = cx + sign * radius * np.sin(yaw + sign * u)
            ys = cy - sign * radius * np.cos(yaw + sign * u)
            yaw += sign * seg
        pts.append(np.stack([xs, ys], axis=1))
        x, y = float(xs[-1]), float(ys[-1])
    return np.vstack(pts), yaw


def dubins_words(start, yaw0: float, goal, yaw1: float, radius: float) -> list[tuple]:
    """The Dubins words that join a pose to a pose, shortest first, untraced.

    Args:
        start: (2,) world xy, metres.
        yaw0: the heading there, radians.
        goal: (2,) world xy, metres.
        yaw1: the heading to arrive along, radians.
        radius: the turning radius, metres (> 0).

    Returns:
        [(length in metres, word, (t, p, q) its segments in turning radii)], shortest first.
    """
    s, g = np.asarray(start, dtype=float), np.asarray(goal, dtype=float)
    dx, dy = (g - s) / radius
    theta = math.atan2(dy, dx)
    d, alpha, beta = math.hypot(dx, dy), _mod(yaw0 - theta), _mod(yaw1 - theta)
    out = []
    for k, word in enumerate(WORDS):
        seg = word_lengths(k, d, alpha, beta)
        if seg is not None:
            out.append((radius * sum(seg), word, seg))
    return sorted(out, key=lambda c: c[0])


def trace(start, yaw0: float, goal, yaw1: float, radius: float, word: tuple) -> tuple | None:
    """A word of :func:`dubins_words` as a sampled path.

    Args:
        start: (2,) world xy, metres.
        yaw0: the heading there, radians.
        goal: (2,) world xy, metres.
        yaw1: the heading to arrive along, radians.
        radius: the turning radius, metres (> 0).
        word: (length, word, segments), as :func:`dubins_words` gives it.

    Returns:
        ((k, 2) points every :data:`SPACING` or closer from ``start`` to ``goal``, metres; the
        end heading unwrapped from ``yaw0``), or None where the traced end misses the goal
        pose by more than :data:`END_TOLERANCE` (a guard on the closed forms).
    """
    pts, end = _trace(np.asarray(start, dtype=float), yaw0, word[1], word[2], radius)
    miss = abs(math.remainder(end - yaw1, 2.0 * math.pi))
    if float(np.hypot(*(pts[-1] - np.asarray(goal)))) > END_TOLERANCE[0] or miss > END_TOLERANCE[1]:
        return None
    return pts, end


def dubins_paths(start, yaw0: float, goal, yaw1: float, radius: float) -> list[tuple]:
    """The Dubins paths from a pose to a pose that exist, shortest first (:func:`dubins_words`,
    each traced, :func:`trace`).

    Args:
        start: (2,) world xy, metres.
        yaw0: the heading there, radians.
        goal: (2,) world xy, metres.
        yaw1: the heading to arrive along, radians.
        radius: the turning radius, metres (> 0).

    Returns:
        [(length in metres, (k, 2) points every :data:`SPACING` or closer from ``start`` to
        ``goal``, the end heading unwrapped from ``yaw0``)], shortest first.
    """
    out = []
    for word in dubins_words(start, yaw0, goal, yaw1, radius):
        traced = trace(start, yaw0, goal, yaw1, radius, word)
        if traced is not None:
            out.append((word[0], *traced))
    return out
