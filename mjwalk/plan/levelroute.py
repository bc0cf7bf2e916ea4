"""Where a walker crosses between levels, and the route over levels a walk takes.

A :class:`Crossing` is a way from one level to another a walker walks in one go: a stair, a
ramp, or one or more single steps (step links through levels with no room to stand on between
them: single treads, or a step block too shallow for a stance, e.g. before a platform). It is
laid out along its axis (the horizontal direction up it, perpendicular to its first riser or up
the ramp): the stance where the walker stands before it on the lower level
(:attr:`Crossing.approach`), the footfalls on its treads or along the ramp, and the stance on
the upper level (:attr:`Crossing.exit`), both a body clearance from the level's edge so the
level planners start and end there. :func:`crossings` finds them in a
:class:`~mjwalk.world.levels.LevelGraph`; :func:`level_route` is the hierarchical route: a
Dijkstra over the start, the goal and the crossings' stances, joined on each level by the
obstacle-aware distance (the occupancy grid's distance field of the level's view,
:func:`mjwalk.world.levelview.level_view`) and across levels by the crossings a walker may take:
every riser at most the walker's step-up limit (:func:`step_up_limit`; a walker below a riser
takes the ramp), with the head's room over every footfall. Costs are seconds: level distance at
the walker's speed, crossings at their stair or ramp gait (:mod:`mjwalk.plan.levelcross`).
:func:`place_crossings` then walks each crossing of a route where along its width it is nearest
the walk, :func:`side_margin` from its sides. Metres, radians, world frame.
"""

from __future__ import annotations

import heapq
import math
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, replace

import numpy as np

from mjwalk.anthropometry import swing_half_width
from mjwalk.errors import PlanningError
from mjwalk.gait.walker import Walker
from mjwalk.plan.options import PlannerOptions
from mjwalk.plan.turnsteps import in_line, stepped_over
from mjwalk.world.levels import LevelGraph, LevelLink
from mjwalk.world.levelview import level_view
from mjwalk.world.norms import HEAD_MARGIN, MAX_RISER, ROUNDING_SLACK, SIDE_CLEARANCE
from mjwalk.world.workplace import Workplace

#: The tread ASR A1.8 §4.5 names particularly safe, 0.29 m (with a 0.17 m riser): a foot landing
#: on a level from a single step lands half of it beyond the riser, as it would on a tread.
SAFE_TREAD = 0.29
#: A walker's default step-up limit, metres: the highest riser of a building stair, 0.19 m
#: (DIN 18065:2020 Table 1; ASR A1.8 §4.5; :data:`mjwalk.world.norms.MAX_RISER`): every operator
#: is expected to climb what a workplace stair may ask. Walkers who cannot (rollator users: a
#: barrier-free route has no steps at all, DIN 18040-1 §4.3.2, "stufenlos") are given their own
#: limit (0: ramps only).
DEFAULT_STEP_UP = MAX_RISER


def step_up_limit(walker: Walker | None, limit: float | None = None) -> float:
    """The highest riser a walker steps up or down, metres.

    Args:
        walker: the walker (None: the reference adult).
        limit: the walker's own limit, metres (None: :data:`DEFAULT_STEP_UP`).

    Returns:
        The limit, metres (>= 0).

    Raises:
        PlanningError: a negative or non-finite limit.
    """
    del walker  # every profile shares the cited default; a profile's own limit is given
    value = DEFAULT_STEP_UP if limit is None else float(limit)
    if not (math.isfinite(value) and value >= 0.0):
        raise PlanningError(f"step-up limit {limit!r} m must be a number >= 0")
    return value


