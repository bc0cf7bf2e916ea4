"""Report of many simulated cycles: walk-length distributions per route, cycle time, collisions.

:func:`report_dict` computes the figures (plain, JSON-ready data); :func:`write_report` writes them
with tables and charts into a folder; :func:`format_summary` gives a short table for the terminal.

Distributions are summarised as in agethen2018 Table 1: median (50th percentile) and
inter-quartile range (75th - 25th percentile, ``numpy.percentile``'s linear interpolation), beside
the grid-A* route length. Lengths in metres, times in seconds. Every route is reported per
direction (from -> to: a route walked there and back is two different walks) and, where it has
several, pooled. Each walk is compared with the grid-A* route between its own two ends (where the
operator stood and where the walk ended, :attr:`WalkRecord.baseline_length`): ``vs A*`` is the
median of the walks' ``length / route - 1``. The grid's 8 directions make its route up to
:data:`~mjwalk.plan.grid.OCTILE_RATIO` times a straight line, so a walk reads down to
:func:`~mjwalk.plan.grid.shortfall_bound` (about -9 % for the station's walks) without being
shorter than the shortest route between its ends.

Cycle times are also given as the 5th, 50th and 95th percentiles, overall and per operator group
(the cycle file's ``[population]``, :mod:`mjwalk.cycle.population`); with a ``takt`` the report
gives the share of cycles over takt with its 95 % Wilson score interval (Wilson, "Probable
inference, the law of succession, and statistical inference", JASA 22:209-212, 1927; good
coverage for small samples and shares near 0 or 1, where the normal approximation is not:
Brown, Cai & DasGupta, Statistical Science 16:101-133, 2001).
"""

from __future__ import annotations

import contextlib
import csv
import json
import math
from collections.abc import Mapping, Sequence
from pathlib import Path

import numpy as np

from mjwalk._io import atomic_path
from mjwalk.cycle.types import TASK_KINDS, CycleResult, operator_dict
from mjwalk.errors import MjwalkError
from mjwalk.plan.walkpath import WalkPath

#: Captured walk-path lengths of the paper's cycle (agethen2018 Table 1, "Baseline" columns):
#: route -> (median, IQR), metres. Pass as ``reference=`` for the assembly station's cycle.
CAPTURE_TABLE1: dict[str, tuple[float, float]] = {
    "T1": (2.38, 0.21),
    "T2": (2.25, 0.40),
    "T3": (3.15, 0.38),
    "T4": (2.44, 0.34),
    "T5": (1.07, 0.21),
}

#: The files :func:`write_report` writes, by key.
REPORT_FILES = {
    "json": "report.json",
    "walks": "walks.csv",
    "cycles": "cycles.csv",
    "markdown": "report.md",
    "spaghetti": "spaghetti.png",
    "histograms": "histograms.png",
}

#: The files :func:`write_report` adds when the runs were scored for ergonomics
#: (``CycleResult.ergonomics``, :mod:`mjwalk.ergonomics`).
ERGONOMICS_FILES = {"ergonomics_csv": "ergonomics.csv", "ergonomics_png": "ergonomics.png"}

#: Contact pairs listed in report.md (all of them are in report.json).
MD_PAIRS = 12

#: Percentiles of the cycle time in the report (P5, P50, P95).
CYCLE_PERCENTILES = (5, 50, 95)
#: Confidence level of the share of cycles over takt.
TAKT_CONFIDENCE = 0.95
#: Operator columns of walks.csv and cycles.csv (empty without a population).
OPERATOR_COLUMNS = ("group", "stature_m", "speed_m_s", "cadence_steps_min")

BaselineArg = Mapping[str | tuple[str, str], WalkPath | Sequence[WalkPath]]


def describe(values) -> dict[str, float]:
    """n, median, q25, q75, iqr, min, max, mean and sd (ddof 1; 0 for one value) of ``values``.

    Empty input gives n = 0 and NaN figures.
    """
    x = np.asarray(values, dtype=float).ravel()
    if x.size == 0:
        nan = float("nan")
        keys = ("median", "q25", "q75", "iqr", "min", "max", "mean", "sd")
        return {"n": 0, **dict.fromkeys(keys, nan)}
    q25, q50, q75 = np.percentile(x, [25, 50, 75])
    return {
        "n": int(x.size),
        "median": float(q50),
        "q25": float(q25),
        "q75": float(q75),
        "iqr": float(q75 - q25),
        "min": float(x.min()),
        "max": float(x.max()),
        "mean": float(x.mean()),
        "sd": float(x.std(ddof=1)) if x.size > 1 else 0.0,
    }


