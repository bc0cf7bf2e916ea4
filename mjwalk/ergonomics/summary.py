"""The workforce's ergonomics: distributions of many runs' scores, overall and per operator group.

:func:`ergonomics_summary` takes one :class:`RunRecord` per simulated cycle (its operator's group
and stature, and its :class:`~mjwalk.ergonomics.assess.RunErgonomics`) and gives, overall and per
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
"""

from __future__ import annotations

from collections import Counter
from dataclasses import dataclass

import numpy as np

from mjwalk.ergonomics import reba, rula
from mjwalk.ergonomics.assess import RunErgonomics

#: Confidence level of the shares.
CONFIDENCE = 0.95
#: Columns of ergonomics.csv.
CSV_COLUMNS = (
    "run", "seed", "group", "stature_m", "task", "kind", "site", "rula_peak", "rula_action_level",
    "reba_peak", "reba_risk_level", "owas_peak", "rula_time_s", "rula_driver", "reba_driver",
    "arm", "upper_arm_score", "lifting_index", "rwl_kg", "mass_kg", "lifts_per_min",
    "lifting_index_note",
)  # fmt: skip


@dataclass
class RunRecord:
    """One run's operator and scores (``group`` "" and ``stature`` None without a population)."""

    run: int
    seed: int | None
    group: str
    stature: float | None
    ergo: RunErgonomics


def _pct(x) -> dict:
    x = np.asarray(x, dtype=float)
    if not len(x):
        return {"p50": None, "p95": None, "n": 0}
    return {"p50": float(np.percentile(x, 50)), "p95": float(np.percentile(x, 95)), "n": len(x)}


def share(k: int, n: int, confidence: float = CONFIDENCE) -> dict:
    """``k`` of ``n`` as a share with its Wilson score interval."""
    from scipy.stats import binomtest

    if n == 0:
        return {"share": None, "low": None, "high": None, "k": 0, "n": 0}
    ci = binomtest(k, n).proportion_ci(confidence_level=confidence, method="wilson")
    return {"share": k / n, "low": float(ci.low), "high": float(ci.high), "k": k, "n": n}


def _stats(records: list[RunRecord]) -> dict:
    n = len(records)
    rp = [r.ergo.rula_peak for r in records]
    bp = [r.ergo.reba_peak for r in records]
    ral = [int(rula.action_level(x)) for x in rp]
    brl = [int(reba.risk_level(x)) for x in bp]
    lis = [lf.li for r in records for lf in r.ergo.lifts if lf.li is not None]
    with_lifts = [r for r in records if r.ergo.lifts]
    return {
        "runs": n,
        "rula_peak": _pct(rp),
        "reba_peak": _pct(bp),
        "rula_action_level": {str(lv): share(sum(a >= lv for a in ral), n) for lv in (1, 2, 3, 4)},
        "reba_risk_level": {str(lv): share(sum(a >= lv for a in brl), n) for lv in (1, 2, 3, 4)},
        "owas_peak": _pct([r.ergo.owas_peak for r in records]),
        "lifting_index": _pct(lis),
        "lifts_per_cycle": len(lis) / n if n else 0.0,
        "cycles_li_over_1": _li_over_1(with_lifts),
        "lifting_index_not_computed": _without_li(with_lifts),
        "iso11226_not_acceptable": share(
            sum(not all(h.acceptable for h in r.ergo.holdings) for r in records), n
        ),
    }


def _li_over_1(with_lifts: list[RunRecord]) -> dict:
    """The share of cycles with a lift index above 1, of the cycles where that is known: a lift
    with an index above 1, or every lift with an index (a cycle whose other lifts have none is
    left out, and counted by :func:`_without_li`)."""
    over = [any(lf.li is not None and lf.li > 1.0 for lf in r.ergo.lifts) for r in with_lifts]
    known = [o or not r.ergo.lifts_without_li for o, r in zip(over, with_lifts, strict=True)]
    return share(sum(over), sum(known))


def _without_li(with_lifts: list[RunRecord]) -> dict:
    """The lifts the NIOSH equation gives no index: how many of all, the share of cycles with
    one, their lifting frequencies (lifts/min) and the limits they crossed (limit: lifts)."""
    lifts = [lf for r in with_lifts for lf in r.ergo.lifts]
    none = [lf for lf in lifts if lf.li is None]
    f = [lf.f for lf in none]
    return {
        "lifts": len(none),
        "of_lifts": len(lifts),
        "cycles": share(sum(bool(r.ergo.lifts_without_li) for r in with_lifts), len(with_lifts)),
        "lifts_per_min": [float(min(f)), float(max(f))] if f else None,
        "limits": dict(Counter(lf.limit for lf in none).most_common()),
    }


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
                "rula": _pct([t.rula for _, t in rows]),
                "reba": _pct([t.reba for _, t in rows]),
                "rula_driver": Counter(t.rula_driver for _, t in rows).most_common(1)[0][0],
            }
        )
    return out


def _stature(records: list[RunRecord]) -> dict | None:
    """Stature dependence: Spearman's rho of stature and peak RULA; per reach task the median
    RULA and upper-arm score of the shortest and tallest thirds."""
    from scipy.stats import spearmanr

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


