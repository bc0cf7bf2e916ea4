"""The station cycle end to end: five walk routes, every task in order, no contacts, repeatable."""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest

from mjwalk.cycle.simulate import prepare, simulate_cycle, simulate_cycles
from mjwalk.cycle.spec import load_cycle_spec
from mjwalk.timeline import check_collisions


@pytest.fixture(scope="module")
def ctx(scenes_dir):
    """The station's cycle at the step model's own pace and the 1.75 m humanoid (its
    [population] left out: these tests pin the cycle's mechanics; the workforce's operators
    are tested in tests/cycle/test_population.py. A short operator may stop where the rack-2 tool is
    just beyond their arm: seed 7 draws a 1.55 m operator whose hand ends 1.3 cm short of it)."""
    spec = load_cycle_spec(scenes_dir / "assembly_station.toml")
    return prepare(dataclasses.replace(spec, population=None))


def test_station_cycle_end_to_end(ctx):
    result = simulate_cycle(ctx, 7, keep_timeline=True)
    spec = ctx.spec
    # every task, in the spec's order, back to back
    assert [t.index for t in result.tasks] == list(range(len(spec.tasks)))
    assert [t.kind for t in result.tasks] == [t.kind for t in spec.tasks]
    for a, b in zip(result.tasks, result.tasks[1:], strict=False):
        assert b.start == pytest.approx(a.end)
        assert b.end > b.start
    assert result.cycle_time == pytest.approx(result.tasks[-1].end)
    # five distinct walk routes T1..T5, seven walks (T2 and T3 there and back)
    assert [w.route for w in result.walks] == ["T1", "T2", "T2", "T3", "T3", "T4", "T5"]
    # each walk ends in its stand zone: within half a step of the site, the work in reach
    step = ctx.step_model.pace().step_length
    for w in result.walks:
        zone = ctx.zone(w.task, spec.stature, step)
        assert zone.contains(w.path.xy[-1])
        assert np.linalg.norm(w.path.xy[-1] - zone.centre) <= 0.5 * step + 1e-9
    # the hand reaches every screw, the tool and the drop-off point
    assert max(a.hand_error for a in result.arms) < 0.01
    assert not any(a.outside for a in result.arms)
    # no humanoid-scene contact (feet on the floor are not contacts unless > 1 cm deep)
    assert result.collisions == []
    assert check_collisions(result) == []
    # the arms move into and out of the reach model's ready posture instead of snapping between
    # two frames (before the ready phase the elbow jumped 87 deg at every reach; now at most
    # 50 deg/frame here, in the short MTM case-E return after the tool pick)
    jm = ctx.jointmap
    for joint in ("elbow_l", "elbow_r", "shoulder_l_flex", "shoulder_r_flex"):
        step = np.abs(np.diff(result.timeline.qpos[:, jm.adr(joint)]))
        assert np.degrees(step.max()) < 60.0, joint
    # a walk's last step lands knee flexed and pelvis low; the final turn settles into standing
    # instead of snapping (knees jumped 57-64 deg in one frame before), and
    # the hanging forearms do not snap into or out of the walking tuck (45 deg/frame before)
    q = result.timeline.qpos
    for joint in ("knee_l", "knee_r", "hip_l_flex", "hip_r_flex", "forearm_l_pron"):
        step = np.degrees(np.abs(np.diff(q[:, jm.adr(joint)])))
        assert step.max() < 30.0, (joint, step.max())
    # the timeline covers the cycle at 30 frames per second
    assert result.timeline.t[-1] == pytest.approx(result.cycle_time, abs=2 / 30)


def test_same_seed_same_cycle(ctx):
    a = simulate_cycle(ctx, 11, collisions=False)
    b = simulate_cycle(ctx, 11, collisions=False)
    assert a.cycle_time == b.cycle_time
    assert [w.length for w in a.walks] == [w.length for w in b.walks]
    c = simulate_cycle(ctx, 12, collisions=False)
    assert [w.length for w in a.walks] != [w.length for w in c.walks]


