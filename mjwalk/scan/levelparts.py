"""A scan level that is no rectangle (an L-shaped platform, a mezzanine round a stairwell) as a
union of rectangles, so that its written boxes hold no air a walker could stand on (issue 47).

:mod:`mjwalk.scan.levelboxes` writes each level as a box over its cells' minimum-area rectangle.
That rectangle is kept when it holds no air a foot could stand on. Air is what the scan saw
below the level: floor seen (floor points, :attr:`mjwalk.scan.obstacles.FloorPlan.seen`)
inside the rectangle, farther than :data:`EDGE_CELLS` cells from the level's cells, in a region
at least a foot wide (:data:`mjwalk.scan.obstacles.GAP_WIDTH`), and what was seen of neither
next to it (the floor's shadow behind the level's edge). Cells of the rectangle where nothing
was seen and that only the level walls in (the blind disc under a scanner standing on the level,
the shadow a rack on the level casts towards its edge) are level, as small unscanned holes are
floor (:data:`mjwalk.scan.obstacles.HOLE_RADIUS`); floor seen within :data:`EDGE_CELLS` of the
rectangle's outline does not open them to the floor, since that outline lies on the level's
ragged edge and the floor seen there is the floor beyond it (hall 1178: a rack by the
mezzanine's edge shadows the deck's corner, and the floor seen beside the deck where the outline
passes made that corner and the scanners' blind discs next to it air). Otherwise the cells are
sampled on a grid along the rectangle's axes and covered greedily by the largest rectangle of
cells not yet covered, each grown while a whole row or column of the level lies beyond it (so
parts overlap rather than leave thin slivers), until what is left holds no rectangle a tread
deep and a person wide (``norms.MIN_TREAD`` by ``norms.STAND_WIDTH``, less a cell each side: no
walk surface; those cells are left out, never air). The parts share the level's height and
touch, so ``mjwalk.world.level_graph`` on the written scene groups them into the one level.
Metres, scene frame.
"""

from __future__ import annotations

import numpy as np
from scipy import ndimage

from mjwalk.scan.obstacles import GAP_WIDTH, FloorPlan
from mjwalk.world.norms import MIN_TREAD, STAND_WIDTH

#: Cells of the rectangle within this many cells of the level's are not air: its outline lies
#: round the outermost cells' centres, and a scanned edge is ragged by a cell or two.
EDGE_CELLS = 2
#: Most rectangles a level is written as (a level more ragged than this keeps its last parts'
#: cells uncovered: not walkable, never air).
MAX_PARTS = 12