@dataclass(frozen=True, eq=False)
class Crossing:
    """A way between two levels, laid out along its axis (module docstring).

    Attributes:
        kind: "step" (one or more single steps), "stair" or "ramp".
        lower, upper: the levels it joins (indices in the graph's levels).
        risers: each riser's height bottom up, metres (a ramp: none).
        origin: world xy of the middle of its first riser or the ramp's foot, metres.
        axis: (2,) unit vector up it, horizontal.
        track: (k,) positions along the axis of the footfalls a flight has, metres from the
            origin: half a tread before the first riser, each tread's middle, half a tread past
            the last riser (steps and stairs); the ramp's foot and head (ramps).
        track_z: (k,) world heights of the surfaces at those footfalls, metres.
        approach, exit: where the walker stands before it on the lower level and after it on
            the upper, metres along the axis (a body clearance off the edges).
        z_lower, z_upper: the two levels' world heights, metres.
        tread: the stair's or steps' tread depth, metres (a ramp: its run).
        slope: a ramp's inclination, radians (0 otherwise).
        half_width: half the width of its first riser or the ramp's foot, metres (0: unknown,
            the walker keeps to its middle).
        sides: a ramp surface's own extent across the axis (right, left), metres left of its
            middle: wider than ``half_width`` where the lower level's longest contact with
            its foot is only part of it; (0, 0) for a flight or when unknown.
        centre: that middle once :meth:`shifted` moves the origin (None: the origin), metres.
    """

    kind: str
    lower: int
    upper: int
    risers: tuple[float, ...]
    origin: np.ndarray
    axis: np.ndarray
    track: np.ndarray
    track_z: np.ndarray
    approach: float
    exit: float
    z_lower: float
    z_upper: float
    tread: float
    slope: float
    half_width: float = 0.0
    sides: tuple[float, float] = (0.0, 0.0)
    centre: np.ndarray | None = None

    def point(self, s) -> np.ndarray:
        """World xy at positions along the axis.

        Args:
            s: position(s) along the axis from the origin, metres.

        Returns:
            (..., 2) world xy, metres.
        """
        return self.origin + np.multiply.outer(np.asarray(s, dtype=float), self.axis)

    def end(self, level: int) -> np.ndarray:
        """Where the walker stands at one end.

        Args:
            level: ``lower`` or ``upper``.

        Returns:
            (2,) world xy of the approach (lower) or exit (upper) stance, metres.
        """
        return self.point(self.approach if level == self.lower else self.exit)

    def height_at(self, s) -> np.ndarray:
        """Surface height under positions along the axis (world metres): the lower level before
        the first riser, each tread's between risers, the upper level past the last; on a ramp
        its plane between foot and head.

        Args:
            s: position(s) along the axis, metres.

        Returns:
            Heights, world metres, shaped as ``s``.
        """
        s = np.asarray(s, dtype=float)
        if self.kind == "ramp":
            run = float(self.track[-1])
            frac = np.clip(s / run, 0.0, 1.0)
            return self.z_lower + frac * (self.z_upper - self.z_lower)
        edges = 0.5 * (self.track[:-1] + self.track[1:])  # the risers between footfalls
        return self.track_z[np.searchsorted(edges, s, side="right")]

    @property
    def yaw(self) -> float:
        """The axis' heading, radians from +x (up the crossing)."""
        return float(math.atan2(self.axis[1], self.axis[0]))

    @property
    def middle(self) -> np.ndarray:
        """World xy of the middle of its first riser or foot, metres, however it is walked."""
        return self.origin if self.centre is None else self.centre

    def shifted(self, offset: float) -> Crossing:
        """The same crossing walked ``offset`` metres to the left of its middle (left of the
        axis): origin moved across the axis, everything along it unchanged; the crossing's
        width and sides stay about its ``centre``, the origin before the first shift.

        Args:
            offset: lateral shift, metres (positive: left of the way up).

        Returns:
            The shifted crossing (``self`` for 0).
        """
        if offset == 0.0:
            return self
        left = np.array([-self.axis[1], self.axis[0]])
        return replace(self, origin=self.origin + float(offset) * left, centre=self.middle)

    def riser_lines(self, floor_z: float) -> list[dict]:
        """Where its risers' edges lie, for the legs' swing over them
        (:func:`mjwalk.body.legs.edgeswing.true_edges`): each riser's edge line (the riser lies
        halfway between the footfall positions on either side, as :meth:`height_at` has it),
        its point and ``half_width`` about the crossing's :attr:`middle` however it is walked.

        Args:
            floor_z: the floor's world height, metres (heights are given above it).

        Returns:
            per riser bottom up: ``xy`` a point of its edge line (world, metres), ``normal``
            the unit axis across it, ``low``/``high`` the surfaces' heights below and above it
            (above the floor, metres), ``half_width`` (metres, 0: unknown); none for a ramp.
        """
        if self.kind == "ramp":
            return []
        return [
            {"xy": [float(v) for v in self.middle + float(s) * self.axis],
             "normal": [float(v) for v in self.axis],
             "low": float(self.track_z[i]) - floor_z, "high": float(self.track_z[i + 1]) - floor_z,
             "half_width": float(self.half_width)}
            for i, s in enumerate(0.5 * (self.track[:-1] + self.track[1:]))
        ]  # fmt: skip

    def fits(self, max_riser: float) -> bool:
        """Whether every riser is at most ``max_riser`` metres (a ramp always fits).

        Args:
            max_riser: the walker's step-up limit, metres.

        Returns:
            True when the walker takes it.
        """
        return all(r <= max_riser + ROUNDING_SLACK for r in self.risers)


