"""The floor of a scene: which plane geom it is (or, in a scene without one, which slab:
:mod:`mjwalk.world.slabfloor`), its height and extent, and whether mjwalk can plan on it (its
clearance grid's size). Used by :func:`mjwalk.world.workplace.load_workplace` and, before any
work, by the scene importers (:mod:`mjwalk.world.meshimport`); the geoms flush with it (floor
tape, inlays: :func:`flush_geoms`) are floor to the contact check. Metres, z up."""

from __future__ import annotations

import math
import weakref
from collections.abc import Sequence

import mujoco
import numpy as np

from mjwalk.errors import SceneError
from mjwalk.world.footprint import geom_footprint
from mjwalk.world.norms import LEVEL_TOLERANCE
from mjwalk.world.slabfloor import MIN_FLOOR_AREA, Slab, find_floor_slabs, find_slab_floor, slab

#: Default height band (metres above the floor) in which a geom counts as an obstacle.
OBSTACLE_Z_RANGE = (0.05, 2.0)
#: Most nodes a floor's clearance grid may have: 1e8, a 200 x 200 m hall at the default 2 cm
#: (a large final-assembly hall). The clearance and walk fields are float64 grids of this many
#: nodes, 0.8 GB each; a plane of size "1e6 1e6" asked for 71 PiB.
MAX_FLOOR_NODES = 1e8
#: A plane is a floor when its normal's z is above this (its normal within 2.56 deg of +z):
#: the clearance field and the humanoid's legs assume a level floor.
FLOOR_MIN_NZ = 0.999


def find_floor(model: mujoco.MjModel, data: mujoco.MjData, label: str) -> int:
    """The floor geom of a model.

    A plane whose normal points up (:data:`FLOOR_MIN_NZ`), the one named like "floor" first,
    else the lowest; in a scene without one, the lowest large slab top (a box, mesh or height
    field: :func:`mjwalk.world.slabfloor.find_slab_floor`).

    Args:
        model: the compiled scene.
        data: its data, kinematics done.
        label: the scene, for messages.

    Returns:
        The floor's geom id.

    Raises:
        SceneError: no plane nor slab, or only tilted planes (naming the tilt), or slabs
            with no clear floor among them.
    """
    planes = [
        g
        for g in range(model.ngeom)
        if model.geom_type[g] == mujoco.mjtGeom.mjGEOM_PLANE
        and data.geom_xmat[g].reshape(3, 3)[2, 2] > FLOOR_MIN_NZ
    ]
    if not planes:
        tiles = slab_floor(model)  # kept per model; when none, the search again names why
        floor = tiles[0] if tiles else find_slab_floor(model, data, label)
        if floor is not None:
            return floor.geom
        tilted = [
            g for g in range(model.ngeom) if model.geom_type[g] == mujoco.mjtGeom.mjGEOM_PLANE
        ]
        if tilted:
            g = max(tilted, key=lambda g: data.geom_xmat[g].reshape(3, 3)[2, 2])
            nz = float(np.clip(data.geom_xmat[g].reshape(3, 3)[2, 2], -1.0, 1.0))
            name = mujoco.mj_id2name(model, mujoco.mjtObj.mjOBJ_GEOM, g) or f"geom{g}"
            raise SceneError(
                f"{label}: no level floor: plane {name!r} is tilted {np.degrees(np.arccos(nz)):.1f}"
                f" deg from horizontal (its normal must point up within "
                f"{np.degrees(np.arccos(FLOOR_MIN_NZ)):.1f} deg; mjwalk plans on level floors)"
            )
        raise SceneError(
            f"{label}: no floor: the scene needs an upward-facing plane geom (e.g. "
            '<geom name="floor" type="plane" size="4 3 0.1"/>) or a box or mesh slab of at '
            f"least {MIN_FLOOR_AREA:g} m^2 whose top is the floor"
        )
    named = [g for g in planes if "floor" in (mujoco.mj_id2name(model, 5, g) or "").lower()]
    return (named or sorted(planes, key=lambda g: data.geom_xpos[g][2]))[0]


