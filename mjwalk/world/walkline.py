"""A turning stair's treads measured on its walk line (DIN 18065; issue 47).

A winder or spiral stair ("gewendelte Treppe") has step edges (nosings) that are not parallel,
so a tread's depth depends on where it is measured. DIN 18065 measures it on the walk line
("Lauflinie", "Gehlinie"): a line without kinks in the walk zone, which for usable widths up to
1 m lies in the middle of the stair; the tread is the chord between the walk line's crossings of
the tread's two nosings, and it must meet the tread limits and the step rule there
(:data:`mjwalk.world.norms.STEP_RULE`), while at the narrow end, within the usable width, a
turned tread must still be :data:`mjwalk.world.norms.WINDER_MIN_NARROW_TREAD` deep.

Here a stair is a chain of single-step :class:`~mjwalk.world.levels.LevelLink`\\ s over treads
(the levels they step onto): each link's edge is a nosing over the width the two surfaces share
(:mod:`mjwalk.world.contacts`), so the walk line crosses it at its middle. A spiral stair
("Spindeltreppe", DIN 18065: a winder round a central post) has treads that narrow to a few
centimetres at the post (every tread shallow at the same side); the part of it shallower than
:data:`~mjwalk.world.norms.WINDER_MIN_NARROW_TREAD` there is no part of its usable width
(:data:`mjwalk.world.norms.USABLE_TREAD_DEPTH`), so the nosings are cut to the stretch where
every tread of the stair is at least that deep (:func:`walk_line_nosings`) and the walk line
crosses each at the middle of that stretch. Metres, world frame, z up.
"""

from __future__ import annotations

import itertools
import math
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
    """The treads a chain of steps passes, measured on its walk line: through the middle of
    each nosing's usable stretch (:func:`usable_span`; the whole nosing where every tread is
    deep enough all along it).

    Args:
        graph: the scene's levels and links.
        chain: single steps bottom up, each onto the level the next one leaves (at least two).

    Returns:
        One :class:`WalkLineTread` per level between the chain's links, bottom up.
    """
    pairs, span = usable_span(chain)
    out = []
    for (below, _), (a, b) in zip(itertools.pairwise(chain), pairs, strict=True):
        if span is None:  # the whole nosings: their middles, the nearer of their like ends
            ma, mb = a.mean(axis=0), b.mean(axis=0)
            ends = np.linalg.norm(b - a, axis=1)
        else:
            ma, mb = (e[0] + 0.5 * (span[0] + span[1]) * (e[1] - e[0]) for e in (a, b))
            ends = np.array([_depth(a, b, u) for u in span])
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


def usable_span(chain: Sequence[LevelLink]) -> tuple[list, tuple[float, float] | None]:
    """Each tread's two nosings, like ends paired all along the chain, and, on a spiral stair,
    the stretch of them (fractions of each nosing from its first end) where every tread is at
    least :data:`~mjwalk.world.norms.USABLE_TREAD_DEPTH` deep: its usable width. A spiral stair
    here is one whose every tread is shallower than that at the same end of its nosings (the
    post); elsewhere the whole nosings are the usable width and a shallow narrow end a fault.

    Args:
        chain: single steps bottom up (:func:`walk_line_treads`).

    Returns:
        ([(lower nosing, upper nosing) per tread, each (2, 2) world xy], (first, last)
        fraction of the usable stretch), the stretch None where it is the whole nosings (no
        spiral) or where no stretch is deep enough on every tread (then the narrow end says so).
    """
    pairs, ref = [], None
    for below, above in itertools.pairwise(chain):
        a = np.asarray(below.upper_edge, dtype=float)
        a = a if ref is None else _like(a, ref)
        b = _like(np.asarray(above.lower_edge, dtype=float), a)  # the pairing that does not cross
        pairs.append((a, b))
        ref = b
    shallow = {
        int(np.argmin(d)) if d.min() < norms.USABLE_TREAD_DEPTH - norms.ROUNDING_SLACK else -1
        for d in (np.linalg.norm(b - a, axis=1) for a, b in pairs)
    }
    if len(shallow) != 1 or -1 in shallow:
        return pairs, None  # no spiral: not every tread narrows under 0.10 m at one side
    lo, hi, cut = 0.0, 1.0, False
    for a, b in pairs:
        part = _deep_part(a, b, norms.USABLE_TREAD_DEPTH)
        if part is None:
            return pairs, None
        cut = cut or part != (0.0, 1.0)
        lo, hi = max(lo, part[0]), min(hi, part[1])
    return pairs, ((lo, hi) if cut and lo < hi else None)