def percentiles(values, qs=CYCLE_PERCENTILES) -> dict[str, float]:
    """``{"n", "p5", "p50", "p95"}`` of ``values`` (NaN when empty)."""
    x = np.asarray(values, dtype=float).ravel()
    out: dict[str, float] = {"n": int(x.size)}
    ps = np.percentile(x, qs) if x.size else [float("nan")] * len(qs)
    out.update({f"p{q}": float(v) for q, v in zip(qs, ps, strict=True)})
    return out


def over_takt(cycle_times, takt: float, confidence: float = TAKT_CONFIDENCE) -> dict:
    """Share of ``cycle_times`` (s) longer than ``takt`` (s), with its Wilson score interval:
    ``{"takt", "runs", "over", "share", "ci_low", "ci_high", "confidence"}``."""
    from scipy.stats import binomtest

    x = np.asarray(cycle_times, dtype=float).ravel()
    n, k = int(x.size), int(np.sum(x > takt))
    out = {"takt": float(takt), "runs": n, "over": k, "confidence": confidence}
    if n == 0:
        return {**out, "share": float("nan"), "ci_low": float("nan"), "ci_high": float("nan")}
    ci = binomtest(k, n).proportion_ci(confidence_level=confidence, method="wilson")
    return {**out, "share": k / n, "ci_low": float(ci.low), "ci_high": float(ci.high)}


def _operators(results: Sequence[CycleResult], takt: float | None) -> dict:
    """Cycle-time percentiles (and the share over takt) per operator group, the operators'
    figures (median speed, cadence, stature) and walk times per group."""
    population = getattr(results[0].spec, "population", None)
    shares = {g.name: g.share for g in population.groups} if population else {}
    names = list(shares) + sorted({r.group for r in results} - set(shares))
    out = {}
    for name in names:
        runs = [r for r in results if r.group == name]
        ops = [r.operator for r in runs if r.operator is not None]
        entry = {
            "share": shares.get(name),
            "runs": len(runs),
            "cycle_time": percentiles([r.cycle_time for r in runs]),
            "walk_time_per_cycle_median": float(
                np.median([sum(w.duration for w in r.walks) for r in runs])
            )
            if runs
            else float("nan"),
            "speed_median": float(np.median([o.speed for o in ops])) if ops else float("nan"),
            "cadence_median": float(np.median([o.cadence for o in ops])) if ops else float("nan"),
            "stature_median": float(np.median([o.stature for o in ops])) if ops else float("nan"),
        }
        if takt is not None:
            entry["over_takt"] = over_takt([r.cycle_time for r in runs], takt)
        out[name] = entry
    return out


def _walk_figures(walks: Sequence) -> dict:
    """The figures of some walks (one direction of a route, or a route pooled): their number,
    length and duration (:func:`describe`), the median of their own grid-A* routes' lengths
    (``baseline_length``), the median of their ``length / route - 1`` (``length_vs_baseline``)
    with its distribution (``vs_baseline``), the lowest value the grid allows them
    (``vs_baseline_floor``, :func:`~mjwalk.plan.grid.shortfall_bound` at their shortest route),
    how many read lower than the bound at their own route (``below_floor``) and how many had
    no grid route between their ends (``without_baseline``)."""
    from mjwalk.plan.grid import shortfall_bound

    base = np.array([w.baseline_length for w in walks], dtype=float)
    has = np.isfinite(base) & (base > 0)
    ratio = np.array([w.length for w in walks], dtype=float)[has] / base[has] - 1.0
    vs = describe(ratio)
    return {
        "walks": len(walks),
        "length": describe([w.length for w in walks]),
        "duration": describe([w.duration for w in walks]),
        "baseline_length": float(np.median(base[has])) if has.any() else float("nan"),
        "length_vs_baseline": vs["median"],
        "vs_baseline": vs,
        "vs_baseline_floor": float(shortfall_bound(base[has].min())) if has.any() else None,
        # walks reading lower than the bound at their own route (it holds where a straight
        # line joins a walk's ends; around obstacles it is not proven)
        "below_floor": int(np.sum(ratio < shortfall_bound(base[has]) - 1e-12)),
        "without_baseline": int((~has).sum()),
    }


