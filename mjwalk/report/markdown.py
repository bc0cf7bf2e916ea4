"""The report as text: the Markdown of ``report.md`` (:func:`format_markdown`) and the short
table for the terminal (:func:`format_summary`), both from the figures of
:func:`~mjwalk.report.figures.report_dict`. A missing or NaN figure prints as "–"."""

from __future__ import annotations

import math
from pathlib import Path

from mjwalk.ergonomics.summary import ergonomics_markdown
from mjwalk.report.levelsplit import split_markdown

#: Contact pairs listed in report.md (all of them are in report.json).
MD_PAIRS = 12

#: Columns of the route table up to ``vs A*`` (the terminal summary shows these).
ROUTE_COLUMNS = 9


def _short_line(arms: dict) -> list[str]:
    """The warning line of a report's hands short of their targets (none when every hand
    ended on its target)."""
    short = arms.get("short_of_target") or {}
    if not short.get("motions"):
        return []
    sites = ", ".join(f"{k} ({v})" for k, v in short["sites"].items())
    return [
        f"WARNING: {short['motions']} of {arms['motions']} arm motion(s) ended more than "
        f"{1000 * short['tolerance']:.0f} mm from their target (max "
        f"{1000 * short['max_error']:.0f} mm; out of reach from every spot tried): {sites}"
    ]


def _f(x: float, digits: int = 2) -> str:
    return "–" if x is None or (isinstance(x, float) and math.isnan(x)) else f"{x:.{digits}f}"


def _pct(x: float | None) -> str:
    return "–" if x is None or math.isnan(x) else f"{100 * x:+.1f} %"


def _route_rows(rep: dict) -> tuple[list[str], list[list[str]]]:
    """The route table: one row per direction of each route, and a pooled row (``both``)
    after a route's directions where it has several; the capture's figures on the route's
    pooled (or only) row."""
    has_ref = any("reference" in e for e in rep["routes"].values())
    has_planner = any("planner_iqr" in e.get("reference", {}) for e in rep["routes"].values())
    head = ["route", "from -> to", "walks", "grid A* [m]", "length 50th [m]", "IQR [m]"]
    head += ["duration 50th [s]", "IQR [s]", "vs A*"]
    if has_ref:
        head += ["capture 50th [m]", "IQR [m]", "median error", "IQR ratio"]
    if has_planner:  # the source's own planner, beside ours
        head += ["source's planner 50th [m]", "IQR [m]"]

    def row(label: str, what: str, e: dict, ref: dict | None) -> list[str]:
        out = [
            label,
            what,
            str(e["walks"]),
            _f(e["baseline_length"]),
            _f(e["length"]["median"]),
            _f(e["length"]["iqr"]),
            _f(e["duration"]["median"]),
            _f(e["duration"]["iqr"]),
            _pct(e["length_vs_baseline"]),
        ]
        if has_ref:
            if ref is not None and "reference" in ref:
                out += [
                    _f(ref["reference"]["median"]),
                    _f(ref["reference"]["iqr"]),
                    _pct(ref["median_error"]),
                    f"{100 * ref['iqr_ratio']:.0f} %",
                ]
            elif "iqr_ratio" in e:  # a direction of a route walked both ways: its IQR alone
                out += ["–"] * 3 + [f"({100 * e['iqr_ratio']:.0f} %)"]
            else:
                out += ["–"] * 4
        if has_planner:
            r = (ref or {}).get("reference", {})
            out += [_f(r.get("planner_median")), _f(r.get("planner_iqr"))]
        return out

    rows = []
    for label, e in rep["routes"].items():
        dirs = e.get("directions") or []
        for d in dirs:
            rows.append(row(label, f"{d['from']} -> {d['to']}", d, e if len(dirs) == 1 else None))
        if len(dirs) != 1:  # several directions (or a report without them): the route pooled
            rows.append(row(label, "both" if dirs else "–", e, e))
    return head, rows


