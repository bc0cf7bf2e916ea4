"""mjwalk.scan.levelboxes and scanlevels: a stair tread whose back lies in the shadow of the
next level's edge is seen shallower than a tread; the flight's regular run is used, not the
tread dropped (issue 47, scan47)."""

from __future__ import annotations

import mujoco
import numpy as np
import pytest

from mjwalk.scan.level import find_floor
from mjwalk.scan.levelboxes import scan_levels
from mjwalk.scan.obstacles import floor_plan
from mjwalk.scan.raycast import synthetic_scan

#: A stair of five 0.17 m risers and 0.28 m treads rising along +x to a 0.85 m deck, and a
#: 0.12 m ledge 0.18 m deep (shallower than a tread, no flight's: never a level).
TREADS = "\n".join(
    f'  <geom name="t{k}" type="box" pos="{0.28 * k - 0.14:.2f} 0 {0.085 * k:.3f}" '
    f'size="0.14 0.6 {0.085 * k:.3f}"/>'
    for k in range(1, 5)
)
STAIR_XML = f"""<mujoco><worldbody>
  <geom name="floor" type="plane" size="4 3 0.05"/>
{TREADS}
  <geom name="deck" type="box" pos="1.87 0 0.425" size="0.75 1.2 0.425"/>
  <geom name="ledge" type="box" pos="-2.0 2.0 0.06" size="0.09 0.6 0.06"/>
</worldbody></mujoco>"""
SCANNERS = [(-1.2, 0.4, 1.6), (-2.4, -0.5, 1.7), (2.2, 0.6, 2.35)]


def _scan(shadow: float):
    """The seeded scan, levelled, with the top tread's back ``shadow`` metres taken out (what
    the deck's edge hides from a scanner on it looking down the flight)."""
    model = mujoco.MjModel.from_xml_string(STAIR_XML)
    pts = synthetic_scan(model, SCANNERS, step_deg=0.4, noise=0.005, seed=4).points
    pts = find_floor(pts).apply(pts)
    hidden = (pts[:, 0] > 1.12 - shadow) & (pts[:, 0] < 1.12) & (np.abs(pts[:, 2] - 0.68) < 0.03)
    pts = pts[~hidden]
    return scan_levels(pts, floor_plan(pts))


@pytest.mark.parametrize("shadow", [0.0, 0.05, 0.09])
def test_a_top_tread_seen_in_part_keeps_the_stair_and_the_deck(shadow):
    lp = _scan(shadow)
    assert lp is not None
    stairs = [k for k in lp.links if k.kind == "stair"]
    assert len(stairs) == 1, [(k.kind, k.lower, k.upper) for k in lp.links]
    s = stairs[0]
    assert len(s.risers) == 5 and s.risers[0] == pytest.approx(0.17, abs=0.005)
    assert s.tread == pytest.approx(0.28, abs=0.01)
    assert lp.heights[s.upper] == pytest.approx(0.85, abs=0.02)
    top = s.via[-1]  # the top tread's box: the flight's full tread, not the part seen
    q = lp.rects[top] @ np.array([1.0, 0.0])
    assert q.max() - q.min() == pytest.approx(0.28, abs=0.01)


def test_a_ledge_shallower_than_a_tread_is_no_level():
    lp = _scan(0.09)
    assert lp is not None
    assert not any(abs(h - 0.12) < 0.01 for h in lp.heights)


def _hall_scan(seed: int):
    """Generated hall ``seed`` (:mod:`mjwalk.world.levelgen`) scanned as ``bench_unseen``
    scans it (0.4 deg rays, 5 mm noise, the hall's scanner spots), levelled, and its plan."""
    import tempfile
    from pathlib import Path

    from mjwalk.world.levelgen import generate_levels
    from mjwalk.world.workplace import load_model

    hall = generate_levels(seed)
    with tempfile.TemporaryDirectory() as tmp:
        model = load_model(hall.write(Path(tmp) / "hall.xml"))
    pts = synthetic_scan(model, list(hall.scanners), step_deg=0.4, noise=0.005, seed=seed).points
    pts = find_floor(pts).apply(pts)
    return pts, floor_plan(pts)


@pytest.mark.slow  # a generated hall's scan: about 40 s on a loaded 2-core machine
def test_generated_hall_1_keeps_its_mezzanine_stair():
    """Hall 1: eight 0.1431 m risers, 0.3422 m treads to a 1.145 m mezzanine; the deck's edge
    hides the top tread's back (0.22 of it seen) and the tread below's last 4 cm."""
    pts, plan = _hall_scan(1)
    lp = scan_levels(pts, plan)
    assert lp is not None
    stairs = [k for k in lp.links if k.kind == "stair" and len(k.risers) == 8]
    assert len(stairs) == 1
    assert stairs[0].risers[0] == pytest.approx(0.1431, abs=0.005)
    assert stairs[0].tread == pytest.approx(0.3422, abs=0.01)
    assert lp.heights[stairs[0].upper] == pytest.approx(1.1448, abs=0.02)


