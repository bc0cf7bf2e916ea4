"""The walk surfaces of an MJCF scene: the floor and every geom top a person can reach and stand on.

A geom's top is a candidate walk surface when it is horizontal (within
``norms.HORIZONTAL_SLOPE``) or a ramp (no steeper than ``norms.MAX_RAMP_SLOPE``), at least a
tread deep and a person wide (``norms.MIN_TREAD`` by ``norms.STAND_WIDTH``), and when enough of it
has the clear headroom ``norms.CLEAR_HEADROOM`` above it to stand on (a surface hidden inside
another geom has none). Of the candidates, only those reachable from the floor count: across
edges that touch (within ``norms.CONTACT_GAP``) with a height difference no larger than a step
(``norms.MAX_RISER``), so a stair's treads and a ramp are reachable and a table, a shelf or the
roof of a car on a flat floor is not (it stays an obstacle). A ramp's end reaches a level across
any of its touching boxes, as in the level graph (:mod:`mjwalk.world.levelgroups`): a deck of
several boxes only a ramp reaches, no box meeting it a body wide, is reached.

Geom types: boxes exactly (level, yawed and tilted: a tilted box's top is a ramp); a vertical
cylinder's top disc (as an inscribed 32-gon); a mesh's top (the convex hull of its vertices
within 1 mm of its highest; where those are no face, as a wedge's ridge, the most upward face of
its convex hull through its highest vertex: a ramp); a finite upward plane other than the floor.
Spheres, capsules, ellipsoids, lying cylinders, height fields and SDFs give no surface. The geoms
over a surface (its :class:`~mjwalk.world.walksurface.Overhead`) are every geom but the humanoid's,
by their footprint in the band above the surface and their bounding box's underside.
"""

from __future__ import annotations

import math
import re
from dataclasses import dataclass, replace

import mujoco
import numpy as np

from mjwalk._args import check_patterns
from mjwalk.errors import InputError
from mjwalk.world.cache import use_disk
from mjwalk.world.contacts import MIN_CROSSING, reachable, surface_contacts
from mjwalk.world.floor import find_floor, floor_rect, floor_top, slab_floor
from mjwalk.world.floorholes import FloorBoxes, floor_boxes, opening_area
from mjwalk.world.footprint import Footprint, geom_footprint, polygon_area
from mjwalk.world.levelgroups import ramp_end_contacts
from mjwalk.world.norms import (
    CLEAR_HEADROOM,
    CONTACT_GAP,
    HEADROOM_SCAN,
    HORIZONTAL_SLOPE,
    LEVEL_TOLERANCE,
    MAX_RAMP_SLOPE,
    MAX_RISER,
    MAX_TREAD,
    MIN_TREAD,
    ROUNDING_SLACK,
    SLOPE_ROUNDING_SLACK,
    STAND_WIDTH,
)
from mjwalk.world.walksurface import HeadroomMap, Overhead, WalkSurface, head_fits

__all__ = [
    "HeadroomMap",
    "Overhead",
    "SurfaceOptions",
    "WalkSurface",
    "find_walk_surfaces",
    "head_fits",
]

#: Bodies whose names start with one of these are a humanoid, never surfaces nor overheads (the
#: same prefixes as ``mjwalk.world.workplace.HUMANOID_PREFIXES``).
HUMANOID_PREFIXES = ("human",)
#: A mesh's top is its vertices within this of its highest one, metres.
MESH_TOP = 1e-3
#: Most sides of the polygon round a cylinder's top disc (fewer on a small disc:
#: :func:`disc_sides`).
DISC_SIDES = 32
#: Floor margin around the other geoms when the floor plane is infinite, metres (as
#: ``mjwalk.world.workplace.workplace_from_model`` does).
INFINITE_FLOOR_MARGIN = 2.0


