"""Crouching for a reach into a low compartment (mjwalk.cycle.crouch): the feet stay planted,
the body stays balanced over them, and a reach that touches the shelf above from a standing or
stooping shoulder becomes clear by MuJoCo's collision check."""

from __future__ import annotations

import sys
from pathlib import Path

import mujoco
import numpy as np
import pytest

import mjwalk.cycle.reaching as reaching
import mjwalk.cycle.reachspot as reachspot
from mjwalk.cycle.crouch import com_ahead, crouch_frames, crouch_pose, trunk_bend
from mjwalk.cycle.handling import BODY_MOTION_TMU, TMU
from mjwalk.cycle.poses import frame_contacts, hand_points, standing_pose
from mjwalk.cycle.simulate import prepare, simulate_cycle
from mjwalk.cycle.spec import load_cycle_spec

sys.path.insert(0, str(Path(__file__).resolve().parents[2] / "benchmarks"))
from bench_heights import box_at


@pytest.fixture(scope="module")
def ctx(low_compartment):
    return prepare(load_cycle_spec(low_compartment))


def _feet(ctx, q):
    """Ankle joint centres (2, 3) and the lowest point of the foot geoms (m) in pose ``q``."""
    m, jm = ctx.model, ctx.jointmap
    d = mujoco.MjData(m)
    d.qpos[:] = q
    mujoco.mj_kinematics(m, d)
    ankles = np.array([d.xanchor[m.joint(f"{jm.prefix}ankle_{p}_flex").id] for p in "lr"])
    return ankles


def _com(ctx, q):
    """How far the centre of mass lies ahead of the ankles in pose ``q`` (m)."""
    d = mujoco.MjData(ctx.model)
    d.qpos[:] = q
    mujoco.mj_kinematics(ctx.model, d)
    return com_ahead(ctx, d)


@pytest.mark.parametrize("drop", [0.05, 0.15, 0.25])
def test_a_crouch_lowers_the_pelvis_with_the_feet_planted_and_balanced(ctx, drop):
    jm = ctx.jointmap
    q0 = standing_pose(ctx, 0.3, -0.2, 0.7)
    q = crouch_pose(ctx, q0, drop)
    assert q[jm.root + 2] == pytest.approx(q0[jm.root + 2] - drop)
    assert np.abs(_feet(ctx, q) - _feet(ctx, q0)).max() < 1e-6  # ankles where they stood
    assert q[jm.adr("knee_l")] > 0.3 and q[jm.adr("knee_r")] > 0.3  # the knees bend
    # the pelvis goes back; the trunk bends until the centre of mass is over the feet as
    # standing (within one balance step's worth)
    assert _com(ctx, q) >= _com(ctx, q0) - 1e-9
    for name in ("hip_l_flex", "knee_l", "ankle_l_flex", "lumbar_flex", "thoracic_flex"):
        lo, hi = jm.limits(name)
        assert lo - 1e-9 <= q[jm.adr(name)] <= hi + 1e-9
    # the way down keeps the feet planted at every pose, from standing to the crouch
    w = np.linspace(0.0, 1.0, 9)
    frames = crouch_frames(ctx, q0, q, w)
    assert np.allclose(frames[0], q0)
    assert np.allclose(frames[-1], q)
    for f in frames:
        assert np.abs(_feet(ctx, f) - _feet(ctx, q0)).max() < 1e-6
    assert np.all(np.diff(frames[:, jm.root + 2]) < 0)  # the pelvis goes down all the way


def _assert_hangs_plumb(ctx, q, sides: str) -> None:
    """In pose ``q`` the palm of each side in ``sides`` ("l", "r") hangs under its shoulder:
    within 10 cm across, at least 30 cm below."""
    d = mujoco.MjData(ctx.model)
    d.qpos[:] = q
    mujoco.mj_kinematics(ctx.model, d)
    palms = hand_points(ctx, q[None])[0]
    for p in sides:
        shoulder = d.xpos[ctx.model.body(f"{ctx.jointmap.prefix}upper_arm_{p}").id]
        palm = palms["lr".index(p)]
        assert np.linalg.norm(palm[:2] - shoulder[:2]) < 0.10
        assert palm[2] < shoulder[2] - 0.3


def test_no_drop_is_the_standing_pose(ctx):
    q0 = standing_pose(ctx, 0.0, 0.0, 0.0)
    assert np.array_equal(crouch_pose(ctx, q0, 0.0), q0)


