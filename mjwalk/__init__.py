"""mjwalk: statistically varied human walking and reaching in MuJoCo assembly workplaces.

The whole pipeline is importable from here; modules load on first use (PEP 562), so
``import mjwalk`` is fast and changes nothing (no environment variable, no mujoco import).
Stages, lowest first: capture (:mod:`mjwalk.mocap`), step model (:mod:`mjwalk.gait`), scene and
clearance (:mod:`mjwalk.world`), walk planning (:mod:`mjwalk.plan`), humanoid and legs
(:mod:`mjwalk.body`), arms (:mod:`mjwalk.arms`), timeline and collisions
(:mod:`mjwalk.timeline`), ergonomic scores (:mod:`mjwalk.ergonomics`), cycles
(:mod:`mjwalk.cycle`), reports (:mod:`mjwalk.report`), video
(:mod:`mjwalk.render`); see ARCHITECTURE.md.
"""

from __future__ import annotations

import importlib
from typing import TYPE_CHECKING, Any

from mjwalk._version import __version__
from mjwalk.conventions import BODY_RADIUS, DEFAULT_STATURE, SAMPLE_RATE_HZ, Side
from mjwalk.errors import (
    CaptureError,
    CycleSpecError,
    InputError,
    MjwalkError,
    ModelFileError,
    PlanningError,
    SceneError,
)

#: Public name -> module that defines it, imported on first access.
_LAZY: dict[str, str] = {
    # capture
    "Take": "mjwalk.mocap",
    "load_amc": "mjwalk.mocap",
    "load_bvh": "mjwalk.mocap",
    # step model
    "Step": "mjwalk.gait.step",
    "StepBatch": "mjwalk.gait.features",
    "StepModel": "mjwalk.gait.model",
    "default_model": "mjwalk.gait.default",
    "generate_corpus": "mjwalk.gait.corpus",
    "segment_take": "mjwalk.gait.segment",
    "segment_takes": "mjwalk.gait.segment",
    "Walker": "mjwalk.gait.walker",
    "Pace": "mjwalk.gait.pace",
    "capture_pace": "mjwalk.gait.pace",
    # scene and clearance
    "ClearanceField": "mjwalk.world.clearance",
    "ClearanceProbe": "mjwalk.world.probe",
    "Workplace": "mjwalk.world.workplace",
    "WorkplaceOptions": "mjwalk.world.workplace",
    "load_workplace": "mjwalk.world.workplace",
    "path_clearance": "mjwalk.world.probe",
    # scans
    "ScanOptions": "mjwalk.scan.scanoptions",
    # walk planning
    "HybridPlanner": "mjwalk.plan.hybrid",
    "PlannerOptions": "mjwalk.plan.options",
    "WalkRequest": "mjwalk.plan.request",
    "PathStep": "mjwalk.plan.walkpath",
    "WalkPath": "mjwalk.plan.walkpath",
    "minimum_jerk_guide": "mjwalk.plan.guide",
    "plan_grid": "mjwalk.plan.grid",
    "level_grid_route": "mjwalk.plan.levelgrid",
    "plan_walk": "mjwalk.plan.walks",
    "plan_walks": "mjwalk.plan.walks",
    "planned_straight_walks": "mjwalk.plan.walktimes",
    # humanoid and legs
    "LegMotion": "mjwalk.body.legs",
    "attach_humanoid": "mjwalk.body.humanoid",
    "build_humanoid": "mjwalk.body.humanoid",
    "humanoid_model": "mjwalk.body.humanoid",
    "legs_from_walk": "mjwalk.body.legs",
    # arms
    "ArmMovements": "mjwalk.arms.armcapture",
    "ReachModel": "mjwalk.arms.reach",
    "arm_movements": "mjwalk.arms.armcapture",
    "default_reach_model": "mjwalk.arms.reachdefault",
    # timeline and collisions
    "Contact": "mjwalk.timeline.collisions",
    "Event": "mjwalk.timeline.timeline",
    "Timeline": "mjwalk.timeline.timeline",
    "check_collisions": "mjwalk.timeline.collisions",
    "collision_report": "mjwalk.timeline.collisions",
    "iter_frames": "mjwalk.timeline.timeline",
    "reach_in_scene": "mjwalk.timeline.reachscene",
    "timeline_from_walk": "mjwalk.timeline.frames",
    # ergonomics
    "BodyAngles": "mjwalk.ergonomics.angles",
    "RunErgonomics": "mjwalk.ergonomics.results",
    "angles_from_timeline": "mjwalk.ergonomics.angles",
    "assess_cycle": "mjwalk.ergonomics.assess",
    "write_angles_csv": "mjwalk.ergonomics.export",
    "write_bvh": "mjwalk.ergonomics.export",
    # cycles and reports
    "CycleResult": "mjwalk.cycle.types",
    "CycleSpec": "mjwalk.cycle.types",
    "Population": "mjwalk.cycle.population",
    "format_markdown": "mjwalk.report",
    "format_summary": "mjwalk.report",
    "load_cycle_spec": "mjwalk.cycle.spec",
    "report_dict": "mjwalk.report",
    "simulate_cycle": "mjwalk.cycle.simulate",
    "simulate_cycles": "mjwalk.cycle.simulate",
    "write_report": "mjwalk.report",
    # video and plots
    "render_frames": "mjwalk.render",
    "render_video": "mjwalk.render",
    "save_plan_png": "mjwalk.render.plot",
}

