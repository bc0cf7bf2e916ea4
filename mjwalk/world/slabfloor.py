"""A floor modelled as a slab: a box, mesh or height field whose flat top is the floor (issue 47).

Hand-written and CAD-exported MJCF often model the floor as a thin box
(``<geom type="box" size="10 10 0.05" pos="0 0 -0.05"/>``) or a mesh slab instead of a plane.
When a scene has no upward plane, :func:`find_slab_floor` chooses its floor among the tops of
such slabs by the rule the scan pipeline uses for a cloud's floor (:mod:`mjwalk.scan.level`,
after the seed paper's §3: the floor is "the large walkable region at the lowest level"): of the
slab tops at least :data:`MIN_FLOOR_AREA` and :data:`FLOOR_SHARE` of the largest, the lowest.
When that one is not also the largest (a large deck above a smaller low slab: which is the
floor?), the scene is ambiguous and refused in one line naming both. A slab top inside another
slab (a foundation block under the floor) is hidden and no candidate. The chosen slab's top
then stands for the plane: it is the floor's height and extent, never an obstacle nor a walk
surface of its own, and its shallow contacts with the humanoid are standing
(:func:`mjwalk.timeline.collisions.floor_geoms`). Metres, world z up.
"""

from __future__ import annotations

from dataclasses import dataclass

import mujoco
import numpy as np
from scipy.cluster.hierarchy import DisjointSet

from mjwalk.errors import SceneError
from mjwalk.world.footprint import polygon_area
from mjwalk.world.norms import CONTACT_GAP, FLOOR_SHARE, LEVEL_TOLERANCE, MIN_FLOOR_AREA

#: A mesh's top is its vertices within this of its highest one, metres (as
#: ``mjwalk.world.surfaces.MESH_TOP``); a height field is flat when its elevations span no more.
FLAT_TOP = 1e-3
#: Areas (m^2) equal to this many decimals are equal when the floor geom is chosen among a floor's
#: slabs (equal tiles placed at different offsets differ in their last bits).
AREA_DIGITS = 6
#: A box's axis is vertical (its top level) when its z component is within this of 1 (as the
#: floor boxes of :mod:`mjwalk.world.floorholes`).
UPRIGHT_EPS = 1e-9


@dataclass(frozen=True)
class Slab:
    """A geom whose top is a horizontal face, as a candidate floor.

    Attributes:
        geom: its geom id.
        name: its name (``"geom<id>"`` when unnamed).
        top: its top face's height, world metres.
        bottom: its lowest point's height, world metres.
        xy: (K, 2) its top face's corners, world metres, counter-clockwise.
    """

    geom: int
    name: str
    top: float
    bottom: float
    xy: np.ndarray

    @property
    def area(self) -> float:
        """The top face's area, square metres."""
        return polygon_area(self.xy)

    @property
    def bounds(self) -> tuple[float, float, float, float]:
        """(xmin, ymin, xmax, ymax) of the top face, world metres."""
        lo, hi = self.xy.min(axis=0), self.xy.max(axis=0)
        return float(lo[0]), float(lo[1]), float(hi[0]), float(hi[1])


