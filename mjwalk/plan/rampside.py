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

from mjwalk.anthropometry import leg_geometry
from mjwalk.plan.levelroute import Crossing, crossings
from mjwalk.plan.walkpath import WalkPath
from mjwalk.world.norms import LEVEL_TOLERANCE
from mjwalk.world.workplace import Workplace

#: Sole points (along the foot, across it) tested against a ramp's plane, here and by the
#: legs (:mod:`mjwalk.body.legs.rampreach`, one grid for both), and the spacing of the points
#: along a swing's chord between two footprints of one foot, metres (a tenth of the shortest
#: foot, 0.18 m at 1.2 m stature).
SOLE_GRID = (9, 5)
CHORD_SPACING = 0.02

#: The key of a walk's ``meta`` under which the planes of the ramps beside it are kept.
META_KEY = "ramps_beside"

#: The key that marks a plane of :data:`META_KEY` as a low top lying on the floor, not a ramp
#: (:mod:`mjwalk.plan.lowtops`): flat, and no level beyond its edges.
LOW_KEY = "low_top"


def ramp_plane(c: Crossing, floor_z: float) -> dict:
    """A ramp crossing's plane as walks record it: the ramp's own, about the middle of its
    foot, wherever the walker crosses it (a crossing walked off its middle,
    :meth:`~mjwalk.plan.levelroute.Crossing.shifted`, has the same plane; before, its foot
    moved with the walker's line and its sides and width with it: generated hall 511's ramp,
    crossed 0.2 m left of its middle, was known 0.2 m past its left side and not over the
    0.2 m along its right one).

    Args:
        c: a ramp crossing (:func:`mjwalk.plan.levelroute.crossings`).
        floor_z: the floor's world height, metres.

    Returns:
        ``slope`` (radians), ``uphill`` (heading up the ramp, radians), ``foot`` (world xy of
        the middle of its foot), ``run`` (horizontal length), ``half_width`` (0: unknown) and
        ``z`` (its foot's height above the floor), metres; ``sides`` (right, left: the ramp
        surface's own extent across its axis, metres left of ``foot``,
        :attr:`~mjwalk.plan.levelroute.Crossing.sides`) when it is known.
    """
    plane = {
        "slope": float(c.slope),
        "uphill": float(c.yaw),
        "foot": [float(v) for v in c.middle],
        "run": float(c.track[-1]),
        "half_width": float(c.half_width),
        "z": float(c.z_lower - floor_z),
    }
    if c.sides[1] > c.sides[0]:
        plane["sides"] = [float(v) for v in c.sides]
    return plane


def surface_plane(plane: dict) -> dict:
    """A ramp's plane (:func:`ramp_plane`) over the ramp surface's whole width (its
    ``sides``), not only the part of its foot the lower level meets (``half_width`` about
    ``foot``, where the walker lines up to cross it): what a foot swinging past the ramp must
    clear. On generated hall 170 (``benchmarks/bench_unseen.py``) the floor's longest contact
    with a ramp's foot was 0.90 of its 1.08 m, and a floor walk along the foot swung its toes
    1.5 cm into the 0.18 m the swings did not know of.

    Args:
        plane: the ramp's plane.

    Returns:
        the plane with ``foot`` the middle of the surface's foot and ``half_width`` half its
        width; ``plane`` itself without ``sides``.
    """
    if "sides" not in plane:
        return plane
    lo, hi = plane["sides"]
    up = float(plane["uphill"])
    foot = np.asarray(plane["foot"], float) + 0.5 * (lo + hi) * np.array(
        [-math.sin(up), math.cos(up)]
    )
    return {**plane, "foot": [float(v) for v in foot], "half_width": 0.5 * (hi - lo)}


def _ramps(workplace: Workplace) -> list[Crossing]:
    """The scene's ramp crossings, kept on the workplace (none in a scene without ramps)."""
    cache = workplace.__dict__
    if "_side_ramps" not in cache:
        graph = workplace.levels
        has = any(k.kind == "ramp" for k in graph.links)
        cache["_side_ramps"] = [c for c in crossings(graph, 0.0) if c.kind == "ramp"] if has else []
    return cache["_side_ramps"]


def sole_points(walk: WalkPath, geom, at: float) -> np.ndarray:
    """The sole points of a walk's footprints standing at one height and of its swings
    between them (each foot's chord from the footprint it leaves to the one it lands on, at
    the landing's heading).

    Args:
        walk: the walk (its steps' footprints, ``foot_z``/``stance_z``).
        geom: the foot's lengths and width (:func:`~mjwalk.anthropometry.leg_geometry`).
        at: the footprints' height above the floor, metres (within ``LEVEL_TOLERANCE``).

    Returns:
        (k, 2) world xy, metres (:data:`SOLE_GRID` points per pose).
    """
    along = np.linspace(-geom.foot_back, geom.foot_front, SOLE_GRID[0])
    across = np.linspace(-0.5, 0.5, SOLE_GRID[1]) * geom.foot_width
    poses = []
    last: dict[str, np.ndarray] = {}
    for s in walk.steps:
        foot, stance = np.asarray(s.foot, float)[:3], np.asarray(s.stance, float)[:3]
        last.setdefault("left" if s.side == "right" else "right", stance)  # the first stance
        if abs(float(s.foot_z) - at) <= LEVEL_TOLERANCE:
            poses.append(foot)
            prev = last.get(s.side)
            if prev is not None:
                k = max(2, math.ceil(np.hypot(*(foot[:2] - prev[:2])) / CHORD_SPACING) + 1)
                u = np.linspace(0.0, 1.0, k)[:, None]
                chord = prev[:2] + u * (foot[:2] - prev[:2])
                poses += [np.array([x, y, foot[2]]) for x, y in chord]
        if abs(float(s.stance_z) - at) <= LEVEL_TOLERANCE:
            poses.append(stance)
        last[s.side] = foot
    if not poses:
        return np.zeros((0, 2))
    p = np.array(poses)
    f = np.stack([np.cos(p[:, 2]), np.sin(p[:, 2])], -1)
    left = np.stack([-f[:, 1], f[:, 0]], -1)
    pts = [p[:, :2] + d * f + w * left for d in along for w in across]
    return np.concatenate(pts)


