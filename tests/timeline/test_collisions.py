"""mjwalk.timeline.collisions: humanoid-vs-scene contacts of a timeline by MuJoCo's collision
detection, its broad phase's helpers and check_collisions on walks and timelines."""

from __future__ import annotations

from pathlib import Path

import mujoco
import numpy as np
import pytest
from test_frames import _scene

from mjwalk.conventions import DEFAULT_STATURE
from mjwalk.errors import MjwalkError
from mjwalk.plan.synthetic import synthetic_walk as make_walk
from mjwalk.timeline import collision_report, timeline_from_walk
from mjwalk.timeline.collisions import check_collisions, floor_geoms, repeats


def test_clear_walk_has_no_contacts():
    tl = timeline_from_walk(make_walk(n_steps=6), _scene(20.0))
    assert collision_report(tl) == []


def test_a_non_finite_pose_is_refused_not_passed():
    """MuJoCo finds no contact at a NaN pose: a timeline with one is an error naming its first
    frame, not a clean report (a stepless stretch of a walk once gave the arms NaN in 672 of
    710 frames of a multi-level cycle, and its collision check reported none)."""
    tl = timeline_from_walk(make_walk(n_steps=6), _scene(2.0))
    tl.qpos[5:9, -1] = np.nan
    with pytest.raises(MjwalkError, match=r"timeline frame 5 .* and 3 more have a non-finite"):
        collision_report(tl)


def test_walk_into_box_is_reported():
    # the path passes through a box at x = 2 m (the walk covers ~3.6 m along +x)
    tl = timeline_from_walk(make_walk(n_steps=6), _scene(2.0))
    contacts = collision_report(tl)
    assert contacts, "walking through a box must be reported"
    assert {c.scene_geom for c in contacts} == {"box"}
    first = min(c.time for c in contacts)
    root_x = np.interp(first, tl.t, tl.root()[:, 0])
    assert 1.0 < root_x < 1.9  # the leading toes, ~0.6 m ahead, reach the face at x = 1.75
    assert max(c.depth for c in contacts) > 0.05
    assert all(not c.body_part.startswith("human/") for c in contacts)
    # a box beside the path (1 m to the left) is not touched
    assert collision_report(timeline_from_walk(make_walk(n_steps=6), _scene(2.0, 1.0))) == []


#: Hybrid-A* walks through the corridor (plan_walks entry->door / door->exit, seed 0, walk
#: indices in the names; saved with WalkPath.save) on which the playback grazed a wall by up to
#: 1.7 cm with a hand or an upper arm, or cut an inner corner with the swing foot (up to 11 cm)
#: although the planner had certified the pelvis path.
CORRIDOR_WALKS = sorted((Path(__file__).parents[1] / "data").glob("corridor_walk_seed0_*.npz"))


@pytest.mark.parametrize("path", CORRIDOR_WALKS, ids=lambda p: p.stem)
def test_certified_corridor_walks_touch_no_wall(path, scenes_dir):
    from mjwalk.plan.walkpath import WalkPath

    walk = WalkPath.load(path)
    contacts = collision_report(timeline_from_walk(walk, scenes_dir / "corridor.xml"))
    assert contacts == [], [(c.body_part, c.scene_geom, round(c.depth, 4)) for c in contacts]


def test_a_shared_geom_table_gives_the_same_candidates_and_contacts():
    """The contact check reading a table of the humanoid's geom poses in every frame (as a
    cycle shares it with its ergonomics) finds the same candidate frames and contacts."""
    from mjwalk.body.humanoid import HUMAN_GROUP
    from mjwalk.timeline.collisions import candidate_frames
    from mjwalk.timeline.geomposes import geom_table

    tl = timeline_from_walk(make_walk(n_steps=6), _scene(2.0))
    m, q = tl.model, np.repeat(tl.qpos, 2, axis=0)[1:]  # holds: repeated poses
    human = m.geom_group == HUMAN_GROUP
    table = geom_table(m, q, np.flatnonzero(human))
    fresh = np.flatnonzero(~repeats(q))
    own = candidate_frames(m, q[fresh], human, floor_geoms(m), 0.01)
    shared = candidate_frames(m, q[fresh], human, floor_geoms(m), 0.01, None, table, fresh)
    assert own.any() and not own.all() and shared.tolist() == own.tolist()
    tl.qpos, tl.t = q, np.arange(len(q)) / tl.fps

    def rows(contacts):
        return [(c.time, c.body_part, c.scene_geom, c.depth, c.pos.tobytes()) for c in contacts]

    got = rows(collision_report(tl, table=table))
    assert got and got == rows(collision_report(tl))


