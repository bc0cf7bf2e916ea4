"""mjwalk.scan.stairfit: a chain of levels fitted as one regular flight (issue 47)."""

from __future__ import annotations

import numpy as np
import pytest

from mjwalk.scan.minrect import min_rectangle, rectangle_size
from mjwalk.scan.obstacles import FloorPlan
from mjwalk.scan.planefit import RISER_TOL
from mjwalk.scan.scanlevels import ScanLevel, ScanLink, seen_in_part
from mjwalk.scan.stairfit import (
    WRITE_MARGIN,
    axis_near,
    cell_centres,
    cell_span,
    fit_stair,
    near_edge,
    tread_slack,
    treads_axis,
)
from mjwalk.scan.writtennorm import stairs_within_norm
from mjwalk.world.norms import MAX_RISER, MAX_TREAD, MIN_RISER, MIN_TREAD, STEP_RULE

RES = 0.02
NY, NX = 60, 120


def _plan() -> FloorPlan:
    z = np.zeros((NY, NX), bool)
    return FloorPlan(0.0, 0.0, RES, ~z, np.zeros((NY, NX), np.int64), np.zeros(1), z,
                     (0.0, 0.0, NX * RES, NY * RES), 0)  # fmt: skip


def _level(i: int, kind: str, h: float, cols: tuple[int, int]) -> ScanLevel:
    cells = np.zeros((NY, NX), bool)
    cells[5:55, cols[0] : cols[1]] = True
    depth = (cols[1] - cols[0]) * RES
    return ScanLevel(i, kind, h, 0.0, 0.0, cells, float(cells.sum()) * RES**2, depth, 1.0, 0)


def test_a_regular_flight_is_fitted():
    """Floor, three 0.28 m treads of 0.17 m risers along +x from x = 0.40, a 0.68 m deck."""
    floor = _level(0, "floor", 0.0, (0, 20))
    treads = [_level(k + 1, "tread", 0.17 * (k + 1), (20 + 14 * k, 34 + 14 * k)) for k in range(3)]
    deck = _level(4, "platform", 0.68, (62, 110))
    fit = fit_stair([0, 1, 2, 3, 4], [floor, *treads, deck], _plan())
    assert fit is not None
    assert fit["riser"] == pytest.approx(0.17)
    assert fit["tread"] == pytest.approx(0.28, abs=1e-6)
    assert fit["run"] == pytest.approx([1.0, 0.0])
    assert fit["top_edge"] == pytest.approx(0.41 + 3 * 0.28, abs=1e-6)  # first cell centres


def test_a_chain_with_a_riser_out_of_the_norms_is_no_stair():
    floor = _level(0, "floor", 0.0, (0, 20))
    treads = [_level(k + 1, "tread", 0.25 * (k + 1), (20 + 14 * k, 34 + 14 * k)) for k in range(3)]
    deck = _level(4, "platform", 1.0, (62, 110))
    assert fit_stair([0, 1, 2, 3, 4], [floor, *treads, deck], _plan()) is None


def test_helpers():
    deck = _level(0, "platform", 0.68, (62, 110))
    plan = _plan()
    assert cell_centres(deck.cells, plan)[:, 0].min() == pytest.approx(1.25)
    rect = np.array([[0.0, 0.0], [2.0, 0.0], [2.0, 1.0], [0.0, 1.0]])
    assert axis_near(rect, np.array([-0.9, 0.2])) == pytest.approx([-1.0, 0.0])
    run, side = np.array([1.0, 0.0]), np.array([0.0, 1.0])
    assert near_edge(deck, plan, run, side, (0.2, 0.9), 0.5) == pytest.approx(1.25)
    assert near_edge(deck, plan, run, side, (2.0, 3.0), 0.5) == float("inf")


