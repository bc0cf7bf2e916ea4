"""Obstacle-aware distance-to-goal for the hybrid A*: a 2-D Dijkstra over the occupancy grid.

:func:`walkable_distance` is the planner's: the route a walker's sampled steps can take. A grid
cell is free where its centre keeps the body radius (:mod:`mjwalk.plan.occupancy`), but every
pelvis sample of a step must keep the body radius plus the safety margin
(:data:`~mjwalk.plan.options.SAFETY_MARGIN`), and the pelvis sways to either side of the line
its steps follow by about :data:`PELVIS_SWAY`. A passage whose clearance lies between the two
(the shipped station's 0.58 m gap between trolley and car: 0.288 m at its middle) is a route
for the grid but one the sampled steps rarely get through: a field through it draws the search
into it and most of the expansions go to searches that are thrown away (issue 47's planning
cost, ``benchmarks/bench_levels.py``). The planner's field therefore routes through passages
that keep body radius + margin + sway wherever such a route reaches the goal; a cell only
tight passages reach has the way out of them to the nearest such route (a tight pocket beside
a roomy route does not draw the search in), and where the tight routes reach the goal without
meeting a roomy one (a goal in a tight spot) the field is the body radius's.
"""

from __future__ import annotations

import functools
import math
import weakref
from dataclasses import dataclass

import numpy as np
from scipy.sparse import csr_matrix
from scipy.sparse.csgraph import dijkstra

from mjwalk._jit import njit
from mjwalk.gait.subjects import REAL_FIGURES
from mjwalk.plan.occupancy import OccupancyGrid

#: The pelvis's lateral sway about the line its steps follow (m): the median of the largest
#: pelvis distance from the step's chord over 1332 steps of the Bandai-Namco motion dataset's
#: `walk` clips (Kobayashi et al. 2023, arXiv:2306.08861; ``mjwalk.gait.subjects.REAL_FIGURES``;
#: about a third of the 7-10 cm adult step width, Perry & Burnfield 2010, ch. 1).
PELVIS_SWAY = REAL_FIGURES["walk"]["sway"][0]


@functools.lru_cache(maxsize=8)
def grid_excess(offsets: tuple) -> float:
    """Largest ratio of the shortest route over grid moves ``offsets`` to the straight line
    (1.0824 for 8 moves, 1.0263 for 16). Dividing grid distances by it keeps them admissible.

    Args:
        offsets: the grid moves (di, dj), as a tuple (hashable: the result is cached).

    Returns:
        The worst route-to-straight-line ratio (>= 1).
    """
    vec = np.array(offsets, dtype=float)
    vec = vec[np.argsort(np.arctan2(vec[:, 1], vec[:, 0]))]
    worst = 1.0
    for m1, m2 in zip(vec, np.roll(vec, -1, axis=0), strict=True):
        # Directions between two neighbouring moves are made of those two moves.
        basis = np.column_stack([m1, m2])
        for t in np.linspace(0.0, 1.0, 65):
            u = (1 - t) * m1 / np.linalg.norm(m1) + t * m2 / np.linalg.norm(m2)
            a, b = np.linalg.solve(basis, u / np.linalg.norm(u))
            worst = max(worst, a * np.linalg.norm(m1) + b * np.linalg.norm(m2))
    return float(worst)


@njit
def _sight_cells(free, gi, gj):
    """(ny, nx) bool: whether the straight line from each free cell's centre to cell (gj, gi)
    (the goal's) runs through free cells only, sampled every half cell (the cells are free
    where they keep the body radius: the walker sees and can walk straight to the goal)."""
    ny, nx = free.shape
    out = np.zeros((ny, nx), dtype=np.bool_)
    for j in range(ny):
        for i in range(nx):
            if not free[j, i]:
                continue
            dx = gi - i
            dy = gj - j
            n = int(2 * max(abs(dx), abs(dy)))
            ok = True
            for k in range(1, n):
                t = k / n
                if not free[int(j + t * dy + 0.5), int(i + t * dx + 0.5)]:  # (both >= 0)
                    ok = False
                    break
            out[j, i] = ok
    return out


