"""mjwalk.ergonomics.assess: a cycle scored task by task with every registered method."""

from __future__ import annotations

from test_angles import humanoid_motion

from mjwalk.ergonomics.angles import angles_from_qpos
from mjwalk.ergonomics.assess import assess_cycle
from mjwalk.ergonomics.registry import SCORES
from mjwalk.ergonomics.score import TaskSpan

FPS = 10.0


def reach_cycle(mass: float = 3.0):
    """A 4 s cycle: 2 s standing (a wait), then 2 s reaching the left arm to 100 deg to take
    a part of ``mass`` kg from a site at the left hand's position."""
    model, jm, qpos = humanoid_motion(20, shoulder_l_flex=100.0, elbow_l=30.0)
    ang = angles_from_qpos(model, jm, qpos)
    spans = [
        TaskSpan(0, "wait", 0, 20),
        TaskSpan(1, "pick", 20, 40, "left", site="shelf", mass=mass, coupling="fair",
                 site_pos=ang.hands[30, 0], reach=True, part="take", lifts=True),
        TaskSpan(2, "empty", 40, 40),
    ]  # fmt: skip
    return ang, spans


def test_each_task_with_frames_gets_its_peaks():
    ang, spans = reach_cycle()
    run = assess_cycle(ang, spans, cycle_time=4.0, fps=FPS)
    assert [t.index for t in run.tasks] == [0, 1]  # the task without frames has no entry
    wait, pick = run.tasks
    assert pick.reach and not wait.reach and pick.site == "shelf"
    assert pick.rula > wait.rula and pick.upper_arm == 4 and pick.side == "left"
    assert 2.0 <= pick.rula_time < 4.0
    assert run.rula.shape == run.reba.shape == (40,) and run.rula_peak == pick.rula
    assert len(run.lifts) == 1 and run.lifts[0].task == 1 and run.lifts[0].hand == "left"
    assert set(SCORES) >= {"rula", "reba", "owas", "niosh", "iso11226"}
