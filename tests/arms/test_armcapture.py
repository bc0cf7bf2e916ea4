"""Reach movements from capture (mjwalk.arms.armcapture): frames, time alignment, mirroring and
body-size scaling on synthetic arms with known answers."""

from __future__ import annotations

import numpy as np
import pytest

from mjwalk.arms.armcapture import (
    ARM_JOINTS,
    HAND_ENDS,
    arm_chain,
    arm_movement,
    arm_movements,
)
from mjwalk.arms.armrep import movement_span, resample_trajectory, segment_directions
from mjwalk.arms.chain import min_jerk
from mjwalk.errors import CaptureError, MjwalkError
from mjwalk.mocap.take import Take

LENGTHS = np.array([0.30, 0.25])


def _raise_chain(lengths=LENGTHS, yaw=0.0, shoulder=(1.0, 2.0, 1.4), hold=(10, 12), T=40):
    """(frames, 3, 3) shoulder, elbow, wrist (world m) of a left arm raised forward from
    hanging to horizontal-and-bent over ``T`` frames (minimum jerk), held still ``hold``
    frames before and after; the body faces ``yaw``. Also the body-frame chain of the movement."""
    tau = min_jerk(np.linspace(0.0, 1.0, T))
    up = 0.5 * np.pi * tau  # upper arm from straight down to forward
    fore = up + 0.6 * tau  # forearm a little further
    u1 = np.stack([np.sin(up), 0.1 * tau, -np.cos(up)], axis=1)
    u2 = np.stack([np.sin(fore), 0.2 * tau, -np.cos(fore)], axis=1)
    u1 /= np.linalg.norm(u1, axis=1, keepdims=True)
    u2 /= np.linalg.norm(u2, axis=1, keepdims=True)
    elbow = lengths[0] * u1
    wrist = elbow + lengths[1] * u2
    body = np.stack([np.zeros_like(elbow), elbow, wrist], axis=1)
    body = np.concatenate([np.repeat(body[:1], hold[0], 0), body, np.repeat(body[-1:], hold[1], 0)])
    c, s = np.cos(yaw), np.sin(yaw)
    rz = np.array([[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]])
    return body @ rz.T + np.asarray(shoulder), body


def _take(chain, yaw=0.0, side="left", name="clip"):
    n = len(chain)
    zeros = np.zeros((n, 3))
    names = ARM_JOINTS["bandai"][side] + (HAND_ENDS["bandai"][side],)[: chain.shape[1] - 3]
    joints = dict(zip(names, np.moveaxis(chain, 1, 0), strict=True))
    return Take(name, 30.0, zeros, np.full(n, yaw), zeros, zeros, zeros, zeros, joints=joints)


HAND = 0.18


def _with_hand(chain, hand=HAND):
    """``chain`` (T, 3, 3) with a hand end (T, 4, 3) continuing the forearm by ``hand`` m."""
    fore = chain[:, 2] - chain[:, 1]
    tip = chain[:, 2] + hand * fore / np.linalg.norm(fore, axis=1, keepdims=True)
    return np.concatenate([chain, tip[:, None]], axis=1)


def test_movement_is_cut_from_rest_to_stop_and_put_in_the_body_frame():
    chain, body = _raise_chain(yaw=0.7)
    c, U, L = arm_movement(chain, 0.7, "left", n=20)
    np.testing.assert_allclose(L, LENGTHS, atol=1e-9)
    # the holds are cut off: the movement runs from rest to the stop (5 % of the peak hand
    # speed) before the highest hand, here within two frames of the raise's ends
    a, b = movement_span(body[:, 2], until=int(np.argmax(body[:, 2, 2])))
    assert abs(a - 10) <= 2 and abs(b - 49) <= 2
    moving = resample_trajectory(body[a : b + 1], 20)
    np.testing.assert_allclose(c, np.r_[moving[0, 1], moving[0, 2], moving[-1, 2]], atol=1e-9)
    np.testing.assert_allclose(U, segment_directions(moving), atol=1e-9)
    np.testing.assert_allclose(np.linalg.norm(U, axis=-1), 1.0, atol=1e-9)


