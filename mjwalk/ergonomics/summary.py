"""The workforce's ergonomics: distributions of many runs' scores, overall and per operator group.

:func:`ergonomics_summary` takes one :class:`RunRecord` per simulated cycle (its operator's group
and stature, and its :class:`~mjwalk.ergonomics.results.RunErgonomics`) and gives, overall and per
group: P50/P95 of each cycle's peak RULA and REBA; the share of cycles reaching each RULA action
level and REBA risk level, with its 95 % Wilson score interval (Wilson 1927; as the report's share
over takt); the NIOSH lifting index per lift (P50/P95) and the share of cycles with a lift index
above 1, and apart from them the lifts the equation gives no index (RWL 0: a frequency beyond Table
5's, or H, V, D or A beyond its limit) with the limit each crossed; ISO 11226's share of cycles
with a static holding that is not acceptable. It names the tasks and body parts that drive the
peaks, and measures the dependence on stature (Spearman's rank correlation of stature and peak
RULA, and each task's median RULA for the shortest and the tallest third of the operators).
:func:`ergonomics_rows` gives the rows of ``ergonomics.csv`` (one per run and task),
:func:`ergonomics_markdown` the report's section.

Each method's figures, its columns of the operator groups' table, its notes and its
ergonomics.csv columns come from the registry (:data:`mjwalk.ergonomics.registry.SCORES`,
through the hooks of :class:`~mjwalk.ergonomics.score.Score`); the per-task table, the peaks'
drivers and the stature dependence read the RULA and REBA peaks.
"""

from __future__ import annotations

from collections import Counter
from dataclasses import dataclass

import numpy as np

from mjwalk.ergonomics.registry import SCORES, STATS_ORDER, TASK_COLUMNS, csv_columns, in_order
from mjwalk.ergonomics.results import RunErgonomics
from mjwalk.ergonomics.score import CONFIDENCE, fmt, percentiles, share
from mjwalk.ergonomics.workforce import exposure_markdown, exposure_summary


def csv_header() -> list[str]:
    """The columns of ergonomics.csv: :data:`~mjwalk.ergonomics.registry.TASK_COLUMNS`, then
    the registered methods' (:func:`~mjwalk.ergonomics.registry.csv_columns`).

    Returns:
        The column names, as the registry is when called.
    """
    return [*TASK_COLUMNS, *(c.name for c in csv_columns())]


#: Columns of ergonomics.csv with the built-in methods (:func:`csv_header` reads the registry
#: as it is when called).
CSV_COLUMNS = tuple(csv_header())


@dataclass
class RunRecord:
    """One run's operator and scores (``group`` "" and ``stature`` None without a population)."""

    run: int
    seed: int | None
    group: str
    stature: float | None
    ergo: RunErgonomics


def _stats(records: list[RunRecord]) -> dict:
    """Every registered method's figures of a group of runs, in report.json's order."""
    runs = [r.ergo for r in records]
    out: dict = {"runs": len(records)}
    for s in SCORES.values():
        out.update(s.stats(runs))
    return {k: out[k] for k in in_order(out, STATS_ORDER)}


def _drivers(records: list[RunRecord]) -> dict:
    """Which tasks and body parts reach each cycle's RULA and REBA peak: over runs, how many
    cycles reach their peak in each (task, body part) (a cycle counts once per task tied at its
    peak)."""
    rula_d: Counter = Counter()
    reba_d: Counter = Counter()
    for r in records:
        for t in r.ergo.tasks:
            label = f"task {t.index} {t.kind} {t.site or ''}".strip()
            if t.rula == r.ergo.rula_peak:
                rula_d[f"{label}: {t.rula_driver}"] += 1
            if t.reba == r.ergo.reba_peak:
                reba_d[f"{label}: {t.reba_driver}"] += 1
    return {"rula": dict(rula_d.most_common()), "reba": dict(reba_d.most_common())}


def _tasks(records: list[RunRecord]) -> list[dict]:
    by: dict[int, list] = {}
    for r in records:
        for t in r.ergo.tasks:
            by.setdefault(t.index, []).append((r, t))
    out = []
    for idx in sorted(by):
        rows = by[idx]
        t0 = rows[0][1]
        out.append(
            {
                "task": idx,
                "kind": t0.kind,
                "site": t0.site,
                "rula": percentiles([t.rula for _, t in rows]),
                "reba": percentiles([t.reba for _, t in rows]),
                "rula_driver": Counter(t.rula_driver for _, t in rows).most_common(1)[0][0],
            }
        )
    return out


def _stature(records: list[RunRecord]) -> dict | None:
    """Stature dependence: Spearman's rho of stature and peak RULA; per reach task the median
    RULA and upper-arm score of the shortest and tallest thirds."""
    from scipy.stats import spearmanr  # deferred: scipy.stats takes ~0.3 s to import

    rec = [r for r in records if r.stature is not None]
    if len(rec) < 6:
        return None
    st = np.array([r.stature for r in rec], dtype=float)
    lo, hi = np.percentile(st, [100 / 3, 200 / 3])
    peaks = np.array([r.ergo.rula_peak for r in rec], dtype=float)
    constant = np.ptp(st) == 0 or np.ptp(peaks) == 0  # rho is undefined
    rho = float("nan") if constant else spearmanr(st, peaks).statistic
    tasks = []
    idxs = sorted({t.index for r in rec for t in r.ergo.tasks if t.reach})
    for idx in idxs:
        short = [t for r in rec if r.stature <= lo for t in r.ergo.tasks if t.index == idx]
        tall = [t for r in rec if r.stature >= hi for t in r.ergo.tasks if t.index == idx]
        if not short or not tall:
            continue
        tasks.append(
            {
                "task": idx,
                "kind": short[0].kind,
                "site": short[0].site,
                "rula_short": float(np.median([t.rula for t in short])),
                "rula_tall": float(np.median([t.rula for t in tall])),
                "upper_arm_short": float(np.median([t.upper_arm for t in short])),
                "upper_arm_tall": float(np.median([t.upper_arm for t in tall])),
            }
        )
    return {
        "short_below_m": float(lo),
        "tall_above_m": float(hi),
        "spearman_rho_stature_rula_peak": None if not np.isfinite(rho) else float(rho),
        "tasks": tasks,
    }


