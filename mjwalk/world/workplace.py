"""The ``Workplace``: an MJCF scene seen from the floor — obstacles, clearance field, stations."""

from __future__ import annotations

import difflib
import functools
import hashlib
import math
import re
from dataclasses import dataclass, field
from pathlib import Path

import mujoco
import numpy as np

from mjwalk._args import check_patterns, finite_points, parse_point
from mjwalk.errors import InputError, SceneError
from mjwalk.world.cache import AUTO_NODES, cached_array, content_key, use_disk
from mjwalk.world.clearance import ClearanceField, build_clearance
from mjwalk.world.floor import (
    OBSTACLE_Z_RANGE,
    check_floor_nodes,
    find_floor,
    floor_rect,
    floor_top,
    slab_floor,
)
from mjwalk.world.floorholes import floor_boxes, wall_openings
from mjwalk.world.footprint import Footprint, geom_footprint
from mjwalk.world.levels import LevelGraph, level_graph
from mjwalk.world.meshimport import concave_mesh_footprints
from mjwalk.world.surfaces import SurfaceOptions, find_walk_surfaces

#: Bodies whose name starts with one of these are part of a humanoid, never obstacles (the
#: humanoid mjwalk attaches names its bodies :data:`mjwalk.body.humanoid.HUMAN_PREFIX`).
HUMANOID_PREFIXES = ("human",)
#: Coarsest clearance grid spacing, metres: the 2 cm the occupancy grids, the walk field and the
#: floor-size limit (:data:`mjwalk.world.floor.MAX_FLOOR_NODES`) are built and checked at.
MAX_RESOLUTION = 0.02


@dataclass(frozen=True)
class WorkplaceOptions:
    """How an MJCF scene is read into a :class:`Workplace`: which geoms are obstacles and how
    the clearance field is built. Checked on construction (InputError, one line).

    Attributes:
        resolution: clearance grid spacing, metres, in (0, :data:`MAX_RESOLUTION`].
        z_range: a geom is an obstacle when its vertical extent overlaps this band of heights
            above the floor (metres, low < high); its footprint is the part inside the band.
            Default :data:`mjwalk.world.floor.OBSTACLE_Z_RANGE`.
        groups: only geoms in these MuJoCo geom groups are obstacles (None: all groups).
        include, exclude: regular expressions on geom names selecting/rejecting obstacles
            (``re.search``; None: no filter).
        humanoid_prefixes: bodies (and their children) whose names start with one of these are
            a humanoid and never obstacles (default :data:`HUMANOID_PREFIXES`).
        cache: keep the clearance field, walk field and occupancy grids on disk, keyed by the
            footprints' geometry, and map them into memory (:mod:`mjwalk.world.cache`; workers
            planning in one hall then share one copy). None: for fields of at least
            :data:`mjwalk.world.cache.AUTO_NODES` nodes (about 20 x 20 m). The 3-D hulls of
            tessellated geoms and large meshes (:mod:`mjwalk.world.hullstore`) are kept
            unless it is False, the level views' and the walk surfaces' included.
    """

    resolution: float = MAX_RESOLUTION
    z_range: tuple[float, float] = OBSTACLE_Z_RANGE
    groups: set[int] | None = None
    include: str | None = None
    exclude: str | None = None
    humanoid_prefixes: tuple[str, ...] = HUMANOID_PREFIXES
    cache: bool | None = None

    def __post_init__(self) -> None:
        if not 0 < self.resolution <= MAX_RESOLUTION:
            raise InputError(
                f"clearance resolution {self.resolution} m must be in (0, {MAX_RESOLUTION}]"
            )
        lo, hi = self.z_range
        if not (math.isfinite(lo) and math.isfinite(hi) and lo < hi):
            raise InputError(f"obstacle z_range {self.z_range} m must be finite, low < high")
        check_patterns(include=self.include, exclude=self.exclude)