__all__ = [
    "BODY_RADIUS",
    "DEFAULT_STATURE",
    "SAMPLE_RATE_HZ",
    "ArmMovements",
    "BodyAngles",
    "CaptureError",
    "ClearanceField",
    "ClearanceProbe",
    "Contact",
    "CycleResult",
    "CycleSpec",
    "CycleSpecError",
    "Event",
    "HybridPlanner",
    "InputError",
    "LegMotion",
    "MjwalkError",
    "ModelFileError",
    "Pace",
    "PathStep",
    "PlannerOptions",
    "PlanningError",
    "Population",
    "ReachModel",
    "RunErgonomics",
    "ScanOptions",
    "SceneError",
    "Side",
    "Step",
    "StepBatch",
    "StepModel",
    "Take",
    "Timeline",
    "WalkPath",
    "WalkRequest",
    "Walker",
    "Workplace",
    "WorkplaceOptions",
    "__version__",
    "angles_from_timeline",
    "arm_movements",
    "assess_cycle",
    "attach_humanoid",
    "build_humanoid",
    "capture_pace",
    "check_collisions",
    "collision_report",
    "default_model",
    "default_reach_model",
    "format_markdown",
    "format_summary",
    "generate_corpus",
    "humanoid_model",
    "iter_frames",
    "legs_from_walk",
    "level_grid_route",
    "load_amc",
    "load_bvh",
    "load_cycle_spec",
    "load_workplace",
    "minimum_jerk_guide",
    "path_clearance",
    "plan_grid",
    "plan_walk",
    "plan_walks",
    "planned_straight_walks",
    "reach_in_scene",
    "render_frames",
    "render_video",
    "report_dict",
    "save_plan_png",
    "segment_take",
    "segment_takes",
    "simulate_cycle",
    "simulate_cycles",
    "timeline_from_walk",
    "write_angles_csv",
    "write_bvh",
    "write_report",
]


def __getattr__(name: str) -> Any:
    module = _LAZY.get(name)
    if module is None:
        raise AttributeError(f"module 'mjwalk' has no attribute {name!r}")
    value = getattr(importlib.import_module(module), name)
    globals()[name] = value  # later look-ups skip __getattr__
    return value


def __dir__() -> list[str]:
    return sorted(set(globals()) | set(__all__))


if TYPE_CHECKING:  # static checkers and IDEs see the lazy names
    from mjwalk.arms.armcapture import ArmMovements, arm_movements
    from mjwalk.arms.reach import ReachModel
    from mjwalk.arms.reachdefault import default_reach_model
    from mjwalk.body.humanoid import attach_humanoid, build_humanoid, humanoid_model
    from mjwalk.body.legs import LegMotion, legs_from_walk
    from mjwalk.cycle.simulate import simulate_cycle, simulate_cycles
    from mjwalk.cycle.spec import load_cycle_spec
    from mjwalk.cycle.types import CycleResult, CycleSpec
    from mjwalk.ergonomics.angles import BodyAngles, angles_from_timeline
    from mjwalk.ergonomics.assess import assess_cycle
    from mjwalk.ergonomics.export import write_angles_csv, write_bvh
    from mjwalk.ergonomics.results import RunErgonomics
    from mjwalk.gait.corpus import generate_corpus
    from mjwalk.gait.default import default_model
    from mjwalk.gait.features import StepBatch
    from mjwalk.gait.model import StepModel
    from mjwalk.gait.segment import segment_take, segment_takes
    from mjwalk.gait.step import Step
    from mjwalk.mocap import Take, load_amc, load_bvh
    from mjwalk.plan.grid import plan_grid
    from mjwalk.plan.guide import minimum_jerk_guide
    from mjwalk.plan.hybrid import HybridPlanner
    from mjwalk.plan.levelgrid import level_grid_route
    from mjwalk.plan.options import PlannerOptions
    from mjwalk.plan.request import WalkRequest
    from mjwalk.plan.walkpath import PathStep, WalkPath
    from mjwalk.plan.walks import plan_walk, plan_walks
    from mjwalk.render import render_frames, render_video
    from mjwalk.render.plot import save_plan_png
    from mjwalk.report import format_markdown, format_summary, report_dict, write_report
    from mjwalk.timeline.collisions import Contact, check_collisions, collision_report
    from mjwalk.timeline.frames import timeline_from_walk
    from mjwalk.timeline.reachscene import reach_in_scene
    from mjwalk.timeline.timeline import Event, Timeline, iter_frames
    from mjwalk.world.clearance import ClearanceField
    from mjwalk.world.probe import ClearanceProbe, path_clearance
    from mjwalk.world.workplace import Workplace, WorkplaceOptions, load_workplace