def test_heading_does_not_change_the_movement():
    a = arm_movement(_raise_chain(yaw=0.0)[0], 0.0)
    b = arm_movement(_raise_chain(yaw=2.5, shoulder=(-3.0, 0.5, 1.3))[0], 2.5)
    for x, y in zip(a, b, strict=True):
        np.testing.assert_allclose(x, y, atol=1e-9)


def test_right_arm_is_mirrored_into_the_left_arm_frame():
    chain, _ = _raise_chain(yaw=0.3)
    left = arm_movement(chain, 0.3, "left")
    # the right arm's movement is the left one mirrored through the body's sagittal plane
    shoulder = chain[:, :1]
    c, s = np.cos(0.3), np.sin(0.3)
    lat = np.array([-s, c, 0.0])  # the body's left in the world
    rel = chain - shoulder
    mirrored = rel - 2.0 * (rel @ lat)[..., None] * lat + shoulder
    right = arm_movement(mirrored, 0.3, "right")
    for x, y in zip(left, right, strict=True):
        np.testing.assert_allclose(x, y, atol=1e-9)


def test_a_taller_walker_making_the_same_movement_gives_the_same_training_pair():
    small, _ = _raise_chain(LENGTHS)
    tall, _ = _raise_chain(1.25 * LENGTHS, shoulder=(0.0, 0.0, 1.7))
    mv = arm_movements([_take(small), _take(tall, name="tall")], "left")
    np.testing.assert_allclose(mv.lengths, 1.125 * LENGTHS)  # the clips' mean arm
    np.testing.assert_allclose(mv.scales, [1.125, 1.125 / 1.25])
    np.testing.assert_allclose(mv.constraints[0], mv.constraints[1], atol=1e-9)
    np.testing.assert_allclose(mv.directions[0], mv.directions[1], atol=1e-9)
    # to a given reference arm: the small walker is that size, so unscaled
    ref = arm_movements([_take(small), _take(tall)], "left", lengths=LENGTHS)
    np.testing.assert_allclose(ref.scales, [1.0, 0.8])
    np.testing.assert_allclose(ref.constraints[1], arm_movement(small, 0.0)[0], atol=1e-9)


def test_still_clips_are_left_out_and_groups_follow_the_takes():
    chain, _ = _raise_chain()
    still = np.repeat(chain[:1], 30, axis=0) + 1e-5 * np.random.default_rng(0).normal(
        size=(30, 3, 3)
    )
    mv = arm_movements(
        [_take(chain, name="a"), _take(still, name="b"), _take(chain, name="c")],
        groups=["x", "y", "z"],
    )
    assert mv.names == ["a", "c"] and list(mv.groups) == ["x", "z"] and len(mv) == 2
    empty = arm_movements([_take(still)])
    assert len(empty) == 0 and empty.constraints.shape == (0, 9)


def test_bad_input_is_named():
    chain, _ = _raise_chain()
    take = _take(chain, side="left")
    with pytest.raises(CaptureError, match=r"no joint UpperArm_R, LowerArm_R, Hand_R"):
        arm_chain(take, "right")
    with pytest.raises(MjwalkError, match="unknown skeleton 'vicon'"):
        arm_chain(take, "left", "vicon")
    with pytest.raises(MjwalkError, match="side must be"):
        arm_chain(take, "both")  # type: ignore[arg-type]
    with pytest.raises(MjwalkError, match="2 groups for 1 takes"):
        arm_movements([take], groups=["a", "b"])
    with pytest.raises(MjwalkError, match=r"\(T >= 2, 3, 3\)"):
        arm_movement(chain[:, :2], 0.0)
    bad = chain.copy()
    bad[5, 2, 0] = np.nan
    with pytest.raises(CaptureError, match="NaN"):
        arm_movement(bad, 0.0)
    with pytest.raises(MjwalkError, match="2 positive segment lengths"):
        arm_movements([take], lengths=np.array([0.3, -0.1]))
    with pytest.raises(MjwalkError, match="3 positive segment lengths"):
        arm_movements([_take(_with_hand(chain))], hand=True, lengths=LENGTHS)


