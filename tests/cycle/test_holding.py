"""Two-handed pick / carry / place (issue 16 item 1, ``hand = "both"``; mjwalk.cycle.holding)."""

import sys
from pathlib import Path

import numpy as np
import pytest

from mjwalk.cycle.holding import hands_moved
from mjwalk.cycle.simulate import (
    carry_abduction,
    carry_pose,
    hand_points,
    prepare,
    simulate_cycle,
    standing_pose,
)
from mjwalk.cycle.spec import load_cycle_spec
from mjwalk.errors import CycleSpecError
from mjwalk.timeline.parts import hand_poses

SPEC = Path(__file__).resolve().parents[2] / "scenes" / "assembly_station_2h.toml"
#: Grip distance of the box in scenes/assembly_station_2h.xml (bench_a_box_left/_right), m.
WIDTH = 0.40


@pytest.fixture(scope="module")
def run():
    ctx = prepare(load_cycle_spec(SPEC))
    return ctx, simulate_cycle(ctx, 0, keep_timeline=True)


@pytest.mark.slow
def test_both_hands_reach_their_grips_without_contacts(run):
    _, r = run
    assert [(a.kind, a.hand) for a in r.arms] == [("pick", "both"), ("place", "both")]
    assert all(a.hand_error < 0.01 for a in r.arms)  # the worse of the two hands
    assert r.collisions == []


@pytest.mark.slow
def test_carry_keeps_both_hands_on_the_part(run):
    ctx, r = run
    carry = next(t for t in r.tasks if t.kind == "carry")
    tl = r.timeline
    # the walk's frames in the carrying posture (all of them: it no longer fades at the ends)
    in_walk = (tl.t >= carry.start) & (tl.t <= carry.end)
    abd = tl.qpos[:, ctx.jointmap.adr("shoulder_l_abd")]
    f = in_walk & np.isclose(abd, carry_abduction(ctx, WIDTH), atol=1e-6)
    assert f.sum() > 5
    h = hand_points(ctx, tl.qpos[f])
    gap = np.linalg.norm(h[:, 0] - h[:, 1], axis=1)
    assert np.all(np.abs(gap - WIDTH) < 0.02), (gap.min(), gap.max())


def _pelvis_frame(q: np.ndarray, p: np.ndarray) -> np.ndarray:
    """Points ``p`` (F, 3) in the pelvis's yaw frame of poses ``q`` (F, nq) (root at 0..7)."""
    yaw = 2.0 * np.arctan2(q[:, 6], q[:, 3])
    d = p - q[:, :3]
    c, s = np.cos(yaw), np.sin(yaw)
    return np.column_stack([c * d[:, 0] + s * d[:, 1], -s * d[:, 0] + c * d[:, 1], d[:, 2]])


@pytest.mark.slow
def test_hands_stay_on_the_part_from_pick_to_place(run):
    """From the end of the pick's hold to the first frame of the place reach the palms keep the
    grip distance (within 2 cm) and, from the end of the pick's return on (turns, walk), the
    part moves with the body: the palms' midpoint stays within 0.1 m of where the carrying
    posture holds it relative to the pelvis."""
    ctx, r = run
    assert ctx.jointmap.root == 0
    tl = r.timeline
    q = tl.qpos
    pick = next(t for t in r.tasks if t.kind == "pick")
    place = next(t for t in r.tasks if t.kind == "place")
    arm_pick, arm_place = r.arms
    # a task from t0 to t1 (s) fills frames round(t0 fps) + 1 .. round(t1 fps)
    p1 = round(pick.end * tl.fps)
    p0 = p1 - round(arm_pick.duration * tl.fps) + 1  # the pick reach's first frame
    still = np.flatnonzero(np.all(q[p0 + 1 : p1 + 1] == q[p0:p1], axis=1))
    assert len(still) > 3  # the hold repeats one pose
    hold_end = p0 + 1 + int(still[-1])
    reach = round((place.end - arm_place.duration) * tl.fps) + 1  # the place reach's first frame
    assert hold_end < p1 < reach
    h = hand_points(ctx, q[hold_end : reach + 1])
    gap = np.linalg.norm(h[:, 0] - h[:, 1], axis=1)
    assert np.abs(gap - WIDTH).max() < 0.02, (gap.min(), gap.max())
    mid = _pelvis_frame(q[p1 : reach + 1], h[p1 - hold_end :].mean(axis=1))
    ref_q = carry_pose(ctx, standing_pose(ctx, 0.0, 0.0, 0.0), WIDTH)
    ref = _pelvis_frame(ref_q[None], hand_points(ctx, ref_q[None]).mean(axis=1))[0]
    dev = np.linalg.norm(mid - ref, axis=1)
    assert dev.max() < 0.1, dev.max()
    # the box leaves the bench the way the hands came: lifted towards the pre-grasp point (10 cm
    # up, 15 cm back) before it swings into the carrying posture, instead of sliding diagonally
    # through the bench's edge; the place lowers it the same way
    c = h.mean(axis=1)
    z0 = c[0, 2]
    away = np.flatnonzero(np.linalg.norm(c[:, :2] - c[0, :2], axis=1) >= 0.10)[0]
    assert c[away, 2] - z0 >= 0.06, c[away, 2] - z0
    # no jumps: each palm moves less than 5 cm a frame relative to the pelvis (1.5 m/s)
    rel = np.stack([_pelvis_frame(q[hold_end : reach + 1], h[:, i]) for i in (0, 1)])
    assert np.linalg.norm(np.diff(rel, axis=1), axis=2).max() < 0.05