def test_monte_carlo_independent_of_jobs(scenes_dir):
    spec = scenes_dir / "assembly_station.toml"
    one = simulate_cycles(spec, runs=3, seed=5, n_jobs=1, collisions=False)
    two = simulate_cycles(spec, runs=3, seed=5, n_jobs=2, collisions=False)
    assert [r.cycle_time for r in one] == [r.cycle_time for r in two]
    assert len({r.cycle_time for r in one}) == 3


def test_a_run_does_not_depend_on_the_runs_before_it(scenes_dir):
    """Run 37 of seed 0 alone, and after run 31 (whose operator's stature rounds to the same
    millimetre): the same cycle. The stand-zone cache handed run 37 the zone made for run 31's
    exact stature (87.6 s alone, 87.47 s after it), so a batch's CSV even changed with
    PYTHONHASHSEED."""
    spec = load_cycle_spec(scenes_dir / "assembly_station.toml")

    def run(ctx, k):
        rng = np.random.default_rng(np.random.SeedSequence([0, k]))
        return simulate_cycle(ctx, rng, run=k, collisions=False)

    alone = run(prepare(spec), 37)
    ctx = prepare(spec)
    run(ctx, 31)
    after = run(ctx, 37)
    assert [w.length for w in after.walks] == [w.length for w in alone.walks]
    assert after.cycle_time == alone.cycle_time


def test_monte_carlo_runs_the_spec_as_edited_in_memory(scenes_dir):
    """A CycleSpec edited in memory is simulated with its edits: the workers used to re-read
    ``spec.path``, so ``dataclasses.replace(spec, ...)`` was silently ignored."""
    spec = load_cycle_spec(scenes_dir / "assembly_station.toml")
    short = dataclasses.replace(spec, tasks=spec.tasks[:2], population=None)
    (result,) = simulate_cycles(short, runs=1, seed=3, collisions=False)
    assert [t.kind for t in result.tasks] == [t.kind for t in spec.tasks[:2]]
    assert result.spec.population is None
    # the same in-memory spec again comes from the worker's cache: the same run
    (again,) = simulate_cycles(short, runs=1, seed=3, collisions=False)
    assert again.cycle_time == result.cycle_time


def test_right_hand_tasks_use_the_right_hand(scenes_dir, tmp_path):
    """Issue 16: ``hand = "right"`` is done with the right arm: its hand reaches the site within
    1 cm while the left hand keeps its place, with no contact."""
    import mujoco

    toml = f"""
name = "right-handed picks"
scene = "{(scenes_dir / "assembly_station.xml").as_posix()}"
start = "stand_rack2"
[[task]]
kind = "pick"
site = "rack2_screw1"
hand = "right"
part = "screw"
[[task]]
kind = "carry"
site = "stand_car1"
hand = "right"
part = "screw"
[[task]]
kind = "fasten"
site = "car_screw1"
hand = "right"
part = "screw"
duration = 1.0
"""
    path = tmp_path / "right.toml"
    path.write_text(toml)
    result = simulate_cycle(load_cycle_spec(path), 3, keep_timeline=True)
    assert [a.hand for a in result.arms] == ["right", "right"]
    assert max(a.hand_error for a in result.arms) < 0.01
    assert result.collisions == []
    tl = result.timeline
    m, data = tl.model, mujoco.MjData(tl.model)
    hl, hr = m.body("human/hand_l").id, m.body("human/hand_r").id
    pelvis = m.body("human/pelvis").id
    for task in (t for t in result.tasks if t.kind in ("pick", "fasten")):
        rel = []
        for k in np.flatnonzero((tl.t >= task.start) & (tl.t <= task.end)):
            data.qpos[:] = tl.qpos[k]
            mujoco.mj_kinematics(m, data)
            R = data.xmat[pelvis].reshape(3, 3)
            rel.append([R.T @ (data.xpos[h] - data.xpos[pelvis]) for h in (hl, hr)])
        rel = np.asarray(rel)
        # in the pelvis frame the left hand barely moves, the right hand travels
        assert np.ptp(rel[:, 0], axis=0).max() < 0.05
        assert np.ptp(rel[:, 1], axis=0).max() > 0.2


