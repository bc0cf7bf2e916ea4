"""One level of a multi-level workplace seen as a flat workplace, for the planners.

A :class:`~mjwalk.world.workplace.Workplace` knows its levels (:attr:`Workplace.levels
<mjwalk.world.workplace.Workplace.levels>`). :func:`level_view` makes the
:class:`~mjwalk.world.workplace.Workplace` of one level that the clearance field, the occupancy
grid, the grid-A* baseline and the hybrid A* work on unchanged:

- its walkable region is the level's surfaces: the floor bounds are their extent, and where the
  surfaces do not cover that extent (an L-shaped platform) the clearance field holds the distance
  to the surfaces' edge, so every edge of the level is a wall; a walker leaves a level only over
  a link, which the level planner (:mod:`mjwalk.plan.levelplan`) walks itself;
- its obstacles are the geoms in the height band above the level's height, the band's foot the
  workplace's (0.05 m) and its top the walker's head: stature plus
  :data:`mjwalk.world.norms.HEAD_MARGIN` (a beam or a mezzanine's underside lower than that is an
  obstacle for this walker and not for a shorter one). Without a head height the band is the
  workplace's own (0.05-2.0 m).

The floor's view with the workplace's own band is the workplace itself: flat scenes plan exactly
as before. Views are built once per level and set of obstacles and kept on the workplace (walkers
of nearby statures share a view when no geom's underside lies between their heads). A view's
field is kept in the workplace cache too unless the workplace's policy is False
(:attr:`~mjwalk.world.workplace.WorkplaceOptions.cache`; as the 3-D hulls, whatever its size: on
the multi-level station the floor's view for a 1.83 m head band builds in 54 ms CPU, the 0.34 m
platform's (11 271 nodes, its edge field included) in 9.3 ms and the mezzanine's in 5.7 ms; each
reads back with its key in 0.2-0.3 ms). It is keyed by everything it is computed from, so a new
process reads the array it would build, bit for bit; the view then has that key as its
``cache_key``, and its walk field and occupancy grids are kept beside it as the workplace's own
are (:meth:`~mjwalk.world.workplace.Workplace.walk_field`,
:func:`mjwalk.plan.occupancy.shared_grid`).
:func:`level_at` tells which level a point stands on (kept on the workplace per point).
Metres, world frame.
"""

from __future__ import annotations

import hashlib
import math
from dataclasses import replace

import mujoco
import numpy as np
from scipy import ndimage

from mjwalk.errors import InputError, SceneError
from mjwalk.world.cache import cached_array, content_key, use_disk
from mjwalk.world.clearance import ClearanceField, build_clearance
from mjwalk.world.floor import find_floor
from mjwalk.world.norms import CONTACT_GAP, EXPOSED_MIN, HEADROOM_SCAN
from mjwalk.world.openings import mark_level
from mjwalk.world.workplace import Workplace, WorkplaceOptions, obstacle_footprints

#: The key under which a workplace keeps its level views.
_VIEWS = "_level_views"
#: The key under which a workplace keeps the levels of the points :func:`level_at` was asked.
_AT = "_level_at"


def level_at(workplace: Workplace, xy, z: float | None = None) -> int | None:
    """The level a point stands on.

    Args:
        workplace: the scene.
        xy: world point (x, y), metres.
        z: the point's world height (a site's), metres; None: the highest surface there with
            room above it.

    Returns:
        The level's index in ``workplace.levels.levels`` (0: the floor's), or None when the
        point is on a ramp or on no surface.
    """
    graph = workplace.levels
    x, y = (float(v) for v in np.asarray(xy, dtype=float)[:2])
    cache = workplace.__dict__.setdefault(_AT, {})  # walks start and end at the same sites
    key = (x, y, None if z is None else float(z))
    if key not in cache:
        s = graph.surface_at((x, y), z)
        cache[key] = None if s is None else graph.level_of[s]
    return cache[key]


def _band_top(head: float | None, default: float) -> float:
    """The obstacle band's top above a level, metres (checked)."""
    if head is None:
        return default
    if not (math.isfinite(head) and EXPOSED_MIN < head <= HEADROOM_SCAN):
        raise InputError(f"head height {head!r} m must be in ({EXPOSED_MIN}, {HEADROOM_SCAN}]")
    return float(head)


def level_view(workplace: Workplace, level: int, head: float | None = None) -> Workplace:
    """The workplace of one level (module docstring), built once and kept on ``workplace``.

    Args:
        workplace: the scene.
        level: the level's index in ``workplace.levels.levels`` (0: the floor).
        head: the walker's head height above the level (stature plus
            :data:`mjwalk.world.norms.HEAD_MARGIN`), metres; the top of the obstacle band.
            None: the workplace's own band.

    Returns:
        The level's workplace: its surfaces' extent as floor bounds, the obstacles in its band,
        the level's edges as walls in the clearance field; ``floor_z`` the level's height. The
        floor's view with the workplace's band is ``workplace`` itself.

    Raises:
        InputError: an unknown level or a head height out of range.
    """
    graph = workplace.levels
    if isinstance(level, bool) or not 0 <= int(level) < len(graph.levels):
        raise InputError(f"{workplace.name}: no level {level!r} (it has {len(graph.levels)})")
    lv = graph.levels[int(level)]
    base = workplace.options or WorkplaceOptions()
    top = _band_top(head, workplace.z_range[1])
    if lv.index == 0 and top == workplace.z_range[1]:
        return workplace
    views = workplace.__dict__.setdefault(_VIEWS, {})
    known = views.get((lv.index, round(top, 3)))  # this level and band seen before
    if known is not None:
        return views[known]
    # the workplace's cache policy, for the hulls its geoms' footprints clip and the view's field
    options = replace(base, z_range=(workplace.z_range[0], top))
    model = workplace.model
    data = mujoco.MjData(model)
    mujoco.mj_kinematics(model, data)
    floor = find_floor(model, data, workplace.name)
    own = frozenset(graph.surfaces[i].geom_id for i in lv.surfaces)
    footprints = obstacle_footprints(
        model, data, floor, options, workplace.name, base=lv.height, skip=own, warn=False
    )
    key = _view_key(lv.index, footprints)
    if key not in views:
        views[key] = _build_view(workplace, lv.index, footprints, options)
    views[(lv.index, round(top, 3))] = key
    return views[key]


