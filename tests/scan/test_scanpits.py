"""mjwalk.scan.scanpits: a pit in a scan is a level when a stair reaches it, an obstacle
otherwise, and an unscanned hole over points below the floor is never filled as floor (issue 47).

Seeded synthetic scans (0.4 deg rays, 5 mm range noise, 1.5 deg tilt) of an 8 x 6 m hall whose
floor is four boxes round a 2 x 2 m opening at x in [-1, 1], y in [-0.5, 1.5]."""

from __future__ import annotations

import math
from dataclasses import replace

import mujoco
import numpy as np
import pytest

from mjwalk.errors import ScanError
from mjwalk.scan import ScanOptions, build_scene
from mjwalk.scan.level import find_floor
from mjwalk.scan.obstacles import GAP_WIDTH, floor_plan
from mjwalk.scan.raycast import synthetic_scan
from mjwalk.scan.scanlevels import ScanLevel, ScanLink
from mjwalk.scan.scanpits import GUARD_HEIGHT, describe_pits, find_pits, gap_boxes, within_norm
from mjwalk.scan.scene import read_sites
from mjwalk.scan.stairfit import WRITE_MARGIN
from mjwalk.world.levels import level_graph
from mjwalk.world.norms import MAX_RISER
from mjwalk.world.surfaces import find_walk_surfaces

HALL = """<mujoco><worldbody>
<geom type="box" pos="0 -1.75 -0.05" size="4 1.25 0.05"/>
<geom type="box" pos="0 2.25 -0.05" size="4 0.75 0.05"/>
<geom type="box" pos="-2.5 0.5 -0.05" size="1.5 1 0.05"/>
<geom type="box" pos="2.5 0.5 -0.05" size="1.5 1 0.05"/>
<geom type="box" pos="3 -2.5 1.0" size="0.5 0.4 1.0"/>
<geom type="box" pos="-3 2.5 1.0" size="0.5 0.4 1.0"/>
%s
</worldbody></mujoco>"""
#: The opening's bottom 0.80 m down, nothing leading into it.
PIT = '<geom name="pit" type="box" pos="0 0.5 -0.85" size="1 1 0.05"/>'
#: The bottom 0.51 m down, reached by a stair of three 0.17 m risers and 0.28 m treads
#: descending along +x from the opening's edge at x = -1.
STAIR = """<geom name="pit" type="box" pos="0.14 0.5 -0.56" size="0.86 1 0.05"/>
<geom name="s1" type="box" pos="-0.86 0.5 -0.35" size="0.14 1 0.18"/>
<geom name="s2" type="box" pos="-0.58 0.5 -0.43" size="0.14 1 0.09"/>"""
#: A shaft 2.5 m deep, walled, its bottom never reached by a ray: only its walls show it; the
#: hall's two long walls (without them the scan has as many points below the floor as above
#: and is refused as upside down, ``mjwalk.scan.level.check_upright``).
SHAFT = """<geom type="box" pos="-1.05 0.5 -1.3" size="0.05 1 1.2"/>
<geom type="box" pos="1.05 0.5 -1.3" size="0.05 1 1.2"/>
<geom type="box" pos="0 -0.55 -1.3" size="1 0.05 1.2"/>
<geom type="box" pos="0 1.55 -1.3" size="1 0.05 1.2"/>
<geom type="box" pos="0 3.05 1.5" size="4 0.05 1.5"/>
<geom type="box" pos="0 -3.05 1.5" size="4 0.05 1.5"/>"""
SCANNERS = [(-2.5, -1.5, 1.6), (2.5, 2.0, 1.6)]
#: A third scanner looks down the stair from the opening's far side.
STAIR_SCANNERS = [*SCANNERS, (2.3, 0.5, 1.7)]
CENTRE = (0.0, 0.5)


def _scan(body: str, scanners=SCANNERS, seed: int = 1) -> np.ndarray:
    model = mujoco.MjModel.from_xml_string(HALL % body)
    return synthetic_scan(model, scanners, step_deg=0.4, noise=0.005, seed=seed).points


@pytest.fixture(scope="module")
def scans():
    return {
        "pit": _scan(PIT),
        "stair": _scan(STAIR, STAIR_SCANNERS),
        "hole": _scan(SHAFT),
    }


