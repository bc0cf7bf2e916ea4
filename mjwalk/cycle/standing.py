"""Where an operator stands to work: a zone, not a point.

A cycle's walk ends at a stand site (``stand_rack2``); real operators do not stop on a mark.
They stop where their gait brings them once the work is within reach, and that place varies
from walk to walk with the approach and the steps. mjwalk models it with two facts:

* **Step quantization.** A walker ends a walk with whole steps; placing the body more finely
  would take an extra shuffle step, which people skip when the work is within reach. The walk
  therefore ends anywhere within half a preferred step of the stand site
  (:data:`ZONE_STEPS` of the walker's step length; about 0.35 m for the reference adult).
* **Reach.** Every target of the work done there (the picks, places and fastenings until the
  next walk) must stay within the arm's reach (:func:`mjwalk.anthropometry.hand_reach`, which
  states its sources): the zone is cut by one disc per target. Where the work lies at the
  limit of reach (a shelf), the zone shrinks to the stand site's near side; where it is well
  within reach (the car's side), operators spread along it.

The hybrid A* takes the zone as its goal area (:class:`~mjwalk.plan.hybrid.HybridPlanner`,
``goal_tolerance`` and ``goal_within``); a cycle's walk aims at a spot drawn in the zone and
ends within half a step of it (:func:`mjwalk.cycle.walking.plan_task_walk`). Metres
throughout; targets are world points (x, y, z up).
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np
from numpy.typing import ArrayLike

from mjwalk.anthropometry import SEG, hand_reach
from mjwalk.conventions import DEFAULT_STATURE
from mjwalk.cycle.memo import Memo
from mjwalk.cycle.targets import reach_target
from mjwalk.cycle.types import TASK_KINDS, grip_sites

if TYPE_CHECKING:
    from mjwalk.cycle.types import CycleSpec
    from mjwalk.world.workplace import Workplace

#: The zone's radius in preferred step lengths (half a step: see the module docstring).
ZONE_STEPS = 0.5
#: Reach discs keep this margin inside the arm's reach (m): the humanoid's reach solver misses
#: by 2 mm at the reach limit (anthropometry.REACH_TRUNK_LEAN_DEG), by 8 mm 1.5 cm beyond it.
REACH_MARGIN = 0.03
#: People stand *in front of* their work: for a one-handed reach the body centre stands between
#: the target and the place where the reaching shoulder is in front of it (half the bi-acromial
#: width to the other side, Winter's 0.259 H / 2), for work faced squarely (fastening, both
#: hands) within a quarter of that width either side; the zone keeps the body within the span
#: of these ranges over all the work there, so the arm reaches into a shelf through its opening
#: rather than across its frame (measured: stands 0.25-0.35 m to the side swept the hand
#: across rack 1's and rack 3's frame posts).
SIDE_SLACK = 0.5 * SEG["shoulder_width"]
#: A half-plane is passed to the planner as a disc of this radius (m) whose edge is the
#: half-plane's boundary: over a zone 1 m across it departs from the line by < 0.5 mm.
HALF_PLANE_DISC = 1000.0
#: The planner takes at most this many discs (mjwalk.plan.stepcheck.MAX_GOAL_DISCS): two for
#: the sides, the rest for the targets farthest from the site.
MAX_DISCS = 6


@dataclass(frozen=True)
class StandZone:
    """A goal area: within ``radius`` of ``centre`` and within each disc (x, y, radius).

    Attributes:
        centre: (2,) the stand site, metres.
        radius: metres.
        discs: ((x, y, r), ...) reach discs and the two side half-planes (as large discs),
            metres.
    """

    centre: tuple[float, float]
    radius: float
    discs: tuple[tuple[float, float, float], ...]

    def __hash__(self) -> int:
        # the dataclass's own hash (of the fields' tuple), computed once: a zone keys the
        # cycle's planners (mjwalk.cycle.context.Planners), asked for on every walk
        h = self.__dict__.get("_hash")
        if h is None:
            h = hash((self.centre, self.radius, self.discs))
            object.__setattr__(self, "_hash", h)
        return h

    def contains(self, xy) -> bool:
        """Whether the floor point ``xy`` lies in the zone (within 1e-9 m of its bounds).

        Args:
            xy: (x, y[, z]) world frame, metres (z ignored).

        Returns:
            True when within ``radius`` of ``centre`` and within every disc.
        """
        p = np.asarray(xy, dtype=float)[:2]
        if np.hypot(*(p - self.centre)) > self.radius + 1e-9:
            return False
        return all(np.hypot(p[0] - x, p[1] - y) <= r + 1e-9 for x, y, r in self.discs)


def stand_zone(
    centre: ArrayLike,
    targets: ArrayLike,
    step_length: float,
    stature: float = DEFAULT_STATURE,
    facing: float | None = None,
    squarely: ArrayLike | None = None,
    hands: Sequence[str | None] | None = None,
) -> StandZone:
    """The zone around the stand site ``centre`` for work on ``targets`` by a walker of
    preferred ``step_length`` and ``stature``.

    Each target's disc has the arm's reach at its height less :data:`REACH_MARGIN`, but never
    excludes the stand site itself (a site placed beyond comfortable reach keeps its own
    distance: the zone then asks no more than the site). Two half-planes keep the body in front
    of the work (:data:`SIDE_SLACK`). With more targets than discs left, the ones farthest from
    the site are kept (they bound the zone).

    Args:
        centre: (x, y) the stand site, world frame (m).
        targets: (k, 3) the reach targets, world frame (m).
        step_length: the walker's preferred step length (m).
        stature: the walker's stature (m).
        facing: the heading the work is done at (radians from +x, counter-clockwise); None:
            towards the targets' centroid.
        squarely: (k,) marks targets reached facing them squarely
            (:func:`~mjwalk.anthropometry.hand_reach` ``turned=False``); None: none.
        hands: (k,) the hand of each target ("left", "right"; else faced squarely), for the
            sides of the zone (:data:`SIDE_SLACK`); None: none.

    Returns:
        The :class:`StandZone` (world frame, metres).
    """
    c = np.asarray(centre, dtype=float)[:2]
    pts = np.asarray(targets, dtype=float).reshape(-1, 3)
    discs = []
    square = np.zeros(len(pts), bool) if squarely is None else np.asarray(squarely, bool)
    for t, sq in zip(pts, square, strict=True):
        own = float(np.hypot(*(t[:2] - c)))
        reach = hand_reach(float(t[2]), stature, turned=not sq)
        r = max(reach - REACH_MARGIN, own + 1e-3)
        discs.append((own, (float(t[0]), float(t[1]), r)))
    discs.sort(key=lambda d: -d[0])
    sides: list[tuple[float, float, float]] = []
    if len(pts):
        if facing is None:
            d = pts[:, :2].mean(axis=0) - c
            facing = float(np.arctan2(d[1], d[0]))
        left = np.array([-np.sin(facing), np.cos(facing)])
        lat = (pts[:, :2] - c) @ left
        slack = SIDE_SLACK * stature
        # the body centre's lateral range per target: the left shoulder is at +slack
        lows, highs = [0.0], [0.0]  # the stand site itself stays in the zone
        for t_lat, hand in zip(lat, hands or [None] * len(lat), strict=True):
            if hand == "left":
                lows.append(t_lat - slack)
                highs.append(t_lat)
            elif hand == "right":
                lows.append(t_lat)
                highs.append(t_lat + slack)
            else:
                lows.append(t_lat - 0.5 * slack)
                highs.append(t_lat + 0.5 * slack)
        lo, hi = min(lows), max(highs)
        for bound, sign in ((hi, 1.0), (lo, -1.0)):  # keep p.left <= hi and p.left >= lo
            centre_disc = c + (bound - sign * HALF_PLANE_DISC) * left
            sides.append((float(centre_disc[0]), float(centre_disc[1]), HALF_PLANE_DISC))
    return StandZone(
        centre=(float(c[0]), float(c[1])),
        radius=ZONE_STEPS * float(step_length),
        discs=tuple(sides) + tuple(d for _, d in discs[: MAX_DISCS - len(sides)]),
    )


def work_zone(
    spec: CycleSpec, workplace: Workplace, i: int, stature: float, step_length: float
) -> StandZone:
    """Where the walk that is task ``i`` of ``spec`` may end (:func:`stand_zone`): near its
    stand site, with every reach target of the work done there (the tasks after it up to the
    next walk) within the arm's reach. A two-handed task's targets are its grip sites
    ``<site>_left`` and ``<site>_right``.

    Args:
        spec: the cycle.
        workplace: its scene.
        i: the index of the walk in ``spec.tasks``.
        stature: the operator's stature (m).
        step_length: the operator's step length (m).

    Returns:
        The stand zone (world frame, metres).
    """
    goal = spec.tasks[i].site
    assert goal is not None  # the spec loader requires a site for walks
    return _site_zone(spec, workplace, goal, i + 1, stature, step_length)


def start_zone(
    spec: CycleSpec, workplace: Workplace, stature: float, step_length: float
) -> StandZone:
    """Where the operator stands when the cycle starts: the stand zone of the cycle's start site
    for the work done there before the first walk (:func:`work_zone`'s rule). A cycle is one
    of many in a shift: its operator starts where the work at the start site left them, not on
    the site's mark.

    Args:
        spec: the cycle.
        workplace: its scene.
        stature: the operator's stature (m).
        step_length: the operator's step length (m).

    Returns:
        The stand zone (world frame, metres).
    """
    return _site_zone(spec, workplace, spec.start, 0, stature, step_length)


def _site_zone(
    spec: CycleSpec,
    workplace: Workplace,
    site: str,
    first: int,
    stature: float,
    step_length: float,
) -> StandZone:
    """The stand zone of ``site`` for the reaches of tasks ``first, first + 1, ...`` up to
    the next walk or carry."""
    work = _site_work(spec, workplace, site, first)
    return _zone_of(work, stature, step_length)


#: What :func:`_site_work` gives: the stand site (x, y), the reach targets (k, 3), which are
#: faced squarely, the hands, the work's heading.
SiteWork = tuple[np.ndarray, list, list, list, float]


def _zone_of(work: SiteWork, stature: float, step_length: float) -> StandZone:
    """:func:`stand_zone` of a site's work (:func:`_site_work`) for an operator."""
    stand, targets, squarely, hands, facing = work
    return stand_zone(stand, targets, step_length, stature, facing, squarely, hands)


def _site_work(spec: CycleSpec, workplace: Workplace, site: str, first: int) -> SiteWork:
    """The operator-free part of :func:`_site_zone`: the stand site's (x, y), the reach
    targets of tasks ``first, ...`` up to the next walk or carry, whether each is faced
    squarely, its hand, and the site's heading."""
    stand = workplace.station(site).pos
    floor = np.array([0.0, 0.0, workplace.floor_z])  # the reach's heights are above the floor
    targets, squarely, hands = [], [], []
    for task in spec.tasks[first:]:
        kind = TASK_KINDS[task.kind]
        if kind.motion == "walk":
            break
        if kind.motion != "reach" or task.site is None:
            continue
        for _, name in grip_sites(task.site, task.hand):
            pos = workplace.station(name).pos
            targets.append(reach_target(task.kind, pos, float(stand[0]), float(stand[1])) - floor)
            # the cycle faces fastenings and two-handed work squarely (simulate_cycle)
            squarely.append(kind.approach == "surface" or task.hand == "both")
            hands.append(None if squarely[-1] else task.hand)
    return stand[:2], targets, squarely, hands, workplace.station(site).yaw


class StandZones:
    """The stand zones of a cycle's walks (:func:`work_zone`), kept by the key (walk index,
    stature rounded to the millimetre, step length rounded to the millimetre), at most
    ``limit`` of them. A zone is made for its key's own rounded figures, not the first
    asker's exact ones: a run's walks must not depend on the runs simulated before it.

    Args:
        spec: the cycle (its tasks and sites; the stature is the key's).
        workplace: its scene.
        limit: how many zones are kept (the oldest go first).
    """

    def __init__(self, spec: CycleSpec, workplace: Workplace, limit: int):
        # each walk's site and targets (the same for every operator), made once per walk
        self._work: Memo[int, SiteWork] = Memo(
            lambda i: _site_work(spec, workplace, str(spec.tasks[i].site), i + 1), limit
        )
        self._memo: Memo[tuple[int, float, float], StandZone] = Memo(
            lambda key: _zone_of(self._work.get(key[0]), key[1], key[2]), limit
        )

    def get(self, i: int, stature: float, step_length: float) -> StandZone:
        """The stand zone of walk ``i`` for an operator of ``stature`` and ``step_length``, made for
        the key's rounded figures (millimetres) and kept.

        Args:
            i: the walk's index in the cycle's tasks.
            stature: the operator's stature (m).
            step_length: the operator's step length (m).

        Returns:
            The :class:`StandZone`.
        """
        return self._memo.get((i, round(stature, 3), round(step_length, 3)))
