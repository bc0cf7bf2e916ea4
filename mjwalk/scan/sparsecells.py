"""Grid cells of a sparse scan joined at the voxel scale, over cells no point was seen in (issue
47).

The seed paper groups walk-surface points by region growing over 0.1 m voxels (§3 A2,
:data:`mjwalk.scan.level.VOXEL`); the floor plan's cells are finer (2 cm). Where a surface is
seen only from afar its points lie farther apart than a cell: a deck's middle under its own
scanner, inside the 30° blind cone (a disc of radius 1.6 tan 30° = 0.92 m for a scanner 1.6 m
over the deck, ``mjwalk.scan.raycast.ELEVATION_DEG``), which the other scanners see only at
grazing angles. On a deck narrower than that disc the sparse band runs from edge to edge, and
cells joined by their 8 neighbours fall apart into the parts either side.

:func:`join_sparse` closes a surface's cells over gaps up to a voxel, the scale the points were
grouped at, and only over cells that are *unseen* at the surface's height
(:func:`unseen_cells`): no point from below the surface up to the top of its obstacle band
(:data:`mjwalk.world.floor.OBSTACLE_Z_RANGE`). A cell holding any point there shows something
else -- a lower surface seen through a gap, a riser's face, an obstacle, noise -- and is never
bridged: the scan saw what is there. Points above the band (a ceiling, a crane rail) say
nothing about the surface.

:func:`enclosed_unseen` takes the wider holes: where two scanners stand on one deck their blind
cones and the shadow of an obstacle standing on the deck leave a region seen by no ray, wider
than a voxel (generated hall 1270: 0.66 m^2 of its mezzanine, written as an obstacle through
the deck that cut the stair's landing off the rest of it). As the floor plan counts an
unscanned hole as floor when it is no wider than a blind cone
(:data:`mjwalk.scan.obstacles.HOLE_RADIUS`), an unseen region is the surface's when it is no
wider than that, touches the surface, and is ringed only by the surface's own cells and by what
stands on it: cells whose lowest point is not below the surface (nothing seen under it) and that
are no walk surface at another height (:func:`other_surfaces`). Nothing seen around such a
region says the surface ends there: an edge shows the floor below beyond it, a pit its walls. A
higher tread or level beside it does say so -- the surface may end at its riser -- so a stair's
tread is never grown into its unseen strip before the next tread (a rule without this split
generated hall 1016's flight of eight risers into five and three). A cell with an obstacle on
it, or a lone point above (a mixed pixel, fewer than :data:`~mjwalk.scan.obstacles.
MIN_BAND_POINTS`), is no walk surface. Metres, the floor plan's grid.
"""

from __future__ import annotations

import numpy as np
from scipy import ndimage

from mjwalk.scan.level import VOXEL
from mjwalk.scan.obstacles import FLOOR_TOL, HOLE_RADIUS, MIN_BAND_POINTS
from mjwalk.world.floor import OBSTACLE_Z_RANGE


def unseen_cells(lowest: np.ndarray, height: float) -> np.ndarray:
    """The cells in which no point lies at or below the top of a surface's obstacle band.

    Args:
        lowest: (ny, nx) the lowest point's height per cell, metres (+inf: no point).
        height: the surface's height, metres above the floor.

    Returns:
        (ny, nx) bool: the cells whose lowest point lies above ``height +
        OBSTACLE_Z_RANGE[1]`` (or that hold none): unseen from under the surface to head
        height above it.
    """
    return np.asarray(lowest) > height + OBSTACLE_Z_RANGE[1]


def join_sparse(
    cells: np.ndarray, resolution: float, within: np.ndarray | None = None
) -> np.ndarray:
    """Cells closed over the gaps a sparse scan leaves between them, up to a voxel.

    Args:
        cells: (ny, nx) bool, the cells holding a surface's points.
        resolution: the grid's cell edge, metres.
        within: (ny, nx) bool, the cells a gap may be closed over (None: any), e.g. those
            :func:`unseen_cells` at the surface's height.

    Returns:
        (ny, nx) bool: ``cells`` and the gaps between them up to :data:`~mjwalk.scan.level.
        VOXEL` wide (a morphological closing by a voxel's square of cells), within ``within``.
    """
    k = max(1, round(VOXEL / resolution))
    grown = ndimage.maximum_filter(cells, size=k, mode="constant", cval=False)
    closed = ndimage.minimum_filter(grown, size=k, mode="constant", cval=False)  # separable
    out = cells | closed
    return out if within is None else out & (within | cells)