def _frame(rect: np.ndarray, res: float) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The rectangle's grid: (u axis (2,), v axis (2,), (nv, nu, 2) sample points), sampled
    about every ``res`` from corner 0 to the opposite corners."""
    e1, e2 = rect[1] - rect[0], rect[3] - rect[0]
    l1, l2 = float(np.hypot(*e1)), float(np.hypot(*e2))
    nu, nv = max(2, round(l1 / res) + 1), max(2, round(l2 / res) + 1)
    gu, gv = np.linspace(0.0, l1, nu), np.linspace(0.0, l2, nv)
    pts = rect[0] + gu[None, :, None] * (e1 / l1) + gv[:, None, None] * (e2 / l2)
    return gu, gv, pts


def _sample(mask: np.ndarray, pts: np.ndarray, plan: FloorPlan) -> np.ndarray:
    """``mask`` (ny, nx) at points (..., 2); False off the grid."""
    ix = np.floor((pts[..., 0] - plan.x0) / plan.resolution).astype(np.int64)
    iy = np.floor((pts[..., 1] - plan.y0) / plan.resolution).astype(np.int64)
    ny, nx = mask.shape
    ok = (ix >= 0) & (ix < nx) & (iy >= 0) & (iy < ny)
    out = np.zeros(pts.shape[:-1], bool)
    out[ok] = mask[iy[ok], ix[ok]]
    return out


def _outside(rect: np.ndarray, pts: np.ndarray) -> np.ndarray:
    """Points (..., 2) outside a rectangle (4, 2) by more than a millimetre."""
    e1, e2 = rect[1] - rect[0], rect[3] - rect[0]
    d = pts - rect[0]
    u, v = d @ e1 / (e1 @ e1), d @ e2 / (e2 @ e2)
    tol1, tol2 = 1e-3 / np.sqrt(e1 @ e1), 1e-3 / np.sqrt(e2 @ e2)
    return (u < -tol1) | (u > 1 + tol1) | (v < -tol2) | (v > 1 + tol2)


def largest_rectangle(mask: np.ndarray) -> tuple[int, int, int, int]:
    """The largest all-True axis-aligned rectangle of a bool grid (the histogram method).

    Args:
        mask: (nv, nu) bool.

    Returns:
        (j0, j1, i0, i1): its rows and columns, ends exclusive; an empty one (0, 0, 0, 0) when
        ``mask`` has no True cell.
    """
    nv, nu = mask.shape
    height = np.zeros(nu, np.int64)
    best, where = 0, (0, 0, 0, 0)
    for j in range(nv):
        height = np.where(mask[j], height + 1, 0)
        stack: list[int] = []
        for i in range(nu + 1):
            h = int(height[i]) if i < nu else 0
            while stack and int(height[stack[-1]]) >= h:
                top = stack.pop()
                left = stack[-1] + 1 if stack else 0
                area = int(height[top]) * (i - left)
                if area > best:
                    best, where = area, (j - int(height[top]) + 1, j + 1, left, i)
            stack.append(i)
    return where


def _grow(occ: np.ndarray, box: tuple[int, int, int, int]) -> tuple[int, int, int, int]:
    """The rectangle grown one row or column at a time while the whole of it is in ``occ``."""
    j0, j1, i0, i1 = box
    nv, nu = occ.shape
    moved = True
    while moved:
        moved = False
        if j0 > 0 and occ[j0 - 1, i0:i1].all():
            j0, moved = j0 - 1, True
        if j1 < nv and occ[j1, i0:i1].all():
            j1, moved = j1 + 1, True
        if i0 > 0 and occ[j0:j1, i0 - 1].all():
            i0, moved = i0 - 1, True
        if i1 < nu and occ[j0:j1, i1].all():
            i1, moved = i1 + 1, True
    return j0, j1, i0, i1


def level_parts(
    cells: np.ndarray, rect: np.ndarray, plan: FloorPlan, built: np.ndarray | None = None
) -> list[np.ndarray]:
    """A level's box outline as the rectangles that cover its cells without air.

    Args:
        cells: (ny, nx) bool, the level's cells (with the cells it reaches under a level a step
            above it) on the floor plan's grid.
        rect: (4, 2) its box outline, counter-clockwise, metres.
        plan: the floor plan (its grid).
        built: (4, 2) the outline its cells gave before an edge was moved onto a stair's last
            riser or a ramp's end; what ``rect`` holds beyond it is level. None: ``rect``.

    Returns:
        ``[rect]`` when it holds no air a foot could stand on; else the parts (4, 2) each,
        counter-clockwise, along ``rect``'s axes, metres.
    """
    res = plan.resolution
    gu, gv, pts = _frame(rect, res)
    occ = _sample(cells, pts, plan)
    seen = _sample(plan.floor if plan.seen is None else plan.seen, pts, plan) & ~occ
    lab, _ = ndimage.label(~occ & ~seen, np.ones((3, 3), bool))
    inside = np.zeros_like(seen)  # the rim's floor is the floor beyond the level's ragged edge
    inside[EDGE_CELLS:-EDGE_CELLS, EDGE_CELLS:-EDGE_CELLS] = True
    near_seen = ndimage.binary_dilation(seen & inside, np.ones((3, 3), bool))
    shadow = np.unique(lab[near_seen & (lab > 0)])
    occ |= (lab > 0) & ~np.isin(lab, shadow)  # unseen, walled in by the level: level
    if built is not None:
        occ |= _outside(built, pts)
    step = min(gu[1] - gu[0], gv[1] - gv[0])
    air = ~ndimage.binary_dilation(occ, np.ones((3, 3), bool), iterations=EDGE_CELLS)
    if not air.any() or 2 * ndimage.distance_transform_edt(air).max() * step - step < GAP_WIDTH:
        return [rect]
    least = (MIN_TREAD - 2 * res, STAND_WIDTH - 2 * res)
    left = occ.copy()
    parts: list[np.ndarray] = []
    while left.any() and len(parts) < MAX_PARTS:
        j0, j1, i0, i1 = largest_rectangle(left)
        du, dv = (i1 - i0) * (gu[1] - gu[0]), (j1 - j0) * (gv[1] - gv[0])
        if min(du, dv) < least[0] or max(du, dv) < least[1]:
            break  # what is left is no walk surface of its own
        j0, j1, i0, i1 = _grow(occ, (j0, j1, i0, i1))
        left[j0:j1, i0:i1] = False
        parts.append(_corners(rect, gu, gv, (j0, j1, i0, i1)))
    return parts or [rect]


def _corners(
    rect: np.ndarray, gu: np.ndarray, gv: np.ndarray, box: tuple[int, int, int, int]
) -> np.ndarray:
    """A block of samples as a rectangle (4, 2): each sample stands for the cell round it, and
    the outline keeps within ``rect``."""
    j0, j1, i0, i1 = box
    du, dv = gu[1] - gu[0], gv[1] - gv[0]
    u0, u1 = max(0.0, gu[i0] - 0.5 * du), min(gu[-1], gu[i1 - 1] + 0.5 * du)
    v0, v1 = max(0.0, gv[j0] - 0.5 * dv), min(gv[-1], gv[j1 - 1] + 0.5 * dv)
    a = (rect[1] - rect[0]) / gu[-1]
    b = (rect[3] - rect[0]) / gv[-1]
    return np.array([rect[0] + u * a + v * b for u, v in ((u0, v0), (u1, v0), (u1, v1), (u0, v1))])
