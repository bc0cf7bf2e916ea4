"""Ramps beside a walk: a floor walk cutting past a ramp's low end (mjwalk.plan.rampside)."""

import math

import mujoco
import numpy as np
import pytest

from mjwalk.body.legs.legheights import step_surfaces
from mjwalk.body.legs.rampreach import SOLE_GRID_SAG, level_planes
from mjwalk.gait.default import default_model
from mjwalk.plan.levelroute import crossings
from mjwalk.plan.rampside import (
    LOW_KEY,
    META_KEY,
    head_heights,
    over_ramp,
    ramp_plane,
    ramps_beside,
    surface_plane,
    with_ramps_beside,
)
from mjwalk.plan.walks import plan_walk
from mjwalk.timeline import collision_report, timeline_from_walk
from mjwalk.world import load_workplace
from mjwalk.world.levelgen import generate_levels

#: A 12 x 8 m floor with a 0.34 m deck (x -4 to -2) reached by a 5.5 deg ramp (the shipped
#: multi-level station's: a 0.1 m slab, top face from (x -2.0, z 0.34) down to (x 1.531, z 0)
#: along +x, 1 m wide); the floor level's obstacles start 0.05 m up, so the ramp's last 0.52 m
#: (x 1.01 to 1.53) is open floor to the planner. Walks go north past the ramp's foot at x = X.
SCENE = """<mujoco model="ramp_side">
  <worldbody>
    <geom name="floor" type="plane" pos="0 0 0" size="6 4 0.05"/>
    <geom name="deck" type="box" size="1.0 0.5 0.17" pos="-3.0 0 0.17"/>
    <geom name="deck_ramp" type="box" size="1.773683 0.5 0.05" pos="-0.239275 0 0.120230"
          euler="0 5.5 0"/>
  </worldbody>
</mujoco>
"""

X = 1.35


@pytest.fixture(scope="module")
def scene(tmp_path_factory):
    path = tmp_path_factory.mktemp("rampside") / "ramp_side.xml"
    path.write_text(SCENE)
    return path


@pytest.fixture(scope="module")
def model():
    return default_model(progress=False)


def _sole_depth(timeline, ramp: str) -> float:
    """The deepest any sole (foot_*, toes_*) goes into the geom ``ramp`` over the timeline, m."""
    m = timeline.model
    names = [mujoco.mj_id2name(m, mujoco.mjtObj.mjOBJ_GEOM, i) or "" for i in range(m.ngeom)]
    soles = {i for i, n in enumerate(names) if "/foot_" in n or "/toes_" in n}
    rg, d, deepest = names.index(ramp), mujoco.MjData(m), 0.0
    for q in timeline.qpos:
        d.qpos[:] = q
        mujoco.mj_kinematics(m, d)
        mujoco.mj_collision(m, d)
        for c in d.contact[: d.ncon]:
            pair = {int(c.geom[0]), int(c.geom[1])}
            if rg in pair and pair & soles:
                deepest = max(deepest, -float(c.dist))
    return deepest


def test_the_scene_s_ramp_foot_is_open_floor_to_the_planner(scene):
    """The premise: the ramp is one surface of the scene, and its obstacle footprint on the
    floor stops 0.52 m short of its foot (the 0.05 m band), where the walks pass."""
    wp = load_workplace(scene)
    ramp = [s for s in wp.levels.surfaces if s.is_ramp]
    assert len(ramp) == 1
    (fp,) = [o for o in wp.obstacles if o.name == "deck_ramp"]
    assert fp.vertices[:, 0].max() == pytest.approx(
        1.531 - 0.05 / math.tan(math.radians(5.5)), abs=0.01
    )


@pytest.mark.parametrize("seed", [0, 2])
def test_a_floor_walk_past_a_ramp_s_foot_stands_on_it(scene, model, seed):
    """Seeded: a floor walk north past the ramp's foot (never crossing it) names the ramp
    beside it, its feet over the ramp stand on the ramp's plane (pitched to it where it carries
    heel and ball, else level on the highest point under the sole,
    :func:`mjwalk.body.legs.rampreach.level_feet_on_ramps`) and the animated walk has no
    contact. Before (fed66aa): the feet stayed at floor height, soles 14.6 mm (seed 0)
    and 14.9 mm (seed 2) into the ramp, 43 and 15 contacts (seeds 1 and 3: 8.8 and 17.1 mm,
    0 and 41; now 0 mm and 0 contacts). Left: seed 2's toes, pushing off from
    the floor beside the ramp's corner, touch its plane 2.9 mm deep (a foot's own clearance,
    under the contact check's 10 mm tolerance for a sole on a walk surface)."""
    wp = load_workplace(scene)
    walk = plan_walk(wp, (X, -2.0, math.pi / 2), (X, 2.0), model, rng=seed)
    assert walk.is_flat and "levels" not in walk.meta  # planned as any floor walk
    marked = with_ramps_beside(wp, walk, 1.75)
    assert META_KEY not in walk.meta  # the planned walk is left as it is
    (plane,) = marked.meta[META_KEY]
    assert plane["slope"] == pytest.approx(math.radians(5.5), abs=1e-3)
    on = [s for s in step_surfaces(marked) if s.land > 0.0]
    assert max(s.land for s in on) > 0.005  # some foot lands on the ramp, above the floor
    # pitched to the plane where it carries heel and ball, else level on its highest point
    assert all(abs(s.land_pitch) > 0.0 or s.land >= SOLE_GRID_SAG for s in on)
    tl = timeline_from_walk(walk, scene)
    assert collision_report(tl) == []
    assert _sole_depth(tl, "deck_ramp") <= 0.003


