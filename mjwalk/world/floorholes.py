"""A floor with openings (a pit, a stair well going down): the floor written as boxes.

A MuJoCo plane is a half-space: it holds no hole, so a scene with a level below its floor (a pit
reached by a stair) cannot keep its floor plane at the floor's height. Such a scene drops the
plane to the bottom of its deepest pit and writes the floor level as boxes whose names start
with :data:`FLOOR_BOX_PREFIX` ("floor_0", "floor_1", ...), their tops at the floor's height and
nothing where the openings are. :func:`floor_boxes` finds them; the workplace's floor is then
at their tops (``Workplace.floor_z``) and its clearance field has a wall at every opening's edge
(:func:`wall_openings`), so the planners on the floor never walk into a pit: a walker gets down
only over a link of the level graph (:mod:`mjwalk.world.levels`), where the plane under the
openings is a level below the floor. A scene without such boxes is as before. Metres, world z
up.
"""

from __future__ import annotations

from dataclasses import dataclass

import mujoco
import numpy as np
from scipy import ndimage

from mjwalk.errors import SceneError
from mjwalk.world.clearance import ClearanceField
from mjwalk.world.footprint import Footprint, geom_footprint
from mjwalk.world.norms import CONTACT_GAP, LEVEL_TOLERANCE

#: Boxes whose names start with this are the floor level of a floor with openings.
FLOOR_BOX_PREFIX = "floor_"


@dataclass(frozen=True)
class FloorBoxes:
    """The boxes a floor with openings is written as.

    Attributes:
        height: their tops' height, world metres (the floor level's).
        geoms: their geom ids.
        footprints: their footprints, world xy.
    """

    height: float
    geoms: tuple[int, ...]
    footprints: tuple[Footprint, ...]


def floor_boxes(
    model: mujoco.MjModel, data: mujoco.MjData, plane: int, label: str
) -> FloorBoxes | None:
    """The boxes of a floor with openings (module docstring), or None for a plain floor.

    Args:
        model: the compiled scene.
        data: its data, kinematics done.
        plane: the floor plane's geom id (:func:`mjwalk.world.floor.find_floor`).
        label: the scene, for messages.

    Returns:
        The boxes, their common top height and footprints; None when no box is named
        :data:`FLOOR_BOX_PREFIX`... or when the floor is no plane.

    Raises:
        SceneError: such a geom that is not a level box, or tops at different heights, or at or
            below the plane.
    """
    if int(model.geom_type[plane]) != mujoco.mjtGeom.mjGEOM_PLANE:
        return None  # a slab floor (:mod:`mjwalk.world.slabfloor`): its top is the floor
    ids = [
        g
        for g in range(model.ngeom)
        if g != plane
        and (mujoco.mj_id2name(model, mujoco.mjtObj.mjOBJ_GEOM, g) or "").startswith(
            FLOOR_BOX_PREFIX
        )
    ]
    if not ids:
        return None
    tops, prints, names = [], [], []
    for g in ids:
        name = mujoco.mj_id2name(model, mujoco.mjtObj.mjOBJ_GEOM, g)
        names.append(name)
        rot = data.geom_xmat[g].reshape(3, 3)
        if int(model.geom_type[g]) != mujoco.mjtGeom.mjGEOM_BOX or abs(rot[2, 2]) < 1 - 1e-9:
            raise SceneError(f"{label}: floor geom {name!r} must be a box with a level top")
        top = float(data.geom_xpos[g][2] + model.geom_size[g][2])
        fp = geom_footprint(model, data, g, top - 2 * model.geom_size[g][2], top)
        if fp is None:
            raise SceneError(f"{label}: floor geom {name!r} has no footprint")
        tops.append(top)
        prints.append(fp)
    if max(tops) - min(tops) > LEVEL_TOLERANCE:
        low, high = (names[int(k)] for k in (np.argmin(tops), np.argmax(tops)))
        raise SceneError(
            f"{label}: the floor boxes' tops differ by {max(tops) - min(tops):.3f} m "
            f"(at most {LEVEL_TOLERANCE} m: one floor level): {high!r} at "
            f"{max(tops):.3f} m, {low!r} at {min(tops):.3f} m; geoms named "
            f"'{FLOOR_BOX_PREFIX}...' are the floor's boxes, rename any other"
        )
    height = float(np.mean(tops))
    if height <= float(data.geom_xpos[plane][2]) + LEVEL_TOLERANCE:
        raise SceneError(
            f"{label}: the floor boxes' tops ({height:.3f} m) must lie above the plane"
        )
    return FloorBoxes(height, tuple(ids), tuple(prints))


def wall_openings(field: ClearanceField, footprints: tuple[Footprint, ...]) -> ClearanceField:
    """A clearance field with a wall at the edge of the floor boxes (every opening's rim).

    Args:
        field: the clearance field of the floor's obstacles, metres.
        footprints: the floor boxes' footprints (:attr:`FloorBoxes.footprints`).

    Returns:
        The field, each node's value at most its distance to the nearest point off the boxes
        (the boxes joined across gaps up to :data:`mjwalk.world.norms.CONTACT_GAP`; negative off
        them), measured by a Euclidean distance transform (exact to half a node).
    """
    gx, gy = field.grid_xy()
    xy = np.stack(np.meshgrid(gx, gy), axis=-1)
    sd = np.full(xy.shape[:2], np.inf)
    for fp in footprints:
        sd = np.minimum(sd, fp.signed_distance(xy))
    inside = sd <= 0.5 * CONTACT_GAP
    if inside.all():
        return field
    res = field.resolution
    inner = ndimage.distance_transform_edt(inside) * res - 0.5 * res
    outer = ndimage.distance_transform_edt(~inside) * res - 0.5 * res
    edge = np.where(inside, inner, -outer)
    return ClearanceField(field.x0, field.y0, res, np.minimum(field.values, edge))


def opening_area(plane: Footprint, footprints: tuple[Footprint, ...]) -> float:
    """The area of a floor's openings: the plane's footprint less the floor boxes'.

    Args:
        plane: the floor plane's footprint (its size), world xy.
        footprints: the floor boxes' footprints (:attr:`FloorBoxes.footprints`; polygons, a
            floor box being a box with a level top).

    Returns:
        Square metres of the plane no floor box covers (the boxes' overlaps counted once): the
        area of the level below the floor a walker may stand on, the pits' openings.
    """
    import shapely  # deferred: shapely is slow to import; only floors with openings need it

    boxes = shapely.union_all([shapely.Polygon(fp.vertices) for fp in footprints])
    return float(shapely.Polygon(plane.vertices).difference(boxes).area)
