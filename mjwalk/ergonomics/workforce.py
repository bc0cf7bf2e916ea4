"""The workforce's continuous exposure (:mod:`mjwalk.ergonomics.exposure`): per operator group and
along stature, over a cycle and over a shift, and the tasks and body parts that drive it.

:func:`exposure_summary` reads one record per run (``run``, ``group``, ``stature`` in metres or
None, ``ergo`` a :class:`~mjwalk.ergonomics.results.RunErgonomics` scored with the exposure
method) and gives:

- per group and overall: the share of operators (runs) in each worst verdict with its 95 %
  Wilson score interval, and P5/P50/P95 of the seconds per cycle above 60 deg of arm elevation
  and above 20 deg of trunk flexion, and of those seconds over a shift;
- along stature: the stature range the runs cover, the binned median of the arm's seconds above
  60 deg (equal-count bins, :data:`STATURE_BINS`), the shortest and the tallest third's medians
  and the least-squares slope (s per 10 cm) with a seeded bootstrap 95 % interval
  (:data:`BOOTSTRAP`, :data:`BOOTSTRAP_SEED`);
- drivers: per task the median seconds above 60 deg of arm elevation and above 20 deg of trunk
  flexion, and per body part and standard how many cycles it makes not acceptable.

A shift is :data:`SHIFT_S` of work; its cycles are the shift over the takt (cycles start at the
takt), else over the runs' median cycle time (cycles back to back).
"""

from __future__ import annotations

import copy
import threading
from collections.abc import Sequence
from concurrent.futures import ThreadPoolExecutor
from typing import Any

import numpy as np

from mjwalk.ergonomics.en1005 import HIGH_FREQ_PER_MIN, VERDICTS
from mjwalk.ergonomics.exposure import PARTS, spread
from mjwalk.ergonomics.score import fmt, fmt_share, share

#: Working time of a shift, s: 8 h less 30 min of breaks (the German Working Hours Act,
#: ArbZG section 4: at least 30 min of breaks for 6 to 9 h of work) = 7.5 h.
SHIFT_S = 7.5 * 3600.0
#: Equal-count stature bins of the binned median trend (fewer when there are fewer than
#: 3 runs a bin).
STATURE_BINS = 5
#: Bootstrap resamples and seed of the stature slope's interval.
BOOTSTRAP = 2000
BOOTSTRAP_SEED = 0
#: The smooth trend's span: the share of the runs nearest each stature that its local line
#: weighs (LOWESS, Cleveland 1979, J. Am. Stat. Assoc. 74:829-836: f = 2/3 is his default).
LOWESS_SPAN = 2.0 / 3.0
#: Statures the smooth trend is given at (evenly spaced over the runs' range).
LOWESS_POINTS = 9


def lowess(x: np.ndarray, y: np.ndarray, at: np.ndarray, span: float = LOWESS_SPAN) -> np.ndarray:
    """A smooth trend of ``y`` along ``x``: at each point of ``at`` the weighted least-squares
    line through the ``span`` share of the runs nearest it, tricube weights on the distance
    over the farthest of them's (Cleveland 1979, one pass, no robustness iterations).

    Args:
        x: (N,) e.g. statures, metres.
        y: (N,) the figure per run.
        at: (M,) where to give the trend.
        span: the share of the N runs each local line weighs (0-1].

    Returns:
        (M,) the trend's values.
    """
    x, y = np.asarray(x, dtype=float), np.asarray(y, dtype=float)
    k = min(len(x), max(3, int(np.ceil(span * len(x)))))
    out = np.empty(len(at))
    for i, a in enumerate(np.asarray(at, dtype=float)):
        d = np.abs(x - a)
        h = max(float(np.sort(d)[k - 1]), 1e-12)
        w = np.clip(1.0 - (d / h) ** 3, 0.0, None) ** 3
        sw = w.sum()
        xm, ym = (w * x).sum() / sw, (w * y).sum() / sw
        den = (w * (x - xm) ** 2).sum()
        b = (w * (x - xm) * (y - ym)).sum() / den if den > 1e-15 else 0.0
        out[i] = ym + b * (a - xm)
    return out