def test_with_the_hand_the_constraint_is_the_hand_ends_start_and_end():
    # the endpoint model a cycle drives the humanoid with: three segments, the hand's end
    small, body = _raise_chain(LENGTHS, yaw=0.4)
    tall, _ = _raise_chain(1.25 * LENGTHS, yaw=-1.0, shoulder=(0.0, 0.0, 1.7))
    takes = [_take(_with_hand(small), yaw=0.4), _take(_with_hand(tall, 1.25 * HAND), yaw=-1.0)]
    mv = arm_movements(takes, "left", hand=True, lengths=np.r_[LENGTHS, HAND])
    assert mv.constraints.shape == (2, 6) and mv.directions.shape == (2, 20, 3, 3)
    np.testing.assert_allclose(mv.scales, [1.0, 0.8])
    np.testing.assert_allclose(mv.constraints[0], mv.constraints[1], atol=1e-9)
    # timed on the hand's end: its start and end positions in the body frame
    tip = _with_hand(body)[:, 3]
    a, b = movement_span(tip, until=int(np.argmax(tip[:, 2])))
    moving = resample_trajectory(_with_hand(body)[a : b + 1], 20)
    np.testing.assert_allclose(mv.constraints[0], np.r_[moving[0, 3], moving[-1, 3]], atol=1e-9)
    np.testing.assert_allclose(mv.directions[0], segment_directions(moving), atol=1e-9)
    np.testing.assert_allclose(mv.directions[0][:, 2], mv.directions[0][:, 1], atol=1e-9)
    # a right arm's is mirrored into the left arm's frame like the 3-joint chain
    right = arm_movement(_with_hand(small) * [1.0, -1.0, 1.0], 0.0, "right")
    left = arm_movement(_with_hand(small), 0.0, "left")
    for x, y in zip(left, right, strict=True):
        np.testing.assert_allclose(x, y, atol=1e-9)
    empty = arm_movements([], hand=True)
    assert empty.constraints.shape == (0, 6) and empty.directions.shape == (0, 20, 3, 3)


def test_a_take_without_a_hand_gets_a_neutral_wrist():
    # no hand-end joint, or one on the wrist (the Bandai BVH's zero-offset End Site): the hand
    # continues the forearm, Winter's hand share over the forearm's long
    chain, _ = _raise_chain()
    fore = chain[:, 2] - chain[:, 1]
    expect = chain[:, 2] + 0.108 / 0.146 * fore
    on_wrist = np.concatenate([chain, chain[:, 2:3]], axis=1)
    for take in (_take(chain), _take(on_wrist)):
        got = arm_chain(take, "left", hand=True)
        assert got.shape == (len(chain), 4, 3)
        np.testing.assert_allclose(got[:, 3], expect, atol=1e-12)
    np.testing.assert_allclose(arm_chain(_take(chain), "left", hand=True)[:, :3], chain)
    # a hand the take holds is used as it is
    held = _with_hand(chain)
    np.testing.assert_allclose(arm_chain(_take(held), "left", hand=True), held)


def test_cmu_hands_come_from_the_capture(shared_data):
    """The CMU ASF skeleton has hands (wrist to the end of the fingers bone); the Bandai clips
    do not (a zero-offset End Site): their hand continues the forearm."""
    from mjwalk.mocap.asf import load_amc
    from mjwalk.mocap.bvh import load_bvh

    cmu = load_amc(shared_data / "cmu-35" / "35_01.amc", shared_data / "cmu-35" / "35.asf")
    chain = arm_chain(cmu, "left", "cmu", hand=True)
    np.testing.assert_allclose(chain[:, 3], cmu.joints["lfingers_end"])
    hand = np.linalg.norm(chain[:, 3] - chain[:, 2], axis=1)
    assert 0.10 < np.median(hand) < 0.20  # a real hand, metres
    clip = next((shared_data / "bandai-raise-hand").glob("*raise-up-left-hand*.bvh"))
    bandai = arm_chain(load_bvh(clip), "left", "bandai", hand=True)
    fore = bandai[:, 2] - bandai[:, 1]
    np.testing.assert_allclose(bandai[:, 3], bandai[:, 2] + 0.108 / 0.146 * fore, atol=1e-9)