def _pits(points):
    pts = find_floor(points).apply(points)
    plan = floor_plan(pts)
    return plan, find_pits(pts, plan)


def _cell(plan, xy):
    return int((xy[1] - plan.y0) / plan.resolution), int((xy[0] - plan.x0) / plan.resolution)


def test_pit_with_a_stair_is_a_level(scans):
    plan, pits = _pits(scans["stair"])
    (pit,) = pits
    assert pit.kind == "level"
    assert pit.bottom is not None and pit.bottom.height == pytest.approx(-0.51, abs=0.02)
    link = pit.link
    assert link is not None and link.kind == "stair" and link.upper == 0
    assert len(link.risers) == 3 and link.risers[0] == pytest.approx(0.17, abs=0.005)
    assert link.tread == pytest.approx(0.28, abs=0.01)
    assert sorted(round(lv.height, 2) for lv in pit.levels) == [-0.51, -0.34, -0.17, 0.0]
    assert "pit level, bottom -0.510 m, reached from the floor by stair 3 risers" in (
        describe_pits(pits)
    )
    assert not plan.floor[_cell(plan, CENTRE)]  # guarded in the scene: never floor


@pytest.mark.parametrize("seed", [1, 2, 3])
def test_the_same_pit_seen_without_its_stair_scanner_still_shows_its_stair(seed):
    """Without the scanner that looks down the stair its treads are seen only sparsely, at
    grazing angles from the two far scanners, rows of points several cells apart with nothing
    seen between them. Joined over those unseen cells (:mod:`mjwalk.scan.sparsecells`) the
    treads are whole and the stair is the true one on every noise seed (before, 1 seed in 5
    found it, tread 0.25 m; the others read the pit as an obstacle)."""
    _, pits = _pits(_scan(STAIR, seed=seed))
    (pit,) = pits
    assert pit.kind == "level"
    link = pit.link
    assert link is not None and link.kind == "stair" and link.upper == 0
    assert len(link.risers) == 3 and link.risers[0] == pytest.approx(0.17, abs=0.005)
    assert link.tread == pytest.approx(0.28, abs=0.025)


def test_pit_without_a_stair_is_an_obstacle_never_floor(scans):
    plan, pits = _pits(scans["pit"])
    (pit,) = pits
    assert pit.kind == "pit" and pit.link is None
    assert pit.bottom is not None and pit.bottom.height == pytest.approx(-0.80, abs=0.02)
    assert pit.size == pytest.approx((2.0, 2.0), abs=0.08)  # measured 1.96-2.00 m
    assert pit.area == pytest.approx(4.0, rel=0.05)
    cell = _cell(plan, CENTRE)
    assert plan.gaps[cell] and not plan.floor[cell] and not plan.void[cell]
    boxes = gap_boxes(plan)
    assert all(b[2][2] == pytest.approx(GUARD_HEIGHT / 2) for b in boxes)
    assert any((np.abs(np.array(CENTRE) - b[1][:2]) <= b[2][:2]).all() for b in boxes)
    area = sum(4 * b[2][0] * b[2][1] for b in boxes)
    assert area == pytest.approx(pit.area, rel=0.05)
    # today's plan, asked for: the pit filled as floor (the hazard the default removes)
    pts = find_floor(scans["pit"]).apply(scans["pit"])
    old = floor_plan(pts, gaps=False)
    assert old.floor[_cell(old, CENTRE)] and old.gaps is None


def test_unscanned_hole_is_an_obstacle(scans):
    """No ray reaches the shaft's bottom: only its walls below the floor show it; 2 x 2 m is
    within the 1 m inscribed radius that unscanned holes are filled up to, and it is an obstacle
    all the same."""
    plan, pits = _pits(scans["hole"])
    (pit,) = pits
    assert pit.kind == "gap" and pit.bottom is None
    assert pit.area == pytest.approx(4.0, rel=0.05)
    assert plan.gaps[_cell(plan, CENTRE)] and not plan.floor[_cell(plan, CENTRE)]
    assert "no bottom scanned: obstacle" in describe_pits(pits)


