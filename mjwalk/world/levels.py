"""Levels and the links between them: the graph a planner walks over several heights.

:func:`level_graph` groups the walk surfaces (:mod:`mjwalk.world.surfaces`) that touch at the
same height (within ``norms.LEVEL_TOLERANCE``) into :class:`Level` s, and joins levels by
:class:`LevelLink` s where a walker crosses from one to another:

- a **step** where an edge of a higher surface meets a lower one at most ``max_riser`` below;
- a **ramp** from the level its low end meets to the level its high end meets (only the ends:
  stepping off a ramp's side is a step link's business and is not linked here);
- a **stair** for a run of at least ``norms.MIN_STAIR_RISERS`` risers over single treads whose
  risers and treads are regular (within ``norms.STAIR_TOLERANCE``) and within the cited limits
  (risers ``norms.MIN_RISER``-``MAX_RISER``, treads ``MIN_TREAD``-``MAX_TREAD``, step rule
  ``norms.STEP_RULE``); it replaces the step links it is made of. Fewer or irregular risers stay
  steps. A tread that meets the next level in several stretches (a landing or a pit's rim
  written as several boxes) goes on at the riser in line with the flight (:func:`_riser_ahead`).

Each link names where it is crossed: a segment on the lower level (a step's riser edge, a ramp's
foot, a stair's first riser) and one on the upper. Metres, radians, world xy.
"""

from __future__ import annotations

import itertools
import math
from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np

from mjwalk.errors import InputError
from mjwalk.world.contacts import Contact, level_contacts, surface_contacts
from mjwalk.world.levelgroups import group_levels
from mjwalk.world.norms import (
    CONTACT_GAP,
    EXPOSED_MIN,
    HEAD_MARGIN,
    LEVEL_TOLERANCE,
    MAX_RISER,
    MAX_TREAD,
    MIN_RISER,
    MIN_STAIR_RISERS,
    MIN_TREAD,
    ROUNDING_SLACK,
    STAIR_TOLERANCE,
    STEP_RULE,
)
from mjwalk.world.walksurface import Segment, WalkSurface
from mjwalk.world.walksurface import head_fits as surface_head_fits

#: Kinds of link between levels.
LINK_KINDS = ("step", "ramp", "stair")


@dataclass(frozen=True)
class LevelOptions:
    """How surfaces become levels and links. Checked on construction (InputError, one line).

    Attributes:
        level_tol: touching surfaces this close in height are one level, metres
            (``norms.LEVEL_TOLERANCE``, 4 mm).
        contact_gap: widest gap between touching edges, metres (``norms.CONTACT_GAP``).
        max_riser: highest step linked, metres (``norms.MAX_RISER``, 0.19 m).
        riser_range, tread_range: (least, greatest) riser and tread of a stair, metres
            (DIN 18065: 0.14-0.19 m, 0.26-0.37 m).
        step_rule: (least, greatest) 2 * riser + tread of a stair, metres (0.59-0.65 m).
        stair_tol: most a stair's risers and treads may differ from the first, metres (5 mm).
        min_stair_risers: fewest risers of a stair (3).
    """

    level_tol: float = LEVEL_TOLERANCE
    contact_gap: float = CONTACT_GAP
    max_riser: float = MAX_RISER
    riser_range: tuple[float, float] = (MIN_RISER, MAX_RISER)
    tread_range: tuple[float, float] = (MIN_TREAD, MAX_TREAD)
    step_rule: tuple[float, float] = STEP_RULE
    stair_tol: float = STAIR_TOLERANCE
    min_stair_risers: int = MIN_STAIR_RISERS

    def __post_init__(self) -> None:
        for name in ("level_tol", "contact_gap", "max_riser", "stair_tol"):
            v = getattr(self, name)
            if not (math.isfinite(v) and v > 0):
                raise InputError(f"level option {name}={v} m must be a positive number")
        if self.max_riser <= self.level_tol:
            raise InputError(f"max_riser {self.max_riser} m must exceed level_tol {self.level_tol}")
        for name in ("riser_range", "tread_range", "step_rule"):
            lo, hi = getattr(self, name)
            if not (math.isfinite(lo) and math.isfinite(hi) and 0 < lo <= hi):
                raise InputError(f"level option {name}={(lo, hi)} m must be 0 < low <= high")
        if int(self.min_stair_risers) < 2:
            raise InputError(f"min_stair_risers {self.min_stair_risers} must be at least 2")


