"""The planning geometry both planners share: the occupancy grid, the endpoint and segment checks.

Cells of :data:`CELL_SIZE` over the floor; a cell is free when its centre keeps the body radius
(:data:`mjwalk.conventions.BODY_RADIUS`) of clearance from every obstacle and from the floor's
edge, and a move (:data:`MOVES_8`, :data:`MOVES_16`) is allowed only when every point along it
(sampled every :data:`SAMPLE_SPACING` metres) does too. The grid-A* baseline
(:mod:`mjwalk.plan.grid`) searches it; the hybrid A* (:mod:`mjwalk.plan.hybrid`) bounds its
heuristic with it (:mod:`mjwalk.plan.heuristic`). :func:`check_endpoint` rejects a start or goal
off the floor or too near an obstacle before either searches.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from mjwalk._jit import njit
from mjwalk.conventions import BODY_RADIUS
from mjwalk.errors import InputError, PlanningError
from mjwalk.world.cache import cached_array, content_key
from mjwalk.world.clearance import bilinear_at
from mjwalk.world.workplace import Workplace

#: Default grid cell size (metres), as in agethen2018.
CELL_SIZE = 0.08
_SQRT2 = math.sqrt(2.0)
#: The 8-connected moves (di, dj), in cells: the grid A*'s.
MOVES_8 = [(1, 0), (-1, 0), (0, 1), (0, -1), (1, 1), (1, -1), (-1, 1), (-1, -1)]
#: 16-connected moves (adds the knight moves): routes at most 2.7 % longer than straight lines.
MOVES_16 = MOVES_8 + [(2, 1), (1, 2), (-1, 2), (-2, 1), (-2, -1), (-1, -2), (1, -2), (2, -1)]
#: Spacing (metres) of the points a move or segment is checked at (every centimetre).
SAMPLE_SPACING = 0.01


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
        """The centre of a cell.

        Args:
            j: the cell's row (along y).
            i: the cell's column (along x).

        Returns:
            (2,) its centre (x0 + i·cell, y0 + j·cell), metres, world frame.
        """
        return np.array([self.x0 + i * self.cell, self.y0 + j * self.cell])

    def index(self, xy: np.ndarray) -> tuple[int, int]:
        """(row j, column i) of the cell containing ``xy``, clipped to the grid.

        Args:
            xy: (2,) a point, metres, world frame.

        Returns:
            (j, i) the nearest cell's row and column.
        """
        ny, nx = self.free.shape
        i = int(np.clip(np.rint((xy[0] - self.x0) / self.cell), 0, nx - 1))
        j = int(np.clip(np.rint((xy[1] - self.y0) / self.cell), 0, ny - 1))
        return j, i


def segment_is_free(workplace: Workplace, a: np.ndarray, b: np.ndarray, radius: float) -> bool:
    """Whether every point of the segment a-b keeps ``radius`` of walking clearance.

    Args:
        workplace: the scene.
        a: (2,) one end, metres, world frame.
        b: (2,) the other end, metres.
        radius: the clearance to keep, metres.

    Returns:
        Whether every sample, :data:`SAMPLE_SPACING` apart, keeps ``radius``.
    """
    n = max(2, int(np.ceil(np.linalg.norm(b - a) / SAMPLE_SPACING)) + 1)
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

    Args:
        workplace: the scene.
        cell: the cell size, metres.
        radius: the body radius the cells and moves keep, metres.
        moves: the moves (di, dj) in cells.

    Returns:
        The grid: origin, cell size, radius, free mask (ny, nx) and move validity.
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
        n = int(np.ceil(length / SAMPLE_SPACING)) + 1
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
    ``benchmarks/bench_scale.py``): every move of every cell sampled every centimetre.

    Args:
        workplace: the scene.
        cell: the cell size, metres.
        radius: the body radius the cells and moves keep, metres.
        moves: the moves (di, dj) in cells.

    Returns:
        The same grid as :func:`occupancy_grid`'s.
    """
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
        n = int(np.ceil(np.linalg.norm(step) / SAMPLE_SPACING)) + 1
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
    distances and the distance to the floor's edge), and the exact walk clearance is
    1-Lipschitz (the field's bilinear lookup is not: up to sqrt(2),
    :attr:`~mjwalk.world.clearance.ClearanceField.lipschitz`), so at ``xy`` it is at least the
    nearest node's value minus the distance to that node.
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
    clearance field is replaced gets a new grid.

    Args:
        workplace: the scene (the grid is kept on it).
        cell: the cell size, metres.
        radius: the body radius the cells and moves keep, metres.
        moves: the moves (di, dj) in cells.

    Returns:
        The workplace's grid for these figures.
    """
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
    closer to one than the body radius.

    Args:
        workplace: the scene.
        xy: (2,) the point, metres, world frame.
        radius: the body radius, metres (not a positive number: InputError).
        what: the point's name in the message ("start", "goal").
    """
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
        nearest = min(dists, key=dists.__getitem__)
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