@dataclass(frozen=True)
class Station:
    """A named site of the scene: world position (metres) and yaw of its local +x axis (radians
    from +x, CCW) — for standing sites, the direction the operator faces."""

    name: str
    pos: np.ndarray
    yaw: float

    @property
    def xy(self) -> np.ndarray:
        return self.pos[:2]


@dataclass
class Workplace:
    """An MJCF workplace prepared for planning.

    Attributes:
        model: the compiled scene.
        source: the MJCF file it came from (None for an in-memory model).
        floor: the floor geom's name; the floor is the plane z = ``floor_z``.
        floor_bounds: (xmin, ymin, xmax, ymax) of the walkable floor, metres.
        obstacles: obstacle footprints (one per obstacle geom; a concave mesh geom gives
            several convex pieces under its name, see :mod:`mjwalk.world.meshimport`).
        clearance: distance to the nearest obstacle footprint, metres (negative inside).
        stations: the scene's named sites.
        z_range: the height band used to select obstacles and to cut their footprints.
    """

    model: mujoco.MjModel
    source: Path | None
    floor: str
    floor_z: float
    floor_bounds: tuple[float, float, float, float]
    obstacles: list[Footprint]
    clearance: ClearanceField
    stations: dict[str, Station] = field(default_factory=dict)
    z_range: tuple[float, float] = OBSTACLE_Z_RANGE
    #: Content key of the arrays cached on disk (:mod:`mjwalk.world.cache`), None when the
    #: workplace is not cached.
    cache_key: str | None = None
    #: How the scene was read (None: the defaults); level views (:mod:`mjwalk.world.levelview`)
    #: select their obstacles alike.
    options: WorkplaceOptions | None = None

    @property
    def levels(self) -> LevelGraph:
        """The scene's walk surfaces grouped into levels and joined by steps, ramps and stairs
        (:func:`mjwalk.world.levels.level_graph`), found once on first use (about 0.1-0.3 s) and
        kept; a flat scene has exactly one level, the floor. The surfaces are selected by the
        same groups and name patterns as the obstacles."""
        cached = getattr(self, "_levels", None)
        if cached is None:
            o = self.options or WorkplaceOptions()
            groups = None if o.groups is None else frozenset(o.groups)
            surface_options = SurfaceOptions(
                groups=groups,
                include=o.include,
                exclude=o.exclude,
                humanoid_prefixes=o.humanoid_prefixes,
                cache=o.cache,
            )
            cached = self._levels = level_graph(
                find_walk_surfaces(self.model, None, surface_options)
            )
        return cached

    @property
    def obstacle_geoms(self) -> list[int]:
        """Geom ids of the obstacles."""
        return [f.geom_id for f in self.obstacles]

    @property
    def name(self) -> str:
        return self.source.stem if self.source else "scene"

    def station(self, name: str) -> Station:
        """A named site.

        Args:
            name: the site's name.

        Returns:
            The site's station (position, yaw).

        Raises:
            SceneError: an unknown name, listing near matches.
        """
        try:
            return self.stations[name]
        except KeyError:
            close = difflib.get_close_matches(name, list(self.stations), n=3)
            hint = f"; did you mean {', '.join(close)}?" if close else ""
            raise SceneError(f"{self.name}: no site named {name!r}{hint}") from None

    def point(self, where: str | np.ndarray | tuple[float, float]) -> np.ndarray:
        """A floor point from a site name, an ``"x,y"`` string or coordinates (metres).

        A site whose name reads as coordinates (a site named "1.5,2") wins: the text is read as
        coordinates only when no site has that name.

        Args:
            where: a site name, ``"x,y"`` or (x, y), world metres.

        Returns:
            (2,) world x, y, metres.

        Raises:
            InputError: malformed or non-finite coordinates.
            SceneError: an unknown site, or fewer than two coordinates.
        """
        if isinstance(where, str):
            if where in self.stations:
                return self.stations[where].xy.copy()
            xy = parse_point(where, f"{self.name}: point")
            return xy if xy is not None else self.station(where).xy.copy()
        try:
            arr = np.asarray(where, dtype=float).ravel()
        except (TypeError, ValueError):
            raise InputError(
                f"{self.name}: a floor point is a site name, 'x,y' or (x, y) metres; got {where!r}"
            ) from None
        if arr.shape[0] < 2:
            raise SceneError(f"{self.name}: a floor point needs x and y, got {where!r}")
        return finite_points(arr[:2], f"{self.name}: point").copy()

    @property
    def fingerprint(self) -> str:
        """A hash of the obstacle geometry (footprints and floor bounds, rounded to 0.1 mm):
        equal for the same scene wherever its file lies, different once an obstacle moves.
        Walks record it (:meth:`mjwalk.plan.walkpath.WalkPath.check_scene`)."""
        cached = getattr(self, "_fingerprint", None)
        if cached is None:
            h = hashlib.sha256()
            h.update(np.round(np.array(self.floor_bounds + (self.floor_z,)), 4).tobytes())
            for fp in sorted(self.obstacles, key=lambda f: (f.bounds(), f.name)):
                h.update(np.round(np.asarray(fp.vertices, dtype=float), 4).tobytes())
                h.update(np.round(np.array([fp.radius]), 4).tobytes())
            cached = self._fingerprint = h.hexdigest()[:16]
        return cached

    def edge_distance(self, xy: np.ndarray) -> np.ndarray:
        """Signed distance from points to the floor's edge.

        Args:
            xy: (..., 2) world x, y, metres.

        Returns:
            (...) metres, positive on the floor.
        """
        xy = np.asarray(xy, dtype=float)
        xmin, ymin, xmax, ymax = self.floor_bounds
        return np.minimum.reduce(
            [xy[..., 0] - xmin, xmax - xy[..., 0], xy[..., 1] - ymin, ymax - xy[..., 1]]
        )

    def on_floor(self, xy: np.ndarray) -> np.ndarray:
        """Whether points lie on the floor.

        Args:
            xy: (..., 2) world x, y, metres.

        Returns:
            (...) bool.
        """
        return self.edge_distance(xy) >= 0.0

    def walk_clearance(self, xy: np.ndarray) -> np.ndarray:
        """Room to walk at points.

        Args:
            xy: (..., 2) world x, y, metres.

        Returns:
            (...) the smaller of obstacle clearance and distance to the floor's edge, metres.
        """
        return np.minimum(self.clearance(xy), self.edge_distance(xy))

    def walk_field(self) -> ClearanceField:
        """:meth:`walk_clearance` as one field (built once, cached): each node holds the smaller
        of its obstacle clearance and its distance to the floor's edge, metres.

        Within the nodes' extent its bilinear lookup never exceeds :meth:`walk_clearance` at
        the same point: the weights are non-negative, so interpolating the minimum gives at
        most the minimum of the interpolations, and the edge distance (a minimum of linear
        functions, concave) is at least its own interpolation. Points beyond the nodes (off
        the floor, or in a strip narrower than one node spacing along its edge) take the
        border nodes' values, at most one node spacing (the border's distance to the floor's
        edge): any test against a clearance above the spacing rejects them, as
        :meth:`walk_clearance` does.

        Returns:
            The field on the clearance field's nodes, metres.
        """
        cached = getattr(self, "_walk_field", None)
        if cached is None:
            c = self.clearance

            def build() -> np.ndarray:
                # the edge distance separates into a row and a column term (no (ny, nx, 2)
                # coordinate array): the same minimum of the same four differences
                gx, gy = c.grid_xy()
                xmin, ymin, xmax, ymax = self.floor_bounds
                ex = np.minimum(gx - xmin, xmax - gx)
                ey = np.minimum(gy - ymin, ymax - gy)
                return np.minimum(c.values, np.minimum(ex[None, :], ey[:, None]))

            if self.cache_key is not None:
                values = cached_array(self.cache_key, "walk", build)
            else:
                values = build()
            cached = ClearanceField(c.x0, c.y0, c.resolution, values)
            self._walk_field = cached
        return cached

    def footprint(self, name: str) -> Footprint:
        """The footprint of an obstacle geom.

        Args:
            name: the geom's name.

        Returns:
            Its (first) footprint.

        Raises:
            SceneError: no obstacle of that name.
        """
        for fp in self.obstacles:
            if fp.name == name:
                return fp
        raise SceneError(f"{self.name}: no obstacle geom named {name!r}")


