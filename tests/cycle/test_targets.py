"""mjwalk.cycle.targets: where the hand aims on a site, the pre-grasp approach to it, and the
headroom that limits the approach's rise under a shelf."""

from __future__ import annotations

import math

import mujoco
import numpy as np
import pytest

from mjwalk.arms.chain import arm_segment_lengths
from mjwalk.cycle.targets import (
    APPROACH_BACK,
    APPROACH_UP,
    EDGE_CLEARANCE,
    FASTEN_STANDOFF,
    PICK_CLEARANCE,
    approach_back_dir,
    approach_offset,
    approach_rise,
    board_run,
    edge_back,
    headroom,
    reach_target,
)

SITE = np.array([1.0, 0.0, 1.0])


def _shelf(z: float) -> mujoco.MjModel:
    """A board 2 cm thick whose underside is ``z`` metres up, over the origin."""
    return mujoco.MjModel.from_xml_string(
        f'<mujoco><worldbody><geom type="box" size="0.5 0.5 0.01" pos="0 0 {z + 0.01}"/>'
        "</worldbody></mujoco>"
    )


def test_a_pick_aims_above_the_site_and_a_fasten_in_front_of_it():
    np.testing.assert_allclose(reach_target("pick", SITE, 0.0, 0.0), SITE + [0, 0, PICK_CLEARANCE])
    np.testing.assert_allclose(
        reach_target("fasten", SITE, 0.0, 0.0), SITE - [FASTEN_STANDOFF, 0.0, 0.0]
    )


def test_the_approach_comes_back_towards_the_operator_and_up_for_shelf_work():
    np.testing.assert_allclose(
        approach_offset("pick", SITE, 0.0, 0.0), [-APPROACH_BACK, 0.0, APPROACH_UP]
    )
    # along the stand site's facing (out of the shelf's opening), not towards the operator
    np.testing.assert_allclose(
        approach_offset("pick", SITE, 0.0, 1.0, facing=0.0, rise=0.04),
        [-APPROACH_BACK, 0.0, 0.04],
        atol=1e-12,
    )
    # a fasten comes in level, towards the operator, whatever the facing
    off = approach_offset("fasten", SITE, 1.0, 1.0, facing=math.pi)
    np.testing.assert_allclose(off, [0.0, APPROACH_BACK, 0.0], atol=1e-12)


def test_headroom_and_the_approachs_rise_under_a_shelf():
    hand = float(arm_segment_lengths(1.75)[2])
    high, low = _shelf(0.9), _shelf(hand + 0.03)
    point = np.zeros(3)
    assert headroom(high, mujoco.MjData(high), point) == pytest.approx(0.9, abs=1e-6)
    assert headroom(high, mujoco.MjData(high), np.array([2.0, 0.0, 0.0])) == math.inf
    assert approach_rise(high, mujoco.MjData(high), 1.75, point) == APPROACH_UP
    assert approach_rise(low, mujoco.MjData(low), 1.75, point) == pytest.approx(0.03, abs=1e-6)


def test_the_board_under_a_target_runs_to_its_front_edge():
    """A board 0.5 m deep whose front edge is at x = 0.25 and a lower board under it: a target
    0.2 m behind the front edge finds the edge 0.2 m (to within a step, never short) towards
    the operator; the pre-grasp point out of it lies a hand's length and 1 cm beyond."""
    m = mujoco.MjModel.from_xml_string(
        '<mujoco><worldbody><geom type="box" size="0.25 0.4 0.01" pos="0 0 1.0"/>'
        '<geom type="box" size="0.25 0.4 0.01" pos="0 0 0.4"/>'
        '<geom type="box" size="0.2 0.2 0.2" pos="0 0 2.5" contype="0" conaffinity="0"/>'
        "</worldbody></mujoco>"
    )
    d = mujoco.MjData(m)
    target = np.array([0.05, 0.0, 1.07])
    run = board_run(m, d, target, np.array([1.0, 0.0]))
    assert 0.2 <= run <= 0.2 + 0.01 + 1e-9
    assert board_run(m, d, target, np.array([-1.0, 0.0])) == pytest.approx(0.3, abs=0.011)
    assert board_run(m, d, np.array([1.0, 0.0, 1.07]), np.array([1.0, 0.0])) == 0.0  # nothing
    hand = arm_segment_lengths(1.6)[2]
    assert edge_back(run, 1.6) == pytest.approx(run + hand + EDGE_CLEARANCE)
    assert edge_back(0.0, 1.6) == APPROACH_BACK  # nothing under it: as before
    off = approach_offset("pick", target, 1.0, 0.0, facing=math.pi, back=edge_back(run, 1.6))
    assert off[0] > 0.25 - target[0]  # the pre-grasp point beyond the front edge
    back = approach_back_dir("pick", target, 0.0, 5.0, math.pi)  # (against the facing)
    np.testing.assert_allclose(back, [1.0, 0.0], atol=1e-12)
    back = approach_back_dir("fasten", target, 0.05, 5.0, math.pi)  # (towards the operator)
    np.testing.assert_allclose(back, [0.0, 1.0], atol=1e-12)
