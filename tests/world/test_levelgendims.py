"""mjwalk.world.levelgendims: a generated flight's risers and treads lie on the written grid and
keep DIN 18065's limits and step rule however the hall's boxes are rounded (issue 47)."""

from __future__ import annotations

import math

import numpy as np
import pytest

from mjwalk.world.levelgendims import (
    DIM_GRID,
    FACE_SLACK,
    TREAD_SLACK,
    WRITE_DECIMALS,
    draw_riser,
    on_grid,
    stair_dims,
)
from mjwalk.world.norms import MAX_RISER, MAX_TREAD, MIN_RISER, MIN_TREAD, STEP_RULE


def _grid_steps(x: float) -> float:
    return abs(x / DIM_GRID - round(x / DIM_GRID))


def test_on_grid_snaps_inside_the_bounds():
    assert on_grid(0.15251) == 0.1526
    assert on_grid(0.15249) == 0.1524
    assert on_grid(0.3449, hi=0.34485) == 0.3448  # the nearest is beyond the bound
    assert on_grid(0.1, lo=0.1401) == 0.1402
    assert on_grid(0.2, 0.10001, 0.10019) is None  # no grid point between
    assert on_grid(0.19, MIN_RISER, MAX_RISER) == MAX_RISER  # the limits lie on the grid


def test_risers_and_treads_on_the_grid_inside_the_limits_as_written():
    """5000 seeded flights: riser and tread on the grid (so each half is a written unit), the
    riser within the limits, the tread and 2 h + g ``TREAD_SLACK`` inside theirs."""
    rng = np.random.default_rng(47)
    for _ in range(5000):
        r, a = stair_dims(rng)
        assert _grid_steps(r) < 1e-6 and _grid_steps(a) < 1e-6
        assert MIN_RISER <= r <= MAX_RISER
        assert MIN_TREAD + TREAD_SLACK <= a + 1e-12 and a - 1e-12 <= MAX_TREAD - TREAD_SLACK
        rule = 2 * r + a
        assert STEP_RULE[0] + TREAD_SLACK <= rule + 1e-12
        assert rule - 1e-12 <= STEP_RULE[1] - TREAD_SLACK
        half = f"{0.5 * r:.{WRITE_DECIMALS}f}"
        assert abs(2 * float(half) - r) < 1e-12  # a box's half-height is written exactly
        r2 = draw_riser(rng)
        assert _grid_steps(r2) < 1e-6 and MIN_RISER <= r2 <= MAX_RISER


@pytest.mark.parametrize("seed", range(5))
def test_written_face_within_face_slack(seed):
    """A box written as levelgen writes it (centre and half-size to ``WRITE_DECIMALS``), at any
    yaw: its face along the yaw lies within ``FACE_SLACK`` of the drawn one, and the bound is
    not loose (the worst of 2000 draws over 0.85 of it: 0.90-0.94 for seeds 0-4)."""
    rng = np.random.default_rng(seed)
    worst = 0.0
    for _ in range(2000):
        yaw = float(rng.uniform(-math.pi, math.pi))
        c = rng.uniform(-10.0, 10.0, 2)
        half = float(rng.uniform(0.1, 1.0))
        d = np.array([math.cos(yaw), math.sin(yaw)])
        cw = np.array([float(f"{x:.{WRITE_DECIMALS}f}") for x in c])
        hw = float(f"{half:.{WRITE_DECIMALS}f}")
        err = abs((cw @ d + hw) - (c @ d + half))
        assert err <= FACE_SLACK + 1e-12
        worst = max(worst, err)
    assert worst > 0.85 * FACE_SLACK