@dataclass(frozen=True)
class Level:
    """Surfaces at one height that touch.

    Attributes:
        index: its place in :attr:`LevelGraph.levels`.
        kind: "floor" (holds the floor), "tread" (one tread alone) or "platform".
        height: area-weighted height of its surfaces, world metres.
        surfaces: indices of its surfaces in :attr:`LevelGraph.surfaces`.
        area: their total area, square metres.
        lowest_ceiling: least free height over it that some walker passes under, metres
            (inf: none; :attr:`mjwalk.world.walksurface.WalkSurface.lowest_ceiling`).
    """

    index: int
    kind: str
    height: float
    surfaces: tuple[int, ...]
    area: float
    lowest_ceiling: float


@dataclass(frozen=True)
class LevelLink:
    """Where a walker gets from one level to another.

    Attributes:
        kind: "step", "ramp" or "stair".
        lower, upper: the levels it joins (indices in :attr:`LevelGraph.levels`).
        rise: height from the lower level to the upper, metres.
        risers: each riser's height, bottom up, metres (a step: one; a ramp: none).
        tread: a stair's mean tread depth, metres (None otherwise).
        slope: a ramp's inclination, radians (None otherwise).
        via: the surfaces walked between the levels, bottom up (a ramp's, a stair's treads;
            none for a step), indices in :attr:`LevelGraph.surfaces`.
        lower_edge, upper_edge: where it leaves the lower level and reaches the upper, world xy
            segments (a step: both its riser's edge).
    """

    kind: str
    lower: int
    upper: int
    rise: float
    risers: tuple[float, ...]
    tread: float | None
    slope: float | None
    via: tuple[int, ...]
    lower_edge: Segment
    upper_edge: Segment


@dataclass(frozen=True)
class LevelGraph:
    """The levels of a scene and their links.

    Attributes:
        surfaces: the walk surfaces (:func:`mjwalk.world.surfaces.find_walk_surfaces`).
        levels: the levels, the floor's first, then by height.
        links: the links, steps then ramps then stairs.
        level_of: for each surface, its level's index (None for a ramp).
        notes: why a ramp links no levels (:func:`_ramp_notes`), one line each.
    """

    surfaces: tuple[WalkSurface, ...]
    levels: tuple[Level, ...]
    links: tuple[LevelLink, ...]
    level_of: tuple[int | None, ...]
    notes: tuple[str, ...] = ()

    def links_of(self, level: int) -> list[LevelLink]:
        """The links that start or end at a level.

        Args:
            level: the level's index.

        Returns:
            Its links, in :attr:`links` order.
        """
        return [k for k in self.links if level in (k.lower, k.upper)]

    def surface_at(self, xy: Sequence[float], z: float | None = None) -> int | None:
        """The surface a point stands on: among the surfaces under ``xy`` with room above them
        there (more than :data:`~mjwalk.world.norms.EXPOSED_MIN` free: a floor box written a
        tenth of a millimetre over the plane under a pit leaves the plane no standing room), the
        one nearest height ``z`` (the highest when None).

        Args:
            xy: world point (x, y), metres.
            z: the point's height (a site's), world metres, or None.

        Returns:
            The surface's index, or None when no surface is under the point.
        """
        p = np.asarray(xy, dtype=float)[:2]
        best, key = None, math.inf
        for i, s in enumerate(self.surfaces):
            if not bool(s.contains(p)) or float(s.free_height(p)) <= EXPOSED_MIN:
                continue
            h = float(s.height_at(p))
            k = -h if z is None else abs(h - z)
            if k < key:
                best, key = i, k
        return best

    def head_fits(
        self, xy: Sequence[float], z: float | None, stature: float, margin: float = HEAD_MARGIN
    ) -> bool:
        """Whether a walker standing at a point has room for the head.

        Args:
            xy: world point (x, y), metres.
            z: the point's height, world metres (None: the highest surface there).
            stature: the walker's body height, metres.
            margin: room added to the stature, metres (:data:`mjwalk.world.norms.HEAD_MARGIN`).

        Returns:
            True when the free height there is at least stature plus margin; False also when no
            surface is under the point.
        """
        i = self.surface_at(xy, z)
        if i is None:
            return False
        return bool(
            surface_head_fits(self.surfaces[i], np.asarray(xy, dtype=float)[:2], stature, margin)
        )

    def reachable(self, start: int = 0, max_riser: float | None = None) -> frozenset[int]:
        """The levels reachable from a level over links a walker takes.

        Args:
            start: the level to start from (the floor's is 0).
            max_riser: the highest riser the walker steps (None: every link); ramps are taken.

        Returns:
            The indices of the levels reachable, ``start`` included.
        """
        seen, todo = {start}, [start]
        while todo:
            cur = todo.pop()
            for k in self.links_of(cur):
                if max_riser is not None and any(r > max_riser + ROUNDING_SLACK for r in k.risers):
                    continue
                nxt = k.upper if k.lower == cur else k.lower
                if nxt not in seen:
                    seen.add(nxt)
                    todo.append(nxt)
        return frozenset(seen)