@dataclass(frozen=True)
class SurfaceOptions:
    """Which geom tops are walk surfaces. Checked on construction (InputError, one line).

    Attributes:
        groups: only geoms in these MuJoCo geom groups can be surfaces (None: all groups).
        include, exclude: regular expressions on geom names selecting/rejecting surfaces
            (``re.search``; None: no filter). The floor is always one.
        humanoid_prefixes: bodies (and their children) named with one of these are a humanoid.
        horizontal_slope: largest slope (rise over run) of a horizontal surface
            (``norms.HORIZONTAL_SLOPE``, 1 %).
        max_ramp_slope: steepest ramp, radians (``norms.MAX_RAMP_SLOPE``, 10 deg).
        min_depth: least depth of a surface, metres (``norms.MIN_TREAD``, 0.26 m).
        min_width: least width of a surface, metres (``norms.STAND_WIDTH``, 0.6 m).
        min_headroom: clear height a surface needs over at least ``min_depth * min_width`` of
            its area, metres (``norms.CLEAR_HEADROOM``, 2.0 m).
        max_riser: highest step between touching surfaces for one to reach the other, metres
            (``norms.MAX_RISER``, 0.19 m).
        contact_gap: widest gap between touching edges, metres (``norms.CONTACT_GAP``).
        level_tol: touching surfaces this close in height are one level when a ramp's end is
            matched to a level for reachability, metres (``norms.LEVEL_TOLERANCE``, 4 mm; as
            :attr:`mjwalk.world.levels.LevelOptions.level_tol`, give both the same value).
        cache: the workplace cache policy for the overhead geoms' 3-D hulls
            (:attr:`mjwalk.world.workplace.WorkplaceOptions.cache`; False: none read or kept on
            disk). The surfaces are the same either way.
    """

    groups: frozenset[int] | None = None
    include: str | None = None
    exclude: str | None = None
    humanoid_prefixes: tuple[str, ...] = HUMANOID_PREFIXES
    horizontal_slope: float = HORIZONTAL_SLOPE
    max_ramp_slope: float = MAX_RAMP_SLOPE
    min_depth: float = MIN_TREAD
    min_width: float = STAND_WIDTH
    min_headroom: float = CLEAR_HEADROOM
    max_riser: float = MAX_RISER
    contact_gap: float = CONTACT_GAP
    level_tol: float = LEVEL_TOLERANCE
    cache: bool | None = None

    def __post_init__(self) -> None:
        if self.groups is not None:
            object.__setattr__(self, "groups", frozenset(int(g) for g in self.groups))
        if not 0 < self.max_ramp_slope < math.pi / 2:
            raise InputError(f"max_ramp_slope {self.max_ramp_slope} rad must be in (0, pi/2)")
        if not 0 <= self.horizontal_slope < math.tan(self.max_ramp_slope):
            raise InputError(
                f"horizontal_slope {self.horizontal_slope} must be in [0, tan(max_ramp_slope))"
            )
        names = ("min_depth", "min_width", "min_headroom", "max_riser", "contact_gap", "level_tol")
        for name in names:
            v = getattr(self, name)
            if not (math.isfinite(v) and v > 0):
                raise InputError(f"surface option {name}={v} m must be a positive number")
        if self.max_riser <= self.level_tol:
            raise InputError(f"max_riser {self.max_riser} m must exceed level_tol {self.level_tol}")
        if self.min_depth > self.min_width:
            raise InputError(f"min_depth {self.min_depth} m must not exceed min_width")
        if self.min_headroom > HEADROOM_SCAN:
            raise InputError(f"min_headroom {self.min_headroom} m must be <= {HEADROOM_SCAN}")
        check_patterns(include=self.include, exclude=self.exclude)


def _geom_name(model: mujoco.MjModel, g: int) -> str:
    return mujoco.mj_id2name(model, mujoco.mjtObj.mjOBJ_GEOM, g) or f"geom{g}"


def _is_humanoid(model: mujoco.MjModel, g: int, prefixes: tuple[str, ...]) -> bool:
    body = int(model.geom_bodyid[g])
    while body > 0:
        if (mujoco.mj_id2name(model, mujoco.mjtObj.mjOBJ_BODY, body) or "").startswith(prefixes):
            return True
        body = int(model.body_parentid[body])
    return False


def _ccw(xy: np.ndarray) -> np.ndarray:
    """The convex polygon through points (K, 2), counter-clockwise (hull of the points)."""
    c = xy.mean(axis=0)
    order = np.argsort(np.arctan2(xy[:, 1] - c[1], xy[:, 0] - c[0]))
    return xy[order]


def _upright_cylinder(model: mujoco.MjModel, data: mujoco.MjData, g: int) -> bool:
    """Whether geom ``g`` is a cylinder standing upright (its top a horizontal disc)."""
    upright = abs(data.geom_xmat[g][8]) > 1 - 1e-9
    return int(model.geom_type[g]) == mujoco.mjtGeom.mjGEOM_CYLINDER and upright


