"""Two-handed pick / carry / place (issue 16 item 1, ``hand = "both"``)."""

from pathlib import Path

import numpy as np
import pytest

from mjwalk.cycle.simulate import carry_abduction, hand_points, prepare, simulate_cycle
from mjwalk.cycle.spec import load_cycle_spec
from mjwalk.errors import CycleSpecError

SPEC = Path(__file__).resolve().parents[1] / "scenes" / "assembly_station_2h.toml"
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
    # the held stretch of the walk: the carrying posture fully in (it fades in and out over
    # ARM_EASE at the walk's ends, where the hands move between the rest and the holding pose)
    in_walk = (tl.t >= carry.start) & (tl.t <= carry.end)
    abd = tl.qpos[:, ctx.jointmap.adr("shoulder_l_abd")]
    f = in_walk & np.isclose(abd, carry_abduction(ctx, WIDTH), atol=1e-6)
    assert f.sum() > 5
    h = hand_points(ctx, tl.qpos[f])
    gap = np.linalg.norm(h[:, 0] - h[:, 1], axis=1)
    assert np.all(np.abs(gap - WIDTH) < 0.02), (gap.min(), gap.max())


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
