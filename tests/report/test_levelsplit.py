"""The walk time split over levels (issue 47): a seeded cycle on the multi-level station walks
the stair and the step, stands on the levels' heights, and its report's split sums to its walk
time; a group with no step-up takes the ramp and the split names it; flat cycles have no split."""

from __future__ import annotations

from types import SimpleNamespace

import numpy as np
import pytest

from mjwalk.body.humanoid import pelvis_height
from mjwalk.cycle.context import prepare
from mjwalk.cycle.simulate import simulate_cycle
from mjwalk.cycle.spec import load_cycle_spec
from mjwalk.cycle.walking import plan_cycle_walks
from mjwalk.gait.walker import Walker
from mjwalk.plan.synthetic import synthetic_walk
from mjwalk.report.figures import report_dict
from mjwalk.report.levelsplit import KINDS, crossings_of, level_split, split_markdown, walk_kinds
from mjwalk.report.markdown import format_markdown


def _spec(tmp_path, scenes_dir, sites, start="stand_stair", population=""):
    path = tmp_path / "c.toml"
    tasks = "".join(f'[[task]]\nkind = "walk"\nsite = "{s}"\n' for s in sites)
    path.write_text(
        f'scene = "{scenes_dir / "multilevel_station.xml"}"\nstart = "{start}"\n'
        f"[walking]\nradius = 0.25\n{population}{tasks}"
    )
    return load_cycle_spec(str(path))


def test_a_cycle_walks_the_stair_and_the_step_and_the_split_sums(tmp_path, scenes_dir):
    spec = _spec(tmp_path, scenes_dir, ["stand_mezz_rack", "stand_platform1"])
    r = simulate_cycle(spec, 3, keep_timeline=True, collisions=False, ergonomics=False)
    ways = [crossings_of(w.path) for w in r.walks]
    assert ways[0] == "stair up"
    assert "stair down" in ways[1] and ("step up" in ways[1] or "ramp up" in ways[1])
    split = level_split([r])
    assert split is not None
    e = split[r.group]
    walk_time = sum(w.duration for w in r.walks)
    assert sum(e["mean"][k] for k in KINDS) == pytest.approx(walk_time, abs=1e-6)
    assert e["mean"]["stairs"] > 0.0 and e["mean"]["level"] > 0.0
    # the operator stands on the platform at its end: root z = 0.34 m + the pelvis height
    tl = r.timeline
    root_z = tl.qpos[-1, tl.jointmap.root + 2]
    assert root_z == pytest.approx(0.34 + pelvis_height(spec.stature), abs=0.03)
    # the walks keep their heights in the timeline: up to the mezzanine and down again
    assert tl.qpos[:, tl.jointmap.root + 2].max() > 1.02 + 0.8 * pelvis_height(spec.stature)
    assert "## Walking over levels" in "\n".join(split_markdown(split))
    # each walk over levels has its grid-A* routes over levels (mjwalk.plan.levelgrid)
    assert all(np.isfinite(w.baseline_length) for w in r.walks)
    md = format_markdown(report_dict([r]))
    assert "compared with the grid-A* routes on each level" in md and "no grid route" not in md


def test_a_group_without_steps_takes_the_ramp(tmp_path, scenes_dir):
    pop = '[population]\nwalker = "adult"\nstep_up = 0.0\n'
    spec = _spec(tmp_path, scenes_dir, ["stand_platform1"], "stand_step", pop)
    ctx = prepare(spec)
    walker = Walker(group="adult")
    ((_, _, _, path),) = plan_cycle_walks(ctx, np.random.default_rng(0), walker)
    assert crossings_of(path) == "ramp up"
    assert path.meta["levels"]["max_riser"] == 0.0
    run = SimpleNamespace(group="adult", walks=[SimpleNamespace(path=path, direction="a->b")])
    e = level_split([run])["adult"]
    assert e["mean"]["ramps"] > 0.0 and e["mean"]["steps"] == 0.0
    assert e["routes"] == {"a->b": {"ramp up": 1}} and e["max_riser"] == [0.0]
    base = ctx.baseline_over_levels(path, walker)  # the group's baseline takes the ramp too
    assert base is not None and "ramp up" in base.meta["levels"]


def test_flat_walks_have_no_split():
    path = synthetic_walk(n_steps=6)
    assert walk_kinds(path) == {"level": path.duration, "stairs": 0.0, "ramps": 0.0, "steps": 0.0}
    run = SimpleNamespace(group="", walks=[SimpleNamespace(path=path, direction="a->b")])
    assert level_split([run]) is None
    assert split_markdown(None) == []
