"""A batch's run simulated again with its timeline (mjwalk.cycle.replay): the same cycle."""

from __future__ import annotations

from pathlib import Path

import pytest

from mjwalk.cycle.context import context_of
from mjwalk.cycle.replay import EXPORT_NAMES, export_runs, replay_run
from mjwalk.cycle.simulate import simulate_cycles
from mjwalk.cycle.spec import load_cycle_spec

ROOT = Path(__file__).resolve().parents[2]


@pytest.fixture(scope="module")
def waits(tmp_path_factory):
    """A two-task cycle of waits (no walk, no reach: cheap), its context and a 2-run batch."""
    path = tmp_path_factory.mktemp("replay") / "waits.toml"
    scene = (ROOT / "scenes" / "assembly_station.xml").as_posix()
    path.write_text(
        f'scene = "{scene}"\nstart = "stand_rack2"\n\n[[task]]\nkind = "wait"\nduration = 0.5\n\n'
        '[[task]]\nkind = "wait"\nduration = 0.25\n'
    )
    spec = load_cycle_spec(path)
    batch = simulate_cycles(spec, runs=2, seed=4, n_jobs=1, collisions=False, progress=False)
    return context_of(spec), batch


def test_replay_is_the_batch_run_with_its_timeline(waits):
    ctx, batch = waits
    again = replay_run(ctx, 4, 1)
    assert again.run == 1 and again.timeline is not None and again.timeline.n_frames > 0
    assert again.cycle_time == batch[1].cycle_time
    assert [t.kind for t in again.tasks] == ["wait", "wait"]


def test_export_runs_writes_each_run_once(waits, tmp_path):
    ctx, batch = waits
    replayed = {0: replay_run(ctx, 4, 0)}
    got = list(export_runs(ctx, 4, batch, tmp_path, ["csv", "csv"], replayed))
    assert [(k, p.name) for k, p in got] == [
        ("csv", EXPORT_NAMES["csv"].format(0)),
        ("csv", EXPORT_NAMES["csv"].format(1)),
    ]
    assert all(p.stat().st_size > 0 for _, p in got)