def test_a_flight_at_the_step_rule_bound_is_not_refused_for_the_grid():
    """A pit's stair of hall 12's shape: three 0.146 m risers, treads 0.352 m deep (2 r + a =
    0.644 m, within the step rule). On the 2 cm grid its edges read 0.36 m apart, 2 r + a =
    0.652 m: within the grid's slack (a cell over the one tread step), so it is a stair, written
    with its tread at the step rule's limit (less ``WRITE_MARGIN``) so the written scene's level
    graph reads a stair too (generated halls 1031/1032: single steps when written at 2 r + a
    over 0.65 m; this test asserted the 0.36 m tread before)."""
    floor = _level(0, "floor", 0.0, (0, 20))
    treads = [_level(k + 1, "tread", 0.146 * (k + 1), (20 + 18 * k, 37 + 18 * k)) for k in range(2)]
    deck = _level(3, "platform", 0.438, (56, 110))
    fit = fit_stair([0, 1, 2, 3], [floor, *treads, deck], _plan())
    assert fit is not None
    rule = 2 * fit["riser"] + fit["tread"]
    assert rule == pytest.approx(STEP_RULE[1] - WRITE_MARGIN, abs=1e-9)
    assert fit["tread"] == pytest.approx(0.65 - 0.292 - WRITE_MARGIN, abs=1e-9)


def test_a_flight_measured_under_the_least_riser_keeps_the_step_rule_as_written():
    """Three 0.14 m risers (DIN 18065's least) and 0.37 m treads (its largest): 2 h + g =
    0.65 m, the step rule's bound. Measured at 0.139995 m, the riser is written at
    ``MIN_RISER + WRITE_MARGIN`` (``writtennorm.stairs_within_norm``), so the tread is fitted
    for that riser: 2 h + g of the written flight within the rule. Before: tread 0.3699 m
    fitted for the measured riser, written risers 0.1401 m, 2 h + g = 0.6501 m (the written
    scene read single steps)."""
    r = 0.139995
    floor = _level(0, "floor", 0.0, (0, 20))
    treads = [_level(k + 1, "tread", r * (k + 1), c) for k, c in enumerate([(20, 38), (38, 57)])]
    deck = _level(3, "platform", 3 * r, (57, 110))
    fit = fit_stair([0, 1, 2, 3], [floor, *treads, deck], _plan())
    assert fit is not None and fit["riser"] == pytest.approx(r, abs=1e-12)
    link = ScanLink("stair", 0, 3, (fit["riser"],) * 3, fit["tread"], (1, 2))
    (out,) = stairs_within_norm([link], [0.0, r, 2 * r, 3 * r])
    assert out.risers[0] == pytest.approx(MIN_RISER + WRITE_MARGIN, abs=1e-12)
    for h in (r, out.risers[0]):  # the rule holds for the riser measured and the one written
        assert STEP_RULE[0] + WRITE_MARGIN - 1e-12 <= 2 * h + fit["tread"]
        assert 2 * h + fit["tread"] <= STEP_RULE[1] - WRITE_MARGIN + 1e-12


def test_a_flight_beyond_the_grids_slack_is_refused():
    """The same flight with treads 0.40 m apart: 2 r + a = 0.692 m, beyond the step rule by
    more than a cell, and a tread deeper than ``MAX_TREAD`` by more than a cell: no stair."""
    floor = _level(0, "floor", 0.0, (0, 20))
    treads = [_level(k + 1, "tread", 0.146 * (k + 1), (20 + 20 * k, 39 + 20 * k)) for k in range(2)]
    deck = _level(3, "platform", 0.438, (60, 110))
    assert fit_stair([0, 1, 2, 3], [floor, *treads, deck], _plan()) is None


def test_tread_slack_shrinks_with_the_flight():
    assert tread_slack(3, RES) == pytest.approx(RES)
    assert tread_slack(6, RES) == pytest.approx(RES / 4)
    assert tread_slack(3, RES) < MAX_TREAD - MIN_TREAD