def lowess_band(
    x: np.ndarray, y: np.ndarray, at: np.ndarray, seed: int = BOOTSTRAP_SEED
) -> tuple[np.ndarray, np.ndarray]:
    """The smooth trend's 95 % band: :func:`lowess` over :data:`BOOTSTRAP` resamples of the
    runs (drawn with replacement, seeded), the 2.5th and 97.5th percentiles at each point.

    Args:
        x: (N,) e.g. statures, metres.
        y: (N,) the figure per run.
        at: (M,) where to give the band.
        seed: the resamples' seed.

    Returns:
        ``(low, high)``, each (M,).
    """
    x, y = np.asarray(x, dtype=float), np.asarray(y, dtype=float)
    at = np.asarray(at, dtype=float)
    idx = np.random.default_rng(seed).integers(0, len(x), size=(BOOTSTRAP, len(x)))
    k = min(len(x), max(3, int(np.ceil(LOWESS_SPAN * len(x)))))
    fits = np.empty((BOOTSTRAP, len(at)))
    # each point's distances to the runs, in increasing order: a resample's k-th nearest is
    # found by counting its draws along this order (:func:`_kth_nearest`)
    dist = [np.abs(x - a) for a in at]
    order = [np.argsort(d, kind="stable") for d in dist]
    # resamples in blocks that stay in the cache (about 1 MB a block); each resample's figures
    # are row reductions of its own row, so they are the same bit for bit in any block size
    block = _block_size(len(x))
    for s in range(0, BOOTSTRAP, block):
        rows = idx[s : s + block]
        # how often each resample drew each run: (N, B) counts, a resample a column
        b = len(rows)
        counts = np.bincount((rows * b + np.arange(b)[:, None]).ravel(), minlength=b * len(x))
        counts = counts.reshape(len(x), b).astype(np.int32)
        h = np.stack([_kth_nearest(counts, d, o, k) for d, o in zip(dist, order, strict=True)])
        fits[s : s + block] = _lowess_rows(x[rows], y[rows], at, h)
    return np.percentile(fits, 2.5, axis=0), np.percentile(fits, 97.5, axis=0)


def _kth_nearest(counts: np.ndarray, dist: np.ndarray, order: np.ndarray, k: int) -> np.ndarray:
    """Each resample's ``k``-th smallest distance ((B,)): ``counts`` (N, B) is how often each
    resample drew each run, ``dist`` (N,) the runs' distances and ``order`` them ascending;
    the distance at the first place along ``order`` where a resample's draws reach ``k``.
    The same value as ``np.partition(dist[rows], k - 1, axis=1)[:, k - 1]`` of the resamples'
    draws ``rows``, without partitioning every resample at every point (issue 50: most of a
    third of the band's time over 10 000 runs)."""
    reached = np.cumsum(counts[order], axis=0, dtype=np.int32)
    return dist[order[(reached < k).sum(axis=0)]]


#: Elements of a block of resamples in :func:`lowess_band` (128 k doubles, 1 MB an array).
_BAND_BLOCK = 1 << 17


def _lowess_rows(xs: np.ndarray, ys: np.ndarray, at: np.ndarray, kth: np.ndarray) -> np.ndarray:
    """:func:`lowess` of each row of ``xs``, ``ys`` (resamples, (B, N)) at ``at`` (M,), each
    row's span at point ``i`` reaching its ``k`` nearest runs, at distance ``kth[i]`` ((M, B),
    :func:`_kth_nearest`): (B, M)."""
    fits = np.empty((len(xs), len(at)))
    for i, a in enumerate(at):  # :func:`lowess`, all resamples at once
        d = np.abs(xs - a)
        h = np.maximum(kth[i][:, None], 1e-12)
        w = np.clip(1.0 - (d / h) ** 3, 0.0, None)
        # the cube of the weights inside the span only: numpy's power takes several times as
        # long over zeros (a third of them); each element's cube is the same bit for bit
        w = np.where(w > 0, np.where(w > 0, w, 1.0) ** 3, 0.0)
        # a resample whose nearest runs all lie at the span's edge (one run drawn k times)
        # weighs them alike instead of not at all
        w = np.where(w.sum(axis=1, keepdims=True) > 0, w, (d <= h).astype(float))
        sw = w.sum(axis=1, keepdims=True)
        xm, ym = (w * xs).sum(axis=1, keepdims=True) / sw, (w * ys).sum(axis=1, keepdims=True) / sw
        den = (w * (xs - xm) ** 2).sum(axis=1)
        num = (w * (xs - xm) * (ys - ym)).sum(axis=1)
        b = np.where(den > 1e-15, num / np.where(den > 1e-15, den, 1.0), 0.0)
        fits[:, i] = ym[:, 0] + b * (a - xm[:, 0])
    return fits


