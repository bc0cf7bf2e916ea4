"""The foot on the floor (mjwalk.body.legs.footpivot): pivots, spins and heel rise."""

from __future__ import annotations

import numpy as np
import pytest

from mjwalk.body.humanoid import leg_geometry
from mjwalk.body.legs.footpivot import ball_offset, heel_rise, pivot_ankle, sole_profile, spin_print
from mjwalk.conventions import DEFAULT_STATURE


def test_spin_print_keeps_its_pivot():
    """Turned about the ball (default) or the heel, that point of the sole stays put and
    the footprint's heading turns by the spin."""
    g = leg_geometry()
    foot = np.array([0.2, -0.3, 0.5])
    spin = np.array([0.0, 0.3, -0.6])
    for lever in (None, -g.foot_back):
        b = ball_offset(g) if lever is None else lever
        fp = spin_print(foot, spin, g, lever)
        assert np.allclose(fp[:, 2], foot[2] + spin)
        piv = fp[:, :2] + b * np.column_stack([np.cos(fp[:, 2]), np.sin(fp[:, 2])])
        assert np.allclose(piv, piv[0]) and np.allclose(fp[0], foot)


def test_pivot_ankle_keeps_the_pivot_on_the_floor():
    """A flat foot's ankle is at ankle height over the footprint; toes up it turns about the
    heel, heel up about the ball: the pivot stays put and the ankle stays at its distance."""
    g = leg_geometry()
    foot = np.array([0.3, -0.1, 0.4])
    flat = pivot_ankle(foot, np.array([0.0]), g)
    assert np.allclose(flat, [[0.3, -0.1, g.ankle_height]])
    fwd = np.array([np.cos(0.4), np.sin(0.4), 0.0])
    heel = np.array([0.3, -0.1, 0.0]) - g.foot_back * fwd
    ball = np.array([0.3, -0.1, 0.0]) + ball_offset(g) * fwd
    up, down = pivot_ankle(foot, np.array([0.3, -0.5]), g)
    r_heel = np.linalg.norm(flat[0] - heel)
    r_ball = np.linalg.norm(flat[0] - ball)
    assert np.linalg.norm(up - heel) == pytest.approx(r_heel)
    assert np.linalg.norm(down - ball) == pytest.approx(r_ball)
    assert up[2] > g.ankle_height and down[2] > g.ankle_height


def test_heel_rise_only_where_the_leg_cannot_reach():
    """heel_rise leaves the pitch where the hip is within reach of the flat foot's ankle, and
    raises the heel (pitch below 0, not under its bound) for a hip 3 cm out of reach ahead,
    bringing the ankle closer to it."""
    g = leg_geometry()
    foot = np.array([0.0, 0.0, 0.0])
    d = float(g.span(0.1))
    near = np.array([0.0, 0.0, g.ankle_height + 0.9 * d])
    assert heel_rise(foot, near, 0.1, 0.0, g) == pytest.approx(0.0)
    far = np.array([0.5, 0.0, g.ankle_height + np.sqrt((d + 0.03) ** 2 - 0.25)])
    p = heel_rise(foot, far, 0.1, 0.0, g)
    assert -1.0472 - 1e-9 <= p < 0.0
    gap = np.linalg.norm(far - pivot_ankle(foot, np.array([p]), g)[0]) - d
    assert gap < 0.03 - 1e-3


def test_ankle_kept_rows_raises_the_heel_as_far_as_the_shank_leans_on():
    """A flat foot under a hip that moves forward and down: the heel rises (pitch below 0) by
    the shank's further lean (the leg's sagittal triangle, worked out here again), none at the
    first sample, never above ``p0`` nor past ``lo``."""
    from mjwalk.body.legs.footpivot import ankle_kept_rows

    g = leg_geometry()
    L1, L2 = g.thigh, g.shank
    n = 6
    hip = np.column_stack(
        [np.linspace(0.0, 0.12, n), np.zeros(n), np.linspace(0.9, 0.84, n) * (L1 + L2)]
    )
    fwd, down = -hip[:, 0], hip[:, 2] - g.ankle_height  # the flat foot's ankle from the hip
    d = np.hypot(fwd, down)
    knee = np.arccos((d**2 - L1**2 - L2**2) / (2 * L1 * L2))
    lean = np.arctan2(fwd, down) + np.arccos((L1**2 + d**2 - L2**2) / (2 * L1 * d)) - knee
    out = np.empty(n)
    args = (g.thigh, g.shank, ball_offset(g), g.foot_back, g.ankle_height)
    ankle_kept_rows(np.zeros(3), hip, np.zeros(n), *args, -1.0, out)
    assert out[0] == 0.0 and np.all(np.diff(out) < 0)  # the heel rises as the shank leans on
    assert out == pytest.approx(lean - lean[0], abs=1e-9)
    ankle_kept_rows(np.zeros(3), hip, np.zeros(n), *args, -0.01, out)
    assert out.min() >= -0.01 and out[-1] == -0.01


def test_sole_profile_of_a_flat_and_a_pitched_foot():
    """The heel, under the ankle, the ball and the toe tip: flat, the sole's length at the
    ankle height below it; pitched, the same points turned about the ankle; toes turned up
    about the ball lift only the tip."""
    g = leg_geometry(DEFAULT_STATURE)
    fwd, up = sole_profile(np.zeros(1), np.zeros(1), g)
    np.testing.assert_allclose(fwd[0], [-g.foot_back, 0.0, ball_offset(g), g.foot_front])
    np.testing.assert_allclose(up[0], -g.ankle_height)
    p = -0.4
    f2, u2 = sole_profile(np.array([p]), np.zeros(1), g)
    turn = np.array([[np.cos(p), -np.sin(p)], [np.sin(p), np.cos(p)]])
    np.testing.assert_allclose(np.stack([f2[0], u2[0]]), turn @ np.stack([fwd[0], up[0]]))
    f3, u3 = sole_profile(np.array([p]), np.array([0.3]), g)
    np.testing.assert_allclose(f3[0, :3], f2[0, :3])
    assert u3[0, 3] > u2[0, 3]
