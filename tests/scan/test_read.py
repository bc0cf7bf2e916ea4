"""mjwalk.scan.read: units, up axes and the checks every cloud passes before a floor is sought."""

from __future__ import annotations

import numpy as np
import pytest
from test_scene import _room_cloud

from mjwalk.errors import ScanError
from mjwalk.scan.read import check_options, check_units, to_metres_z_up
from mjwalk.world.units import UP_AXES


def test_options_are_checked_and_the_up_key_normalised():
    assert check_options("mm", "y", "f") == "+y"
    assert check_options("m", "-Z", "f") == "-z"
    with pytest.raises(ScanError, match="f: unknown units 'furlong'"):
        check_options("furlong", "+z", "f")
    with pytest.raises(ScanError, match="f: unknown up axis 'w'"):
        check_options("m", "w", "f")


def test_centimetres_y_up_become_metres_z_up():
    room = _room_cloud(spacing=0.1)
    raw = room @ UP_AXES["+y"] / 0.01  # what a y-up file in centimetres holds
    pts, scale, axes = to_metres_z_up(raw, units="cm", up="+y", source="f")
    assert scale == 0.01
    np.testing.assert_array_equal(axes, UP_AXES["+y"])
    np.testing.assert_allclose(pts, room, atol=1e-9)


def test_offset_nan_and_shape_checks():
    room = _room_cloud(spacing=0.1)
    pts, _, _ = to_metres_z_up(room + 1000.0, offset=(1000.0, 1000.0, 1000.0))
    np.testing.assert_allclose(pts, room, atol=1e-9)
    bad = room.copy()
    bad[3, 1] = np.nan
    with pytest.raises(ScanError, match=r"1 of \d+ points have NaN"):
        to_metres_z_up(bad, source="f")
    assert len(to_metres_z_up(bad, drop_invalid=True)[0]) == len(room) - 1
    with pytest.raises(ScanError, match=r"points must be an \(N, 3\) array"):
        to_metres_z_up(room[:, :2], source="f")


def test_millimetre_cloud_read_as_metres_names_the_units():
    with pytest.raises(ScanError, match="pass --units mm"):
        check_units(_room_cloud(spacing=0.1) * 1000.0, "m", "f")