def _directions(walks: Sequence) -> dict[tuple[str, str], list]:
    """Walks by direction (start site, goal site), in order of first appearance."""
    out: dict[tuple[str, str], list] = {}
    for w in walks:
        out.setdefault((w.start_site, w.goal_site), []).append(w)
    return out


def _routes(results: Sequence[CycleResult]) -> list[str]:
    """Route labels in order of first appearance."""
    seen: dict[str, None] = {}
    for r in results:
        for w in r.walks:
            seen.setdefault(w.route, None)
    return list(seen)


def split_failed(
    results: Sequence[CycleResult],
) -> tuple[list[CycleResult], list[CycleResult]]:
    """The simulated cycles and the failed runs (``result.error`` set, from
    ``simulate_cycles(on_error="record")``); MjwalkError when every run failed."""
    ok = [r for r in results if getattr(r, "error", None) is None]
    failed = [r for r in results if getattr(r, "error", None) is not None]
    if not ok:
        raise MjwalkError(
            f"report: all {len(failed)} run(s) failed; the first (run {failed[0].run}): "
            f"{failed[0].error}"
        )
    return ok, failed


def report_dict(
    results: Sequence[CycleResult],
    *,
    reference: Mapping[str, tuple[float, float]] | None = None,
) -> dict:
    """The report's figures as plain data (JSON-ready).

    Args:
        results: simulated cycles (normally of one spec, one per Monte-Carlo run).
        reference: optional captured (median, IQR) walk length per route, metres (e.g.
            :data:`CAPTURE_TABLE1`); adds ``reference``, ``median_error`` (relative) and
            ``iqr_ratio`` to those routes.

    Returns:
        ``{"name", "scene", "models", "runs", "routes": {label: {...}}, "cycle_time", "collisions",
        "task_time": {kind: {...}}, "arms", "per_run"}``; see the Markdown report for meanings.
    """
    if not results:
        raise MjwalkError("report: no cycle results to report")
    results, failed = split_failed(results)
    spec = results[0].spec
    takt = getattr(spec, "takt", None)
    population = getattr(spec, "population", None)
    routes = {}
    for label in _routes(results):
        walks = [w for r in results for w in r.walks if w.route == label]
        entry = {
            # the route's walks pooled over its directions
            **_walk_figures(walks),
            # each direction (from -> to) apart: a route walked there and back is two walks
            "directions": [
                {"from": a, "to": b, **_walk_figures(ws)}
                for (a, b), ws in _directions(walks).items()
            ],
        }
        length = entry["length"]
        if reference is not None and label in reference:
            ref_median, ref_iqr = (float(v) for v in reference[label])
            entry["reference"] = {"median": ref_median, "iqr": ref_iqr}
            entry["median_error"] = length["median"] / ref_median - 1.0
            entry["iqr_ratio"] = length["iqr"] / ref_iqr if ref_iqr > 0 else float("nan")
        routes[label] = entry

    per_run_collisions = [len(r.collisions) for r in results]
    pairs: dict[str, int] = {}
    for r in results:
        for c in r.collisions:
            key = f"{getattr(c, 'body_part', '?')} vs {getattr(c, 'scene_geom', '?')}"
            pairs[key] = pairs.get(key, 0) + 1

    kinds = [k for k in TASK_KINDS if any(t.kind == k for r in results for t in r.tasks)]
    task_time = {}
    for kind in kinds:
        spans = [t.duration for r in results for t in r.tasks if t.kind == kind]
        per_cycle = [sum(t.duration for t in r.tasks if t.kind == kind) for r in results]
        task_time[kind] = {
            "count_per_cycle": len(spans) / len(results),
            "task": describe(spans),
            "per_cycle": describe(per_cycle),
        }
    arms = [a for r in results for a in r.arms]
    return {
        "name": spec.name,
        "spec": str(spec.path),
        "scene": str(spec.scene),
        "models": {  # "default" or the model files the runs used
            "step": str(getattr(spec, "step_model", "default")),
            "reach": str(getattr(spec, "reach_model", "default")),
            "reach_right": getattr(spec, "reach_model_right", None),  # None: reach mirrored
        },
        "runs": len(results),
        "failed_runs": [
            {
                "run": r.run,
                "entropy": getattr(r, "entropy", None),
                "error": r.error,
                "operator": operator_dict(r.operator),
            }
            for r in failed
        ],
        "routes": routes,
        "baseline": _baseline_note(spec),
        "cycle_time": {
            **describe([r.cycle_time for r in results]),
            **percentiles([r.cycle_time for r in results]),
        },
        "takt": takt,
        "over_takt": None if takt is None else over_takt([r.cycle_time for r in results], takt),
        "population": None if population is None else population.describe(),
        "groups": _operators(results, takt) if population is not None else {},
        "collisions": {
            "total": int(sum(per_run_collisions)),
            "runs_with_collisions": int(sum(n > 0 for n in per_run_collisions)),
            "per_run": describe(per_run_collisions),
            "by_pair": dict(sorted(pairs.items(), key=lambda kv: -kv[1])),
        },
        "task_time": task_time,
        "arms": {
            "motions": len(arms),
            "max_hand_error": max((a.hand_error for a in arms), default=0.0),
            "median_hand_error": float(np.median([a.hand_error for a in arms])) if arms else 0.0,
            "outside_range": int(sum(a.outside for a in arms)),
            # hands that ended off their target (out of the operator's reach from every spot
            # tried): the reach is recorded, but the part was not where the hand was
            "short_of_target": _short_of_target(arms),
        },
        "ergonomics": _ergonomics(results),
        "per_run": [
            {
                "run": r.run,
                "seed": r.seed,
                "entropy": getattr(r, "entropy", None),
                "cycle_time": r.cycle_time,
                "collisions": len(r.collisions),
                "operator": operator_dict(r.operator),
            }
            for r in results
        ],
    }