def floor_top(model: mujoco.MjModel, data: mujoco.MjData, floor: int) -> float:
    """The height of a floor geom's walk face: a plane's own, a slab's top.

    Args:
        model: the compiled scene.
        data: its data, kinematics done.
        floor: the floor's geom id (:func:`find_floor`).

    Returns:
        World z of the floor, metres.
    """
    if int(model.geom_type[floor]) == mujoco.mjtGeom.mjGEOM_PLANE:
        return float(data.geom_xpos[floor][2])
    s = _floor_slab(model, data, floor)
    return float(data.geom_xpos[floor][2]) if s is None else s.top


def floor_rect(
    model: mujoco.MjModel, data: mujoco.MjData, floor: int
) -> tuple[float, float, float, float] | None:
    """The extent of a floor geom: a finite plane's rectangle (its size about its centre), a
    slab floor's top faces' bounding box (every slab of it, :func:`slab_floor`); None for an
    infinite plane.

    Args:
        model: the compiled scene.
        data: its data, kinematics done.
        floor: the floor's geom id (:func:`find_floor`).

    Returns:
        (xmin, ymin, xmax, ymax), world metres, or None.
    """
    if int(model.geom_type[floor]) != mujoco.mjtGeom.mjGEOM_PLANE:
        tiles = slab_floor(model)
        if not any(t.geom == floor for t in tiles):
            one = slab(model, data, floor)
            tiles = () if one is None else (one,)
        if tiles:
            b = np.array([t.bounds for t in tiles])
            return (
                float(b[:, 0].min()), float(b[:, 1].min()), float(b[:, 2].max()),
                float(b[:, 3].max()),
            )  # fmt: skip
    fx, fy = model.geom_size[floor][:2]
    if fx > 0 and fy > 0:
        cx, cy = data.geom_xpos[floor][:2]
        return (cx - fx, cy - fy, cx + fx, cy + fy)
    return None


def floor_planes(
    model: mujoco.MjModel, data: mujoco.MjData, floors: np.ndarray
) -> tuple[np.ndarray, np.ndarray] | None:
    """The planes floor geoms stand for: a plane's own, a slab's top (a humanoid over the slab
    reaches it only through its top).

    Args:
        model: the compiled scene.
        data: its data, kinematics done.
        floors: (P,) the floors' geom ids.

    Returns:
        (P, 3) their unit normals and (P, 3) a point of each, world metres; None when one of
        them is neither a plane nor a slab (:func:`mjwalk.world.slabfloor.slab`).
    """
    normals, origins = np.zeros((len(floors), 3)), np.zeros((len(floors), 3))
    for i, g in enumerate(np.asarray(floors, dtype=np.int64).tolist()):
        if int(model.geom_type[g]) == mujoco.mjtGeom.mjGEOM_PLANE:
            normals[i], origins[i] = data.geom_xmat[g].reshape(3, 3)[:, 2], data.geom_xpos[g]
            continue
        s = _floor_slab(model, data, g)
        if s is None:
            return None
        normals[i], origins[i] = (0.0, 0.0, 1.0), (*data.geom_xpos[g][:2], s.top)
    return normals, origins


#: The slab floor of each model (:func:`slab_floor`), kept while the model lives: the contact
#: check asks for it every report, the workplace three times at load.
_SLAB_FLOORS: weakref.WeakKeyDictionary = weakref.WeakKeyDictionary()


def slab_floor(model: mujoco.MjModel) -> tuple[Slab, ...]:
    """The slabs a model's floor is made of (:func:`~mjwalk.world.slabfloor.find_floor_slabs`:
    the lowest large slab top and the slabs side by side with it), found once per model; none
    in a model with a plane, or when no slab is clearly the floor. The humanoid's geoms, not
    fixed to the world, are never one, so a scene with and without it has the same.

    Args:
        model: the compiled scene (with or without the humanoid).

    Returns:
        The floor's slabs, the floor geom's first; empty without a slab floor.
    """
    hit = _SLAB_FLOORS.get(model)
    if hit is not None and hit[0] == model.ngeom:
        return hit[1]
    tiles: tuple[Slab, ...] = ()
    if not (model.geom_type == mujoco.mjtGeom.mjGEOM_PLANE).any():
        data = mujoco.MjData(model)
        mujoco.mj_kinematics(model, data)
        try:
            tiles = find_floor_slabs(model, data, "scene")
        except SceneError:  # no clear floor: loading the workplace says so
            tiles = ()
    _SLAB_FLOORS[model] = (model.ngeom, tiles)
    return tiles


