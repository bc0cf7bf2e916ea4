"""Grid A*: the deterministic baseline planner (agethen2018 §5.2 compares against it).

An 8-connected grid of 0.08 m cells over the floor; a cell is free when its centre keeps the body
radius of clearance from every obstacle and from the floor's edge, and a move is allowed only when
every point along it (sampled every centimetre) does too. The route is a polyline through cell
centres, from the exact start point to the exact goal point.
"""

from __future__ import annotations

import heapq
import math
import time
from dataclasses import dataclass

import numpy as np

from mjwalk._jit import njit
from mjwalk.conventions import BODY_RADIUS
from mjwalk.errors import InputError, PlanningError
from mjwalk.plan.walkpath import WalkPath
from mjwalk.world.cache import cached_array, content_key
from mjwalk.world.clearance import bilinear_at
from mjwalk.world.workplace import Workplace

#: Default grid cell size (metres), as in agethen2018.
CELL_SIZE = 0.08
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
#: The 8-connected moves (di, dj) of the grid A*.
MOVES_8 = [(1, 0), (-1, 0), (0, 1), (0, -1), (1, 1), (1, -1), (-1, 1), (-1, -1)]
#: 16-connected moves (adds the knight moves): routes at most 2.7 % longer than straight lines.
MOVES_16 = MOVES_8 + [(2, 1), (1, 2), (-1, 2), (-2, 1), (-2, -1), (-1, -2), (1, -2), (2, -1)]
_MOVES = MOVES_8
_SAMPLE_SPACING = 0.01


@dataclass
class OccupancyGrid:
    """Cells over the floor: centres ``x0 + i * cell``, ``y0 + j * cell`` (metres) and, for each
    move ``offsets[k]`` = (di, dj), whether it is collision-free from each cell
    (``moves[k, j, i]``).
    """

    x0: float
    y0: float
    cell: float
    radius: float
    free: np.ndarray
    moves: np.ndarray
    offsets: tuple[tuple[int, int], ...] = tuple(MOVES_8)

    @property
    def shape(self) -> tuple[int, int]:
        return self.free.shape

    def centre(self, j: int, i: int) -> np.ndarray:
        return np.array([self.x0 + i * self.cell, self.y0 + j * self.cell])

    def index(self, xy: np.ndarray) -> tuple[int, int]:
        """(row j, column i) of the cell containing ``xy``, clipped to the grid."""
        ny, nx = self.free.shape
        i = int(np.clip(np.rint((xy[0] - self.x0) / self.cell), 0, nx - 1))
        j = int(np.clip(np.rint((xy[1] - self.y0) / self.cell), 0, ny - 1))
        return j, i


def shortfall_bound(route_length, cell: float = CELL_SIZE):
    """The lowest ``walk / route - 1`` the grid's discretisation allows a walk between the
    ends of a grid-A* route of ``route_length`` metres (scalar or array), when a straight free
    line joins those ends: the walk is at least that line's length L, and the route at most
    :data:`OCTILE_RATIO` * L + :data:`END_EXCESS` * ``cell`` (so the bound is
    ``(1 - END_EXCESS * cell / route_length) / OCTILE_RATIO - 1``: -8.9 % for a 2.4 m route on
    8 cm cells, -7.6 % for long ones). Around obstacles the route's cells keep their own
    clearance, which this does not bound."""
    length = np.asarray(route_length, dtype=float)
    return (1.0 - END_EXCESS * cell / length) / OCTILE_RATIO - 1.0


def segment_is_free(workplace: Workplace, a: np.ndarray, b: np.ndarray, radius: float) -> bool:
    """Whether every point of the segment a-b keeps ``radius`` of walking clearance."""
    n = max(2, int(np.ceil(np.linalg.norm(b - a) / _SAMPLE_SPACING)) + 1)
    pts = a + np.linspace(0.0, 1.0, n)[:, None] * (b - a)
    return bool(np.all(workplace.walk_clearance(pts) >= radius))


def _grid_origin(workplace: Workplace, cell: float) -> tuple[float, float]:
    """Centre (x, y) of the grid's first cell, metres: the cells are centred on the floor."""
    xmin, ymin, xmax, ymax = workplace.floor_bounds
    nx = int(np.floor((xmax - xmin) / cell))
    ny = int(np.floor((ymax - ymin) / cell))
    return xmin + 0.5 * (xmax - xmin - (nx - 1) * cell), ymin + 0.5 * (
        ymax - ymin - (ny - 1) * cell
    )