def _ergonomic_records(results: Sequence[CycleResult]) -> list:
    """The runs scored for ergonomics as :class:`mjwalk.ergonomics.summary.RunRecord`."""
    from mjwalk.ergonomics.summary import RunRecord

    return [
        RunRecord(r.run, r.seed, r.group, None if r.operator is None else r.operator.stature, e)
        for r in results
        if (e := getattr(r, "ergonomics", None)) is not None
    ]


def _ergonomics(results: Sequence[CycleResult]) -> dict | None:
    """The ergonomics section's figures (None when no run was scored)."""
    from mjwalk.ergonomics.summary import ergonomics_summary

    records = _ergonomic_records(results)
    return ergonomics_summary(records) if records else None


def _baseline_note(spec) -> dict:
    """What ``vs A*`` compares with: the grid A*'s cell and radius, the walks' ends, and the
    constants of its tolerance (:func:`~mjwalk.plan.grid.shortfall_bound`)."""
    from mjwalk.plan.grid import CELL_SIZE, END_EXCESS, OCTILE_RATIO

    return {
        "planner": "grid A* (8-connected)",
        "between": "each walk's own start and end (pelvis)",
        "cell": CELL_SIZE,
        "radius": getattr(spec, "radius", None),
        "octile_ratio": OCTILE_RATIO,
        "end_excess": END_EXCESS * CELL_SIZE,
        "floor": "(1 - end_excess / route) / octile_ratio - 1",
    }


def _short_of_target(arms: Sequence) -> dict:
    """The arm motions whose hand ended farther than
    :data:`~mjwalk.cycle.standoff.REACH_TOLERANCE` from its target: how many, by site (most
    first), and the largest miss (m)."""
    from mjwalk.cycle.standoff import REACH_TOLERANCE

    short = [a for a in arms if a.hand_error > REACH_TOLERANCE]
    sites: dict[str, int] = {}
    for a in short:
        sites[a.site] = sites.get(a.site, 0) + 1
    return {
        "motions": len(short),
        "tolerance": REACH_TOLERANCE,
        "sites": dict(sorted(sites.items(), key=lambda kv: -kv[1])),
        "max_error": max((a.hand_error for a in short), default=0.0),
    }


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


#: Columns of the route table up to ``vs A*`` (the terminal summary shows these).
ROUTE_COLUMNS = 9


def _pct(x: float | None) -> str:
    return "–" if x is None or math.isnan(x) else f"{100 * x:+.1f} %"


