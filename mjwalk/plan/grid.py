"""Grid A*: the deterministic baseline planner (agethen2018 §5.2 compares against it).

An 8-connected search over the occupancy grid (:mod:`mjwalk.plan.occupancy`: 0.08 m cells, free
where the body radius of clearance is kept, moves checked every centimetre). The route is a
polyline through cell centres, from the exact start point to the exact goal point.
"""

from __future__ import annotations

import math
import time

import numpy as np

from mjwalk._jit import njit
from mjwalk.conventions import BODY_RADIUS
from mjwalk.errors import PlanningError
from mjwalk.plan.occupancy import (
    CELL_SIZE,
    MOVES_8,
    SAMPLE_SPACING,
    OccupancyGrid,
    check_endpoint,
    occupancy_grid,
    segment_is_free,
)
from mjwalk.plan.walkpath import WalkPath
from mjwalk.world.clearance import ClearanceField, bilinear_at
from mjwalk.world.workplace import Workplace

#: Walking speed (m/s) used to time the baseline's route (median speed of the Bandai walk capture).
NOMINAL_SPEED = 1.13
_SQRT2 = math.sqrt(2.0)
#: The 8-connected (octile) metric's largest ratio to the straight-line distance:
#: max over theta of cos(theta) + (sqrt(2) - 1) sin(theta) = sqrt(4 - 2 sqrt(2)) = 1.0824,
#: 22.5 degrees off the grid's axes. A grid route between two points a straight free line joins
#: is at most this much longer than the line, plus :data:`END_EXCESS`.
OCTILE_RATIO = math.sqrt(4.0 - 2.0 * _SQRT2)
#: What linking two off-grid ends to the grid adds at most over the octile distance between
#: them, in cells (each end joins a centre of the 3 x 3 cells around it): sqrt(2) - 1. Found by
#: exhaustive search over both ends' offsets in their cells (21 x 21 each) and 61 directions of
#: the first octant at 3-60 cells; tests/plan/test_grid.py checks the bound on plan_grid.
END_EXCESS = _SQRT2 - 1.0
_MOVES = MOVES_8


def shortfall_bound(route_length, cell: float = CELL_SIZE):
    """The lowest ``walk / route - 1`` the grid's discretisation allows a walk between the
    ends of a grid-A* route of ``route_length`` metres (scalar or array), when a straight free
    line joins those ends: the walk is at least that line's length L, and the route at most
    :data:`OCTILE_RATIO` * L + :data:`END_EXCESS` * ``cell`` (so the bound is
    ``(1 - END_EXCESS * cell / route_length) / OCTILE_RATIO - 1``: -8.9 % for a 2.4 m route on
    8 cm cells, -7.6 % for long ones). Around obstacles the route's cells keep their own
    clearance, which this does not bound.

    Args:
        route_length: the grid route's length, metres (scalar or array).
        cell: the grid's cell size, metres.

    Returns:
        The bound (a fraction, same shape as ``route_length``).
    """
    length = np.asarray(route_length, dtype=float)
    return (1.0 - END_EXCESS * cell / length) / OCTILE_RATIO - 1.0