def _make_levels(surfaces: Sequence[WalkSurface], groups: list[list[int]]) -> list[Level]:
    """The levels of the groups: the floor's first, then by height and first name."""

    def key(g: list[int]) -> tuple:
        has_floor = any(surfaces[i].kind == "floor" for i in g)
        return (not has_floor, min(surfaces[i].z for i in g), surfaces[g[0]].name)

    out = []
    for k, g in enumerate(sorted(groups, key=key)):
        area = sum(surfaces[i].area for i in g)
        height = sum(surfaces[i].z * surfaces[i].area for i in g) / area
        kinds = {surfaces[i].kind for i in g}
        kind = (
            "floor"
            if "floor" in kinds
            else ("tread" if kinds == {"tread"} and len(g) == 1 else "platform")
        )
        ceiling = min(surfaces[i].lowest_ceiling for i in g)
        out.append(Level(k, kind, float(height), tuple(sorted(g)), float(area), float(ceiling)))
    return out


def _step_links(
    surfaces: Sequence[WalkSurface], contacts: list[Contact], level_of: list[int | None], tol: float
) -> list[LevelLink]:
    """A step link for each contact from a higher horizontal surface down to a lower one."""
    out = []
    for c in contacts:
        la, lb = level_of[c.a], level_of[c.b]
        if la is None or lb is None or la == lb or c.rise_range[1] >= -tol:
            continue
        riser = -c.rise
        out.append(LevelLink("step", lb, la, riser, (riser,), None, None, (), c.edge, c.edge))
    return out


def _ramp_links(
    surfaces: Sequence[WalkSurface], contacts: list[Contact], level_of: list[int | None], tol: float
) -> list[LevelLink]:
    """A ramp link for each ramp whose low end meets one level and whose high end another."""
    out = []
    for r, s in enumerate(surfaces):
        if not s.is_ramp:
            continue
        ends: dict[str, Contact] = {}
        for c in contacts:
            if c.a != r or level_of[c.b] is None or max(map(abs, c.rise_range)) > tol:
                continue
            z = float(np.mean(s.height_at(np.asarray(c.edge))))
            end = "low" if abs(z - s.z_low) <= tol else ("high" if abs(z - s.z_high) <= tol else "")
            if end and (end not in ends or c.length > ends[end].length):
                ends[end] = c
        if "low" in ends and "high" in ends:
            lo, hi = ends["low"], ends["high"]
            lower, upper = level_of[lo.b], level_of[hi.b]
            assert lower is not None and upper is not None
            rise = s.z_high - s.z_low
            out.append(
                LevelLink("ramp", lower, upper, rise, (), None, s.slope, (r,), lo.edge, hi.edge)
            )
    return out


