"""mjwalk.scan.levelboxes: stairs fitted as regular flights, levels written as walkable boxes,
and the written scene's own level graph agrees (issue 47)."""

from __future__ import annotations

import math
import re

import mujoco
import numpy as np
import pytest
from test_scanlevels import LEVELS_XML, SCANNERS

from mjwalk.scan import build_scene
from mjwalk.scan.level import find_floor
from mjwalk.scan.levelboxes import band_top, describe, scan_levels, square_to_flight
from mjwalk.scan.obstacles import TOP_STEP, floor_plan
from mjwalk.scan.raycast import synthetic_scan
from mjwalk.world.floor import OBSTACLE_Z_RANGE
from mjwalk.world.levels import level_graph
from mjwalk.world.norms import STAIR_TOLERANCE
from mjwalk.world.surfaces import find_walk_surfaces


@pytest.fixture(scope="module")
def hall_scene():
    model = mujoco.MjModel.from_xml_string(LEVELS_XML)
    scan = synthetic_scan(model, SCANNERS, step_deg=0.4, noise=0.005, seed=3)
    return build_scene(scan.points, source="hall")


def _links(graph_links, heights):
    """The distinct connections (kind, lower height, upper height, risers): the MJCF graph
    links a step once per edge crossed (a dais free on four sides: four links), the scan once
    per pair of levels."""
    return sorted(
        {
            (k.kind, round(heights[k.lower], 2), round(heights[k.upper], 2), len(k.risers))
            for k in graph_links
        }
    )


def test_stair_is_recognised_as_one_regular_flight(hall_scene):
    lp = hall_scene.levels
    assert lp is not None
    stairs = [k for k in lp.links if k.kind == "stair"]
    assert len(stairs) == 1
    s = stairs[0]
    assert len(s.risers) == 4 and s.risers[0] == pytest.approx(0.17, abs=0.005)
    assert s.tread == pytest.approx(0.28, abs=0.01)
    assert [k.kind for k in lp.links].count("step") == 1  # floor -> dais
    assert "stair L0 -> L" in describe(lp)


def test_written_scene_has_the_same_levels_and_links(hall_scene):
    lp = hall_scene.levels
    graph = level_graph(find_walk_surfaces(mujoco.MjModel.from_xml_string(hall_scene.xml)))
    assert sorted(lv.height for lv in graph.levels) == pytest.approx(sorted(lp.heights), abs=1e-3)
    scan_links = _links(lp.links, lp.heights)
    mjcf_links = _links(graph.links, [lv.height for lv in graph.levels])
    assert scan_links == mjcf_links
    assert 'material="scan_level"' in hall_scene.xml


def test_table_stays_an_obstacle_and_floor_obstacles_spare_the_levels(hall_scene):
    plan = hall_scene.plan
    r = plan.resolution
    ix = int((-1.9 - plan.x0) / r)
    iy = int((-1.6 - plan.y0) / r)
    assert plan.obstacles[iy, ix] > 0  # the table
    ix = int((1.6 - plan.x0) / r)
    iy = int((0.0 - plan.y0) / r)
    assert plan.obstacles[iy, ix] == 0 and not plan.void[iy, ix]  # under the deck's box


def test_flat_scan_has_no_levels():
    model = mujoco.MjModel.from_xml_string(
        """<mujoco><worldbody><geom name="floor" type="plane" size="3 3 0.05"/>
        <geom name="box" type="box" pos="1 0 0.5" size="0.3 0.3 0.5"/></worldbody></mujoco>"""
    )
    scan = synthetic_scan(model, [(-1.0, 0.0, 1.5)], step_deg=0.5, noise=0.005, seed=1)
    pts = find_floor(scan.points).apply(scan.points)
    assert scan_levels(pts, floor_plan(pts)) is None
    assert build_scene(scan.points).levels is None


#: Scanner positions in scenes/multilevel_station.xml (x, y, height), metres: round the car,
#: before the step and the stair, on the platform's side and over the mezzanine.
STATION_SCANNERS = [
    (-3.3, 1.6, 1.6), (-4.9, 1.2, 1.6), (3.3, 0.0, 1.6), (0.2, -1.2, 1.6),
    (-2.8, 3.2, 1.9), (4.5, 2.0, 1.6), (-4.9, -3.0, 2.6),
]  # fmt: skip