def test_a_riser_measured_over_the_limit_within_the_scans_tolerance_is_a_stair():
    """Hall 108's pit stair: three 0.19 m risers (DIN 18065's largest) and 0.26 m treads, its
    bottom measured 0.5703 m down: a riser of 0.1901 m, over the limit by less than the scan's
    riser tolerance (``planefit.RISER_TOL``): a stair. A riser over it by more is none."""
    for riser, ok in ((0.1901, True), (MAX_RISER + RISER_TOL - 1e-4, True), (0.20, False)):
        floor = _level(0, "floor", 0.0, (0, 20))
        treads = [
            _level(k + 1, "tread", riser * (k + 1), (20 + 13 * k, 33 + 13 * k)) for k in range(2)
        ]
        deck = _level(3, "platform", 3 * riser, (46, 110))
        fit = fit_stair([0, 1, 2, 3], [floor, *treads, deck], _plan())
        assert (fit is not None) is ok, riser
        if ok:
            assert fit["riser"] == pytest.approx(riser)


def _scanned(u: tuple[float, float], run: np.ndarray, origin: np.ndarray, shape) -> np.ndarray:
    """The grid cells a dense scan (2 mm spacing) of the strip ``u`` along ``run`` (1.37 m
    across it) holds points in: every cell the strip overlaps, as a scan's rasterisation."""
    side = np.array([-run[1], run[0]])
    uu, vv = np.meshgrid(np.arange(u[0], u[1], 0.002), np.arange(0.0, 1.37, 0.002))
    xy = origin + uu.reshape(-1, 1) * run + vv.reshape(-1, 1) * side
    ij = np.floor(xy / RES).astype(int)
    cells = np.zeros(shape, bool)
    cells[ij[:, 1], ij[:, 0]] = True
    return cells


def test_a_flight_turned_against_the_grid_is_fitted():
    """Hall 1016's flight (seed 1016 of ``bench_unseen``): eight 0.178 m risers, 0.282 m
    treads, climbing at 126 deg from +x, its top tread seen 0.18 m deep (the deck's edge shadows
    its back). Each tread holds every cell it overlaps, and the next riser's foot points (within
    ``FLOOR_TOL`` of it) scattered 5 mm past the riser (the scan's range noise sigma); on a grid
    turned 36 deg against the flight a cell spans 0.028 m along the climb, not 0.02 m, so a
    tread's back cell and the next one's front cell lie up to 0.028 m past each other: a
    regular flight, fitted as one (the edge tolerance counted in cells along the climb,
    ``stairfit.cell_span``). On the base tree (cells counted as 0.02 m) it was refused."""
    shape = (260, 260)
    a, r, n = 0.282, 0.178, 8
    run = np.array([np.cos(np.radians(126.0)), np.sin(np.radians(126.0))])
    origin = np.array([4.0, 1.4])
    noise = 0.005  # the riser's foot points within FLOOR_TOL of a tread: a range sigma past it
    spans = [(-0.5, noise)] + [(k * a, (k + 1) * a + noise) for k in range(n - 2)]
    spans += [((n - 2) * a, (n - 2) * a + 0.18), ((n - 1) * a, (n - 1) * a + 1.5)]
    levels = []
    for k, u in enumerate(spans):
        cells = _scanned(u, run, origin, shape)
        depth, width = rectangle_size(min_rectangle(cells, 0.0, 0.0, RES))
        kind = "floor" if k == 0 else "platform" if k == n else "tread"
        area = float(cells.sum()) * RES**2
        levels.append(ScanLevel(k, kind, k * r, 0.0, 0.0, cells, area, depth, width, 0))
    assert seen_in_part(levels[n - 1], RES)
    z = np.zeros(shape, bool)
    plan = FloorPlan(0.0, 0.0, RES, ~z, np.zeros(shape, np.int64), np.zeros(1), z,
                     (0.0, 0.0, 5.2, 5.2), 0)  # fmt: skip
    fit = fit_stair(list(range(n + 1)), levels, plan)
    assert fit is not None
    assert fit["riser"] == pytest.approx(r)
    assert fit["tread"] == pytest.approx(a, abs=tread_slack(n, RES))
    assert fit["run"] == pytest.approx(run, abs=0.02)