def ergonomics_summary(records: list[RunRecord], takt: float | None = None) -> dict:
    """The report's ergonomics figures (see the module docstring).

    Args:
        records: the scored runs.
        takt: the cycle's takt, s (None: none given); a shift's cycles for the exposure.

    Returns:
        Plain, JSON-ready data: ``exposure`` (:func:`~mjwalk.ergonomics.workforce.
        exposure_summary`), ``methods``, ``overall`` and per-group figures, ``drivers``,
        ``tasks`` and ``stature``.
    """
    groups: dict[str, list[RunRecord]] = {}
    for r in records:
        groups.setdefault(r.group, []).append(r)
    return {
        "exposure": exposure_summary(records, takt),
        "methods": {
            **{name: sc.source for name, sc in SCORES.items()},
            "shares": "cycles reaching at least the level, with 95 % Wilson score interval",
        },
        "overall": _stats(records),
        "groups": {g: _stats(rs) for g, rs in groups.items() if g},
        "drivers": _drivers(records),
        "tasks": _tasks(records),
        "stature": _stature(records),
    }


def ergonomics_rows(records: list[RunRecord]) -> list[list]:
    """Rows of ergonomics.csv (:func:`csv_header`): one per run and task.

    Args:
        records: the scored runs.

    Returns:
        The rows, each a list of cells in the header's order.
    """
    cols = csv_columns()
    rows = []
    for r in records:
        for t in r.ergo.tasks:
            rows.append(
                [
                    r.run, r.seed, r.group, "" if r.stature is None else f"{r.stature:.3f}",
                    t.index, t.kind, t.site or "", *(c.cell(r.ergo, t) for c in cols),
                ]
            )  # fmt: skip
    return rows


def _table(head: list[str], rows: list[list[str]]) -> list[str]:
    return [
        "| " + " | ".join(head) + " |",
        "|" + "|".join("---" for _ in head) + "|",
        *["| " + " | ".join(r) + " |" for r in rows],
    ]


def ergonomics_markdown(e: dict) -> list[str]:
    """The report.md section of the ergonomics figures.

    Args:
        e: :func:`ergonomics_summary`'s figures.

    Returns:
        Markdown lines.
    """
    blocks = [("all operators", e["overall"])] + list(e["groups"].items())
    table = [c for sc in SCORES.values() for c in sc.table]
    head = ["operators", "runs", *(c.name for c in table)]
    rows = [[name, str(s["runs"]), *(c.cell(s) for c in table)] for name, s in blocks]
    out = [
        "## Ergonomics",
        "",
        *exposure_markdown(e.get("exposure")),
        "Each cycle's peak score over its timeline: RULA (McAtamney & Corlett 1993), REBA "
        "(Hignett & McAtamney 2000), the revised NIOSH lifting index per lift of a part with a "
        "mass (Waters et al. 1993), ISO 11226 static postures. Shares are of cycles reaching "
        "the level, with their 95 % Wilson score interval.",
        "",
        *_table(head, rows),
        "",
        *(line for sc in SCORES.values() for line in sc.notes(e["overall"])),
        "Per task (P50 / P95 of the task's peak over runs) and the body part that most often "
        "drives its RULA peak:",
        "",
        *_table(
            ["task", "kind", "site", "RULA P50", "RULA P95", "REBA P50", "REBA P95", "driver"],
            [
                [
                    str(t["task"]),
                    t["kind"],
                    t["site"] or "",
                    fmt(t["rula"]["p50"]),
                    fmt(t["rula"]["p95"]),
                    fmt(t["reba"]["p50"]),
                    fmt(t["reba"]["p95"]),
                    t["rula_driver"],
                ]
                for t in e["tasks"]
            ],
        ),
        "",
        "Where the cycles reach their RULA peak (task: body part, cycles; the most frequent): "
        + "; ".join(f"{k} ({v})" for k, v in list(e["drivers"]["rula"].items())[:5])
        + ".",
    ]
    st = e.get("stature")
    if st:
        out += [
            "",
            "Stature: Spearman's rho of stature and peak RULA "
            f"{fmt(st['spearman_rho_stature_rula_peak'], 2)}; "
            f"per reach, the median RULA (upper-arm score) of operators up to "
            f"{st['short_below_m']:.2f} m and from {st['tall_above_m']:.2f} m:",
            "",
            *_table(
                [
                    "task",
                    "kind",
                    "site",
                    "RULA short",
                    "RULA tall",
                    "upper arm short",
                    "upper arm tall",
                ],
                [
                    [
                        str(t["task"]),
                        t["kind"],
                        t["site"] or "",
                        fmt(t["rula_short"]),
                        fmt(t["rula_tall"]),
                        fmt(t["upper_arm_short"]),
                        fmt(t["upper_arm_tall"]),
                    ]
                    for t in st["tasks"]
                ],
            ),
        ]
    return [*out, ""]


__all__ = [
    "CONFIDENCE",
    "CSV_COLUMNS",
    "RunRecord",
    "csv_header",
    "ergonomics_markdown",
    "ergonomics_rows",
    "ergonomics_summary",
    "share",
]
