"""Ramps beside a walk (issue 47): the ramps whose low end a walk passes over without crossing
them.

A level's obstacles start :data:`~mjwalk.world.workplace.WorkplaceOptions` ``z_range[0]``
(0.05 m) above it, so the first part of a ramp's run from its foot (0.52 m of a 5.5 deg ramp)
is open floor to the planners: a walk that cuts past a ramp's foot from the side, or along
it, sets its feet there. A person stands on the ramp's surface where a foot lands on it
(its side edge rises at most those 0.05 m there, about a third of the lowest riser of a
building stair, 0.14 m: DIN 18065:2020 Table 1 as :data:`mjwalk.world.norms.MIN_RISER` cites
it -- a low step up, not a face to keep clear of; keeping floor walks off it instead would
change every floor level's clearance field and walks, where standing on it changes only the
legs of the walks that pass there). The walk
records those ramps' planes (``meta["ramps_beside"]``, the same entries as a crossed ramp's
``plane`` in ``meta["levels"]["route"]``: :func:`ramp_plane`), and the legs stand each such
foot on the highest point of the plane under its sole and swing it over the plane
(:func:`mjwalk.body.legs.rampreach.level_feet_on_ramps`, ``swing_over_ramps``), as they do
for the level steps of a walk that crosses the ramp. Metres above the floor, radians.
"""

from __future__ import annotations

import math
from dataclasses import replace

import numpy as np

from mjwalk.plan.levelroute import Crossing, crossings
from mjwalk.plan.walkpath import WalkPath
from mjwalk.world.norms import LEVEL_TOLERANCE
from mjwalk.world.workplace import Workplace

#: How far from a ramp's plane (its run and width) a footprint's sole may reach, metres: more
#: than the longest foot the humanoid scales to (0.334 m at the largest walker stature, 2.2 m:
#: ``mjwalk.gait.walker.STATURE_RANGE``, ``mjwalk.anthropometry.leg_geometry``), so every sole
#: that can overhang the plane is looked at (the legs test its sole points themselves).
SOLE_REACH = 0.35

#: The key of a walk's ``meta`` under which the planes of the ramps beside it are kept.
META_KEY = "ramps_beside"


def ramp_plane(c: Crossing, floor_z: float) -> dict:
    """A ramp crossing's plane as walks record it.

    Args:
        c: a ramp crossing (:func:`mjwalk.plan.levelroute.crossings`).
        floor_z: the floor's world height, metres.

    Returns:
        ``slope`` (radians), ``uphill`` (heading up the ramp, radians), ``foot`` (world xy of
        the middle of its foot), ``run`` (horizontal length), ``half_width`` (0: unknown) and
        ``z`` (its foot's height above the floor), metres.
    """
    return {
        "slope": float(c.slope),
        "uphill": float(c.yaw),
        "foot": [float(v) for v in c.origin],
        "run": float(c.track[-1]),
        "half_width": float(c.half_width),
        "z": float(c.z_lower - floor_z),
    }


def _ramps(workplace: Workplace) -> list[Crossing]:
    """The scene's ramp crossings, kept on the workplace (none in a scene without ramps)."""
    cache = workplace.__dict__
    if "_side_ramps" not in cache:
        graph = workplace.levels
        has = any(k.kind == "ramp" for k in graph.links)
        cache["_side_ramps"] = [c for c in crossings(graph, 0.0) if c.kind == "ramp"] if has else []
    return cache["_side_ramps"]


def _near(c: Crossing, xy: np.ndarray) -> np.ndarray:
    """Whether points (k, 2) lie within :data:`SOLE_REACH` of a ramp's plane (its rectangle)."""
    rel = xy - np.asarray(c.origin, dtype=float)
    up = np.array([math.cos(c.yaw), math.sin(c.yaw)])
    along = rel @ up
    across = np.abs(rel @ np.array([-up[1], up[0]]))
    half = float(c.half_width) if c.half_width > 0.0 else math.inf
    run = float(c.track[-1])
    return (along >= -SOLE_REACH) & (along <= run + SOLE_REACH) & (across <= half + SOLE_REACH)


def ramps_beside(
    workplace: Workplace, walk: WalkPath, crossed: list[dict] | None = None
) -> list[dict]:
    """The planes of the ramps a walk's footprints stand beside on the ramp's lower level.

    Args:
        workplace: the scene.
        walk: the walk (its steps' footprints and ``foot_z``/``stance_z``, metres above the
            floor).
        crossed: the planes of the ramps the walk's route crosses (left out).

    Returns:
        the planes (:func:`ramp_plane`) of the ramps, other than ``crossed``, with a footprint
        standing at their foot's height within :data:`SOLE_REACH` of their plane; [] in a
        scene without ramps.
    """
    ramps = _ramps(workplace)
    if not ramps or not walk.steps:
        return []
    xy = np.array([s.foot[:2] for s in walk.steps] + [s.stance[:2] for s in walk.steps], float)
    z = np.array([s.foot_z for s in walk.steps] + [s.stance_z for s in walk.steps], float)
    out = []
    for c in ramps:
        plane = ramp_plane(c, workplace.floor_z)
        if crossed and plane in crossed:
            continue
        at_foot = np.abs(z - plane["z"]) <= LEVEL_TOLERANCE
        if np.any(at_foot & _near(c, xy)):
            out.append(plane)
    return out


def with_ramps_beside(workplace: Workplace, walk: WalkPath) -> WalkPath:
    """``walk`` with the ramps beside it in its ``meta`` (:data:`META_KEY`), when it has any.

    Args:
        workplace: the scene the walk was planned in.
        walk: the walk (a walk over levels: its route's crossed ramps are left out).

    Returns:
        ``walk`` itself when no ramp is beside it (or it already names them), else a copy whose
        ``meta`` names them.
    """
    if META_KEY in walk.meta:
        return walk
    route = (walk.meta.get("levels") or {}).get("route") or []
    crossed = [e["plane"] for e in route if e.get("kind") == "ramp" and "plane" in e]
    beside = ramps_beside(workplace, walk, crossed)
    if not beside:
        return walk
    return replace(walk, meta={**walk.meta, META_KEY: beside})