def _route_rows(rep: dict) -> tuple[list[str], list[list[str]]]:
    """The route table: one row per direction of each route, and a pooled row (``both``)
    after a route's directions where it has several; the capture's figures on the route's
    pooled (or only) row."""
    has_ref = any("reference" in e for e in rep["routes"].values())
    head = ["route", "from -> to", "walks", "grid A* [m]", "length 50th [m]", "IQR [m]"]
    head += ["duration 50th [s]", "IQR [s]", "vs A*"]
    if has_ref:
        head += ["capture 50th [m]", "IQR [m]", "median error", "IQR ratio"]

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
            else:
                out += ["–"] * 4
        return out

    rows = []
    for label, e in rep["routes"].items():
        dirs = e.get("directions") or []
        for d in dirs:
            rows.append(row(label, f"{d['from']} -> {d['to']}", d, e if len(dirs) == 1 else None))
        if len(dirs) != 1:  # several directions (or a report without them): the route pooled
            rows.append(row(label, "both" if dirs else "–", e, e))
    return head, rows


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
    """The report as Markdown (the content of ``report.md``)."""
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
        from mjwalk.ergonomics.summary import ergonomics_markdown

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
        f"{g['speed']}, cadence {g['cadence']}"
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
    """A short plain-text table of a report (from :func:`report_dict`) for the terminal."""
    ct = rep["cycle_time"]
    head, rows = _route_rows(rep)
    # the capture columns stay in report.md
    head, rows = head[:ROUTE_COLUMNS], [r[:ROUTE_COLUMNS] for r in rows]
    widths = [max(len(h), *(len(r[k]) for r in rows)) for k, h in enumerate(head)]
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


def _operator_cells(r: CycleResult) -> list[str]:
    """The OPERATOR_COLUMNS of a run (empty strings without an operator)."""
    op = getattr(r, "operator", None)
    if op is None:
        return [""] * len(OPERATOR_COLUMNS)
    return [op.group, f"{op.stature:.2f}", f"{op.speed:.4f}", f"{op.cadence:.2f}"]


def _cell(x: float, digits: int = 4) -> str:
    """A CSV cell: ``x`` to ``digits`` places, empty for NaN."""
    return "" if math.isnan(x) else f"{x:.{digits}f}"


def _write_walks_csv(path: Path, results: Sequence[CycleResult]) -> None:
    """One row per walk: its direction (``from``, ``to``), length, duration, its own grid-A*
    route (``baseline_length_m``: between ``start_x, start_y`` and ``end_x, end_y``, the
    walk's ends; empty when the grid planner found none) and ``vs_baseline`` (length over that
    route, minus 1)."""
    with open(path, "w", newline="") as fh:
        w = csv.writer(fh)
        w.writerow(
            [
                "run", "seed", "task", "route", "from", "to",
                "length_m", "duration_s", "baseline_length_m", "vs_baseline", "steps",
                "start_x", "start_y", "end_x", "end_y",
                *OPERATOR_COLUMNS,
            ]
        )  # fmt: skip
        for r in results:
            for wk in r.walks:
                w.writerow(
                    [
                        r.run,
                        r.seed,
                        wk.task,
                        wk.route,
                        wk.start_site,
                        wk.goal_site,
                        f"{wk.length:.4f}",
                        f"{wk.duration:.4f}",
                        _cell(wk.baseline_length),
                        _cell(wk.vs_baseline, 5),
                        len(wk.path.steps),
                        *(f"{v:.4f}" for v in (*wk.path.xy[0], *wk.path.xy[-1])),
                        *_operator_cells(r),
                    ]
                )


def _write_cycles_csv(path: Path, results: Sequence[CycleResult]) -> None:
    kinds = [k for k in TASK_KINDS if any(t.kind == k for r in results for t in r.tasks)]
    with open(path, "w", newline="") as fh:
        w = csv.writer(fh)
        w.writerow(
            ["run", "seed", "cycle_time_s", "walked_length_m", "walked_time_s", "collisions"]
            + ["max_hand_error_m", "reach_outside_range"]
            + [f"{k}_time_s" for k in kinds]
            + list(OPERATOR_COLUMNS)
        )
        for r in results:
            w.writerow(
                [
                    r.run,
                    r.seed,
                    f"{r.cycle_time:.4f}",
                    f"{sum(wk.length for wk in r.walks):.4f}",
                    f"{sum(wk.duration for wk in r.walks):.4f}",
                    len(r.collisions),
                    f"{max((a.hand_error for a in r.arms), default=0.0):.4f}",
                    sum(a.outside for a in r.arms),
                ]
                + [f"{sum(t.duration for t in r.tasks if t.kind == k):.4f}" for k in kinds]
                + _operator_cells(r)
            )


