"""mjwalk.scan.scanramps: ramps of a scan fitted, written as tilted boxes, linked (issue 47)."""

from __future__ import annotations

import math

import mujoco
import numpy as np
import pytest

from mjwalk.errors import ScanError
from mjwalk.scan import build_scene
from mjwalk.scan.level import find_floor
from mjwalk.scan.levelboxes import describe
from mjwalk.scan.obstacles import floor_plan
from mjwalk.scan.raycast import synthetic_scan
from mjwalk.scan.scanlevels import find_levels, find_regions
from mjwalk.scan.scanramps import ScanRamp, find_ramps, ramp_box, within_limit, within_noise
from mjwalk.scan.scene import read_sites
from mjwalk.scan.stairfit import WRITE_MARGIN
from mjwalk.world.levels import level_graph
from mjwalk.world.norms import MAX_RAMP_SLOPE
from mjwalk.world.surfaces import find_walk_surfaces


def _hall(deg: float) -> str:
    """A deck 0.30 m high (x -2.5..-0.5, y -1..1) reached only by a ramp of ``deg`` degrees
    down towards +x (a 0.1 m slab, 1.0 m wide), and a 0.75 m table."""
    th = math.radians(deg)
    run = 0.3 / math.tan(th)
    xm = -0.5 + 0.5 * run
    pos = (xm - 0.05 * math.sin(th), 0.0, 0.15 - 0.05 * math.cos(th))
    half = 0.5 * run / math.cos(th)
    return f"""<mujoco><worldbody>
  <geom name="floor" type="plane" size="5 3 0.05"/>
  <geom name="deck" type="box" pos="-1.5 0 0.15" size="1.0 1.0 0.15"/>
  <geom name="ramp" type="box" pos="{pos[0]:.6f} 0 {pos[2]:.6f}" size="{half:.6f} 0.5 0.05"
        euler="0 {deg} 0"/>
  <geom name="table" type="box" pos="1.0 -2.0 0.375" size="0.5 0.3 0.375"/>
</worldbody></mujoco>"""


SCANNERS = [(1.5, 1.5, 1.6), (-1.5, -1.8, 1.7), (3.5, -0.6, 1.6), (-3.2, 1.5, 1.6)]


def _scan(deg: float):
    model = mujoco.MjModel.from_xml_string(_hall(deg))
    return synthetic_scan(model, SCANNERS, step_deg=0.4, noise=0.005, seed=5)


@pytest.fixture(scope="module")
def ramp_scan():
    """A seeded synthetic scan (0.4 deg rays, 5 mm range noise, 1.5 deg tilt) of the hall with
    a 6 deg ramp."""
    return _scan(6.0)


def test_ramp_is_fitted_between_floor_and_deck(ramp_scan):
    pts = find_floor(ramp_scan.points).apply(ramp_scan.points)
    plan = floor_plan(pts)
    regions, _, _ = find_regions(pts, plan)
    ramps = find_ramps(pts, plan, regions)
    assert len(ramps) == 1
    r = ramps[0]
    assert regions[r.lower].height == 0.0
    assert regions[r.upper].height == pytest.approx(0.30, abs=0.01)
    assert math.degrees(r.slope) == pytest.approx(6.0, abs=0.5)
    assert r.run @ [-1.0, 0.0] == pytest.approx(1.0, abs=1e-6)  # climbs towards -x
    assert -r.s_hi == pytest.approx(-0.5, abs=0.03)  # meets the deck's edge
    assert -r.s_lo == pytest.approx(-0.5 + 0.3 / math.tan(math.radians(6)), abs=0.1)
    assert r.width == pytest.approx(1.0, abs=0.06)
    # by steps alone the deck is no level: the ramp is its only way up
    assert len(find_levels(pts, plan)[0]) == 1


def test_ramp_link_in_the_scan_and_in_the_written_scene(ramp_scan):
    scene = build_scene(ramp_scan.points, source="ramp hall")
    lp = scene.levels
    assert lp is not None and [lv.kind for lv in lp.levels] == ["floor", "platform"]
    (link,) = lp.links
    assert link.kind == "ramp" and (link.lower, link.upper) == (0, 1)
    assert math.degrees(link.slope) == pytest.approx(6.0, abs=0.5)
    assert link.rise == pytest.approx(lp.heights[1], abs=1e-9)
    assert "ramp  L0 -> L1  rise 0.30" in describe(lp)
    assert 'material="scan_ramp"' in scene.xml and "xyaxes=" in scene.xml
    graph = level_graph(find_walk_surfaces(mujoco.MjModel.from_xml_string(scene.xml)))
    ramps = [k for k in graph.links if k.kind == "ramp"]
    assert len(ramps) == 1
    assert math.degrees(ramps[0].slope) == pytest.approx(6.0, abs=0.5)
    assert sorted(lv.height for lv in graph.levels) == pytest.approx(lp.heights, abs=1e-3)
    # the ramp's floor obstacles are gone; the table stays one
    plan = scene.plan
    r = plan.resolution
    for x, y, obstacle in ((1.0, 0.0, False), (1.0, -2.0, True)):
        ix, iy = int((x - plan.x0) / r), int((y - plan.y0) / r)
        assert (plan.obstacles[iy, ix] > 0) == obstacle


