"""mjwalk.world.units: the length units and up axes imported files may declare."""

from __future__ import annotations

import numpy as np

from mjwalk.world.units import UNITS, UP_AXES


def test_units_are_metres_per_unit():
    assert UNITS == {"m": 1.0, "cm": 0.01, "mm": 0.001, "in": 0.0254, "ft": 0.3048}


def test_up_axes_are_rotations_taking_the_named_axis_to_plus_z():
    for key, rot in UP_AXES.items():
        np.testing.assert_allclose(rot @ rot.T, np.eye(3), atol=1e-12)
        assert np.linalg.det(rot) == 1.0
        axis = np.zeros(3)
        axis["xyz".index(key[1])] = 1.0 if key[0] == "+" else -1.0
        np.testing.assert_array_equal(rot @ axis, [0.0, 0.0, 1.0])