def write_report(
    results: Sequence[CycleResult],
    out_dir: str | Path,
    *,
    workplace=None,
    baseline: BaselineArg | None = None,
    reference: Mapping[str, tuple[float, float]] | None = None,
) -> dict[str, Path]:
    """Write the report of ``results`` into ``out_dir`` (created if needed).

    Files (keys of the returned dict, see :data:`REPORT_FILES`): ``report.json`` (the figures of
    :func:`report_dict`), ``walks.csv`` (one row per walk per run), ``cycles.csv`` (one row per
    run), ``report.md`` (Markdown tables), ``spaghetti.png`` (every run's walk paths on the floor
    plan, coloured by route, each with its own grid-A* route dashed) and ``histograms.png``
    (cycle time, and walk lengths per route and direction); with runs scored for ergonomics also
    ``ergonomics.csv`` (one row per run and task) and ``ergonomics.png``
    (:data:`ERGONOMICS_FILES`). All are written to temporary files first and renamed into place
    together at the end, so an error leaves none of them
    half-written (nor any new one at all).

    Args:
        results: the simulated cycles.
        out_dir: folder to write into.
        workplace: the scene (:class:`mjwalk.world.Workplace`) for the floor plan; default: loaded
            from the first result's ``spec.scene``.
        baseline: grid-A* routes to draw instead, keyed by route label or by
            ``(start_site, goal_site)``; each value one :class:`WalkPath` or several. Default:
            each drawn walk's own route (``WalkRecord.baseline``, between the walk's ends, as
            the simulation recorded it); ``{}`` draws none.
        reference: captured (median, IQR) walk length per route, e.g. :data:`CAPTURE_TABLE1`.
    """
    from mjwalk.plot import histograms_png, spaghetti_png  # matplotlib: loaded when drawing

    rep = report_dict(results, reference=reference)
    results = split_failed(results)[0]  # the failed runs are listed in the report only
    if workplace is None:
        from mjwalk.world import shared_workplace

        workplace = shared_workplace(results[0].spec.scene)
    routes = baseline
    for key, value in (routes or {}).items():
        paths = [value] if isinstance(value, WalkPath) else value
        if not isinstance(paths, Sequence) or not all(isinstance(p, WalkPath) for p in paths):
            raise MjwalkError(
                f"write_report: baseline[{key!r}] must be a WalkPath or a list of them, "
                f"got {type(value).__name__}"
            )
    out_dir = Path(out_dir)
    names = {**REPORT_FILES, **(ERGONOMICS_FILES if rep.get("ergonomics") else {})}
    targets = {key: out_dir / name for key, name in names.items()}
    with contextlib.ExitStack() as stack:
        tmp = {key: stack.enter_context(atomic_path(p)) for key, p in targets.items()}
        tmp["json"].write_text(json.dumps(_jsonable(rep), indent=2, allow_nan=False) + "\n")
        _write_walks_csv(tmp["walks"], results)
        _write_cycles_csv(tmp["cycles"], results)
        tmp["markdown"].write_text(format_markdown(rep), encoding="utf-8")
        spaghetti_png(tmp["spaghetti"], results, workplace, routes, rep)
        histograms_png(tmp["histograms"], results, rep)
        if "ergonomics_csv" in tmp:
            from mjwalk.ergonomics.summary import CSV_COLUMNS, ergonomics_rows
            from mjwalk.plot import ergonomics_png

            records = _ergonomic_records(results)
            with open(tmp["ergonomics_csv"], "w", newline="") as fh:
                w = csv.writer(fh)
                w.writerow(CSV_COLUMNS)
                w.writerows(ergonomics_rows(records))
            ergonomics_png(tmp["ergonomics_png"], records)
    return targets


def _jsonable(obj):
    """NaN/inf -> None (strict JSON), numpy scalars -> Python."""
    if isinstance(obj, dict):
        return {str(k): _jsonable(v) for k, v in obj.items()}
    if isinstance(obj, list | tuple):
        return [_jsonable(v) for v in obj]
    if isinstance(obj, np.generic):
        obj = obj.item()
    if isinstance(obj, float) and not math.isfinite(obj):
        return None
    return obj
