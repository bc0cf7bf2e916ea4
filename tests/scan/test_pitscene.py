"""mjwalk.scan.pitscene: a pit a stair reaches is written as a level below the floor with its
stair (the floor plane at its bottom, the floor as boxes round the opening); the written scene
loads with the floor at 0, the pit at its depth and the stair between them, and a walk is
planned from the floor down into the pit (issue 47).

The seeded synthetic scan of tests/scan/test_scanpits.py: an 8 x 6 m hall, a 2 x 2 m opening at
x in [-1, 1], y in [-0.5, 1.5], its bottom 0.51 m down, reached by three 0.17 m risers and
0.28 m treads descending along +x from x = -1."""

from __future__ import annotations

import mujoco
import numpy as np
import pytest
import shapely
from test_scanpits import PIT, STAIR, STAIR_SCANNERS, _scan

from mjwalk.gait.default import default_model
from mjwalk.plan.walks import plan_walk
from mjwalk.scan import build_scene
from mjwalk.scan.pitscene import pit_floor
from mjwalk.scan.scene import read_sites
from mjwalk.world import load_workplace
from mjwalk.world.floorholes import FLOOR_BOX_PREFIX


@pytest.fixture(scope="module")
def stair_scan():
    return _scan(STAIR, STAIR_SCANNERS)


@pytest.fixture(scope="module")
def written(stair_scan, tmp_path_factory):
    d = tmp_path_factory.mktemp("pit")
    sites = d / "sites.toml"
    sites.write_text("[site.floor_a]\nxy = [-3.0, -2.0]\n[site.pit_b]\nxy = [0.5, 0.5]\n")
    scene = build_scene(stair_scan, source="stair", sites=read_sites(sites))
    path = d / "pit.xml"
    path.write_text(scene.xml)
    return scene, path


def test_reached_pit_is_written_as_a_level_with_its_stair(written):
    scene, _ = written
    model = mujoco.MjModel.from_xml_string(scene.xml)
    names = [model.geom(g).name for g in range(model.ngeom)]
    assert not any(n.startswith("scan_pit_") and "tread" not in n for n in names)  # no guard
    assert sum(n.startswith(FLOOR_BOX_PREFIX) for n in names) >= 4
    assert sum(n.startswith("scan_pit_tread_") for n in names) == 2
    plane = model.geom("floor")
    assert model.geom_pos[plane.id][2] == pytest.approx(-0.51, abs=0.02)
    assert scene.site_z["pit_b"] == pytest.approx(-0.51, abs=0.02)
    assert scene.site_z["floor_a"] == pytest.approx(0.0, abs=0.01)
    assert "written as a level below the floor with its stair" in scene.xml


def test_written_scene_gives_the_floor_the_pit_and_the_stair(written):
    _, path = written
    wp = load_workplace(path)
    graph = wp.levels
    assert wp.floor_z == 0.0
    assert graph.levels[0].kind == "floor" and graph.levels[0].height == pytest.approx(0.0)
    heights = sorted(lv.height for lv in graph.levels)
    assert heights == pytest.approx([-0.51, -0.34, -0.17, 0.0], abs=0.02)  # target: 2 cm
    (stair,) = graph.links
    assert stair.kind == "stair" and stair.upper == 0
    assert graph.levels[stair.lower].height == pytest.approx(-0.51, abs=0.02)
    assert len(stair.risers) == 3 and stair.risers[0] == pytest.approx(0.17, abs=0.005)
    assert stair.tread == pytest.approx(0.28, abs=0.01)
    assert float(wp.walk_clearance((0.0, 0.5))) < 0  # the opening is a wall on the floor