@njit
def _walk_min(values, x0, y0, res, bounds, xs, ys, ts, sx, sy, js, is_, radius):
    """For each cell (js[c], is_[c]): whether every point ``centre + ts[s] * (sx, sy)`` keeps
    ``radius`` of walking clearance, with the arithmetic of :meth:`ClearanceField.__call__`
    (bilinear) and :meth:`Workplace.edge_distance`; stops at a cell's first failing point."""
    out = np.empty(js.shape[0], dtype=np.bool_)
    for c in range(js.shape[0]):
        cx, cy = xs[is_[c]], ys[js[c]]
        ok = True
        for s in range(ts.shape[0]):
            x = cx + ts[s] * sx
            y = cy + ts[s] * sy
            edge = min(x - bounds[0], bounds[2] - x, y - bounds[1], bounds[3] - y)
            if edge < radius:
                ok = False
                break
            v = bilinear_at(values, x0, y0, res, x, y)
            if v < radius:
                ok = False
                break
        out[c] = ok
    return out


def occupancy_grid(
    workplace: Workplace,
    cell: float = CELL_SIZE,
    radius: float = BODY_RADIUS,
    moves: list[tuple[int, int]] = MOVES_8,
) -> OccupancyGrid:
    """Build the free-cell mask and the validity of each of ``moves`` for ``workplace``.

    A cell is free when the walking clearance at its centre is at least ``radius``; a move
    when every point along it, every centimetre, is. The points are sampled only where the
    clearance field leaves the answer open: the bilinear field is at most sqrt(2)-Lipschitz
    (its nodes hold a 1-Lipschitz distance, so each partial derivative is at most 1) and the
    edge distance 1-Lipschitz, so a move of length L whose two end cells both keep
    ``radius + sqrt(2) L / 2`` is free throughout. Only the cells near obstacles and the
    floor's edge are sampled, with the same points and arithmetic as before (the same grid).
    """
    xmin, ymin, xmax, ymax = workplace.floor_bounds
    nx = int(np.floor((xmax - xmin) / cell))
    ny = int(np.floor((ymax - ymin) / cell))
    x0, y0 = _grid_origin(workplace, cell)
    xs = x0 + cell * np.arange(nx)
    ys = y0 + cell * np.arange(ny)
    gx, gy = np.meshgrid(xs, ys)
    centres = np.stack([gx, gy], axis=-1)
    walk = workplace.walk_clearance(centres)
    del gx, gy, centres
    free = walk >= radius
    f = workplace.clearance
    bounds = np.asarray(workplace.floor_bounds, dtype=float)
    valid = np.zeros((len(moves), ny, nx), dtype=bool)
    for k, (di, dj) in enumerate(moves):
        step = np.array([di, dj], dtype=float) * cell
        length = float(np.linalg.norm(step))
        n = int(np.ceil(length / _SAMPLE_SPACING)) + 1
        ts = np.linspace(0.0, 1.0, n)
        # the cells whose move target exists on the grid
        src = (slice(max(0, -dj), ny - max(0, dj)), slice(max(0, -di), nx - max(0, di)))
        dst = (slice(max(0, dj), ny - max(0, -dj)), slice(max(0, di), nx - max(0, -di)))
        inner = np.zeros((ny, nx), dtype=bool)
        inner[src] = True
        sure = np.zeros((ny, nx), dtype=bool)
        sure[src] = np.minimum(walk[src], walk[dst]) >= radius + _SQRT2 * length / 2 + 1e-9
        open_ = free & inner & ~sure
        js, is_ = np.nonzero(open_)
        ok = sure & free
        ok[js, is_] = _walk_min(
            f.values, f.x0, f.y0, f.resolution, bounds, xs, ys, ts, step[0], step[1], js, is_,
            float(radius),
        )  # fmt: skip
        valid[k] = ok
    return OccupancyGrid(x0, y0, cell, radius, free, valid, tuple(moves))