def _top_face(model: mujoco.MjModel, data: mujoco.MjData, g: int) -> np.ndarray | None:
    """World corners (K, 3) of geom ``g``'s top face (a convex polygon), or None."""
    gtype = int(model.geom_type[g])
    pos, rot, size = data.geom_xpos[g], data.geom_xmat[g].reshape(3, 3), model.geom_size[g]
    if gtype == mujoco.mjtGeom.mjGEOM_BOX:
        k = int(np.argmax(np.abs(rot[2])))  # the box axis closest to vertical
        sgn = 1.0 if rot[2, k] > 0 else -1.0
        a, b = [i for i in range(3) if i != k]
        corners = [
            pos + sgn * size[k] * rot[:, k] + sa * size[a] * rot[:, a] + sb * size[b] * rot[:, b]
            for sa, sb in ((-1, -1), (1, -1), (1, 1), (-1, 1))
        ]
        return np.array(corners)
    if _upright_cylinder(model, data, g):
        n = disc_sides(float(size[0]))
        ang = np.linspace(0, 2 * np.pi, n, endpoint=False)
        r = size[0] / math.cos(math.pi / n)  # the sides touch the rim
        rim = np.column_stack([r * np.cos(ang), r * np.sin(ang)])
        top = pos[2] + size[1]
        return np.column_stack([pos[0] + rim[:, 0], pos[1] + rim[:, 1], np.full(n, top)])
    if gtype == mujoco.mjtGeom.mjGEOM_PLANE and rot[2, 2] > 1 - 1e-9 and size[0] > 0:
        ex, ey = rot[:, 0] * size[0], rot[:, 1] * size[1]
        return np.array([pos - ex - ey, pos + ex - ey, pos + ex + ey, pos - ex + ey])
    if gtype == mujoco.mjtGeom.mjGEOM_MESH:
        m = model.geom_dataid[g]
        v = model.mesh_vert[model.mesh_vertadr[m] : model.mesh_vertadr[m] + model.mesh_vertnum[m]]
        w = np.asarray(v, dtype=float) @ rot.T + pos
        top = w[w[:, 2] >= w[:, 2].max() - MESH_TOP]
        from scipy.spatial import ConvexHull, QhullError  # deferred: ~1 s import, meshes only

        try:
            hull = ConvexHull(top[:, :2]) if len(top) >= 3 else None
        except QhullError:  # the highest vertices on a line: a wedge's ridge
            hull = None
        if hull is None:
            return _sloped_top(w)
        return np.column_stack([top[hull.vertices, :2], np.full(len(hull.vertices), w[:, 2].max())])
    return None


def disc_sides(radius: float) -> int:
    """Sides of the polygon round a disc of ``radius`` (m), its sides touching the rim, as a
    walk surface's footprint: :data:`DISC_SIDES`, or fewer where the sides would be shorter
    than a crossing (``contacts.MIN_CROSSING``, a body wide): a round dais is stepped onto
    across a side, and a contact is sought along each side alone, so 32 sides of a 1.5 m dais
    gave it no way up. The sides touch the rim so that a foot kept off one is off the disc
    (inscribed sides cut up to 3.6 cm off a 0.9 m dais, and the toes before them caught its
    rim); the corners reach past it (3.8 cm at 0.9 m), far from any stance.

    Args:
        radius: the disc's radius, metres.

    Returns:
        The number of sides, 3 to :data:`DISC_SIDES`.
    """
    half = MIN_CROSSING / (2.0 * radius)
    return int(min(DISC_SIDES, max(3, math.floor(math.pi / math.atan(half) + ROUNDING_SLACK))))


def _sloped_top(w: np.ndarray) -> np.ndarray | None:
    """World corners (K, 3) of a mesh's top where its highest vertices are no face: the most
    upward face of its convex hull (as MuJoCo collides it) through its highest vertex, e.g. a
    wedge's ramp; None for a degenerate mesh. The slope limit is the caller's."""
    from scipy.spatial import ConvexHull, QhullError  # deferred: ~1 s import, meshes only

    try:
        eq = ConvexHull(w).equations  # (F, 4): outward unit normal, offset
    except QhullError:  # a flat or degenerate mesh
        return None
    through = np.abs(eq[:, :3] @ w[np.argmax(w[:, 2])] + eq[:, 3]) <= MESH_TOP
    if not np.any(through & (eq[:, 2] > 0.0)):
        return None
    plane = eq[np.flatnonzero(through)[np.argmax(eq[through, 2])]]
    face = w[np.abs(w @ plane[:3] + plane[3]) <= MESH_TOP]
    try:
        return face[ConvexHull(face[:, :2]).vertices]
    except QhullError:
        return None