@pytest.mark.slow  # about 22 s on a loaded 2-core machine (the hybrid A* on a scanned scene)
def test_a_walk_is_planned_from_the_floor_down_into_the_pit(written):
    _, path = written
    wp = load_workplace(path)
    walk = plan_walk(wp, "floor_a", "pit_b", default_model(progress=False), rng=5)
    walk.validate()
    route = walk.meta["levels"]["route"]
    assert [r["kind"] for r in route] == ["level", "stair", "level"]
    assert route[1]["direction"] == "down" and route[1]["risers"] == 3
    graph = wp.levels
    for s in walk.steps:  # every footfall within 1 cm of the surface under it
        i = graph.surface_at(s.foot[:2], s.foot_z)
        assert i is not None
        assert abs(float(graph.surfaces[i].height_at(np.asarray(s.foot[:2]))) - s.foot_z) <= 0.01
    for tread in (s for s in graph.surfaces if s.kind == "tread"):
        assert sum(bool(tread.contains(s.foot[:2])) for s in walk.steps) == 1
    assert walk.z[-1] == pytest.approx(-0.51, abs=0.02)


def test_unreached_pit_stays_a_guard_rail_box():
    points = _scan(PIT)
    scene = build_scene(points, source="pit")
    assert "scan_pit_0" in scene.xml and FLOOR_BOX_PREFIX not in scene.xml
    assert pit_floor(scene.plan, scene.pits) is None


@pytest.mark.slow  # a second seeded scan and a walk on it: about 25 s on a loaded machine
def test_a_turned_pit_keeps_its_stair_and_is_walked_into(tmp_path):
    """The same hall turned 30 deg about z (scanners with it): the flight runs along neither
    axis, so the floor boxes over the grid meet its last riser only in a staircase of cells;
    the written scene has a floor box turned to the flight at its top, and the level graph
    gives the floor, the pit and one stair of three risers (not single steps, not nothing), down
    which a walk is planned."""
    import math

    from test_scanpits import HALL

    c, s = math.cos(math.radians(30)), math.sin(math.radians(30))
    turn = lambda x, y: (c * x - s * y, s * x + c * y)  # noqa: E731
    xml = (HALL % STAIR).replace("<worldbody>", '<worldbody><body euler="0 0 30">')
    model = mujoco.MjModel.from_xml_string(xml.replace("</worldbody>", "</body></worldbody>"))
    scanners = [(*turn(x, y), z) for x, y, z in STAIR_SCANNERS]
    from mjwalk.scan.raycast import synthetic_scan

    points = synthetic_scan(model, scanners, step_deg=0.4, noise=0.005, seed=1).points
    sites = tmp_path / "sites.toml"
    (ax, ay), (bx, by) = turn(-3.0, -2.0), turn(0.5, 0.5)
    sites.write_text(
        f"[site.floor_a]\nxy = [{ax:.4f}, {ay:.4f}]\n[site.pit_b]\nxy = [{bx:.4f}, {by:.4f}]\n"
    )
    scene = build_scene(points, source="turned", sites=read_sites(sites))
    path = tmp_path / "turned.xml"
    path.write_text(scene.xml)
    wp = load_workplace(path)
    graph = wp.levels
    (stair,) = graph.links
    assert stair.kind == "stair" and stair.upper == 0 and len(stair.risers) == 3
    assert stair.risers[0] == pytest.approx(0.17, abs=0.005)
    assert stair.tread == pytest.approx(0.28, abs=0.01)
    assert graph.levels[stair.lower].height == pytest.approx(-0.51, abs=0.02)
    assert graph.levels[stair.lower].area == pytest.approx(3.9, abs=0.15)  # the 2 x 2 m opening
    walk = plan_walk(wp, "floor_a", "pit_b", default_model(progress=False), rng=5)
    route = walk.meta["levels"]["route"]
    assert [r["kind"] for r in route] == ["level", "stair", "level"]
    assert walk.z[-1] == pytest.approx(-0.51, abs=0.02)


