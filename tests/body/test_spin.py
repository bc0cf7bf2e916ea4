"""Spin turns of grounded feet (mjwalk.body.legs.spin)."""

from __future__ import annotations

import numpy as np

from mjwalk.body.humanoid import leg_geometry, pelvis_height
from mjwalk.body.legs.footpivot import ball_offset, pivot_ankle
from mjwalk.body.legs.spin import SPIN_HEEL, spin_turns
from mjwalk.body.legs.steps import FootTracks


def _tracks(n, prints, ground_l):
    g = leg_geometry(1.75)
    left = [pivot_ankle(prints, np.zeros(n), g), np.zeros(n), np.zeros(n), np.zeros(n),
            ground_l, prints.copy()]  # fmt: skip
    right = [np.zeros((n, 3)), np.zeros(n), np.zeros(n), np.zeros(n), np.zeros(n, bool),
             np.zeros((n, 3))]  # fmt: skip
    return FootTracks(*({"l": a, "r": b} for a, b in zip(left, right, strict=True)))


def test_a_planted_foot_spins_about_its_ball_as_the_pelvis_turns():
    """The pelvis turns 69 deg in place over a flat left foot: the hip cannot rotate that far,
    so the foot turns (by 26 deg) about its ball, which stays put, its heel raised by
    SPIN_HEEL; the statistics count one turned contact."""
    g = leg_geometry(1.75)
    n = 60
    yaw = np.linspace(0, 1.2, n)
    root = np.column_stack([np.zeros(n), np.zeros(n), np.full(n, pelvis_height(1.75) - 0.03)])
    prints = np.tile([0.0, g.hip_y, 0.0], (n, 1))
    feet = _tracks(n, prints, np.ones(n, bool))
    stats = spin_turns(feet, root, yaw, g)
    assert stats["r"] == (0.0, 0)
    worst, count = stats["l"]
    assert count == 1 and 0.3 < worst < 0.6
    fp = feet.prints["l"]
    ball = fp[:, :2] + ball_offset(g) * np.column_stack([np.cos(fp[:, 2]), np.sin(fp[:, 2])])
    assert np.allclose(ball, ball[0], atol=1e-9)
    assert feet.fyaw["l"][-1] == worst
    assert feet.pitch["l"].min() == -np.deg2rad(SPIN_HEEL)
    assert np.allclose(feet.ankle["l"], pivot_ankle(fp, feet.pitch["l"], g))


def test_feet_in_the_air_do_not_spin():
    g = leg_geometry(1.75)
    n = 30
    yaw = np.linspace(0, 1.2, n)
    root = np.column_stack([np.zeros(n), np.zeros(n), np.full(n, 0.9)])
    prints = np.tile([0.0, g.hip_y, 0.0], (n, 1))
    feet = _tracks(n, prints, np.zeros(n, bool))
    ankle = feet.ankle["l"].copy()
    assert spin_turns(feet, root, yaw, g) == {"l": (0.0, 0), "r": (0.0, 0)}
    assert np.array_equal(feet.ankle["l"], ankle)