def test_written_scene_guards_the_gap_and_refuses_a_site_in_it(scans, tmp_path):
    scene = build_scene(scans["hole"], source="hole")
    model = mujoco.MjModel.from_xml_string(scene.xml)
    names = [model.geom(g).name for g in range(model.ngeom)]
    assert any(n.startswith("scan_pit_") for n in names)
    assert "gaps in the floor" in scene.xml and scene.pits
    sites = tmp_path / "sites.toml"
    sites.write_text("[site.in_pit]\nxy = [0.0, 0.5]\n")
    with pytest.raises(ScanError, match="not on the scanned floor"):
        build_scene(scans["hole"], source="hole", sites=read_sites(sites))
    filled = build_scene(scans["hole"], ScanOptions(gaps="floor"), source="hole")
    assert "scan_pit" not in filled.xml and not filled.pits
    free = build_scene(scans["hole"], ScanOptions(voids="free"), source="hole")
    assert "scan_pit_0" in free.xml  # no void policy makes a gap walkable
    assert not free.plan.floor[_cell(free.plan, CENTRE)]


#: A 10 x 6 m hall (its floor four boxes round a 4 x 2 m opening at x in [-2, 2], y in
#: [-0.5, 1.5], walls along its long sides) whose pit, 0.51 m deep, is reached by a ramp of
#: 9.06 deg (0.51 m over 3.2 m, within norms.MAX_RAMP_SLOPE) descending along +x from the
#: opening's west rim; its flat bottom is x in [1.2, 2]. The MJCF twin is the pit_ramp_xml
#: fixture (tests/conftest.py), whose ramp the level graph links and the planner walks.
RAMP_HALL = """<mujoco><worldbody>
<geom type="box" pos="0 -1.75 -0.05" size="5 1.25 0.05"/>
<geom type="box" pos="0 2.25 -0.05" size="5 0.75 0.05"/>
<geom type="box" pos="-3.5 0.5 -0.05" size="1.5 1 0.05"/>
<geom type="box" pos="3.5 0.5 -0.05" size="1.5 1 0.05"/>
<geom type="box" pos="0 3.05 1.5" size="5 0.05 1.5"/>
<geom type="box" pos="0 -3.05 1.5" size="5 0.05 1.5"/>
<geom name="pit" type="box" pos="0 0.5 -0.56" size="2 1 0.05"/>
<geom name="ramp" type="box" pos="-0.39213 0.5 -0.30438" euler="0 9.05536 0"
 size="1.62020 1 0.05"/>
</worldbody></mujoco>"""


def test_a_pit_reached_by_a_ramp_is_a_level():
    """Seeded scan of RAMP_HALL: the pit's bottom is found at its depth and the ramp down to it
    (looked for below the floor) is its link, within 2 cm and 0.3 deg."""
    model = mujoco.MjModel.from_xml_string(RAMP_HALL)
    scanners = [(-3.0, -1.5, 1.6), (3.0, 2.0, 1.6), (2.8, 0.5, 1.7)]
    pts = synthetic_scan(model, scanners, step_deg=0.4, noise=0.005, seed=1).points
    (pit,) = _pits(pts)[1]
    assert pit.kind == "level"
    # the bottom's region at the candidate height takes in the ramp's lowest strip; the cells
    # whose points lie at the bottom's height keep it level (scanpits._flat_layer)
    assert pit.bottom is not None and pit.bottom.height == pytest.approx(-0.51, abs=0.02)
    assert pit.link is not None and pit.link.kind == "ramp" and pit.ramp is not None
    assert math.degrees(pit.ramp.slope) == pytest.approx(9.06, abs=0.3)
    assert pit.ramp.h_hi == 0.0 and pit.ramp.length == pytest.approx(3.2, abs=0.05)
    assert pit.ramp.width == pytest.approx(2.0, abs=0.05)
    assert "reached from the floor by ramp 9." in describe_pits([pit])


def test_a_slot_narrower_than_a_foot_stays_floor():
    """A 6 cm cable channel 0.3 m deep is below :data:`GAP_WIDTH` (a small foot's width)."""
    assert GAP_WIDTH == pytest.approx(0.0825)
    model = mujoco.MjModel.from_xml_string(
        """<mujoco><worldbody>
        <geom type="box" pos="0 -1.53 -0.05" size="3 1.5 0.05"/>
        <geom type="box" pos="0 1.53 -0.05" size="3 1.5 0.05"/>
        <geom type="box" pos="0 0 -0.35" size="3 0.1 0.05"/>
        </worldbody></mujoco>"""
    )
    pts = synthetic_scan(model, [(-1.5, -1.0, 1.6), (1.5, 1.0, 1.6)], step_deg=0.4, seed=2).points
    lv = find_floor(pts).apply(pts)
    plan = floor_plan(lv)
    assert not find_pits(lv, plan)
    assert plan.floor[_cell(plan, (0.0, 0.0))]