def _length(seg) -> float:
    """A segment's length, metres."""
    return float(np.linalg.norm(np.asarray(seg[1], dtype=float) - np.asarray(seg[0], dtype=float)))


def _mid(seg) -> np.ndarray:
    return 0.5 * (np.asarray(seg[0], dtype=float) + np.asarray(seg[1], dtype=float))


def _axis_up(graph: LevelGraph, edge, upper_surfaces: Sequence[int]) -> np.ndarray:
    """The unit normal of ``edge`` pointing onto the surfaces above it."""
    a, b = (np.asarray(p, dtype=float) for p in edge)
    n = _normal(a, b)
    probe = _mid(edge) + 0.05 * n
    if any(bool(graph.surfaces[i].contains(probe)) for i in upper_surfaces):
        return n
    return -n


def _step_chains(graph: LevelGraph, clear: float) -> list[list[LevelLink]]:
    """Chains of step links from a level walked on over levels only stepped over to another."""
    passed = stepped_over(graph, clear)
    steps = [k for k in graph.links if k.kind == "step"]
    out = []
    for first in steps:
        if passed[first.lower]:
            continue
        todo = [[first]]
        while todo:
            chain = todo.pop()
            top = chain[-1].upper
            if not passed[top]:
                out.append(chain)
                continue
            if len(chain) >= len(steps):
                continue
            todo.extend(chain + [k] for k in steps if k.lower == top and in_line(chain[-1], k))
    return out


def _flight(graph: LevelGraph, edges, risers, lower: int, upper: int, kind: str, clear: float):
    """A step or stair crossing over ``edges`` (bottom up) with ``risers``."""
    above = _surfaces_above(graph, edges[0], lower)
    axis = _axis_up(graph, edges[0], above)
    origin = _mid(edges[0])
    d = np.array([float((_mid(e) - origin) @ axis) for e in edges])
    tread = float(np.mean(np.diff(d))) if len(d) > 1 else SAFE_TREAD
    track = np.concatenate([[d[0] - 0.5 * tread], 0.5 * (d[:-1] + d[1:]), [d[-1] + 0.5 * tread]])
    z0 = graph.levels[lower].height
    track_z = z0 + np.concatenate([[0.0], np.cumsum(risers)])
    return Crossing(
        kind, lower, upper, tuple(float(r) for r in risers), origin, axis, track, track_z,
        -clear, float(d[-1]) + clear, z0, graph.levels[upper].height, tread, 0.0,
        0.5 * _length(edges[0]),
    )  # fmt: skip


def _surfaces_above(graph: LevelGraph, edge, lower: int) -> list[int]:
    """The surfaces that touch ``edge`` and are not on level ``lower``."""
    probe = _mid(edge)[None]
    return [
        i for i, s in enumerate(graph.surfaces)
        if graph.level_of[i] != lower and float(s.footprint.signed_distance(probe)[0]) <= 0.03
    ]  # fmt: skip