def _line_distance(seg: Segment, other: Segment) -> float:
    """Distance from ``other``'s midpoint to the line through ``seg``, metres."""
    a, b = np.asarray(seg[0]), np.asarray(seg[1])
    m = 0.5 * (np.asarray(other[0]) + np.asarray(other[1]))
    d = (b - a) / max(float(np.linalg.norm(b - a)), 1e-12)
    return float(abs((m - a) @ np.array([-d[1], d[0]])))


def _is_stair(chain: list[LevelLink], options: LevelOptions) -> bool:
    """Whether a chain of step links is a stair: enough regular risers and treads, in limits."""
    if len(chain) < options.min_stair_risers:
        return False
    risers = np.array([k.rise for k in chain])
    treads = np.array(
        [_line_distance(a.upper_edge, b.lower_edge) for a, b in itertools.pairwise(chain)]
    )
    (r0, r1), (t0, t1), (s0, s1) = options.riser_range, options.tread_range, options.step_rule
    tol = options.stair_tol
    rule = 2 * risers[:-1] + treads
    return bool(
        np.ptp(risers) <= tol
        and np.ptp(treads) <= tol
        and np.all((risers >= r0 - ROUNDING_SLACK) & (risers <= r1 + ROUNDING_SLACK))
        and np.all((treads >= t0 - ROUNDING_SLACK) & (treads <= t1 + ROUNDING_SLACK))
        and np.all((rule >= s0 - ROUNDING_SLACK) & (rule <= s1 + ROUNDING_SLACK))
    )


def _riser_ahead(
    prev: LevelLink, ups: list[LevelLink], options: LevelOptions
) -> tuple[LevelLink | None, list[LevelLink]]:
    """Of several step links up from a tread, the riser the flight goes on, and every link that
    riser is made of.

    A tread's next riser is parallel to its previous one (both its ends equally far from the
    previous riser's line, within ``stair_tol``: a regular tread, DIN 18065) and the nearest
    such edge; the next level may meet it in several stretches (a pit's rim written as several
    floor boxes, issue 47's scanned hall 1117; a scanned deck's box 1 cm behind the inferred top
    tread written as part of it, hall 1038), which are one riser when they lie within
    ``contact_gap`` of the nearest (surfaces that close touch) and rise to the same level. The
    longest of its stretches within ``stair_tol`` of the nearest is where the flight is crossed
    (so the tread is measured to the riser's front).

    Args:
        prev: the step link onto the tread.
        ups: the step links up from the tread, of the flight's riser.
        options: the stair tolerance.

    Returns:
        (the link the flight takes, the links of its riser), or (None, []) when no edge is in
        line with the flight or the in-line edges rise to different levels.
    """

    def depth(k: LevelLink) -> tuple[float, float]:  # its ends' distances (a point: (p, p))
        a, b = k.lower_edge
        return _line_distance(prev.upper_edge, (a, a)), _line_distance(prev.upper_edge, (b, b))

    inline = [k for k in ups if abs(np.subtract(*depth(k))) <= options.stair_tol]
    if not inline:
        return None, []
    near = min(float(np.mean(depth(k))) for k in inline)
    riser = [k for k in inline if float(np.mean(depth(k))) <= near + options.contact_gap]
    if len({k.upper for k in riser}) != 1:
        return None, []
    front = [k for k in riser if float(np.mean(depth(k))) <= near + options.stair_tol]
    return max(front, key=lambda k: _segment_length(k.lower_edge)), riser


