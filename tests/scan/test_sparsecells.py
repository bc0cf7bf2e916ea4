"""mjwalk.scan.sparsecells: a sparse scan's cells joined over gaps up to a voxel (issue 47)."""

from __future__ import annotations

import numpy as np
from scipy import ndimage

from mjwalk.scan.level import VOXEL
from mjwalk.scan.sparsecells import join_sparse

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