def _view_key(level: int, footprints) -> str:
    """A key for a level's set of obstacle footprints (views with equal keys are equal)."""
    h = hashlib.sha256(str(level).encode())
    for fp in footprints:
        h.update(fp.name.encode())
        h.update(np.round(np.asarray(fp.vertices, dtype=float), 4).tobytes())
        h.update(np.round(np.array([fp.radius]), 4).tobytes())
    return h.hexdigest()


def _build_view(
    workplace: Workplace, level: int, footprints, options: WorkplaceOptions
) -> Workplace:
    """The view of ``level`` with ``footprints`` as obstacles (:func:`level_view`)."""
    graph = workplace.levels
    lv = graph.levels[level]
    resolution = workplace.clearance.resolution
    if level == 0:
        bounds = workplace.floor_bounds
    else:
        b = np.array([graph.surfaces[i].footprint.bounds() for i in lv.surfaces])
        bounds = (
            float(b[:, 0].min()),
            float(b[:, 1].min()),
            float(b[:, 2].max()),
            float(b[:, 3].max()),
        )
    disk = None
    if use_disk(options.cache, True):  # (module docstring)
        disk = _field_key(graph, lv, footprints, bounds, resolution)
        values = cached_array(
            disk, "levelview", lambda: _view_field(graph, lv, footprints, bounds, resolution)
        )
    else:
        values = _view_field(graph, lv, footprints, bounds, resolution)
    field = ClearanceField(bounds[0], bounds[1], resolution, values)
    view = Workplace(
        model=workplace.model,
        source=workplace.source,
        floor=workplace.floor,
        floor_z=lv.height,
        floor_bounds=bounds,
        obstacles=footprints,
        clearance=field,
        stations=workplace.stations,
        z_range=options.z_range,
        cache_key=disk,
        options=options,
    )
    mark_level(view, graph, level)  # its openings, for the side choice (mjwalk.world.openings)
    return view


def _view_field(graph, lv, footprints, bounds, resolution: float) -> np.ndarray:
    """The view's field values (:func:`_build_view`): the clearance to ``footprints`` over
    ``bounds`` every ``resolution`` metres, off the floor's level bounded by the distance to
    the level's edge (:func:`_edge_field`), metres."""
    field = build_clearance(footprints, bounds, resolution)
    if lv.index == 0:
        return field.values
    return np.minimum(field.values, _edge_field(graph, lv, field))


def _field_key(graph, lv, footprints, bounds, resolution: float) -> str:
    """The workplace cache's key (:func:`mjwalk.world.cache.content_key`) of
    :func:`_view_field`'s values: the bounds, the resolution, the obstacles' geometry in order
    and, off the floor's level, the level's surfaces' geometry and the gap that joins them
    (:func:`_edge_field`)."""
    edges = [] if lv.index == 0 else [graph.surfaces[i].footprint for i in lv.surfaces]
    return content_key(
        "levelview",
        tuple(float(v) for v in bounds),
        float(resolution),
        [(len(f.vertices), float(f.radius)) for f in footprints],
        None if lv.index == 0 else float(CONTACT_GAP),
        [(len(f.vertices), float(f.radius)) for f in edges],
        arrays=[np.asarray(f.vertices, dtype=float) for f in [*footprints, *edges]],
    )


def _edge_field(graph, lv, field: ClearanceField) -> np.ndarray:
    """Distance from each node of ``field`` to the edge of the level's surfaces, metres
    (negative off them): the surfaces joined across gaps up to
    :data:`mjwalk.world.norms.CONTACT_GAP`, rasterised on the nodes, measured by a Euclidean
    distance transform (exact to half a node)."""
    gx, gy = field.grid_xy()
    xy = np.stack(np.meshgrid(gx, gy), axis=-1)
    sd = np.full(xy.shape[:2], np.inf)
    for i in lv.surfaces:
        sd = np.minimum(sd, graph.surfaces[i].footprint.signed_distance(xy))
    inside = sd <= 0.5 * CONTACT_GAP
    if not inside.any():
        raise SceneError(f"level L{lv.index} has no node on its surfaces")
    res = field.resolution
    padded = np.pad(inside, 1, constant_values=False)  # beyond the extent: off the level
    inner = ndimage.distance_transform_edt(padded)[1:-1, 1:-1] * res - 0.5 * res
    outer = ndimage.distance_transform_edt(~inside) * res - 0.5 * res
    return np.where(inside, inner, -outer)