def test_too_steep_a_ramp_is_no_ramp():
    """15 deg is steeper than norms.MAX_RAMP_SLOPE (10 deg): it stays an obstacle, the deck no
    level."""
    scan = _scan(15.0)
    assert build_scene(scan.points).levels is None


def test_a_ramp_measured_a_hair_over_the_limit_is_written_at_it():
    """A 10.02 deg ramp: seed 5 fits its plane at 10.0023 deg, within ``TRIM_SIGMAS`` of the
    fit's standard error (0.008 deg) over ``norms.MAX_RAMP_SLOPE``: the scan cannot tell it
    from a 10 deg ramp (as a riser within ``planefit.RISER_TOL`` of DIN 18065's), so it is a
    ramp, written at the limit less ``stairfit.WRITE_MARGIN`` of rise, and a ramp in the
    written scene (before: refused, the deck no level). 10.1 deg is still no ramp."""
    scene = build_scene(_scan(10.02).points)
    assert scene.levels is not None
    (ramp,) = [k for k in scene.levels.links if k.kind == "ramp"]
    assert MAX_RAMP_SLOPE - math.radians(0.01) < ramp.slope < MAX_RAMP_SLOPE
    surfaces = find_walk_surfaces(mujoco.MjModel.from_xml_string(scene.xml))
    assert [k.kind for k in level_graph(surfaces).links] == ["ramp"]
    assert build_scene(_scan(10.1).points).levels is None


def _ramp(deg: float, rise: float = 0.3) -> ScanRamp:
    """A ramp along +x from s = 0 up ``rise`` at ``deg`` degrees."""
    run = rise / math.tan(math.radians(deg))
    slope = math.radians(deg)
    return ScanRamp(0, 1, np.array([1.0, 0.0]), 0.0, run, -0.5, 0.5, 0.0, rise, 0.001, slope)


def test_within_noise_and_within_limit():
    limit = math.tan(MAX_RAMP_SLOPE)
    assert within_noise(limit + 2.9e-4, 1e-4) and not within_noise(limit + 3.1e-4, 1e-4)
    steep = within_limit(_ramp(10.001))
    assert steep.s_hi == _ramp(10.001).s_hi and steep.s_lo < 0.0  # the low end moved out
    assert steep.h_hi - steep.h_lo == pytest.approx(limit * steep.length - WRITE_MARGIN)
    assert steep.slope < MAX_RAMP_SLOPE
    gentle = _ramp(9.0)
    assert within_limit(gentle) is gentle  # within the limit: unchanged


def test_ramp_box_top_face_meets_both_levels():
    ramp = ScanRamp(0, 1, np.array([0.6, 0.8]), 1.0, 4.0, -0.5, 0.5, 0.1, 0.4, 0.003, 0.1)
    _, pos, half, material, xyaxes = ramp_box(ramp, "r")
    ex, ey = xyaxes[:3], xyaxes[3:]
    ez = np.cross(ex, ey)
    top = pos + half[2] * ez
    low, high = top - half[0] * ex, top + half[0] * ex
    assert low[:2] @ ramp.run == pytest.approx(1.0) and low[2] == pytest.approx(0.1)
    assert high[:2] @ ramp.run == pytest.approx(4.0) and high[2] == pytest.approx(0.4)
    assert 2 * half[1] == pytest.approx(1.0) and material == "scan_ramp"
    bottom_high = high - 2 * half[2] * ez  # under the high end the box reaches the lower level
    assert bottom_high[2] == pytest.approx(0.1)
    assert math.degrees(ramp.slope) == pytest.approx(math.degrees(math.atan(0.1)))


def _sites(tmp_path, text: str):
    path = tmp_path / "sites.toml"
    path.write_text(text)
    return read_sites(path)


def test_sites_stand_on_levels(ramp_scan, tmp_path):
    """A site on the deck is written at the deck's height, one on the floor at 0; a site picked
    in the scan on the deck too; one on the ramp or the table is refused."""
    sites = _sites(tmp_path, "[site.deck]\nxy = [-1.5, 0.3]\n[site.floor]\nxy = [2.0, 2.0]\n")
    scene = build_scene(ramp_scan.points, sites=sites)
    h = scene.levels.heights[1]
    assert scene.site_z == {"deck": pytest.approx(h), "floor": 0.0}
    assert f'<site name="deck" pos="-1.5000 0.3000 {h:.4f}"' in scene.xml
    assert '<site name="floor" pos="2.0000 2.0000 0.0"' in scene.xml
    model = mujoco.MjModel.from_xml_string(scene.xml)
    assert model.site("deck").pos[2] == pytest.approx(0.30, abs=0.01)
    picked = np.linalg.solve(scene.matrix, [-1.5, 0.3, 0.3, 1.0])[:3]  # in the scan's frame
    text = f"[site.p]\nscan = [{picked[0]:.6f}, {picked[1]:.6f}, {picked[2]:.6f}]\n"
    by_scan = build_scene(ramp_scan.points, sites=_sites(tmp_path, text))
    assert by_scan.site_z["p"] == pytest.approx(h)
    for x, y in ((1.0, 0.0), (1.0, -2.0)):  # the ramp, the table
        bad = _sites(tmp_path, f"[site.x]\nxy = [{x}, {y}]\n")
        with pytest.raises(ScanError, match="not on the scanned floor or a level"):
            build_scene(ramp_scan.points, sites=bad)


