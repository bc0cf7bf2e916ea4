"""A level's openings (drops) as obstacle footprints, for the side choice and the berth.

A level's edges are walls of its clearance field (:mod:`mjwalk.world.levelview`,
:mod:`mjwalk.world.floorholes`): the planners never walk off a level. To the question which side
a walker passes an obstacle on and how much room it leaves (:mod:`mjwalk.plan.sides`,
:mod:`mjwalk.plan.detour`) a field's wall is not an obstacle, though: a pit beside a bench left
the walker the pit's rim as free room (issues 47/48: 8 of 16 walks passed the bench nearer than
0.30 m, 3 of 16 with a box in the pit's place). People keep from a drop as from an obstacle, so
a level's **openings** are obstacle footprints to those questions:

- an opening is a hole in the level: a region off the level's surfaces (joined across gaps up to
  :data:`~mjwalk.world.norms.CONTACT_GAP`, as the level's edge field joins them) that they
  enclose. The level's outer boundary (a flat floor's rectangle, a platform's or mezzanine's
  rim) is no opening: it is the floor's edge of the level's view, which the planners already
  treat as such;
- less the surfaces a walker steps onto from the rim (the via surfaces of the level's links, a
  stair's treads or a ramp, the treads reached by steps over treads only, and every surface
  within a step, ``LevelOptions.max_riser``, of the
  level's height): a drop is where the walk surface ends over a drop too deep to step
  (DIN 18065's 0.19 m riser, :data:`~mjwalk.world.norms.MAX_RISER`), not where a step, stair or
  ramp connects;
- each opening cut into convex pieces (footprints are convex: constrained Delaunay triangles
  merged while their union stays convex); a rectangular pit is one piece. A piece no wider
  than :data:`~mjwalk.world.norms.CONTACT_GAP` (ASR A1.5/1,2: floor gaps up to 20 mm are walked
  over) is no opening: a scanned floor's boxes leave such strips between a tread and the rim,
  or along a pit's cell-stepped edge (issue 47, a synthetic scan of ``scenes/pit_station``).

They are found once per level view (:func:`level_openings`, kept on the workplace) and joined to
its obstacles by :func:`passing_footprints`; a workplace without openings (every flat scene) gives
its own obstacle list, so its plans are exactly as before. Metres, world frame (z up).
"""

from __future__ import annotations

import numpy as np

from mjwalk.world.footprint import Footprint
from mjwalk.world.levels import LevelOptions

__all__ = [
    "OPENING_PREFIX",
    "level_openings",
    "mark_level",
    "openings_of",
    "passing_footprints",
]

#: Names of the openings' footprints start with this (then the level and a count).
OPENING_PREFIX = "opening_"
#: The key under which a workplace keeps its level's openings.
_OPENINGS = "_level_openings"
#: The key under which a level's view keeps its level graph and level's index.
_LEVEL = "_level_of_view"
#: The key under which a workplace keeps its obstacles joined with its openings.
_PASSING = "_passing_footprints"
#: Pieces smaller than this (square metres) are dropped. ASSUMPTION: a sliver narrower than the
#: contact gap (0.02 m) along a metre's edge is an artefact of joining surfaces, not a drop a
#: foot fits into (ASR A1.5/1,2: gaps up to 20 mm are walked over).
_SLIVER_AREA = 0.02 * 0.02
#: Metres by which a piece's width may exceed the contact gap and still be walked over (the
#: rounding of shapely's coordinates: a 2 cm strip of a 2 cm floor-plan grid).
_WIDTH_TOL = 1e-9
#: Relative area by which a union may fall short of its convex hull and still count as convex
#: (rounding of shapely's coordinates).
_CONVEX_TOL = 1e-9


def level_openings(workplace) -> tuple[Footprint, ...]:
    """The openings of the level ``workplace`` is the view of (module doc), found on first use
    and kept on it. A level's view (:func:`mjwalk.world.levelview.level_view`) is marked with
    its level at construction (:func:`mark_level`); any other workplace is the floor's view
    (level 0 of its own level graph).

    Args:
        workplace: the scene or a level's view (:class:`~mjwalk.world.workplace.Workplace`).

    Returns:
        The openings' convex footprints (none on a flat floor).
    """
    kept = workplace.__dict__.get(_OPENINGS)
    if kept is None:
        graph, level = workplace.__dict__.get(_LEVEL) or (workplace.levels, 0)
        kept = openings_of(graph, level)
        workplace.__dict__[_OPENINGS] = kept
    return kept


