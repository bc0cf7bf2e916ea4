"""Steps and stairs the scan measured just outside DIN 18065's riser limits, within its noise,
written inside them (issue 47).

The scan accepts a riser within ``planefit.RISER_TOL`` of the norm's range
(``norms.MIN_RISER``-``MAX_RISER``): it cannot tell a riser built at the limit from one a hair
beyond it. The written scene is loaded as any scene, whose level graph holds the norm exactly
(``norms.ROUNDING_SLACK``, 1e-6 m), so a level written where the scan measured it, a hair over
0.19 m above the one below, is no step there and the level above it none of the scene's (hall
1129). :func:`steps_within_norm` lowers a platform reached by single steps, and
:func:`stairs_within_norm` writes a flight at its limiting riser (its treads and top level moved
to that riser's multiples above its bottom), each a margin inside the limit that survives the
written boxes' rounding. A level other links depend on keeps its measured height (moving it
would move them), but for a landing a flight goes on from (flights are written bottom up) and
a flight's top that is otherwise only ramps' ends: a ramp is written from its levels' heights
as written (:func:`ramps_to_levels`), its low end moved down its run if the limit needs it
(``scanramps.within_limit``), so it keeps its own norm.
Metres, scene frame (floor at z = 0); pits below the floor:
:func:`mjwalk.scan.scanpits.within_norm`.
"""

from __future__ import annotations

import dataclasses

from mjwalk.scan.scanlevels import ScanLink
from mjwalk.scan.scanramps import ScanRamp, within_limit
from mjwalk.scan.stairfit import written_riser
from mjwalk.world.norms import MAX_RISER

#: How far under :data:`~mjwalk.world.norms.MAX_RISER` a step the scan measured over it (within
#: its noise) is written, metres: the written box's centre and half-height are each rounded to
#: 1e-5 m (:func:`mjwalk.scan.scene.write_scene`), so its top may land 2e-5 m off.
WRITTEN_UNDER = 2e-5


def _held_levels(links: list[ScanLink], own: ScanLink) -> set[int]:
    """The levels whose height links other than ``own`` depend on: every other link's upper
    end, and every other link's lower end but a stair's (a flight up from a landing is written
    after the flight below it, from the landing's height as written)."""
    out: set[int] = set()
    for k in links:
        if k is not own:
            out.add(k.upper)
            if k.kind != "stair":
                out.add(k.lower)
    return out


def _only_ramps_on(links: list[ScanLink], own: ScanLink, level: int) -> bool:
    """Whether every link but ``own`` (and a flight up from ``level``) that starts or ends on
    ``level`` is a ramp: a ramp follows its levels as written (:func:`ramps_to_levels`)."""
    return all(
        k.kind == "ramp"
        for k in links
        if k is not own and (k.upper == level or (k.lower == level and k.kind != "stair"))
    )


def steps_within_norm(links: list[ScanLink], heights: list[float]) -> list[ScanLink]:
    """Lower, in ``heights``, a platform reached only by single steps whose measured riser
    lies over :data:`~mjwalk.world.norms.MAX_RISER` but within the scan's noise (the scan
    accepted it: ``RISER_TOL``) to :data:`WRITTEN_UNDER` under the norm, so that the written
    scene, loaded with the norm's own limit, keeps the step the scan recognised (hall 1129: a
    0.19 m step platform fitted at 0.19001 m and written at 0.19002 m was no step, and so no
    level, in the written scene). A platform that is also a stair's, a ramp's or another
    step's lower end keeps its measured height.

    Args:
        links: the scan's links.
        heights: each level's written height, metres (changed in place).

    Returns:
        The links, the lowered platforms' step risers as written.
    """
    lower_of = {k.lower for k in links}
    others = {k.upper for k in links if k.kind != "step"}
    tops: dict[int, float] = {}
    for k in links:
        if k.kind == "step" and k.upper not in lower_of | others:
            cap = heights[k.lower] + MAX_RISER - WRITTEN_UNDER
            if heights[k.upper] > cap:
                tops[k.upper] = min(tops.get(k.upper, heights[k.upper]), cap)
    for j, h in tops.items():
        heights[j] = h
    return [
        dataclasses.replace(k, risers=(heights[k.upper] - heights[k.lower],))
        if k.upper in tops
        else k
        for k in links
    ]