def check_scene_path(path: Path) -> None:
    """Refuse a path that is not a scene file.

    Args:
        path: the MJCF path.

    Raises:
        SceneError: a folder (named as one) or a missing file.
    """
    if path.is_dir():
        raise SceneError(f"{path} is a folder, not an MJCF scene file")
    if not path.is_file():
        raise SceneError(f"{path}: scene file not found")


def load_model(source: str | Path) -> mujoco.MjModel:
    """Compile an MJCF file.

    Args:
        source: the MJCF path.

    Returns:
        The compiled model.

    Raises:
        SceneError: a missing file, or MuJoCo's parse or compile error, naming the file.
    """
    path = Path(source)
    check_scene_path(path)
    try:
        return mujoco.MjModel.from_xml_path(str(path))
    except ValueError as exc:  # mujoco reports parse and compile errors as ValueError
        msg = str(exc).strip().replace("\n", " ")
        raise SceneError(f"{path}: not a valid MJCF scene: {msg}") from exc


def _body_name(model: mujoco.MjModel, body: int) -> str:
    return mujoco.mj_id2name(model, mujoco.mjtObj.mjOBJ_BODY, body) or ""


def _is_humanoid_geom(model: mujoco.MjModel, g: int, prefixes: tuple[str, ...]) -> bool:
    body = model.geom_bodyid[g]
    while body > 0:
        if _body_name(model, body).startswith(prefixes):
            return True
        body = model.body_parentid[body]
    return False


