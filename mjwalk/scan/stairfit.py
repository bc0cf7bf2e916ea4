"""A chain of scan levels fitted as one regular flight (issue 47): from a level over single
treads to a level, as stairs are built (DIN 18065 allows 5 mm, ``norms.STAIR_TOLERANCE``).

The riser is the rise between the two end levels over the number of risers; the tread depth and
the first riser's place a least-squares line through the treads' front and back edges along the
climb (across the treads' shared long axis, :func:`treads_axis`, else the top level's axis
nearest the treads' run; into a pit, whose top is the floor, the
axis all its treads share, :func:`~mjwalk.scan.minrect.common_axis`, and the floor's rim along
the flight as the last riser, :func:`rim_edge`); when a tread is seen in part (its back in
the shadow of the next tread or level), through the treads' front edges and the top level's. The
chain is a stair when each tread's fitted height and edges lie within the scan's tolerance of
the flight (:data:`HEIGHT_TOL`, :data:`EDGE_CELLS`) and the flight is within the norms (riser
``MIN_RISER``-``MAX_RISER``, tread ``MIN_TREAD``-``MAX_TREAD``, step rule ``STEP_RULE``; the
riser measured, so within ``planefit.RISER_TOL`` of them, the tread within :func:`tread_slack`).
Used by :mod:`mjwalk.scan.levelboxes` (flights up), :mod:`mjwalk.scan.scanpits` (down into pits)
and :mod:`mjwalk.scan.hiddentread`. Metres, scene frame (floor at z = 0).
"""

from __future__ import annotations

import math

import numpy as np

from mjwalk.scan.minrect import common_axis, min_rectangle, principal_axis
from mjwalk.scan.obstacles import FLOOR_TOL, FloorPlan
from mjwalk.scan.planefit import RISER_TOL
from mjwalk.scan.scanlevels import ScanLevel, seen_in_part
from mjwalk.world.norms import (
    MAX_RISER,
    MAX_TREAD,
    MIN_RISER,
    MIN_TREAD,
    STAIR_TOLERANCE,
    STAND_WIDTH,
    STEP_RULE,
)

#: Most a tread's fitted height may differ from its regular flight's, metres: the build
#: tolerance ``STAIR_TOLERANCE`` (5 mm, DIN 18065) plus the scan's range noise (5 mm, the sigma
#: ``mjwalk.scan.obstacles.FLOOR_TOL`` is six of).
HEIGHT_TOL = STAIR_TOLERANCE + FLOOR_TOL / 6
#: Most a tread's edge may differ from its flight's, in cells of the floor plan, besides
#: ``STAIR_TOLERANCE``: an edge lies somewhere in its outermost cell, one more for the riser's
#: cell that its points block. A cell is measured along the flight's climb
#: (:func:`cell_span`): a square cell spans ``res (|cos a| + |sin a|)`` along a direction at
#: ``a`` to the grid, up to ``res * sqrt(2)`` for a flight at 45 deg to the hall's axes.
EDGE_CELLS = 2
#: Metres inside the norm's limits (tread, step rule) a flight measured beyond them is written
#: at (generated hall 1044's 0.2602 m treads, measured under ``MIN_TREAD``, written at it, read
#: 0.25999... m: single steps).
#: ASSUMPTION: ten times the 1e-5 m the scene's boxes are written to (five decimals,
#: ``mjwalk.scan.levelboxes``), so the written flight's 2 h + g reads within the rule after
#: rounding; far below the floor plan's 2 cm grid.
WRITE_MARGIN = 1e-4


def cell_span(run: np.ndarray, res: float) -> float:
    """How far a square grid cell extends along a direction (its projection's length).

    A region's edge read from its cells' centres lies up to half this from the true edge on
    either side; on a flight turned against the grid that is more than half a cell edge.

    Args:
        run: (2,) unit direction (a flight's climb), the floor plan's frame.
        res: the grid's cell edge, metres.

    Returns:
        ``res * (|run_x| + |run_y|)``, metres: ``res`` along a grid axis, ``res * sqrt(2)`` at
        45 deg.
    """
    return res * (abs(float(run[0])) + abs(float(run[1])))


def cell_centres(cells: np.ndarray, plan: FloorPlan) -> np.ndarray:
    """The centres of a region's cells.

    Args:
        cells: (ny, nx) bool on the floor plan's grid.
        plan: the floor plan (its grid).

    Returns:
        (M, 2) x, y, metres.
    """
    iy, ix = np.nonzero(cells)
    r = plan.resolution
    return np.column_stack([plan.x0 + (ix + 0.5) * r, plan.y0 + (iy + 0.5) * r])


