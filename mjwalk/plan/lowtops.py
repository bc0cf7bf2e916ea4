"""Low tops on a walk surface (issue 47): anti-fatigue mats, cable bridges, floor plates --
static geoms lying on the floor, a platform or a mezzanine whose top is neither flush with it
nor in the obstacle band above it.

A geom whose whole height lies within ``norms.LEVEL_TOLERANCE`` (4 mm; ASR A1.5/1,2 §3.4:
height differences up to 4 mm are no trip points) of the floor or of a level is that floor
(:func:`mjwalk.world.floor.flush_geoms`); one reaching into the obstacle band (from the
workplace's ``z_range[0]``, 0.05 m, :data:`mjwalk.world.floor.OBSTACLE_Z_RANGE`, above the
floor and above each level, :func:`mjwalk.world.levelview.level_view`) is an obstacle the
planners walk round. Between them (a 10-20 mm mat, a 30-50 mm cable bridge) lies a top the
planners walk over as floor, though a foot there cannot stand at the floor's height: it is
about the body's own least toe clearance in swing on level ground or above it (1-2 cm:
1.29 +- 0.45 cm, Winter 1992, Phys Ther 72:45-53; Begg et al. 2007, Gait Posture 25:191-198),
so neither the legs' flat stance nor their flat swing clears it, and the soles stood in it
(a 15 mm mat before a bench: 80-108 foot-mat contacts per walk onto or off it, 15 mm deep;
the same mat on a 0.34 m platform: 74-108 per walk across it).
A person stands on such a top as on a ramp's low end beside a floor walk
(:mod:`mjwalk.plan.rampside`): each low top becomes a flat plane in the walk's
``meta["ramps_beside"]`` (marked :data:`~mjwalk.plan.rampside.LOW_KEY`), so the legs stand a
footprint over it on its top (:func:`mjwalk.body.legs.rampreach.level_feet_on_ramps`: the whole
sole over it, flat on it; part of it, level on its top), lift the pelvis with the feet as on
levels, and swing the sole over it (``swing_over_ramps``, ``swings_clear_ramps``; the edge swing
where a foot's two grounds differ by more than :data:`~mjwalk.body.legs.edgeswing.LEVEL_STEP`).
A top lies on the surface a walk's footprints stand on: its geom's bottom within
``LEVEL_TOLERANCE`` of their height (the floor, a platform, a mezzanine, a tread) and its
outline under their soles; a geom lying at that height elsewhere (a tool on a shelf as high as
a mezzanine) is under no sole of theirs.
A geom's top is the top of its bounding box in its own frame when that frame's z axis is
vertical (a box's, a mesh's or a plate's top face, turned about z), else of its world bounding
box (conservative). Metres above the floor, radians; world frame.
"""

from __future__ import annotations

import math
from dataclasses import replace

import mujoco
import numpy as np

from mjwalk.anthropometry import leg_geometry
from mjwalk.conventions import BODY_RADIUS
from mjwalk.plan.rampside import LOW_KEY, META_KEY, SOLE_GRID, over_ramp, sole_points
from mjwalk.plan.walkpath import WalkPath
from mjwalk.world.floor import flush_geoms, geom_z_extents
from mjwalk.world.norms import LEVEL_TOLERANCE
from mjwalk.world.workplace import Workplace

#: The least |z| of a geom frame's z axis for its own bounding box's top to be taken as a
#: horizontal top: within 1 % of vertical, as walk surfaces are found
#: (:mod:`mjwalk.world.surfaces`).
VERTICAL_MIN = 0.9999


def low_tops(model: mujoco.MjModel, floor_z: float, band: float, level: float = 0.0) -> list[dict]:
    """The low tops lying on a walk surface: every static geom (welded to the world) that can
    collide, not flush with the floor, whose bottom lies within ``LEVEL_TOLERANCE`` of the
    surface's height and whose top is more than ``LEVEL_TOLERANCE`` above it and at most
    ``band``.

    Args:
        model: the compiled scene.
        floor_z: the floor's world height, metres.
        band: the obstacle band's bottom above the surface, metres (the workplace's
            ``z_range[0]``).
        level: the surface's height above the floor, metres (0: the floor; a platform's, a
            mezzanine's).

    Returns:
        each top as a flat plane in :func:`~mjwalk.plan.rampside.ramp_plane`'s form (``slope``
        0, ``uphill`` its frame's x heading, ``foot`` the middle of its -x edge, ``run`` its
        length, ``half_width`` half its width, ``z`` its height above the floor, metres) with
        ``low_top`` (its geom's id); [] when there are none.
    """
    return [p for b, p in thin_geoms(model, floor_z, band) if is_low(b, p["z"], level, band)]