def test_cell_span():
    assert cell_span(np.array([1.0, 0.0]), RES) == pytest.approx(RES)
    assert cell_span(np.array([0.0, -1.0]), RES) == pytest.approx(RES)
    assert cell_span(np.array([1.0, 1.0]) / np.sqrt(2.0), RES) == pytest.approx(RES * np.sqrt(2))


def _written_hall(seed: int, tmp_path):
    """levelgen's hall ``seed``, scanned as benchmarks/bench_unseen.py does (seeded), the
    scene built from the scan, written and loaded: (the hall, the scene, the written model)."""
    import mujoco  # deferred: only the slow generated-hall tests need MuJoCo

    from mjwalk.scan.raycast import synthetic_scan
    from mjwalk.scan.scene import build_scene
    from mjwalk.world.levelgen import generate_levels
    from mjwalk.world.workplace import load_model

    hall = generate_levels(seed)
    xml = tmp_path / "hall.xml"
    xml.write_text(hall.xml)
    pts = synthetic_scan(load_model(xml), list(hall.scanners), step_deg=0.4, noise=0.005, seed=seed)
    scene = build_scene(pts.points, source=f"levels_{seed}")
    return hall, scene, mujoco.MjModel.from_xml_string(scene.xml)


def _pit_links(model):
    from mjwalk.world.levels import level_graph  # deferred: with the slow tests' imports
    from mjwalk.world.surfaces import find_walk_surfaces

    graph = level_graph(find_walk_surfaces(model))
    return [k for k in graph.links if graph.levels[k.lower].height < -0.05]


@pytest.mark.slow  # a generated hall's scan: about 30 s on a loaded 2-core machine
def test_a_pit_flight_turns_with_all_its_treads(tmp_path):
    """Hall 1069: its pit's stair runs along the hall's y axis (5 risers 0.1402 m, 1.52 m
    wide). Its top tread's own rectangle tips 1.2 deg (a cell at a corner); the flight's axis
    from all four treads lies within atan(res / width) (one cell over the tread's width, half
    what one tread's rectangle allows) of the true one, and the written pit links the floor by
    the stair alone (before: 1.19 deg, and two extra ``step`` links beside the stair)."""
    import mujoco  # deferred: only the slow generated-hall tests need MuJoCo

    _, _, model = _written_hall(1069, tmp_path)
    yaws = []
    for g in range(model.ngeom):
        name = mujoco.mj_id2name(model, mujoco.mjtObj.mjOBJ_GEOM, g) or ""
        if name.startswith("scan_pit_tread_"):
            q = model.geom_quat[g]
            yaws.append(2 * np.arctan2(q[3], q[0]))
    assert len(yaws) == 4
    off = [abs((y + np.pi / 4) % (np.pi / 2) - np.pi / 4) for y in yaws]  # from the hall's axes
    assert max(off) <= np.arctan(RES / 1.52), np.degrees(off)
    links = _pit_links(model)
    assert [(k.kind, len(k.risers)) for k in links] == [("stair", 5)]


@pytest.mark.slow  # a generated hall's scan: about 30 s on a loaded 2-core machine
def test_a_pit_flight_meets_the_floor_edge(tmp_path):
    """Hall 1067: a pit 0.69 m deep reached by 4 risers of 0.1724 m and 0.2964 m treads. Its
    three treads' edges alone gave 0.285 m, the top tread written 5 cm short of the floor; the
    floor's rim in the fit puts the tread within a cell over the flight's three treads of the
    true one and the written pit is reached by its stair (before: no link to the pit)."""
    _, scene, model = _written_hall(1067, tmp_path)
    (pit,) = [p for p in scene.pits if p.bottom is not None]
    assert pit.link is not None and pit.link.kind == "stair"
    assert pit.link.tread == pytest.approx(0.2964, abs=RES / 3)
    links = _pit_links(model)
    assert [(k.kind, len(k.risers)) for k in links] == [("stair", 4)]
    assert links[0].risers[0] == pytest.approx(0.1724, abs=0.005)


