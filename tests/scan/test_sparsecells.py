"""mjwalk.scan.sparsecells: a sparse scan's cells joined over unseen gaps up to a voxel (issue
47)."""

from __future__ import annotations

import numpy as np
from scipy import ndimage

from mjwalk.scan.level import VOXEL
from mjwalk.scan.obstacles import HOLE_RADIUS, MIN_BAND_POINTS
from mjwalk.scan.sparsecells import enclosed_unseen, join_sparse, other_surfaces, unseen_cells
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


def _deck_grid() -> tuple[np.ndarray, np.ndarray]:
    """A 40 x 40 grid: a deck at 1.2 m over cells 5-34 with the floor seen around it, an
    obstacle standing on the deck at its edge (rows 16-23, columns 30-34) and, beside it, a
    bay no ray reached (rows 16-23, columns 20-29). Returns (deck cells, lowest per cell)."""
    lowest = np.zeros((40, 40), np.float32)  # the floor seen all round
    deck = np.zeros((40, 40), bool)
    deck[5:35, 5:35] = True
    lowest[deck] = 1.2
    lowest[16:24, 30:35] = 1.25  # the obstacle's faces and top, over the deck
    lowest[16:24, 20:30] = np.inf  # the bay
    deck[16:24, 20:35] = False
    return deck, lowest


def test_an_unseen_bay_ringed_by_the_surface_and_what_stands_on_it_is_the_surface():
    """Hall 1270's mezzanine: its two scanners' blind cones beside an obstacle standing at its
    edge; the bay is open to the outside only through the obstacle's cells."""
    deck, lowest = _deck_grid()
    assert not ndimage.binary_fill_holes(deck)[20, 25]  # not a hole of the deck's cells
    holes = enclosed_unseen(deck, lowest, 1.2, RES, np.zeros_like(deck))
    assert holes[16:24, 20:30].all()
    assert holes.sum() == 8 * 10


def test_an_unseen_region_where_the_floor_shows_round_it_is_not_the_surface():
    deck, lowest = _deck_grid()
    lowest[16:24, 30:35] = 0.0  # the floor seen there: the deck ends at the bay
    assert not enclosed_unseen(deck, lowest, 1.2, RES, np.zeros_like(deck)).any()


def test_an_unseen_region_wider_than_a_blind_cone_or_at_the_grid_edge_is_not_the_surface():
    n = 2 * round(HOLE_RADIUS / RES) + 20
    deck = np.ones((n, n), bool)
    lowest = np.full((n, n), 1.2, np.float32)
    wide = np.zeros((n, n), bool)
    wide[5:-5, 5:-5] = True  # inscribed radius over HOLE_RADIUS
    deck[wide], lowest[wide] = False, np.inf
    assert not enclosed_unseen(deck, lowest, 1.2, RES, np.zeros_like(deck)).any()
    deck, lowest = _deck_grid()
    lowest[:, 0], deck[:, 0] = np.inf, False
    lowest[20, :20] = np.inf  # a corridor of unseen cells to the grid's edge
    assert not enclosed_unseen(deck, lowest, 1.2, RES, np.zeros_like(deck))[20, 25]


def test_an_unseen_region_beside_another_levels_cells_is_not_the_surface():
    """Hall 1016's flight: a tread's unseen strip ringed by the tread and the next tread up (its
    lowest point above the tread's) is where the tread ends at a riser, not the tread."""
    deck, lowest = _deck_grid()
    lowest[16:24, 30:35] = 1.2 + 0.17  # the next tread's top beside the bay, not an obstacle
    assert enclosed_unseen(deck, lowest, 1.2, RES, np.zeros_like(deck))[
        20, 25
    ]  # as high as an obstacle
    above = np.zeros_like(deck)
    above[16:24, 30:35] = True  # ... a walk surface at its own height
    assert not enclosed_unseen(deck, lowest, 1.2, RES, above).any()


def test_other_surfaces_are_the_surface_cells_at_the_other_heights():
    near = np.zeros((3, 4, 4), np.int32)
    band = np.zeros((3, 4, 4), np.int32)
    near[0, 0, 0] = 5  # the floor, left out
    near[1, 1, 1] = 1  # a tread: no band points over it
    near[2, 2, 2] = 3  # a surface with an obstacle on it: no walk surface
    band[2, 2, 2] = MIN_BAND_POINTS
    band[1, 3, 3] = 9  # band points only: an obstacle
    got = other_surfaces(near, band, 0)
    assert got[1, 1] and got.sum() == 1
    assert other_surfaces(near, band, 1).sum() == 1  # the floor's cell
