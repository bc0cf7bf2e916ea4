"""A walk over a winder or spiral stair along its walk line (DIN 18065; issue 47).

A stair whose step edges (nosings) turn from one tread to the next
(:func:`mjwalk.plan.turnsteps.turned_chains`) and whose treads meet DIN 18065's rules on its
walk line (:mod:`mjwalk.world.walkline`) is a :class:`WinderCrossing` (:func:`winder_crossings`).
It is walked step over step as a straight flight is (:mod:`mjwalk.plan.levelcross`), but along
the walk line: one footfall per tread at the middle of the tread's walk-line chord (between the
line's crossings of its two nosings), the foot turned along the chord (the walk line's tangent
there: the chord of an arc is parallel to the tangent at its middle), so the heading turns
tread by tread; feet alternate left and right, each half the walker's step width beside the
walk line as on a straight flight, moved towards it, and past it within the stair's walk zone
(:data:`mjwalk.world.norms.WALK_ZONE_SHARE`), where that is what keeps the foot wholly on its
tread (:func:`tread_foot`); where no place holds the whole foot it hangs over the tread's nosing
as on a straight flight, keeping :data:`mjwalk.world.norms.MIN_TREAD_SHARE` of its length on
the tread; a tread that holds that share of the walker's foot nowhere in the walk zone is
refused.
On the levels before and after the stair the foot stands off the first and last nosing along
their normals, its toes (heel) at least :data:`mjwalk.plan.levelcross.RISER_GAP` from the
riser. A step that climbs or descends a riser takes the stair gait's step time
(:func:`mjwalk.gait.stairs.stair_gait`, the stair's highest riser and mean walk-line tread, as
for straight flights); a level step the walker's level step time.

The level route takes it as a crossing (:mod:`mjwalk.plan.winderroute`: its stances, line-up,
limits and the walk led in to it); the legs' swing over a nosing that is not square to the
step (:mod:`mjwalk.body.legs.edgeswing` measures edges along the step's chord) is to come.
Metres, seconds, radians, world frame, z up, yaw from +x.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from mjwalk.anthropometry import leg_geometry
from mjwalk.conventions import SAMPLE_RATE_HZ
from mjwalk.errors import PlanningError
from mjwalk.gait.stairs import MIN_TREAD, StairGeometry, stair_gait
from mjwalk.gait.walker import Walker
from mjwalk.plan.footfallwalk import footfall_walk
from mjwalk.plan.levelcross import DEFAULT_STEP_WIDTH, RISER_GAP
from mjwalk.plan.turnsplit import WALKING_TURN_MAX
from mjwalk.plan.turnsteps import turned_chains
from mjwalk.plan.walkpath import WalkPath
from mjwalk.world.footprint import Footprint
from mjwalk.world.levels import LevelGraph, LevelLink
from mjwalk.world.norms import DESCENT_LOW_CLEARANCE, MIN_TREAD_SHARE, WALK_ZONE_SHARE
from mjwalk.world.walkline import (
    WalkLineTread,
    walk_line_faults,
    walk_line_nosings,
    walk_line_treads,
)

#: Least gap (m) between a foot on a winder's tread and every edge of the tread (its nosings,
#: its narrow end, its sides): the clearance under which stair-descent studies count a foot's
#: clearance as low (:data:`mjwalk.world.norms.DESCENT_LOW_CLEARANCE`, 5 mm, Hamel et al. 2005),
#: the gap a foot on a straight flight's tread keeps off its risers
#: (:data:`mjwalk.plan.levelcross.TREAD_RISER_GAP`).
TREAD_EDGE_GAP = DESCENT_LOW_CLEARANCE
#: Spacing (m) of the places across a tread where a foot is tried (:func:`tread_foot`): 5 mm,
#: the edge gap itself, so no place that keeps it is missed by more than it.
ACROSS_STEP = 0.005


@dataclass(frozen=True, eq=False)
class WinderCrossing:
    """A winder or spiral stair between two levels, walked along its walk line.

    Attributes:
        lower, upper: the levels it joins (indices in the graph's levels).
        treads: its treads measured on the walk line, bottom up.
        nosings: (n + 1) step edges bottom up, each (2, 2) world xy, metres: the first leaves
            the lower level, the last reaches the upper; cut to the stair's usable width
            (:func:`mjwalk.world.walkline.walk_line_nosings`), so each middle is on the walk line.
        outlines: each tread's top outline (its surface's footprint, world xy).
        risers: each riser's height bottom up, metres.
        z: (n + 2,) world heights of the lower level, each tread and the upper level, metres.
        clear: how far from the first and last nosing the walker stands before and after it,
            metres.
    """

    lower: int
    upper: int
    treads: tuple[WalkLineTread, ...]
    nosings: tuple[np.ndarray, ...]
    outlines: tuple[Footprint, ...]
    risers: tuple[float, ...]
    z: np.ndarray
    clear: float

    def normal(self, i: int) -> np.ndarray:
        """The unit horizontal normal of nosing ``i``, pointing up the stair.

        Args:
            i: the nosing's index (negative from the top).

        Returns:
            (2,) unit vector.
        """
        a, b = self.nosings[i]
        d = (b - a) / max(float(np.linalg.norm(b - a)), 1e-12)
        n = np.array([-d[1], d[0]])
        t = self.treads[min(i % len(self.nosings), len(self.treads) - 1)]  # the tread above
        return n if float(n @ np.subtract(t.end, t.start)) >= 0.0 else -n  # or, last, below

    def end(self, level: int) -> np.ndarray:
        """Where the walker stands before (lower level) or after (upper level) the stair.

        Args:
            level: ``lower`` or ``upper``.

        Returns:
            (2,) world xy, metres: :attr:`clear` off the first or last nosing's middle.
        """
        if level == self.lower:
            return self.nosings[0].mean(axis=0) - self.clear * self.normal(0)
        return self.nosings[-1].mean(axis=0) + self.clear * self.normal(-1)

    @property
    def tread(self) -> float:
        """The mean walk-line tread, metres."""
        return float(np.mean([t.tread for t in self.treads]))

    def riser_lines(self, floor_z: float) -> list[dict]:
        """Its nosings as :meth:`mjwalk.plan.levelroute.Crossing.riser_lines` gives a flight's:
        the walk line's crossing, the nosing's normal up the stair, the heights either side
        (above ``floor_z``) and half its length.

        Args:
            floor_z: the floor's world height, metres.

        Returns:
            One dict per nosing bottom up (``xy``, ``normal``, ``low``, ``high``,
            ``half_width``).
        """
        return [
            {"xy": [float(v) for v in e.mean(axis=0)], "normal": [float(v) for v in self.normal(i)],
             "low": float(self.z[i]) - floor_z, "high": float(self.z[i + 1]) - floor_z,
             "half_width": 0.5 * float(np.linalg.norm(e[1] - e[0]))}
            for i, e in enumerate(self.nosings)
        ]  # fmt: skip


def winder_crossings(graph: LevelGraph, clear: float) -> list[WinderCrossing]:
    """The winders of a level graph whose treads meet DIN 18065 on their walk line (those that
    break it stay refused, :func:`mjwalk.plan.turnsteps.turning_steps`).

    Args:
        graph: the scene's levels and links.
        clear: how far from the first and last nosing the walker stands, metres.

    Returns:
        One crossing per pair of levels joined only by turning steps that meet the rules.
    """
    out = []
    for (lo, up), chain in turned_chains(graph, clear).items():
        treads = walk_line_treads(graph, chain)
        if walk_line_faults(treads):
            continue
        out.append(_winder(graph, chain, treads, (lo, up), clear))
    return out


def _winder(graph: LevelGraph, chain: list[LevelLink], treads, ends, clear) -> WinderCrossing:
    """The crossing of one conforming chain of turning steps."""
    lo, up = ends
    outlines = []
    for t in treads:
        surface = graph.surfaces[graph.levels[t.level].surfaces[0]]
        outlines.append(surface.footprint)
    z = [graph.levels[lo].height] + [graph.levels[t.level].height for t in treads]
    return WinderCrossing(
        lo, up, tuple(treads), tuple(walk_line_nosings(chain)),
        tuple(outlines), tuple(float(k.rise) for k in chain),
        np.array([*z, graph.levels[up].height]), float(clear),
    )  # fmt: skip


def sole_corners(centre: np.ndarray, yaw: float, stature: float) -> np.ndarray:
    """The four corners of a foot's sole (its length along ``yaw``, its width across).

    Args:
        centre: (2,) the sole's centre, world xy, metres.
        yaw: the foot's heading, radians.
        stature: the walker's stature, metres (:func:`mjwalk.anthropometry.leg_geometry`).

    Returns:
        (4, 2) world xy, metres.
    """
    h = np.array([math.cos(yaw), math.sin(yaw)])
    return _corners(np.asarray(centre, dtype=float)[None], h, stature)[0]


def tread_foot(
    c: WinderCrossing, i: int, stature: float, want: float, direction: str = "up"
) -> np.ndarray:
    """Where a foot's sole is centred on tread ``i``, turned along the tread's walk-line chord:
    the chord's middle moved ``want`` metres across it (left of the way up), or, where the
    sole would not keep :data:`TREAD_EDGE_GAP` inside the tread's outline there, the nearest
    place (moved across the chord within the walk zone, half
    :data:`~mjwalk.world.norms.WALK_ZONE_SHARE` of the tread's mean nosing length either side
    of the walk line, and along it within the tread) where it does. On a winder the nosings
    slant apart across the foot's width, so a tread deep enough on the walk line may hold the
    foot only towards its wide end, and there its middle lies further round the turn. Where
    no place holds the whole sole, the foot hangs over the tread's nosing as on a straight
    flight (:mod:`mjwalk.plan.treadshare`): the nearest place where the part of the sole
    towards the riser at the tread's back, :data:`~mjwalk.world.norms.MIN_TREAD_SHARE` of
    its length (the toes going up; going down the heel, kept
    :data:`~mjwalk.plan.levelcross.RISER_GAP` off that riser, whose nosing the landing heel
    passes), keeps the edge gap inside the tread (:func:`held_corners`).

    Args:
        c: the winder.
        i: the tread's index, bottom up.
        stature: the walker's stature, metres.
        want: the offset across the walk line the foot would take, metres (positive: left of
            the way up).
        direction: "up" or "down", the way the foot faces (its heel or toes over the nosing).

    Returns:
        (2,) the sole's centre, world xy, metres.

    Raises:
        PlanningError: no place within the walk zone keeps that share of the sole on the
            tread.
    """
    t = c.treads[i]
    start, end = np.asarray(t.start), np.asarray(t.end)
    h = (end - start) / float(np.linalg.norm(end - start))
    left = np.array([-h[1], h[0]])
    width = 0.5 * sum(float(np.linalg.norm(e[1] - e[0])) for e in c.nosings[i : i + 2])
    half = 0.5 * WALK_ZONE_SHARE * width
    u = np.arange(-half, half + 1e-9, ACROSS_STEP)
    v = np.arange(-0.5 * t.tread, 0.5 * t.tread + 1e-9, ACROSS_STEP)
    uu, vv = (a.ravel() for a in np.meshgrid(u, v))
    cost = np.hypot(uu - np.clip(want, -half, half), vv)
    order = np.argsort(cost, kind="stable")
    uu, vv = uu[order], vv[order]
    centres = 0.5 * (start + end) + uu[:, None] * left + vv[:, None] * h
    corners = _corners(centres, h, stature)  # (n, 4, 2)
    fits = np.all(c.outlines[i].signed_distance(corners) <= -TREAD_EDGE_GAP + 1e-12, axis=1)
    if fits.any():
        return centres[int(np.argmax(fits))]
    held = held_corners(centres, h, stature, direction)
    fits = np.all(c.outlines[i].signed_distance(held) <= -TREAD_EDGE_GAP + 1e-12, axis=1)
    if fits.any():
        return centres[int(np.argmax(fits))]
    g = leg_geometry(stature)
    raise PlanningError(
        f"winder tread {t.name}: {100 * MIN_TREAD_SHARE:.0f} % of a "
        f"{g.foot_front + g.foot_back:.3f} m foot (stature {stature:.2f} m) keeps "
        f"{TREAD_EDGE_GAP * 1000:.0f} mm inside it going {direction} nowhere within the walk "
        f"zone ({2 * half:.2f} m wide)"
    )


def held_corners(centres: np.ndarray, h: np.ndarray, stature: float, direction: str) -> np.ndarray:
    """The corners of the part of a sole a tread must hold where the foot hangs over its nosing
    (:func:`tread_foot`): :data:`~mjwalk.world.norms.MIN_TREAD_SHARE` of the foot's length from
    its end up the stair (the toes going up, the heel going down), at the foot's width; going
    down it reaches on past the heel by :data:`~mjwalk.plan.levelcross.RISER_GAP` less
    :data:`TREAD_EDGE_GAP`, so that, held the edge gap inside the tread, the heel keeps
    ``RISER_GAP`` off the riser behind it, as on a straight flight
    (:data:`mjwalk.plan.levelcross.TREAD_RISER_GAP`).

    Args:
        centres: (n, 2) the soles' centres, world xy, metres.
        h: (2,) the unit direction up the stair along the feet (the tread's walk-line chord).
        stature: the walker's stature, metres (:func:`mjwalk.anthropometry.leg_geometry`).
        direction: "up" or "down".

    Returns:
        (n, 4, 2) world xy, metres.
    """
    g = leg_geometry(stature)
    h = np.asarray(h, dtype=float)
    w = np.array([-h[1], h[0]])
    top = 0.5 * (g.foot_front + g.foot_back)  # the sole's end up the stair, from its centre
    reach = top + (RISER_GAP - TREAD_EDGE_GAP if direction == "down" else 0.0)
    bottom = top - MIN_TREAD_SHARE * (g.foot_front + g.foot_back)
    across = 0.5 * g.foot_width * w
    offsets = np.array([a * h + b * across for a in (reach, bottom) for b in (1, -1)])
    return np.asarray(centres, dtype=float)[:, None, :] + offsets[None]


def _corners(centres: np.ndarray, h: np.ndarray, stature: float) -> np.ndarray:
    """(n, 4, 2) sole corners of feet centred at ``centres`` (n, 2), heading the unit ``h``."""
    g = leg_geometry(stature)
    w = np.array([-h[1], h[0]])
    half = 0.5 * (g.foot_front + g.foot_back)
    offsets = np.array(
        [a * half * h + b * 0.5 * g.foot_width * w for a in (1, -1) for b in (1, -1)]
    )
    return centres[:, None, :] + offsets[None]


@dataclass(frozen=True)
class WinderFootfalls:
    """The footfalls of a walk over a winder, in order, the closing step last.

    Attributes:
        centre: (k, 2) each sole's centre, world xy, metres.
        ankle: (k, 2) the point under each ankle, world xy, metres.
        yaw: (k,) each foot's heading, radians, unwrapped (each within pi of the one before).
        z: (k,) world heights of the surfaces under them, metres.
        times: (k,) each step's duration, seconds.
        tread: (k,) the tread each stands on (index bottom up), -1 on a level.
        side: the first step's swinging foot.
    """

    centre: np.ndarray
    ankle: np.ndarray
    yaw: np.ndarray
    z: np.ndarray
    times: np.ndarray
    tread: np.ndarray
    side: str = "left"


def winder_footfalls(
    c: WinderCrossing, direction: str, walker: Walker, step_width: float | None = None,
    foot: str = "left",
) -> WinderFootfalls:  # fmt: skip
    """The footfalls of a walk up or down a winder from standing at one end's stance to
    standing at the other's (module docstring); the ``foot`` swings first (the other
    where the stance is the first footfall: the walker stands there already, its first step is
    onto the stair).

    Args:
        c: the winder.
        direction: "up" or "down".
        walker: the walker (stature, step length and time, stair gait).
        step_width: lateral distance of the feet, metres (None: the walker's, else
            :data:`mjwalk.plan.levelcross.DEFAULT_STEP_WIDTH`).
        foot: the foot the footfall before the first nosing takes, "left" or "right" (a
            walk led in to the winder chooses it so its feet alternate,
            :func:`mjwalk.plan.winderroute.winder_cross_walk`).

    Returns:
        The footfalls.

    Raises:
        PlanningError: ``direction`` is neither, a tread has no place for the foot, or a step
            turns the walker more than :data:`mjwalk.plan.turnsplit.WALKING_TURN_MAX` (60 deg,
            Patla et al. 1991).
    """
    if direction not in ("up", "down"):
        raise PlanningError(f"winder walk direction {direction!r} must be 'up' or 'down'")
    width = step_width or walker.step_width or DEFAULT_STEP_WIDTH
    g = leg_geometry(walker.stature)
    off = max(0.5 * c.tread, RISER_GAP + 0.5 * (g.foot_front + g.foot_back))
    stance = max(c.clear, off)
    m0, m1 = c.nosings[0].mean(axis=0), c.nosings[-1].mean(axis=0)
    n0, n1 = c.normal(0), c.normal(-1)
    run = math.ceil((stance - off) / walker.step_length - 1e-9)  # level steps to the stance
    beyond = off + (stance - off) * np.arange(1, run + 1) / max(run, 1)
    n = len(c.treads)
    if direction == "up":
        order, sign = list(range(n)), 1.0
        first, last, nf, nl, zf, zl = m0 - off * n0, m1, n0, n1, c.z[0], c.z[-1]
        level = [m1 + d * n1 for d in [off, *beyond, stance]]
    else:
        order, sign = list(range(n))[::-1], -1.0
        first, last, nf, nl, zf, zl = m1 + off * n1, m0, -n1, -n0, c.z[-1], c.z[0]
        level = [m0 - d * n0 for d in [off, *beyond, stance]]
    del last
    k = 1 + n + len(level)
    lead = 1.0 if foot == "left" else -1.0  # the left foot left of the way
    side = np.where(np.arange(k) % 2 == 0, lead, -lead)
    centre = [first + 0.5 * width * side[0] * np.array([-nf[1], nf[0]])]
    yaw, z, tread = [math.atan2(nf[1], nf[0])], [zf], [-1]
    for j, i in enumerate(order, start=1):
        centre.append(tread_foot(c, i, walker.stature, sign * side[j] * 0.5 * width, direction))
        chord = np.subtract(c.treads[i].end, c.treads[i].start) * sign
        yaw.append(math.atan2(chord[1], chord[0]))
        z.append(float(c.z[i + 1]))
        tread.append(i)
    across = np.array([-nl[1], nl[0]])
    for j, p in enumerate(level, start=1 + n):
        centre.append(p + 0.5 * width * side[j] * across)
        yaw.append(math.atan2(nl[1], nl[0]))
        z.append(float(zl))
        tread.append(-1)
    centre_a, yaw_a, z_a = np.array(centre), np.unwrap(np.array(yaw)), np.array(z)
    turn = float(np.max(np.abs(np.diff(yaw_a))))
    if turn > WALKING_TURN_MAX + 1e-9:
        raise PlanningError(
            f"winder walk turns {math.degrees(turn):.0f} deg in one step, more than "
            f"{math.degrees(WALKING_TURN_MAX):.0f} deg (a walking direction change within a step)"
        )
    h = np.stack([np.cos(yaw_a), np.sin(yaw_a)], axis=1)
    ankle = centre_a - 0.5 * (g.foot_front - g.foot_back) * h
    geometry = StairGeometry(max(c.risers), max(c.tread, MIN_TREAD))
    climb = stair_gait(walker, geometry, "up" if direction == "up" else "down").step_time
    before = np.concatenate([[c.z[0] if direction == "up" else c.z[-1]], z_a[:-1]])
    times = np.where(np.abs(z_a - before) > 1e-6, climb, walker.step_duration)
    at = 0 if stance > off + 1e-9 else 1  # standing at the first footfall: no step to it
    return WinderFootfalls(
        centre_a[at:], ankle[at:], yaw_a[at:], z_a[at:], times[at:], np.array(tread)[at:],
        foot if at == 0 else ("right" if foot == "left" else "left"),
    )  # fmt: skip


def winder_time(c: WinderCrossing, direction: str, walker: Walker) -> float:
    """How long the walk over a winder takes, from standing at one stance to standing at the
    other: the sum of its steps' times (:func:`winder_footfalls`).

    Args:
        c: the winder.
        direction: "up" or "down".
        walker: the walker.

    Returns:
        Seconds.
    """
    return float(np.sum(winder_footfalls(c, direction, walker).times))


def winder_walk(
    c: WinderCrossing, direction: str, walker: Walker, floor_z: float,
    step_width: float | None = None,
) -> WalkPath:  # fmt: skip
    """The walk over a winder from standing at its stance, the feet side by side facing the
    first footfall's heading, their soles centred on it (as every footfall's), to standing at
    the other end's (:func:`winder_footfalls`): the 120 Hz pelvis path between the feet
    (:func:`mjwalk.plan.footfallwalk.footfall_walk`), its heading turning with each step's.

    Args:
        c: the winder.
        direction: "up" or "down".
        walker: the walker.
        floor_z: the floor's world height, metres (heights are given above it).
        step_width: lateral distance of the feet, metres (None: as :func:`winder_footfalls`).

    Returns:
        The walk from t = 0; ``meta`` names the crossing ("winder") and its nosings'
        ``edges`` (:meth:`WinderCrossing.riser_lines`).
    """
    width = step_width or walker.step_width or DEFAULT_STEP_WIDTH
    f = winder_footfalls(c, direction, walker, width)
    level = c.lower if direction == "up" else c.upper
    yaw0 = float(f.yaw[0])
    g = leg_geometry(walker.stature)
    ahead = np.array([math.cos(yaw0), math.sin(yaw0)])
    xy0 = c.end(level) - 0.5 * (g.foot_front - g.foot_back) * ahead  # the soles on the stance
    z0 = float(c.z[0] if direction == "up" else c.z[-1])
    left = np.array([-ahead[1], ahead[0]])
    feet = {
        name: (np.array([*(xy0 + sign * 0.5 * width * left), yaw0]), z0)
        for name, sign in (("left", 1.0), ("right", -1.0))
    }
    track = (f.ankle, f.z, f.times, f.yaw)
    return footfall_path(c, direction, track, (feet, f.side), (xy0, z0, yaw0), floor_z)


def footfall_path(
    c, direction: str, track: tuple, feet: tuple[dict, str], start: tuple, floor_z: float
) -> WalkPath:
    """The walk over a winder's footfalls, every step turning from the one before
    (:func:`mjwalk.plan.footfallwalk.footfall_walk`), as a :class:`WalkPath`.

    Args:
        c: the winder (its ``lower``, ``upper`` and :meth:`WinderCrossing.riser_lines`).
        direction: "up" or "down".
        track: (ankle points (k, 2) world xy, surface heights (k,) world z, step durations
            (k,) s, headings (k,) radians) of the footfalls.
        feet: ({"left", "right"}: (foot pose (3,), world z) before the first step, the first
            step's swinging foot).
        start: (pelvis xy (2,), pelvis world z, heading in radians) before the first step.
        floor_z: the floor's world height, metres.

    Returns:
        The walk from t = 0, heights above ``floor_z``; ``meta`` names the crossing
        ("winder") and its nosings' ``edges``.
    """
    ankle, z, times, yaw = track
    across = np.stack([-np.sin(yaw), np.cos(yaw)], axis=1)
    was = np.concatenate([[start[2]], yaw[:-1]])
    xy, zz, yaws, steps = footfall_walk(
        (ankle, z, times, yaw, across, 0.0), feet[0], feet[1], start,
        (was, len(times), float(yaw[-1])), floor_z,
    )  # fmt: skip
    n = steps[-1].end
    meta = {"crossing": "winder", "direction": direction, "lower": c.lower, "upper": c.upper,
            "edges": c.riser_lines(floor_z)}  # fmt: skip
    return WalkPath(
        t=np.arange(n + 1) / SAMPLE_RATE_HZ, xy=xy, yaw=yaws, steps=steps, meta=meta,
        z=zz - floor_z,
    )  # fmt: skip
