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
from mjwalk.plan.walkpath import PathStep, WalkPath
from mjwalk.world.workplace import Workplace

#: How each crossing kind is counted in the walk record.
KIND_NAMES = {"stair": "stairs", "ramp": "ramps", "step": "steps"}


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
        walk's (its planner's counts) with ``seconds`` summed over the level walks.
    """
    ts: list[np.ndarray] = []
    xys: list[np.ndarray] = []
    yaws: list[np.ndarray] = []
    zs: list[np.ndarray] = []
    steps: list[PathStep] = []
    t_end, total, seconds = 0.0, 0, 0.0
    meta: dict = {}
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
    meta = {**meta, "planner": "level_hybrid_astar", "seconds": seconds}
    return WalkPath(
        t=np.concatenate(ts),
        xy=np.concatenate(xys),
        yaw=np.concatenate(yaws),
        steps=steps,
        meta=meta,
        z=np.concatenate(zs),
    )


def _add(table: dict, key: str, walk: WalkPath) -> None:
    row = table.setdefault(key, {"seconds": 0.0, "length": 0.0, "steps": 0})
    row["seconds"] += walk.duration
    row["length"] += walk.length
    row["steps"] += len(walk.steps)


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
        metres, steps); ``per_level``: level walks' seconds, length and steps by level ("L0"...);
        ``per_kind``: the same by kind ("level", "stairs", "ramps", "steps"); ``max_riser``.
    """
    route: list[dict] = []
    per_level: dict[str, dict] = {}
    per_kind: dict[str, dict] = {}
    graph = workplace.levels
    for leg, walk in parts:
        entry: dict = {
            "seconds": walk.duration,
            "length": walk.length,
            "steps": len(walk.steps),
        }
        c = leg.crossing
        if c is None:
            lv = graph.levels[leg.level]
            entry = {"kind": "level", "level": lv.index, "height": lv.height, **entry}
            _add(per_level, f"L{lv.index}", walk)
            _add(per_kind, "level", walk)
        else:
            entry = {
                "kind": c.kind,
                "direction": leg.direction,
                "from": leg.level,
                "to": c.upper if leg.level == c.lower else c.lower,
                "risers": len(c.risers),
                **entry,
            }
            _add(per_kind, KIND_NAMES[c.kind], walk)
        route.append(entry)
    return {
        "route": route,
        "per_level": per_level,
        "per_kind": per_kind,
        "max_riser": max_riser,
    }