def test_a_long_shallow_ramp_scanned_sparsely_is_one_ramp():
    """A 0.387 m deck reached by a 3.9 deg ramp 5.7 m long (hall 12 of bench_unseen), scanned
    from its foot and from over the deck: half-way the ramp's points lie 4-5 cm apart, wider
    than the 2 cm grid, so its cells fell apart and the part meeting the group was too short to
    reach the deck. Seeded synthetic scan (0.4 deg rays, 5 mm noise)."""
    th = math.radians(3.9)
    run = 0.387 / math.tan(th)
    x, z = -0.5 + 0.5 * run - 0.05 * math.sin(th), 0.1935 - 0.05 * math.cos(th)
    half = 0.5 * run / math.cos(th)
    xml = f"""<mujoco><worldbody>
  <geom name="floor" type="plane" size="8 4 0.05"/>
  <geom name="deck" type="box" pos="-1.75 0 0.1935" size="1.25 1.25 0.1935"/>
  <geom name="ramp" type="box" pos="{x:.6f} 0 {z:.6f}" size="{half:.6f} 0.58 0.05"
        euler="0 3.9 0"/>
</worldbody></mujoco>"""
    scanners = [(-0.5 + run + 1.2, 0.35, 1.6), (-1.75, -0.3, 0.387 + 1.6)]
    model = mujoco.MjModel.from_xml_string(xml)
    scan = synthetic_scan(model, scanners, step_deg=0.4, noise=0.005, seed=3)
    lp = build_scene(scan.points, source="long ramp").levels
    assert lp is not None and len(lp.heights) == 2
    assert lp.heights[1] == pytest.approx(0.387, abs=0.01)
    (link,) = lp.links
    assert link.kind == "ramp" and (link.lower, link.upper) == (0, 1)
    assert math.degrees(link.slope) == pytest.approx(3.9, abs=0.3)
    assert link.run == pytest.approx(run, abs=0.15)


@pytest.mark.slow  # a whole hall's synthetic scan: 76 s under load
def test_a_ramp_up_to_a_deck_narrower_than_its_scanners_blind_cone(tmp_path):
    """Generated hall 107 (bench_unseen): a 0.543 m deck 1.67 m deep, reached by an 8.4 deg
    ramp, scanned from 1.6 m over its centre. The scanner's 30 deg blind cone leaves a disc of
    radius 0.92 m that the other scanners see only sparsely, from edge to edge of the deck: its
    2 cm cells fell apart, the region kept one side (1.2 m² of 4.66), the other side's points
    joined the ramp's voxel group and tilted its plane (rms 43 mm): no ramp. Joined at the
    voxel scale over the cells no point was seen in (:mod:`mjwalk.scan.sparsecells`) the deck
    is one region and the ramp is found. Seeded synthetic scan (0.4 deg rays, 5 mm noise) from
    the hall's scanners."""
    from mjwalk.world.levelgen import generate_levels
    from mjwalk.world.workplace import load_model

    hall = generate_levels(107)
    model = load_model(hall.write(tmp_path / "levels_107.xml"))
    (true,) = [k for k in hall.links if k.kind == "ramp"]
    deck = model.geom("ramp_deck")
    area = 4 * float(deck.size[0] * deck.size[1])
    pts = synthetic_scan(model, list(hall.scanners), step_deg=0.4, noise=0.005, seed=107).points
    pts = find_floor(pts).apply(pts)
    plan = floor_plan(pts)
    regions, _, _ = find_regions(pts, plan)
    at = [r for r in regions if abs(r.height - true.upper) <= 0.02 and r.area >= 0.5 * area]
    assert len(at) == 1 and at[0].area >= 0.95 * area  # the whole deck (and a ramp's strip)
    ramps = find_ramps(pts, plan, regions)
    assert len(ramps) == 1
    r = ramps[0]
    assert regions[r.lower].height == 0.0 and regions[r.upper] is at[0]
    rect = np.asarray(model.geom("ramp_ramp").size)
    run = 2 * float(rect[0]) * math.cos(math.asin(true.upper / (2 * float(rect[0]))))
    assert r.length == pytest.approx(run, abs=0.1)
    assert r.width == pytest.approx(2 * float(rect[1]), abs=0.06)