def _reference_md(rep: dict) -> list[str]:
    """The line under the route table naming the published figures beside it."""
    source = rep.get("reference_source")
    if not source:
        return []
    return [
        "",
        f"`capture` and `source's planner`: {source} (the captured walks' lengths and the "
        "source's own planner's, pooled over a route's directions; on the route's pooled "
        "row; a direction's own IQR over the route's captured one in brackets on its row). "
        "A route's spread here comes from where its walks start and end (the stand "
        "zones) and from how each walk curves between them (mjwalk.plan.guide).",
    ]


def _baseline_md(rep: dict) -> list[str]:
    """The paragraph under the route table saying what ``vs A*`` compares and how low the
    grid lets it read."""
    note = rep.get("baseline")
    if not note:
        return []
    dirs = [d for e in rep["routes"].values() for d in e.get("directions") or []]
    lows = [
        (d["vs_baseline"]["min"], d["vs_baseline_floor"]) for d in dirs if d["vs_baseline"]["n"]
    ]
    missing = sum(d.get("without_baseline", 0) for d in dirs)
    example = (1.0 - note["end_excess"] / 2.4) / note["octile_ratio"] - 1.0
    out = [
        "`grid A*` and `vs A*`: each walk is compared with the grid-A* route between its own "
        "start and end (where the operator stood and where the walk ended, not the sites' "
        f"marks; {100 * note['cell']:.0f} cm cells, body radius {_f(note['radius'])} m); "
        "`grid A*` is the median of those routes' lengths, `vs A*` the median of each walk's "
        "length over its own route, minus 1. No walk is shorter than the shortest way between "
        "its ends, but the grid's route moves in 8 directions: it is up to "
        f"{100 * (note['octile_ratio'] - 1):.1f} % longer than a straight line, plus "
        f"{1000 * note['end_excess']:.0f} mm joining the ends to the grid, so a walk may read "
        f"down to (1 - {note['end_excess']:.3f} m / route) / {note['octile_ratio']:.4f} - 1 "
        f"({_pct(example)} for a 2.4 m route) and still be no shorter than the shortest way "
        "(where a straight line joins its ends).",
    ]
    if rep.get("levels"):  # walks over levels: the grid routes on their levels
        out[-1] += (
            " A walk over levels is compared with the grid-A* routes on each level of the route "
            "over levels its operator can take (the step, ramp or stair the level search "
            "finds for their step-up limit), joined through the crossings' stances, each "
            "crossing walked straight (`mjwalk.plan.levelgrid`)."
        )
    if lows:
        low = min(v for v, _ in lows)
        floor = min(f for _, f in lows if f is not None)
        below = sum(d.get("below_floor", 0) for d in dirs)
        out += [
            "",
            f"Lowest `vs A*` of a walk: {_pct(low)} (the grid allows down to {_pct(floor)} for "
            "the shortest route here); "
            + (
                "every walk within the grid's discretisation."
                if not below
                else f"{below} walk(s) below the bound at their own route (around obstacles?)."
            ),
        ]
    if missing:
        out += [
            "",
            f"{missing} walk(s) had no grid route between their ends (left out of `vs A*`).",
        ]
    return out


def _md_table(head: list[str], rows: list[list[str]]) -> str:
    lines = ["| " + " | ".join(head) + " |", "|" + "|".join("---" for _ in head) + "|"]
    lines += ["| " + " | ".join(r) + " |" for r in rows]
    return "\n".join(lines)


