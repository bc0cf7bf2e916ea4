"""Risers and treads a generated hall (:mod:`mjwalk.world.levelgen`) draws, kept inside DIN
18065's limits as they are written, not only as they are drawn (issue 47).

The generator writes its MJCF in metres to :data:`WRITE_DECIMALS` decimals, a box as its centre
and half-sizes. A riser or tread drawn inside the limits could come out beyond them: hall 1065's
flight, drawn with 0.1525 m risers and 2 h + g = 0.6499 m, was written with half-heights rounded
to 0.1 mm, risers of 0.1524 and 0.1526 m, and read as single steps (2 h + g 0.65006 m). So:

- a riser and a tread are drawn on a grid of :data:`DIM_GRID` (two written units), so half of
  one (a half-size; a mid-height between two levels on the grid) is written exactly and every
  written riser is exactly the drawn one; the norms' riser limits lie on that grid;
- a tread's depth is read between two box faces, each written within :data:`FACE_SLACK` of where
  it was drawn, so the tread is drawn :data:`TREAD_SLACK` inside the tread limits and the step
  rule (its risers exact, 2 h + g moves by its tread's error only).

Metres, horizontal distances along a flight's climb.
"""

from __future__ import annotations

import math

import numpy as np

from mjwalk.world.norms import MAX_RISER, MAX_TREAD, MIN_RISER, MIN_TREAD, STEP_RULE

#: Decimals the generator writes metres with (a box's ``pos`` and ``size``): 0.1 mm, far below
#: a scan's precision, and short MJCF text.
WRITE_DECIMALS = 4
#: One written unit, metres: a written coordinate lies within half of it of the drawn one.
WRITE_UNIT = 10.0**-WRITE_DECIMALS
#: The grid risers and treads are drawn on, metres: two written units, so their halves are
#: written units.
DIM_GRID = 2 * WRITE_UNIT
#: Most a written box face lies from the drawn one along any horizontal direction, metres: the
#: centre's x and y each rounded by up to half a unit, so along a direction at ``a`` to the axes
#: by ``WRITE_UNIT / 2 (|cos a| + |sin a|)``, at most ``WRITE_UNIT / sqrt(2)``; and the half-size
#: by up to half a unit when it is not on the grid (the floor boxes round a pit's opening).
FACE_SLACK = WRITE_UNIT * (1.0 / math.sqrt(2.0) + 0.5)
#: Most a written tread's depth lies from the drawn one, metres: it lies between two faces.
TREAD_SLACK = 2 * FACE_SLACK


def on_grid(x: float, lo: float = -math.inf, hi: float = math.inf) -> float | None:
    """The point of the :data:`DIM_GRID` grid nearest ``x`` within ``[lo, hi]``.

    Args:
        x: a length, metres.
        lo: the least value allowed, metres.
        hi: the largest value allowed, metres.

    Returns:
        The grid point (rounded to :data:`WRITE_DECIMALS` decimals), or None when no grid point
        lies within ``[lo, hi]``.
    """
    k_lo = math.ceil(lo / DIM_GRID - 1e-9) if math.isfinite(lo) else -math.inf
    k_hi = math.floor(hi / DIM_GRID + 1e-9) if math.isfinite(hi) else math.inf
    if k_lo > k_hi:
        return None
    k = min(max(round(x / DIM_GRID), k_lo), k_hi)
    return round(int(k) * DIM_GRID, WRITE_DECIMALS)


def draw_riser(rng: np.random.Generator) -> float:
    """A riser in [``MIN_RISER``, ``MAX_RISER``] on the :data:`DIM_GRID` grid, metres.

    Args:
        rng: the generator drawn from (one uniform draw).

    Returns:
        The riser, metres.
    """
    r = on_grid(float(rng.uniform(MIN_RISER, MAX_RISER)), MIN_RISER, MAX_RISER)
    assert r is not None  # the limits lie on the grid
    return r


def stair_dims(rng: np.random.Generator) -> tuple[float, float]:
    """A flight's riser and tread, metres: on the :data:`DIM_GRID` grid, the riser in
    [``MIN_RISER``, ``MAX_RISER``], the tread :data:`TREAD_SLACK` inside [``MIN_TREAD``,
    ``MAX_TREAD``] and the step rule 2 h + g :data:`TREAD_SLACK` inside ``STEP_RULE``, so both
    hold as the hall is written.

    Args:
        rng: the generator drawn from (a riser, then a tread, until the riser leaves room).

    Returns:
        (riser, tread), metres.
    """
    while True:
        r = draw_riser(rng)
        lo = max(MIN_TREAD, STEP_RULE[0] - 2 * r) + TREAD_SLACK
        hi = min(MAX_TREAD, STEP_RULE[1] - 2 * r) - TREAD_SLACK
        if hi > lo:
            a = on_grid(float(rng.uniform(lo, hi)), lo, hi)
            if a is not None:
                return r, a