def test_both_needs_grip_sites(tmp_path):
    text = SPEC.read_text().replace('site = "bench_a_box"', 'site = "bench_a_box_left"')
    bad = tmp_path / "bad.toml"
    bad.write_text(
        text.replace(
            'scene = "assembly_station_2h.xml"',
            f'scene = "{SPEC.parent / "assembly_station_2h.xml"}"',
        )
    )
    with pytest.raises(CycleSpecError, match="grip"):
        load_cycle_spec(bad)


def test_no_one_handed_reach_while_both_hands_hold_the_part(tmp_path):
    """Both hands are on the box's grips from its pick to its place: a one-handed pick in
    between is refused by name (it used to run with the arms at rest and the box left in the
    air), and the same pick after the place is accepted."""
    base = SPEC.read_text().replace(
        'scene = "assembly_station_2h.xml"',
        f'scene = "{SPEC.parent / "assembly_station_2h.xml"}"',
    )
    one_hand = '\n[[task]]\nkind = "pick"\nsite = "bench_b_box_left"\nhand = "left"\n'
    between = base.replace(
        '[[task]]\nkind = "place"', one_hand.lstrip("\n") + '\n[[task]]\nkind = "place"'
    )
    assert between != base
    bad = tmp_path / "between.toml"
    bad.write_text(between)
    with pytest.raises(
        CycleSpecError, match=r"one-handed pick \(left hand\) while both hands hold"
    ):
        load_cycle_spec(bad)
    good = tmp_path / "after.toml"
    good.write_text(base + one_hand)
    assert [t.hand for t in load_cycle_spec(good).tasks][-1] == "left"


@pytest.fixture(scope="module")
def shelves(tmp_path_factory):
    """The two-handed station with the box on a shelf board over bench a, its grips 1.85 m up
    (above a 1.75 m operator's shoulder, 0.4 m above the 1.45 m shoulder), placed on a shelf as
    high over bench b."""
    sys.path.insert(0, str(SPEC.parents[1] / "benchmarks"))
    from bench_heights import box_at

    folder = tmp_path_factory.mktemp("shelves")
    xml = SPEC.with_suffix(".xml").read_text()
    (folder / "assembly_station_2h.xml").write_text(
        box_at(box_at(xml, "bench_a", 1.85), "bench_b", 1.85)
    )
    (folder / "cycle.toml").write_text(SPEC.read_text())
    return simulate_cycle(prepare(load_cycle_spec(folder / "cycle.toml")), 0)


def test_a_part_on_a_high_shelf_is_picked_and_placed_clear_of_the_boards(shelves):
    """Both hands on the grips (within 1 cm), no contact with the scene: the hands come onto
    the box's sides pointing along their approach, in and down over the board's edge, and the
    box lifted off the board is pulled clear of its front edge before it is lowered into the
    carrying posture (on the place, the reverse). Before, the forearms sloped up through the
    edge and the lowering arms swung the hands down through it: 108 contact frames in the
    pick, 59 in the place."""
    r = shelves
    assert [a.kind for a in r.arms] == ["pick", "place"]
    assert max(a.hand_error for a in r.arms) < 0.01
    assert r.collisions == []


def test_hands_moved_keeps_the_hands_directions():
    """``hands_moved`` moves each wrist by its offset and keeps the hand's direction."""
    ctx = prepare(load_cycle_spec(SPEC))

    def wrists(q):  # (2, 3): the hand bodies' origins in pose q
        return hand_poses(ctx.model, ctx.jointmap, q[None])[0][0]

    q = carry_pose(ctx, standing_pose(ctx, 0.3, -0.2, 0.7), WIDTH)
    offsets = np.array([[0.05, -0.03, 0.10], [-0.02, 0.04, 0.08]])
    moved = hands_moved(ctx, q, offsets)
    np.testing.assert_allclose(wrists(moved) - wrists(q), offsets, atol=1e-9)
    before, after = (hand_points(ctx, p[None])[0] - wrists(p) for p in (q, moved))
    np.testing.assert_allclose(after, before, atol=1e-9)
