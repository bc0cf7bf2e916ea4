"""mjwalk: statistically varied human walking and reaching in MuJoCo assembly workplaces."""

import sys as _sys

if "mujoco" not in _sys.modules:  # pick a headless OpenGL backend before mujoco loads
    from mjwalk._gl import select_gl_backend as _select_gl_backend

    _select_gl_backend()

from mjwalk.cycle.simulate import check_collisions, simulate_cycle, simulate_cycles
from mjwalk.cycle.spec import load_cycle_spec
from mjwalk.errors import (
    CaptureError,
    CycleSpecError,
    MjwalkError,
    ModelFileError,
    PlanningError,
    SceneError,
)
from mjwalk.gait import Step
from mjwalk.gait.corpus import generate_corpus
from mjwalk.gait.default import default_model
from mjwalk.gait.features import StepBatch
from mjwalk.gait.model import StepModel
from mjwalk.gait.segment import segment_take, segment_takes
from mjwalk.mocap import Take, load_amc, load_bvh
from mjwalk.plan import PathStep, WalkPath
from mjwalk.plan.grid import plan_grid
from mjwalk.plan.hybrid import plan_walk, plan_walks
from mjwalk.world import Workplace, load_workplace
from mjwalk.world.probe import ClearanceProbe, path_clearance

__version__: str = __import__("mjwalk._version", fromlist=["__version__"]).__version__

__all__ = [
    "CaptureError",
    "ClearanceProbe",
    "CycleSpecError",
    "MjwalkError",
    "ModelFileError",
    "PathStep",
    "PlanningError",
    "SceneError",
    "Step",
    "StepBatch",
    "StepModel",
    "Take",
    "WalkPath",
    "Workplace",
    "check_collisions",
    "default_model",
    "generate_corpus",
    "load_amc",
    "load_bvh",
    "load_cycle_spec",
    "load_workplace",
    "path_clearance",
    "plan_grid",
    "plan_walk",
    "plan_walks",
    "segment_take",
    "segment_takes",
    "simulate_cycle",
    "simulate_cycles",
]