def _ramp(graph: LevelGraph, link: LevelLink, clear: float) -> Crossing:
    """The crossing of a ramp link."""
    s = graph.surfaces[link.via[0]]
    axis = np.array([math.cos(s.uphill), math.sin(s.uphill)])
    origin = _mid(link.lower_edge)
    run = float((_mid(link.upper_edge) - origin) @ axis)
    z0, z1 = graph.levels[link.lower].height, graph.levels[link.upper].height
    left = np.array([-axis[1], axis[0]])
    across = (np.asarray(s.footprint.vertices, float)[:, :2] - origin) @ left
    return Crossing(
        "ramp", link.lower, link.upper, (), origin, axis, np.array([0.0, run]),
        np.array([z0, z1]), -clear, run + clear, z0, z1, run, float(link.slope or 0.0),
        0.5 * _length(link.lower_edge), (float(across.min()), float(across.max())),
    )  # fmt: skip


def crossings(graph: LevelGraph, clear: float) -> list[Crossing]:
    """The crossings of a level graph: its stairs and ramps, and its chains of single steps
    over tread levels (module docstring).

    Args:
        graph: the scene's levels and links.
        clear: how far from a level's edge the walker stands before and after a crossing,
            metres (the body radius and a grid cell).

    Returns:
        The crossings, stairs and ramps in the graph's order, then the step chains.
    """
    out = []
    for k in graph.links:
        if k.kind == "ramp":
            out.append(_ramp(graph, k, clear))
        elif k.kind == "stair":
            edges = [k.lower_edge]
            for j, i in enumerate(k.via):  # each tread's far edge is the next riser ...
                far = _riser_after(graph.surfaces[i], edges[-1])
                nxt = graph.surfaces[k.via[j + 1]] if j + 1 < len(k.via) else None
                above = k.upper_edge if nxt is None else nxt.footprint.vertices
                edges.append(_under_nosing(far, edges[-1], above))  # ... unless overhung
            out.append(_flight(graph, edges, k.risers, k.lower, k.upper, "stair", clear))
    for chain in _step_chains(graph, clear):
        edges = [c.lower_edge for c in chain]
        risers = [c.rise for c in chain]
        out.append(_flight(graph, edges, risers, chain[0].lower, chain[-1].upper, "step", clear))
    return out


def _riser_after(tread, below) -> tuple[tuple[float, float], tuple[float, float]]:
    """The far edge of a stair tread (the next riser's), parallel to the riser ``below``:
    ``below`` moved across the tread by its depth."""
    a, b = (np.asarray(p, dtype=float) for p in below)
    n = _normal(a, b)
    centre = np.asarray(tread.centre, dtype=float)
    off = float((centre - _mid(below)) @ n)
    shift = 2.0 * off * n  # the tread's centre lies half its depth beyond its near edge
    (x0, y0), (x1, y1) = a + shift, b + shift
    return ((float(x0), float(y0)), (float(x1), float(y1)))