@dataclass
class GoalDistance:
    """Walking distance (metres) from every grid cell to the goal centre, around obstacles.

    ``cells[j, i]`` is the 8-connected shortest route from cell (j, i) into the goal area plus
    the straight line from there to the goal centre (``inf`` where the goal cannot be reached).
    :meth:`__call__` turns it into a lower bound of the true distance from any point to the
    goal centre (agethen2018 §4.2 uses the straight-line distance to the centre).
    """

    grid: OccupancyGrid
    goal: np.ndarray
    tolerance: float
    cells: np.ndarray

    def __post_init__(self) -> None:
        self._excess = grid_excess(tuple(self.grid.offsets))
        ny, nx = self.grid.free.shape
        at = np.rint((self.goal - (self.grid.x0, self.grid.y0)) / self.grid.cell)
        gi, gj = (int(v) for v in np.clip(at, 0, (nx - 1, ny - 1)))
        # the sight flags and the flat bounds depend on the grid, the cells and the goal's cell
        # only: the planners of one goal (an operator's each) share them
        key = (id(self.grid), id(self.cells), gi, gj)
        hit = _SIGHTS.get(key)
        if hit is not None and hit[0]() is self.grid and hit[1] is self.cells:
            self.in_sight, self._scaled = hit[2], hit[3]
        else:
            self.in_sight = _sight_cells(self.grid.free, gi, gj)
            # flat, for one gather per lookup: the bounds, then the sight flags (flat_bound)
            self._scaled = np.concatenate(
                [(self.cells / self._excess).ravel(), self.in_sight.ravel().astype(float)]
            )
            if self._scaled.nbytes <= _SIGHTS_BYTES:
                self.in_sight.setflags(write=False)
                self._scaled.setflags(write=False)
                while len(_SIGHTS) >= _SIGHTS_KEPT:
                    _SIGHTS.pop(next(iter(_SIGHTS)))
                _SIGHTS[key] = (weakref.ref(self.grid), self.cells, self.in_sight, self._scaled)
        self._origin = np.array([self.grid.x0, self.grid.y0])
        self._top = np.array([nx - 1.0, ny - 1.0])

    def flat_bound(self) -> np.ndarray:
        """Grid distances divided by the worst excess, flat (row-major over (ny, nx)): the
        cell term of :meth:`__call__`, for compiled lookups (:mod:`mjwalk.plan.stepcheck`);
        followed by the ny·nx flags of :attr:`in_sight` (1.0 or 0.0, same order).

        Returns:
            (2·ny·nx,) the scaled grid distances (metres), then the sight flags.
        """
        return self._scaled

    def sees(self, xy: np.ndarray) -> bool:
        """Whether the goal is in sight from ``xy`` (the nearest cell's :attr:`in_sight`).

        Args:
            xy: (2,) a point, metres, world frame.

        Returns:
            Whether the goal is in sight from the nearest cell.
        """
        j, i = self.grid.index(np.asarray(xy, dtype=float))
        return bool(self.in_sight[j, i])

    def reachable(self, xy: np.ndarray) -> bool:
        """Whether a route leads from the cell containing ``xy`` to the goal.

        Args:
            xy: (2,) a point, metres, world frame.

        Returns:
            Whether the nearest cell's grid distance is finite.
        """
        j, i = self.grid.index(np.asarray(xy, dtype=float))
        return bool(np.isfinite(self.cells[j, i]))

    def __call__(self, xy: np.ndarray) -> np.ndarray:
        """Admissible distance to the goal centre (metres) at points (..., 2).

        max(Euclidean distance to the goal centre, grid distance of the point's cell divided by
        the worst 8-connected excess, minus the point's offset from its cell centre).
        """
        xy = np.asarray(xy, dtype=float)
        g = self.grid
        f = np.rint((xy - self._origin) / g.cell)
        ij = np.minimum(np.maximum(f, 0.0, out=f), self._top, out=f).astype(np.intp)
        d = xy - (self._origin + ij * g.cell)
        offset = np.hypot(d[..., 0], d[..., 1])
        grid_bound = self._scaled[ij[..., 1] * g.free.shape[1] + ij[..., 0]] - offset
        euclid = np.hypot(xy[..., 0] - self.goal[0], xy[..., 1] - self.goal[1])
        return np.maximum(euclid, grid_bound)


