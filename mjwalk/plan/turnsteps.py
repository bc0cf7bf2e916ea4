"""Single steps as a flight, and steps that turn: a winder or spiral stair (issue 47).

A crossing over single steps (:func:`mjwalk.plan.levelroute.crossings`) is a straight flight
over levels only stepped over (:func:`stepped_over`), each step edge in line with the one below
it (:func:`in_line`), the footfalls laid along one axis. A stair whose treads are wedges round a
post or a winder's corner (DIN 18065:2020 allows such "gewendelte" stairs, a tread measured as
the chord of the walk line between its nosings) has step edges that turn from one tread to the
next, so no straight crossing joins the levels at its ends: one that meets DIN 18065 on its
walk line is walked along it (:mod:`mjwalk.plan.windercross`, routed by
:mod:`mjwalk.plan.winderroute`), one that breaks it is refused. :func:`turning_steps` names
such stairs, one line each, with the stair measured on its walk line
(:mod:`mjwalk.world.walkline`): a tread that breaks DIN 18065's step rule there is named with
its numbers, so the refusal says why. Metres, world frame.
"""

from __future__ import annotations

import itertools

import numpy as np

from mjwalk.world import norms
from mjwalk.world.levels import LevelGraph, LevelLink
from mjwalk.world.walkline import walk_line_faults, walk_line_treads


def turning_steps(graph: LevelGraph, clear: float) -> list[str]:
    """Levels joined only by single steps whose edges turn (a winder or spiral stair).

    Each such stair is measured on its walk line (:mod:`mjwalk.world.walkline`, DIN 18065):
    the line says whether its treads meet the step rule there, and if not, which tread breaks
    it and by how much.

    Args:
        graph: the scene's levels and links.
        clear: how far from a level's edge the walker stands before and after a crossing,
            metres (as :func:`mjwalk.plan.levelroute.crossings` is given it).

    Returns:
        One line per pair of walked levels (lower, upper) that a chain of steps over treads
        joins only if it turns, naming the treads where it turns and its walk-line figures;
        empty when there is none.
    """
    return [
        f"the steps from L{lo} to L{up} " + _verdict(graph, chain)
        for (lo, up), chain in sorted(turned_chains(graph, clear).items())
    ]


def turned_chains(graph: LevelGraph, clear: float) -> dict[tuple[int, int], list[LevelLink]]:
    """Per pair of walked levels joined only by steps that turn, the chain of steps between
    them that DIN 18065 faults least on its walk line (a side step onto the first tread is no
    stair's way).

    Args:
        graph: the scene's levels and links.
        clear: how far from a level's edge the walker stands, metres.

    Returns:
        {(lower, upper): the chain's step links bottom up}; empty when there is none.
    """
    straight, turned = _chains(graph, clear)
    out = {}
    for ends, chains in sorted(turned.items()):
        if ends in straight:
            continue
        scored = [
            (len(walk_line_faults(walk_line_treads(graph, c))), i) for i, c in enumerate(chains)
        ]
        out[ends] = chains[min(scored)[1]]
    return out


def _chains(
    graph: LevelGraph, clear: float
) -> tuple[set[tuple[int, int]], dict[tuple[int, int], list[list[LevelLink]]]]:
    """Every chain of steps over treads between two walked levels: the level pairs one
    straight chain joins, and per pair the chains that turn."""
    passed = stepped_over(graph, clear)
    steps = [k for k in graph.links if k.kind == "step"]
    straight: set[tuple[int, int]] = set()
    turned: dict[tuple[int, int], list[list[LevelLink]]] = {}
    for first in steps:
        if passed[first.lower] or not passed[first.upper]:
            continue  # a chain starts on a walked level and goes over a tread
        todo: list[tuple[list[LevelLink], bool]] = [([first], False)]
        while todo:
            chain, turns = todo.pop()
            top = chain[-1].upper
            if not passed[top]:
                ends = (chain[0].lower, top)
                if turns:
                    turned.setdefault(ends, []).append(chain)
                else:
                    straight.add(ends)
                continue
            if len(chain) >= len(steps):
                continue  # each step rises, so no chain is longer
            for k in steps:
                if k.lower == top:
                    todo.append((chain + [k], turns or not in_line(chain[-1], k)))
    return straight, turned


def _verdict(graph: LevelGraph, chain: list[LevelLink]) -> str:
    """Where a turning chain turns and what its walk line says, as the end of a refusal."""
    turns = [b.upper for b, a in itertools.pairwise(chain) if not in_line(b, a)]
    names = ", ".join(graph.surfaces[graph.levels[i].surfaces[0]].name for i in turns)
    treads = walk_line_treads(graph, chain)
    faults = walk_line_faults(treads)
    if faults:
        return (
            f"turn at {names} (a winder or spiral stair) and break DIN 18065 on its walk line "
            f"(the middle of its width): {'; '.join(faults)}: no stair a walk takes"
        )
    t = [x.tread for x in treads]
    r = [x.step for x in treads]
    return (
        f"turn at {names} (a winder or spiral stair; on its walk line treads {min(t):.3f}-"
        f"{max(t):.3f} m, 2R + T {min(r):.3f}-{max(r):.3f} m, within DIN 18065's step rule): "
        "walked along its walk line"
    )


def stepped_over(graph: LevelGraph, clear: float) -> list[bool]:
    """Per level, whether walks only step over it: a tread, or one surface less than two
    clearances deep (a 0.4 m step block, deeper than ``norms.MAX_TREAD``): no crossing's
    stance fits ``clear`` from both its edges; it is passed in one footfall, as a tread.

    Args:
        graph: the scene's levels and links.
        clear: how far from a level's edge the walker stands, metres.

    Returns:
        One flag per level of ``graph``, True where walks only step over it.
    """
    own: dict[int | None, list] = {}  # the surfaces per level (a ramp's: on none)
    for s, i in zip(graph.surfaces, graph.level_of, strict=True):
        own.setdefault(i, []).append(s)
    return [
        lv.kind == "tread"
        or (lv.kind == "platform" and len(own[i]) == 1 and own[i][0].depth < 2.0 * clear)
        for i, lv in enumerate(graph.levels)
    ]


def in_line(below: LevelLink, above: LevelLink) -> bool:
    """Whether step ``above`` lies straight across the level ``below`` steps onto: its edge
    parallel, the depth the same within ``norms.STAIR_TOLERANCE`` (a block's sides meet the
    floor too, and a chain from a side edge is no flight).

    Args:
        below: the step onto the level.
        above: a step off it.

    Returns:
        True when ``above`` continues ``below`` as a straight flight's next step.
    """
    a = np.asarray(below.lower_edge, dtype=float)
    d = (a[1] - a[0]) / max(float(np.linalg.norm(a[1] - a[0])), 1e-12)
    n = np.array([-d[1], d[0]])  # the edge's unit normal
    d = (np.asarray(above.lower_edge, dtype=float) - a[0]) @ n
    return bool(abs(d[1] - d[0]) <= norms.STAIR_TOLERANCE and min(abs(d[0]), abs(d[1])) > 0.0)