def slab(model: mujoco.MjModel, data: mujoco.MjData, g: int) -> Slab | None:
    """Geom ``g`` as a slab: a box with a vertical axis, a mesh whose highest vertices (within
    :data:`FLAT_TOP`) span a face, or an upright height field whose elevations span at most
    :data:`FLAT_TOP`; None for any other geom.

    Args:
        model: the compiled scene.
        data: its data, kinematics done.
        g: the geom id.

    Returns:
        The slab (its top face), or None.
    """
    gtype = int(model.geom_type[g])
    pos, rot = data.geom_xpos[g], data.geom_xmat[g].reshape(3, 3)
    name = mujoco.mj_id2name(model, mujoco.mjtObj.mjOBJ_GEOM, g) or f"geom{g}"
    if gtype == mujoco.mjtGeom.mjGEOM_BOX:
        size = model.geom_size[g]
        k = int(np.argmax(np.abs(rot[2])))
        if abs(rot[2, k]) < 1 - UPRIGHT_EPS:
            return None
        a, b = [i for i in range(3) if i != k]
        ea, eb = rot[:2, a] * size[a], rot[:2, b] * size[b]
        c = pos[:2]
        xy = np.array([c - ea - eb, c + ea - eb, c + ea + eb, c - ea + eb])
        if ea[0] * eb[1] - ea[1] * eb[0] < 0:  # a mirrored frame: keep counter-clockwise
            xy = xy[::-1]
        half = float(np.abs(rot[2]) @ size)
        return Slab(g, name, float(pos[2] + half), float(pos[2] - half), xy)
    if gtype == mujoco.mjtGeom.mjGEOM_MESH:
        m = int(model.geom_dataid[g])
        v = model.mesh_vert[model.mesh_vertadr[m] : model.mesh_vertadr[m] + model.mesh_vertnum[m]]
        w = np.asarray(v, dtype=float) @ rot.T + pos
        top = w[w[:, 2] >= w[:, 2].max() - FLAT_TOP]
        from scipy.spatial import ConvexHull, QhullError  # deferred: ~1 s import, meshes only

        try:
            hull = ConvexHull(top[:, :2]) if len(top) >= 3 else None
        except QhullError:  # the highest vertices on a line: a ridge, no face
            hull = None
        if hull is None:
            return None
        return Slab(g, name, float(w[:, 2].max()), float(w[:, 2].min()), top[hull.vertices, :2])
    if gtype == mujoco.mjtGeom.mjGEOM_HFIELD and rot[2, 2] > 1 - UPRIGHT_EPS:
        h = int(model.geom_dataid[g])
        rx, ry, elev, base = (float(s) for s in model.hfield_size[h])
        n = int(model.hfield_nrow[h] * model.hfield_ncol[h])
        z = np.asarray(model.hfield_data[model.hfield_adr[h] : model.hfield_adr[h] + n]) * elev
        if float(np.ptp(z)) > FLAT_TOP:
            return None
        ex, ey = rot[:2, 0] * rx, rot[:2, 1] * ry
        c = pos[:2]
        xy = np.array([c - ex - ey, c + ex - ey, c + ex + ey, c - ex + ey])
        return Slab(g, name, float(pos[2] + z.max()), float(pos[2] - base), xy)
    return None


def _hidden(s: Slab, others: list[Slab]) -> bool:
    """Whether ``s``'s top lies inside another slab (its top within that one's height, its face
    within that one's extent): no one stands on it."""
    x0, y0, x1, y1 = s.bounds
    for o in others:
        if o.geom == s.geom or not (o.bottom < s.top < o.top - LEVEL_TOLERANCE):
            continue
        ox0, oy0, ox1, oy1 = o.bounds
        if ox0 <= x0 and oy0 <= y0 and x1 <= ox1 and y1 <= oy1:
            return True
    return False


def _joined(a: Slab, b: Slab) -> bool:
    """Whether two slabs are one surface: tops within ``norms.LEVEL_TOLERANCE`` and faces at
    most ``norms.CONTACT_GAP`` apart in xy (touching or overlapping)."""
    if abs(a.top - b.top) > LEVEL_TOLERANCE:
        return False
    ax0, ay0, ax1, ay1 = a.bounds
    bx0, by0, bx1, by1 = b.bounds
    g = CONTACT_GAP
    if ax0 > bx1 + g or bx0 > ax1 + g or ay0 > by1 + g or by0 > ay1 + g:
        return False
    import shapely  # deferred: shapely is slow to import; only slabs side by side need it

    return bool(shapely.Polygon(a.xy).distance(shapely.Polygon(b.xy)) <= g)


def slab_regions(slabs: list[Slab]) -> list[tuple[Slab, ...]]:
    """Slabs side by side as one surface each (a hall floor exported as several box tiles):
    joined where their tops lie within ``norms.LEVEL_TOLERANCE`` (ASR A1.5/1,2 §3.4: 4 mm is
    no trip point) and their faces touch, overlap or lie at most ``norms.CONTACT_GAP`` apart
    (ASR A1.5/1,2: a gap up to 20 mm is walked over): the rule by which
    :func:`mjwalk.world.levels.level_graph` joins touching surfaces into one level, and the
    scan pipeline reads the boxes it writes a level as (:mod:`mjwalk.scan.levelparts`) back as
    one.

    Args:
        slabs: the slabs.

    Returns:
        The regions (each a tuple of slabs, in the order given), in the order of their first
        slab.
    """
    joined = DisjointSet(range(len(slabs)))
    for i in range(len(slabs)):
        for j in range(i + 1, len(slabs)):
            if not joined.connected(i, j) and _joined(slabs[i], slabs[j]):
                joined.merge(i, j)
    groups: dict[int, list[Slab]] = {}
    for i, s in enumerate(slabs):
        groups.setdefault(joined[i], []).append(s)
    return [tuple(g) for g in groups.values()]