def _scored(records: Sequence) -> list:
    """The records whose runs the exposure method scored."""
    return [r for r in records if "exposure_verdict" in r.ergo.extra]


def _group(records: Sequence, per_shift: float) -> dict[str, Any]:
    """A group's verdict shares and exposure over a cycle and over a shift."""
    n = len(records)
    verdicts = [r.ergo.extra["exposure_verdict"] for r in records]
    arm = np.array([r.ergo.extra["arm_over60_s"] for r in records])
    trunk = np.array([r.ergo.extra["trunk_over20_s"] for r in records])
    st = [r.stature for r in records if r.stature is not None]
    return {
        "runs": n,
        "verdicts": {v: share(verdicts.count(v), n) for v in VERDICTS},
        "arm_over60_s": spread(arm),
        "arm_over60_per_min": spread(
            [r.ergo.extra.get("arm_over60_per_min", 0.0) for r in records]
        ),
        "trunk_over20_s": spread(trunk),
        "arm_over60_shift_min": spread(arm * per_shift / 60.0),
        "trunk_over20_shift_min": spread(trunk * per_shift / 60.0),
        "stature_m": spread(st),
    }


def stature_trend(stature: np.ndarray, y: np.ndarray) -> dict[str, Any] | None:
    """How an exposure figure follows stature (module docstring).

    Args:
        stature: (N,) metres.
        y: (N,) the figure per run.

    Returns:
        ``range_m``, ``bins`` (each ``from_m``, ``to_m``, ``median``, ``n``), ``short_third``
        and ``tall_third`` (``up_to_m``/``from_m``, ``median``), ``slope_per_10cm`` with
        ``low``/``high`` (bootstrap 95 %), ``smooth`` (:func:`lowess` at
        :data:`LOWESS_POINTS` statures: ``stature_m``, ``value`` and its 95 % band ``low``,
        ``high``, :func:`lowess_band`); None with fewer than 6 runs or one stature.
    """
    x, y = np.asarray(stature, dtype=float), np.asarray(y, dtype=float)
    if len(x) < 6 or np.ptp(x) == 0 or not np.isfinite(y).all():
        return None
    # the report asks for the same trends more than once (report.json, report.md, the plot):
    # over thousands of runs each costs seconds (the bootstrap bands); same figures, same trend
    key = (x.tobytes(), y.tobytes())
    with _TRENDS_LOCK:
        kept = _TRENDS.get(key)
    if kept is None:
        kept = _trend(x, y)
        with _TRENDS_LOCK:  # :func:`exposure_summary` asks for two trends at once
            if len(_TRENDS) >= _TRENDS_KEPT:
                _TRENDS.pop(next(iter(_TRENDS)))
            _TRENDS[key] = kept
    return copy.deepcopy(kept)


#: The last trends :func:`stature_trend` gave, by their figures (a report's few).
_TRENDS: dict[tuple[bytes, bytes], dict[str, Any]] = {}
_TRENDS_KEPT = 8
_TRENDS_LOCK = threading.Lock()