def plan_grid(
    workplace: Workplace,
    start,
    goal,
    *,
    cell: float = CELL_SIZE,
    radius: float = BODY_RADIUS,
    speed: float = NOMINAL_SPEED,
    grid: OccupancyGrid | None = None,
) -> WalkPath:
    """Shortest 8-connected grid route from ``start`` to ``goal`` (grid A*).

    Args:
        workplace: the scene.
        start: a site name, an ``"x,y"`` string or (x, y) in metres.
        goal: the same for the goal.
        cell: grid cell size, metres.
        radius: body radius, metres: the route keeps this clearance from obstacles and the
            floor's edge.
        speed: walking speed (m/s) used to give the route its times.
        grid: a prebuilt :func:`occupancy_grid` (to plan many routes in one scene).

    Returns:
        A WalkPath through the start point, cell centres and the goal point (no steps: the
        baseline has no gait); ``meta`` records expansions and planning time.

    Raises:
        PlanningError: start or goal off the floor, in or too near an obstacle, or unreachable.
    """
    t0 = time.perf_counter()
    a = workplace.point(start)
    b = workplace.point(goal)
    check_endpoint(workplace, a, radius, "start")
    check_endpoint(workplace, b, radius, "goal")
    if grid is None or grid.cell != cell or grid.radius != radius:
        grid = occupancy_grid(workplace, cell, radius)
    if grid.offsets != tuple(MOVES_8):  # the octile heuristic is admissible for 8 moves only
        grid = occupancy_grid(workplace, cell, radius, MOVES_8)
    ny, nx = grid.shape
    n = nx * ny
    start_node, goal_node = n, n + 1
    start_links = _near_cells(workplace, grid, a, radius)
    goal_links = dict(_near_cells(workplace, grid, b, radius))
    direct = np.linalg.norm(b - a) <= 1.5 * cell and segment_is_free(workplace, a, b, radius)
    if direct:
        start_links.append((goal_node, float(np.linalg.norm(b - a))))
    parent, expansions, found = _astar(grid, b, start_links, goal_links)
    if not found:
        raise PlanningError(
            f"goal ({b[0]:.3f}, {b[1]:.3f}) is unreachable from start ({a[0]:.3f}, {a[1]:.3f}) "
            f"in {workplace.name} with body radius {radius} m (searched {expansions} cells)"
        )
    pts = _route_points(parent, start_node, goal_node, grid, a, b)
    seg = np.diff(pts, axis=0)
    yaw = np.arctan2(seg[:, 1], seg[:, 0])
    yaw = np.unwrap(np.append(yaw, yaw[-1])) if len(yaw) else np.zeros(1)
    dist = np.concatenate([[0.0], np.cumsum(np.linalg.norm(seg, axis=1))])
    return WalkPath(
        t=dist / speed,
        xy=pts,
        yaw=yaw,
        meta={
            "planner": "grid_astar",
            "cell": cell,
            "radius": radius,
            "expansions": expansions,
            "seconds": time.perf_counter() - t0,
        },
    ).stamp_scene(workplace)


