"""The steps between a scan's walk-surface regions (issue 47): regions whose edges touch along a
body's width with a riser of at most ``norms.MAX_RISER`` between them, an edge's unseen strip
counted as its own.

A scanner does not see the strip of a surface just behind the riser that rises from it when the
riser stands between them (a tread's back under the next tread's nosing; a landing's edge in
front of the next flight's first riser, a flight turned at the landing hiding it from the
scanners beyond). A scanner that does see such a strip sees it at a grazing angle, its rows of
points several cells apart (0.4 deg rays 2.8 m away meet a tread 13 deg below the eye 8.6 cm
apart), so the cells there that hold a point at the region's height are not joined to the
region's (8-neighbourhood) either. Cells beyond a region's edge with nothing in its obstacle band
(unseen, seen at the region's height, or over a lower surface seen) are its own for the touching
test (:func:`with_shadow`), up to a depth:

- a tread's, up to the deepest tread (``norms.MAX_TREAD``);
- a platform's (a landing, a mezzanine), up to the least tread (``norms.MIN_TREAD``; a choice,
  no norm: a strip a tread deep could hold a tread of its own, which would be seen in part);
- the floor's, none (its unseen cells are the scan's voids, :mod:`mjwalk.scan.voids`).

Metres, floor-plan grid.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from typing import Protocol

import numpy as np
from scipy import ndimage

from mjwalk.scan.obstacles import MIN_BAND_POINTS
from mjwalk.scan.planefit import RISER_TOL
from mjwalk.world.contacts import MIN_CROSSING
from mjwalk.world.norms import CONTACT_GAP, MAX_RISER, MAX_TREAD, MIN_TREAD


class Region(Protocol):
    """What the steps need of a region (:class:`mjwalk.scan.scanlevels.ScanLevel`)."""

    @property
    def kind(self) -> str: ...
    @property
    def height(self) -> float: ...
    @property
    def depth(self) -> float: ...
    @property
    def cells(self) -> np.ndarray: ...
    @property
    def peak(self) -> int: ...


class Rasters(Protocol):
    """What the steps need of the layers (:class:`mjwalk.scan.scanlevels.Layers`)."""

    band: np.ndarray


def touching(lower: np.ndarray, upper: np.ndarray, res: float) -> bool:
    """Whether two regions' edges touch along at least a body's width.

    Args:
        lower: (ny, nx) bool cells of the lower region.
        upper: (ny, nx) bool cells of the upper region.
        res: the cell edge, metres.

    Returns:
        True when the cells of ``upper``'s rim within ``CONTACT_GAP`` and two cells of
        ``lower`` span at least ``MIN_CROSSING``.
    """
    d = math.ceil(CONTACT_GAP / res) + 2
    near = ndimage.binary_dilation(lower, np.ones((3, 3), bool), iterations=d)
    rim = upper & ~ndimage.binary_erosion(upper, np.ones((3, 3), bool))
    return float((rim & near).sum()) * res >= MIN_CROSSING


def with_shadow(level: Region, layers: Rasters, res: float) -> np.ndarray:
    """A region's cells and the unseen cells beyond its edges that may be its own.

    Args:
        level: the region.
        layers: the rasterised layers it was found at (``level.peak``).
        res: the cell edge, metres.

    Returns:
        (ny, nx) bool: its cells and the cells beyond them with fewer than
        ``MIN_BAND_POINTS`` points in its band, up to the depth the module's docstring gives
        (a tread's: to the deepest tread; a platform's: the least tread; the floor's: none).
    """
    if level.kind == "tread":
        n = math.ceil((MAX_TREAD - level.depth) / res)
    elif level.kind == "platform":
        n = math.ceil(MIN_TREAD / res)
    else:
        n = 0
    if n <= 0:
        return level.cells
    k = level.peak
    clear = layers.band[k] < MIN_BAND_POINTS
    grow = ndimage.binary_dilation
    return grow(level.cells, np.ones((3, 3), bool), iterations=n, mask=clear | level.cells)


def region_steps(found: Sequence[Region], layers: Rasters, res: float) -> list[tuple[int, int]]:
    """The steps between regions.

    Args:
        found: the regions, the floor first.
        layers: the rasterised layers they were found at.
        res: the cell edge, metres.

    Returns:
        (lower, upper) index pairs: a riser of at most ``norms.MAX_RISER`` (measured: within
        ``planefit.RISER_TOL`` of it) between regions whose edges touch (the lower one's
        unseen strip counted, :func:`with_shadow`).
    """
    steps = []
    for i, a in enumerate(found):
        reach = with_shadow(a, layers, res)
        for j, b in enumerate(found):
            if 0 < b.height - a.height <= MAX_RISER + RISER_TOL and touching(reach, b.cells, res):
                steps.append((i, j))
    return steps