@pytest.mark.slow
def test_multilevel_station_scan_levels_within_2cm(scenes_dir, tmp_path, capsys):
    """Seeded synthetic scan of the multi-level station (0.3 deg rays, 5 mm range noise, 1.5 deg
    tilt): the platform (0.34 m), the step (0.17 m), the stair's five treads and the mezzanine
    (1.02 m) are levels within 2 cm (measured: 0.5 mm); the stair is six risers of 0.17 m with
    0.28 m treads (measured 0.282 m); the 5.5 deg ramp joins the floor to the platform (measured
    5.50 deg in the scan, 5.50 deg in the written scene); mjwalk scan prints and draws them; the
    written scene's own level graph has the same levels and connections."""
    from mjwalk import cli
    from mjwalk.world.workplace import load_model

    scan = synthetic_scan(
        load_model(scenes_dir / "multilevel_station.xml"), STATION_SCANNERS, step_deg=0.3, seed=0
    )
    src = tmp_path / "station.xyz"
    np.savetxt(src, scan.points, fmt="%.4f")
    out, png = tmp_path / "station.xml", tmp_path / "top.png"
    assert cli.main(["scan", str(src), "-o", str(out), "--png", str(png)]) == 0
    assert png.stat().st_size > 0
    # the platform and the tread at 0.34 m differ by 0.2 mm: either may be L3 or L4
    ramp_line = r"ramp  L0 -> L[34]  rise 0\.340 m over 3\.53 m, slope 5\.50 deg"
    assert re.search(ramp_line, capsys.readouterr().out)
    graph = level_graph(find_walk_surfaces(mujoco.MjModel.from_xml_path(str(out))))
    truth = [0.0, 0.17, 0.17, 0.34, 0.34, 0.51, 0.68, 0.85, 1.02]
    assert sorted(lv.height for lv in graph.levels) == pytest.approx(truth, abs=0.02)
    links = _links(graph.links, [lv.height for lv in graph.levels])
    assert links == [
        ("ramp", 0.0, 0.34, 0), ("stair", 0.0, 1.02, 6), ("step", 0.0, 0.17, 1),
        ("step", 0.17, 0.34, 1),
    ]  # fmt: skip
    (ramp,) = [k for k in graph.links if k.kind == "ramp"]
    assert np.degrees(ramp.slope) == pytest.approx(5.5, abs=0.5)
    stair = next(k for k in graph.links if k.kind == "stair")
    assert stair.tread == pytest.approx(0.28, abs=0.01)
    # regular within a tenth of DIN 18065's 5 mm (norms.STAIR_TOLERANCE): measured 20 um since
    # every region's plane is fitted on its inner cells (scanstair47), exactly equal before
    assert np.ptp(stair.risers) < STAIR_TOLERANCE / 10
    assert stair.risers[0] == pytest.approx(0.17, abs=0.005)


def test_cli_prints_levels_and_links(tmp_path, capsys):
    from mjwalk import cli

    model = mujoco.MjModel.from_xml_string(LEVELS_XML)
    scan = synthetic_scan(model, SCANNERS, step_deg=0.4, noise=0.005, seed=3)
    src = tmp_path / "hall.xyz"
    np.savetxt(src, scan.points, fmt="%.4f")
    assert cli.main(["scan", str(src), "-o", str(tmp_path / "hall.xml")]) == 0
    out = capsys.readouterr().out
    assert "levels: 6, links: 2" in out
    assert "stair L0 -> L5  4 risers x 0.170 m" in out
    assert "+0.75 m" in out  # the table: a surface no step reaches, still printed


def test_cli_says_pits_are_not_levels(tmp_path, capsys):
    """A 2 x 2 m pit 0.8 m deep that nothing leads down into: an obstacle, said so, not
    silently dropped (tests/scan/test_scanpits.py has the pits)."""
    from mjwalk import cli

    model = mujoco.MjModel.from_xml_string(
        """<mujoco><worldbody>
        <geom type="box" pos="0 -1.75 -0.05" size="4 1.25 0.05"/>
        <geom type="box" pos="0 2.25 -0.05" size="4 0.75 0.05"/>
        <geom type="box" pos="-2.5 0.5 -0.05" size="1.5 1 0.05"/>
        <geom type="box" pos="2.5 0.5 -0.05" size="1.5 1 0.05"/>
        <geom type="box" pos="3 -2.5 1.0" size="0.5 0.4 1.0"/>
        <geom type="box" pos="-3 2.5 1.0" size="0.5 0.4 1.0"/>
        <geom name="pit" type="box" pos="0 0.5 -0.85" size="1 1 0.05"/>
        </worldbody></mujoco>"""
    )
    scan = synthetic_scan(model, [(-2.5, -1.5, 1.6), (2.5, 2.0, 1.6)], step_deg=0.4, seed=1)
    src = tmp_path / "pit.xyz"
    np.savetxt(src, scan.points, fmt="%.4f")
    assert cli.main(["scan", str(src), "-o", str(tmp_path / "pit.xml")]) == 0
    out = capsys.readouterr().out
    assert "pit, bottom -0.800 m, no step or stair reaches it: obstacle" in out