def occupancy_grid_sampled(
    workplace: Workplace,
    cell: float = CELL_SIZE,
    radius: float = BODY_RADIUS,
    moves: list[tuple[int, int]] = MOVES_8,
) -> OccupancyGrid:
    """:func:`occupancy_grid` the way it was first written (kept as the reference of tests and
    ``benchmarks/bench_scale.py``): every move of every cell sampled every centimetre."""
    xmin, ymin, xmax, ymax = workplace.floor_bounds
    nx = int(np.floor((xmax - xmin) / cell))
    ny = int(np.floor((ymax - ymin) / cell))
    x0 = xmin + 0.5 * (xmax - xmin - (nx - 1) * cell)
    y0 = ymin + 0.5 * (ymax - ymin - (ny - 1) * cell)
    gx, gy = np.meshgrid(x0 + cell * np.arange(nx), y0 + cell * np.arange(ny))
    centres = np.stack([gx, gy], axis=-1)
    free = workplace.walk_clearance(centres) >= radius
    valid = np.zeros((len(moves), ny, nx), dtype=bool)
    for k, (di, dj) in enumerate(moves):
        step = np.array([di, dj], dtype=float) * cell
        n = int(np.ceil(np.linalg.norm(step) / _SAMPLE_SPACING)) + 1
        ts = np.linspace(0.0, 1.0, n)
        pts = centres[:, :, None, :] + ts[None, None, :, None] * step
        ok = workplace.walk_clearance(pts).min(axis=-1) >= radius
        # The target cell must exist on the grid.
        if di > 0:
            ok[:, -di:] = False
        if di < 0:
            ok[:, :-di] = False
        if dj > 0:
            ok[-dj:, :] = False
        if dj < 0:
            ok[:-dj, :] = False
        valid[k] = ok & free
    return OccupancyGrid(x0, y0, cell, radius, free, valid, tuple(moves))


def _clearly_free(workplace: Workplace, xy: np.ndarray, radius: float) -> bool:
    """Whether the walk-clearance field proves that ``xy`` keeps ``radius`` (a quick accept).

    The field's nodes hold exact walk clearances (the minimum of the footprints' signed
    distances and the distance to the floor's edge), and walk clearance is 1-Lipschitz, so at
    ``xy`` it is at least the nearest node's value minus the distance to that node.
    """
    f = workplace.walk_field()
    ny, nx = f.values.shape
    i = min(max(round((float(xy[0]) - f.x0) / f.resolution), 0), nx - 1)
    j = min(max(round((float(xy[1]) - f.y0) / f.resolution), 0), ny - 1)
    gap = math.hypot(float(xy[0]) - f.x0 - i * f.resolution, float(xy[1]) - f.y0 - j * f.resolution)
    return float(f.values[j, i]) - gap >= radius


def shared_grid(
    workplace: Workplace,
    cell: float = CELL_SIZE,
    radius: float = BODY_RADIUS,
    moves: list[tuple[int, int]] = MOVES_8,
) -> OccupancyGrid:
    """:func:`occupancy_grid`, built once per workplace, cell size, radius and moves and kept
    on the workplace (planners to several goals of one scene share it). A workplace whose
    clearance field is replaced gets a new grid."""
    cache = workplace.__dict__.setdefault("_grids", {})
    key = (float(cell), float(radius), tuple(moves), id(workplace.clearance))
    if key not in cache:
        if workplace.cache_key is None:
            cache[key] = occupancy_grid(workplace, cell, radius, moves)
        else:  # kept on disk beside the workplace's clearance field (mjwalk.world.cache)
            disk = content_key(workplace.cache_key, "grid", *key[:3])
            built: list[OccupancyGrid] = []

            def build() -> OccupancyGrid:
                if not built:
                    built.append(occupancy_grid(workplace, cell, radius, moves))
                return built[0]

            free = cached_array(disk, "free", lambda: build().free)
            valid = cached_array(disk, "moves", lambda: build().moves)
            x0, y0 = _grid_origin(workplace, cell)
            cache[key] = OccupancyGrid(x0, y0, cell, radius, free, valid, tuple(moves))
    return cache[key]


