"""mjwalk.cycle.context: a process prepares each spec once (by path, or by the pickle of an
in-memory spec), builds each operator's humanoid once per stature, and an operator's context
shares the cycle's caches."""

from __future__ import annotations

import dataclasses

import mujoco
import numpy as np
import pytest

from mjwalk.body.humanoid import attach_humanoid
from mjwalk.cycle.context import (
    GOAL_TOLERANCE,
    HUMANOIDS,
    Humanoids,
    context_of,
    operator_context,
)
from mjwalk.cycle.seeding import run_generator
from mjwalk.cycle.simulate import simulate_cycle
from mjwalk.cycle.spec import load_cycle_spec
from mjwalk.errors import SceneError
from mjwalk.gait.walker import REFERENCE_CADENCE, Walker
from mjwalk.plan.hybrid import HybridPlanner
from mjwalk.plan.options import PlannerOptions


@pytest.fixture(scope="module")
def station(scenes_dir):
    return scenes_dir / "assembly_station.toml"


def test_a_spec_is_prepared_once_per_path_and_per_content(station):
    ctx = context_of(station)
    assert context_of(str(station)) is ctx  # the key is the path as a string
    same = context_of(dataclasses.replace(ctx.spec))  # an equal copy: one key (its pickle)
    assert context_of(dataclasses.replace(ctx.spec)) is same
    assert same.spec == ctx.spec and same is not ctx


def test_an_operators_context_has_their_humanoid_and_shares_the_caches(station):
    ctx = context_of(station)
    assert operator_context(ctx, None) is ctx
    tall = operator_context(ctx, Walker(stature=1.9, speed=1.2, cadence=100.0))
    assert tall.spec.stature == 1.9 and tall.turn_rate == pytest.approx(100.0 / REFERENCE_CADENCE)
    assert tall.model.nq == ctx.model.nq and tall.model is not ctx.model
    assert (tall.planners, tall.zones, tall.routes) == (ctx.planners, ctx.zones, ctx.routes)
    scene = str(ctx.spec.scene)
    assert tall.model is HUMANOIDS.model(scene, 1.9)[0]  # built once for that stature
    assert tall.clearance is HUMANOIDS.clearance(scene, 1.9)
    again = operator_context(ctx, Walker(stature=1.9, speed=1.0, cadence=90.0))
    assert again.model is tall.model and again.turn_rate != tall.turn_rate
    same = operator_context(ctx, Walker(stature=ctx.spec.stature, speed=1.0, cadence=90.0))
    assert same.model is ctx.model  # the cycle's own stature: its own humanoid


def _model_bytes(model, path) -> bytes:
    mujoco.mj_saveModel(model, str(path), None)
    return path.read_bytes()


def test_a_humanoid_on_the_parsed_scene_is_the_one_on_its_file(station, tmp_path):
    scene = str(context_of(station).spec.scene)
    kept = Humanoids(limit=2)
    for stature in (1.55, 1.93):
        model, jm = kept.model(scene, stature)
        again, jm_file = attach_humanoid(scene, stature)  # the file parsed anew
        assert _model_bytes(model, tmp_path / "a.mjb") == _model_bytes(again, tmp_path / "b.mjb")
        assert repr(jm) == repr(jm_file)
    with pytest.raises(SceneError, match="no such scene file"):
        kept.model(str(tmp_path / "missing.xml"), 1.7)


def test_grid_routes_are_kept_per_pair_of_sites(station):
    ctx = context_of(station)
    d = ctx.baseline("stand_rack1", "stand_rack2")
    assert d > 0.0 and ctx.baseline("stand_rack1", "stand_rack2") == d
    assert ctx.occupancy() is ctx.occupancy()  # the grid is built once