def test_cli_prints_the_gaps(tmp_path, capsys, scans):
    from mjwalk import cli

    src = tmp_path / "stair.xyz"
    np.savetxt(src, scans["stair"], fmt="%.4f")
    png = tmp_path / "top.png"
    assert cli.main(["scan", str(src), "-o", str(tmp_path / "s.xml"), "--png", str(png)]) == 0
    out = capsys.readouterr().out
    assert "gaps in the floor (unscanned, points below it): 1, 1 written as levels below" in out
    assert "stair 3 risers x 0.170 m, tread 0.28" in out
    assert png.stat().st_size > 0
    assert cli.main(["scan", str(src), "-o", str(tmp_path / "f.xml"), "--gaps", "floor"]) == 0
    out = capsys.readouterr().out
    assert "gaps in the floor" not in out and "-0.51 m" in out  # still said, as before


def test_flat_scans_give_exactly_todays_xml():
    """Where a scan has no gap, looking for gaps changes nothing: the MJCF is byte-identical to
    the one written with ``gaps="floor"`` (the pipeline before gaps were looked for, which
    :func:`mjwalk.scan.obstacles.floor_plan` keeps exactly with ``gaps=False``), for seeded
    synthetic scans: a flat room with a box, the same seen from two scanners with
    ``voids="fill"``, and the small hall of rectangular levels and a stair
    (tests/scan/test_scanlevels.py). On 5553d3d the three were also checked byte-identical to
    that tree's output (sha256 17bc9f90, da0a36f9, 4e2a6656 in this venv); the digests are not
    asserted here because they depend on the MuJoCo and NumPy versions pip installs."""
    from test_scanlevels import LEVELS_XML
    from test_scanlevels import SCANNERS as HALL_SCANNERS

    flat = """<mujoco><worldbody><geom name="floor" type="plane" size="3 3 0.05"/>
        <geom name="box" type="box" pos="1 0 0.5" size="0.3 0.3 0.5"/></worldbody></mujoco>"""
    cases = {
        "flat": (flat, [(-1.0, 0.0, 1.5)], 1, ScanOptions()),
        "flat_fill": (flat, [(-1.0, 0.0, 1.5), (2.0, 2.0, 1.6)], 1, ScanOptions(voids="fill")),
        "hall": (LEVELS_XML, HALL_SCANNERS, 3, ScanOptions()),
    }
    for name, (xml, scanners, seed, opts) in cases.items():
        model = mujoco.MjModel.from_xml_string(xml)
        scan = synthetic_scan(model, scanners, step_deg=0.5 if "flat" in name else 0.4,
                              noise=0.005, seed=seed)  # fmt: skip
        out = build_scene(scan.points, opts, source=name).xml
        old = build_scene(scan.points, replace(opts, gaps="floor"), source=name).xml
        assert out == old, name


@pytest.mark.parametrize(
    "name", ["pcl-room-scan/room_scan1.pcd", "e57-pump-room/pumpAVisualReferenceImage.e57"]
)
def test_real_scans_noise_below_the_floor_is_no_gap(shared_data, name):
    """The shared real scans are flat: their few points 5-10 cm below the floor (range noise,
    single cells) make no gap, and their floor plans are those without gaps looked for."""
    from mjwalk.scan.read import read_scan

    cloud = read_scan(shared_data / "scans" / name)
    pts = find_floor(cloud.points).apply(cloud.points)
    plan, old = floor_plan(pts), floor_plan(pts, gaps=False)
    assert not plan.gaps.any() and not find_pits(pts, plan)
    assert (plan.floor == old.floor).all() and (plan.void == old.void).all()
    assert plan.holes_filled == old.holes_filled


