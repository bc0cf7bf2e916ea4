"""The report's split of walk time over levels (issue 47): per operator group, how much of a
cycle's walking is level walking, stairs, ramps and single steps, and which crossings each
group's walks take -- a group whose step-up limit is below a riser (``[population] step_up``,
:mod:`mjwalk.cycle.stepup`) is shown with the route it takes instead (the ramp).

Read from each walk's ``meta["levels"]`` (:func:`mjwalk.plan.levelstitch.level_meta`), which
counts each step by the surfaces its foot leaves and lands on: the line-up steps before a
stair, the steps on past it and a crossing's stance steps are level walking; a walk on the
floor alone counts as level walking. A report of cycles with no walk over levels has
no split (:func:`level_split` gives None) and its files are exactly as before. Seconds.
"""

from __future__ import annotations

from collections import Counter
from collections.abc import Sequence

import numpy as np

#: The kinds of walking the split gives, in its columns' order.
KINDS = ("level", "stairs", "ramps", "steps")


def walk_kinds(path) -> dict[str, float]:
    """A walk's seconds per kind.

    Args:
        path: the walk (:class:`~mjwalk.plan.walkpath.WalkPath`).

    Returns:
        {kind: seconds} over :data:`KINDS` (a walk on one level: all of it ``level``).
    """
    levels = path.meta.get("levels")
    if not levels:
        return {"level": float(path.duration), "stairs": 0.0, "ramps": 0.0, "steps": 0.0}
    per_kind = levels.get("per_kind", {})
    return {k: float(per_kind.get(k, {}).get("seconds", 0.0)) for k in KINDS}


def crossings_of(path) -> str:
    """The crossings a walk takes, in order ("stair up, step down"), or "" on one level.

    Args:
        path: the walk.

    Returns:
        The crossings' kinds and directions joined by ", ".
    """
    route = (path.meta.get("levels") or {}).get("route", [])
    return ", ".join(f"{e['kind']} {e['direction']}" for e in route if e["kind"] != "level")


def level_split(results: Sequence) -> dict | None:
    """The split of walk time per operator group.

    Args:
        results: the successful cycle results (``walks``, ``group``).

    Returns:
        None when no walk leaves the floor; else {group: {"runs", "walk_time" (median seconds
        of walking per cycle), "median" and "mean" ({kind: seconds per cycle}), "share" ({kind:
        share of the group's walk time}), "max_riser" (the step-up limits its walks used, m),
        "routes" ({walk direction: {crossings: count}})}}; the group "" without a population.
    """
    if not any(w.path.meta.get("levels") for r in results for w in r.walks):
        return None
    out: dict[str, dict] = {}
    for name in dict.fromkeys(r.group for r in results):
        runs = [r for r in results if r.group == name]
        per_run = np.array(
            [[sum(walk_kinds(w.path)[k] for w in r.walks) for k in KINDS] for r in runs]
        )
        total = float(per_run.sum())
        routes: dict[str, Counter] = {}
        risers = set()
        for r in runs:
            for w in r.walks:
                levels = w.path.meta.get("levels")
                if levels:
                    routes.setdefault(w.direction, Counter())[crossings_of(w.path)] += 1
                    risers.add(round(float(levels["max_riser"]), 3))
        out[name] = {
            "runs": len(runs),
            "walk_time": float(np.median(per_run.sum(axis=1))),
            "median": dict(zip(KINDS, np.median(per_run, axis=0).tolist(), strict=True)),
            "mean": dict(zip(KINDS, per_run.mean(axis=0).tolist(), strict=True)),
            "share": {
                k: float(per_run[:, i].sum() / total) if total > 0 else 0.0
                for i, k in enumerate(KINDS)
            },
            "max_riser": sorted(risers),
            "routes": {d: dict(c.most_common()) for d, c in routes.items()},
        }
    return out


def split_markdown(split: dict | None) -> list[str]:
    """The report.md section of the split (nothing without one).

    Args:
        split: :func:`level_split`'s figures.

    Returns:
        Markdown lines: the table of walk time per group and kind, then the crossings each
        group's walks over levels took.
    """
    if not split:
        return []
    head = ["operator group", "runs", "walk time 50th [s]"]
    head += [f"{k} mean [s] (share)" for k in KINDS] + ["step-up limit [m]"]
    rows, notes = [], []
    for name, e in split.items():
        cells = [f"{e['mean'][k]:.1f} ({100 * e['share'][k]:.0f} %)" for k in KINDS]
        limit = ", ".join(f"{v:.2f}" for v in e["max_riser"]) or "–"
        rows.append([name or "all", str(e["runs"]), f"{e['walk_time']:.1f}", *cells, limit])
        for direction, taken in e["routes"].items():
            ways = "; ".join(f"{way or 'one level'} ({n}x)" for way, n in taken.items())
            notes.append(f"- {name or 'all'}, {direction}: {ways}")
    table = ["| " + " | ".join(head) + " |", "|" + "---|" * len(head)]
    table += ["| " + " | ".join(r) + " |" for r in rows]
    return [
        "## Walking over levels",
        "",
        "Walk time per cycle split into level walking, stairs, ramps and single steps, per "
        "operator group (means per cycle; the share of the group's walk time). A group whose "
        "step-up limit (`[population] step_up`) is below a riser takes the ramp instead:",
        "",
        *table,
        "",
        "Crossings taken per walk direction:",
        "",
        *notes,
        "",
    ]