def check_endpoint(workplace: Workplace, xy: np.ndarray, radius: float, what: str) -> None:
    """Raise PlanningError when a start or goal point is off the floor, inside an obstacle or
    closer to one than the body radius."""
    if isinstance(radius, bool | str) or not (math.isfinite(radius) and radius > 0):
        raise InputError(f"body radius must be a positive number of metres, got {radius!r}")
    if _clearly_free(workplace, xy, radius):
        return
    label = f"{what} ({xy[0]:.3f}, {xy[1]:.3f})"
    if not bool(workplace.on_floor(xy)):
        b = workplace.floor_bounds
        raise PlanningError(
            f"{label} is off the floor of {workplace.name} "
            f"(x in [{b[0]:g}, {b[2]:g}], y in [{b[1]:g}, {b[3]:g}] m)"
        )
    dists: dict[str, float] = {}
    for fp in workplace.obstacles:  # a concave mesh has several pieces under one name
        d = float(fp.signed_distance(xy[None])[0])
        dists[fp.name] = min(d, dists.get(fp.name, d))
    if dists:
        nearest = min(dists, key=dists.get)
        if dists[nearest] < 0:
            raise PlanningError(f"{label} is inside obstacle {nearest!r} of {workplace.name}")
        if dists[nearest] < radius:
            raise PlanningError(
                f"{label} is {dists[nearest]:.3f} m from obstacle {nearest!r}, closer than the "
                f"body radius {radius:.3f} m"
            )
    edge = float(workplace.edge_distance(xy))
    if edge < radius:
        raise PlanningError(
            f"{label} is {edge:.3f} m from the floor's edge, closer than the body radius {radius} m"
        )


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
        start, goal: a site name, an ``"x,y"`` string or (x, y) in metres.
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

    def near_cells(p: np.ndarray) -> list[tuple[int, float]]:
        """The free centres of the 3 x 3 cells around ``p`` joined to it by a free segment
        (sampled as :func:`segment_is_free` samples it, all segments in one field lookup)."""
        j0, i0 = grid.index(p)
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
        counts = [max(2, int(np.ceil(d / _SAMPLE_SPACING)) + 1) for d in dist]
        pts = np.concatenate(
            [
                p + np.linspace(0.0, 1.0, k)[:, None] * (c - p)
                for k, c in zip(counts, ends, strict=True)
            ]
        )
        ok = workplace.walk_clearance(pts) >= radius
        seg_ok = np.logical_and.reduceat(ok, np.cumsum([0, *counts[:-1]]))
        return [
            (j * nx + i, float(d))
            for (j, i), d, good in zip(cells, dist, seg_ok, strict=True)
            if good
        ]

    start_links = near_cells(a)
    goal_links = dict(near_cells(b))
    direct = np.linalg.norm(b - a) <= 1.5 * cell and segment_is_free(workplace, a, b, radius)

    x0, y0, bx, by = float(grid.x0), float(grid.y0), float(b[0]), float(b[1])

    def h(node: int) -> float:
        if node == goal_node:
            return 0.0
        dx = abs(x0 + cell * (node % nx) - bx)
        dy = abs(y0 + cell * (node // nx) - by)
        return max(dx, dy) + (_SQRT2 - 1.0) * min(dx, dy)  # octile: admissible on the grid

    moves = grid.moves.reshape(len(_MOVES), -1).T  # (cells, moves): one row per cell
    offsets = [dj * nx + di for di, dj in _MOVES]
    costs = [cell * (_SQRT2 if di and dj else 1.0) for di, dj in _MOVES]

    g_cost = {start_node: 0.0}
    parent: dict[int, int] = {}
    heap: list[tuple[float, int, int]] = [(0.0, 0, start_node)]
    closed = set()
    counter = 1
    expansions = 0
    found = False
    while heap:
        _, _, node = heapq.heappop(heap)
        if node in closed:
            continue
        closed.add(node)
        expansions += 1
        if node == goal_node:
            found = True
            break
        if node == start_node:
            nbrs = list(start_links)
            if direct:
                nbrs.append((goal_node, float(np.linalg.norm(b - a))))
        else:
            nbrs = [
                (node + off, c)
                for off, c, ok in zip(offsets, costs, moves[node].tolist(), strict=True)
                if ok
            ]
            if node in goal_links:
                nbrs.append((goal_node, goal_links[node]))
        g0 = g_cost[node]
        for nb, c in nbrs:
            if nb in closed:
                continue
            g1 = g0 + c
            if g1 < g_cost.get(nb, math.inf):
                g_cost[nb] = g1
                parent[nb] = node
                heapq.heappush(heap, (g1 + h(nb), counter, nb))
                counter += 1
    if not found:
        raise PlanningError(
            f"goal ({b[0]:.3f}, {b[1]:.3f}) is unreachable from start ({a[0]:.3f}, {a[1]:.3f}) "
            f"in {workplace.name} with body radius {radius} m (searched {expansions} cells)"
        )
    chain = [goal_node]
    while chain[-1] != start_node:
        chain.append(parent[chain[-1]])
    chain.reverse()
    pts = np.array(
        [
            a if v == start_node else b if v == goal_node else grid.centre(v // nx, v % nx)
            for v in chain
        ]
    )
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
