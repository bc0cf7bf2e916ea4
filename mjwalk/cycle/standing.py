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
``goal_tolerance`` and ``goal_within``) and ends the walk at the first place in it its sampled
steps reach. Metres throughout; targets are world points (x, y, z up).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike

from mjwalk.anthropometry import hand_reach
from mjwalk.conventions import DEFAULT_STATURE

#: The zone's radius in preferred step lengths (half a step: see the module docstring).
ZONE_STEPS = 0.5
#: Reach discs keep this margin inside the arm's reach (m): the reach solver's hand error grows
#: from about 2 mm at the reach limit (anthropometry.REACH_TRUNK_LEAN_DEG).
REACH_MARGIN = 0.02
#: The planner takes at most this many discs (mjwalk.plan.stepcheck.MAX_GOAL_DISCS).
MAX_DISCS = 4


@dataclass(frozen=True)
class StandZone:
    """A goal area: within ``radius`` of ``centre`` and within each disc (x, y, radius).

    Attributes:
        centre: (2,) the stand site, metres.
        radius: metres.
        discs: ((x, y, r), ...) reach discs, metres.
    """

    centre: tuple[float, float]
    radius: float
    discs: tuple[tuple[float, float, float], ...]

    def contains(self, xy) -> bool:
        """Whether the floor point ``xy`` lies in the zone."""
        p = np.asarray(xy, dtype=float)[:2]
        if np.hypot(*(p - self.centre)) > self.radius + 1e-9:
            return False
        return all(np.hypot(p[0] - x, p[1] - y) <= r + 1e-9 for x, y, r in self.discs)


def stand_zone(
    centre: ArrayLike,
    targets: ArrayLike,
    step_length: float,
    stature: float = DEFAULT_STATURE,
) -> StandZone:
    """The zone around the stand site ``centre`` (x, y) for work on ``targets`` (k, 3) by a
    walker of preferred ``step_length`` and ``stature`` (metres).

    Each target's disc has the arm's reach at its height less :data:`REACH_MARGIN`, but never
    excludes the stand site itself (a site placed beyond comfortable reach keeps its own
    distance: the zone then asks no more than the site). With more than :data:`MAX_DISCS`
    targets the ones farthest from the site are kept (they bound the zone)."""
    c = np.asarray(centre, dtype=float)[:2]
    discs = []
    for t in np.asarray(targets, dtype=float).reshape(-1, 3):
        own = float(np.hypot(*(t[:2] - c)))
        r = max(hand_reach(float(t[2]), stature) - REACH_MARGIN, own + 1e-3)
        discs.append((own, (float(t[0]), float(t[1]), r)))
    discs.sort(key=lambda d: -d[0])
    return StandZone(
        centre=(float(c[0]), float(c[1])),
        radius=ZONE_STEPS * float(step_length),
        discs=tuple(d for _, d in discs[:MAX_DISCS]),
    )