def workplace_from_model(
    model: mujoco.MjModel,
    *,
    source: Path | None = None,
    options: WorkplaceOptions | None = None,
) -> Workplace:
    """Prepare a compiled model for planning.

    Args:
        model: the compiled scene.
        source: the MJCF file it came from, named in errors (None for an in-memory model).
        options: obstacle selection and clearance field settings (None: the defaults).

    Returns:
        The workplace: floor, obstacle footprints, clearance field and named sites.

    Raises:
        SceneError: no floor, a floor too large, unsupported obstacle geom.
    """
    label = str(source) if source else "scene"
    if options is None:
        options = WorkplaceOptions()
    resolution = options.resolution
    data = mujoco.MjData(model)
    mujoco.mj_kinematics(model, data)
    floor = find_floor(model, data, label)
    holes = floor_boxes(model, data, floor, label)
    floor_z = floor_top(model, data, floor) if holes is None else holes.height
    floor_name = mujoco.mj_id2name(model, mujoco.mjtObj.mjOBJ_GEOM, floor) or f"geom{floor}"
    rect = floor_rect(model, data, floor)
    if rect is not None:  # a finite floor: refused before the obstacles are read
        check_floor_nodes(rect, resolution, label, floor_name)
    if holes is None:
        footprints = obstacle_footprints(model, data, floor, options, label)
    else:  # a floor with openings: the band above the boxes, which are not obstacles
        skip = frozenset(holes.geoms)
        footprints = obstacle_footprints(model, data, floor, options, label, floor_z, skip)
    if rect is not None:
        bounds = rect
    else:  # an infinite plane: the obstacles' extent plus 2 m
        if not footprints:
            raise SceneError(f"{label}: the floor plane is infinite and there are no obstacles")
        b = np.array([f.bounds() for f in footprints])
        bounds = (b[:, 0].min() - 2, b[:, 1].min() - 2, b[:, 2].max() + 2, b[:, 3].max() + 2)
    check_floor_nodes(bounds, resolution, label, floor_name)
    key, clearance = _clearance(footprints, bounds, options)
    if holes is not None:
        key, clearance = None, wall_openings(clearance, holes.footprints)
    tiles = slab_floor(model) if rect is not None and holes is None else ()
    if tiles:  # slab tops off their bounding box (a yawed slab, an L of tiles): walls at edges
        walled = wall_openings(clearance, tuple(Footprint(t.name, t.geom, t.xy) for t in tiles))
        key, clearance = (key, clearance) if walled is clearance else (None, walled)
    return Workplace(
        model=model,
        source=source,
        floor=floor_name,
        floor_z=floor_z,
        floor_bounds=(float(bounds[0]), float(bounds[1]), float(bounds[2]), float(bounds[3])),
        obstacles=footprints,
        clearance=clearance,
        stations=_stations(model, data),
        z_range=options.z_range,
        cache_key=key,
        options=options,
    )