def test_turns_on_the_spot_go_at_the_operators_cadence(ctx):
    """A turn on the spot is made of steps: a walker at 90 steps/min takes 113/90 as long as
    the reference adult (113 steps/min) for the same half turn; without an operator, 1:1."""
    from mjwalk.cycle.context import operator_context
    from mjwalk.cycle.poses import turn_frames
    from mjwalk.gait.walker import REFERENCE_CADENCE, Walker

    assert operator_context(ctx, None) is ctx
    _, ref = turn_frames(ctx, (0.0, 0.0), 0.0, np.pi, 30.0)
    slow = Walker(stature=ctx.spec.stature, speed=1.0, cadence=90.0)
    _, dt = turn_frames(operator_context(ctx, slow), (0.0, 0.0), 0.0, np.pi, 30.0)
    assert dt / ref == pytest.approx(REFERENCE_CADENCE / 90.0, rel=0.05)


def test_station_run_330_keeps_the_turning_knee_off_rack_2(scenes_dir):
    """Run 330 of 2000 (seed 0): a 1.81 m fatigued operator's route T4 to rack 2 turned right
    beside rack 2's frame, and the left knee, bending in its foot's plane 50 degrees behind the
    pelvis's turn, went 3.0 cm into ``rack2_frame_r`` (7 contacts at 70.6-70.7 s) where the
    planner probed the knee ahead along the pelvis's yaw. With the knee probed along the swing
    foot's yaw (mjwalk.plan.options.SWING_TURN_PHASES) that run has no contact."""
    spec = scenes_dir / "assembly_station.toml"
    (result,) = simulate_cycles(spec, runs=2000, seed=0, only=[330])
    assert result.operator is not None and round(result.operator.stature, 2) == 1.81
    assert result.error is None
    assert result.collisions == []


@pytest.mark.slow
def test_station_run_732_keeps_a_tall_operators_carrying_hand_off_the_car(scenes_dir):
    """Run 732 of 2000 (seed 0): a 2.02 m operator carrying screws in the left hand to car
    stand 2 lowered the hand from the carrying posture as the room to the car shrank, and the
    left index finger went 7.4 mm into ``car_body`` (41.9 s, 0.46 s before the walk's end): the
    arms' keep-in ramp (mjwalk.timeline.frames.ARM_ROOM) was in fixed metres, the hand's reach
    is not. With the ramp scaled to the stature (``arm_room``) that run has no contact."""
    spec = scenes_dir / "assembly_station.toml"
    (result,) = simulate_cycles(spec, runs=2000, seed=0, only=[732])
    assert result.operator is not None and round(result.operator.stature, 2) == 2.02
    assert result.error is None
    assert result.collisions == []


@pytest.mark.parametrize("seed", [0, 3])
def test_contact_check_and_ergonomics_sharing_kinematics_match_each_alone(ctx, seed):
    """A cycle computes its humanoid's geom poses once for the contact check and the ergonomics
    (``timeline.geomposes.GeomTable``); each asked alone computes its own: the same contacts and
    scores, bit for bit."""
    import pickle

    both = simulate_cycle(ctx, seed)
    contacts = simulate_cycle(ctx, seed, ergonomics=False).collisions
    scores = simulate_cycle(ctx, seed, collisions=False).ergonomics

    def rows(found):
        return [(c.time, c.body_part, c.scene_geom, c.depth, c.pos.tobytes()) for c in found]

    assert rows(both.collisions) == rows(contacts)
    assert pickle.dumps(both.ergonomics) == pickle.dumps(scores)


