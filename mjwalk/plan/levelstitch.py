"""The parts of a walk over levels -- level walks and crossings -- joined into one
:class:`~mjwalk.plan.walkpath.WalkPath`, and the walk record that splits it by level and kind.

Each part starts where the one before it ends (the crossings are laid out from the level walk's
last sample, the level walks start at the crossings' last), so the shared sample is kept once;
yaw continues unwrapped; a level walk gets its level's height under every sample and foot.
Metres above the floor, seconds, radians.
"""

from __future__ import annotations

import math
from collections.abc import Sequence

import numpy as np

from mjwalk.plan.levelroute import RouteLeg
from mjwalk.plan.rampside import ramp_plane
from mjwalk.plan.walkpath import PathStep, WalkPath
from mjwalk.world.norms import LEVEL_TOLERANCE
from mjwalk.world.workplace import Workplace

#: How each crossing kind is counted in the walk record (a winder's steps as stairs: DIN 18065
#: counts winders among stairs, "gewendelte Treppen").
KIND_NAMES = {"stair": "stairs", "ramp": "ramps", "step": "steps", "winder": "stairs"}


def _part_heights(
    workplace: Workplace, leg: RouteLeg, walk: WalkPath
) -> tuple[np.ndarray, list[PathStep]]:
    """The part's heights above the floor per sample and its steps with their feet's heights."""
    if walk.z is not None:
        return np.asarray(walk.z, dtype=float), walk.steps
    h = workplace.levels.levels[leg.level].height - workplace.floor_z
    steps = [
        PathStep(s.side, s.start, s.end, s.foot, s.stance, foot_z=h, stance_z=h) for s in walk.steps
    ]
    return np.full(len(walk.t), h), steps


def stitch(workplace: Workplace, parts: Sequence[tuple[RouteLeg, WalkPath]]) -> WalkPath:
    """Join the parts of a walk over levels into one walk.

    Args:
        workplace: the scene (the levels' heights).
        parts: (route leg, walk) pairs in order; each walk starts at t = 0 where the one before
            ends.

    Returns:
        The walk: samples, steps and heights of all parts in order; ``meta`` the first level
        walk's (its planner's counts) with ``seconds`` summed over the level walks and
        ``edges`` the crossings' riser edges in order (:meth:`~mjwalk.plan.levelroute.
        Crossing.riser_lines`).
    """
    ts: list[np.ndarray] = []
    xys: list[np.ndarray] = []
    yaws: list[np.ndarray] = []
    zs: list[np.ndarray] = []
    steps: list[PathStep] = []
    t_end, total, seconds = 0.0, 0, 0.0
    meta: dict = {}
    edges: list[dict] = []  # the crossings' riser edges (levelroute.Crossing.riser_lines)
    for k, (leg, walk) in enumerate(parts):
        z, part_steps = _part_heights(workplace, leg, walk)
        first = 0 if k == 0 else 1
        base = 0 if k == 0 else total - 1
        yaw = np.asarray(walk.yaw, dtype=float)
        if yaws:
            yaw = yaw + 2 * math.pi * round((yaws[-1][-1] - yaw[0]) / (2 * math.pi))
        ts.append(np.asarray(walk.t[first:], dtype=float) + t_end)
        xys.append(np.asarray(walk.xy, dtype=float)[first:])
        yaws.append(yaw[first:])
        zs.append(z[first:])
        for s in part_steps:
            steps.append(
                PathStep(
                    s.side, base + s.start, base + s.end, s.foot, s.stance,
                    foot_z=float(s.foot_z), stance_z=float(s.stance_z),
                )
            )  # fmt: skip
        t_end = float(ts[-1][-1]) if len(ts[-1]) else t_end
        total += len(walk.t) - first
        if "crossing" not in walk.meta:
            meta = meta or dict(walk.meta)
            seconds += float(walk.meta.get("seconds", 0.0))
        edges += walk.meta.get("edges", [])
    meta = {**meta, "planner": "level_hybrid_astar", "seconds": seconds, "edges": edges}
    return WalkPath(
        t=np.concatenate(ts),
        xy=np.concatenate(xys),
        yaw=np.concatenate(yaws),
        steps=steps,
        meta=meta,
        z=np.concatenate(zs),
    )


#: Most a foot's height may differ from a level's and still stand on it, metres: the levels' own
#: tolerance (:data:`mjwalk.world.norms.LEVEL_TOLERANCE`, 4 mm, ASR A1.5/1,2). A crossing's
#: footfalls on a level take its height exactly; a tread or a ramp footfall differs by a riser
#: (>= 0.14 m, DIN 18065) or a ramp step's rise.
SAME_HEIGHT = LEVEL_TOLERANCE


def _add(table: dict, key: str, seconds: float, length: float, steps: int) -> None:
    row = table.setdefault(key, {"seconds": 0.0, "length": 0.0, "steps": 0})
    row["seconds"] += seconds
    row["length"] += length
    row["steps"] += steps