#: :class:`GoalDistance`'s sight flags and flat bounds, by grid, cells and goal cell (the cells
#: held: their id stays theirs while the entry lives; the grid weakly); the last few, and only
#: grids up to :data:`_SIGHTS_BYTES` of flat bounds, a memory bound (the station's: 0.12 MB).
_SIGHTS: dict[tuple[int, ...], tuple[weakref.ref, np.ndarray, np.ndarray, np.ndarray]] = {}
_SIGHTS_KEPT = 8
_SIGHTS_BYTES = 2 * 2**20


#: Distance fields already computed, by grid, goal and the set of goal cells (a field depends on
#: the tolerance only through which cell centres it takes in, so the operators of a population,
#: whose stand zones differ by millimetres, share one). The grid is held weakly; the oldest
#: fields go first beyond :data:`_FIELDS_BYTES` (a 100 m hall's field alone is 200 MB: such
#: fields are not kept).
_FIELDS: dict[tuple, tuple[weakref.ref, np.ndarray]] = {}
_FIELDS_BYTES = 64 * 2**20
#: :func:`_field`'s keys of :data:`_FIELDS` by grid, goal and tolerance (the grid weakly); the
#: last few.
_FIELD_KEYS: dict[tuple[int, float, float, float], tuple[weakref.ref, tuple]] = {}
_FIELD_KEYS_KEPT = 64


def goal_distance(grid: OccupancyGrid, goal: np.ndarray, tolerance: float) -> GoalDistance:
    """Route length from every cell to the goal centre (Dijkstra, scipy.sparse.csgraph).

    The cells inside the goal area are joined to a virtual goal node by their straight-line
    distance to the goal centre; Dijkstra runs from that node over the reversed move graph.
    The field of the same grid, goal and goal cells is computed once per process.

    Args:
        grid: the occupancy grid (16-connected for the planner).
        goal: (2,) the goal centre, metres, world frame.
        tolerance: the goal area's radius, metres (cells within it join the goal node).

    Returns:
        The goal's :class:`GoalDistance` field (shared per grid, goal and goal cells).
    """
    return GoalDistance(grid, np.asarray(goal, float), tolerance, _field(grid, goal, tolerance))


def walkable_distance(
    grid: OccupancyGrid, roomy: OccupancyGrid, goal: np.ndarray, tolerance: float
) -> GoalDistance:
    """:func:`goal_distance` along passages the sampled steps get through (module doc).

    Args:
        grid: the body radius's occupancy grid (16-connected for the planner).
        roomy: the same cells and moves keeping body radius + safety margin + pelvis sway
            (:data:`PELVIS_SWAY`).
        goal: (2,) the goal centre, metres, world frame.
        tolerance: the goal area's radius, metres (cells within it join the goal node).

    Returns:
        A :class:`GoalDistance` on ``grid`` (its sight flags ``grid``'s) whose cells hold the
        route length over ``roomy`` where that reaches the goal; elsewhere the route over
        ``grid`` to the nearest such cell and on from there; ``grid``'s own field where no
        such route meets one.
    """
    cells = _field(grid, goal, tolerance)
    if roomy is not grid and roomy.free.shape == grid.free.shape:
        wide = _field(roomy, goal, tolerance)
        key = (id(grid), id(wide))
        hit = _WALKABLE.get(key)
        if hit is not None and hit[0]() is grid and hit[1] is wide:
            cells = hit[2]
        elif np.isfinite(wide).any():
            reach = np.isfinite(wide)
            out = _dijkstra_field(grid, np.where(reach, wide, 0.0), reach)
            # (a cell whose tight routes reach the goal without meeting a roomy one: its own)
            cells = np.where(reach, wide, np.where(np.isfinite(out), out, cells))
            cells.setflags(write=False)
            while len(_WALKABLE) >= _WALKABLE_KEPT:
                _WALKABLE.pop(next(iter(_WALKABLE)))
            _WALKABLE[key] = (weakref.ref(grid), wide, cells)
    return GoalDistance(grid, np.asarray(goal, float), tolerance, cells)


