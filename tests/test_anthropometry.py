"""Body dimensions from stature (Winter's segment table): heights, leg geometry, hand reach."""

from __future__ import annotations

import numpy as np
import pytest

from mjwalk.anthropometry import (
    SEG,
    hand_reach,
    knee_height,
    leg_geometry,
    pelvis_height,
    shoulder_geometry,
    swing_half_width,
)


def test_heights_are_winters_fractions_of_stature():
    assert pelvis_height(1.75) == pytest.approx(0.530 * 1.75)
    assert knee_height(1.60) == pytest.approx((SEG["ankle_height"] + SEG["shank"]) * 1.60)
    assert knee_height(1.75) == pytest.approx(0.285 * 1.75, abs=0.005)
    assert 0 < knee_height() < pelvis_height()


def test_leg_geometry_scales_with_stature_and_span_inverts():
    short, tall = leg_geometry(1.55), leg_geometry(1.86)
    assert tall.thigh / short.thigh == pytest.approx(1.86 / 1.55)
    assert short.foot_back + short.foot_front == pytest.approx(SEG["foot_length"] * 1.55)
    knee = np.linspace(0.0, 2.0, 9)
    span = tall.span(knee)
    assert span[0] == pytest.approx(tall.thigh + tall.shank)  # straight leg
    assert np.all(np.diff(span) < 0)  # bending shortens the leg
    assert tall.knee_for_span(span) == pytest.approx(knee, abs=1e-6)  # arccos near 1: ~1e-8
    assert tall.knee_for_span(10.0) == 0.0  # out of reach: clipped to straight


def test_shoulder_half_width_grows_with_stature():
    off, rad = shoulder_geometry(1.75)
    assert off == pytest.approx(0.5 * SEG["shoulder_width"] * 1.75)
    assert sum(shoulder_geometry(1.9)) > off + rad


def test_hand_reach():
    # about an arm's length plus the trunk lean at a shelf of 1.1 m, for a mean adult
    assert 0.55 < hand_reach(1.1) < 0.9
    assert hand_reach(1.1, turned=False) < hand_reach(1.1)  # reaching across the body
    assert hand_reach(1.1, stature=1.9) > hand_reach(1.1, stature=1.55)
    assert hand_reach(1.1, lean_deg=20) > hand_reach(1.1, lean_deg=0)
    assert hand_reach(3.5) == 0.0  # out of reach overhead


def test_swing_half_width_adds_the_abducted_arm_to_the_shoulders():
    off, rad = shoulder_geometry(1.75)
    width = swing_half_width(1.75)
    # the hand hangs 6 deg out over an arm of 0.44 statures: 8 cm beyond the shoulder
    assert width - off - rad == pytest.approx(0.44 * 1.75 * np.sin(np.radians(6.0)), abs=1e-6)
    assert 0.305 < width < 0.36  # wider than half of Fruin's 0.61 m body ellipse
    assert swing_half_width(1.9) / width == pytest.approx(1.9 / 1.75)