def stairs_within_norm(links: list[ScanLink], heights: list[float]) -> list[ScanLink]:
    """Write a flight whose fitted riser lies outside the norm's range
    (``norms.MIN_RISER``-``MAX_RISER``; the scan accepted it within ``planefit.RISER_TOL``), or
    within :data:`~mjwalk.scan.stairfit.WRITE_MARGIN` inside a limit, at the limit taken
    ``WRITE_MARGIN`` inside: its treads and its top level move, in ``heights``, to that riser's
    multiples above its bottom (by at most the riser count times ``RISER_TOL`` +
    ``WRITE_MARGIN``). A flight of 0.19 m risers fitted at 0.190008 m was written with risers
    over the norm: no stair in the written scene, only its first tread a step up. Flights are
    taken bottom up, each from its bottom as written (hall 1169: a flight of 0.14 m risers
    fitted at 0.139995 m up to the landing the next flight starts from). A flight whose top is
    otherwise only ramps' ends moves it too (a deck reached by a ramp and by a flight of 0.14 m
    risers fitted at 0.139995 m: the flight was written so, four single steps); the caller
    writes those ramps to the heights as written (:func:`ramps_to_levels`). A flight whose
    treads, or whose top, another step or stair (but a flight up from its top) starts or ends
    on keeps its riser.

    Args:
        links: the scan's links (a stair's ``via``: its tread levels, bottom up).
        heights: each level's written height, metres (changed in place).

    Returns:
        The links, the moved flights' risers as written.
    """
    new: dict[int, ScanLink] = {}
    stairs = [k for k in links if k.kind == "stair" and k.risers]
    for k in sorted(stairs, key=lambda k: heights[k.lower]):
        n = len(k.risers)
        r = (heights[k.upper] - heights[k.lower]) / n
        held = _held_levels(links, k)
        if not set(k.via) & held and (k.upper not in held or _only_ramps_on(links, k, k.upper)):
            r = written_riser(r)
            heights[k.upper] = heights[k.lower] + n * r
        for j, i in enumerate(k.via, start=1):
            heights[i] = heights[k.lower] + j * r
        if r != k.risers[0]:
            new[id(k)] = dataclasses.replace(k, risers=(r,) * n)
    return [new.get(id(k), k) for k in links]


def ramps_to_levels(
    ramps: list[ScanRamp], links: list[ScanLink], before: list[float], heights: list[float]
) -> tuple[list[ScanRamp], list[ScanLink]]:
    """The ramps whose end level :func:`stairs_within_norm` moved, moved with it: each end by
    its level's move, the low end then moved down the run if the ramp would be over
    ``norms.MAX_RAMP_SLOPE`` (``scanramps.within_limit``), so that it still meets its levels
    and keeps its own norm. Ramps whose levels kept their heights are unchanged.

    Args:
        ramps: the scan's ramps (``lower``/``upper`` index ``heights``).
        links: the scan's links, the ramps' among them in the order of ``ramps``.
        before: each level's height before the flights were written, metres.
        heights: each level's written height, metres.

    Returns:
        The ramps and the links, the moved ramps' (slope, radians; run, metres) as written.
    """
    out, moved = [], False
    for r in ramps:
        d_lo, d_hi = heights[r.lower] - before[r.lower], heights[r.upper] - before[r.upper]
        if d_lo or d_hi:
            r = within_limit(dataclasses.replace(r, h_lo=r.h_lo + d_lo, h_hi=r.h_hi + d_hi))
            moved = True
        out.append(r)
    if not moved:
        return ramps, links
    it = iter(out)
    links = [
        dataclasses.replace(k, slope=(n := next(it)).slope, run=n.length) if k.kind == "ramp" else k
        for k in links
    ]
    return out, links
