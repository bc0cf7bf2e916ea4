"""The report's figures: walk-length distributions per route and direction, cycle time,
collisions, task times and arm motions of many simulated cycles, as plain JSON-ready data
(:func:`report_dict`).

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

from collections.abc import Mapping, Sequence

import numpy as np
from scipy.stats import binomtest

from mjwalk.cycle.standoff import REACH_TOLERANCE
from mjwalk.cycle.types import TASK_KINDS, CycleResult, operator_dict
from mjwalk.ergonomics.summary import RunRecord, ergonomics_summary
from mjwalk.errors import MjwalkError
from mjwalk.plan.grid import END_EXCESS, OCTILE_RATIO, shortfall_bound
from mjwalk.plan.occupancy import CELL_SIZE
from mjwalk.report.levelsplit import level_split

#: Captured walk-path lengths of the paper's cycle (agethen2018 Table 1, "Baseline" columns):
#: route -> (median, IQR), metres. Pass as ``reference=`` for the assembly station's cycle.
CAPTURE_TABLE1: dict[str, tuple[float, float]] = {
    "T1": (2.38, 0.21),
    "T2": (2.25, 0.40),
    "T3": (3.15, 0.38),
    "T4": (2.44, 0.34),
    "T5": (1.07, 0.21),
}

#: Percentiles of the cycle time in the report (P5, P50, P95).
CYCLE_PERCENTILES = (5, 50, 95)
#: Confidence level of the share of cycles over takt.
TAKT_CONFIDENCE = 0.95


def describe(values) -> dict[str, float]:
    """Summary figures of a sample.

    Args:
        values: the sample (any shape, flattened).

    Returns:
        ``{"n", "median", "q25", "q75", "iqr", "min", "max", "mean", "sd"}``: percentiles by
        ``numpy.percentile``'s linear interpolation, iqr = q75 - q25, sd with ddof 1 (0 for
        one value). Empty input gives n = 0 and NaN figures.
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


def walks_summary(paths: Sequence) -> dict[str, dict[str, float]]:
    """Length, duration and planning time of planned walks, each summarised by :func:`describe`.

    Args:
        paths: the walks (:class:`~mjwalk.plan.walkpath.WalkPath`, with ``meta["seconds"]``).

    Returns:
        ``{"length": ... (m), "duration": ... (s), "planning_ms": ... (ms)}``, each
        :func:`describe`'s dict (``median``, ``iqr``, ...).
    """
    return {
        "length": describe([p.length for p in paths]),
        "duration": describe([p.duration for p in paths]),
        "planning_ms": describe([1000 * p.meta["seconds"] for p in paths]),
    }


def percentiles(values, qs=CYCLE_PERCENTILES) -> dict[str, float]:
    """Percentiles of a sample.

    Args:
        values: the sample (any shape, flattened).
        qs: the percentiles to give, in [0, 100] (default :data:`CYCLE_PERCENTILES`).

    Returns:
        ``{"n", "p5", "p50", "p95"}`` for the default ``qs`` (``"p{q}"`` for each), NaN when
        empty.
    """
    x = np.asarray(values, dtype=float).ravel()
    out: dict[str, float] = {"n": int(x.size)}
    ps = np.percentile(x, qs) if x.size else [float("nan")] * len(qs)
    out.update({f"p{q}": float(v) for q, v in zip(qs, ps, strict=True)})
    return out


def over_takt(cycle_times, takt: float, confidence: float = TAKT_CONFIDENCE) -> dict:
    """Share of cycles longer than the takt, with its Wilson score interval.

    Args:
        cycle_times: the cycles' times, seconds.
        takt: the takt time, seconds.
        confidence: confidence level of the interval.

    Returns:
        ``{"takt", "runs", "over", "share", "ci_low", "ci_high", "confidence"}``: ``over`` of
        ``runs`` cycles took longer than ``takt``, share = over / runs (NaN, with its interval,
        when there are no runs).
    """
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
    """The simulated cycles and the failed runs apart, each in the given order.

    Args:
        results: a batch's results; failed runs have ``result.error`` set
            (``simulate_cycles(on_error="record")``).

    Returns:
        ``(simulated, failed)``.

    Raises:
        MjwalkError: every run failed (naming the first one's error).
    """
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
    reference: Mapping[str, tuple[float, ...]] | None = None,
) -> dict:
    """The report's figures as plain data (JSON-ready).

    Args:
        results: simulated cycles (normally of one spec, one per Monte-Carlo run).
        reference: optional captured (median, IQR) walk length per route, metres (e.g.
            :data:`CAPTURE_TABLE1`), optionally followed by the source's own planner's
            (median, IQR); adds ``reference`` (``median``, ``iqr``, ``planner_median``,
            ``planner_iqr``), ``median_error`` (relative) and ``iqr_ratio`` to those routes.
            Default: the spec's own (:attr:`CycleSpec.reference`, its [reference] table), and
            ``reference_source`` at the top level.

    Returns:
        ``{"name", "scene", "models", "runs", "routes": {label: {...}}, "cycle_time", "collisions",
        "task_time": {kind: {...}}, "arms", "per_run"}``; see the Markdown report for meanings.
    """
    if not results:
        raise MjwalkError("report: no cycle results to report")
    results, failed = split_failed(results)
    spec = results[0].spec
    if reference is None:
        reference = getattr(spec, "reference", None)
    takt = getattr(spec, "takt", None)
    population = getattr(spec, "population", None)
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
        "routes": _route_figures(results, reference),
        "reference_source": getattr(spec, "reference_source", "") if reference else "",
        "baseline": _baseline_note(spec),
        "cycle_time": {
            **describe([r.cycle_time for r in results]),
            **percentiles([r.cycle_time for r in results]),
        },
        "takt": takt,
        "over_takt": None if takt is None else over_takt([r.cycle_time for r in results], takt),
        "population": None if population is None else population.describe(),
        "groups": _operators(results, takt) if population is not None else {},
        "collisions": _collision_figures(results),
        "task_time": _task_times(results),
        "arms": _arm_figures([a for r in results for a in r.arms]),
        "ergonomics": _ergonomics(results, takt),
        **_levels(results),
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


