"""The cited figures agree with each other and with the shipped multi-level scene's stair."""

from __future__ import annotations

import math

from mjwalk.world import norms


def test_stair_figures_are_consistent():
    assert norms.MIN_RISER < norms.MAX_RISER and norms.MIN_TREAD < norms.MAX_TREAD
    lo, hi = norms.STEP_RULE
    assert lo <= 2 * 0.17 + 0.29 <= hi  # ASR A1.8's particularly safe stair
    assert lo <= 2 * 0.17 + 0.28 <= hi  # the shipped multi-level station's stair
    assert norms.MIN_STAIR_RISERS == 3


def test_ramp_and_headroom_figures_are_consistent():
    assert norms.BARRIER_FREE_RAMP_SLOPE < norms.MAX_RAMP_SLOPE
    assert math.radians(5.5) < norms.MAX_RAMP_SLOPE  # the shipped ramp
    assert math.tan(math.radians(5.5)) > math.tan(norms.BARRIER_FREE_RAMP_SLOPE)  # not barrier-free
    assert norms.HORIZONTAL_SLOPE < math.tan(norms.MAX_RAMP_SLOPE)
    assert norms.OVERHEAD_MIN < norms.CLEAR_HEADROOM <= norms.HEADROOM_SCAN
    assert 2.2 + norms.HEAD_MARGIN <= norms.HEADROOM_SCAN  # the tallest walker fits the scan


def test_side_clearance_leaves_a_building_stair_room_for_a_walker():
    # a 1.0 m flight (DIN 18065's least usable width for buildings in general; the shipped
    # one) less the room to both sides leaves 0.7 m, more than the 0.61 m of Fruin's body ellipse
    assert 1.0 - 2 * norms.SIDE_CLEARANCE >= 0.61