def format_markdown(rep: dict) -> str:
    """The report as Markdown (the content of ``report.md``).

    Args:
        rep: the report's figures (:func:`~mjwalk.report.figures.report_dict`).

    Returns:
        The Markdown text: title, models and failed runs, then the sections on walk paths per
        route, cycle time (and operators, with a population), time per task kind, collisions,
        arms and, when scored, ergonomics.
    """
    ct = rep["cycle_time"]
    col = rep["collisions"]
    out = [
        f"# Cycle report: {rep['name'] or Path(rep['spec']).stem}",
        "",
        f"Spec `{rep['spec']}`, scene `{rep['scene']}`, {rep['runs']} simulated run(s).",
        *_models_md(rep),
        "",
        *_failed_md(rep),
        "## Walk paths per route",
        "",
        "Median (50th percentile) and inter-quartile range of the walked length and duration "
        "per direction (from -> to) and, for a route walked both ways, pooled (`both`), "
        "beside the grid-A* route length (layout of agethen2018 Table 1).",
        "",
        _md_table(*_route_rows(rep)),
        *_reference_md(rep),
        "",
        *_baseline_md(rep),
        "",
        "## Cycle time",
        "",
        _md_table(
            ["P5 [s]", "P50 [s]", "P95 [s]", "IQR [s]", "min [s]", "max [s]", "mean [s]"]
            + ["sd [s]"],
            [[_f(ct[k]) for k in ("p5", "p50", "p95", "iqr", "min", "max", "mean", "sd")]],
        ),
        "",
        *_takt_md(rep),
        *_operators_md(rep),
        *split_markdown(rep.get("levels")),
        "## Time per task kind",
        "",
        _md_table(
            ["kind", "tasks per cycle", "task median [s]", "task IQR [s]", "per cycle median [s]"],
            [
                [
                    kind,
                    _f(e["count_per_cycle"], 1),
                    _f(e["task"]["median"]),
                    _f(e["task"]["iqr"]),
                    _f(e["per_cycle"]["median"]),
                ]
                for kind, e in rep["task_time"].items()
            ],
        ),
        "",
        "## Collisions",
        "",
        f"{col['total']} humanoid-vs-scene contact(s) in total; {col['runs_with_collisions']} of "
        f"{rep['runs']} run(s) had any (per run: median {_f(col['per_run']['median'], 1)}, "
        f"max {_f(col['per_run']['max'], 0)}).",
    ]
    if col["by_pair"]:
        out += [
            "",
            _md_table(
                ["body part vs scene geom", "contacts"],
                [[k, str(v)] for k, v in list(col["by_pair"].items())[:MD_PAIRS]],
            ),
        ]
        if len(col["by_pair"]) > MD_PAIRS:
            out += ["", f"(the {MD_PAIRS} most frequent of {len(col['by_pair'])} pairs)"]
    arms = rep["arms"]
    short = _short_line(arms)
    out += [
        "",
        "## Arms",
        "",
        f"{arms['motions']} arm motion(s); hand error at the target: median "
        f"{_f(1000 * arms['median_hand_error'], 0)} mm, max {_f(1000 * arms['max_hand_error'], 0)} "
        f"mm; {arms['outside_range']} outside the reach model's trained range.",
        *(["", *short] if short else []),
        "",
    ]
    if rep.get("ergonomics"):
        out += ergonomics_markdown(rep["ergonomics"])
    return "\n".join(out)


def _models_md(rep: dict) -> list[str]:
    """The models line of the Markdown report (none for a report without them)."""
    models = rep.get("models")
    if not models:
        return []
    right = models.get("reach_right")
    arms = (
        f"reach `{models['reach']}` (the right arm mirrors it)"
        if right is None
        else f"left arm `{models['reach']}`, right arm `{right}`"
    )
    return [f"Models: step `{models['step']}`, {arms}."]


def _failed_md(rep: dict) -> list[str]:
    failed = rep.get("failed_runs") or []
    if not failed:
        return []
    out = [
        f"**{len(failed)} run(s) failed** and are left out of every figure below (re-simulate "
        "one alone with `mjwalk simulate ... --only-run K`):",
        "",
    ]
    out += [f"- run {f['run']}: {f['error']}" for f in failed]
    return out + [""]


def _share_ci(e: dict | None) -> str:
    if not e:
        return "–"
    return (
        f"{100 * e['share']:.0f} % [{100 * e['ci_low']:.0f}-{100 * e['ci_high']:.0f} %]"
        if e["runs"]
        else "–"
    )


def _takt_md(rep: dict) -> list[str]:
    e = rep.get("over_takt")
    if not e:
        return []
    return [
        f"Takt {_f(e['takt'], 1)} s: {e['over']} of {e['runs']} cycle(s) over takt, "
        f"{_share_ci(e)} (share, {100 * e['confidence']:.0f} % Wilson score interval).",
        "",
    ]