def obstacle_footprints(
    model: mujoco.MjModel,
    data: mujoco.MjData,
    floor: int,
    options: WorkplaceOptions,
    label: str,
    base: float | None = None,
    skip: frozenset[int] = frozenset(),
    warn: bool = True,
) -> list[Footprint]:
    """The footprints of the obstacle geoms ``options`` selects (not the floor, not a
    humanoid's, not planes), cut to its height band above the floor (or above ``base``).

    Unless ``options.cache`` is False, a geom's 3-D hull of at least
    :data:`mjwalk.world.hullstore.DISK_HULL_POINTS` points is read from and kept in the
    workplace cache, whatever the scene's size (qhull takes some 60 ms for one).

    Args:
        model: the compiled scene.
        data: its data, kinematics done.
        floor: the floor geom's id.
        options: the selection (groups, name patterns, humanoid prefixes) and the height band.
        label: the scene's name in errors.
        base: world height the band is measured from, metres (None: the floor's; a level's
            height for :mod:`mjwalk.world.levelview`).
        skip: further geom ids that are never obstacles (a level's own surfaces).
        warn: whether to warn of meshes whose hull hides walk faces
            (:func:`~mjwalk.world.meshimport.concave_mesh_footprints`; a level's view of a
            scene already loaded does not look again).

    Returns:
        The footprints, in geom order (a concave mesh gives several pieces).

    Raises:
        SceneError: a height field or SDF geom among the selected ones.
    """
    groups, include, exclude = options.groups, options.include, options.exclude
    z_range = options.z_range
    disk = use_disk(options.cache, True)
    floor_z = floor_top(model, data, floor) if base is None else float(base)
    footprints: list[Footprint] = []
    for g in range(model.ngeom):
        if g == floor or g in skip or _is_humanoid_geom(model, g, options.humanoid_prefixes):
            continue
        gname = mujoco.mj_id2name(model, mujoco.mjtObj.mjOBJ_GEOM, g) or f"geom{g}"
        if groups is not None and model.geom_group[g] not in groups:
            continue
        if include is not None and not re.search(include, gname):
            continue
        if exclude is not None and re.search(exclude, gname):
            continue
        gtype = int(model.geom_type[g])
        if gtype == mujoco.mjtGeom.mjGEOM_PLANE:
            continue  # other planes (a second floor level, a ceiling) are not footprints
        if gtype in (mujoco.mjtGeom.mjGEOM_HFIELD, mujoco.mjtGeom.mjGEOM_SDF):
            raise SceneError(
                f"{label}: geom {gname!r} is a height field/SDF; mjwalk obstacles must be "
                "primitives or meshes (exclude it with exclude=...)"
            )
        z0, z1 = floor_z + z_range[0], floor_z + z_range[1]
        pieces = concave_mesh_footprints(model, data, g, z0, z1, warn)  # None unless concave
        if pieces is not None:
            footprints.extend(pieces)
            continue
        fp = geom_footprint(model, data, g, z0, z1, disk)
        if fp is not None:
            footprints.append(fp)
    return footprints


