"""How much of a walker's foot stands on a straight flight's treads, and the flights a walker's
foot refuses (issue 47: each foot on a tread, not hanging over the nosing).

A foot on a straight flight's tread is placed as :func:`mjwalk.plan.levelcross.tread_setback`
puts it: centred where it fits, its ends :data:`~mjwalk.plan.levelcross.TREAD_RISER_GAP` off
the risers; a foot longer than that hangs over the tread's nosing (going up its toes keep that
gap off the riser ahead and the heel hangs back; going down its heel keeps
:data:`~mjwalk.plan.levelcross.RISER_GAP` off the riser behind and the toes hang forward). Its
share on the tread (:func:`tread_shares`) is the length of the sole at least
:data:`~mjwalk.plan.windercross.TREAD_EDGE_GAP` inside the tread over the foot's length, as
on a winder's tread (:func:`mjwalk.plan.windercross.tread_foot`). A flight on whose treads a
walker's foot keeps less than :data:`~mjwalk.world.norms.MIN_TREAD_SHARE` of its length, up
or down, is not taken by that walker (:func:`flight_refusal`), as a winder whose treads hold
its foot nowhere (:func:`mjwalk.plan.winderroute.foot_refusal`); a route refused names it
(:func:`flight_notes`). Positions along the walking direction; metres.
"""

from __future__ import annotations

import numpy as np

from mjwalk.anthropometry import leg_geometry
from mjwalk.gait.walker import Walker
from mjwalk.plan.levelcross import flight_setback
from mjwalk.plan.levelroute import Crossing
from mjwalk.plan.windercross import TREAD_EDGE_GAP
from mjwalk.world.norms import MIN_TREAD_SHARE

#: The crossings whose footfalls stand on straight treads (a ramp has none; a winder is
#: :mod:`mjwalk.plan.windercross`'s).
FLIGHT_KINDS = ("step", "stair")


def tread_shares(c: Crossing, stature: float, direction: str) -> np.ndarray:
    """The share of the foot's length on its tread, at least :data:`TREAD_EDGE_GAP` inside its
    edges, of each footfall on a tread of a straight flight (its track's inner positions),
    placed as :func:`mjwalk.plan.levelcross.tread_setback` places it.

    Args:
        c: the crossing.
        stature: the walker's stature, metres (:func:`mjwalk.anthropometry.leg_geometry`).
        direction: "up" or "down".

    Returns:
        (t,) shares in [0, 1] in walking order, one per tread (empty: a ramp, a winder, a
        single step).
    """
    if c.kind not in FLIGHT_KINDS or len(c.track) < 3:
        return np.empty(0)
    up = direction == "up"
    track = np.sort((1.0 if up else -1.0) * np.asarray(c.track, dtype=float))  # walking order
    s = track[1:-1]  # the footfalls on treads
    g = leg_geometry(stature)
    ankle = s - flight_setback(s, track, up, stature)
    edges = 0.5 * (track[:-1] + track[1:])  # the risers, in walking order
    low = np.maximum(ankle - g.foot_back, edges[:-1] + TREAD_EDGE_GAP)
    high = np.minimum(ankle + g.foot_front, edges[1:] - TREAD_EDGE_GAP)
    share = (high - low) / (g.foot_front + g.foot_back)
    return np.clip(share, 0.0, 1.0)


def flight_refusal(c: Crossing, walker: Walker) -> str | None:
    """Why a walker's foot stands on a straight flight's treads with less than
    :data:`~mjwalk.world.norms.MIN_TREAD_SHARE` of its length, up or down, else None (and None
    for a ramp or a winder).

    Args:
        c: the crossing.
        walker: the walker (stature: its foot).

    Returns:
        The reason, one line, or None when the walker takes it.
    """
    for direction in ("up", "down"):
        shares = tread_shares(c, walker.stature, direction)
        if len(shares) and float(shares.min()) < MIN_TREAD_SHARE - 1e-9:
            g = leg_geometry(walker.stature)
            return (
                f"its {c.tread:.3f} m treads hold {100 * float(shares.min()):.0f} % of a "
                f"{g.foot_front + g.foot_back:.3f} m foot (stature {walker.stature:.2f} m) "
                f"going {direction}, less than the {100 * MIN_TREAD_SHARE:.0f} % a foot keeps "
                "on a tread"
            )
    return None


def flight_notes(flights: list[Crossing], walker: Walker) -> list[str]:
    """Why a walker does not take each of the straight flights its foot refuses
    (:func:`flight_refusal`), one line each, for a route's refusal.

    Args:
        flights: the scene's crossings (ramps and winders are skipped).
        walker: the walker.

    Returns:
        The lines (empty when its foot keeps every flight).
    """
    lines = []
    for c in flights:
        why = flight_refusal(c, walker)
        if why is not None:
            lines.append(f"the {c.kind} from L{c.lower} to L{c.upper} is not taken: {why}")
    return lines
