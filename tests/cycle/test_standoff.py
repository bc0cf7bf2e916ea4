"""The reach's stand-off (issue 17 item 5): an operator standing too close to a shelf steps back
until the reaching arm clears it, so station cycles have no humanoid-scene contacts."""

from __future__ import annotations

import math

import numpy as np
import pytest

import mjwalk.cycle.reaching as reaching
import mjwalk.cycle.reachspot as reachspot
import mjwalk.cycle.targets as targets
from mjwalk.cycle.poses import frame_contacts
from mjwalk.cycle.reachspot import ReachStart, reach_task
from mjwalk.cycle.simulate import prepare, simulate_cycles
from mjwalk.cycle.spec import load_cycle_spec
from mjwalk.cycle.standoff import REACH_CLEARANCE, ArmClearance

#: Where run 42 of ``simulate_cycles(station, 300, seed=0)`` ended its walk T3 to rack 1 before
#: this fix (world, m): 0.035 m closer to the shelf than the stand site and 0.08 m to its side.
#: Turned to bring screw 1 ahead of the left shoulder, its relaxed left hand touched the
#: front edge of ``rack1_shelf`` (thumb tip 3.1 mm deep). Here 1 cm closer to the screw: since
#: reaches are timed by the hand's true path (their frames changed), the hand clears the edge
#: by 0.2 mm from the walk's end point, short of the 1 cm stand-off; 1 cm closer it was 8.8 mm
#: in; since reaches swing the elbow out, keep the wrist in its functional range (reachgen) and
#: the hand comes in pointing along its approach, it is 12.9 mm in (the index finger).
CLOSE_TO_RACK1 = (-2.66876101, -1.70230865)


#: The reaches' hold (s), frame rate and the reference adult's timing.
PACE = reaching.ReachPace(0.4, 30.0, reaching.default_timing)


@pytest.fixture(scope="module")
def ctx(scenes_dir):
    return prepare(load_cycle_spec(scenes_dir / "assembly_station.toml"))


def _pick(ctx, site: str):
    return next(t for t in ctx.spec.tasks if t.kind == "pick" and t.site == site)


def _reach(ctx, site, xy, yaw):
    return reach_task(ctx, _pick(ctx, site), ReachStart(xy[0], xy[1], yaw), PACE)


def _contacts(ctx, frames):
    return frame_contacts(ctx, frames)


def test_too_close_to_a_shelf_the_operator_steps_back(ctx, monkeypatch):
    yaw = ctx.workplace.station("stand_rack1").yaw
    # without the stand-off (no step back allowed) the index finger touches the shelf's front
    # edge (with the old hand directions, the elbow also touched the rack's upright)
    with monkeypatch.context() as m:
        m.setattr(reachspot, "step_back_offsets", lambda: np.array([0.0]))
        # (nor the approach from out of the board, which alone clears it by 2.7 mm)
        m.setattr(reachspot, "board_run", lambda *_: 0.0)
        stay = _reach(ctx, "rack1_screw1", CLOSE_TO_RACK1, yaw)
    assert stay.step_back == 0.0
    assert stay.distance < 0.0  # overlapping
    hits = _contacts(ctx, np.vstack([stay.turn, stay.frames]))
    assert "rack1_shelf" in {c.scene_geom for c in hits}
    assert {c.scene_geom for c in hits} <= {"rack1_shelf", "rack1_frame_r"}
    assert all("_l_" in f"{c.body_part}_" for c in hits)  # the left arm's parts
    # with it: a short step back, away from the target, and the whole reach clears by 1 cm
    r = _reach(ctx, "rack1_screw1", CLOSE_TO_RACK1, yaw)
    assert 0.0 < r.step_back <= 0.06
    assert r.distance == np.inf
    assert ArmClearance(ctx.model, ctx.jointmap, REACH_CLEARANCE).clear(
        np.vstack([r.turn, r.frames])
    )
    assert _contacts(ctx, np.vstack([r.turn, r.frames])) == []
    target = ctx.workplace.station("rack1_screw1").pos[:2]
    before = math.dist(CLOSE_TO_RACK1, target)
    assert math.dist((r.x, r.y), target) == pytest.approx(before + r.step_back, abs=1e-9)
    # the step happens during the turn, which ends where the reach starts
    root = ctx.jointmap.root
    np.testing.assert_allclose(r.turn[0, root : root + 2], CLOSE_TO_RACK1, atol=0.02)
    np.testing.assert_allclose(r.turn[-1, root : root + 2], (r.x, r.y), atol=1e-12)
    np.testing.assert_allclose(r.frames[0, root : root + 2], (r.x, r.y), atol=1e-12)
    # and the hand still gets onto the screw
    assert r.error < 0.01