def _clip_above(corners: np.ndarray, z0: float) -> np.ndarray:
    """A planar polygon (K, 3)'s part at or above height ``z0`` (a ramp dug into the floor)."""
    if corners[:, 2].min() >= z0:
        return corners
    out = []
    for i in range(len(corners)):
        p, q = corners[i], corners[(i + 1) % len(corners)]
        if p[2] >= z0:
            out.append(p)
        if (p[2] - z0) * (q[2] - z0) < 0:
            out.append(p + (z0 - p[2]) / (q[2] - p[2]) * (q - p))
    return np.array(out)


def _calipers(v: np.ndarray) -> tuple[float, float]:
    """(least width, extent across it) of a convex polygon (K, 2), metres."""
    best = (math.inf, 0.0)
    for i in range(len(v)):
        e = v[(i + 1) % len(v)] - v[i]
        n = float(np.linalg.norm(e))
        if n < 1e-12:
            continue
        e = e / n
        across = (v - v[i]) @ np.array([-e[1], e[0]])
        along = (v - v[i]) @ e
        w = float(across.max() - across.min())
        if w < best[0]:
            best = (w, float(along.max() - along.min()))
    return best


class _Geoms:
    """The scene's geoms for the overhead search: world bounding boxes and whole footprints."""

    def __init__(self, model: mujoco.MjModel, data: mujoco.MjData, disk: bool) -> None:
        self.model, self.data, self.disk = model, data, disk
        c, h = model.geom_aabb[:, :3], model.geom_aabb[:, 3:]
        signs = np.array(np.meshgrid([-1, 1], [-1, 1], [-1, 1])).reshape(3, -1).T  # (8, 3)
        rot = data.geom_xmat.reshape(-1, 3, 3)
        local = c[:, None, :] + signs[None] * h[:, None, :]  # (G, 8, 3)
        world = np.einsum("gij,gkj->gki", rot, local) + data.geom_xpos[:, None, :]
        self.lo, self.hi = world.min(axis=1), world.max(axis=1)  # (G, 3) each
        self.whole: dict[int, Footprint | None] = {}

    def footprint(self, g: int, z0: float, z1: float) -> Footprint | None:
        """Geom ``g``'s footprint between heights z0 and z1; its whole footprint (computed once)
        when it reaches no more than 1 cm below z0 and not above z1 (a geom standing on the
        surface: the same, without cutting a curved hull)."""
        if self.lo[g, 2] >= z0 - 0.01 and self.hi[g, 2] <= z1:
            if g not in self.whole:
                lo = self.lo[g, 2]
                self.whole[g] = geom_footprint(self.model, self.data, g, lo, z1, self.disk)
            return self.whole[g]
        return geom_footprint(self.model, self.data, g, z0, z1, self.disk)

    def ceiling_plane(self, g: int) -> Overhead:
        """A plane facing down as an overhead over its rectangle (an infinite one: everywhere)."""
        name = _geom_name(self.model, g)
        z = float(self.data.geom_xpos[g][2])
        sx, sy = self.model.geom_size[g][:2]
        half = (sx, sy) if sx > 0 else (1e6, 1e6)
        box = np.array([[-1, -1], [1, -1], [1, 1], [-1, 1]]) * half + self.data.geom_xpos[g][:2]
        return Overhead(name, Footprint(name, g, box), z, z)


def _overheads(geoms: _Geoms, skip: set[int], z_low: float, z_high: float, bounds) -> tuple:
    """The geoms (not in ``skip``) over a surface from ``z_low`` to ``z_high`` within ``bounds``."""
    out = []
    model, data = geoms.model, geoms.data
    x0, y0, x1, y1 = bounds
    z0, z1 = z_low + 1e-3, z_high + HEADROOM_SCAN
    for g in range(model.ngeom):
        if g in skip:
            continue
        if int(model.geom_type[g]) == mujoco.mjtGeom.mjGEOM_PLANE:
            if data.geom_xmat[g][8] < -1 + 1e-9 and z_low < data.geom_xpos[g][2] <= z1:
                out.append(geoms.ceiling_plane(g))
            continue
        lo, hi = geoms.lo[g], geoms.hi[g]
        if hi[2] < z0 or lo[2] > z1 or lo[0] >= x1 or hi[0] <= x0 or lo[1] >= y1 or hi[1] <= y0:
            continue
        fp = geoms.footprint(g, z0, z1)
        if fp is None:
            continue
        b = fp.bounds()
        if b[0] >= x1 or b[2] <= x0 or b[1] >= y1 or b[3] <= y0:
            continue
        out.append(Overhead(fp.name, fp, float(lo[2]), float(hi[2])))
    return tuple(out)