def over_ramp(plane: dict, xy: np.ndarray, widen: float = 0.0) -> np.ndarray:
    """Which points lie over a ramp's plane: the planners' and the legs' one test.

    Args:
        plane: the ramp's plane (:func:`ramp_plane` or :func:`surface_plane`).
        xy: (..., 2) world points, metres.
        widen: metres added to each side of its width, when the width is known (a plane of
            ``half_width`` 0 has no sides).

    Returns:
        (...,) bool: within its run, foot and top included, and its (widened) width.
    """
    rel = np.asarray(xy, dtype=float) - np.asarray(plane["foot"], dtype=float)
    up = float(plane["uphill"])
    along = rel @ np.array([math.cos(up), math.sin(up)])
    across = np.abs(rel @ np.array([-math.sin(up), math.cos(up)]))
    half = float(plane.get("half_width", 0.0))
    sides = across <= half + widen if half > 0.0 else np.ones_like(along, dtype=bool)
    return (along >= 0.0) & (along <= float(plane["run"])) & sides


def head_heights(plane: dict, xy: np.ndarray) -> np.ndarray:
    """The height of the level a ramp's head meets (its foot's height plus its rise) under the
    points past its head and within its width: the ground a sole reaching over a ramp's crest
    stands on there (generated hall 514, ``benchmarks/bench_unseen.py``).

    Args:
        plane: the ramp's plane (:func:`ramp_plane` or :func:`surface_plane`).
        xy: (..., 2) world points, metres.

    Returns:
        (...,) the height above the floor, metres; -inf elsewhere (over the ramp, before its
        foot, beside it; everywhere for a low top's plane, :data:`LOW_KEY`).
    """
    rel = np.asarray(xy, dtype=float) - np.asarray(plane["foot"], dtype=float)
    up, run = float(plane["uphill"]), float(plane["run"])
    along = rel @ np.array([math.cos(up), math.sin(up)])
    across = np.abs(rel @ np.array([-math.sin(up), math.cos(up)]))
    half = float(plane.get("half_width", 0.0))
    past = (along > run) & ((across <= half) if half > 0.0 else True)
    if LOW_KEY in plane:  # a low top (its geom id may be 0): no level past its far edge
        past = np.zeros_like(along, dtype=bool)
    top = float(plane.get("z", 0.0)) + math.tan(float(plane["slope"])) * run
    return np.where(past, top, -np.inf)


def ramps_beside(
    workplace: Workplace, walk: WalkPath, stature: float, crossed: list[dict] | None = None
) -> list[dict]:
    """The planes of the ramps a walk's soles stand or swing over on the ramp's lower level.

    Args:
        workplace: the scene.
        walk: the walk (its steps' footprints and ``foot_z``/``stance_z``, metres above the
            floor).
        stature: the walker's stature, metres (the foot's size).
        crossed: the planes of the ramps the walk's route crosses (left out).

    Returns:
        the planes (:func:`ramp_plane`) of the ramps, other than ``crossed``, over which a
        sole point (:data:`SOLE_GRID`) of a footprint standing at their foot's height, or of
        a swing between two such footprints, lies (a ramp's sides widened by one grid spacing
        across the foot, as the legs' swing over a ramp takes them); [] in a scene without
        ramps.
    """
    ramps = _ramps(workplace)
    if not ramps or not walk.steps:
        return []
    geom = leg_geometry(stature)
    widen = geom.foot_width / (SOLE_GRID[1] - 1)
    out: list[dict] = []
    soles: dict[float, np.ndarray] = {}
    for c in ramps:
        plane = ramp_plane(c, workplace.floor_z)
        if crossed and plane in crossed:
            continue
        at = round(plane["z"], 6)
        if at not in soles:
            soles[at] = sole_points(walk, geom, plane["z"])
        if np.any(over_ramp(surface_plane(plane), soles[at], widen)):
            out.append(plane)
    return out


def with_ramps_beside(workplace: Workplace, walk: WalkPath, stature: float) -> WalkPath:
    """``walk`` with the ramps beside it in its ``meta`` (:data:`META_KEY`), when it has any.

    Args:
        workplace: the scene the walk was planned in.
        walk: the walk (a walk over levels: its route's crossed ramps are left out).
        stature: the walker's stature, metres.

    Returns:
        ``walk`` itself when no ramp is beside it (or it already names them), else a copy whose
        ``meta`` names them.
    """
    if META_KEY in walk.meta:
        return walk
    route = (walk.meta.get("levels") or {}).get("route") or []
    crossed = [e["plane"] for e in route if e.get("kind") == "ramp" and "plane" in e]
    beside = ramps_beside(workplace, walk, stature, crossed)
    if not beside:
        return walk
    return replace(walk, meta={**walk.meta, META_KEY: beside})