def test_walks_away_from_a_ramp_and_flat_scenes_name_none(scene, scenes_dir, model):
    """A floor walk 2 m from the ramp names none; nor do the shipped station's floor walks to
    and from the floor before the ramp's foot (their soles stay off it: their legs stay the
    flat synthesis's), nor any walk in a scene without ramps; a walk over levels leaves out
    the ramp its route crosses."""
    wp = load_workplace(scene)
    far = plan_walk(wp, (X + 2.0, -2.0, math.pi / 2), (X + 2.0, 2.0), model, rng=0)
    assert ramps_beside(wp, far, 1.75) == []
    assert with_ramps_beside(wp, far, 1.75) is far
    flat = load_workplace(scenes_dir / "open_floor.xml")
    walk = plan_walk(flat, (-1.0, -1.0), (1.0, 1.0), model, rng=0)
    assert ramps_beside(flat, walk, 1.75) == []
    station = load_workplace(scenes_dir / "multilevel_station.xml")
    for ends in (("stand_car3", "stand_ramp"), ("stand_ramp", "stand_car1")):
        assert ramps_beside(station, plan_walk(station, *ends, model, rng=0), 1.75) == []
    up = plan_walk(station, "stand_ramp", "stand_platform2", model, rng=3)
    assert "ramp" in [e["kind"] for e in up.meta["levels"]["route"]]
    assert META_KEY not in with_ramps_beside(station, up, 1.75).meta


def test_level_planes_of_a_floor_walk_make_every_step_level(scene, model):
    """A walk without a route over levels: its ramps beside are its planes, every step level;
    without them, none (the legs leave it flat)."""
    wp = load_workplace(scene)
    walk = plan_walk(wp, (X, -2.0, math.pi / 2), (X, 2.0), model, rng=0)
    assert level_planes(walk, len(walk.steps)) == ([], [True] * len(walk.steps))
    planes, level = level_planes(with_ramps_beside(wp, walk, 1.75), len(walk.steps))
    assert len(planes) == 1 and level == [True] * len(walk.steps)
    assert np.isfinite(planes[0]["run"])


def test_the_shipped_station_s_floor_walk_past_the_ramp_s_foot_stands_on_it(scenes_dir, model):
    """Seeded: on the shipped multi-level station, the floor walk from the floor before the
    ramp's foot to the floor before the step (seed 3) turns past the ramp's low end. Before
    (fed66aa) its feet stayed at floor height there: 201 contacts with the ramp, 34.0 mm deep
    (seed 0: 46, 34.4 mm); now it names the ramp and has none."""
    scene = scenes_dir / "multilevel_station.xml"
    station = load_workplace(scene)
    walk = plan_walk(station, "stand_ramp", "stand_step", model, rng=3)
    assert len(ramps_beside(station, walk, 1.75)) == 1
    assert collision_report(timeline_from_walk(walk, scene)) == []


def test_over_ramp_takes_the_run_with_its_ends_and_the_widened_width():
    """One test of "over the ramp" for the planners and the legs: a ramp rising along +y
    from (1, 0), 2 m long, 1 m wide. Its foot and top lines are on it; its sides, known,
    are widened by ``widen``; a plane of unknown width (``half_width`` 0) has none."""
    plane = {"foot": (1.0, 0.0), "uphill": math.pi / 2, "run": 2.0, "half_width": 0.5}
    xy = np.array([[1.0, 0.0], [1.0, 2.0], [1.0, -0.01], [1.0, 2.01], [1.55, 1.0], [0.45, 1.0]])
    assert over_ramp(plane, xy).tolist() == [True, True, False, False, False, False]
    assert over_ramp(plane, xy, widen=0.1).tolist() == [True, True, False, False, True, True]
    assert over_ramp({**plane, "half_width": 0.0}, xy[4:]).all()