def _surface_from_face(
    model, g: int, corners: np.ndarray, options: SurfaceOptions
) -> WalkSurface | None:
    """A candidate surface from a top face's world corners, or None (too steep or too small)."""
    n = np.cross(corners[1] - corners[0], corners[2] - corners[0])
    n = n / np.linalg.norm(n) * (1.0 if n[2] >= 0 else -1.0)
    slope = float(math.acos(min(1.0, float(n[2]))))
    if slope > options.max_ramp_slope + SLOPE_ROUNDING_SLACK:  # a ramp at the limit is one
        return None
    horizontal = math.tan(slope) <= options.horizontal_slope
    xy = _ccw(corners[:, :2])
    depth, width = _calipers(xy)
    # a box exactly MIN_TREAD deep is a tread: the corners' rounding is no shortfall
    if depth < options.min_depth - ROUNDING_SLACK or width < options.min_width - ROUNDING_SLACK:
        return None
    zc = float(corners[:, 2].mean())  # the plane's height over the vertices' mean
    centre = corners[:, :2].mean(axis=0)
    # a box exactly MAX_TREAD deep is a tread too (yawed, its depth came out 0.37 m + 3e-16 and
    # a two-riser step's tread was a platform with no room to stand on between the steps, so
    # the platform above was out of reach: generated hall 710, ``benchmarks/bench_unseen.py``)
    tread = depth <= MAX_TREAD + ROUNDING_SLACK
    kind = "ramp" if not horizontal else ("tread" if tread else "platform")
    name = _geom_name(model, g)
    return WalkSurface(
        geom_id=g,
        name=name,
        kind=kind,
        z=zc,
        footprint=Footprint(name, g, xy),
        area=polygon_area(xy),
        centre=(float(centre[0]), float(centre[1])),
        slope=0.0 if horizontal else slope,
        uphill=0.0 if horizontal else float(math.atan2(-n[1], -n[0])),
        z_low=zc if horizontal else float(corners[:, 2].min()),
        z_high=zc if horizontal else float(corners[:, 2].max()),
        depth=depth,
        width=width,
    )


def _floor_surface(model, data, floor: int, disk: bool) -> WalkSurface:
    """The floor as a walk surface (an infinite plane: the other geoms' extent plus a margin; a
    slab: its own top face, a yawed one's turned rectangle, :mod:`mjwalk.world.slabfloor`; the
    slabs side by side with it are surfaces of its height, one level with it)."""
    z = floor_top(model, data, floor)
    c = data.geom_xpos[floor][:2]
    own = [t for t in slab_floor(model) if t.geom == floor]
    if own:
        xy, name = own[0].xy, _geom_name(model, floor)
        x0, y0, x1, y1 = own[0].bounds
        depth, width = _calipers(xy)  # as every surface's: a yawed slab's its turned rectangle's
        return WalkSurface(
            floor, name, "floor", z, Footprint(name, floor, xy), polygon_area(xy),
            ((x0 + x1) / 2, (y0 + y1) / 2), 0.0, 0.0, z, z, depth, width,
        )  # fmt: skip
    rect = floor_rect(model, data, floor)
    if rect is not None:
        bounds = rect
    else:
        boxes = [
            fp.bounds()
            for g in range(model.ngeom)
            if g != floor
            and (fp := geom_footprint(model, data, g, z, z + HEADROOM_SCAN, disk)) is not None
        ]
        b = np.array(boxes) if boxes else np.array([[c[0] - 1, c[1] - 1, c[0] + 1, c[1] + 1]])
        m = INFINITE_FLOOR_MARGIN
        bounds = (b[:, 0].min() - m, b[:, 1].min() - m, b[:, 2].max() + m, b[:, 3].max() + m)
    x0, y0, x1, y1 = (float(v) for v in bounds)
    xy = np.array([[x0, y0], [x1, y0], [x1, y1], [x0, y1]])
    name = _geom_name(model, floor)
    depth, width = sorted((x1 - x0, y1 - y0))
    return WalkSurface(
        floor, name, "floor", z, Footprint(name, floor, xy), (x1 - x0) * (y1 - y0),
        ((x0 + x1) / 2, (y0 + y1) / 2), 0.0, 0.0, z, z, depth, width,
    )  # fmt: skip