def _clearance(
    footprints: list[Footprint],
    bounds: tuple[float, float, float, float],
    options: WorkplaceOptions,
) -> tuple[str | None, ClearanceField]:
    """The clearance field over ``bounds`` and its cache key (None: not cached)."""
    resolution = options.resolution
    key = None
    nx = int(np.floor((bounds[2] - bounds[0]) / resolution + 1e-9)) + 1
    ny = int(np.floor((bounds[3] - bounds[1]) / resolution + 1e-9)) + 1
    if use_disk(options.cache, nx * ny >= AUTO_NODES):
        key = content_key(
            "clearance",
            tuple(float(v) for v in bounds),
            float(resolution),
            [(len(f.vertices), float(f.radius)) for f in footprints],
            arrays=[f.vertices for f in footprints],
        )
        values = cached_array(
            key, "clearance", lambda: build_clearance(footprints, bounds, resolution).values
        )
        return key, ClearanceField(bounds[0], bounds[1], resolution, values)
    return key, build_clearance(footprints, bounds, resolution)


def _stations(model: mujoco.MjModel, data: mujoco.MjData) -> dict[str, Station]:
    """The model's named sites: position and the yaw of their local +x axis."""
    stations = {}
    for s in range(model.nsite):
        sname = mujoco.mj_id2name(model, mujoco.mjtObj.mjOBJ_SITE, s)
        if sname:
            xmat = data.site_xmat[s].reshape(3, 3)
            stations[sname] = Station(
                sname, data.site_xpos[s].copy(), float(np.arctan2(xmat[1, 0], xmat[0, 0]))
            )
    return stations


def load_workplace(
    source: str | Path,
    options: WorkplaceOptions | None = None,
    *,
    groups: set[int] | None = None,
    include: str | None = None,
    exclude: str | None = None,
    cache: bool | None = None,
) -> Workplace:
    """Load an MJCF workplace: its floor, obstacle geoms, clearance field and named sites.

    Args:
        source: path of the MJCF file.
        options: obstacle selection and clearance field settings (None: the defaults).
        groups: shorthand for :attr:`WorkplaceOptions.groups`, for calls without ``options``.
        include: shorthand for :attr:`WorkplaceOptions.include`.
        exclude: shorthand for :attr:`WorkplaceOptions.exclude`.
        cache: shorthand for :attr:`WorkplaceOptions.cache`.

    Returns:
        The workplace (:func:`workplace_from_model` of the compiled file).

    Raises:
        InputError: ``options`` together with a shorthand, or a bad option value.
        SceneError: missing file, malformed MJCF, no floor, unsupported obstacle geom.
    """
    shorthand = (groups, include, exclude, cache)
    if options is None:
        options = WorkplaceOptions(groups=groups, include=include, exclude=exclude, cache=cache)
    elif any(v is not None for v in shorthand):
        raise InputError("load_workplace: give options= or groups/include/exclude/cache, not both")
    path = Path(source)
    model = load_model(path)
    return workplace_from_model(model, source=path, options=options)


@functools.lru_cache(maxsize=8)
def _shared(path: str, mtime: float) -> Workplace:
    return load_workplace(path)


def shared_workplace(source: str | Path) -> Workplace:
    """:func:`load_workplace` with default settings, loaded once per process and file
    version: the cycle simulator, its spec checks, playback and the report all read the same
    scene. Treat the result as read-only.

    Args:
        source: the MJCF path.

    Returns:
        The shared workplace.
    """
    check_scene_path(Path(source))
    path = Path(source).resolve()
    return _shared(str(path), path.stat().st_mtime)