def test_a_reach_into_a_low_compartment_crouches_and_is_clear(ctx, monkeypatch):
    """Standing or stooping, the thumb and forearm go through the upper shelf's front edge;
    crouched, the reach is clear, the hand on its target, the feet planted; it takes the
    MTM-1 bend and arise on top of the reach."""
    jm = ctx.jointmap
    task = ctx.spec.tasks[0]
    st = ctx.workplace.station("stand_rack1")

    def reach():
        return reachspot.reach_task(
            ctx,
            task,
            reachspot.ReachStart(st.pos[0], st.pos[1], st.yaw),
            reaching.ReachPace(0.4, 30.0, reaching.default_timing),
        )

    with monkeypatch.context() as m:
        m.setattr(reachspot, "CROUCH_DROPS", ())
        standing = reach()
    assert standing.distance < 0.0
    assert {c.scene_geom for c in frame_contacts(ctx, standing.frames)} & {"rack1_shelf"}
    r = reach()
    assert r.distance == np.inf
    assert not frame_contacts(ctx, np.vstack([r.turn, r.frames]))
    assert r.error < 0.01
    z = r.frames[:, jm.root + 2]
    assert z.min() < r.turn[-1, jm.root + 2] - 0.05  # crouched
    assert z[-1] == pytest.approx(r.turn[-1, jm.root + 2])  # and up again
    ankles = _feet(ctx, r.turn[-1])
    for f in r.frames[:: max(1, len(r.frames) // 20)]:
        assert np.abs(_feet(ctx, f) - ankles).max() < 1e-6
    # the way down and up each last at least the MTM-1 bend / arise (reference adult)
    down = np.flatnonzero(z <= z.min() + 1e-9)[0]
    up = len(z) - 1 - np.flatnonzero(z <= z.min() + 1e-9)[-1]
    assert (down + 1) / 30.0 >= BODY_MOTION_TMU["B"] * TMU - 1 / 30.0
    assert up / 30.0 >= BODY_MOTION_TMU["AB"] * TMU - 1 / 30.0
    # the free (right) arm hangs plumb from the bent trunk, not swept back with it
    _assert_hangs_plumb(ctx, r.frames[down], "r")


@pytest.fixture(scope="module")
def pallets(scenes_dir, tmp_path_factory):
    """The two-handed station with the box on a pallet 6 cm high (bench a) and bench b a
    pallet 35 cm high: a pick from the floor, a place low."""
    folder = tmp_path_factory.mktemp("pallets")
    xml = (scenes_dir / "assembly_station_2h.xml").read_text()
    xml = box_at(box_at(xml, "bench_a", 0.16), "bench_b", 0.45)
    (folder / "assembly_station_2h.xml").write_text(xml)
    (folder / "cycle.toml").write_text((scenes_dir / "assembly_station_2h.toml").read_text())
    return prepare(load_cycle_spec(folder / "cycle.toml"))


def test_a_two_handed_pick_from_the_floor_crouches_with_both_hands_on_the_part(pallets):
    """Standing, the hands end a third of a metre and more above the box's grips; the operator
    crouches and bends, both hands on their grips, clear of the scene, the feet planted, the
    arms hanging plumb on the way down, and the part comes up in the carrying posture."""
    ctx = pallets
    jm = ctx.jointmap
    task = ctx.spec.tasks[0]
    st = ctx.workplace.station("stand_bench_a")
    r = reachspot.reach_task(
        ctx,
        task,
        reachspot.ReachStart(st.pos[0], st.pos[1], st.yaw),
        reaching.ReachPace(0.4, 30.0, reaching.default_timing),
    )
    assert r.error < 0.01 and r.distance == np.inf
    assert not frame_contacts(ctx, np.vstack([r.turn, r.frames]))
    z = r.frames[:, jm.root + 2]
    z0 = r.turn[-1, jm.root + 2]
    assert z.min() < z0 - 0.05 and z[-1] == pytest.approx(z0)  # crouched, and up again
    ankles = _feet(ctx, r.turn[-1])
    for f in r.frames[:: max(1, len(r.frames) // 20)]:
        assert np.abs(_feet(ctx, f) - ankles).max() < 1e-6
    # at the bottom of the way down (MTM-1 bend: at least 29 TMU) the trunk is bent and the
    # hands hang under the shoulders (within 10 cm across), not swept back with the trunk
    down = np.flatnonzero(z <= z.min() + 1e-9)[0]
    assert (down + 1) / 30.0 >= BODY_MOTION_TMU["B"] * TMU - 1 / 30.0
    q = r.frames[down]
    assert q[jm.adr("lumbar_flex")] > r.turn[-1, jm.adr("lumbar_flex")] + 0.2
    _assert_hangs_plumb(ctx, q, "lr")
    # both palms end on their grips, the part's width apart, and come up holding it there
    grips = np.array([ctx.workplace.station(f"bench_a_box_{s}").pos for s in ("left", "right")])
    gaps = np.linalg.norm(np.diff(hand_points(ctx, r.frames), axis=1)[:, 0], axis=1)
    at = int(np.argmin(np.linalg.norm(hand_points(ctx, r.frames) - grips[None], axis=2).max(1)))
    assert gaps[at:] == pytest.approx(gaps[at], abs=0.02)


def test_a_two_handed_cycle_from_and_to_pallets_ends_every_hand_on_target(pallets):
    """The whole cycle (pick from the floor, carry, place on the low pallet): every hand on
    its target, no contact with the scene, no warning of a hand short of its target."""
    res = simulate_cycle(pallets, rng=0)
    assert [a.kind for a in res.arms] == ["pick", "place"]
    assert max(a.hand_error for a in res.arms) < 0.01
    assert not res.collisions
    # the pick crouches: MTM-1 bend and arise on top of the standing station's pick
    assert res.tasks[0].duration > BODY_MOTION_TMU["B"] * TMU + BODY_MOTION_TMU["AB"] * TMU


def test_a_two_handed_pick_deep_on_a_bench_bends_briefly(scenes_dir, tmp_path):
    """The box 25 cm further back on bench a (grips at 1.05 m, above the knee): standing the
    hands fall short; the trunk bends forward (no crouch) and both hands reach the grips. A
    bend that keeps the hands above the knee is no MTM-1 bend (B): the body goes down at a
    full bend's pace for as long as its angle needs, well under B's 29 TMU."""
    xml = (scenes_dir / "assembly_station_2h.xml").read_text()
    for x in ("0", "-0.2", "0.2"):  # bench a's box and grips (bench b's lie at y = 0.1)
        xml = xml.replace(f'pos="{x} -0.1 1.05"', f'pos="{x} 0.15 1.05"')
    assert xml.count(" 0.15 1.05") == 4
    (tmp_path / "assembly_station_2h.xml").write_text(xml)
    (tmp_path / "c.toml").write_text((scenes_dir / "assembly_station_2h.toml").read_text())
    ctx = prepare(load_cycle_spec(tmp_path / "c.toml"))
    jm = ctx.jointmap
    st = ctx.workplace.station("stand_bench_a")
    task = ctx.spec.tasks[0]

    def reach():
        return reachspot.reach_task(
            ctx,
            task,
            reachspot.ReachStart(st.pos[0], st.pos[1], st.yaw),
            reaching.ReachPace(0.4, 30.0, reaching.default_timing),
        )

    r = reach()
    assert r.error < 0.01 and r.distance == np.inf
    assert not frame_contacts(ctx, np.vstack([r.turn, r.frames]))
    z = r.frames[:, jm.root + 2]
    assert np.allclose(z, r.turn[-1, jm.root + 2])  # no crouch
    bend = trunk_bend(ctx, r.frames, r.turn[-1])
    assert np.radians(5.0) < bend.max() < np.radians(45.0)
    down = np.flatnonzero(bend >= bend.max() - 1e-9)[0]
    assert (down + 1) / 30.0 < 0.5 * BODY_MOTION_TMU["B"] * TMU
    with pytest.MonkeyPatch.context() as m:  # upright only: short of the grips
        m.setattr(reaching, "leaning", lambda ctx, q0, *a: q0)
        m.setattr(reachspot, "CROUCH_DROPS", ())
        assert reach().error > 0.02


def test_a_one_handed_stoop_below_the_knee_takes_mtm_bend_and_arise(scenes_dir, tmp_path):
    """A one-handed pick from a pallet 25 cm high (the hand's target 0.41 m up, below the
    1.75 m operator's knee at 0.50 m): the operator stoops (no crouch), and the stoop takes at
    least MTM-1's bend (B) on the way down and its arise (AB) on the way up."""
    xml = box_at((scenes_dir / "assembly_station_2h.xml").read_text(), "bench_a", 0.35)
    (tmp_path / "p.xml").write_text(xml)
    (tmp_path / "c.toml").write_text(
        'scene = "p.xml"\nstart = "stand_bench_a"\n[humanoid]\nstature = 1.75\n'
        '[[task]]\nkind = "pick"\nsite = "bench_a_box"\nhand = "left"\n'
    )
    ctx = prepare(load_cycle_spec(tmp_path / "c.toml"))
    st = ctx.workplace.station("stand_bench_a")
    r = reachspot.reach_task(
        ctx,
        ctx.spec.tasks[0],
        reachspot.ReachStart(st.pos[0], st.pos[1], st.yaw),
        reaching.ReachPace(0.4, 30.0, reaching.default_timing),
    )
    assert r.error < 0.01 and r.distance == np.inf
    z = r.frames[:, ctx.jointmap.root + 2]
    assert np.allclose(z, r.turn[-1, ctx.jointmap.root + 2])  # a stoop, not a crouch
    bend = trunk_bend(ctx, r.frames, r.turn[-1])
    assert bend.max() > np.radians(45.0)
    deepest = np.flatnonzero(bend >= bend.max() - 1e-9)
    assert (deepest[0] + 1) / 30.0 >= BODY_MOTION_TMU["B"] * TMU - 1 / 30.0
    assert (len(bend) - 1 - deepest[-1]) / 30.0 >= BODY_MOTION_TMU["AB"] * TMU - 1 / 30.0