def test_out_of_reach_the_operator_steps_in(ctx, monkeypatch):
    """From a spot 0.35 m further from the shelf than the stand site (where a step back for the
    reach before, or a short operator's walk, may leave them; 0.25 m until the default reach
    model's working area grew to a top shelf, which reaches from there) the hand falls short of
    the screw;
    the operator steps in towards it (a negative step back) until the hand is on it, clear of
    the shelf. Before, the reach stayed put and the hand ended up to 36 mm short (short
    operators of the station, runs 154 and 287 of 300, after a step back)."""
    st = ctx.workplace.station("stand_rack2")
    site = ctx.workplace.station("rack2_screw1").pos
    back = (st.pos[:2] - site[:2]) / np.linalg.norm(st.pos[:2] - site[:2])
    xy = st.pos[:2] + 0.35 * back
    with monkeypatch.context() as m:  # no steps (and no lean): the hand falls short
        m.setattr(reachspot, "step_back_offsets", lambda: np.array([0.0]))
        m.setattr(reaching, "leaning", lambda ctx, q0, *a: q0)
        stay = _reach(ctx, "rack2_screw1", xy, st.yaw)
    assert stay.step_back == 0.0 and stay.error > 0.03
    r = _reach(ctx, "rack2_screw1", xy, st.yaw)
    assert -0.2 <= r.step_back < 0.0  # measured: 0.08 m in
    assert r.error < 0.01
    assert r.distance == np.inf and _contacts(ctx, np.vstack([r.turn, r.frames])) == []
    assert math.dist((r.x, r.y), site[:2]) == pytest.approx(
        math.dist(xy, site[:2]) + r.step_back, abs=1e-9
    )


def test_step_backs_do_not_add_up(ctx):
    """A reach at the stand where the walk ended (``home``) starts from that spot again, not
    from where a step back for the reach before left the operator: here 0.2 m back, and the
    screw is clear and in reach from the walk's end, so the operator steps forward onto it
    during the turn (before, the steps added up: an unseen workplace's operator drifted 0.4 m
    from the walk's end, and the next reaches ended up to 187 mm short)."""
    st = ctx.workplace.station("stand_rack2")
    site = ctx.workplace.station("rack2_screw1").pos
    back = (st.pos[:2] - site[:2]) / np.linalg.norm(st.pos[:2] - site[:2])
    here = st.pos[:2] + 0.2 * back
    r = reach_task(
        ctx,
        _pick(ctx, "rack2_screw1"),
        ReachStart(here[0], here[1], st.yaw, home=(float(st.pos[0]), float(st.pos[1]))),
        PACE,
    )
    assert r.step_back == 0.0 and r.error < 0.01 and r.distance == np.inf
    np.testing.assert_allclose((r.x, r.y), st.pos[:2], atol=1e-12)
    root = ctx.jointmap.root
    np.testing.assert_allclose(r.turn[0, root : root + 2], here, atol=0.02)
    np.testing.assert_allclose(r.turn[-1, root : root + 2], st.pos[:2], atol=1e-12)


