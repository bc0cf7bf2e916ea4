"""The planner's stance-lean check (mjwalk.plan.lean, used by mjwalk.plan.stepcheck): the stance
leg must follow the pelvis within the ankle's eversion/inversion and the hip's
adduction/abduction ranges."""

from __future__ import annotations

import math

import numpy as np

from mjwalk.body.humanoid import leg_geometry
from mjwalk.plan import lean, stepcheck
from mjwalk.plan.options import lean_params

M = 16
#: A step frame heading +y (world): the step's local frame (x right, y forward) is the world's.
FRAME = math.pi / 2


def _par() -> np.ndarray:
    """The planner's own stance-lean slots (1.75 m humanoid, ROM_DEG limits)."""
    return stepcheck.params(**lean_params())


def _compiled(pelvis, yaw, stance, stance_left, par) -> bool:
    """stance_lean_ok on pelvis samples (M, 2) and yaws (M,) (world = step frame, see FRAME)
    through a hand-made decoder: no features, the pelvis yaws in its offset."""
    offset = np.zeros(2 * M + 2, complex)
    offset[M + 2 :] = np.asarray(yaw) - FRAME
    loc = np.zeros(M + 2, complex)
    loc[:M] = pelvis[:, 0] + 1j * pelvis[:, 1]
    return lean.stance_lean_ok(
        np.zeros((1, 1)), 0, np.zeros((1, 2 * M + 2), complex), offset, loc, M,
        complex(stance[0], stance[1]), stance[2] - FRAME, stance_left, par,
    )  # fmt: skip


def _straight(stance_x: float):
    """A straight step heading +y (pelvis 0 -> 0.6 m, yaw along), the right foot standing
    ``stance_x`` m to the right of the pelvis line at y = 0.3, pointing ahead."""
    pelvis = np.column_stack([np.zeros(M), np.linspace(0.0, 0.6, M)])
    return pelvis, np.full(M, FRAME), np.array([stance_x, 0.3, FRAME])


def test_lean_is_the_ankle_inversion_of_the_leg_ik():
    """With the sole level sideways and the hip as high as the straight leg reaches, the check's
    ankle lean is the leg IK's ankle inversion (mjwalk.body.legs.leg_ik, unclipped)."""
    from mjwalk.body.legs import leg_ik

    g, par = leg_geometry(), _par()
    for x in (-0.3, -0.1, 0.0, 0.1, 0.35):
        pelvis, yaw, stance = _straight(x)
        inv, _ = lean.stance_lean(pelvis, yaw, stance, False, par)
        hip = pelvis + [g.hip_y, 0.0]  # the right hip, heading +y
        d = stance[:2] - hip
        h = np.sqrt((g.thigh + g.shank - 1e-9) ** 2 - (d**2).sum(1))
        rel = np.column_stack([d[:, 1], -d[:, 0], -h])  # pelvis frame: x forward, y left
        ik = leg_ik(rel, np.zeros(M), np.zeros(M), "right", g, clip=False)
        np.testing.assert_allclose(inv, ik["ankle_r_inv"], atol=2e-3)


def test_hand_made_placements_beyond_the_lean_range_are_refused():
    """A right stance foot 0.1 m right of the pelvis line (about under its hip) is accepted; one
    crossed 0.25 m to the left (the hip 0.34 m lateral of it: eversion 23-25 deg, range 15) and
    one 0.6 m out to the right (inversion 37-40 deg, range 35) are refused; a foot turned 60 deg
    off the walking direction beside the hip (as at a corridor corner) everts the ankle as
    well. The compiled check and its NumPy form agree."""
    par = _par()
    cases = {0.1: True, 0.0: True, -0.25: False, 0.6: False}
    for x, ok in cases.items():
        pelvis, yaw, stance = _straight(x)
        inv, abd = lean.stance_lean(pelvis, yaw, stance, False, par)
        assert lean.lean_in_range(inv, abd, par) is ok, (x, np.degrees(inv).round(1))
        assert _compiled(pelvis, yaw, stance, False, par) is ok, x
    pelvis, yaw, stance = _straight(0.15)
    stance[2] += math.radians(60)  # turned left: the hip now lies lateral of the foot's axis
    assert not lean.lean_in_range(*lean.stance_lean(pelvis, yaw, stance, False, par), par)
    assert not _compiled(pelvis, yaw, stance, False, par)
    # mirrored: a left stance foot
    pelvis, yaw, stance = _straight(-0.1)
    assert _compiled(pelvis, yaw, stance, True, par)
    pelvis, yaw, stance = _straight(0.25)
    assert not _compiled(pelvis, yaw, stance, True, par)


def test_compiled_lean_check_agrees_with_numpy():
    """On 2000 random placements and curved, turning pelvis paths both forms give the same
    verdict (the rare placements within 1e-9 rad of a limit excepted)."""
    rng = np.random.default_rng(0)
    par = _par()
    t = np.linspace(0.0, 1.0, M)
    refused = 0
    for _ in range(2000):
        turn = rng.uniform(-0.8, 0.8)
        yaw = FRAME + turn * t
        pelvis = np.column_stack([rng.uniform(-0.1, 0.1) * t**2, rng.uniform(0.3, 0.8) * t])
        stance = np.array([rng.uniform(-0.4, 0.4), rng.uniform(-0.2, 0.6), FRAME])
        stance[2] += rng.uniform(-1.2, 1.2)
        left = bool(rng.integers(2))
        want = lean.lean_in_range(*lean.stance_lean(pelvis, yaw, stance, left, par), par)
        assert _compiled(pelvis, yaw, stance, left, par) is want
        refused += not want
    assert 300 < refused < 1700  # both verdicts well represented
