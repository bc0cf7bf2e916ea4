"""A winder stair as a crossing of the route over levels (issue 47).

A conforming winder (:func:`mjwalk.plan.windercross.winder_crossings`: DIN 18065 met on its
walk line) becomes a :class:`WinderWay`, a :class:`~mjwalk.plan.levelroute.Crossing` of kind
``"winder"`` laid out along a bent axis: the walk line from the lower stance through each
nosing's middle to the upper stance, extended beyond the stances along the first and last
nosing's normals. So the route over levels (:func:`mjwalk.plan.levelsearch.level_route`) takes
it as it takes a straight flight: its stances are route nodes, its riser limit
(:meth:`~mjwalk.plan.levelroute.Crossing.fits`) and headroom
(:func:`~mjwalk.plan.levelroute.crossing_headroom`, over its walk line) are checked, a level
walk to it ends at its line-up point a step length before its stance
(:func:`~mjwalk.plan.levelcross.approach_point`), and the walk record counts its steps onto
and off its treads as stairs (:func:`mjwalk.plan.levelstitch.step_kinds`). A walker whose foot
some tread of it holds nowhere within its walk zone, not even
:data:`~mjwalk.world.norms.MIN_TREAD_SHARE` of it hanging over the nosing
(:func:`mjwalk.plan.windercross.tread_foot`; a straight flight's rule:
:mod:`mjwalk.plan.treadshare`), does not take it (:func:`foot_refusal`), and a route refused
names why (:func:`winder_notes`).

The walk over it (:func:`winder_cross_walk`) arrives already walking, as over a straight
flight (:func:`mjwalk.plan.levelcross.cross_walk`'s ``lead_in``): level steps from where the
level walk ended along the first nosing's normal into the footfall before it, then the
winder's footfalls (:func:`mjwalk.plan.windercross.winder_footfalls`), feet alternating with
the step that brought the walker there. Metres, seconds, radians, world frame, z up, yaw from +x.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace

import numpy as np

from mjwalk.anthropometry import leg_geometry
from mjwalk.conventions import other_side
from mjwalk.errors import PlanningError
from mjwalk.gait.walker import Walker
from mjwalk.plan.levelcross import DEFAULT_STEP_WIDTH, ENTRY_TURN, RISER_GAP, spot_turn
from mjwalk.plan.levelroute import Crossing, RouteLeg, crossing_headroom
from mjwalk.plan.turnsplit import wrap
from mjwalk.plan.turnsteps import turning_steps
from mjwalk.plan.walkpath import PathStep, WalkPath
from mjwalk.plan.windercross import (
    WinderCrossing,
    footfall_path,
    winder_crossings,
    winder_footfalls,
)
from mjwalk.plan.windercross import winder_time as footfalls_time
from mjwalk.world.levels import LevelGraph
from mjwalk.world.norms import HEAD_MARGIN


@dataclass(frozen=True, eq=False)
class WinderWay(Crossing):
    """A conforming winder as a route crossing (module docstring).

    Positions along its bent axis are metres along the walk line from the first nosing's
    middle (negative before it); :attr:`origin` is that middle and :attr:`axis` the heading
    into the winder at the end it is entered from (:func:`oriented`; up: the first nosing's
    normal).

    Attributes:
        winder: the winder.
        knots: (n + 3,) positions of the lower stance, each nosing's middle and the upper
            stance along the walk line, metres.
        vertices: (n + 3, 2) world xy of those points, metres.
    """

    winder: WinderCrossing | None = None
    knots: np.ndarray | None = None
    vertices: np.ndarray | None = None

    def point(self, s) -> np.ndarray:
        """World xy at positions along the walk line, beyond its stances along the first and
        last nosing's normals.

        Args:
            s: position(s) along the walk line, metres.

        Returns:
            (..., 2) world xy, metres.
        """
        assert self.winder is not None and self.knots is not None and self.vertices is not None
        s = np.asarray(s, dtype=float)
        k, v = self.knots, self.vertices
        xy = np.stack([np.interp(s, k, v[:, 0]), np.interp(s, k, v[:, 1])], axis=-1)
        below = np.minimum(s - k[0], 0.0)[..., None] * self.winder.normal(0)
        above = np.maximum(s - k[-1], 0.0)[..., None] * self.winder.normal(-1)
        return xy + below + above

    def height_at(self, s) -> np.ndarray:
        """Surface height under positions along the walk line: the lower level before the first
        nosing, each tread between its nosings, the upper level past the last.

        Args:
            s: position(s) along the walk line, metres.

        Returns:
            Heights, world metres, shaped as ``s``.
        """
        assert self.winder is not None and self.knots is not None
        nosing = self.knots[1:-1]
        return self.winder.z[np.searchsorted(nosing, np.asarray(s, dtype=float), side="right")]

    def riser_lines(self, floor_z: float) -> list[dict]:
        """Its nosings for the legs' swing (:meth:`mjwalk.plan.windercross.WinderCrossing.
        riser_lines`).

        Args:
            floor_z: the floor's world height, metres.

        Returns:
            One dict per nosing bottom up.
        """
        assert self.winder is not None
        return self.winder.riser_lines(floor_z)


def winder_way(w: WinderCrossing) -> WinderWay:
    """A conforming winder as a route crossing, entered from below (:func:`oriented`).

    Args:
        w: the winder.

    Returns:
        Its :class:`WinderWay`: stances :attr:`~WinderCrossing.clear` off the first and last
        nosing, its footfall track the middles of its walk-line treads.
    """
    middles = [e.mean(axis=0) for e in w.nosings]
    vertices = np.array([w.end(w.lower), *middles, w.end(w.upper)])
    gaps = np.linalg.norm(np.diff(vertices, axis=0), axis=1)
    knots = np.concatenate([[0.0], np.cumsum(gaps)]) - gaps[0]  # 0 at the first nosing
    nosing = knots[1:-1]
    track = np.concatenate(
        [[-0.5 * w.treads[0].tread], 0.5 * (nosing[:-1] + nosing[1:]),
         [nosing[-1] + 0.5 * w.treads[-1].tread]]
    )  # fmt: skip
    return WinderWay(
        "winder", w.lower, w.upper, w.risers, middles[0], w.normal(0), track, w.z.copy(),
        float(knots[0]), float(knots[-1]), float(w.z[0]), float(w.z[-1]), w.tread, 0.0,
        winder=w, knots=knots, vertices=vertices,
    )  # fmt: skip


def oriented(c: Crossing, direction: str) -> Crossing:
    """A crossing as walked ``direction``: a winder's :attr:`~Crossing.axis` the heading into
    it at the end it is entered from, so that its ``yaw`` up and ``yaw + pi`` down are the
    headings a walk lines up with (a straight flight's axis is one line: unchanged).

    Args:
        c: the crossing.
        direction: "up" or "down".

    Returns:
        The crossing (a winder entered from above: its axis the last nosing's normal).
    """
    if not isinstance(c, WinderWay) or c.winder is None or direction == "up":
        return c
    return replace(c, axis=c.winder.normal(-1))


def oriented_legs(legs: list[RouteLeg]) -> list[RouteLeg]:
    """A route's legs with each winder :func:`oriented` the way its leg walks it (every other
    leg as it was).

    Args:
        legs: the route's legs (:func:`mjwalk.plan.levelsearch.level_route`).

    Returns:
        The legs.
    """
    return [
        leg
        if leg.crossing is None or leg.crossing.kind != "winder"
        else replace(leg, crossing=oriented(leg.crossing, leg.direction))
        for leg in legs
    ]


def route_winders(graph: LevelGraph, clear: float) -> list[WinderWay]:
    """The conforming winders of a level graph as route crossings, kept on the graph per
    clearance.

    Args:
        graph: the scene's levels and links.
        clear: how far from the first and last nosing the walker stands, metres.

    Returns:
        One :class:`WinderWay` per conforming winder (empty in a scene without one).
    """
    cache = graph.__dict__.setdefault("_route_winders", {})
    key = round(clear, 6)
    if key not in cache:
        cache[key] = [winder_way(w) for w in winder_crossings(graph, clear)]
    return cache[key]


def foot_refusal(c: Crossing, walker: Walker) -> str | None:
    """Why a walker's foot stands on some tread of the winder nowhere within its walk zone (not
    even :data:`~mjwalk.world.norms.MIN_TREAD_SHARE` of it), up or down
    (:func:`mjwalk.plan.windercross.tread_foot`), else None (and None for any other crossing).

    Args:
        c: the crossing.
        walker: the walker (stature: its foot).

    Returns:
        The reason, one line, or None when the walker takes it.
    """
    if not isinstance(c, WinderWay) or c.winder is None:
        return None
    for direction in ("up", "down"):
        try:
            winder_footfalls(c.winder, direction, walker)
        except PlanningError as err:
            return str(err)
    return None


def way_in(c: Crossing, direction: str, yaw0: float) -> tuple[float, np.ndarray]:
    """The heading into a winder at the end it is entered from, and the headings of the steps
    on the spot a walker facing ``yaw0`` there turns first (:func:`~mjwalk.plan.levelcross.
    spot_turn`): the one source of both the walk's turn (:func:`winder_cross_walk`) and its
    time in the route's estimate (:func:`winder_time`).

    Args:
        c: the winder (:class:`WinderWay`).
        direction: "up" (along the first nosing's normal) or "down" (against the last's).
        yaw0: the walker's heading where the walk over it begins, radians.

    Returns:
        (the heading into it, radians, the nearer turn from ``yaw0``; (m,) the headings after
        each step on the spot, empty within :data:`~mjwalk.plan.levelcross.ENTRY_TURN`).
    """
    assert isinstance(c, WinderWay) and c.winder is not None
    w = c.winder
    nf = w.normal(0) if direction == "up" else -w.normal(-1)
    heading = yaw0 + wrap(math.atan2(nf[1], nf[0]) - yaw0)
    return heading, spot_turn(yaw0, heading)


def winder_time(c: Crossing, direction: str, walker: Walker, arrival: float | None = None) -> float:
    """How long the walk over a winder takes from its stance to standing at the other
    (:func:`mjwalk.plan.windercross.winder_time`), with the steps on the spot before it when
    the walker arrives facing ``arrival`` (:func:`way_in`, as :func:`winder_cross_walk` walks
    them: one level step time each).

    Args:
        c: the winder.
        direction: "up" or "down".
        walker: the walker.
        arrival: the heading the walker arrives at, radians, or None (no turn counted).

    Returns:
        Seconds.
    """
    assert isinstance(c, WinderWay) and c.winder is not None
    t = footfalls_time(c.winder, direction, walker)
    return t if arrival is None else t + winder_entry_time(c, direction, walker, arrival)


def winder_entry_time(c: Crossing, direction: str, walker: Walker, arrival: float) -> float:
    """How long a walker who arrives at a winder facing ``arrival`` turns on the spot before
    it: one level step time (:attr:`Walker.step_duration <mjwalk.gait.walker.Walker.
    step_duration>`) per step on the spot of :func:`way_in`, as :func:`winder_cross_walk`
    walks them (the last part of the turn taken by its first step).

    Args:
        c: the winder (:class:`WinderWay`).
        direction: "up" or "down".
        walker: the walker (its level step time).
        arrival: the walker's heading where the walk over it begins, radians.

    Returns:
        Seconds (0 for a turn within :data:`~mjwalk.plan.levelcross.ENTRY_TURN`).
    """
    return way_in(c, direction, arrival)[1].size * walker.step_duration


def winder_notes(graph: LevelGraph, clear: float, walker: Walker, max_riser: float) -> list[str]:
    """Why no winder of a scene serves a walker, one line each, for a route's refusal: the
    winders that break DIN 18065 on their walk line (:func:`mjwalk.plan.turnsteps.
    turning_steps`), and of the conforming ones each the walker does not take (a riser above
    its step-up limit, no headroom, its foot on no tread).

    Args:
        graph: the scene's levels and links.
        clear: how far from the first and last nosing the walker stands, metres.
        walker: the walker.
        max_riser: its step-up limit, metres.

    Returns:
        The lines (empty when there is no winder).
    """
    lines = [n for n in turning_steps(graph, clear) if "break DIN 18065" in n]
    for c in route_winders(graph, clear):
        where = f"the winder from L{c.lower} to L{c.upper}"
        if not c.fits(max_riser):
            lines.append(
                f"{where} has a {max(c.risers):.3f} m riser, above the walker's step-up limit "
                f"{max_riser:.2f} m"
            )
        elif crossing_headroom(graph, c) < walker.stature + HEAD_MARGIN:
            lines.append(f"{where} has no headroom for a {walker.stature:.2f} m walker")
        elif (why := foot_refusal(c, walker)) is not None:
            lines.append(f"{where} is not taken: {why}")
    return lines


def _lead_in(w: WinderCrossing, direction: str, xy0: np.ndarray, walker: Walker) -> np.ndarray:
    """Distances (m) off the entered nosing's middle, along its outward normal, of the level
    steps from ``xy0`` into the footfall before it (the last of them that footfall, none
    longer than the walker's step length; none when ``xy0`` is no farther off than it)."""
    g = leg_geometry(walker.stature)
    off = max(0.5 * w.tread, RISER_GAP + 0.5 * (g.foot_front + g.foot_back))
    m, out = (w.nosings[0].mean(axis=0), -w.normal(0))
    if direction == "down":
        m, out = w.nosings[-1].mean(axis=0), w.normal(-1)
    d0 = float(np.dot(xy0 - m, out))
    if d0 <= off + 1e-9:
        return np.empty(0)
    n = max(1, math.ceil((d0 - off) / walker.step_length - 1e-9))
    return d0 + (off - d0) * np.arange(1, n + 1) / n


def _feet(last: PathStep | None, xy0: np.ndarray, yaw0: float, z0: float, setup: tuple) -> dict:
    """Where each foot stands before the walk: as ``last`` left them, else side by side at
    ``xy0`` facing ``yaw0`` on the level at world height ``z0`` (``setup``: width, floor_z)."""
    width, floor_z = setup
    if last is not None:
        side = other_side(last.side)
        return {
            last.side: (np.asarray(last.foot, dtype=float), float(last.foot_z) + floor_z),
            side: (np.asarray(last.stance, dtype=float), float(last.stance_z) + floor_z),
        }
    left = np.array([-math.sin(yaw0), math.cos(yaw0)])
    return {
        name: (np.array([*(xy0 + sign * 0.5 * width * left), yaw0]), z0)
        for name, sign in (("left", 1.0), ("right", -1.0))
    }


def winder_cross_walk(
    c: Crossing,
    direction: str,
    walker: Walker,
    start: tuple[np.ndarray, float],
    last: PathStep | None,
    floor_z: float,
) -> WalkPath:
    """The walk over a winder from where the walker is (module docstring): steps on the spot
    first where it faces more than :data:`~mjwalk.plan.levelcross.ENTRY_TURN` off the way in
    (:func:`way_in`), level steps along the entered nosing's normal
    into the footfall before it (the walker led in, already walking, from the level walk's end
    at the line-up point; or from standing), then the winder's footfalls
    (:func:`mjwalk.plan.windercross.winder_footfalls`) to standing at the far stance.

    Args:
        c: the winder (:class:`WinderWay`).
        direction: "up" or "down".
        walker: the walker.
        start: the pelvis' world xy (metres) and heading (radians) where the walk begins.
        last: the step that brought the walker there (its landing foot stays the stance foot
            of the first step here), or None (standing with the feet side by side).
        floor_z: the floor's world height, metres.

    Returns:
        The walk from t = 0, heights above ``floor_z``; ``meta`` names the crossing
        ("winder") and its nosings' ``edges``.

    Raises:
        PlanningError: a tread has no place for the walker's foot, or a step turns too far.
    """
    assert isinstance(c, WinderWay) and c.winder is not None
    w = c.winder
    width = walker.step_width or DEFAULT_STEP_WIDTH
    xy0, yaw0 = np.asarray(start[0], dtype=float), float(start[1])
    nf = w.normal(0) if direction == "up" else -w.normal(-1)
    m = w.nosings[0].mean(axis=0) if direction == "up" else w.nosings[-1].mean(axis=0)
    z0 = float(w.z[0] if direction == "up" else w.z[-1])
    heading, spots = way_in(c, direction, yaw0)
    lead = _lead_in(w, direction, xy0, walker)
    swing = other_side(last.side) if last is not None else "left"
    k0 = len(spots) + len(lead)  # the steps before the winder's own
    on_tread = swing if k0 % 2 == 0 else other_side(swing)
    f = winder_footfalls(w, direction, walker, width, foot=other_side(on_tread))
    keep = int(np.argmax(f.tread >= 0))  # the footfall before the nosing is the lead-in's
    sign = np.where(np.arange(k0) % 2 == 0, 1.0, -1.0) * (1.0 if swing == "left" else -1.0)
    g = leg_geometry(walker.stature)
    back = 0.5 * (g.foot_front - g.foot_back)  # sole centre to ankle
    yaws = np.concatenate([spots, np.full(len(lead), heading)])
    h = np.stack([np.cos(yaws), np.sin(yaws)], axis=1)
    across = np.stack([-h[:, 1], h[:, 0]], axis=1)
    base = np.concatenate([np.repeat(xy0[None], len(spots), 0), m - lead[:, None] * nf])
    centre = base + (0.5 * width * sign)[:, None] * across
    yaw_all = np.unwrap(np.concatenate([[yaw0], yaws, f.yaw[keep:]]))[1:]
    ankle = np.concatenate([centre - back * h, f.ankle[keep:]]) if k0 else f.ankle[keep:]
    z = np.concatenate([np.full(k0, z0), f.z[keep:]])
    times = np.concatenate([np.full(k0, walker.step_duration), f.times[keep:]])
    turn = float(np.max(np.abs(np.diff(np.concatenate([[yaw0], yaw_all])))))
    if turn > ENTRY_TURN + 1e-6:
        raise PlanningError(f"winder walk turns {math.degrees(turn):.0f} deg in one step")
    feet = _feet(last, xy0, yaw0, z0, (width, floor_z))
    pelvis_z = 0.5 * (feet["left"][1] + feet["right"][1])
    track = (ankle, z, times, yaw_all)
    return footfall_path(c, direction, track, (feet, swing), (xy0, pelvis_z, yaw0), floor_z)