def test_a_target_below_a_standing_reach_is_reached_bending_forward(low_compartment):
    """A pick site 0.76 m high in rack 1 (on a shelf added at 0.7 m) is below the standing
    operator's reach from the stand site: no step brings it within the arm (the hand ended
    40 mm short). The operator bends the trunk forward (lumbar and thoracic flexion) just far
    enough, and the hand ends on it; the lean comes in with the reach and goes with it."""
    low = prepare(load_cycle_spec(low_compartment))
    st = low.workplace.station("stand_rack1")
    task = low.spec.tasks[0]
    jm = low.jointmap
    lumbar = jm.adr("lumbar_flex")

    def reach():
        return reach_task(low, task, ReachStart(st.pos[0], st.pos[1], st.yaw), PACE)

    r = reach()
    assert r.error < 0.01
    assert r.frames[:, lumbar].max() > np.radians(5.0)  # bent forward
    assert r.frames[0, lumbar] < r.frames[:, lumbar].max()  # and back up at the end
    assert abs(r.frames[-1, lumbar] - r.turn[-1, lumbar]) < 1e-9
    with pytest.MonkeyPatch.context() as m:  # upright only (no lean, no crouch)
        m.setattr(reaching, "leaning", lambda ctx, q0, *a: q0)
        m.setattr(reachspot, "CROUCH_DROPS", ())
        upright = reach()
    assert upright.error > 0.03


def test_station_runs_of_short_operators_reach_every_target(scenes_dir):
    """Runs 154 and 287 of 300 (seed 0; 1.52 and 1.48 m operators) reach every target within
    1 cm with no contact (hand errors up to 36 mm when a step back for the first screw left
    the second out of reach)."""
    res = simulate_cycles(scenes_dir / "assembly_station.toml", runs=300, seed=0, only=[154, 287])
    for r in res:
        assert r.operator is not None and r.operator.stature < 1.55
        assert r.collisions == []
        assert max(a.hand_error for a in r.arms) < 0.01, r.run


def test_a_clear_reach_stays_where_the_walk_ended(ctx):
    st = ctx.workplace.station("stand_rack2")
    r = _reach(ctx, "rack2_screw1", st.pos[:2], st.yaw)
    assert r.step_back == 0.0
    assert r.distance == np.inf
    assert (r.x, r.y) == (float(st.pos[0]), float(st.pos[1]))


def test_arm_clearance_measures_the_gap(ctx):
    """The clearance check reports the true gap (m) when it is below its margin."""
    yaw = ctx.workplace.station("stand_rack1").yaw
    r = _reach(ctx, "rack1_screw1", CLOSE_TO_RACK1, yaw)  # clear by 1 cm after the step back
    frames = np.vstack([r.turn, r.frames])
    wide = ArmClearance(ctx.model, ctx.jointmap, 0.3)
    gap = wide.distance(frames)
    assert REACH_CLEARANCE <= gap < 0.3  # measured: 0.12 m (the step back changed the reach)
    assert not wide.clear(frames)
    assert ArmClearance(ctx.model, ctx.jointmap, REACH_CLEARANCE).distance(frames) == np.inf
    assert not ctx.model.geom_margin.any()  # the cycle's own model keeps its margins


def test_station_runs_that_touched_rack1_are_contact_free(scenes_dir):
    """Runs 42, 202 and 284 of 300 (seed 0) touched rack1_shelf with the left thumb or index
    fingertip (up to 6.3 mm deep) while picking rack1_screw1 before the stand-off."""
    res = simulate_cycles(
        scenes_dir / "assembly_station.toml", runs=300, seed=0, only=[42, 202, 284]
    )
    assert [r.run for r in res] == [42, 202, 284]
    for r in res:
        assert r.collisions == [], (r.run, r.collisions[:3])
        assert max(a.hand_error for a in r.arms) < 0.01
        assert all(0.0 <= a.step_back <= 0.2 for a in r.arms)


def _station_with_shelf_above(scenes_dir, tmp_path, top: float, visual_only: bool = False):
    """The station with a second shelf over rack 1's (centre ``top`` m): a compartment."""
    import shutil

    shelf = (
        '<geom name="rack1_shelf" type="box" size="0.4 0.25 0.02" pos="0 0 1.0" material="shelf"/>'
    )
    extra = ' contype="0" conaffinity="0"' if visual_only else ""
    above = (
        f'<geom name="rack1_shelf_above" type="box" size="0.4 0.25 0.02" pos="0 0 {top}" '
        f'material="shelf"{extra}/>'
    )
    xml = (scenes_dir / "assembly_station.xml").read_text()
    assert shelf in xml
    (tmp_path / "assembly_station.xml").write_text(xml.replace(shelf, f"{shelf}\n{above}"))
    shutil.copy(scenes_dir / "assembly_station.toml", tmp_path / "station.toml")
    return prepare(load_cycle_spec(tmp_path / "station.toml"))