def axis_near(rect: np.ndarray, run: np.ndarray) -> np.ndarray:
    """The rectangle's axis nearest a direction.

    Args:
        rect: (4, 2) corners in order, metres.
        run: (2,) the direction.

    Returns:
        (2,) the unit axis, signed to point along ``run``.
    """
    axes = [rect[1] - rect[0], rect[3] - rect[0]]
    axes = [a / np.hypot(*a) for a in axes]
    a = max(axes, key=lambda v: abs(float(v @ run)))
    return a if a @ run > 0 else -a


def tread_rect(tread: ScanLevel, plan: FloorPlan) -> np.ndarray:
    """A tread's minimum-area rectangle.

    Args:
        tread: the region.
        plan: the floor plan (its grid).

    Returns:
        (4, 2) corners, metres.
    """
    return min_rectangle(tread.cells, plan.x0, plan.y0, plan.resolution)


def fit_stair(chain: list[int], levels: list[ScanLevel], plan: FloorPlan) -> dict | None:
    """A chain of levels fitted as one regular flight, or None when it is not a stair.

    Args:
        chain: level indices bottom up: a level, the treads, a level.
        levels: the levels.
        plan: the floor plan (its grid).

    Returns:
        None, or: ``riser`` and ``tread`` (metres), ``heights`` of the treads, ``rects`` (4, 2)
        of the treads, ``top_edge`` (the last riser's place along ``run``), ``run`` (the unit
        climb direction) and the largest deviations ``dz``, ``dxy`` (metres).
    """
    n = len(chain) - 1
    bottom, top, treads = levels[chain[0]], levels[chain[-1]], [levels[i] for i in chain[1:-1]]
    riser = (top.height - bottom.height) / n
    heights = [bottom.height + (k + 1) * riser for k in range(n - 1)]
    dz = max(abs(t.height - h) for t, h in zip(treads, heights, strict=True))
    mids = [cell_centres(t.cells, plan).mean(axis=0) for t in treads]
    top_rect = min_rectangle(top.cells, plan.x0, plan.y0, plan.resolution)
    # a flight down into a pit (its top the floor, whose outline is the hall's) turns with its
    # own treads: the axis all its treads' rectangles fit best (one tread's own rectangle can
    # tip by atan(2 res / width), 1.2 deg in generated hall 1069, and its top tread then met
    # the cell-stepped floor edge in two stretches)
    if top.kind != "floor":
        axis = treads_axis(treads, plan)
        # a raised flight climbs across its treads' long axis when they agree on one
        # (:func:`treads_axis`); else along its top level's rectangle, nearest the treads' run
        rect = top_rect if axis is None else _unit_square(np.array([-axis[1], axis[0]]))
        run = axis_near(rect, mids[-1] - mids[0])
    else:
        axis = common_axis([t.cells for t in treads], plan.x0, plan.y0, plan.resolution)
        run = axis_near(_unit_square(axis), mids[-1] - mids[0])
    side = np.array([-run[1], run[0]])
    rows, rhs, lefts, rights = [], [], [], []
    for k, t in enumerate(treads):
        c = cell_centres(t.cells, plan)
        along, across = c @ run, c @ side
        rows += [[1.0, 0.0, k], [0.0, 1.0, k]]
        rhs += [along.min(), along.max()]
        lefts.append(across.min())
        rights.append(across.max())
    a, b = np.array(rows), np.array(rhs)
    if top.kind == "floor":
        # into a pit the floor's edge is the last riser, seen whole from the floor's side: the
        # flight's spacing is fitted through it too, so the top tread meets it (generated hall
        # 1067: three treads' edges alone gave 0.285 m for 0.2964 m, the top tread written
        # 5 cm short of the floor and the pit unreachable)
        span = (float(np.median(lefts)), float(np.median(rights)))
        front = rim_edge(top, plan, run, side, span, rhs[-2])
        if np.isfinite(front):
            a, b = np.vstack([a, [1.0, 0.0, n - 1]]), np.append(b, front)
    coef, *_ = np.linalg.lstsq(a, b, rcond=None)
    dxy = float(np.abs(a @ coef - b).max())
    cell = cell_span(run, plan.resolution)  # a cell's extent along the climb
    tol = STAIR_TOLERANCE + EDGE_CELLS * cell
    if dxy > tol or any(seen_in_part(t, plan.resolution) for t in treads):
        top_front = near_edge(top, plan, run, side, (min(lefts), max(rights)), rhs[-2])
        coef, dxy = _shadowed_fit(np.array(rhs), top_front, cell)
    first, tread = float(coef[0]), float(coef[2])
    slack = tread_slack(n, plan.resolution)
    rule_slack = slack + 2 * RISER_TOL  # 2 s + a: twice the measured riser's, the tread's
    ok = (
        dz <= HEIGHT_TOL
        and dxy <= tol
        and MIN_RISER - RISER_TOL <= riser <= MAX_RISER + RISER_TOL
        and MIN_TREAD - slack <= tread <= MAX_TREAD + slack
        and STEP_RULE[0] - rule_slack <= 2 * riser + tread <= STEP_RULE[1] + rule_slack
    )
    if not ok:
        return None
    tread = _written_tread(tread, riser)
    w0, w1 = float(np.median(lefts)), float(np.median(rights))
    rects = []
    for k in range(n - 1):
        s0, s1 = first + k * tread, first + (k + 1) * tread
        corners = [(s0, w0), (s1, w0), (s1, w1), (s0, w1)]
        rects.append(np.array([u * run + v * side for u, v in corners]))
    return {
        "riser": riser, "tread": tread, "heights": heights, "rects": rects, "run": run,
        "top_edge": first + (n - 1) * tread, "top_rect": top_rect, "dz": dz, "dxy": dxy,
    }  # fmt: skip