def walk_line_nosings(chain: Sequence[LevelLink]) -> list[np.ndarray]:
    """Each step's nosing (its lower edge) cut to the stair's usable stretch
    (:func:`usable_span`), so its middle is where the walk line crosses it.

    Args:
        chain: single steps bottom up (:func:`walk_line_treads`).

    Returns:
        (2, 2) world xy per link, bottom up: its lower edge itself where nothing is cut.
    """
    pairs, span = usable_span(chain)
    edges = [np.asarray(k.lower_edge, dtype=float) for k in chain]
    if span is None:
        return edges
    first = _like(edges[0], pairs[0][0])
    lines = [first, *(b for _, b in pairs)]  # the last tread's upper nosing is the top link's
    return [e[0] + np.outer(span, e[1] - e[0]) for e in lines]


def _like(edge: np.ndarray, ref: np.ndarray) -> np.ndarray:
    """``edge`` with its ends in the order of ``ref``'s: like ends paired (the pairing whose
    end-to-end distances sum least, the one that does not cross)."""
    same = np.linalg.norm(edge - ref, axis=1).sum()
    crossed = np.linalg.norm(edge[::-1] - ref, axis=1).sum()
    return edge if same <= crossed else edge[::-1]


def _depth(a: np.ndarray, b: np.ndarray, u: float) -> float:
    """A tread's depth between its nosings ``a`` and ``b`` (like ends paired) at fraction ``u``
    of their length from their first ends, metres."""
    return float(np.linalg.norm((b[0] - a[0]) + u * ((b[1] - a[1]) - (b[0] - a[0]))))


def _deep_part(a: np.ndarray, b: np.ndarray, depth: float) -> tuple[float, float] | None:
    """The longest stretch (fractions) of nosings ``a``, ``b`` where the tread between them is
    at least ``depth`` deep, None where it is nowhere: its depth |D0 + u (D1 - D0)| is convex
    in u, so it is shallower only on one interval between the roots of a quadratic."""
    d0, e = b[0] - a[0], (b[1] - a[1]) - (b[0] - a[0])
    qa, qb, qc = float(e @ e), 2.0 * float(d0 @ e), float(d0 @ d0) - depth * depth
    if qa <= 1e-18:  # parallel nosings: as deep all along
        return (0.0, 1.0) if qc >= 0.0 else None
    disc = qb * qb - 4.0 * qa * qc
    if disc <= 0.0:
        return (0.0, 1.0)  # nowhere shallower
    r0, r1 = ((-qb - math.sqrt(disc)) / (2 * qa), (-qb + math.sqrt(disc)) / (2 * qa))
    if r1 <= 0.0 or r0 >= 1.0:
        return (0.0, 1.0)  # shallower only beyond the nosings' ends
    parts = [p for p in ((0.0, r0), (r1, 1.0)) if p[1] > p[0]]
    return max(parts, key=lambda p: p[1] - p[0]) if parts else None


def walk_line_faults(treads: Sequence[WalkLineTread]) -> list[str]:
    """Each tread that breaks DIN 18065 on the walk line, named with its faults.

    Args:
        treads: a stair's treads (:func:`walk_line_treads`).

    Returns:
        One phrase per faulty tread ("tread <name>: <fault>; <fault>"), bottom up; empty when
        every tread meets the rules.
    """
    return [f"tread {t.name}: {'; '.join(t.faults())}" for t in treads if t.faults()]