def test_a_ramp_s_surface_plane_spans_its_whole_width(tmp_path):
    """Generated hall 170 (``benchmarks/bench_unseen.py``): the floor's longest contact with
    the ramp's foot is 0.90 m of its 1.08 m, so the crossing's plane (where the walker lines
    up) is 0.45 m either side of that part's middle; its surface plane spans the ramp geom's
    whole width (0.54 m half width), its foot on the geom's axis, the slope and run kept."""
    xml = generate_levels(170).write(tmp_path / "levels_170.xml")
    wp = load_workplace(xml, cache=False)
    (c,) = [c for c in crossings(wp.levels, 0.0) if c.kind == "ramp"]
    plane = ramp_plane(c, wp.floor_z)
    whole = surface_plane(plane)
    assert plane["half_width"] == pytest.approx(0.45, abs=0.005)
    assert whole["half_width"] == pytest.approx(0.54, abs=1e-3)
    m = mujoco.MjModel.from_xml_path(str(xml))
    d = mujoco.MjData(m)
    mujoco.mj_forward(m, d)
    g = m.geom("ramp_ramp").id
    side = d.geom_xmat[g].reshape(3, 3)[:2, 1]  # the box's y axis: across the ramp
    rel = np.asarray(whole["foot"]) - d.geom_xpos[g][:2]
    assert abs(float(rel @ side)) / np.linalg.norm(side) < 1e-3  # on its axis
    assert {k: whole[k] for k in ("slope", "uphill", "run", "z")} == {
        k: plane[k] for k in ("slope", "uphill", "run", "z")
    }
    assert (
        surface_plane({k: v for k, v in plane.items() if k != "sides"})["half_width"]
        == (plane["half_width"])
    )


def test_a_ramp_crossed_off_its_middle_records_the_ramp_s_own_plane(tmp_path):
    """Generated hall 511's ramp crossed 0.2 m left of its middle (the level planner walks a
    wide crossing on the side nearest the walk, :func:`~mjwalk.plan.levelroute.place_on_edge`):
    its recorded plane is the ramp's own, the one a walk passing beside it records. Before,
    its foot moved with the walker's line and its width and sides with it: the ramp was known
    0.2 m past its left side, over the floor, and not over the 0.2 m along its right side."""
    xml = generate_levels(511).write(tmp_path / "levels_511.xml")
    wp = load_workplace(xml, cache=False)
    (c,) = [c for c in crossings(wp.levels, 0.0) if c.kind == "ramp"]
    plane = ramp_plane(c, wp.floor_z)
    for offset in (0.2, -0.15):
        assert ramp_plane(c.shifted(offset), wp.floor_z) == plane
    left = np.array([-c.axis[1], c.axis[0]])
    right_side = np.asarray(plane["foot"]) + (plane["sides"][0] + 0.1) * left + 0.5 * c.axis
    assert over_ramp(surface_plane(plane), right_side)  # 0.1 m inside its right side
    was = {**plane, "foot": [float(v) for v in c.shifted(0.2).origin]}
    assert not over_ramp(surface_plane(was), right_side)


@pytest.mark.slow
@pytest.mark.parametrize(
    ("seed", "ends", "rng"),
    [(170, ("mezz_0", "platform_0"), 4), (159, ("floor_0", "pit_0"), 8),
     (153, ("mezz_0", "platform_0"), 7)],
)  # fmt: skip
def test_generated_halls_walks_past_a_ramp_keep_their_soles_off_it(tmp_path, seed, ends, rng):
    """Seeded, generated halls of ``benchmarks/bench_unseen.py`` whose walks pass a ramp's foot
    without crossing it, the default walker: no sole goes into the ramp. At 83e038b: 24.3 mm
    (hall 170: toes over the strip of the ramp beside the part of its foot the floor meets),
    21.8 mm (hall 159: a stance foot on that strip) and 11.7 mm (hall 153: the flat steps of
    a step's crossing, turning past the ramp's foot, were not level steps to the legs; the
    foot hung toes down where the ankle could not dorsiflex further). Over rng 0-11 of the
    three walks the deepest was 24.3 mm, with one PlanningError; now 0.0 mm (7 um: a sole
    resting on it), none."""
    xml = generate_levels(seed).write(tmp_path / f"levels_{seed}.xml")
    wp = load_workplace(xml, cache=False)
    walk = plan_walk(wp, *ends, rng=rng)
    assert ramps_beside(wp, walk, 1.75)
    assert _sole_depth(timeline_from_walk(walk, xml), "ramp_ramp") <= 1e-4  # a sole on it


def test_head_heights_are_the_upper_level_past_the_head_within_the_width():
    """Past a ramp's head (and within its width) the ground is the level the head meets: the
    foot's height plus the rise; over the ramp, before its foot and beside it, none."""
    plane = {"slope": 0.1, "uphill": np.pi / 2, "foot": [1.0, 2.0], "run": 3.0,
             "half_width": 0.5, "z": 0.2}  # fmt: skip
    pts = np.array([[1.0, 5.2], [1.4, 5.01], [1.0, 4.9], [1.0, 1.9], [1.6, 5.2]])
    top = 0.2 + np.tan(0.1) * 3.0
    assert head_heights(plane, pts) == pytest.approx([top, top, -np.inf, -np.inf, -np.inf])
    # a low top's plane (mjwalk.plan.lowtops) has no level past its far edge, whatever its
    # geom's id: geom 0 too (a mat written before the floor read as a ramp's head before)
    for g in (0, 7):
        low = {**plane, "slope": 0.0, LOW_KEY: g}
        assert np.all(head_heights(low, pts) == -np.inf)