def test_a_task_on_a_platform_scores_as_the_same_task_on_the_floor():
    """Issue 47: heights are measured above the surface stood on. A pick of a 5 kg part on a
    0.34 m platform (the body, the site and the ground all 0.34 m up) gives the same NIOSH V,
    RWL and LI, hand height and RULA/REBA/OWAS peaks as on the floor. Before, its V and hand
    height were 34 cm higher and its feet, 0.34 m above the cycle's lowest ankle, were
    'not down' (RULA's legs unsupported)."""
    from types import SimpleNamespace

    from mjwalk.body.humanoid import humanoid_model, pelvis_height
    from mjwalk.cycle.simulate import cycle_ergonomics
    from mjwalk.ergonomics.angles import angles_from_qpos
    from mjwalk.timeline.timeline import Timeline

    model, jm = humanoid_model()
    q0 = jm.neutral_qpos(model)
    q0[jm.root + 2] = pelvis_height(1.75)
    qpos = np.tile(q0, (60, 1))  # a walk, a wait, the pick (arm raised, trunk bent)
    for name, deg in (("shoulder_l_flex", 60.0), ("elbow_l", 30.0), ("lumbar_flex", 40.0)):
        qpos[40:, jm.adr(name)] = np.radians(deg)
    hand = angles_from_qpos(model, jm, qpos[50:51]).hands[0, 0]
    task = dict(hand="left", mass=5.0, coupling="fair", duration=None)
    spec = SimpleNamespace(tasks=[
        SimpleNamespace(kind="walk", site="stand", **task),
        SimpleNamespace(kind="wait", site=None, **task),
        SimpleNamespace(kind="pick", site="shelf", **task),
    ])  # fmt: skip
    starts, ends = [0, 20, 40], [20, 40, 60]
    out = []
    for up in (0.0, 0.34):
        q = qpos.copy()
        q[20:, jm.root + 2] += up  # walked up onto the platform
        tl = Timeline(model=model, jointmap=jm, fps=10.0, t=np.arange(60) / 10.0, qpos=q,
                      scene="", stature=1.75)  # fmt: skip
        wp = SimpleNamespace(
            floor_z=0.0, stations={"shelf": SimpleNamespace(pos=hand + [0, 0, up])}
        )
        ground = np.where(np.arange(60) < 20, 0.0, up)
        out.append(cycle_ergonomics(tl, spec, starts, ends, 60.0, wp, ground=ground))
    floor, platform = out
    (a,), (b,) = floor.lifts, platform.lifts
    assert b.v == pytest.approx(a.v, abs=1e-9) and b.h == pytest.approx(a.h, abs=1e-9)
    assert b.rwl == pytest.approx(a.rwl, abs=1e-9) and b.li == pytest.approx(a.li, abs=1e-9)
    for s, t in zip(floor.tasks, platform.tasks, strict=True):
        assert (s.rula, s.reba, s.owas, s.rula_driver) == (t.rula, t.reba, t.owas, t.rula_driver)
        assert t.extra["hand_height_max_m"] == pytest.approx(s.extra["hand_height_max_m"])


@pytest.mark.slow
@pytest.mark.parametrize(("run", "stature"), [(5909, 1.67), (9828, 1.71), (4395, 1.56)])
def test_the_station_runs_with_a_backward_step_simulate(scenes_dir, run, stature):
    """Seeded: runs 5909 and 9828 of ``mjwalk simulate scenes/assembly_station.toml --runs
    10000`` (seed 0) planned walk 4 with a step whose foot landed 0.43-0.47 m behind its start
    pelvis, the pelvis going back; run 4395 (at bebb988) walk 6 with a step whose foot landed
    0.24 m behind its stance foot. The leg synthesis reached the stance foot only with the
    pelvis 6.3, 7.5 and 6.8 cm lowered and refused the run (PlanningError). The step check
    refuses steps going backward and walking steps whose foot does not pass the stance foot
    (:data:`mjwalk.plan.options.MIN_STEP_ADVANCE`): all three simulate, with no contact."""
    spec = load_cycle_spec(scenes_dir / "assembly_station.toml")
    (r,) = simulate_cycles(spec, 10000, seed=0, only=[run], on_error="raise")
    assert r.error is None
    assert r.operator is not None and r.operator.stature == pytest.approx(stature)
    assert r.collisions == []
