"""Grid A*: clearance checked with MuJoCo geometry, optimality on a known route, bad input."""

from __future__ import annotations

import math
import time

import numpy as np
import pytest

from mjwalk import PlanningError
from mjwalk.plan.grid import END_EXCESS, OCTILE_RATIO, plan_grid, shortfall_bound
from mjwalk.plan.occupancy import CELL_SIZE, occupancy_grid
from mjwalk.world import load_workplace
from mjwalk.world.probe import ClearanceProbe, path_clearance

ROUTES = {
    "assembly_station": [
        ("stand_rack2", "stand_car1"),
        ("stand_car1", "stand_rack3"),
        ("stand_rack3", "stand_car2"),
        ("stand_car2", "stand_rack1"),
        ("stand_rack1", "stand_car3"),
        ("stand_car3", "stand_rack2"),
        ("stand_rack2", "stand_rack3"),
        ("-3.5,-2.5", "3.5,2.7"),
    ],
    "corridor": [("entry", "exit"), ("entry", "door")],
    "open_floor": [("west", "east"), ("-4,-4", "4,4.2")],
}


@pytest.mark.parametrize("scene", list(ROUTES))
def test_paths_keep_body_radius_by_mujoco_geometry(scenes_dir, scene):
    path = scenes_dir / f"{scene}.xml"
    wp = load_workplace(path)
    probe = ClearanceProbe(path)
    for a, b in ROUTES[scene]:
        route = plan_grid(wp, a, b, radius=0.25)
        np.testing.assert_allclose(route.xy[0], wp.point(a))
        np.testing.assert_allclose(route.xy[-1], wp.point(b))
        clearance = path_clearance(probe, route.xy, spacing=0.01)
        assert clearance.min() >= 0.25 - 1e-3, (a, b, clearance.min())
        assert route.length >= np.linalg.norm(route.xy[-1] - route.xy[0]) - 1e-9


def test_corridor_route_passes_the_door(scenes_dir):
    wp = load_workplace(scenes_dir / "corridor.xml")
    route = plan_grid(wp, "entry", "exit")
    crossing = np.flatnonzero(np.diff(np.sign(route.xy[:, 1])) != 0)
    assert len(crossing) >= 1
    assert np.all(np.abs(route.xy[crossing, 0]) < 0.45 - 0.25 + 0.01)


def test_length_on_a_known_route(tmp_path):
    """A thin wall (x in [-0.1, 0.1], y from the floor edge to -0.35) between start and goal.

    Inflated by the body radius its end is a disc of radius 0.25 around (+-0.1, -0.35). The
    shortest route in the 8-connected (octile) metric climbs 0.1036 m, runs diagonally to the
    point where a 45 degree line touches the disc, over the cap and down the mirror image:
    2 * (4.2232 * sqrt(2) + 0.1036) + 2 * (0.0732 * sqrt(2) + 0.1036) + 0.2 = 12.766 m.
    (The Euclidean taut string is 12.685 m; 8-connectivity may add to it, nothing else may.)
    """
    xml = """<mujoco><worldbody><geom name="floor" type="plane" size="5 5 .1"/>
      <geom name="wall" type="box" size="0.1 2.325 1" pos="0 -2.675 1"/></worldbody></mujoco>"""
    f = tmp_path / "wall.xml"
    f.write_text(xml)
    wp = load_workplace(f)
    route = plan_grid(wp, "-4.5,-4.5", "4.5,-4.5", radius=0.25)
    c = 0.25 * math.sqrt(2) - 0.25  # the diagonal tangent to the disc passes 0.1036 m above S
    dx = 4.5 - 0.1 - 0.25 / math.sqrt(2)
    leg = dx * math.sqrt(2) + c
    cap = (0.25 - 0.25 / math.sqrt(2)) * math.sqrt(2) + c
    reference = 2 * leg + 2 * cap + 0.2
    assert reference == pytest.approx(12.766, abs=1e-3)
    assert route.length == pytest.approx(reference, rel=0.01)
    assert route.length > 12.685  # never shorter than the Euclidean optimum
    straight = plan_grid(wp, "-4.0,3.0", "4.0,3.0")
    assert straight.length == pytest.approx(8.0, rel=0.01)
    diagonal = plan_grid(wp, "-4.0,-1.0", "-1.0,2.0")
    assert diagonal.length == pytest.approx(3 * math.sqrt(2), rel=0.01)


def test_route_between_off_grid_points_is_within_the_octile_bound(scenes_dir):
    """On an open floor the route between two off-grid points a straight line joins is at
    most OCTILE_RATIO times the line plus END_EXCESS cells (the report's tolerance of
    ``vs A*``, :func:`shortfall_bound`), and never shorter than the line."""
    wp = load_workplace(scenes_dir / "open_floor.xml")
    grid = occupancy_grid(wp, radius=0.25)
    rng = np.random.default_rng(4)
    worst = -1.0
    for _ in range(40):
        a = rng.uniform(-4.0, 4.0, 2)
        b = np.clip(a + rng.uniform(-3.0, 3.0, 2), -4.0, 4.0)
        route = plan_grid(wp, a, b, radius=0.25, grid=grid)
        line = float(np.linalg.norm(b - a))
        assert line - 1e-9 <= route.length <= OCTILE_RATIO * line + END_EXCESS * CELL_SIZE + 1e-9
        worst = max(worst, (route.length - OCTILE_RATIO * line) / CELL_SIZE)
        # a walk along the line itself reads no lower than the bound
        assert line / route.length - 1 >= shortfall_bound(route.length) - 1e-12
    assert worst > -0.5  # some routes come near the bound (it is not loose by cells)