def region_area(region: tuple[Slab, ...]) -> float:
    """The area of slabs side by side, their overlaps counted once, square metres.

    Args:
        region: the slabs (:func:`slab_regions`).

    Returns:
        Square metres.
    """
    if len(region) == 1:
        return region[0].area
    import shapely  # deferred: shapely is slow to import; only slabs side by side need it

    return float(shapely.union_all([shapely.Polygon(s.xy) for s in region]).area)


def find_floor_slabs(model: mujoco.MjModel, data: mujoco.MjData, label: str) -> tuple[Slab, ...]:
    """The floor of a scene without a floor plane: the lowest large slab top (module docstring),
    with the slabs side by side with it at its height (:func:`slab_regions`: a floor of box
    tiles is one floor). The rule reads regions: their areas (overlaps once) against
    :data:`MIN_FLOOR_AREA` and :data:`FLOOR_SHARE`, the lowest large one the floor.

    Only geoms fixed to the world (``body_weldid`` 0) are candidates, so a humanoid's or a
    moving part's geoms never are.

    Args:
        model: the compiled scene.
        data: its data, kinematics done.
        label: the scene, for messages.

    Returns:
        The floor's slabs, the largest first (the floor geom: a "floor"-named one among equals,
        then the lowest id), the others by geom id (not those within another's face: tape on
        it); empty when no region is large enough.

    Raises:
        SceneError: the lowest large region is not the largest one (naming both).
    """
    static = model.body_weldid[model.geom_bodyid] == 0
    slabs = [s for g in np.flatnonzero(static).tolist() if (s := slab(model, data, g)) is not None]
    slabs = [s for s in slabs if s.area > 0.0]
    slabs = [s for s in slabs if not _hidden(s, slabs)]
    regions = [(r, region_area(r)) for r in slab_regions(slabs)]
    regions = [(r, a) for r, a in regions if a >= MIN_FLOOR_AREA]
    if not regions:
        return ()
    largest = max(a for _, a in regions)
    large = [(r, a) for r, a in regions if a >= FLOOR_SHARE * largest]
    top = {id(r): min(s.top for s in r) for r, _ in large}
    low = min(top.values())
    main = {id(r): max(r, key=lambda s: (round(s.area, AREA_DIGITS), *_rank(s))) for r, _ in large}
    level = [(r, a) for r, a in large if top[id(r)] <= low + LEVEL_TOLERANCE]
    floor, area = max(level, key=lambda ra: (ra[1], *_rank(main[id(ra[0])])))
    big, big_area = max(large, key=lambda ra: (ra[1], -main[id(ra[0])].geom))
    if big_area > area and top[id(big)] > low + LEVEL_TOLERANCE:
        f, b = main[id(floor)], main[id(big)]
        raise SceneError(
            f"{label}: no clear floor: {f.name!r} (top z = {f.top:.4g} m, "
            f"{area:.3g} m^2) is the lowest large slab, {b.name!r} (top z = "
            f"{b.top:.4g} m, {big_area:.3g} m^2) the largest; add a floor plane "
            '(<geom name="floor" type="plane" .../>) at the floor\'s height'
        )
    first = main[id(floor)]
    # a slab on the floor within its face (tape, an inlay) adds no floor: it stays a geom
    # flush with the floor (mjwalk.world.floor.flush_geoms), as on a plane
    rest = [s for s in floor if s is not first and not _within(s, floor)]
    return (first, *sorted(rest, key=lambda s: s.geom))


def _within(s: Slab, others: tuple[Slab, ...]) -> bool:
    """Whether ``s``'s face lies within another slab's (their bounding boxes)."""
    x0, y0, x1, y1 = s.bounds
    for o in others:
        ox0, oy0, ox1, oy1 = o.bounds
        if o is not s and ox0 <= x0 and oy0 <= y0 and x1 <= ox1 and y1 <= oy1:
            return True
    return False


def _rank(s: Slab) -> tuple[bool, int]:
    """A floor slab's precedence among slabs (or regions) of equal area: "floor" in its name,
    then the lower geom id."""
    return "floor" in s.name.lower(), -s.geom


def find_slab_floor(model: mujoco.MjModel, data: mujoco.MjData, label: str) -> Slab | None:
    """The floor geom's slab of a scene without a floor plane (:func:`find_floor_slabs`' first).

    Args:
        model: the compiled scene.
        data: its data, kinematics done.
        label: the scene, for messages.

    Returns:
        The floor's (largest) slab, or None when no slab top is large enough
        (:data:`MIN_FLOOR_AREA`).

    Raises:
        SceneError: the lowest large slab top is not the largest one (naming both).
    """
    tiles = find_floor_slabs(model, data, label)
    return tiles[0] if tiles else None