#: :func:`walkable_distance`'s fields, by grid and roomy field (kept while that is in
#: :data:`_FIELDS`: the entry holds it); the last few, a memory bound.
_WALKABLE: dict[tuple[int, int], tuple[weakref.ref, np.ndarray, np.ndarray]] = {}
_WALKABLE_KEPT = 16


def _field(grid: OccupancyGrid, goal: np.ndarray, tolerance: float) -> np.ndarray:
    """:func:`goal_distance`'s cells (ny, nx), metres (``inf``: no route), kept per grid, goal
    and goal cells (and by grid, goal and tolerance, looked up before the goal cells are
    found: that takes a whole-grid distance, 0.5 ms on the station's grid)."""
    quick = (id(grid), float(goal[0]), float(goal[1]), float(tolerance))
    known = _FIELD_KEYS.get(quick)
    if known is not None and known[0]() is grid:
        hit = _FIELDS.get(known[1])
        if hit is not None and hit[0]() is grid:
            return hit[1]
    ny, nx = grid.free.shape
    gx = grid.x0 + grid.cell * np.arange(nx)
    gy = grid.y0 + grid.cell * np.arange(ny)
    cx, cy = np.meshgrid(gx, gy)
    to_goal = np.hypot(cx - goal[0], cy - goal[1])
    inside = (to_goal <= max(tolerance, grid.cell)) & grid.free
    if not inside.any():  # no free cell centre in the goal area: use the nearest free cells
        j, i = grid.index(goal)
        inside = np.zeros_like(grid.free)
        inside[max(0, j - 1) : j + 2, max(0, i - 1) : i + 2] = True
        inside &= grid.free
    if not inside.any():
        return np.full((ny, nx), np.inf)
    key = (id(grid), float(goal[0]), float(goal[1]), np.packbits(inside).tobytes())
    while len(_FIELD_KEYS) >= _FIELD_KEYS_KEPT:
        _FIELD_KEYS.pop(next(iter(_FIELD_KEYS)))
    _FIELD_KEYS[quick] = (weakref.ref(grid), key)
    hit = _FIELDS.get(key)
    if hit is not None and hit[0]() is grid:
        return hit[1]
    field = _dijkstra_field(grid, to_goal, inside)
    if field.nbytes <= _FIELDS_BYTES:
        while _FIELDS and sum(f.nbytes for _, f in _FIELDS.values()) + field.nbytes > _FIELDS_BYTES:
            _FIELDS.pop(next(iter(_FIELDS)))
        _FIELDS[key] = (weakref.ref(grid), field)
    return field


def _dijkstra_field(grid: OccupancyGrid, to_goal: np.ndarray, inside: np.ndarray) -> np.ndarray:
    """The route-length field to the goal cells ``inside`` (joined to a virtual goal node by
    their distance ``to_goal`` to the goal centre, or any value to start from), with the rim of
    :func:`_rim`."""
    ny, nx = grid.free.shape
    n = nx * ny
    moves = _move_graph(grid)
    # the goal node's row (the last) after the move graph's rows: the matrix that
    # scipy's COO -> CSR conversion gives for all edges at once (columns ascending)
    cols = np.flatnonzero(inside.ravel()).astype(moves.indices.dtype)
    indptr = moves.indptr.copy()
    indptr[-1] += len(cols)
    graph = csr_matrix(
        (
            np.concatenate([moves.data, to_goal[inside]]),
            np.concatenate([moves.indices, cols]),
            indptr,
        ),
        shape=(n + 1, n + 1),
    )
    dist = dijkstra(graph, directed=True, indices=n)[:n].reshape(ny, nx)
    field = _rim(grid, dist)
    field.setflags(write=False)  # shared by every GoalDistance of these goal cells
    return field


#: The reversed move graphs of the grids seen (:func:`_move_graph`), grids held weakly, the
#: last two kept (one is about 1 MB for the station's 100 x 75 cells, 12 bytes per move).
_GRAPHS: dict[int, tuple[weakref.ref, csr_matrix]] = {}
_GRAPHS_KEPT = 2


