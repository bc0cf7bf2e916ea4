"""A turning stair's treads measured on its walk line (DIN 18065; issue 47).

A winder or spiral stair ("gewendelte Treppe") has step edges (nosings) that are not parallel,
so a tread's depth depends on where it is measured. DIN 18065 measures it on the walk line
("Lauflinie", "Gehlinie"): a line without kinks in the walk zone, which for usable widths up to
1 m lies in the middle of the stair; the tread is the chord between the walk line's crossings of
the tread's two nosings, and it must meet the tread limits and the step rule there
(:data:`mjwalk.world.norms.STEP_RULE`), while at the narrow end, within the usable width, a
turned tread must still be :data:`mjwalk.world.norms.WINDER_MIN_NARROW_TREAD` deep.

Here a stair is a chain of single-step :class:`~mjwalk.world.levels.LevelLink`\\ s over treads
(the levels they step onto): each link's edge is a nosing over the usable width the two
surfaces share (:mod:`mjwalk.world.contacts`), so the walk line crosses it at its middle. Metres,
world frame, z up.
"""

from __future__ import annotations

import itertools
from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np

from mjwalk.world import norms
from mjwalk.world.levels import LevelGraph, LevelLink


@dataclass(frozen=True)
class WalkLineTread:
    """One tread of a stair measured as DIN 18065 does.

    Attributes:
        name: the tread's surface name (its level's first surface).
        level: the tread's level (index in :attr:`LevelGraph.levels`).
        tread: the chord between the middles of its lower and upper nosing (the walk line's
            crossings), metres.
        riser: the riser up onto it, metres.
        narrow: its depth at the narrow end of the usable width: the nearer of the distances
            between the two nosings' like ends, metres.
        start, end: the walk line's crossings of its lower and upper nosing, world xy metres.
    """

    name: str
    level: int
    tread: float
    riser: float
    narrow: float
    start: tuple[float, float]
    end: tuple[float, float]

    @property
    def step(self) -> float:
        """The step rule's 2 R + T on the walk line, metres."""
        return 2.0 * self.riser + self.tread

    def faults(self) -> list[str]:
        """What of DIN 18065 / ASR A1.8 this tread breaks, one phrase each (numbers in them).

        Returns:
            Empty when its walk-line tread meets the step rule and the tread limits and its
            narrow end is deep enough.
        """
        slack, out = norms.ROUNDING_SLACK, []
        lo, hi = norms.STEP_RULE
        if not lo - slack <= self.step <= hi + slack:
            out.append(
                f"2R + T = 2 x {self.riser:.3f} + {self.tread:.3f} = {self.step:.3f} m on the walk "
                f"line, outside the step rule {lo:.2f}-{hi:.2f} m"
            )
        if not norms.MIN_TREAD - slack <= self.tread <= norms.MAX_TREAD + slack:
            out.append(
                f"walk-line tread {self.tread:.3f} m outside {norms.MIN_TREAD:.2f}-"
                f"{norms.MAX_TREAD:.2f} m"
            )
        if self.narrow < norms.WINDER_MIN_NARROW_TREAD - slack:
            out.append(
                f"{self.narrow:.3f} m deep at its narrow end, under "
                f"{norms.WINDER_MIN_NARROW_TREAD:.2f} m"
            )
        return out


def walk_line_treads(graph: LevelGraph, chain: Sequence[LevelLink]) -> list[WalkLineTread]:
    """The treads a chain of steps passes, measured on its walk line.

    Args:
        graph: the scene's levels and links.
        chain: single steps bottom up, each onto the level the next one leaves (at least two).

    Returns:
        One :class:`WalkLineTread` per level between the chain's links, bottom up.
    """
    out = []
    for below, above in itertools.pairwise(chain):
        a = np.asarray(below.upper_edge, dtype=float)
        b = np.asarray(above.lower_edge, dtype=float)
        ma, mb = a.mean(axis=0), b.mean(axis=0)
        same = np.linalg.norm(b - a, axis=1)  # like ends paired: a0-b0, a1-b1
        crossed = np.linalg.norm(b[::-1] - a, axis=1)
        ends = same if same.sum() <= crossed.sum() else crossed  # the pairing that does not cross
        level = below.upper
        out.append(
            WalkLineTread(
                name=graph.surfaces[graph.levels[level].surfaces[0]].name,
                level=level,
                tread=float(np.linalg.norm(mb - ma)),
                riser=float(below.rise),
                narrow=float(ends.min()),
                start=(float(ma[0]), float(ma[1])),
                end=(float(mb[0]), float(mb[1])),
            )
        )
    return out


def walk_line_faults(treads: Sequence[WalkLineTread]) -> list[str]:
    """Each tread that breaks DIN 18065 on the walk line, named with its faults.

    Args:
        treads: a stair's treads (:func:`walk_line_treads`).

    Returns:
        One phrase per faulty tread ("tread <name>: <fault>; <fault>"), bottom up; empty when
        every tread meets the rules.
    """
    return [f"tread {t.name}: {'; '.join(t.faults())}" for t in treads if t.faults()]
