"""Handling times (issue 14 item 4, issue 16 item 3): MTM-1 reach times grow with distance, the
operator's pace divides them, and each task's time varies by a lognormal factor, so a cycle's
task times spread between runs. Seeded, with stated tolerances."""

from __future__ import annotations

import numpy as np
import pytest

from mjwalk.cycle.handling import REACH_TMU, TMU, reach_duration, reach_tmu, task_factor
from mjwalk.cycle.spec import load_cycle_spec
from mjwalk.gait.walker import Walker


def test_reach_time_grows_with_distance_and_slows_with_pace():
    d = np.linspace(0.0, 1.0, 41)
    for case in REACH_TMU:
        t = np.array([reach_tmu(x, case) for x in d])
        assert np.all(np.diff(t) > 0)
        assert t[-1] > 2 * t[4]  # 1 m takes more than twice 0.1 m
    # the MTM-1 card's entries: 10 in case B = 11.5 TMU, 30 in = 25.8 TMU
    assert reach_tmu(0.254, "B") == pytest.approx(11.5)
    assert reach_duration(0.762, None, "B") == pytest.approx(25.8 * TMU)
    slow = Walker(1.7, 0.685, 100.0)  # half the reference pace
    assert reach_duration(0.5, slow) == pytest.approx(2 * reach_duration(0.5))


def test_task_factor_is_lognormal_with_median_one():
    rng = np.random.default_rng(3)
    f = np.array([task_factor(rng, 0.2) for _ in range(4000)])
    assert np.median(f) == pytest.approx(1.0, abs=0.02)  # se of the median ~0.004
    assert np.std(f) / np.mean(f) == pytest.approx(0.2, abs=0.015)
    assert np.mean(f) > np.median(f)  # right-skewed


def test_task_times_vary_between_runs(tmp_path, scenes_dir):
    """A cycle of handling only (no walks), 6 runs: the pick times spread (IQR > 0.02 s; they
    were one constant before), and the hand still lands within 1 cm."""
    from mjwalk.cycle.simulate import prepare, simulate_cycle

    scene = (scenes_dir / "assembly_station.xml").as_posix()
    path = tmp_path / "h.toml"
    path.write_text(
        f'scene = "{scene}"\nstart = "stand_rack2"\n'
        '[[task]]\nkind = "pick"\nsite = "rack2_screw2"\n'
        '[[task]]\nkind = "pick"\nsite = "rack2_screw1"\n'
    )
    ctx = prepare(load_cycle_spec(path))
    runs = [simulate_cycle(ctx, k, collisions=False) for k in range(6)]
    near = np.array([r.tasks[0].end - r.tasks[0].start for r in runs])
    assert np.percentile(near, 75) - np.percentile(near, 25) > 0.02
    assert max(r.arms[0].hand_error for r in runs) < 0.01