def _move_graph(grid: OccupancyGrid) -> csr_matrix:
    """The grid's moves as a sparse (n + 1, n + 1) graph (n cells; the last row, the virtual
    goal node's, empty), reversed (:func:`_reversed_graph`). The same for every goal of the
    grid: built once per grid (building it was half of a distance field's time)."""
    hit = _GRAPHS.get(id(grid))
    if hit is not None and hit[0]() is grid:
        return hit[1]
    graph = _reversed_graph(grid)
    while len(_GRAPHS) >= _GRAPHS_KEPT:
        _GRAPHS.pop(next(iter(_GRAPHS)))
    _GRAPHS[id(grid)] = (weakref.ref(grid), graph)
    return graph


def _reversed_graph(grid: OccupancyGrid) -> csr_matrix:
    """The reversed move graph as CSR, (n + 1) nodes: row t holds the cells s from which a move
    reaches t (weight: the move's length), columns ascending; row n (the virtual goal node,
    whose edges :func:`_dijkstra_field` appends per goal) empty.

    Built in place, row by row in column order, it is the matrix a COO of every reversed edge
    gives after ``tocsr()`` (which sorts the columns of each row): the same arrays, so the same
    Dijkstra, without the COO's and the sort's ~60 MB of temporaries on a 36 x 10 m hall (they
    flushed the cache the planning after it works in)."""
    ny, nx = grid.free.shape
    n = nx * ny
    flat_moves = grid.moves.reshape(len(grid.offsets), n)
    shift = [dj * nx + di for di, dj in grid.offsets]
    # in a row t the sources s = t - shift ascend as the shifts descend
    order = sorted(range(len(shift)), key=lambda k: -shift[k])
    targets = [np.flatnonzero(flat_moves[k]) + shift[k] for k in order]
    counts = np.zeros(n + 1, dtype=np.int64)
    for t in targets:
        counts[t] += 1
    indptr = np.zeros(n + 2, dtype=np.int64)
    np.cumsum(counts, out=indptr[1:])
    nnz = int(indptr[-1])
    index_type = np.int32 if max(nnz, n + 1) < 2**31 else np.int64
    indices = np.empty(nnz, dtype=index_type)
    data = np.empty(nnz)
    fill = indptr[:-1].copy()
    for k, t in zip(order, targets, strict=True):
        at = fill[t]
        indices[at] = t - shift[k]
        di, dj = grid.offsets[k]
        data[at] = grid.cell * math.hypot(di, dj)
        fill[t] += 1
    return csr_matrix((data, indices, indptr.astype(index_type)), shape=(n + 1, n + 1))


def _rim(grid: OccupancyGrid, dist: np.ndarray) -> np.ndarray:
    """Give blocked cells next to reachable ones the route through their best neighbour.

    A cell is blocked when its *centre* lies within the body radius of an obstacle, but a
    point that the planner's continuous checks accept (a walk's end, where the next walk
    starts) may still have a blocked cell as its nearest one; without this rim it would be
    called unreachable and get an infinite heuristic. Compiled (:func:`_rim_cells`): as
    NumPy code (a shifted copy, a sum and a choice per move) it streamed some 20 MB of
    temporaries through the cache on a 36 x 10 m hall, and the search after it found its
    data evicted.
    """
    di = np.array([o[0] for o in grid.offsets], dtype=np.int64)
    dj = np.array([o[1] for o in grid.offsets], dtype=np.int64)
    steps = np.array([grid.cell * math.hypot(a, b) for a, b in grid.offsets])
    return _rim_cells(np.ascontiguousarray(dist, dtype=float), grid.free, di, dj, steps)


@njit
def _rim_cells(dist, free, di, dj, steps):
    """``dist`` with every blocked cell lowered to its in-grid neighbours' dist + move length
    (moves ``di``, ``dj``, lengths ``steps``), the neighbours' values before any lowering."""
    out = dist.copy()
    ny, nx = dist.shape
    for j in range(ny):
        for i in range(nx):
            if free[j, i]:
                continue
            best = out[j, i]
            for k in range(steps.shape[0]):
                jj = j + dj[k]
                ii = i + di[k]
                if 0 <= jj < ny and 0 <= ii < nx:
                    v = dist[jj, ii] + steps[k]
                    if v < best:
                        best = v
            out[j, i] = best
    return out