def written_riser(riser: float) -> float:
    """A flight's riser as the writers write it, metres: within DIN 18065's range
    (``norms.MIN_RISER``..``MAX_RISER``) ``WRITE_MARGIN`` inside each limit, so that the written
    scene's level graph, exact at the norm, still reads a stair after the written coordinates'
    rounding (:func:`mjwalk.scan.writtennorm.stairs_within_norm`,
    :func:`mjwalk.scan.scanpits.within_norm`; the tread is fitted for it, :func:`fit_stair`).

    Args:
        riser: the riser measured, metres.

    Returns:
        The riser written, metres (``riser`` itself when it lies within that range).
    """
    return min(max(riser, MIN_RISER + WRITE_MARGIN), MAX_RISER - WRITE_MARGIN)


def _written_tread(tread: float, riser: float) -> float:
    """A fitted tread as written, metres. One measured within the grid's slack outside the
    norm's range is written at its limit (the grid cannot tell them apart; the written scene's
    level graph is exact at the norm, so a margin inside it survives the written coordinates'
    rounding: ``WRITE_MARGIN``), and so is one whose step rule 2 h + g is (generated halls
    1031 and 1032 of benchmarks/bench_unseen.py: 2 h + g 0.656 and 0.6500+ m written, single
    steps in the scene). The rule holds for the riser measured and for the one written, which
    the writer takes to the norm's range (``writtennorm.stairs_within_norm``,
    ``scanpits.within_norm``): a flight of 0.14 m risers and 0.37 m treads (2 h + g = 0.65 m)
    measured at 0.139995 m, its tread fitted at 0.3699 m, was written with 0.1401 m risers,
    2 h + g = 0.6501 m: single steps in the written scene."""
    written = written_riser(riser)
    low, high = min(riser, written), max(riser, written)
    tread = min(max(tread, MIN_TREAD + WRITE_MARGIN), MAX_TREAD - WRITE_MARGIN)
    rule = (STEP_RULE[0] + WRITE_MARGIN - 2 * low, STEP_RULE[1] - WRITE_MARGIN - 2 * high)
    return min(max(tread, rule[0]), rule[1])


def treads_axis(treads: list[ScanLevel], plan: FloorPlan) -> np.ndarray | None:
    """The long axis a raised flight's treads share (across the climb), or None.

    A flight's treads are its many parallel riser edges: each a person wide
    (``norms.STAND_WIDTH``) and at most ``MAX_TREAD`` deep, so their pooled second moments
    (:func:`~mjwalk.scan.minrect.principal_axis`, read from all their cells) give the flight's
    axis. Its top level's own minimum rectangle rests on a few hull corners and can turn by
    ``atan(2 res / width)``; a square landing's is, besides, no axis at all (its moments are
    alike in every direction): generated hall 1163's 1.19 m landing's lay 1.18 deg off its
    flight. The axis holds when the pooled moments are as long as such a tread's,
    ``(STAND_WIDTH / MAX_TREAD)**2`` (2.6, a square's 1), and every tread's own axis lies within
    ``atan(2 res / STAND_WIDTH)`` of it (a cell at either end of the narrowest tread).

    Args:
        treads: the flight's treads, bottom up.
        plan: the floor plan (its grid).

    Returns:
        (2,) the unit axis along the treads' width, scene frame; None when they give none.
    """
    res = plan.resolution
    axis, ratio, own = principal_axis([t.cells for t in treads], plan.x0, plan.y0, res)
    tol = math.atan2(2 * res, STAND_WIDTH)
    agree = all(abs(float(a @ axis)) >= math.cos(tol) for a in own)
    return axis if ratio >= (STAND_WIDTH / MAX_TREAD) ** 2 and agree else None