def test_static_scene_placed_in_a_used_data_is_that_of_a_new_one():
    """The broad phase's static scene built in the caller's MjData, left in any pose (here a
    walk's frame, the humanoid's joints bent), holds the numbers a new MjData gives: the
    scene's geoms are welded to the world (issue 50: no MjData made per new model)."""
    from mjwalk.body.humanoid import HUMAN_GROUP
    from mjwalk.timeline import collisions as col

    tl = timeline_from_walk(make_walk(n_steps=4), _scene(2.0))
    m = tl.model
    human, floor = m.geom_group == HUMAN_GROUP, floor_geoms(m)
    fresh = col._static_scene(m, human, floor)
    col._STATIC.pop(m)  # built again, now in a used data
    used = mujoco.MjData(m)
    used.qpos[:] = tl.qpos[len(tl.qpos) // 2] + 0.3  # every joint off its place
    again = col._static_scene(m, human, floor, used)
    assert again is not fresh
    for name in fresh.__dataclass_fields__:
        a, b = getattr(fresh, name), getattr(again, name)
        assert a.dtype == b.dtype and a.tobytes() == b.tobytes(), name


def test_floor_test_skips_high_geoms_without_changing_the_frames():
    """The broad phase's floor test skips a geom centred higher above the floor than its
    extent bound (StaticScene.low): the same candidate frames as testing every geom (an
    infinite bound), on a walk lowered so that its feet sink to various depths."""
    from mjwalk.body.humanoid import HUMAN_GROUP
    from mjwalk.timeline import collisions as col
    from mjwalk.timeline.geomposes import geom_poses

    tl = timeline_from_walk(make_walk(n_steps=6), _scene(2.0))
    m, q = tl.model, tl.qpos.copy()
    q[:, 2] -= np.linspace(0.0, 0.05, len(q))  # the pelvis (free joint z) ever lower
    human = m.geom_group == HUMAN_GROUP
    scene = col._static_scene(m, human, floor_geoms(m))
    assert (scene.low >= scene.rbound * (1.0 - 1e-12)).all()
    xpos, xmat = geom_poses(m, q, scene.hid)
    args = (np.arange(len(q)), xpos, xmat, scene.types, scene.size, scene.rbound)
    args += (scene.reach_solid, scene.n_sub, scene.sub_reach, scene.centre, scene.half)
    args += (scene.normals, scene.origins, 0.01 - col.BROAD_SLACK)
    got = col._touching(*args, scene.low)
    every = col._touching(*args, np.full_like(scene.low, np.inf))
    assert got.tolist() == every.tolist() and got.any() and not got.all()


def test_repeats_is_numpys_row_equality():
    rng = np.random.default_rng(3)
    q = rng.normal(size=(60, 9))
    for f in (5, 6, 7, 30, 31):  # holds
        q[f] = q[f - 1]
    q[12], q[13] = q[11], q[11]
    q[13, 8] = -q[11, 8] if q[11, 8] == 0.0 else q[11, 8] + 1e-15  # one number apart
    q[40, 2] = 0.0
    q[41] = q[40]
    q[41, 2] = -0.0  # equal to 0.0
    q[50, 3] = np.nan
    q[51] = q[50]  # NaN equals nothing: not a repeat
    want = np.r_[False, np.all(q[1:] == q[:-1], axis=1)]
    got = repeats(q)
    assert got.dtype == bool and got.tolist() == want.tolist()
    assert got[[5, 6, 7, 12, 30, 31, 41]].all() and not got[[13, 51]].any()
    assert repeats(np.zeros((0, 4))).tolist() == [] and repeats(q[:1]).tolist() == [False]


def test_repeats_and_floor_geoms():
    q = np.array([[0.0, 1.0], [0.0, 1.0], [0.5, 1.0], [0.5, 1.0], [0.5, 1.0]])
    assert repeats(q).tolist() == [False, True, False, True, True]
    m = _scene(2.0).compile()
    floor = floor_geoms(m)
    assert floor.dtype == bool and floor.shape == (m.ngeom,)
    assert floor[mujoco.mj_name2id(m, mujoco.mjtObj.mjOBJ_GEOM, "floor")]
    assert not floor[mujoco.mj_name2id(m, mujoco.mjtObj.mjOBJ_GEOM, "box")]


def test_check_collisions_of_a_timeline_and_of_a_walk_in_a_scene(tmp_path):
    path = tmp_path / "box.xml"
    path.write_text(_scene(2.0).to_xml())
    walk = make_walk(n_steps=6)
    tl = timeline_from_walk(walk, path)
    got, want = check_collisions(tl), collision_report(tl)
    assert want and [(c.time, c.scene_geom) for c in got] == [(c.time, c.scene_geom) for c in want]
    with pytest.raises(MjwalkError, match="needs the scene"):
        check_collisions(walk)
    with pytest.raises(MjwalkError, match="cannot check"):
        check_collisions(42)


_MULTI = Path(__file__).resolve().parents[2] / "scenes" / "multilevel_station.xml"


def _stair_walk(direction, stature=DEFAULT_STATURE):
    """A walk up or down the shipped stair (6 x 0.17/0.28 m, heading -y from y = 0.04)."""
    from mjwalk.plan.synthetic import synthetic_stair_walk  # deferred: only these tests use it

    if direction == "up":
        start = (-4.9, 0.04, -np.pi / 2)
    else:
        start = (-4.9, -1.64, np.pi / 2)
    return synthetic_stair_walk(0.17, 0.28, 6, direction, start=start, stature=stature)


def test_walk_tops_only_in_scenes_on_several_levels():
    """The stair's treads and the mezzanine are walk tops of the multi-level station; a flat
    scene has none (its contacts are checked as before)."""
    from mjwalk.timeline.collisions import (
        walk_tops,
    )  # deferred: keeps the imports above as they were

    tl = timeline_from_walk(_stair_walk("up"), _MULTI)
    tops = walk_tops(tl)
    names = [
        mujoco.mj_id2name(tl.model, mujoco.mjtObj.mjOBJ_GEOM, g) for g in range(tl.model.ngeom)
    ]
    on = {n for n, t in zip(names, tops, strict=True) if t}
    assert {"stair_tread1", "stair_tread5", "mezzanine", "platform"} <= on
    assert "floor" not in on and "stair_wall_w" not in on
    assert walk_tops(timeline_from_walk(make_walk(n_steps=2), _scene(20.0))) is None  # MjSpec
    flat = _MULTI.parent / "assembly_station.xml"
    assert walk_tops(timeline_from_walk(make_walk(n_steps=2), flat)) is None


@pytest.mark.parametrize("direction", ["up", "down"])
def test_soles_on_treads_are_standing_not_contacts(direction):
    """Up and down the shipped stair no sole contact left in the report lies on a tread's top
    face within the floor tolerance, 1 cm or more inside its edges (those are standing); what
    is left is deeper, on an edge or against a riser."""
    tl = timeline_from_walk(_stair_walk(direction), _MULTI)
    m = tl.model
    for c in collision_report(tl):
        if c.body_part.startswith(("foot_", "toes_")) and c.depth <= 0.01:
            g = mujoco.mj_name2id(m, mujoco.mjtObj.mjOBJ_GEOM, c.scene_geom)
            top = m.geom_pos[g][2] + m.geom_size[g][2]
            inside = np.all(np.abs(c.pos[:2] - m.geom_pos[g][:2]) < m.geom_size[g][:2] - 0.01)
            assert not (abs(c.pos[2] - top) < 0.005 and inside)


@pytest.mark.parametrize("direction", ["up", "down"])
def test_stair_walk_has_no_contacts(direction):
    assert collision_report(timeline_from_walk(_stair_walk(direction), _MULTI)) == []


@pytest.mark.parametrize("direction", ["up", "down"])
@pytest.mark.parametrize("stature", [1.85, 2.02])
def test_tall_walkers_stair_walk_has_no_contacts(direction, stature):
    """Feet longer than the 0.28 m tread (0.281 m at 1.85 m, 0.307 m at 2.02 m) hang over a
    nosing instead of standing into a riser (:data:`mjwalk.plan.levelcross.TREAD_RISER_GAP`).
    Before: at 1.85 m, centred, the toes stood 0.6 mm into every riser ahead going up and the
    heel into every riser behind going down, and the landing heel caught the upper tread's
    nosing 11 mm deep (the multi-level station's cycle, run 7 of 10: 225 contacts)."""
    walk = _stair_walk(direction, stature)
    assert collision_report(timeline_from_walk(walk, _MULTI, stature=stature)) == []


def test_walk_tops_of_a_floor_with_an_opening_are_its_floor_boxes(tmp_path, pit_xml):
    """A floor written as boxes round a pit (:mod:`mjwalk.world.floorholes`): a sole resting on
    a floor box's top is standing, as on a tread; the plane under the pit too."""
    from mjwalk.timeline.collisions import walk_tops  # deferred: as above

    path = tmp_path / "pit.xml"
    path.write_text(pit_xml)
    tl = timeline_from_walk(make_walk(n_steps=2, start=(-3.0, -2.0, 0.0)), path)
    names = [
        mujoco.mj_id2name(tl.model, mujoco.mjtObj.mjOBJ_GEOM, g) for g in range(tl.model.ngeom)
    ]
    tops = walk_tops(tl)
    assert tops is not None
    on = {n for n, t in zip(names, tops, strict=True) if t}
    assert {"floor_0", "floor_1", "floor_2", "floor_3", "s1", "s2", "floor"} <= on
    assert "rack" not in on


def test_capsules_are_covered_by_spheres_within_a_quarter_of_their_radius():
    """The broad phase's cover of a capsule: ceil(SUB_PER_RADIUS half-length / radius) spheres
    along its axis, each of its radius plus a piece's half-length, at most (1 + 1/SUB_PER_RADIUS)
    its radius, and every point of the axis within a piece's half-length of a sphere's centre,
    for each of the humanoid's capsules (its exactness against the full check: the small-box
    and clearance tests in test_kernels)."""
    from mjwalk.body.humanoid import HUMAN_GROUP
    from mjwalk.timeline.collisions import SUB_PER_RADIUS

    m = timeline_from_walk(make_walk(n_steps=2), _scene(2.0)).model
    cap = (m.geom_group == HUMAN_GROUP) & (m.geom_type == mujoco.mjtGeom.mjGEOM_CAPSULE)
    assert SUB_PER_RADIUS >= 1 and cap.sum() > 10
    for r, h in m.geom_size[cap, :2]:
        n = max(1, int(np.ceil(SUB_PER_RADIUS * h / r)))
        assert r + h / n <= (1 + 1 / SUB_PER_RADIUS) * r + 1e-12
        centres = -h + (2 * np.arange(n) + 1) * h / n
        axis = np.linspace(-h, h, 101)
        assert (np.abs(axis[:, None] - centres).min(axis=1) <= h / n + 1e-12).all()


def test_feet_on_floor_tape_stand_on_the_floor():
    # yellow tape (a 2 mm box, 5 cm wide) across the walk at x = 1.2 m: the feet stand on it
    # (within the floor's 4 mm level tolerance), as on the floor (before: foot_*/toes_* on
    # 'tape', 2 mm deep); a 15 mm mat is no floor, its contacts are still reported
    xml = """<mujoco><worldbody><geom name="floor" type="plane" size="10 10 .1"/>
    <geom name="tape" type="box" size=".025 2 {h}" pos="{x} 0 {h}"/></worldbody></mujoco>"""
    walk = make_walk(n_steps=6)
    for x in (0.9, 1.2, 1.5, 1.8):
        tape = mujoco.MjSpec.from_string(xml.format(x=x, h=0.001))
        assert collision_report(timeline_from_walk(walk, tape)) == []
    mat = mujoco.MjSpec.from_string(xml.format(x=1.2, h=0.0075).replace(".025 2", ".5 2"))
    assert {c.scene_geom for c in collision_report(timeline_from_walk(walk, mat))} == {"tape"}
