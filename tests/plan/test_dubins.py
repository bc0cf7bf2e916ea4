"""Shortest paths of bounded curvature between two poses (mjwalk.plan.dubins)."""

from __future__ import annotations

import math

import numpy as np
import pytest

from mjwalk.plan.dubins import SPACING, WORDS, dubins_paths, dubins_words, word_lengths


def test_every_word_that_exists_ends_at_the_goal_pose():
    """2000 random pose pairs and radii: every word the closed forms give (Shkel & Lumelsky
    2001) traces to the goal point and heading (dubins_paths drops none of them), its points
    at most SPACING apart, and LSL and RSR always exist."""
    rng = np.random.default_rng(0)
    for _ in range(2000):
        s, g = rng.uniform(-3, 3, 2), rng.uniform(-3, 3, 2)
        a, b, r = rng.uniform(-4, 4), rng.uniform(-4, 4), rng.uniform(0.3, 1.5)
        dx, dy = (g - s) / r
        th = math.atan2(dy, dx)
        alpha, beta = (a - th) % math.tau, (b - th) % math.tau
        exist = [word_lengths(k, math.hypot(dx, dy), alpha, beta) for k in range(6)]
        assert exist[0] is not None and exist[1] is not None
        paths = dubins_paths(s, a, g, b, r)
        assert len(paths) == sum(e is not None for e in exist)
        for length, pts, end in paths:
            assert np.hypot(*(pts[-1] - g)) < 1e-6
            assert abs(math.remainder(end - b, math.tau)) < 1e-9
            steps = np.hypot(*np.diff(pts, axis=0).T)
            assert steps.max() <= SPACING + 1e-9
            assert steps.sum() == pytest.approx(length, rel=5e-3)  # chords of the arcs
        assert [p[0] for p in paths] == sorted(p[0] for p in paths)


def test_known_shortest_paths():
    """Along the line: the straight run. A U-turn across twice the radius: a half circle to
    the left (pi r). Each path's turn is no sharper than its radius."""
    straight = dubins_words((0.0, 0.0), 0.0, (3.0, 0.0), 0.0, 0.5)[0]
    assert straight[0] == pytest.approx(3.0) and straight[1] == "LSL"
    r = 0.45
    length, pts, end = dubins_paths((0.0, 0.0), math.pi / 2, (-2 * r, 0.0), -math.pi / 2, r)[0]
    assert length == pytest.approx(math.pi * r)
    assert end == pytest.approx(1.5 * math.pi)  # unwrapped: a left turn of pi
    assert np.hypot(*(pts - (-r, 0.0)).T) == pytest.approx(r)
    assert WORDS == ("LSL", "RSR", "LSR", "RSL", "RLR", "LRL")