def surface_levels(
    steps: Sequence[PathStep], heights: dict[int, float], leave: float
) -> list[int | None]:
    """The level each step is walked on, by the surfaces its swinging foot leaves and lands on
    and its other foot stands on: a step with all three on one level's height (within
    :data:`SAME_HEIGHT`) is level walking on it; a step onto or off a tread, up or down a
    riser or on a ramp is on none. A step's foot leaves where the step before it had its
    stance foot.

    Args:
        steps: the steps in order, their ``foot_z`` and ``stance_z`` set (metres above the
            floor).
        heights: {level index: height above the floor, metres} of the levels the steps may
            stand on.
        leave: the height the first step's foot leaves, metres above the floor.

    Returns:
        Per step, the index of the level it is walked on, or None (a step on a stair, step or
        ramp).
    """
    out: list[int | None] = []
    for s in steps:
        zs = (leave, float(s.foot_z), float(s.stance_z))
        on = [lv for lv, h in heights.items() if max(abs(z - h) for z in zs) <= SAME_HEIGHT]
        out.append(on[0] if on else None)
        leave = float(s.stance_z)  # the stance foot swings next
    return out


def step_kinds(workplace: Workplace, leg: RouteLeg, walk: WalkPath) -> list[int | None]:
    """:func:`surface_levels` of a crossing's walk: its line-up steps before a flight, its
    stance steps and its steps on past a flight are level walking; its steps onto, over and
    off the treads or risers, and on the ramp, count as the crossing's kind. The first step's
    foot leaves the level the crossing starts from (the walker stands there on both feet).

    Args:
        workplace: the scene (the floor's height).
        leg: the crossing's route leg.
        walk: the crossing's walk (:func:`mjwalk.plan.levelcross.cross_walk`; heights above
            the floor).

    Returns:
        Per step, the index of the level it is walked on, or None for a step counted as the
        crossing's kind.
    """
    c = leg.crossing
    assert c is not None
    heights = {
        c.lower: c.z_lower - workplace.floor_z,
        c.upper: c.z_upper - workplace.floor_z,
    }
    return surface_levels(walk.steps, heights, heights[leg.level])


def _add_crossing(workplace: Workplace, leg: RouteLeg, walk: WalkPath, tables) -> dict:
    """Add a crossing's walk to the per-level and per-kind tables step by step
    (:func:`step_kinds`); its level steps' seconds and count, and the walk's length (m: its
    sample distances summed as :attr:`~mjwalk.plan.walkpath.WalkPath.length` sums them, the
    same float)."""
    per_level, per_kind = tables
    c = leg.crossing
    assert c is not None
    gaps = np.linalg.norm(np.diff(walk.xy, axis=0), axis=1)  # as WalkPath.length
    seg = np.concatenate(([0.0], np.cumsum(gaps)))
    t = np.asarray(walk.t, dtype=float)
    level = {"seconds": 0.0, "steps": 0}
    for s, lv in zip(walk.steps, step_kinds(workplace, leg, walk), strict=True):
        row = (float(t[s.end] - t[s.start]), float(seg[s.end] - seg[s.start]), 1)
        if lv is None:
            _add(per_kind, KIND_NAMES[c.kind], *row)
            continue
        _add(per_kind, "level", *row)
        _add(per_level, f"L{workplace.levels.levels[lv].index}", *row)
        level["seconds"] += row[0]
        level["steps"] += 1
    level["length"] = float(gaps.sum())
    return level


def level_meta(
    workplace: Workplace, parts: Sequence[tuple[RouteLeg, WalkPath]], max_riser: float
) -> dict:
    """The walk record of a walk over levels.

    Args:
        workplace: the scene.
        parts: (route leg, walk) pairs in order.
        max_riser: the walker's step-up limit used, metres.

    Returns:
        ``route``: one entry per part (kind, level or levels, seconds, horizontal length in
        metres, steps; a crossing also its level steps' ``level_seconds`` and
        ``level_steps``; a ramp also its ``plane``: ``slope`` in radians, ``uphill`` heading
        in radians, ``foot`` the world xy of the middle of its foot, ``run`` its horizontal
        length, ``half_width`` its half width (0: unknown) and ``z`` its foot's height above
        the floor, metres); ``per_level``: seconds, length and steps walked on each level
        ("L0"...): the level walks and the crossings' level steps; ``per_kind``: the same by
        kind ("level", "stairs", "ramps", "steps"), each crossing step counted by the surfaces
        its foot leaves and lands on (:func:`step_kinds`); ``max_riser``.
    """
    route: list[dict] = []
    per_level: dict[str, dict] = {}
    per_kind: dict[str, dict] = {}
    graph = workplace.levels
    for leg, walk in parts:
        c = leg.crossing
        level = None if c is None else _add_crossing(workplace, leg, walk, (per_level, per_kind))
        length = walk.length if level is None else level["length"]  # each read once
        row = (walk.duration, length, len(walk.steps))
        entry: dict = {"seconds": row[0], "length": row[1], "steps": row[2]}
        if c is None:
            lv = graph.levels[leg.level]
            entry = {"kind": "level", "level": lv.index, "height": lv.height, **entry}
            _add(per_level, f"L{lv.index}", *row)
            _add(per_kind, "level", *row)
        else:
            assert level is not None
            entry = {
                "kind": c.kind,
                "direction": leg.direction,
                "from": leg.level,
                "to": c.upper if leg.level == c.lower else c.lower,
                "risers": len(c.risers),
                **entry,
                "level_seconds": level["seconds"],
                "level_steps": level["steps"],
            }
            if c.kind == "ramp":  # its plane, for the feet on it (legs.rampreach.plane_pitch)
                entry["plane"] = ramp_plane(c, workplace.floor_z)
        route.append(entry)
    return {
        "route": route,
        "per_level": per_level,
        "per_kind": per_kind,
        "max_riser": max_riser,
    }