def test_under_a_shelf_the_hand_comes_in_low_enough_to_clear_it(scenes_dir, tmp_path):
    """A pick from a compartment 26 cm high (screw 1 on rack 1's shelf, a shelf over it at
    1.30 m): the pre-grasp point does not rise (the space above the target is less than a
    hand's length), and the reach is clear by MuJoCo's collision check; with the open-shelf
    rise of 10 cm the thumb and forearm touched the upper shelf (16 mm deep)."""
    from mjwalk.arms.chain import arm_segment_lengths

    ctx = _station_with_shelf_above(scenes_dir, tmp_path, 1.30)
    st = ctx.workplace.station("stand_rack1")
    site = ctx.workplace.station("rack1_screw1").pos
    target = targets.reach_target("pick", site, st.pos[0], st.pos[1])
    free = 1.28 - target[2]  # to the upper shelf's underside
    assert targets.headroom(ctx.model, ctx.scratch(), target) == pytest.approx(free, abs=1e-6)
    assert free < arm_segment_lengths(ctx.spec.stature)[2]
    assert targets.approach_rise(ctx.model, ctx.scratch(), ctx.spec.stature, target) == 0.0
    r = _reach(ctx, "rack1_screw1", st.pos[:2], st.yaw)
    assert r.distance == np.inf
    assert r.error < 0.01
    assert not _contacts(ctx, np.vstack([r.turn, r.frames]))
    root_z = ctx.jointmap.root + 2
    assert np.allclose(r.frames[:, root_z], r.turn[-1, root_z])  # standing: no crouch needed
    with pytest.MonkeyPatch.context() as m:  # the open-shelf rise, standing (no crouch)
        m.setattr(reachspot, "approach_rise", lambda *_: targets.APPROACH_UP)
        m.setattr(reachspot, "CROUCH_DROPS", ())
        m.setattr(reachspot, "board_run", lambda *_: 0.0)  # (nor from out of the board)
        old = _reach(ctx, "rack1_screw1", st.pos[:2], st.yaw)
    assert old.distance < 0.0
    # open above (the station as shipped), or under a shelf that is only drawn: the full rise
    shipped = prepare(load_cycle_spec(scenes_dir / "assembly_station.toml"))
    assert (
        targets.approach_rise(shipped.model, shipped.scratch(), shipped.spec.stature, target)
        == targets.APPROACH_UP
    )
    (tmp_path / "drawn").mkdir()
    drawn = _station_with_shelf_above(scenes_dir, tmp_path / "drawn", 1.30, visual_only=True)
    assert targets.headroom(drawn.model, drawn.scratch(), target) == np.inf
    assert (
        targets.approach_rise(drawn.model, drawn.scratch(), drawn.spec.stature, target)
        == targets.APPROACH_UP
    )


def test_clearances_of_two_statures_share_one_mjdata_and_measure_as_with_their_own(scenes_dir):
    """Every stature's ArmClearance computes in one MjData per model layout and thread
    (CLEARANCE_DATA, issue 50): the distances of seeded poses are those a fresh MjData of each
    model gives, bit for bit, in either order of use."""
    import mujoco

    from mjwalk.body.humanoid import attach_humanoid

    scene = scenes_dir / "assembly_station.xml"
    a = ArmClearance(*attach_humanoid(scene, 1.62))
    b = ArmClearance(*attach_humanoid(scene, 1.86))
    assert a.data is b.data
    rng = np.random.default_rng(7)

    def poses(c):
        q = np.tile(c.model.qpos0, (12, 1))
        q[:, 7:] += rng.normal(0.0, 0.3, (12, c.model.nq - 7))
        return q

    qa, qb = poses(a), poses(b)
    shared = [a.distance(qa), b.distance(qb), a.distance(qa, broad_phase=False)]
    for c in (a, b):
        c.data = mujoco.MjData(c.model)
    own = [a.distance(qa), b.distance(qb), a.distance(qa, broad_phase=False)]
    assert shared == own
    assert any(np.isfinite(shared))  # the poses reach into the scene: distances were compared