def test_bad_endpoints(scenes_dir):
    wp = load_workplace(scenes_dir / "assembly_station.xml")
    with pytest.raises(PlanningError, match="inside obstacle 'car_body'"):
        plan_grid(wp, "stand_rack2", "0,1.4")
    with pytest.raises(PlanningError, match="off the floor"):
        plan_grid(wp, "9,0", "stand_car1")
    with pytest.raises(PlanningError, match="closer than the body radius"):
        plan_grid(wp, "stand_rack2", "3.3,-0.9")  # 0.1 m from the pillar


def test_unreachable_goal_fails_fast(caged_station):
    """A goal walled in by four boxes in the station scene: PlanningError in under 2 s."""
    wp = caged_station
    t0 = time.perf_counter()
    with pytest.raises(PlanningError, match="unreachable"):
        plan_grid(wp, "stand_rack2", "3.0,0.9")
    assert time.perf_counter() - t0 < 2.0


def _heapq_route(grid, b, start_links, goal_links):
    """The grid A* as a plain heapq loop (the planner before it was compiled): the nodes it
    pops, in order, and the parent of each reached node."""
    import heapq

    ny, nx = grid.shape
    start, goal = nx * ny, nx * ny + 1
    moves = grid.moves.reshape(len(grid.offsets), -1).T
    offsets = [dj * nx + di for di, dj in grid.offsets]
    costs = [grid.cell * (math.sqrt(2.0) if di and dj else 1.0) for di, dj in grid.offsets]

    def h(v):
        if v == goal:
            return 0.0
        dx = abs(grid.x0 + grid.cell * (v % nx) - b[0])
        dy = abs(grid.y0 + grid.cell * (v // nx) - b[1])
        return max(dx, dy) + (math.sqrt(2.0) - 1.0) * min(dx, dy)

    g, parent, heap, closed, count, popped = {start: 0.0}, {}, [(0.0, 0, start)], set(), 1, []
    while heap:
        v = heapq.heappop(heap)[2]
        if v in closed:
            continue
        closed.add(v)
        popped.append(v)
        if v == goal:
            break
        nbrs = (
            list(start_links)
            if v == start
            else [(v + o, c) for o, c, ok in zip(offsets, costs, moves[v], strict=True) if ok]
            + ([(goal, goal_links[v])] if v in goal_links else [])
        )
        for w, c in nbrs:
            if w not in closed and g[v] + c < g.get(w, math.inf):
                g[w], parent[w] = g[v] + c, v
                heapq.heappush(heap, (g[w] + h(w), count, w))
                count += 1
    return popped, parent


def test_compiled_search_pops_as_heapq_does(scenes_dir):
    """The compiled open list pops the cells in heapq's order of (f, push count): the same
    expansions and the same parents (routes equal to the last bit), ties included (the
    station's routes cross open floor where many cells share f)."""
    from mjwalk.plan.grid import _astar  # the search alone, without the route around it

    wp = load_workplace(scenes_dir / "assembly_station.xml")
    grid = occupancy_grid(wp, radius=0.25)
    nx = grid.shape[1]
    for a, b in ROUTES["assembly_station"]:
        pa, pb = wp.point(a), wp.point(b)
        ja, ia = grid.index(pa)
        jb, ib = grid.index(pb)
        start_links = [(ja * nx + ia, float(np.linalg.norm(grid.centre(ja, ia) - pa)))]
        goal_links = {jb * nx + ib: float(np.linalg.norm(grid.centre(jb, ib) - pb))}
        popped, parent = _heapq_route(grid, pb, start_links, goal_links)
        got, expansions, found = _astar(grid, pb, start_links, goal_links)
        assert found and expansions == len(popped)
        reached = np.flatnonzero(got >= 0)
        assert {int(v): int(got[v]) for v in reached} == parent


class _OtherClearance:
    """A clearance model that is not a ClearanceField (its lookup is the field's own): the grid
    A* takes the NumPy path for its ends."""

    def __init__(self, field):
        self.field = field

    def __call__(self, xy):
        return self.field(xy)


def test_compiled_end_links_equal_the_numpy_ones(scenes_dir):
    """The compiled end links (each end joined to the free centres of its 3 x 3 cells) give the
    same routes, to the last bit, as the NumPy path a clearance model other than a
    ClearanceField takes: 300 random start/goal pairs all over the station (ends near
    obstacles and the floor's edge too, some refused by both) and the station's routes."""
    wp = load_workplace(scenes_dir / "assembly_station.xml")
    grid = occupancy_grid(wp, radius=0.25)
    other = load_workplace(scenes_dir / "assembly_station.xml")
    other.walk_field()  # built from the field before it is wrapped (the end checks use it)
    other.clearance = _OtherClearance(wp.clearance)
    rng = np.random.default_rng(7)
    xmin, ymin, xmax, ymax = wp.floor_bounds
    pts = rng.uniform((xmin + 0.2, ymin + 0.2), (xmax - 0.2, ymax - 0.2), size=(300, 2, 2))
    pairs = [(a, b) for a, b in pts] + [
        (wp.point(a), wp.point(b)) for a, b in ROUTES["assembly_station"]
    ]
    planned = 0
    for a, b in pairs:
        try:
            r1 = plan_grid(wp, a, b, radius=0.25, grid=grid)
        except PlanningError as exc:
            with pytest.raises(PlanningError) as again:
                plan_grid(other, a, b, radius=0.25, grid=grid)
            assert str(again.value) == str(exc)
            continue
        r2 = plan_grid(other, a, b, radius=0.25, grid=grid)
        assert r1.xy.tobytes() == r2.xy.tobytes() and r1.t.tobytes() == r2.t.tobytes()
        planned += 1
    assert planned > 100