def _operators_md(rep: dict) -> list[str]:
    if not rep.get("population"):
        return []
    takt = rep.get("takt") is not None
    head = ["operator group", "share", "runs", "speed 50th [m/s]", "cadence 50th [/min]"]
    head += ["stature 50th [m]", "walk time 50th [s]", "P5 [s]", "P50 [s]", "P95 [s]"]
    if takt:
        head += ["over takt [95 % CI]"]
    rows = []
    for name, e in rep["groups"].items():
        ct = e["cycle_time"]
        row = [
            name,
            "–" if e["share"] is None else f"{100 * e['share']:.0f} %",
            str(e["runs"]),
            _f(e["speed_median"]),
            _f(e["cadence_median"], 0),
            _f(e["stature_median"]),
            _f(e["walk_time_per_cycle_median"], 1),
            _f(ct["p5"], 1),
            _f(ct["p50"], 1),
            _f(ct["p95"], 1),
        ]
        if takt:
            row.append(_share_ci(e.get("over_takt")))
        rows.append(row)
    figures = [
        f"- {g['group']} ({100 * g['share']:.0f} %): stature {g['stature']}, speed "
        f"{g['speed']}, cadence {g['cadence']}; correlation speed-cadence "
        f"{g.get('speed_cadence_rho', 0):.2f}, stature-step length "
        f"{g.get('stature_step_rho', 0):.2f}"
        for g in rep["population"]
    ]
    return [
        "## Operators",
        "",
        "Each run's operator is drawn from the cycle file's `[population]`:",
        "",
        *figures,
        "",
        "Cycle time per operator group (the operator's pace sets the walk and the handling "
        "times; walk time is the walks' total per cycle):",
        "",
        _md_table(head, rows),
        "",
    ]


def format_summary(rep: dict) -> str:
    """A short plain-text table of a report for the terminal.

    Args:
        rep: the report's figures (:func:`~mjwalk.report.figures.report_dict`).

    Returns:
        The lines to print: name and runs, cycle time, the route table (without the capture
        columns) and any warnings.
    """
    ct = rep["cycle_time"]
    head, rows = _route_rows(rep)
    # the capture columns stay in report.md
    head, rows = head[:ROUTE_COLUMNS], [r[:ROUTE_COLUMNS] for r in rows]
    # a cycle without walks has no rows
    widths = [max([len(h), *(len(r[k]) for r in rows)]) for k, h in enumerate(head)]
    fmt = "  ".join(f"{{:<{w}}}" for w in widths)
    lines = [
        f"{rep['name'] or Path(rep['spec']).stem}: {rep['runs']} run(s)",
        f"cycle time  median {_f(ct['median'], 1)} s  IQR {_f(ct['iqr'], 1)} s  "
        f"(min {_f(ct['min'], 1)}, max {_f(ct['max'], 1)}, mean {_f(ct['mean'], 1)}, "
        f"sd {_f(ct['sd'], 1)})",
        *(
            [
                f"cycle time  P5 {_f(ct['p5'], 1)} s  P50 {_f(ct['p50'], 1)} s  P95 "
                f"{_f(ct['p95'], 1)} s"
            ]
            if "p5" in ct
            else []
        ),
        *(
            [f"over takt {_f(rep['over_takt']['takt'], 1)} s  {_share_ci(rep['over_takt'])}"]
            if rep.get("over_takt")
            else []
        ),
        *(
            f"  {name:<12} {e['runs']:>4} run(s)  P5 {_f(e['cycle_time']['p5'], 1)}  P50 "
            f"{_f(e['cycle_time']['p50'], 1)}  P95 {_f(e['cycle_time']['p95'], 1)} s"
            + (f"  over takt {_share_ci(e['over_takt'])}" if e.get("over_takt") else "")
            for name, e in (rep.get("groups") or {}).items()
        ),
        fmt.format(*head).rstrip(),
        *(fmt.format(*r).rstrip() for r in rows),
        *(
            f"FAILED run {f['run']} (left out of the figures; --only-run {f['run']} re-simulates "
            f"it): {f['error']}"
            for f in rep.get("failed_runs") or []
        ),
        f"collisions  {rep['collisions']['total']} total, "
        f"{rep['collisions']['runs_with_collisions']} run(s) with any",
        *_short_line(rep["arms"]),
    ]
    return "\n".join(lines)