def test_an_obstacle_part_without_band_points_gets_the_lowest_bin():
    """Cells the floor plan closed between obstacle points may be left apart, holding no band
    point, when a level's cells leave the obstacle (hall 17 of bench_unseen): their top is the
    band's lowest bin, as the floor plan gives such an obstacle, not an error."""
    assert band_top(np.float32(-np.inf), 0.0) == pytest.approx(OBSTACLE_Z_RANGE[0] + TOP_STEP)
    assert band_top(np.float32(-np.inf), 0.3) == pytest.approx(0.3 + OBSTACLE_Z_RANGE[0] + TOP_STEP)
    assert band_top(np.float32(0.51), 0.0) > 0.5


def test_a_landing_turned_less_than_a_cell_over_its_width_is_squared_to_its_flight():
    """A flight's top level's rectangle turned 0.14 deg from the flight (generated hall 1068:
    its written last tread read 2 mm deep, over the step rule) is turned onto the flight's
    axes about its centre; one turned 5 deg (more than a 2 cm cell subtends over its 1.4 m
    edge, 0.82 deg) is a level turned from its flight and kept."""
    run = np.array([math.cos(0.3), math.sin(0.3)])
    side = np.array([-run[1], run[0]])

    def rect(turn_deg: float) -> np.ndarray:
        c, s = math.cos(math.radians(turn_deg)), math.sin(math.radians(turn_deg))
        u, v = c * run + s * side, -s * run + c * side
        mid = np.array([2.0, 1.0])
        return np.array(
            [mid + a * 0.7 * u + b * 0.7 * v for a, b in ((-1, -1), (1, -1), (1, 1), (-1, 1))]
        )

    squared = square_to_flight(rect(0.14), run, 0.02)
    e = squared[1] - squared[0]
    assert abs(float(e @ side)) == pytest.approx(0.0, abs=1e-9)  # an edge along the run
    assert squared.mean(axis=0) == pytest.approx([2.0, 1.0], abs=1e-9)
    assert np.linalg.norm(e) == pytest.approx(1.4, abs=1e-9)
    kept = rect(5.0)
    assert np.array_equal(square_to_flight(kept, run, 0.02), kept)


@pytest.mark.slow  # a generated hall's scan: about 10 s, 40 s on a loaded 2-core machine
def test_a_step_at_the_norms_limit_stays_a_step_in_the_written_scene(tmp_path):
    """Hall 1129's 0.19 m step platform (DIN 18065's largest riser) is fitted at 0.19001 m,
    within the scan's noise over the norm: the scan keeps it as a step, and so must the scene
    it writes (written at 0.19002 m, it was no step there, and the platform no level)."""
    from mjwalk.scan.raycast import synthetic_scan
    from mjwalk.scan.scene import write_scene
    from mjwalk.world.levelgen import generate_levels
    from mjwalk.world.norms import MAX_RISER
    from mjwalk.world.workplace import load_model, load_workplace

    hall = generate_levels(1129)
    model = load_model(hall.write(tmp_path / "hall.xml"))
    scan = synthetic_scan(model, list(hall.scanners), step_deg=0.4, noise=0.005, seed=1129)
    scene = build_scene(scan.points, source="levels_1129")
    assert scene.levels is not None
    steps = [k for k in scene.levels.links if k.kind == "step"]
    assert any(k.risers[0] == pytest.approx(MAX_RISER, abs=0.005) for k in steps)
    assert all(k.risers[0] <= MAX_RISER for k in steps)  # as written
    graph = load_workplace(write_scene(scene, tmp_path / "scan.xml"), cache=False).levels
    z0 = graph.levels[0].height
    top = [j for j, lv in enumerate(graph.levels) if abs(lv.height - z0 - MAX_RISER) < 0.005]
    assert len(top) == 1
    assert any(k.kind == "step" and k.upper == top[0] for k in graph.links)