def _floor_slab(model: mujoco.MjModel, data: mujoco.MjData, g: int) -> Slab | None:
    """Geom ``g``'s slab: the kept one when it is a slab of the floor (:func:`slab_floor`),
    else :func:`~mjwalk.world.slabfloor.slab`'s."""
    for t in slab_floor(model):
        if t.geom == g:
            return t
    return slab(model, data, g)


def slab_floor_mask(model: mujoco.MjModel) -> np.ndarray:
    """The slabs a model's floor is made of (:func:`slab_floor`, kept per model), as a mask;
    no geom in a model with a plane, or when no slab is clearly the floor.

    Args:
        model: the compiled scene (with or without the humanoid).

    Returns:
        (ngeom,) bool mask.
    """
    mask = np.zeros(model.ngeom, dtype=bool)
    mask[[t.geom for t in slab_floor(model)]] = True
    return mask


def check_floor_nodes(bounds, resolution: float, label: str, floor: str) -> None:
    """Refuse a floor whose clearance grid would be too large.

    Args:
        bounds: (xmin, ymin, xmax, ymax) of the floor, metres.
        resolution: the clearance grid spacing, metres.
        label: the scene, for messages.
        floor: the floor geom's name, for messages.

    Raises:
        SceneError: more than :data:`MAX_FLOOR_NODES` nodes, or an extent that is not finite.
    """
    w, d = float(bounds[2] - bounds[0]), float(bounds[3] - bounds[1])
    if not (math.isfinite(w) and math.isfinite(d)):
        raise SceneError(f"{label}: the floor {floor!r} has no finite extent")
    nodes = (w / resolution + 1) * (d / resolution + 1)
    if nodes > MAX_FLOOR_NODES:
        side = math.sqrt(MAX_FLOOR_NODES) * resolution
        raise SceneError(
            f"{label}: the floor {floor!r} spans {w:.6g} x {d:.6g} m; mjwalk plans on floors "
            f"of at most {MAX_FLOOR_NODES:.0e} clearance-grid nodes ({side:.0f} x {side:.0f} m "
            f"at {resolution:g} m): give the plane the size of the hall (MJCF size is half "
            "the side)"
        )


def check_floor_size(model: mujoco.MjModel, label: str, resolution: float = 0.02) -> None:
    """Refuse a model whose floor :func:`load_workplace` could not plan on.

    An infinite plane's floor is its obstacles' extent plus 2 m, as there. A scene without a
    floor passes (load_workplace names that itself).

    Args:
        model: the compiled scene.
        label: the scene, for messages.
        resolution: the clearance grid spacing, metres.

    Raises:
        SceneError: the floor is larger than :data:`MAX_FLOOR_NODES` allow.
    """
    data = mujoco.MjData(model)
    mujoco.mj_kinematics(model, data)
    try:
        floor = find_floor(model, data, label)
    except SceneError:
        return
    name = mujoco.mj_id2name(model, mujoco.mjtObj.mjOBJ_GEOM, floor) or f"geom{floor}"
    rect = floor_rect(model, data, floor)
    if rect is not None:
        check_floor_nodes(rect, resolution, label, name)
        return
    floor_z = float(data.geom_xpos[floor][2])
    z0, z1 = floor_z + OBSTACLE_Z_RANGE[0], floor_z + OBSTACLE_Z_RANGE[1]
    boxes = [
        fp.bounds()
        for g in range(model.ngeom)
        if int(model.geom_type[g]) != mujoco.mjtGeom.mjGEOM_PLANE
        and (fp := geom_footprint(model, data, g, z0, z1)) is not None
    ]
    if boxes:
        b = np.array(boxes)
        bounds = (b[:, 0].min() - 2, b[:, 1].min() - 2, b[:, 2].max() + 2, b[:, 3].max() + 2)
        check_floor_nodes(bounds, resolution, label, name)