def mark_level(view, graph, level: int) -> None:
    """Mark ``view`` as the view of ``level`` of ``graph`` (:func:`level_openings` finds that
    level's openings, on first use).

    Args:
        view: a level's :class:`~mjwalk.world.workplace.Workplace`.
        graph: the scene's :class:`~mjwalk.world.levels.LevelGraph`.
        level: the level's index in ``graph.levels``.
    """
    view.__dict__[_LEVEL] = (graph, int(level))


def passing_footprints(workplace) -> list[Footprint]:
    """The footprints the side choice and the berth keep from: the workplace's obstacles, then
    its level's openings (:func:`level_openings`). Kept on the workplace; without openings the
    workplace's own obstacle list.

    Args:
        workplace: the scene or a level's view.

    Returns:
        The footprints, obstacles first in ``workplace.obstacles``' order.
    """
    openings = level_openings(workplace)
    if not openings:
        return workplace.obstacles
    obstacles = workplace.obstacles
    ids = tuple(map(id, obstacles))  # the kept footprints live on: their ids are not reused
    kept = workplace.__dict__.get(_PASSING)
    if kept is None or kept[0] != ids:
        kept = (ids, [*obstacles, *openings], tuple(obstacles))
        workplace.__dict__[_PASSING] = kept
    return kept[1]


def openings_of(graph, level: int, options: LevelOptions | None = None) -> tuple[Footprint, ...]:
    """The openings of one level of a level graph (module doc) as convex footprints.

    Args:
        graph: the scene's :class:`~mjwalk.world.levels.LevelGraph`.
        level: the level's index in ``graph.levels``.
        options: the gap that joins surfaces and the highest step
            (:class:`~mjwalk.world.levels.LevelOptions`; None: the defaults).

    Returns:
        The footprints (polygons, counter-clockwise), named ``opening_L<level>_<k>``, geom id -1.
    """
    lv = graph.levels[int(level)]
    if len(lv.surfaces) < 3:
        return ()  # convex surfaces enclose a hole only three or more at a time (a flat floor)
    import shapely  # deferred: slow to import (as in meshextrude); only level views need it

    o = options or LevelOptions()
    half = 0.5 * o.contact_gap

    def polygon(fp: Footprint):
        return shapely.Polygon(np.asarray(fp.vertices, dtype=float)).buffer(
            half, join_style="mitre"
        )

    own = shapely.union_all([polygon(graph.surfaces[i].footprint) for i in lv.surfaces])
    holes = [
        shapely.Polygon(ring).buffer(half, join_style="mitre")  # back to the surfaces' edges
        for part in getattr(own, "geoms", [own])
        for ring in part.interiors
    ]
    if not holes:
        return ()
    linked = {i for k in graph.links_of(lv.index) for i in k.via} | _tread_steps(graph, lv.index)
    stepped = [
        i
        for i, s in enumerate(graph.surfaces)
        if i not in lv.surfaces and (i in linked or _step_apart(s, lv.height) <= o.max_riser)
    ]
    reach = shapely.union_all(
        [shapely.Polygon(np.asarray(graph.surfaces[i].footprint.vertices)) for i in stepped]
    )
    out: list[Footprint] = []
    for hole in holes:
        rest = hole.difference(reach) if stepped else hole
        for part in getattr(rest, "geoms", [rest]):
            for piece in _wide_pieces(part, o.contact_gap):
                v = np.asarray(shapely.geometry.polygon.orient(piece, 1.0).exterior.coords)
                name = f"{OPENING_PREFIX}L{lv.index}_{len(out)}"
                out.append(Footprint(name, -1, np.ascontiguousarray(v[:-1])))
    return tuple(out)


