"""WalkSurface arithmetic: heights on a ramp, free height under overheads, head clearance."""

from __future__ import annotations

import math

import numpy as np
import pytest

from mjwalk.errors import InputError
from mjwalk.world.footprint import Footprint
from mjwalk.world.norms import HEAD_MARGIN
from mjwalk.world.walksurface import Overhead, WalkSurface, head_fits


def square(name: str, x0: float, y0: float, x1: float, y1: float) -> Footprint:
    return Footprint(name, 0, np.array([[x0, y0], [x1, y0], [x1, y1], [x0, y1]]))


def ramp(overhead=()) -> WalkSurface:
    slope = math.atan(0.1)  # rising 10 % towards +y
    return WalkSurface(
        0, "r", "ramp", 0.5, square("r", 0, 0, 1, 10), 10.0, (0.5, 5.0), slope, math.pi / 2,
        0.0, 1.0, 1.0, 10.0, tuple(overhead),
    )  # fmt: skip


def test_height_on_a_ramp():
    r = ramp()
    assert r.height_at(np.array([[0.5, 0.0], [0.2, 10.0], [0.9, 5.0]])) == pytest.approx(
        [0.0, 1.0, 0.5]
    )


def test_free_height_and_head_fits():
    beam = Overhead("beam", square("beam", -1, 4, 2, 6), bottom=2.4, top=2.6)
    r = ramp([beam])
    xy = np.array([[0.5, 5.0], [0.5, 2.0]])
    assert r.free_height(xy) == pytest.approx([1.9, math.inf])
    assert list(head_fits(r, xy, 1.90)) == [False, True]
    assert list(head_fits(r, xy, 1.60)) == [True, True]
    assert bool(head_fits(r, xy[0], 1.9 - HEAD_MARGIN))
    # under the beam the ramp rises from 0.4 to 0.6 m: 2.0 down to 1.8 m free (nodes 5 cm apart)
    assert r.lowest_ceiling == pytest.approx(1.8, abs=0.006)
    assert r.headroom.clear_area(2.0) == pytest.approx(8.0, abs=0.2)
    with pytest.raises(InputError, match="stature"):
        head_fits(r, xy, 0.0)


def test_kind_is_checked():
    with pytest.raises(InputError, match="kind"):
        WalkSurface(0, "x", "roof", 0.0, square("x", 0, 0, 1, 1), 1.0, (0.5, 0.5), 0, 0, 0, 0, 1, 1)
