"""The report's files: ``report.json``, ``walks.csv``, ``cycles.csv``, ``report.md``,
``spaghetti.png`` and ``histograms.png`` in one folder (:func:`write_report`), written all or
nothing: each to a temporary file first, renamed into place together at the end."""

from __future__ import annotations

import contextlib
import csv
import json
import math
from collections.abc import Mapping, Sequence
from pathlib import Path

import numpy as np

from mjwalk._io import atomic_path
from mjwalk.cycle.types import TASK_KINDS, CycleResult
from mjwalk.ergonomics.summary import csv_header, ergonomics_rows
from mjwalk.errors import MjwalkError
from mjwalk.plan.walkpath import WalkPath
from mjwalk.report.figures import ergonomic_records, report_dict, split_failed
from mjwalk.report.levelsplit import KINDS, crossings_of, walk_kinds
from mjwalk.report.markdown import format_markdown
from mjwalk.world import shared_workplace

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

#: Operator columns of walks.csv and cycles.csv (empty without a population).
OPERATOR_COLUMNS = ("group", "stature_m", "speed_m_s", "cadence_steps_min")

BaselineArg = Mapping[str | tuple[str, str], WalkPath | Sequence[WalkPath]]


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
    route, minus 1). When a walk leaves the floor, also its seconds per kind
    (:data:`~mjwalk.report.levelsplit.KINDS`) and the crossings it takes."""
    levels = any(wk.path.meta.get("levels") for r in results for wk in r.walks)
    with open(path, "w", newline="") as fh:
        w = csv.writer(fh)
        w.writerow(
            [
                "run", "seed", "task", "route", "from", "to",
                "length_m", "duration_s", "baseline_length_m", "vs_baseline", "steps",
                "start_x", "start_y", "end_x", "end_y",
                *OPERATOR_COLUMNS,
                *([f"{k}_s" for k in KINDS] + ["crossings"] if levels else []),
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
                        *(_level_cells(wk.path) if levels else []),
                    ]
                )


def _level_cells(path: WalkPath) -> list[str]:
    """A walk's seconds per kind and its crossings (walks.csv's level columns)."""
    kinds = walk_kinds(path)
    return [*(f"{kinds[k]:.4f}" for k in KINDS), crossings_of(path)]


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
    report: dict | None = None,
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
        report: :func:`report_dict` of the same ``results`` and ``reference`` when the caller
            has it already (``mjwalk simulate`` prints it too); None: computed here. Over
            thousands of runs it takes seconds (the stature trends' bootstrap bands).

    Returns:
        The path of each file written, by its key in :data:`REPORT_FILES` (and
        :data:`ERGONOMICS_FILES`).
    """
    # deferred: matplotlib loads only when a report is drawn
    from mjwalk.render.plot import histograms_png, spaghetti_png

    rep = report_dict(results, reference=reference) if report is None else report
    results = split_failed(results)[0]  # the failed runs are listed in the report only
    if workplace is None:
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
            from mjwalk.render.plot import ergonomics_png  # deferred: matplotlib, when drawing

            records = ergonomic_records(results)
            with open(tmp["ergonomics_csv"], "w", newline="") as fh:
                w = csv.writer(fh)
                w.writerow(csv_header())
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