def _normal(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """The unit normal (2,) of the segment a -> b, its direction turned 90 deg CCW."""
    d = (b - a) / max(float(np.linalg.norm(b - a)), 1e-12)
    return np.array([-d[1], d[0]])


#: Least overlap (m) of the next tread over a tread's far edge taken as a nosing's projection
#: (Unterschneidung): DIN 18065 §6.6 asks at least 30 mm of it on open stairs (no risers), and
#: the going (Auftritt) is measured nosing to nosing, without it (public summaries checked:
#: baunetzwissen.de "Unterschneidung", treppen-abc.com; the standard itself not); below a
#: millimetre the two edges are one line (a box stair's, up to its corners' rounding).
NOSING_OVERLAP = 1e-3


def _under_nosing(far, below, above) -> tuple[tuple[float, float], tuple[float, float]]:
    """The riser after a tread: its far edge ``far``, or, where the surface above (its points
    ``above``: the next tread's footprint, or the upper level's edge) reaches back over it by
    more than :data:`NOSING_OVERLAP` (an open stair's overlapping treads, DIN 18065's
    Unterschneidung), the nosing's line over it: a foot on the tread keeps off that, not the
    far edge under it (the toes under a 3 cm overlap caught the nosing as they lifted)."""
    f0, f1 = (np.asarray(p, dtype=float) for p in far)
    up = _mid(far) - _mid(below)
    n = _normal(f0, f1)
    n = n if float(up @ n) >= 0.0 else -n  # up the stair
    back = float(np.min((np.asarray(above, dtype=float) - _mid(far)) @ n))
    if back >= -NOSING_OVERLAP:
        return far
    (x0, y0), (x1, y1) = f0 + back * n, f1 + back * n
    return ((float(x0), float(y0)), (float(x1), float(y1)))


@dataclass(frozen=True)
class RouteLeg:
    """One part of a route over levels.

    Attributes:
        kind: "level" (a walk on one level) or "cross" (a crossing).
        level: the level walked on (a "level" leg) or the level left (a "cross" leg).
        start, end: world xy where it starts and ends, metres.
        crossing: the crossing (a "cross" leg), else None.
        direction: "up" or "down" (a "cross" leg), else "".
    """

    kind: str
    level: int
    start: np.ndarray
    end: np.ndarray
    crossing: Crossing | None = None
    direction: str = ""


def head_fits_crossing(graph: LevelGraph, c: Crossing, stature: float) -> bool:
    """Whether a walker's head has room over every footfall and stance of a crossing.

    Args:
        graph: the level graph.
        c: the crossing.
        stature: the walker's stature, metres.

    Returns:
        True when the free height at every point is at least stature plus
        :data:`mjwalk.world.norms.HEAD_MARGIN`.
    """
    return not crossing_headroom(graph, c) < stature + HEAD_MARGIN


def crossing_headroom(graph: LevelGraph, c: Crossing) -> float:
    """The least free height over a crossing's footfalls and stances: a walker's head fits
    (:func:`head_fits_crossing`) when stature plus margin is not above it, so it is measured
    once per crossing for every stature.

    Args:
        graph: the level graph.
        c: the crossing.

    Returns:
        Metres (inf when nothing is over it).
    """
    s = np.concatenate([[c.approach], c.track, [c.exit]])
    least = math.inf
    for p, z in zip(c.point(s), c.height_at(s), strict=True):
        i = graph.surface_at(p, float(z))
        if i is None:
            continue  # the edge between two surfaces: its neighbours decide
        least = min(least, float(graph.surfaces[i].free_height(p)))
    return least


def dijkstra(n: int, edges: Mapping[int, list[tuple[int, float]]], source: int, target: int):
    """Least-cost path in a small graph.

    Args:
        n: number of nodes.
        edges: for each node, its (neighbour, cost) pairs (asked for as nodes are popped).
        source: the first node's index.
        target: the last node's index.

    Returns:
        The nodes from source to target, or None when the target is unreachable; and the cost.
    """
    dist = [math.inf] * n
    prev = [-1] * n
    dist[source] = 0.0
    heap = [(0.0, source)]
    while heap:
        d, u = heapq.heappop(heap)
        if d > dist[u]:
            continue
        if u == target:
            break
        for v, w in edges.get(u, []):
            if d + w < dist[v]:
                dist[v], prev[v] = d + w, u
                heapq.heappush(heap, (d + w, v))
    if not math.isfinite(dist[target]):
        return None, math.inf
    path = [target]
    while path[-1] != source:
        path.append(prev[path[-1]])
    return path[::-1], dist[target]


def place_on_edge(legs: Sequence[RouteLeg], margin: float, step: float = 0.05) -> list[RouteLeg]:
    """Each crossing of a route walked where it is nearest the walk: along a wide stair, step
    or ramp the walker keeps to the side it comes from and goes to rather than its middle.

    The lateral offset (multiples of ``step`` from the middle, at most the crossing's half
    width less ``margin`` either way, so the body stays within its width) that makes the
    straight lines from the leg before it to its first stance and from its last stance to the
    leg after it shortest; the legs next to it start and end at the shifted stances.

    Args:
        legs: the route's legs (:func:`mjwalk.plan.levelplan.level_route`).
        margin: how far the walker's middle stays from a crossing's sides, metres (the body
            radius).
        step: the offsets' spacing, metres (the stances are goals whose fields are kept).

    Returns:
        The legs, each crossing shifted (:meth:`Crossing.shifted`) and its neighbours' ends
        moved with it.
    """
    out = list(legs)
    for k, leg in enumerate(out):
        c = leg.crossing
        if c is None or c.half_width - margin < step:
            continue
        room = math.floor((c.half_width - margin) / step + 1e-9)
        before = out[k - 1].start if k > 0 else leg.start
        after = out[k + 1].end if k + 1 < len(out) else leg.end
        left = np.array([-c.axis[1], c.axis[0]])
        offsets = step * np.arange(-room, room + 1)
        near = np.abs(offsets) + 0.0  # ties: the middle
        cost = [
            float(
                np.hypot(*(leg.start + o * left - before)) + np.hypot(*(after - leg.end - o * left))
            )
            + 1e-6 * n
            for o, n in zip(offsets, near, strict=True)
        ]
        shifted = c.shifted(float(offsets[int(np.argmin(cost))]))
        a, b = shifted.end(leg.level), shifted.end(c.upper if leg.level == c.lower else c.lower)
        out[k] = replace(leg, start=a, end=b, crossing=shifted)
        if k > 0:
            out[k - 1] = replace(out[k - 1], end=a)
        if k + 1 < len(out):
            out[k + 1] = replace(out[k + 1], start=b)
    return out


def place_crossings(
    workplace: Workplace, legs: list[RouteLeg], options: PlannerOptions, head: float
) -> list[RouteLeg]:
    """The route's crossings walked nearest the walk (:func:`mjwalk.plan.levelroute.
    place_on_edge`) where every moved stance keeps the body radius in its level's view and the
    head has room over the moved crossing. The walker's middle keeps :func:`side_margin` from
    a crossing's sides: its swinging arms clear a stair's walls.

    Args:
        workplace: the scene.
        legs: the route (:func:`level_route`).
        options: the planner's options (the body radius).
        head: the walker's head height above a level (stature plus
            :data:`mjwalk.world.norms.HEAD_MARGIN`), metres.

    Returns:
        The legs with the crossings moved, or ``legs`` (the crossings' middles) when a moved
        one does not fit.
    """
    cache = workplace.__dict__.setdefault("_placed_routes", {})  # walks repeat their routes
    key = (
        tuple(
            (leg.kind, leg.level, *np.round(leg.start, 6), *np.round(leg.end, 6), id(leg.crossing))
            for leg in legs
        ),
        options.radius,
        round(head, 3),
    )
    if key not in cache:
        cache[key] = _placed(workplace, legs, options, head)
    return cache[key]


def _placed(workplace: Workplace, legs: list[RouteLeg], options, head: float) -> list[RouteLeg]:
    """:func:`place_crossings` without its cache."""
    placed = place_on_edge(legs, side_margin(head - HEAD_MARGIN, options.radius))
    for leg in placed:
        c = leg.crossing
        if c is None:
            continue
        for lv in (c.lower, c.upper):
            view = level_view(workplace, lv, head)
            if float(view.walk_clearance(c.end(lv))) < options.radius:
                return legs
        if not head_fits_crossing(workplace.levels, c, head - HEAD_MARGIN):
            return legs
    return placed


def side_margin(stature: float, radius: float) -> float:
    """How far a walker's middle stays from the sides of a stair, ramp or step it walks on:
    half its width with the arms swinging (:func:`mjwalk.anthropometry.swing_half_width`) and
    the room people leave to a stair's wall or the side of its treads
    (:data:`mjwalk.world.norms.SIDE_CLEARANCE`), at least the body radius.

    Args:
        stature: the walker's stature, metres.
        radius: the planner's body radius, metres.

    Returns:
        The margin, metres (0.50 m at 1.75 m: a 1.0 m flight is walked in its middle).
    """
    return max(float(radius), swing_half_width(stature) + SIDE_CLEARANCE)