def _unit_square(axis: np.ndarray) -> np.ndarray:
    """An axis and its normal as a unit square's corners, (4, 2), for :func:`axis_near`."""
    normal = np.array([-axis[1], axis[0]])
    return np.array([[0.0, 0.0], axis, axis + normal, normal])


def tread_slack(risers: int, res: float) -> float:
    """How far a flight's fitted tread may lie from its true one on the floor plan's grid.

    A tread's edges are read as the centres of its first and last cells along the climb, each
    up to a cell from the true edge (its outermost cell, or the next one when the riser's
    points block it, :data:`EDGE_CELLS`); the tread is the least-squares spacing of those edges
    over the flight's ``risers - 2`` tread steps (the top level's front with a shadowed back:
    one more), so it is known to within a cell over that span. The norm's ranges (tread, step
    rule) are checked with this much slack: a regular flight within them is not refused for
    where the grid cut its edges. Metres.

    Args:
        risers: the flight's risers (at least ``norms.MIN_STAIR_RISERS``).
        res: the grid's cell edge, metres.

    Returns:
        ``res / max(1, risers - 2)``, metres (at least 1e-9).
    """
    return max(res / max(1, risers - 2), 1e-9)


def near_edge(
    top: ScanLevel, plan: FloorPlan, run: np.ndarray, side: np.ndarray, span, start: float
) -> float:
    """Where a level begins along a flight: its first cells beyond a place within its width.

    Args:
        top: the level.
        plan: the floor plan (its grid).
        run: (2,) the flight's unit climb direction.
        side: (2,) the unit direction across it.
        span: (least, most) across ``side`` of the flight's width, metres.
        start: the place along ``run`` looked beyond, metres.

    Returns:
        The centre of ``top``'s first cells along ``run`` beyond ``start`` within ``span``,
        metres along ``run``; inf when none.
    """
    along, _ = _cells_beyond(top, plan, (run, side), span, start)
    return float(along.min()) if along.size else math.inf


def rim_edge(
    top: ScanLevel, plan: FloorPlan, run: np.ndarray, side: np.ndarray, span, start: float
) -> float:
    """Where a level begins along a flight, the median over the flight's width: per strip one
    cell wide across ``side``, its first cell beyond ``start``. A cell-stepped edge or a cell
    of the level beside the flight's side (generated hall 1069: floor 8 cm nearer than the
    rim, beside the top tread) moves a few strips, not the median.

    Args:
        top: the level.
        plan: the floor plan (its grid).
        run: (2,) the flight's unit climb direction.
        side: (2,) the unit direction across it.
        span: (least, most) across ``side`` of the flight's width, metres.
        start: the place along ``run`` looked beyond, metres.

    Returns:
        The median of the strips' first cell centres along ``run``, metres; inf when none.
    """
    along, across = _cells_beyond(top, plan, (run, side), span, start)
    if not along.size:
        return math.inf
    strip = np.round(across / plan.resolution).astype(np.int64)
    firsts = [float(along[strip == k].min()) for k in np.unique(strip)]
    return float(np.median(firsts))


def _cells_beyond(top: ScanLevel, plan: FloorPlan, axes, span, start: float):
    """A level's cell centres beyond ``start`` along a flight within its width: (along,
    across) metres on the flight's ``axes`` (run, side) (:func:`near_edge`, :func:`rim_edge`)."""
    c = cell_centres(top.cells, plan)
    along, across = c @ axes[0], c @ axes[1]
    mine = (along > start) & (across >= span[0]) & (across <= span[1])
    return along[mine], across[mine]


def _shadowed_fit(edges: np.ndarray, top_front: float, res: float) -> tuple[np.ndarray, float]:
    """A flight fitted to its treads' front edges and the top level's (a tread's back may lie
    in the shadow of the next tread or level, so it is seen shorter, never longer).

    Args:
        edges: (2 (n - 1),) each tread's first and last cell centre along the run, metres.
        top_front: the top level's first cell centre along the run, metres.
        res: a grid cell's extent along the run (:func:`cell_span`), metres.

    Returns:
        (coef: (3,) the first front edge, unused, the tread depth; dxy: the largest front
        residual or back edge seen beyond the next front, metres).
    """
    fronts = np.append(edges[0::2], top_front)
    k = np.arange(len(fronts), dtype=float)
    if not np.isfinite(top_front):
        return np.zeros(3), math.inf
    a = np.column_stack([np.ones_like(k), k])
    (first, tread), *_ = np.linalg.lstsq(a, fronts, rcond=None)
    dxy = float(np.abs(a @ np.array([first, tread]) - fronts).max())
    beyond = edges[1::2] - (first + (k[1:]) * tread - res)
    return np.array([first, 0.0, tread]), max(dxy, float(np.max(beyond, initial=0.0)))