def _first_riser(
    first: LevelLink, steps: list[LevelLink], options: LevelOptions
) -> list[LevelLink]:
    """The stretches of a flight's first riser: the step links from its bottom onto its first
    tread in line with ``first`` (both ends within ``stair_tol`` of its line); a floor written
    as boxes round a pit meets it in several (hall 1162: a 0.55 m one was a step of its own).

    Args:
        first: the step link the flight starts with.
        steps: all step links.
        options: the stair tolerance.

    Returns:
        ``first`` and the other stretches, in ``steps``' order.
    """

    def in_line(k: LevelLink) -> bool:
        a, b = k.lower_edge
        return (
            max(_line_distance(first.lower_edge, (a, a)), _line_distance(first.lower_edge, (b, b)))
            <= options.stair_tol
        )

    return [
        k
        for k in steps
        if k is first or (k.lower == first.lower and k.upper == first.upper and in_line(k))
    ]


def _segment_length(seg: Segment) -> float:
    """A segment's length, metres."""
    return float(np.linalg.norm(np.subtract(seg[1], seg[0])))


def _stairs(
    steps: list[LevelLink], levels: list[Level], options: LevelOptions
) -> list[tuple[list[LevelLink], list[LevelLink]]]:
    """The chains of step links that are stairs: from a non-tread level over single treads, each
    step up near the previous riser, to a non-tread level; where a tread meets the next level on
    several edges, the one in line with the flight (:func:`_riser_ahead`). Each chain comes with
    the step links it replaces (its own and the other stretches of its risers)."""
    up: dict[int, list[LevelLink]] = {}
    for k in steps:
        up.setdefault(k.lower, []).append(k)
    out = []
    used: set[int] = set()
    for first in steps:
        if levels[first.lower].kind == "tread" or levels[first.upper].kind != "tread":
            continue
        if first.upper in used:
            continue
        chain, replaced = [first], [first]
        while levels[chain[-1].upper].kind == "tread":
            nxt = [
                k
                for k in up.get(chain[-1].upper, [])
                if abs(k.rise - chain[-1].rise) <= options.stair_tol
                and _line_distance(chain[-1].upper_edge, k.lower_edge) > options.contact_gap
            ]
            if len(nxt) == 1:
                chain.append(nxt[0])
                replaced.append(nxt[0])
                continue
            ahead, riser = _riser_ahead(chain[-1], nxt, options)
            if ahead is None:
                break
            chain.append(ahead)
            replaced += riser
        if levels[chain[-1].upper].kind != "tread" and _is_stair(chain, options):
            stretches = _first_riser(first, steps, options)
            chain[0] = max(stretches, key=lambda k: _segment_length(k.lower_edge))
            replaced += [k for k in stretches if k is not first]
            out.append((chain, replaced))
            used.update(k.upper for k in chain[:-1])
    return out


def level_graph(surfaces: Sequence[WalkSurface], options: LevelOptions | None = None) -> LevelGraph:
    """The levels of a set of walk surfaces and the steps, ramps and stairs between them.

    Args:
        surfaces: the walk surfaces, the floor first
            (:func:`mjwalk.world.surfaces.find_walk_surfaces`).
        options: tolerances and stair limits (None: the cited defaults).

    Returns:
        The level graph.

    Raises:
        InputError: no surfaces.
    """
    options = options or LevelOptions()
    if not surfaces:
        raise InputError(
            "level_graph: no walk surfaces (find_walk_surfaces gives the floor at least)"
        )
    contacts = surface_contacts(surfaces, options.contact_gap, options.max_riser)
    levels = _make_levels(surfaces, group_levels(surfaces, contacts, options.level_tol))
    level_of: list[int | None] = [None] * len(surfaces)
    for lv in levels:
        for i in lv.surfaces:
            level_of[i] = lv.index
    steps = _step_links(surfaces, contacts, level_of, options.level_tol)
    ramp_ends = level_contacts(surfaces, level_of, options.contact_gap, options.max_riser)
    ramps = _ramp_links(surfaces, ramp_ends, level_of, options.level_tol)
    stairs = []
    for chain, replaced in _stairs(steps, levels, options):
        treads = tuple(levels[k.upper].surfaces[0] for k in chain[:-1])
        depth = float(
            np.mean(
                [_line_distance(a.upper_edge, b.lower_edge) for a, b in itertools.pairwise(chain)]
            )
        )
        risers = tuple(k.rise for k in chain)
        stairs.append(
            LevelLink(
                "stair", chain[0].lower, chain[-1].upper, float(sum(risers)), risers, depth, None,
                treads, chain[0].lower_edge, chain[-1].upper_edge,
            )
        )  # fmt: skip
        steps = [k for k in steps if all(k is not c for c in replaced)]
    notes = _ramp_notes(surfaces, ramp_ends, level_of, options.level_tol, ramps)
    return LevelGraph(
        tuple(surfaces), tuple(levels), tuple(steps + ramps + stairs), tuple(level_of), notes
    )