def flush_geoms(
    model: mujoco.MjModel, data: mujoco.MjData, levels: Sequence[float] = ()
) -> np.ndarray:
    """The geoms flush with a floor: floor tape, markings, inlaid plates -- every static geom
    (welded to the world) whose whole height lies within ``norms.LEVEL_TOLERANCE`` (4 mm) of a
    level floor plane's (:data:`FLOOR_MIN_NZ`), of a slab floor's top (:func:`slab_floor_mask`)
    or of one of ``levels`` (a platform's, a mezzanine's, a tread's top: tape on a platform is
    the platform's floor as tape on the floor is the floor's). They are one level with that
    floor, as :func:`mjwalk.world.levels.level_graph` groups surfaces within that tolerance
    (ASR A1.5/1,2 §3.4: height differences up to 4 mm are no trip points), so a foot on them
    stands on it. Heights from MuJoCo's ``geom_aabb`` turned into the world (conservative for
    a turned geom); the floors themselves are not counted.

    Args:
        model: the compiled scene (with or without the humanoid).
        data: its data, kinematics done (any pose: the static geoms do not move).
        levels: world heights of further horizontal walk surfaces, metres
            (:func:`mjwalk.timeline.walktops.level_heights`; none: the floors alone).

    Returns:
        (ngeom,) bool mask (the caller's own copy).
    """
    plane, static, placed = _fixed_masks(model)
    # the mask depends on the levels, the model's boxes and where its static geoms and planes
    # lie, nothing else: kept per model by those (a cycle asks again with every contact check)
    key = (
        tuple(float(z) for z in levels),
        model.geom_aabb.tobytes(),
        data.geom_xpos[placed].tobytes(),
        data.geom_xmat[placed].tobytes(),
    )
    kept = _FLUSH.setdefault(model, {})
    if key not in kept:
        if len(kept) >= FLUSH_KEPT:
            kept.pop(next(iter(kept)))  # the oldest first
        kept[key] = _flush_mask(model, data, key[0], plane, static)
    return kept[key].copy()


#: :func:`flush_geoms`' masks kept per model (by levels and placement; the oldest dropped
#: first): a cycle's contact checks ask with one or two sets of levels.
FLUSH_KEPT = 8
_FLUSH: weakref.WeakKeyDictionary = weakref.WeakKeyDictionary()
#: :func:`_fixed_masks` per model (fixed once compiled).
_FIXED: weakref.WeakKeyDictionary = weakref.WeakKeyDictionary()


def _fixed_masks(model: mujoco.MjModel) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """(ngeom,) the planes, the static geoms (welded to the world) and the ids of either, of a
    compiled model, kept per model."""
    hit = _FIXED.get(model)
    if hit is None or len(hit[0]) != model.ngeom:
        plane = model.geom_type == mujoco.mjtGeom.mjGEOM_PLANE
        static = model.body_weldid[model.geom_bodyid] == 0
        hit = _FIXED[model] = (plane, static, np.flatnonzero(plane | static))
    return hit


def _flush_mask(
    model: mujoco.MjModel,
    data: mujoco.MjData,
    levels: tuple[float, ...],
    plane: np.ndarray,
    static: np.ndarray,
) -> np.ndarray:
    """:func:`flush_geoms` computed (``plane``, ``static``: :func:`_fixed_masks`)."""
    floors = data.geom_xpos[plane & (data.geom_xmat[:, 8] > FLOOR_MIN_NZ), 2].tolist()
    slabs = slab_floor_mask(model)
    floors += [t.top for t in slab_floor(model)]
    floors += list(levels)
    bottom, top = geom_z_extents(model, data)
    out = np.zeros(model.ngeom, dtype=bool)
    for z in floors:
        out |= (bottom >= z - LEVEL_TOLERANCE) & (top <= z + LEVEL_TOLERANCE)
    return out & static & ~plane & ~slabs


def geom_z_extents(model: mujoco.MjModel, data: mujoco.MjData) -> tuple[np.ndarray, np.ndarray]:
    """Every geom's lowest and highest world z: MuJoCo's ``geom_aabb`` (in the geom's frame)
    turned into the world (exact for a geom upright or turned about z, conservative otherwise).

    Args:
        model: the compiled scene.
        data: its data, kinematics done.

    Returns:
        (ngeom,) bottoms and (ngeom,) tops, world metres.
    """
    up = data.geom_xmat[:, 6:9]  # each geom's rotation's third row: its axes' world z parts
    centre = data.geom_xpos[:, 2] + np.einsum("gj,gj->g", up, model.geom_aabb[:, :3])
    half = np.einsum("gj,gj->g", np.abs(up), model.geom_aabb[:, 3:])
    return centre - half, centre + half
