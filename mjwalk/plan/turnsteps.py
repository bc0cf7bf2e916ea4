"""Single steps as a flight, and steps that turn: a winder or spiral stair (issue 47).

A crossing over single steps (:func:`mjwalk.plan.levelroute.crossings`) is a straight flight
over levels only stepped over (:func:`stepped_over`), each step edge in line with the one below
it (:func:`in_line`), the footfalls laid along one axis. A stair whose treads are wedges round a
post or a winder's corner (DIN 18065:2020 allows such "gewendelte" stairs, a tread measured as
the chord of the walk line between its nosings) has step edges that turn from one tread to the
next, so no crossing joins the levels at its ends and a walk between them is refused.
:func:`turning_steps` names such stairs, one line each, so the refusal says why. Metres, world
frame.
"""

from __future__ import annotations

import numpy as np

from mjwalk.world import norms
from mjwalk.world.levels import LevelGraph, LevelLink


def turning_steps(graph: LevelGraph, clear: float) -> list[str]:
    """Levels joined only by single steps whose edges turn (a winder or spiral stair).

    Args:
        graph: the scene's levels and links.
        clear: how far from a level's edge the walker stands before and after a crossing,
            metres (as :func:`mjwalk.plan.levelroute.crossings` is given it).

    Returns:
        One line per pair of walked levels (lower, upper) that a chain of steps over treads
        joins only if it turns, naming the treads where it turns; empty when there is none.
    """
    passed = stepped_over(graph, clear)
    steps = [k for k in graph.links if k.kind == "step"]
    straight: set[tuple[int, int]] = set()
    turned: dict[tuple[int, int], list[int]] = {}
    for first in steps:
        if passed[first.lower] or not passed[first.upper]:
            continue  # a chain starts on a walked level and goes over a tread
        todo: list[tuple[list[LevelLink], list[int]]] = [([first], [])]
        while todo:
            chain, turns = todo.pop()
            top = chain[-1].upper
            if not passed[top]:
                ends = (chain[0].lower, top)
                if turns:
                    turned.setdefault(ends, turns)
                else:
                    straight.add(ends)
                continue
            if len(chain) >= len(steps):
                continue  # each step rises, so no chain is longer
            for k in steps:
                if k.lower == top:
                    turn = [] if in_line(chain[-1], k) else [top]
                    todo.append((chain + [k], turns + turn))
    out = []
    for (lo, up), turns in sorted(turned.items()):
        if (lo, up) in straight:
            continue
        names = ", ".join(graph.surfaces[graph.levels[i].surfaces[0]].name for i in turns)
        out.append(
            f"the steps from L{lo} to L{up} turn at {names} (a winder or spiral stair): walks "
            "over levels take straight flights only"
        )
    return out


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