@pytest.mark.slow  # a generated hall's scan: about 30 s on a loaded 2-core machine
def test_a_flight_turns_with_its_treads_not_the_landings_rectangle(tmp_path):
    """Hall 1163: a turning stair, 3 risers of 0.19 m up to a 1.19 m square landing at 0.57 m
    and 5 more to a deck, both flights square to the landing (yaw 102.85 / 12.85 deg). The
    landing's own minimum rectangle lies on a 1:4 lattice edge (104.04 deg); on 5d9c79e the
    first flight, fitted along it, met the landing (written square to the second flight) 1.2 cm
    off its tread, and the written scene had three steps for its stair. Its treads' pooled
    second moments give 102.95 deg (``stairfit.treads_axis``): the flight within atan(res /
    width) (a cell over the treads' width) of the hall's, and both flights stairs."""
    import mujoco  # deferred: only the slow generated-hall tests need MuJoCo

    from mjwalk.world.levels import level_graph  # deferred: with the slow tests' imports
    from mjwalk.world.surfaces import find_walk_surfaces

    _, scene, model = _written_hall(1163, tmp_path)
    assert scene.levels is not None
    low = [k for k in scene.levels.links if k.kind == "stair" and len(k.risers) == 3]
    (first,) = low
    yaws = []
    for i in first.via:
        g = mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_GEOM, f"scan_level_{i}")
        q = model.geom_quat[g]
        yaws.append(2 * np.arctan2(q[3], q[0]))
    true = np.radians(102.8533)
    off = [abs((y - true + np.pi / 4) % (np.pi / 2) - np.pi / 4) for y in yaws]
    assert max(off) <= np.arctan(RES / 1.045), np.degrees(off)  # the treads 1.045 m wide
    graph = level_graph(find_walk_surfaces(model))
    stairs = sorted(len(k.risers) for k in graph.links if k.kind == "stair")
    assert stairs == [3, 5]


def _turned(
    centre: tuple[float, float], yaw: float, half: tuple[float, float], shape
) -> np.ndarray:
    """The cells whose centres lie in a rectangle of half sides ``half`` (along, across
    ``yaw``) round ``centre``, metres, on the ``RES`` grid."""
    gx, gy = np.meshgrid((np.arange(shape[1]) + 0.5) * RES, (np.arange(shape[0]) + 0.5) * RES)
    u = (gx - centre[0]) * np.cos(yaw) + (gy - centre[1]) * np.sin(yaw)
    v = -(gx - centre[0]) * np.sin(yaw) + (gy - centre[1]) * np.cos(yaw)
    return (np.abs(u) <= half[0]) & (np.abs(v) <= half[1])