def _selected(model, g: int, options: SurfaceOptions) -> bool:
    name = _geom_name(model, g)
    if options.groups is not None and int(model.geom_group[g]) not in options.groups:
        return False
    if options.include is not None and not re.search(options.include, name):
        return False
    return not (options.exclude is not None and re.search(options.exclude, name))


def find_walk_surfaces(
    model: mujoco.MjModel, data: mujoco.MjData | None = None, options: SurfaceOptions | None = None
) -> tuple[WalkSurface, ...]:
    """The walk surfaces of a scene: the floor and the geom tops reachable from it.

    Args:
        model: the compiled scene.
        data: its data with the kinematics done (None: made here, ``mj_kinematics``).
        options: which geoms can be surfaces and the limits (None: the cited defaults).

    Returns:
        The floor first, then the other surfaces by height and name, each with the geoms over it.

    Raises:
        SceneError: the scene has no level floor.
    """
    options = options or SurfaceOptions()
    if data is None:
        data = mujoco.MjData(model)
        mujoco.mj_kinematics(model, data)
    floor = find_floor(model, data, "scene")
    human = {g for g in range(model.ngeom) if _is_humanoid(model, g, options.humanoid_prefixes)}
    disk = use_disk(options.cache, True)  # 3-D hulls kept as obstacle_footprints keeps them
    ground = _floor_surface(model, data, floor, disk)
    floor_skip = human | {floor}
    geoms = _Geoms(model, data, disk)
    holes = floor_boxes(model, data, floor, "scene")
    if holes is None:
        found = [_with_overhead(ground, geoms, floor_skip)]
    else:  # the floor level is the boxes; the plane under its openings is a level below it
        found = _floor_with_openings(holes, ground, geoms, floor_skip, options)
        floor_skip = floor_skip | set(holes.geoms)
    for g in range(model.ngeom):
        if g in floor_skip or not _selected(model, g, options):
            continue
        corners = _top_face(model, data, g)
        if corners is None:
            continue
        corners = _clip_above(corners, ground.z)  # the plane: under a floor with openings too
        if len(corners) < 3:
            continue
        s = _surface_from_face(model, g, corners, options)
        if s is None:
            continue
        s = _with_overhead(s, geoms, floor_skip | {g})
        if s.headroom.clear_area(options.min_headroom) < options.min_depth * options.min_width:
            continue
        found.append(s)
    contacts = surface_contacts(found, options.contact_gap, options.max_riser)
    # a ramp's end meets a level across its boxes, as in the level graph (levelgroups)
    contacts += ramp_end_contacts(
        found, contacts, options.contact_gap, options.max_riser, options.level_tol
    )
    keep = reachable(len(found), contacts)
    if holes is not None:  # every floor box is the floor: each one's edge may be a few cells
        for i, s in enumerate(found):  # of a staircase round a turned flight, touching little
            if s.kind == "floor" and i not in keep:
                keep |= reachable(len(found), contacts, i)
    rest = sorted((found[i] for i in keep if i > 0), key=lambda s: (s.z_low, s.name))
    return (found[0], *rest)


def _floor_with_openings(
    holes: FloorBoxes, ground: WalkSurface, geoms: _Geoms, skip: set[int], options: SurfaceOptions
) -> list[WalkSurface]:
    """The surfaces of a floor with openings (:mod:`mjwalk.world.floorholes`): each floor box's
    top as a "floor" surface (of any size: the boxes tile the floor), then the plane below as a
    "platform" (the pits' bottom: open to stand on only under the openings, its area theirs)."""
    model, data = geoms.model, geoms.data
    tiny = replace(options, min_depth=1e-6, min_width=1e-6)
    out = []
    for g in holes.geoms:
        corners = _top_face(model, data, g)
        s = None if corners is None else _surface_from_face(model, g, corners, tiny)
        if s is not None:
            out.append(_with_overhead(replace(s, kind="floor"), geoms, skip | {g}))
    area = opening_area(ground.footprint, holes.footprints)  # the pits' openings, not the plane
    bottom = _with_overhead(replace(ground, kind="platform", area=area), geoms, skip)
    return [*out, bottom]


def _with_overhead(s: WalkSurface, geoms: _Geoms, skip: set[int]) -> WalkSurface:
    """``s`` with the geoms over it."""
    over = _overheads(geoms, skip, s.z_low, s.z_high, s.footprint.bounds())
    return WalkSurface(
        s.geom_id, s.name, s.kind, s.z, s.footprint, s.area, s.centre, s.slope, s.uphill,
        s.z_low, s.z_high, s.depth, s.width, over,
    )  # fmt: skip