def test_a_stair_at_the_step_rule_bound_is_a_stair_on_the_grid():
    """Three 0.146 m risers over 0.352 m treads (hall 12 of bench_unseen: 2 r + a = 0.644 m,
    within DIN 18065's 0.59-0.65 m) down into the opening from x = -0.996: on the 2 cm grid
    the treads' edges read 0.36 m apart, 2 r + a = 0.652 m, and the flight was taken for three
    single steps. Within a cell of the grid over its one tread step it is a stair."""
    x0, a, r = -0.996, 0.352, 0.146
    body = f"""<geom name="pit" type="box" pos="{(x0 + 2 * a + 1) / 2:.4f} 0.5 {-3 * r - 0.05:.4f}"
      size="{(1 - x0 - 2 * a) / 2:.4f} 1 0.05"/>
<geom name="s1" type="box" pos="{x0 + a / 2:.4f} 0.5 {(-r - 0.53) / 2:.4f}"
      size="{a / 2:.4f} 1 {(0.53 - r) / 2:.4f}"/>
<geom name="s2" type="box" pos="{x0 + 1.5 * a:.4f} 0.5 {(-2 * r - 0.53) / 2:.4f}"
      size="{a / 2:.4f} 1 {(0.53 - 2 * r) / 2:.4f}"/>"""
    _, pits = _pits(_scan(body, STAIR_SCANNERS))
    (pit,) = pits
    link = pit.link
    assert link is not None and link.kind == "stair" and link.upper == 0
    assert len(link.risers) == 3 and link.risers[0] == pytest.approx(r, abs=0.005)
    assert link.tread == pytest.approx(a, abs=0.02)


@pytest.mark.slow  # about 15 s CPU (the scan), over a minute under load
def test_a_pit_stair_of_the_largest_risers_in_a_generated_hall(tmp_path):
    """levelgen's hall 108 (seeded): a pit 0.57 m deep reached by three 0.19 m risers (DIN
    18065's largest) and 0.2619 m treads. Its top tread measures 0.1901 m below the floor, over
    the limit by less than the scan's riser tolerance (``planefit.RISER_TOL``): the pit is a
    level and its flight a stair (before: no step from the floor, the pit an obstacle)."""
    from mjwalk.world.levelgen import generate_levels
    from mjwalk.world.workplace import load_model

    hall = generate_levels(108)
    xml = tmp_path / "hall.xml"
    xml.write_text(hall.xml)
    scan = synthetic_scan(load_model(xml), list(hall.scanners), step_deg=0.4, noise=0.005, seed=108)
    scene = build_scene(scan.points, source="hall108")
    (pit,) = [p for p in scene.pits if p.bottom is not None]
    assert pit.kind == "level" and pit.bottom.height == pytest.approx(-0.57, abs=0.02)
    link = pit.link
    assert link is not None and link.kind == "stair" and len(link.risers) == 3
    assert link.risers[0] == pytest.approx(0.19, abs=0.005)
    # written at the norm's limit: the written scene's level graph links the pit by its stair
    graph = level_graph(find_walk_surfaces(mujoco.MjModel.from_xml_string(scene.xml)))
    (down,) = [k for k in graph.links if graph.levels[k.lower].height < -0.5]
    assert down.kind == "stair" and len(down.risers) == 3


def test_a_stair_measured_within_the_tolerance_over_the_limit_is_written_at_it():
    """A pit's flight of three risers measured 0.1904 m (within ``planefit.RISER_TOL`` of the
    0.19 m limit): its bottom and treads move to multiples of 0.19 m less WRITE_MARGIN below
    the floor; a flight within the norm is left as measured."""
    cells = np.zeros((4, 4), bool)
    lv = [ScanLevel(k, "tread", h, 0.0, 0.0, cells, 0.0, 0.3, 1.0, 0) for k, h in
          enumerate((0.0, -0.5712, -0.3808, -0.1904))]  # fmt: skip
    link = ScanLink("stair", 1, 0, (0.1904,) * 3, 0.27, (2, 3))
    new_link, new_levels = within_norm(link, tuple(lv))
    riser = MAX_RISER - WRITE_MARGIN  # inside the limit, so the written boxes keep it
    assert new_link.risers == (riser,) * 3
    assert [x.height for x in new_levels] == pytest.approx([0.0, -3 * riser, -2 * riser, -riser])
    ok = ScanLink("stair", 1, 0, (0.17,) * 3, 0.27, (2, 3))
    assert within_norm(ok, tuple(lv)) == (ok, tuple(lv))