def _trend(x: np.ndarray, y: np.ndarray) -> dict[str, Any]:
    """:func:`stature_trend` of checked figures."""
    order = np.argsort(x, kind="stable")
    k = max(1, min(STATURE_BINS, len(x) // 3))
    bins = [
        {
            "from_m": float(x[i].min()),
            "to_m": float(x[i].max()),
            "median": float(np.median(y[i])),
            "n": len(i),
        }
        for i in np.array_split(order, k)
    ]
    lo, hi = np.percentile(x, [100 / 3, 200 / 3])
    rng = np.random.default_rng(BOOTSTRAP_SEED)
    idx = rng.integers(0, len(x), size=(BOOTSTRAP, len(x)))
    slopes = np.concatenate(
        [_slopes(x[rows], y[rows]) for rows in np.array_split(idx, _blocks(len(x)))]
    )
    slope = float(np.polyfit(x, y, 1)[0])
    at = np.linspace(x.min(), x.max(), LOWESS_POINTS)
    fit = lowess(x, y, at)
    band = lowess_band(x, y, at)
    smooth = [
        {"stature_m": float(a), "value": float(v), "low": float(lo_), "high": float(hi_)}
        for a, v, lo_, hi_ in zip(at, fit, *band, strict=True)
    ]
    return {
        "range_m": [float(x.min()), float(x.max())],
        "bins": bins,
        "short_third": {"up_to_m": float(lo), "median": float(np.median(y[x <= lo]))},
        "tall_third": {"from_m": float(hi), "median": float(np.median(y[x >= hi]))},
        "slope_per_10cm": 0.1 * slope,
        "low": 0.1 * float(np.percentile(slopes, 2.5)),
        "high": 0.1 * float(np.percentile(slopes, 97.5)),
        "confidence": 0.95,
        "smooth": smooth,
    }


def _block_size(n: int) -> int:
    """How many of the :data:`BOOTSTRAP` resamples of ``n`` runs make one block in the cache
    (:data:`_BAND_BLOCK` elements a block)."""
    return max(1, min(BOOTSTRAP, _BAND_BLOCK // max(1, n)))


def _blocks(n: int) -> int:
    """How many blocks of :func:`_block_size` the :data:`BOOTSTRAP` resamples of ``n`` runs
    make."""
    return -(-BOOTSTRAP // _block_size(n))


def _slopes(xs: np.ndarray, ys: np.ndarray) -> np.ndarray:
    """The least-squares slope of each resample (row) of ``xs``, ``ys`` ((B, N)) whose
    statures are not all one; row reductions, so the same bit for bit in any block."""
    xc = xs - xs.mean(axis=1, keepdims=True)
    den = (xc**2).sum(axis=1)
    ok = den > 0
    return (xc * (ys - ys.mean(axis=1, keepdims=True))).sum(axis=1)[ok] / den[ok]


def _drivers(records: Sequence) -> dict[str, Any]:
    """Per task the median seconds beyond the limits; per part and standard the cycles it makes
    not acceptable."""
    by: dict[int, list] = {}
    for r in records:
        for t in r.ergo.tasks:
            by.setdefault(t.index, []).append(t)
    tasks = [
        {
            "task": i,
            "kind": ts[0].kind,
            "site": ts[0].site,
            "arm_over60_s": float(np.median([t.extra["arm_over60_s"] for t in ts])),
            "trunk_over20_s": float(np.median([t.extra["trunk_over20_s"] for t in ts])),
            "arm_peak_deg": float(np.median([t.extra["arm_peak_deg"] for t in ts])),
        }
        for i, ts in sorted(by.items())
    ]
    tasks.sort(key=lambda t: (-t["arm_over60_s"], -t["trunk_over20_s"]))
    parts = {
        f"{p} {std}": sum(r.ergo.extra["exposure"][p][std] == VERDICTS[2] for r in records)
        for p in PARTS
        for std in ("en1005", "iso11226")
    }
    return {"tasks": tasks, "not_acceptable_cycles": parts}


def exposure_summary(records: Sequence, takt: float | None = None) -> dict[str, Any] | None:
    """The workforce's exposure figures (module docstring).

    Args:
        records: the scored runs (``run``, ``group``, ``stature``, ``ergo``).
        takt: the takt, s (None: cycles back to back).

    Returns:
        Plain data: ``shift`` (``working_s``, ``cycles``, ``basis``), ``overall``, ``groups``,
        ``stature`` (of the arm's seconds above 60 deg; None without enough statures),
        ``stature_arm_top`` (of the arm's elevation at the highest grasp,
        :func:`mjwalk.ergonomics.exposure.arm_at_top`) and ``drivers``; None when no run was
        scored for exposure.
    """
    rec = _scored(records)
    if not rec:
        return None
    cycle = float(np.median([r.ergo.extra["cycle_time_s"] for r in rec]))
    basis = "takt" if takt else "median cycle time"
    per_shift = SHIFT_S / (takt or max(cycle, 1e-9))
    groups: dict[str, list] = {}
    for r in rec:
        groups.setdefault(r.group, []).append(r)
    st = [r for r in rec if r.stature is not None]
    x = np.array([r.stature for r in st])
    arm = np.array([r.ergo.extra["arm_over60_s"] for r in st])
    arm_top = np.array([r.ergo.extra.get("arm_top_deg", np.nan) for r in st])
    # both trends at once: their bootstrap bands, most of the report's time over thousands of
    # runs, are numpy's work on large arrays, which lets a second thread run (issue 50: the
    # report follows the batch, when both cores are free); the same figures as one by one
    with ThreadPoolExecutor(max_workers=2) as pool:
        trend, top = pool.map(stature_trend, (x, x), (arm, arm_top))
    return {
        "shift": {
            "working_s": SHIFT_S,
            "cycles": per_shift,
            "basis": basis,
            "source": "8 h less 30 min breaks (ArbZG section 4)",
        },
        "overall": _group(rec, per_shift),
        "groups": {g: _group(rs, per_shift) for g, rs in groups.items() if g},
        "stature": trend,
        "stature_arm_top": top,
        "drivers": _drivers(rec),
    }


def _row(name: str, g: dict) -> str:
    """A markdown row of a group's verdict shares and exposure."""
    v, a, s = g["verdicts"], g["arm_over60_s"], g["stature_m"]
    cells = [
        name, str(g["runs"]),
        "-" if s["min"] is None else f"{s['min']:.2f}-{s['max']:.2f}",
        *(fmt_share(v[k]) for k in VERDICTS),
        f"{fmt(a['p50'])} ({fmt(a['p5'])}-{fmt(a['p95'])})",
        fmt(g["arm_over60_per_min"]["p50"]),
        fmt(g["trunk_over20_s"]["p50"]),
        fmt(g["arm_over60_shift_min"]["p50"]),
    ]  # fmt: skip
    return "| " + " | ".join(cells) + " |"


def exposure_markdown(e: dict[str, Any] | None) -> list[str]:
    """report.md's opening of the ergonomics section: verdict shares per group, the stature
    trend and the drivers.

    Args:
        e: :func:`exposure_summary`'s figures (None: no lines).

    Returns:
        Markdown lines.
    """
    if not e:
        return []
    sh = e["shift"]
    out = [
        "Continuous exposure of the upper arms and the trunk (EN 1005-4 zones and frequencies, "
        "ISO 11226 holding times; each cycle's worst verdict over both standards and body "
        "parts). Shares of operators (runs) with their 95 % Wilson interval; seconds per cycle "
        f"(P50, P5-P95); a shift is {sh['working_s'] / 3600:.1f} h of work, "
        f"{sh['cycles']:.0f} cycles at the {sh['basis']}.",
        "",
        "| operators | runs | stature m | acceptable | conditionally acc. | not acceptable "
        "| arm >60 deg s | arm >60 deg entries/min | trunk >20 deg s | arm >60 deg min/shift |",
        "|---|---|---|---|---|---|---|---|---|---|",
        _row("all operators", e["overall"]),
        *(_row(g, v) for g, v in e["groups"].items()),
        "",
        *_same_verdict_lines(e),
    ]
    t = e["stature"]
    if t:
        bins = "; ".join(
            f"{b['from_m']:.2f}-{b['to_m']:.2f} m: {b['median']:.1f} s" for b in t["bins"]
        )
        out += [
            f"Along stature ({t['range_m'][0]:.2f}-{t['range_m'][1]:.2f} m), the arm's seconds "
            f"above 60 deg per cycle: binned median {bins}; shortest third (to "
            f"{t['short_third']['up_to_m']:.2f} m) {t['short_third']['median']:.1f} s, tallest "
            f"third (from {t['tall_third']['from_m']:.2f} m) {t['tall_third']['median']:.1f} s; "
            f"slope {t['slope_per_10cm']:+.2f} s per 10 cm (95 % {t['low']:+.2f} to "
            f"{t['high']:+.2f}).",
            "",
            *_trend_table(t, e.get("stature_arm_top")),
        ]
    return out + _drivers_lines(e["drivers"])


def _same_verdict_lines(e: dict[str, Any]) -> list[str]:
    """A sentence when every run has the same verdict: the stature effect is then in the
    continuous figures (none otherwise)."""
    v = e["overall"]["verdicts"]
    same = [k for k in VERDICTS if v[k]["share"] == 1.0]
    if not same or e["overall"]["runs"] < 2:
        return []
    f = e["overall"]["arm_over60_per_min"]
    return [
        f"Every run is {same[0]}: the verdicts do not tell operators apart here (the arm goes "
        f"above 60 deg {fmt(f['p5'])}-{fmt(f['p95'])} times a minute, P5-P95, against EN "
        f"1005-4's high frequency from {HIGH_FREQ_PER_MIN:g}/min); how far and how long the arm "
        "is raised, below, follow stature.",
        "",
    ]


def _trend_table(t: dict[str, Any], top: dict[str, Any] | None) -> list[str]:
    """The smooth trends along stature (LOWESS with its bootstrap 95 % band) at every other
    stature of :data:`LOWESS_POINTS`: the arm's seconds above 60 deg and, where known, its
    elevation at the highest grasp; the latter's slope."""
    rows = [
        "| stature m | arm >60 deg s per cycle (95 %) | arm at the highest grasp deg (95 %) |",
        "|---|---|---|",
    ]
    for i in range(0, len(t["smooth"]), 2):
        a = t["smooth"][i]
        b = top["smooth"][i] if top else None
        cell = f"{b['value']:.0f} ({b['low']:.0f}-{b['high']:.0f})" if b else "-"
        rows.append(
            f"| {a['stature_m']:.2f} | {a['value']:.1f} ({a['low']:.1f}-{a['high']:.1f}) | {cell} |"
        )
    if top:
        rows += [
            "",
            f"Smooth trends (LOWESS, span {LOWESS_SPAN:.2f}; bootstrap 95 % band). The arm's "
            f"elevation at the highest grasp changes by {top['slope_per_10cm']:+.1f} deg per "
            f"10 cm of stature (95 % {top['low']:+.1f} to {top['high']:+.1f}); shortest third "
            f"{top['short_third']['median']:.0f} deg, tallest third "
            f"{top['tall_third']['median']:.0f} deg.",
        ]
    return [*rows, ""]


def _drivers_lines(d: dict[str, Any]) -> list[str]:
    """The drivers' sentence: the three tasks longest beyond the limits and the body parts that
    make cycles not acceptable ("none" when no cycle is)."""
    top = [x for x in d["tasks"] if x["arm_over60_s"] > 0 or x["trunk_over20_s"] > 0][:3]
    if not top:
        return []
    parts = ", ".join(f"{k} {v}" for k, v in d["not_acceptable_cycles"].items() if v)
    return [
        "Tasks that drive it (median s above 60 deg arm / 20 deg trunk): "
        + "; ".join(
            f"task {x['task']} {x['kind']} {x['site'] or ''}: {x['arm_over60_s']:.1f} / "
            f"{x['trunk_over20_s']:.1f}"
            for x in top
        )
        + ". Cycles not acceptable by body part and standard: "
        + (parts or "none")
        + ".",
        "",
    ]


__all__ = [
    "BOOTSTRAP",
    "BOOTSTRAP_SEED",
    "LOWESS_POINTS",
    "LOWESS_SPAN",
    "SHIFT_S",
    "STATURE_BINS",
    "exposure_markdown",
    "exposure_summary",
    "lowess",
    "lowess_band",
    "stature_trend",
]