def test_a_raised_flight_climbs_across_its_treads_not_its_square_landings_rectangle():
    """Halls 1163 and 1166's first flights, as their cells read: three 0.19 m risers, two
    0.27 m treads 1.04 m wide, up to a 1.19 m square landing, all turned 1.0 deg from +x. The
    landing's own minimum rectangle lies on the grid (1.0 deg off: a square's cells tip its
    hull at a corner); the treads' pooled second moments, read from all their cells, give the
    flight within 0.3 deg (``stairfit.treads_axis``). On 5d9c79e the flight climbed along the
    landing's rectangle, 1.0 deg off."""
    shape = (200, 200)
    yaw = np.radians(1.0)
    run = np.array([np.cos(yaw), np.sin(yaw)])
    land_c = np.array([2.0, 2.0])
    land = _turned(tuple(land_c), yaw, (0.595, 0.595), shape)
    r = min_rectangle(land, 0.0, 0.0, RES)
    assert abs(r[1][1] - r[0][1]) < 1e-9 or abs(r[1][0] - r[0][0]) < 1e-9  # on the grid
    cells = [_turned(tuple(land_c - (0.595 + 0.135 + 0.27 * k) * run), yaw, (0.135, 0.52), shape)
             for k in (1, 0)]  # fmt: skip
    floor = _turned(tuple(land_c - (0.595 + 0.54 + 0.3) * run), yaw, (0.3, 0.52), shape)
    levels = [ScanLevel(0, "floor", 0.0, 0.0, 0.0, floor, 1.0, 0.6, 1.04, 0)]
    for k, c in enumerate(cells):
        levels.append(ScanLevel(k + 1, "tread", 0.19 * (k + 1), 0.0, 0.0, c, 0.28, 0.27, 1.04, 0))
    levels.append(ScanLevel(3, "platform", 0.57, 0.0, 0.0, land, 1.42, 1.19, 1.19, 0))
    z = np.zeros(shape, bool)
    plan = FloorPlan(0.0, 0.0, RES, ~z, np.zeros(shape, np.int64), np.zeros(1), z,
                     (0.0, 0.0, 4.0, 4.0), 0)  # fmt: skip
    fit = fit_stair([0, 1, 2, 3], levels, plan)
    assert fit is not None
    assert np.degrees(np.arccos(min(1.0, float(fit["run"] @ run)))) <= 0.3
    axis = treads_axis(levels[1:3], plan)
    assert axis is not None and abs(float(axis @ run)) < np.sin(np.radians(0.3))


def test_treads_that_disagree_give_no_axis():
    """Two treads, one turned 90 deg against the other (no flight's riser edges): no shared
    axis, the flight falls back to its top level's rectangle; a square gives none either."""
    shape = (100, 100)
    a = _turned((0.5, 1.0), 0.0, (0.135, 0.52), shape)
    b = _turned((1.5, 1.0), np.pi / 2, (0.135, 0.52), shape)
    sq = _turned((1.0, 1.0), 0.0, (0.3, 0.3), shape)
    z = np.zeros(shape, bool)
    plan = FloorPlan(0.0, 0.0, RES, ~z, np.zeros(shape, np.int64), np.zeros(1), z,
                     (0.0, 0.0, 2.0, 2.0), 0)  # fmt: skip
    tread = [
        ScanLevel(k, "tread", 0.19, 0.0, 0.0, c, 0.28, 0.27, 1.04, 0) for k, c in enumerate((a, b))
    ]
    assert treads_axis(tread, plan) is None
    assert treads_axis([ScanLevel(0, "tread", 0.19, 0.0, 0.0, sq, 0.36, 0.6, 0.6, 0)], plan) is None
    assert treads_axis(tread[:1], plan) == pytest.approx([0.0, 1.0], abs=1e-9) or treads_axis(
        tread[:1], plan
    ) == pytest.approx([0.0, -1.0], abs=1e-9)


@pytest.mark.slow  # a generated hall's scan: about 30 s on a loaded 2-core machine
def test_a_flight_whose_treads_read_on_the_grid_stays_a_stair(tmp_path):
    """Hall 1166: 3 risers of 0.1726 m up to a 1.2 m landing, 4 more to a deck, the hall
    turned about 0.9 deg. The first flight's two treads' own rectangles lie on the grid (0.0 and
    90.0 deg); e7cd430's axis shared by treads and landing (their rectangles' summed area)
    took it, and the written scene had three steps for the stair. Their pooled second moments
    read 91.02 deg: both flights stairs."""
    from mjwalk.world.levels import level_graph  # deferred: with the slow tests' imports
    from mjwalk.world.surfaces import find_walk_surfaces

    _, _, model = _written_hall(1166, tmp_path)
    graph = level_graph(find_walk_surfaces(model))
    stairs = sorted(len(k.risers) for k in graph.links if k.kind == "stair")
    assert stairs == [3, 4]