def _wide_pieces(part, gap: float) -> list:
    """The convex pieces of one connected part of a hole that are no gap walked over.

    A convex part is kept when wider than ``gap``. A part that is not (a pit's cell-stepped
    edge, a strip between a tread and the rim joining the pit) is first opened by a disc
    ``gap`` wide (eroded, then grown, by half of it: what remains is where the part is wider
    than ``gap``), and all pieces of that are kept: the width of each piece says nothing there,
    since cutting a wide region into convex pieces leaves thin triangles along its edges
    (generated hall 1095's scanned pit lost 0.06 of its 2.55 m^2 so, and its written scene's
    opening was smaller than the hall's beyond the bench's tolerance). Pieces under
    :data:`_SLIVER_AREA` are dropped either way.
    """
    pieces = _convex_pieces(part)
    if len(pieces) == 1:
        return [p for p in pieces if p.area >= _SLIVER_AREA and _width(p) > gap + _WIDTH_TOL]
    r = 0.5 * gap + _WIDTH_TOL
    core = part.buffer(-r, join_style="mitre").buffer(r, join_style="mitre").intersection(part)
    return [
        p
        for region in getattr(core, "geoms", [core])
        if region.geom_type == "Polygon"
        for p in _convex_pieces(region)
        if p.area >= _SLIVER_AREA
    ]


def _tread_steps(graph, level: int) -> set[int]:
    """The surfaces of the tread levels a walker reaches from ``level`` by steps over treads
    only: a stair whose treads the level graph did not join into one stair link (a scanned
    pit's, whose top tread meets the rim on two edges) is stepped onto all the same.

    Args:
        graph: the scene's level graph.
        level: the level's index.

    Returns:
        The surfaces' indices in ``graph.surfaces``.
    """
    seen, todo, out = {int(level)}, [int(level)], set()
    while todo:
        here = todo.pop()
        for k in graph.links_of(here):
            there = k.upper if k.lower == here else k.lower
            if k.kind == "step" and there not in seen and graph.levels[there].kind == "tread":
                seen.add(there)
                todo.append(there)
                out.update(graph.levels[there].surfaces)
    return out


def _step_apart(surface, height: float) -> float:
    """How far (m) the surface's heights (a ramp's from low to high end) lie from ``height``."""
    lo, hi = float(surface.z_low), float(surface.z_high)
    return max(0.0, lo - height, height - hi)


def _width(piece) -> float:
    """The width (m) of a convex shapely Polygon: its least extent across, over the directions
    normal to its edges (a convex polygon's narrowest strip lies along one of its edges)."""
    v = np.asarray(piece.exterior.coords, dtype=float)
    d = np.diff(v, axis=0)
    length = np.hypot(d[:, 0], d[:, 1])
    keep = length > 0.0
    d, a = d[keep] / length[keep, None], v[:-1][keep]
    rel = v[None, :, :] - a[:, None, :]  # (edges, vertices, 2)
    across = np.abs(d[:, None, 0] * rel[..., 1] - d[:, None, 1] * rel[..., 0])
    return float(across.max(axis=1).min()) if len(d) else 0.0


def _convex_pieces(poly) -> list:
    """``poly`` (a shapely Polygon) cut into convex polygons: itself if convex, else its
    constrained Delaunay triangles merged pairwise while each union stays convex."""
    import shapely  # deferred: see openings_of

    if poly.is_empty or poly.area <= 0.0:
        return []
    poly = poly.simplify(0.0)
    if poly.area >= poly.convex_hull.area * (1.0 - _CONVEX_TOL) and not poly.interiors:
        return [poly]
    pieces = list(shapely.constrained_delaunay_triangles(poly).geoms)
    merged = True
    while merged:
        merged = False
        for a in range(len(pieces)):
            for b in range(a + 1, len(pieces)):
                if pieces[a].intersection(pieces[b]).length <= 0.0:
                    continue  # no shared edge
                union = shapely.union(pieces[a], pieces[b]).simplify(0.0)
                if union.geom_type == "Polygon" and union.area >= union.convex_hull.area * (
                    1.0 - _CONVEX_TOL
                ):
                    pieces[a] = union
                    del pieces[b]
                    merged = True
                    break
            if merged:
                break
    return pieces