def is_low(bottom: float, top: float, level: float, band: float) -> bool:
    """Whether a geom from ``bottom`` to ``top`` lies on a surface ``level`` high as a low top.

    Args:
        bottom: the geom's bottom above the floor, metres.
        top: its top above the floor, metres.
        level: the surface's height above the floor, metres.
        band: the obstacle band's bottom above the surface, metres.

    Returns:
        its bottom within ``LEVEL_TOLERANCE`` of the surface, its top above that and at most
        ``band`` above the surface.
    """
    return abs(bottom - level) <= LEVEL_TOLERANCE and LEVEL_TOLERANCE < top - level <= band


def thin_geoms(model: mujoco.MjModel, floor_z: float, band: float) -> list[tuple[float, dict]]:
    """Every geom that is a low top of some surface (:func:`low_tops`): static, able to
    collide, no plane, not flush with the floor, and at most ``band`` plus
    ``LEVEL_TOLERANCE`` high, with its bottom.

    Args:
        model: the compiled scene.
        floor_z: the floor's world height, metres.
        band: the obstacle band's bottom above a surface, metres.

    Returns:
        (its bottom above the floor, metres; its top's plane as :func:`low_tops` gives it) in
        geom order; [] when there are none.
    """
    data = mujoco.MjData(model)
    mujoco.mj_kinematics(model, data)
    bottom, top = (z - floor_z for z in geom_z_extents(model, data))
    static = model.body_weldid[model.geom_bodyid] == 0
    collides = (model.geom_contype != 0) | (model.geom_conaffinity != 0)
    plane = model.geom_type == mujoco.mjtGeom.mjGEOM_PLANE
    thin = (top - bottom > 0.0) & (top - bottom <= band + LEVEL_TOLERANCE)
    pick = thin & static & collides & ~plane & ~flush_geoms(model, data)
    return [(float(bottom[g]), _top_plane(model, data, g, float(top[g])))
            for g in np.flatnonzero(pick).tolist()]  # fmt: skip


def _top_plane(model: mujoco.MjModel, data: mujoco.MjData, g: int, z: float) -> dict:
    """Geom ``g``'s top as a flat plane (:func:`low_tops`), ``z`` metres above the floor."""
    mat = data.geom_xmat[g].reshape(3, 3)
    box = model.geom_aabb[g]
    lo, hi = box[:3] - box[3:], box[:3] + box[3:]
    if abs(mat[2, 2]) >= VERTICAL_MIN:
        corners = np.array([[x, y, 0.0] for x in (lo[0], hi[0]) for y in (lo[1], hi[1])])
    else:  # the world bounding box of its eight corners
        c8 = np.array([[x, y, z] for x in (lo[0], hi[0]) for y in (lo[1], hi[1])
                       for z in (lo[2], hi[2])])  # fmt: skip
        w = c8 @ mat.T
        corners = np.array([[x, y, 0.0] for x in (w[:, 0].min(), w[:, 0].max())
                            for y in (w[:, 1].min(), w[:, 1].max())])  # fmt: skip
        mat = np.eye(3)
    xy = corners @ mat.T[:, :2] + data.geom_xpos[g, :2]  # (-,-), (-,+), (+,-), (+,+)
    axis = xy[2] - xy[0]
    foot = 0.5 * (xy[0] + xy[1])
    return {
        "slope": 0.0,
        "uphill": math.atan2(float(axis[1]), float(axis[0])),
        "foot": [float(v) for v in foot],
        "run": float(np.hypot(*axis)),
        "half_width": 0.5 * float(np.hypot(*(xy[1] - xy[0]))),
        "z": z,
        LOW_KEY: int(g),
    }


def _scene_tops(workplace: Workplace) -> list[tuple[float, dict]]:
    """The scene's thin geoms (:func:`thin_geoms`), kept on the workplace."""
    cache = workplace.__dict__
    if "_low_tops" not in cache:
        cache["_low_tops"] = thin_geoms(workplace.model, workplace.floor_z, workplace.z_range[0])
    return cache["_low_tops"]