def ergonomics_summary(records: list[RunRecord]) -> dict:
    """The report's ergonomics figures (plain, JSON-ready data); see the module docstring."""
    groups: dict[str, list[RunRecord]] = {}
    for r in records:
        groups.setdefault(r.group, []).append(r)
    return {
        "methods": {
            "rula": "McAtamney & Corlett 1993; action levels 1 (1-2) 2 (3-4) 3 (5-6) 4 (7)",
            "reba": "Hignett & McAtamney 2000; risk levels 0 (1) 1 (2-3) 2 (4-7) 3 (8-10) 4 (11+)",
            "owas": "Karhu et al. 1977; action categories 1-4",
            "niosh": "revised NIOSH lifting equation, Waters et al. 1993 / 1994",
            "iso11226": "ISO 11226:2000 static trunk and upper-arm postures",
            "shares": "cycles reaching at least the level, with 95 % Wilson score interval",
        },
        "overall": _stats(records),
        "groups": {g: _stats(rs) for g, rs in groups.items() if g},
        "drivers": _drivers(records),
        "tasks": _tasks(records),
        "stature": _stature(records),
    }


def ergonomics_rows(records: list[RunRecord]) -> list[list]:
    """Rows of ergonomics.csv (:data:`CSV_COLUMNS`): one per run and task."""
    rows = []
    for r in records:
        lifts = {lf.task: lf for lf in r.ergo.lifts}
        for t in r.ergo.tasks:
            lf = lifts.get(t.index)
            rows.append(
                [
                    r.run, r.seed, r.group, "" if r.stature is None else f"{r.stature:.3f}",
                    t.index, t.kind, t.site or "", t.rula, int(rula.action_level(t.rula)),
                    t.reba, int(reba.risk_level(t.reba)), t.owas, f"{t.rula_time:.3f}",
                    t.rula_driver, t.reba_driver, t.side, t.upper_arm,
                    "" if lf is None or lf.li is None else f"{lf.li:.3f}",
                    "" if lf is None else f"{lf.rwl:.3f}", "" if lf is None else f"{lf.mass:.3f}",
                    "" if lf is None else f"{lf.f:.2f}",
                    "" if lf is None or lf.li is not None else f"no lifting index: {lf.reason}",
                ]
            )  # fmt: skip
    return rows


def _f(x, d: int = 1) -> str:
    return "-" if x is None else f"{x:.{d}f}"


def _share(e: dict) -> str:
    if e["share"] is None:
        return "-"
    return f"{100 * e['share']:.0f} % ({100 * e['low']:.0f}-{100 * e['high']:.0f})"


def _table(head: list[str], rows: list[list[str]]) -> list[str]:
    return [
        "| " + " | ".join(head) + " |",
        "|" + "|".join("---" for _ in head) + "|",
        *["| " + " | ".join(r) + " |" for r in rows],
    ]


def _without_li_markdown(w: dict) -> list[str]:
    """The paragraph on the lifts without a lifting index (none when every lift has one)."""
    if not w["lifts"]:
        return []
    lo, hi = w["lifts_per_min"]
    freq = f"{lo:.1f}" if round(lo, 1) == round(hi, 1) else f"{lo:.1f}-{hi:.1f}"
    limits = "; ".join(f"{k} ({v} lifts)" for k, v in w["limits"].items())
    return [
        f"No NIOSH lifting index for {w['lifts']} of {w['of_lifts']} lifts "
        f"({w['cycles']['k']} of {w['cycles']['n']} cycles with lifts; left out of LI P50, "
        f"LI P95 and cycles LI>1): their recommended weight limit is 0 at {freq} lifts/min (a "
        f"cycle's lifts over its cycle time, cycles back to back). Limits crossed: {limits}. "
        "ergonomics.csv gives the reason per lift.",
        "",
    ]


def ergonomics_markdown(e: dict) -> list[str]:
    """The report.md section of :func:`ergonomics_summary`'s figures."""
    blocks = [("all operators", e["overall"])] + list(e["groups"].items())
    head = ["operators", "runs", "RULA P50", "RULA P95", "RULA AL>=3", "RULA AL 4",
            "REBA P50", "REBA P95", "REBA >=3 (high)", "LI P50", "LI P95", "cycles LI>1",
            "cycles without LI", "ISO 11226 not acc."]  # fmt: skip
    rows = [
        [
            name, str(s["runs"]), _f(s["rula_peak"]["p50"]), _f(s["rula_peak"]["p95"]),
            _share(s["rula_action_level"]["3"]), _share(s["rula_action_level"]["4"]),
            _f(s["reba_peak"]["p50"]), _f(s["reba_peak"]["p95"]), _share(s["reba_risk_level"]["3"]),
            _f(s["lifting_index"]["p50"], 2), _f(s["lifting_index"]["p95"], 2),
            _share(s["cycles_li_over_1"]), _share(s["lifting_index_not_computed"]["cycles"]),
            _share(s["iso11226_not_acceptable"]),
        ]
        for name, s in blocks
    ]  # fmt: skip
    out = [
        "## Ergonomics",
        "",
        "Each cycle's peak score over its timeline: RULA (McAtamney & Corlett 1993), REBA "
        "(Hignett & McAtamney 2000), the revised NIOSH lifting index per lift of a part with a "
        "mass (Waters et al. 1993), ISO 11226 static postures. Shares are of cycles reaching "
        "the level, with their 95 % Wilson score interval.",
        "",
        *_table(head, rows),
        "",
        *_without_li_markdown(e["overall"]["lifting_index_not_computed"]),
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
                    _f(t["rula"]["p50"]),
                    _f(t["rula"]["p95"]),
                    _f(t["reba"]["p50"]),
                    _f(t["reba"]["p95"]),
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
            f"{_f(st['spearman_rho_stature_rula_peak'], 2)}; "
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
                        _f(t["rula_short"]),
                        _f(t["rula_tall"]),
                        _f(t["upper_arm_short"]),
                        _f(t["upper_arm_tall"]),
                    ]
                    for t in st["tasks"]
                ],
            ),
        ]
    return [*out, ""]
