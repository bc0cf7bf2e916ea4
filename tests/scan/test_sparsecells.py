"""mjwalk.scan.sparsecells: a sparse scan's cells joined over unseen gaps up to a voxel (issue
47)."""

from __future__ import annotations

import numpy as np
from scipy import ndimage

from mjwalk.scan.level import VOXEL
from mjwalk.scan.sparsecells import join_sparse, unseen_cells
from mjwalk.world.floor import OBSTACLE_Z_RANGE

RES = 0.02


def _lattice(step: int, n: int = 60) -> np.ndarray:
    """Cells holding a point every ``step`` cells in x and y (scan lines ``step`` apart)."""
    cells = np.zeros((n, n), bool)
    cells[5:-5:step, 5:-5:step] = True
    return cells


def _parts(cells: np.ndarray) -> int:
    return int(ndimage.label(cells, np.ones((3, 3), bool))[1])


def test_points_up_to_a_voxel_apart_are_one_surface():
    k = round(VOXEL / RES)  # 5 cells
    for step in range(2, k + 1):  # gaps of up to k - 1 cells: under a voxel
        cells = _lattice(step)
        assert _parts(cells) > 1
        joined = join_sparse(cells, RES)
        assert _parts(joined) == 1
        assert (joined >= cells).all()


def test_points_farther_apart_than_a_voxel_stay_apart():
    cells = _lattice(round(VOXEL / RES) + 2)
    assert (join_sparse(cells, RES) == cells).all()


def test_gaps_are_closed_only_within_the_cells_allowed():
    cells = _lattice(3)
    within = np.ones_like(cells)
    within[:, 30] = False  # an obstacle's column between two scan lines
    joined = join_sparse(cells, RES, within)
    assert not joined[:, 30].any()
    assert (joined >= cells).all()
    assert _parts(joined) == 2


def test_a_dense_surface_is_unchanged():
    cells = np.zeros((40, 40), bool)
    cells[5:20, 5:30] = True
    assert (join_sparse(cells, RES) == cells).all()


def test_unseen_cells_hold_no_point_from_below_to_the_band_top():
    h = 0.5
    lowest = np.full((4, 4), np.inf, np.float32)
    lowest[0, 0] = 0.0  # the floor seen through a gap below the surface
    lowest[0, 1] = h  # the surface itself
    lowest[0, 2] = h + 1.0  # an obstacle in the band
    lowest[0, 3] = h + OBSTACLE_Z_RANGE[1] + 0.5  # a ceiling over the band only
    unseen = unseen_cells(lowest, h)
    assert unseen[0].tolist() == [False, False, False, True]
    assert unseen[1:].all()


def test_a_gap_where_a_lower_surface_was_seen_is_not_bridged():
    """Two scan lines 3 cells apart over a floor seen between them (a real gap) stay apart;
    over cells with no point they are one surface."""
    cells = np.zeros((20, 20), bool)
    cells[5:15, 5] = cells[5:15, 8] = True
    lowest = np.full(cells.shape, np.inf, np.float32)
    lowest[cells] = 0.5
    lowest[:, 6:8] = 0.0
    assert _parts(join_sparse(cells, RES, unseen_cells(lowest, 0.5))) == 2
    lowest[:, 6:8] = np.inf
    assert _parts(join_sparse(cells, RES, unseen_cells(lowest, 0.5))) == 1