def _ramp_notes(
    surfaces: Sequence[WalkSurface],
    contacts: list[Contact],
    level_of: list[int | None],
    tol: float,
    ramps: list[LevelLink],
) -> tuple[str, ...]:
    """Why each ramp that links no levels does not: the levels its lowest and highest edge
    contacts meet and the largest lip there (a ramp's end must meet its level within ``tol``,
    ASR A1.5/1,2's 4 mm: no trip point; a ramp with a cross-slope, which DIN 18040-1 §4.3.8
    rules out, has lips at both ends)."""
    linked = {k.via[0] for k in ramps}
    out = []
    for r, s in enumerate(surfaces):
        if not s.is_ramp or r in linked:
            continue
        ends = [
            (float(np.mean(s.height_at(np.asarray(c.edge)))), max(map(abs, c.rise_range)), c.b)
            for c in contacts
            if c.a == r and level_of[c.b] is not None
        ]
        if not ends:
            out.append(f"ramp {s.name!r} meets no level at either end")
            continue
        low, high = min(ends), max(ends)
        said = [
            f"its {what} end meets L{level_of[b]} with a lip of up to {1000 * lip:.1f} mm"
            for what, (_, lip, b) in (("low", low), ("high", high))
            if lip > tol and (what == "low" or high is not low)
        ]
        why = ", ".join(said) if said else "its ends do not meet two levels"
        out.append(
            f"ramp {s.name!r} links no levels: {why} (a ramp's ends must meet their levels "
            f"within {1000 * tol:.0f} mm: ASR A1.5/1,2, no trip points; DIN 18040-1: no "
            "cross-slope)"
        )
    return tuple(out)


def describe_levels(graph: LevelGraph) -> str:
    """A printout of the levels and links, one line each (for ``mjwalk plan``/``scan``).

    Args:
        graph: the level graph.

    Returns:
        The text, lines separated by newlines, no trailing newline.
    """
    lines = [f"levels: {len(graph.levels)}, links: {len(graph.links)}"]
    for lv in graph.levels:
        names = ", ".join(graph.surfaces[i].name for i in lv.surfaces)
        ceil = "" if math.isinf(lv.lowest_ceiling) else f", ceiling {lv.lowest_ceiling:.2f} m"
        lines.append(
            f"  L{lv.index} {lv.kind:<8} {lv.height:+.3f} m {lv.area:7.2f} m2  {names}{ceil}"
        )
    links: dict[str, int] = {}  # a round podium's top is a polygon: one step per edge, one line
    for k in graph.links:
        if k.kind == "step":
            what = f"riser {k.rise:.3f} m"
        elif k.kind == "ramp":
            slope = k.slope or 0.0
            pct = 100 * math.tan(slope)
            what = f"slope {math.degrees(slope):.2f} deg ({pct:.1f} %), rise {k.rise:.3f} m"
        else:
            r = float(np.mean(k.risers))
            g = k.tread or 0.0
            what = f"{len(k.risers)} risers x {r:.3f} m, tread {g:.3f} m (2h+g {2 * r + g:.3f} m)"
        line = f"  {k.kind:<5} L{k.lower} -> L{k.upper}  {what}"
        links[line] = links.get(line, 0) + 1
    lines += [line if n == 1 else f"{line}  ({n} edges)" for line, n in links.items()]
    lines += [f"  note: {n}" for n in graph.notes]
    return "\n".join(lines)
