"""Spin turns of grounded feet (mjwalk.body.legs.spin)."""

from __future__ import annotations

import numpy as np

from mjwalk.body.humanoid import leg_geometry, pelvis_height
from mjwalk.body.legs.footpivot import ball_offset, pivot_ankle, spin_print
from mjwalk.body.legs.ik import ik_lengths, leg_ik_world
from mjwalk.body.legs.spin import SPIN_HEEL, SPIN_ROUNDS, _spin_rounds, spin_turns
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


def _reference_rounds(spin, foot, k_h, p, need, target, root, yaw, side, g):
    """The NumPy rounds ``spin._turn_contact`` ran before they were compiled (kept verbatim
    as the bit-for-bit reference of :func:`~mjwalk.body.legs.spin._spin_rounds`)."""
    sgn = 1.0 if side == "l" else -1.0
    heel_ph = np.arange(len(spin)) < k_h

    def prints(spin):
        ball, back = ball_offset(g), -g.foot_back
        fp = np.empty((len(spin), 3))
        fp[heel_ph] = spin_print(foot, spin[heel_ph], g, back)
        base = fp[k_h - 1] if k_h else foot
        rest = spin[~heel_ph] - (spin[k_h - 1] if k_h else 0.0)
        fp[~heel_ph] = spin_print(base, rest, g, ball)
        return fp

    for _ in range(SPIN_ROUNDS):
        fp = prints(spin)
        rot = leg_ik_world(pivot_ankle(fp, p, g), fp[:, 2], p, root, yaw, side, g)
        err = rot[f"hip_{side}_rot"] - target
        spin = spin + np.where(need, sgn * err, 0.0)
        spin = np.where(need, spin, 0.0)
    fp = prints(spin)
    return fp, pivot_ankle(fp, p, g)


def test_compiled_spin_rounds_are_the_numpy_rounds_bit_for_bit():
    """``_spin_rounds`` gives the footprints and ankles of the NumPy rounds it replaces, to
    the bit, with and without a heel phase, on seeded random contacts of both legs."""
    g = leg_geometry(1.75)
    rng = np.random.default_rng(7)
    for case in range(60):
        m = int(rng.integers(5, 90))
        side = "lr"[case % 2]
        k_h = [0, int(rng.integers(1, m)), m][case % 3]
        foot = np.array([rng.uniform(-3, 3), rng.uniform(-3, 3), rng.uniform(-np.pi, np.pi)])
        p = rng.uniform(-0.3, 0.3, m)
        need = rng.random(m) < 0.7
        target = rng.uniform(-0.8, 0.8, m)
        yaw = foot[2] + rng.uniform(-1.2, 1.2, m)
        root = np.column_stack([foot[0] + rng.uniform(-0.2, 0.2, (m, 2)), np.full(m, 0.9)])
        fp, a_ = np.empty((m, 3)), np.empty((m, 3))
        sgn = 1.0 if side == "l" else -1.0
        sole = (ball_offset(g), float(g.foot_back), float(g.ankle_height))
        _spin_rounds(np.zeros(m), foot, k_h, p, need, target, root, yaw, sgn, float(g.hip_y),
                     ik_lengths(g), sole, SPIN_ROUNDS, fp, a_)  # fmt: skip
        fp0, a0 = _reference_rounds(np.zeros(m), foot, k_h, p, need, target, root, yaw, side, g)
        assert fp.tobytes() == fp0.tobytes() and a_.tobytes() == a0.tobytes(), case