@pytest.mark.slow  # a seeded scan and two walks on it: about 30 s on a loaded machine
def test_a_pit_reached_by_a_ramp_is_written_with_it_and_walked_into(tmp_path):
    """The seeded scan of test_scanpits.RAMP_HALL (a 0.51 m pit, a 9.06 deg ramp down to it):
    the written scene has the ramp as a tilted box and the floor round the opening; the level
    graph links the floor and the pit by one ramp, and walks go down it and back up."""
    from test_scanpits import RAMP_HALL

    from mjwalk.scan.raycast import synthetic_scan

    model = mujoco.MjModel.from_xml_string(RAMP_HALL)
    scanners = [(-3.0, -1.5, 1.6), (3.0, 2.0, 1.6), (2.8, 0.5, 1.7)]
    points = synthetic_scan(model, scanners, step_deg=0.4, noise=0.005, seed=1).points
    sites = tmp_path / "sites.toml"
    sites.write_text("[site.floor_a]\nxy = [-4.0, -2.0]\n[site.pit_b]\nxy = [1.6, 0.5]\n")
    scene = build_scene(points, source="ramp", sites=read_sites(sites))
    assert "scan_pit_ramp_" in scene.xml and "with its ramp" in scene.xml
    path = tmp_path / "ramp.xml"
    path.write_text(scene.xml)
    wp = load_workplace(path)
    (link,) = wp.levels.links
    assert link.kind == "ramp" and link.upper == 0
    assert np.degrees(link.slope) == pytest.approx(9.06, abs=0.3)
    assert wp.levels.levels[link.lower].height == pytest.approx(-0.51, abs=0.02)
    model_ = default_model(progress=False)
    for start, goal, direction in (("floor_a", "pit_b", "down"), ("pit_b", "floor_a", "up")):
        walk = plan_walk(wp, start, goal, model_, rng=5)
        kinds = [(r["kind"], r.get("direction")) for r in walk.meta["levels"]["route"]]
        assert ("ramp", direction) in kinds
        assert walk.z[-1 if direction == "down" else 0] == pytest.approx(-0.51, abs=0.02)


#: An 8 x 6 m hall along the axes (its walls along its long sides) whose 2 x 2 m pit and stair
#: (those of test_scanpits.STAIR) are turned 20 deg about the opening's centre (0, 0.5): axis
#: boxes keep clear of the opening, four boxes turned with it close the floor round it.
TURNED_PIT = """<mujoco><worldbody>
<geom type="box" pos="-3 0 -0.05" size="1.5 3 0.05"/>
<geom type="box" pos="3 0 -0.05" size="1.5 3 0.05"/>
<geom type="box" pos="0 -2.25 -0.05" size="4 0.75 0.05"/>
<geom type="box" pos="0 2.6 -0.05" size="4 0.4 0.05"/>
<geom type="box" pos="0 3.05 1.5" size="4 0.05 1.5"/>
<geom type="box" pos="0 -3.05 1.5" size="4 0.05 1.5"/>
<body pos="0 0.5 0" euler="0 0 20">
<geom type="box" pos="0 1.5 -0.05" size="2 0.5 0.05"/>
<geom type="box" pos="0 -1.5 -0.05" size="2 0.5 0.05"/>
<geom type="box" pos="-1.5 0 -0.05" size="0.5 1 0.05"/>
<geom type="box" pos="1.5 0 -0.05" size="0.5 1 0.05"/>
<geom name="pit" type="box" pos="0.14 0 -0.56" size="0.86 1 0.05"/>
<geom name="s1" type="box" pos="-0.86 0 -0.35" size="0.14 1 0.18"/>
<geom name="s2" type="box" pos="-0.58 0 -0.43" size="0.14 1 0.09"/>
</body>
</worldbody></mujoco>"""