def _levels(results: Sequence[CycleResult]) -> dict:
    """``{"levels": split}`` when a walk leaves the floor (:mod:`mjwalk.report.levelsplit`),
    else nothing: a flat cycle's report is as before."""
    split = level_split(results)
    return {} if split is None else {"levels": split}


def _route_figures(
    results: Sequence[CycleResult], reference: Mapping[str, tuple[float, ...]] | None
) -> dict:
    """Each route's walk figures, pooled and per direction, beside its reference when given."""
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
            ref_median, ref_iqr, *planner = (float(v) for v in reference[label])
            entry["reference"] = {"median": ref_median, "iqr": ref_iqr}
            if len(planner) == 2:  # the source's own planner's figures
                entry["reference"]["planner_median"] = planner[0]
                entry["reference"]["planner_iqr"] = planner[1]
            entry["median_error"] = length["median"] / ref_median - 1.0
            entry["iqr_ratio"] = length["iqr"] / ref_iqr if ref_iqr > 0 else float("nan")
            # each direction's spread against the route's captured IQR (issue 48, station
            # spread: each direction at least 60 % of it; the source pools the directions)
            for d in entry["directions"]:
                d["iqr_ratio"] = d["length"]["iqr"] / ref_iqr if ref_iqr > 0 else float("nan")
        routes[label] = entry
    return routes


def _collision_figures(results: Sequence[CycleResult]) -> dict:
    """Collisions: total, runs with any, per run, and by body part vs scene geom (most first)."""
    per_run_collisions = [len(r.collisions) for r in results]
    pairs: dict[str, int] = {}
    for r in results:
        for c in r.collisions:
            key = f"{getattr(c, 'body_part', '?')} vs {getattr(c, 'scene_geom', '?')}"
            pairs[key] = pairs.get(key, 0) + 1
    return {
        "total": int(sum(per_run_collisions)),
        "runs_with_collisions": int(sum(n > 0 for n in per_run_collisions)),
        "per_run": describe(per_run_collisions),
        "by_pair": dict(sorted(pairs.items(), key=lambda kv: -kv[1])),
    }


def _task_times(results: Sequence[CycleResult]) -> dict:
    """Per task kind (in :data:`TASK_KINDS` order, kinds done only): how many per cycle, and
    the times of one task and of all of that kind in a cycle (s)."""
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
    return task_time


def _arm_figures(arms: Sequence) -> dict:
    """The arm motions: how many, the hands' errors (m), how many left the model's range."""
    return {
        "motions": len(arms),
        "max_hand_error": max((a.hand_error for a in arms), default=0.0),
        "median_hand_error": float(np.median([a.hand_error for a in arms])) if arms else 0.0,
        "outside_range": int(sum(a.outside for a in arms)),
        # hands that ended off their target (out of the operator's reach from every spot
        # tried): the reach is recorded, but the part was not where the hand was
        "short_of_target": _short_of_target(arms),
    }


def ergonomic_records(results: Sequence[CycleResult]) -> list:
    """The runs scored for ergonomics, as the ergonomics summary reads them.

    Args:
        results: simulated cycles (runs without ``ergonomics`` are left out).

    Returns:
        One :class:`mjwalk.ergonomics.summary.RunRecord` per scored run (run, seed, operator
        group, stature in metres or None, its ergonomics), in order.
    """
    return [
        RunRecord(r.run, r.seed, r.group, None if r.operator is None else r.operator.stature, e)
        for r in results
        if (e := getattr(r, "ergonomics", None)) is not None
    ]


def _ergonomics(results: Sequence[CycleResult], takt: float | None) -> dict | None:
    """The ergonomics section's figures (None when no run was scored)."""
    records = ergonomic_records(results)
    return ergonomics_summary(records, takt) if records else None


def _baseline_note(spec) -> dict:
    """What ``vs A*`` compares with: the grid A*'s cell and radius, the walks' ends, and the
    constants of its tolerance (:func:`~mjwalk.plan.grid.shortfall_bound`)."""
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