def test_a_zones_planner_is_the_one_its_options_build_sharing_its_sites(station):
    ctx = context_of(station)
    spec = ctx.spec
    i = next(k for k, t in enumerate(spec.tasks) if t.site == "stand_rack2")
    site = ctx.planner("stand_rack2")
    for stature, step in ((1.62, 0.61), (1.87, 0.74)):
        zone = ctx.zone(i, stature, step)
        planner = ctx.planner("stand_rack2", zone)
        assert ctx.planner("stand_rack2", zone) is planner and planner is not site
        options = PlannerOptions(
            radius=spec.radius,
            goal_tolerance=zone.radius,
            goal_within=zone.discs,
            field_tolerance=GOAL_TOLERANCE,
        )
        own = HybridPlanner(ctx.workplace, "stand_rack2", ctx.step_model, options)
        assert planner.options == own.options and set(vars(planner)) == set(vars(own))
        assert planner.goal_within.tobytes() == own.goal_within.tobytes()
        assert planner.distance is site.distance and planner.grid is site.grid
        for a, b in zip(planner.params.vectors(stature), own.params.vectors(stature), strict=True):
            assert a.tobytes() == b.tobytes()
        assert planner.options.goal_tolerance == zone.radius != site.options.goal_tolerance


def _lifted_station(scenes_dir, tmp_path, dz: float = 0.5):
    """The multi-level station and its cycle moved up by ``dz`` (m): the scene wrapped in a
    frame, the cycle's TOML pointing at it."""
    xml = (scenes_dir / "multilevel_station.xml").read_text()
    i, j = xml.index("<worldbody>") + len("<worldbody>"), xml.index("</worldbody>")
    scene = tmp_path / "lifted.xml"
    scene.write_text(f'{xml[:i]}<frame pos="0 0 {dz}">{xml[i:j]}</frame>{xml[j:]}')
    toml = (scenes_dir / "multilevel_station.toml").read_text()
    cycle = tmp_path / "lifted.toml"
    cycle.write_text(toml.replace('scene = "multilevel_station.xml"', f'scene = "{scene}"'))
    return cycle


def test_the_ground_is_the_world_height_of_the_surface_stood_on(scenes_dir, tmp_path):
    """On the station moved up by 0.5 m, the ground under a site on the floor is 0.5 m and on
    the 0.34 m platform 0.84 m (world z: the standing pose's pelvis stands on it)."""
    flat = context_of(scenes_dir / "multilevel_station.toml")
    up = context_of(_lifted_station(scenes_dir, tmp_path))
    assert up.workplace.floor_z == pytest.approx(0.5, abs=1e-12)
    for site, height in (("stand_rack1", 0.0), ("stand_platform1", 0.34)):
        xy = flat.workplace.station(site).xy
        assert flat.ground(xy) == pytest.approx(height, abs=1e-9)
        assert up.ground(xy) == pytest.approx(0.5 + height, abs=1e-9)


@pytest.mark.slow
def test_the_lifted_station_cycle_walks_as_the_station_and_touches_nothing(scenes_dir, tmp_path):
    """Seeded (batch seed 0, run 0, a fatigued operator: its walks in ``walks.csv`` are the
    station's): the station moved up by 0.5 m plans the same walks, plays the body 0.5 m higher
    in every frame and has 0 contacts."""
    flat_spec = load_cycle_spec(scenes_dir / "multilevel_station.toml")
    up_spec = load_cycle_spec(_lifted_station(scenes_dir, tmp_path))
    flat, up = (
        simulate_cycle(s, run_generator(0, 0), keep_timeline=True, ergonomics=False)
        for s in (flat_spec, up_spec)
    )
    assert up.collisions == []
    assert len(up.walks) == len(flat.walks) > 0
    for a, b in zip(flat.walks, up.walks, strict=True):
        np.testing.assert_allclose(b.path.xy, a.path.xy, atol=1e-9)
    r = flat.timeline.jointmap.root
    assert up.timeline.qpos.shape == flat.timeline.qpos.shape
    dz = up.timeline.qpos[:, r + 2] - flat.timeline.qpos[:, r + 2]
    np.testing.assert_allclose(dz, 0.5, atol=1e-9)
