"""mjwalk.scan.limits: the resolution, extent and floor-plan size a scan must keep to."""

from __future__ import annotations

import numpy as np
import pytest

from mjwalk.errors import ScanError
from mjwalk.scan.limits import (
    MAX_EXTENT,
    RESOLUTION_RANGE,
    check_extent,
    check_plan_size,
    check_resolution,
)


def test_resolution_is_a_float_in_range():
    assert check_resolution("0.05") == 0.05
    assert check_resolution(RESOLUTION_RANGE[0]) == RESOLUTION_RANGE[0]
    with pytest.raises(ScanError, match=r"resolution 0\.2 m is outside 0\.005-0\.1 m"):
        check_resolution(0.2)
    with pytest.raises(ScanError, match=r"resolution 'fine' is not a number of metres"):
        check_resolution("fine")
    with pytest.raises(ScanError, match=r"^nan m is outside"):
        check_resolution(float("nan"), "")


def test_stray_points_and_far_coordinates_are_refused():
    room = np.random.default_rng(0).uniform(0, 10, (1000, 3))
    check_extent(room, "room")
    stray = np.vstack([room, [[0.0, 3 * MAX_EXTENT, 0.0]]])
    with pytest.raises(ScanError, match=r"room: the cloud spans .* along y.*1 stray point"):
        check_extent(stray, "room")
    with pytest.raises(ScanError, match=r"beyond 1e\+07 m .* --offset=0,20000000,0"):
        check_extent(room + [0.0, 2e7, 0.0], "far")


def test_a_floor_plan_too_large_names_a_coarser_resolution():
    shed = np.array([[0.0, 0.0, 0.0], [300.0, 200.0, 0.0]])
    check_plan_size(shed, 0.1, "shed")
    with pytest.raises(ScanError, match=r"shed: a floor plan of 302.0 x 202.0 m .* --resolution"):
        check_plan_size(shed, 0.02, "shed")