def tops_under(workplace: Workplace, walk: WalkPath, stature: float) -> list[dict]:
    """The low tops a walk's soles stand or swing over, on the surfaces its footprints stand on.

    Args:
        workplace: the scene.
        walk: the walk (its footprints at their surfaces' heights above the floor,
            ``foot_z``/``stance_z``: 0 on the floor).
        stature: the walker's stature, metres (the foot's size).

    Returns:
        the planes (:func:`low_tops`) of the tops lying at the height of some of the walk's
        footprints (heights in rising order, the floor's first) under a
        :data:`~mjwalk.plan.rampside.SOLE_GRID` point of one of those footprints or of a swing
        between two of them, each grown on every side by the grid's spacing along the foot
        (3.4 cm at 1.75 m), so a top's edge crossing a sole between two grid points still
        carries it (rng 3 of the mat station: a foot beside the 15 mm mat's edge 16.6 mm into
        its side); [] without low tops.
    """
    thin = _scene_tops(workplace)
    if not thin or not walk.steps:
        return []
    band = workplace.z_range[0]
    geom = leg_geometry(stature)
    pad = (geom.foot_back + geom.foot_front) / (SOLE_GRID[0] - 1)  # the grid's spacing along
    out: list[dict] = []
    for at in sorted({float(z) for s in walk.steps for z in (s.foot_z, s.stance_z)}):
        tops = [p for b, p in thin if is_low(b, p["z"], at, band)
                and all(q[LOW_KEY] != p[LOW_KEY] for q in out)]  # fmt: skip
        soles = sole_points(walk, geom, at) if tops else np.zeros((0, 2))
        for p in tops if len(soles) else []:
            grown = grow(p, pad)
            if np.any(over_ramp(grown, soles)):
                out.append(grown)
    return out


def stand_top(workplace: Workplace, xy, level: float) -> float:
    """The ground under an operator standing at a point of a surface: the highest low top
    lying on the surface whose outline, grown by the body's radius
    (:data:`~mjwalk.conventions.BODY_RADIUS`, within which the standing feet lie), holds the
    point (conservative: a foot beside the top's edge stands at most its height above the
    surface, in the air, never in it), else the surface itself.

    Args:
        workplace: the scene.
        xy: the operator's pelvis (x, y), world metres.
        level: the surface's height above the floor, metres.

    Returns:
        Metres above the floor: ``level`` itself without such a top.
    """
    thin = _scene_tops(workplace)
    if not thin:  # a scene without low tops (most): the surface itself (asked ~80 times a cycle)
        return level
    band = workplace.z_range[0]
    point = np.asarray(xy, dtype=float)[:2]
    out = level
    for b, p in thin:
        if (
            is_low(b, p["z"], level, band)
            and p["z"] > out
            and over_ramp(grow(p, BODY_RADIUS), point)
        ):
            out = p["z"]
    return out


def grow(plane: dict, pad: float) -> dict:
    """A low top's plane (:func:`low_tops`) grown by ``pad`` metres on every side.

    Args:
        plane: the plane.
        pad: metres.

    Returns:
        the plane, its ``foot`` moved ``pad`` back along its axis, its ``run`` and width
        ``2 * pad`` longer.
    """
    up = np.array([math.cos(plane["uphill"]), math.sin(plane["uphill"])])
    foot = [float(v) for v in np.asarray(plane["foot"]) - pad * up]
    return {**plane, "foot": foot, "run": plane["run"] + 2 * pad,
            "half_width": plane["half_width"] + pad}  # fmt: skip


def with_low_tops(workplace: Workplace, walk: WalkPath, stature: float) -> WalkPath:
    """``walk`` with the low tops under it added to its ``meta["ramps_beside"]``.

    Args:
        workplace: the scene the walk was planned in.
        walk: the walk.
        stature: the walker's stature, metres.

    Returns:
        ``walk`` itself when no low top lies under it (or they are named already), else a copy
        whose ``meta`` names them.
    """
    meta = walk.meta or {}
    have = meta.get(META_KEY, [])
    if any(LOW_KEY in p for p in have):
        return walk
    tops = tops_under(workplace, walk, stature)
    if not tops:
        return walk
    return replace(walk, meta={**meta, META_KEY: [*have, *tops]})