def _route_points(parent, start_node, goal_node, grid: OccupancyGrid, a, b) -> np.ndarray:
    """The route's points (n, 2), metres: ``a``, the centres (x0 + i·cell, y0 + j·cell) of the
    ``grid`` cells on the chain of ``parent`` links back from ``goal_node`` to ``start_node``,
    in order, and ``b`` (:func:`_chain`)."""
    chain = _chain(parent, start_node, goal_node)
    inner = chain[1:-1]  # the cells between the two ends (node index j * nx + i)
    nx = grid.shape[1]
    pts = np.empty((len(chain), 2))
    pts[0], pts[-1] = a, b
    pts[1:-1, 0] = grid.x0 + (inner % nx) * grid.cell
    pts[1:-1, 1] = grid.y0 + (inner // nx) * grid.cell
    return pts


@njit
def _chain(parent, start_node, goal_node):
    """The nodes from ``start_node`` to ``goal_node`` along the ``parent`` links (int64)."""
    n = 1
    v = goal_node
    while v != start_node:
        v = parent[v]
        n += 1
    out = np.empty(n, dtype=np.int64)
    v = goal_node
    for k in range(n - 1, -1, -1):
        out[k] = v
        v = parent[v]
    return out


def _near_cells(
    workplace: Workplace, grid: OccupancyGrid, p: np.ndarray, radius: float
) -> list[tuple[int, float]]:
    """The free centres (node index, distance in metres) of the 3 x 3 cells around ``p``
    joined to it by a free segment (sampled as :func:`segment_is_free` samples it). With a
    :class:`~mjwalk.world.clearance.ClearanceField` the compiled :func:`_near_kernel` tests
    them (the same samples, lookups and distances to the last bit, stopping at a segment's
    first failing sample); another clearance model: all segments in one NumPy lookup."""
    ny, nx = grid.shape
    j0, i0 = grid.index(p)
    c = workplace.clearance
    if isinstance(c, ClearanceField):
        nodes = np.empty(9, dtype=np.int64)
        dists = np.empty(9)
        bounds = np.asarray(workplace.floor_bounds, dtype=float)
        k = _near_kernel(
            grid.free, float(grid.x0), float(grid.y0), float(grid.cell), j0, i0,
            float(p[0]), float(p[1]), c.values, float(c.x0), float(c.y0), float(c.resolution),
            bounds, float(radius), SAMPLE_SPACING, nodes, dists,
        )  # fmt: skip
        return [(int(nodes[m]), float(dists[m])) for m in range(k)]
    cells = [
        (j, i)
        for j in range(max(0, j0 - 1), min(ny, j0 + 2))
        for i in range(max(0, i0 - 1), min(nx, i0 + 2))
        if grid.free[j, i]
    ]
    if not cells:
        return []
    ends = np.array([grid.centre(j, i) for j, i in cells])
    dist = np.linalg.norm(ends - p, axis=1)
    counts = [max(2, int(np.ceil(d / SAMPLE_SPACING)) + 1) for d in dist]
    # each segment's samples p + s (c - p), s = linspace(0, 1, k): all segments at once
    s = np.concatenate([_unit_steps(k) for k in counts])
    pts = p + s[:, None] * np.repeat(ends - p, counts, axis=0)
    ok = workplace.walk_clearance(pts) >= radius
    seg_ok = np.logical_and.reduceat(ok, np.cumsum([0, *counts[:-1]]))
    return [
        (j * nx + i, float(d)) for (j, i), d, good in zip(cells, dist, seg_ok, strict=True) if good
    ]


@njit
def _near_kernel(free, gx0, gy0, cell, j0, i0, px, py, values, fx0, fy0, res, bounds, radius,
                 spacing, nodes, dists):  # fmt: skip
    """:func:`_near_cells`' test of the free cells of the 3 x 3 around cell (``j0``, ``i0``),
    row by row, for the point (``px``, ``py``): each centre's distance as ``np.linalg.norm``
    sums it, its segment sampled at ``np.linspace(0, 1, k)`` (k as :func:`_near_cells` counts
    them), each sample's walk clearance as ``Workplace.walk_clearance`` computes it (the field's
    bilinear lookup, :func:`~mjwalk.world.clearance.bilinear_at`, and the distance to the
    floor's ``bounds``, xmin, ymin, xmax, ymax); a segment fails at its first sample short of
    ``radius``. Writes the joined cells' node indices and distances (m) into ``nodes`` and
    ``dists`` and returns how many there are."""
    ny, nx = free.shape
    xmin, ymin, xmax, ymax = bounds[0], bounds[1], bounds[2], bounds[3]
    m = 0
    for j in range(max(0, j0 - 1), min(ny, j0 + 2)):
        for i in range(max(0, i0 - 1), min(nx, i0 + 2)):
            if not free[j, i]:
                continue
            ex = (gx0 + i * cell) - px
            ey = (gy0 + j * cell) - py
            d = math.sqrt(ex * ex + ey * ey)
            k = max(2, math.ceil(d / spacing) + 1)
            step = 1.0 / (k - 1)  # np.linspace(0, 1, k): arange(k) * step, its last 1.0
            good = True
            for a in range(k):
                s = 1.0 if a == k - 1 else a * step
                x = px + s * ex
                y = py + s * ey
                clear = bilinear_at(values, fx0, fy0, res, x, y)
                edge = min(x - xmin, xmax - x, y - ymin, ymax - y)
                if not min(clear, edge) >= radius:
                    good = False
                    break
            if good:
                nodes[m] = j * nx + i
                dists[m] = d
                m += 1
    return m


def _unit_steps(k: int) -> np.ndarray:
    """``np.linspace(0, 1, k)``, kept per ``k`` (read-only): a route's ends sample their
    segments with a handful of sample counts."""
    steps = _UNIT_STEPS.get(k)
    if steps is None:
        steps = _UNIT_STEPS[k] = np.linspace(0.0, 1.0, k)
        steps.setflags(write=False)
    return steps


#: :func:`_unit_steps` by sample count.
_UNIT_STEPS: dict[int, np.ndarray] = {}


def _astar(
    grid: OccupancyGrid,
    b: np.ndarray,
    start_links: list[tuple[int, float]],
    goal_links: dict[int, float],
) -> tuple[np.ndarray, int, bool]:
    """A* over the grid's cells, from the start node (index cells) to the goal node (cells + 1)
    at ``b`` (x, y, metres), the start joined to ``start_links`` (node, metres; the goal node
    among them where the straight line is free) and the cells of ``goal_links`` to the goal.
    Returns each reached node's parent (-1: none), the number of expansions and whether the
    goal was reached (the compiled :func:`_astar_kernel`)."""
    nx = grid.shape[1]
    cell = grid.cell
    moves = np.ascontiguousarray(grid.moves.reshape(len(_MOVES), -1))  # (moves, cells)
    offsets = np.array([dj * nx + di for di, dj in _MOVES], dtype=np.int64)
    costs = np.array([cell * (_SQRT2 if di and dj else 1.0) for di, dj in _MOVES])
    s_nodes = np.array([v for v, _ in start_links], dtype=np.int64)
    s_costs = np.array([c for _, c in start_links], dtype=float)
    g_nodes = np.array(list(goal_links), dtype=np.int64)
    g_costs = np.array(list(goal_links.values()), dtype=float)
    xy = np.array([float(grid.x0), float(grid.y0), float(b[0]), float(b[1]), float(cell)])
    parent, expansions, found = _astar_kernel(
        moves, offsets, costs, s_nodes, s_costs, g_nodes, g_costs, xy, nx
    )
    return parent, int(expansions), bool(found)


@njit
def _astar_kernel(moves, offsets, costs, s_nodes, s_costs, g_nodes, g_costs, xy, nx):
    """The grid A* loop: an open list ordered by (f, push count) as ``heapq`` orders the
    tuples (f, count, node) (the count is unique, so every correct heap pops the same order),
    the octile heuristic to ``xy[2:4]`` (admissible on the grid), arithmetic in the order of
    the original Python loop so the routes are the same to the last bit."""
    n = moves.shape[1]
    start_node, goal_node = n, n + 1
    x0, y0, bx, by, cell = xy[0], xy[1], xy[2], xy[3], xy[4]
    g_cost = np.full(n + 2, np.inf)
    parent = np.full(n + 2, -1, dtype=np.int64)
    closed = np.zeros(n + 2, dtype=np.bool_)
    cap = 1024
    hf = np.empty(cap)
    hc = np.empty(cap, dtype=np.int64)
    hn = np.empty(cap, dtype=np.int64)
    size = 1
    hf[0], hc[0], hn[0] = 0.0, 0, start_node
    g_cost[start_node] = 0.0
    counter = 1
    expansions = 0
    nb_nodes = np.empty(len(offsets) + len(s_nodes) + 1, dtype=np.int64)
    nb_costs = np.empty(len(offsets) + len(s_nodes) + 1)
    while size > 0:
        node = hn[0]
        size -= 1  # pop: the last entry sifts down from the root
        if size > 0:
            _sift_down(hf, hc, hn, size, hf[size], hc[size], hn[size])
        if closed[node]:
            continue
        closed[node] = True
        expansions += 1
        if node == goal_node:
            return parent, expansions, True
        m = 0
        if node == start_node:
            for k in range(len(s_nodes)):
                nb_nodes[m], nb_costs[m] = s_nodes[k], s_costs[k]
                m += 1
        else:
            for k in range(len(offsets)):
                if moves[k, node]:
                    nb_nodes[m], nb_costs[m] = node + offsets[k], costs[k]
                    m += 1
            for k in range(len(g_nodes)):
                if g_nodes[k] == node:
                    nb_nodes[m], nb_costs[m] = goal_node, g_costs[k]
                    m += 1
        g0 = g_cost[node]
        for k in range(m):
            nb = nb_nodes[k]
            if closed[nb]:
                continue
            g1 = g0 + nb_costs[k]
            if g1 < g_cost[nb]:
                g_cost[nb] = g1
                parent[nb] = node
                if nb == goal_node:
                    h = 0.0
                else:
                    dx = abs(x0 + cell * (nb % nx) - bx)
                    dy = abs(y0 + cell * (nb // nx) - by)
                    h = max(dx, dy) + (_SQRT2 - 1.0) * min(dx, dy)
                if size == cap:
                    cap *= 2
                    hf, hc, hn = _grown(hf, cap), _grown(hc, cap), _grown(hn, cap)
                _sift_up(hf, hc, hn, size, g1 + h, counter, nb)
                size += 1
                counter += 1
    return parent, expansions, False


@njit
def _grown(a, cap):
    """``a`` copied into an array of ``cap`` entries (the open list's room, doubled)."""
    out = np.empty(cap, dtype=a.dtype)
    out[: len(a)] = a
    return out


@njit
def _sift_up(hf, hc, hn, i, f, c, v):
    """Put the entry (f, c, v) at slot ``i`` of the open list and move it up to its place."""
    while i > 0:
        up = (i - 1) >> 1
        if hf[up] < f or (hf[up] == f and hc[up] < c):
            break
        hf[i], hc[i], hn[i] = hf[up], hc[up], hn[up]
        i = up
    hf[i], hc[i], hn[i] = f, c, v


@njit
def _sift_down(hf, hc, hn, size, f, c, v):
    """Put the entry (f, c, v) at the root of the open list of ``size`` entries and move it
    down to its place."""
    i = 0
    while True:
        child = 2 * i + 1
        if child >= size:
            break
        right = child + 1
        if right < size and (
            hf[right] < hf[child] or (hf[right] == hf[child] and hc[right] < hc[child])
        ):
            child = right
        if f < hf[child] or (f == hf[child] and c < hc[child]):
            break
        hf[i], hc[i], hn[i] = hf[child], hc[child], hn[child]
        i = child
    hf[i], hc[i], hn[i] = f, c, v