@pytest.mark.slow  # a generated hall's scan: about 40 s on a loaded 2-core machine
def test_generated_hall_0_finds_a_tread_beside_a_stronger_surface():
    """Hall 0: the stair's 0.3766 m tread lies 4 cm over a 0.337 m platform elsewhere (found at
    a second candidate height) and shares a riser's line of cells with the tread above it: a
    region at another height sharing only its rim cells is no duplicate."""
    from mjwalk.scan.scanlevels import find_regions

    pts, plan = _hall_scan(0)
    found, _, _ = find_regions(pts, plan)
    treads = [r.height for r in found if r.kind == "tread"]
    for h in (0.1883, 0.3766, 0.5649, 0.7532):
        assert min(abs(t - h) for t in treads) < 0.01, (h, sorted(treads))


def _written_links(pts, lp):
    """The stairs of the scene the scan writes, as the MJCF level graph finds them: (lower
    height, upper height, risers)."""
    import mujoco

    from mjwalk.scan.scene import build_scene
    from mjwalk.world.levels import level_graph
    from mjwalk.world.surfaces import find_walk_surfaces

    scene = build_scene(pts, source="hall")
    graph = level_graph(find_walk_surfaces(mujoco.MjModel.from_xml_string(scene.xml)))
    h = [lv.height for lv in graph.levels]
    return {(round(h[k.lower], 2), round(h[k.upper], 2), len(k.risers)) for k in graph.links
            if k.kind == "stair"}  # fmt: skip


@pytest.mark.slow  # a generated hall's scan: about 60 s on a loaded 2-core machine
def test_generated_hall_0_infers_its_hidden_top_tread():
    """Hall 0: seven 0.1883 m risers, 0.2675 m treads to a 1.318 m mezzanine; its top tread lies
    under the mezzanine's edge (about 0.10 of it seen, no region). The flight's regular rise and
    run put it back (:mod:`mjwalk.scan.hiddentread`), and the written scene climbs the flight
    to the mezzanine (written in parts: its landing strip is one of them)."""
    pts, plan = _hall_scan(0)
    lp = scan_levels(pts, plan)
    assert lp is not None
    stairs = [k for k in lp.links if k.kind == "stair" and len(k.risers) == 7]
    assert len(stairs) == 1
    assert stairs[0].risers[0] == pytest.approx(0.1883, abs=0.005)
    assert stairs[0].tread == pytest.approx(0.2675, abs=0.01)
    assert lp.heights[stairs[0].upper] == pytest.approx(1.3181, abs=0.02)
    assert (0.0, 1.32, 7) in _written_links(pts, lp)


@pytest.mark.slow  # a generated hall's scan: about 60 s on a loaded 2-core machine
def test_generated_hall_8_climbs_its_upper_flight_from_the_landing():
    """Hall 8: a 0.760 m landing, then turned 90 deg, four 0.1521 m risers and 0.3236 m treads
    to a 1.369 m mezzanine; the landing's strip before the upper flight's first riser is seen
    by no scanner (:mod:`mjwalk.scan.regionsteps`)."""
    pts, plan = _hall_scan(8)
    lp = scan_levels(pts, plan)
    assert lp is not None
    h = lp.heights
    upper = [k for k in lp.links if k.kind == "stair" and abs(h[k.lower] - 0.7605) < 0.02]
    assert len(upper) == 1
    assert len(upper[0].risers) == 4 and upper[0].risers[0] == pytest.approx(0.1521, abs=0.005)
    assert upper[0].tread == pytest.approx(0.3236, abs=0.01)
    assert h[upper[0].upper] == pytest.approx(1.3689, abs=0.02)
    assert (0.76, 1.37, 4) in _written_links(pts, lp)


@pytest.mark.slow  # a generated hall's scan: about 40 s on a loaded 2-core machine
def test_generated_hall_1016_keeps_its_flight_turned_against_the_grid():
    """Hall 1016: eight 0.1782 m risers, 0.2822 m treads climbing at 126 deg from +x (36 deg
    against the floor plan's grid) to a 1.4256 m mezzanine, its top tread seen 0.19 m deep. A
    cell spans 0.028 m along that climb; with edges allowed 0.02 m cells the flight was refused
    (a back edge 0.0475 m past the next front's line, tolerance 0.045 m), its top tread dropped
    and the mezzanine unreachable (base 1eaa92b)."""
    pts, plan = _hall_scan(1016)
    lp = scan_levels(pts, plan)
    assert lp is not None
    stairs = [k for k in lp.links if k.kind == "stair" and len(k.risers) == 8]
    assert len(stairs) == 1, [(k.kind, len(k.risers)) for k in lp.links]
    assert stairs[0].risers[0] == pytest.approx(0.1782, abs=0.005)
    assert stairs[0].tread == pytest.approx(0.2822, abs=0.01)
    assert lp.heights[stairs[0].upper] == pytest.approx(1.4256, abs=0.02)
    assert any(abs(h - 1.2474) < 0.02 for h in lp.heights)