def other_surfaces(near: np.ndarray, band: np.ndarray, k: int) -> np.ndarray:
    """The walk-surface cells at every candidate height but one: another level's or tread's.

    Args:
        near: (K, ny, nx) points per cell within ``FLOOR_TOL`` of each candidate height.
        band: (K, ny, nx) points per cell in each candidate's obstacle band
            (:data:`mjwalk.world.floor.OBSTACLE_Z_RANGE` above it).
        k: the candidate left out (the surface's own).

    Returns:
        (ny, nx) bool: the cells holding a point within ``FLOOR_TOL`` of a candidate height
        other than ``k`` and fewer than :data:`~mjwalk.scan.obstacles.MIN_BAND_POINTS` in its
        band (as ``scanlevels.regions_at`` takes a surface's cells).
    """
    out = np.zeros(near.shape[1:], bool)
    for j in range(near.shape[0]):
        if j != k:
            out |= (near[j] > 0) & (band[j] < MIN_BAND_POINTS)
    return out


def unseen_regions(lowest: np.ndarray, height: float) -> tuple[np.ndarray, list]:
    """The connected regions unseen at a surface's height, labelled once for every region of
    that height :func:`enclosed_unseen` is asked about.

    Args:
        lowest: (ny, nx) the lowest point's height per cell, metres (+inf: no point).
        height: the surface's height, metres above the floor.

    Returns:
        The (ny, nx) labels (8-neighbour, 0: seen) of :func:`unseen_cells` at ``height`` and
        ``ndimage.find_objects``' slices of each label.
    """
    lab, _ = ndimage.label(unseen_cells(lowest, height), np.ones((3, 3), bool))
    return lab, ndimage.find_objects(lab)


def enclosed_unseen(
    cells: np.ndarray,
    lowest: np.ndarray,
    height: float,
    resolution: float,
    elsewhere: np.ndarray,
    regions: tuple[np.ndarray, list] | None = None,
) -> np.ndarray:
    """The unseen holes a surface encloses (see the module's docstring).

    Args:
        cells: (ny, nx) bool, the surface's cells.
        lowest: (ny, nx) the lowest point's height per cell, metres (+inf: no point).
        height: the surface's height, metres above the floor.
        resolution: the grid's cell edge, metres.
        elsewhere: (ny, nx) bool, the walk-surface cells at other heights
            (:func:`other_surfaces`).
        regions: :func:`unseen_regions` at ``height`` (None: labelled here).

    Returns:
        (ny, nx) bool: the cells of the connected (8-neighbour) regions :func:`unseen_cells`
        at ``height`` that touch ``cells``, lie off the grid's edge, are no wider than
        :data:`~mjwalk.scan.obstacles.HOLE_RADIUS` (inscribed radius) and whose ringing cells
        are all ``cells`` or, none of ``elsewhere``, cells whose lowest point is at least
        ``height`` less :data:`~mjwalk.scan.obstacles.FLOOR_TOL` (the surface, what stands on
        it).
    """
    low = np.asarray(lowest)
    lab, objects = regions if regions is not None else unseen_regions(low, height)
    out = np.zeros(lab.shape, bool)
    ny, nx = lab.shape
    rows, cols = np.flatnonzero(cells.any(1)), np.flatnonzero(cells.any(0))
    if not rows.size:
        return out
    # the regions touching the cells, looked for within the cells' box and a cell round it
    sub = (
        slice(max(rows[0] - 1, 0), min(rows[-1] + 2, ny)),
        slice(max(cols[0] - 1, 0), min(cols[-1] + 2, nx)),
    )
    near = ndimage.binary_dilation(cells[sub], np.ones((3, 3), bool)) & (lab[sub] > 0)
    for r in sorted(set(np.unique(lab[sub][near]).tolist()) - {0}):
        sl = objects[r - 1]
        if sl is None or sl[0].start == 0 or sl[1].start == 0:
            continue
        if sl[0].stop == ny or sl[1].stop == nx:
            continue
        box = (slice(sl[0].start - 1, sl[0].stop + 1), slice(sl[1].start - 1, sl[1].stop + 1))
        comp = lab[box] == r
        ring = ndimage.binary_dilation(comp, np.ones((3, 3), bool)) & ~comp
        own = cells[box][ring]
        on = ~elsewhere[box][ring] & (low[box][ring] >= height - FLOOR_TOL)
        if not own.any() or not (own | on).all():
            continue  # the surface ends there: an edge, a pit, another tread or level
        if ndimage.distance_transform_edt(comp).max() * resolution > HOLE_RADIUS:
            continue
        out[box] |= comp
    return out