@pytest.mark.slow  # a seeded scan and the written scene's levels: about 15 s when loaded
def test_a_pit_turned_in_its_hall_keeps_its_stair(tmp_path):
    """The stair's run is taken from its own treads, not from the floor's outline (the hall's):
    before, the flight of TURNED_PIT did not fit along x and the scan linked the pit by three
    single steps (with other scanners: a stair of 0.26 m treads, and the written scene had no
    pit level at all); now one stair of three 0.17 m risers and 0.28 m treads, in the scan and
    in the written scene."""
    from mjwalk.scan.raycast import synthetic_scan

    model = mujoco.MjModel.from_xml_string(TURNED_PIT)
    c, s = np.cos(np.radians(20)), np.sin(np.radians(20))
    scanners = [(-2.5, -1.5, 1.6), (2.5, 2.0, 1.6), (2.3 * c, 0.5 + 2.3 * s, 1.7)]
    points = synthetic_scan(model, scanners, step_deg=0.4, noise=0.005, seed=1).points
    scene = build_scene(points, source="turned pit")
    (pit,) = scene.pits
    assert pit.link is not None and pit.link.kind == "stair"
    assert pit.link.tread == pytest.approx(0.28, abs=0.01)
    path = tmp_path / "turned_pit.xml"
    path.write_text(scene.xml)
    wp = load_workplace(path)
    (stair,) = wp.levels.links
    assert stair.kind == "stair" and len(stair.risers) == 3 and stair.upper == 0
    assert stair.tread == pytest.approx(0.28, abs=0.01)
    assert wp.levels.levels[stair.lower].height == pytest.approx(-0.51, abs=0.02)


@pytest.mark.slow
def test_a_floor_strip_snapped_onto_a_riser_is_not_written():
    """Generated hall 6 (a pit reached by a stair along y): a one-cell floor strip beside the
    flight's last riser had both faces snapped onto the riser's line, and the scene was written
    with a box of zero width, which MuJoCo refuses ('size 1 must be positive in geom floor_9').
    An empty box covers nothing: it is left out and the scene compiles."""
    from mjwalk.scan.raycast import synthetic_scan
    from mjwalk.world.levelgen import generate_levels

    hall = generate_levels(6)
    model = mujoco.MjModel.from_xml_string(hall.xml)
    scan = synthetic_scan(model, list(hall.scanners), step_deg=0.4, noise=0.005, seed=6)
    scene = build_scene(scan.points, source="levels_6")
    assert scene.pits and any(p.bottom is not None for p in scene.pits)
    built = mujoco.MjModel.from_xml_string(scene.xml)
    boxes = built.geom_size[built.geom_type == mujoco.mjtGeom.mjGEOM_BOX]
    assert np.all(boxes > 0)


@pytest.mark.slow  # a seeded scan of a generated hall and the written scene's levels: ~30 s
def test_a_cell_stepped_rim_at_the_stair_top_is_one_floor_box_the_stair_reaches():
    """Generated hall 1057 (a 3-riser pit stair along x): the pit's cell-stepped rim cut the
    floor beside the flight's top riser into eleven strips 6-34 cm wide, each snapped onto the
    riser, each touching the top tread along less than a body's width; the written scene's
    pit (bottom and treads) was reached by nothing, and the floor level's opening covered the
    stair (3.52 m^2). Strips of one extent are joined: the pit is a level again, reached by
    one stair of three 0.167 m risers, and the opening is the pit less its stair."""
    from mjwalk.scan.raycast import synthetic_scan
    from mjwalk.world.levelgen import generate_levels
    from mjwalk.world.openings import openings_of
    from mjwalk.world.workplace import workplace_from_model

    hall = generate_levels(1057)
    model = mujoco.MjModel.from_xml_string(hall.xml)
    scan = synthetic_scan(model, list(hall.scanners), step_deg=0.4, noise=0.005, seed=1057)
    scene = build_scene(scan.points, source="levels_1057")
    wp = workplace_from_model(mujoco.MjModel.from_xml_string(scene.xml))
    graph = wp.levels
    (stair,) = [k for k in graph.links if k.kind == "stair" and k.upper == 0]
    assert len(stair.risers) == 3 and np.mean(stair.risers) == pytest.approx(0.167, abs=0.005)
    assert graph.levels[stair.lower].height == pytest.approx(-0.502, abs=0.02)
    ops = openings_of(graph, 0)
    # one opening (in convex pieces: the rim's cell steps leave bays open to the pit, which
    # are part of it, mjwalk.world.openings), west of the treads
    whole = shapely.union_all([shapely.Polygon(fp.vertices) for fp in ops])
    assert whole.geom_type == "Polygon" and whole.bounds[2] < 0.91
