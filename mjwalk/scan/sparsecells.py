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
nothing about the surface. Metres, the floor plan's grid.
"""

from __future__ import annotations

import numpy as np
from scipy import ndimage

from mjwalk.scan.level import VOXEL
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
