"""Top-view plots of a workplace (floor plan, obstacles, clearance shading, walk paths) and the
report's charts (walks by route over the floor plan, cycle-time and walk-length histograms)."""

from __future__ import annotations

import itertools
import math
from collections.abc import Sequence
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np
from matplotlib import lines as mlines
from matplotlib.collections import LineCollection
from matplotlib.patches import Circle, Polygon, Rectangle

from mjwalk._io import atomic_path
from mjwalk.cycle.types import CycleResult
from mjwalk.ergonomics.workforce import stature_trend
from mjwalk.plan.walkpath import WalkPath
from mjwalk.world.workplace import Workplace


def draw_floor(ax, workplace: Workplace, *, shade: bool = True, sites: bool = True) -> None:
    """Draw the floor outline, clearance shading, obstacle footprints and stand sites on ``ax``.

    Args:
        ax: the matplotlib axes (x and y in metres, world frame).
        workplace: the scene.
        shade: shade the clearance field (0-1.5 m) with its colour bar.
        sites: mark and name the sites below 0.05 m (stand positions).
    """
    xmin, ymin, xmax, ymax = workplace.floor_bounds
    if shade:
        f = workplace.clearance
        ex = f.extent
        img = ax.imshow(
            np.clip(f.values, 0.0, 1.5),
            origin="lower",
            extent=(ex[0], ex[2], ex[1], ex[3]),
            cmap="Greens",
            alpha=0.55,
            vmin=0.0,
            vmax=1.5,
        )
        plt.colorbar(img, ax=ax, shrink=0.7, label="clearance to obstacles [m]")
    ax.add_patch(Rectangle((xmin, ymin), xmax - xmin, ymax - ymin, fill=False, lw=1.5, ec="k"))
    for fp in workplace.obstacles:
        if fp.is_polygon:
            ax.add_patch(Polygon(fp.vertices, closed=True, fc="0.45", ec="0.2", lw=0.5))
        elif np.allclose(fp.vertices[0], fp.vertices[-1]):
            ax.add_patch(Circle(fp.vertices[0], fp.radius, fc="0.45", ec="0.2", lw=0.5))
        else:  # a stadium: the segment drawn with round caps at its true width
            (x0, y0), (x1, y1) = fp.vertices[0], fp.vertices[-1]
            ax.plot([x0, x1], [y0, y1], color="0.45", lw=1, solid_capstyle="round")
            for c in (fp.vertices[0], fp.vertices[-1]):
                ax.add_patch(Circle(c, fp.radius, fc="0.45", ec="none"))
            d = np.array([y1 - y0, x0 - x1]) / np.hypot(x1 - x0, y1 - y0) * fp.radius
            quad = np.array(
                [fp.vertices[0] + d, fp.vertices[-1] + d, fp.vertices[-1] - d, fp.vertices[0] - d]
            )
            ax.add_patch(Polygon(quad, closed=True, fc="0.45", ec="none"))
    if sites:
        for st in workplace.stations.values():
            if st.pos[2] < 0.05:
                ax.plot(*st.xy, marker="o", ms=3, color="tab:blue")
                ax.annotate(st.name, st.xy, fontsize=6, xytext=(3, 3), textcoords="offset points")
    ax.set_xlim(xmin - 0.1, xmax + 0.1)
    ax.set_ylim(ymin - 0.1, ymax + 0.1)
    ax.set_aspect("equal")
    ax.set_xlabel("x [m]")
    ax.set_ylabel("y [m]")


def draw_paths(
    ax,
    paths: Sequence[WalkPath],
    *,
    color=None,
    label: str | None = None,
    footprints=False,
    lw: float = 1.0,
    alpha: float = 0.8,
) -> None:
    """Draw walk paths (and optionally their footprints) on ``ax``.

    Args:
        ax: the matplotlib axes (world frame, metres).
        paths: the walks; the first one's start (square) and end (star) are marked.
        color: their colour (None: matplotlib's next).
        label: legend label, given to the first walk only.
        footprints: also draw each walk's footprints as arrows along the foot's yaw (left red,
            right green).
        lw: line width, points.
        alpha: line opacity.
    """
    for k, p in enumerate(paths):
        ax.plot(
            p.xy[:, 0], p.xy[:, 1], color=color, lw=lw, alpha=alpha, label=label if k == 0 else None
        )
        if footprints and p.steps:
            fp = p.footprints()
            for side, col in ((0, "tab:red"), (1, "tab:green")):
                sel = fp[:, 0] == side
                ax.quiver(
                    fp[sel, 1],
                    fp[sel, 2],
                    np.cos(fp[sel, 3]),
                    np.sin(fp[sel, 3]),
                    color=col,
                    scale=40,
                    width=0.003,
                    alpha=0.7,
                )
    _mark_ends(ax, paths)


def _mark_ends(ax, paths: Sequence[WalkPath]) -> None:
    """Mark the first walk's start (a square) and end (a star) on ``ax``, if there is one."""
    if paths:
        ax.plot(*paths[0].xy[0], marker="s", color="k", ms=6)
        ax.plot(*paths[0].xy[-1], marker="*", color="k", ms=9)


def save_plan_png(
    path: str | Path,
    workplace: Workplace,
    paths: Sequence[WalkPath] = (),
    *,
    baseline: WalkPath | None = None,
    title: str | None = None,
    footprints: bool = False,
) -> None:
    """Write a top-view PNG of ``workplace`` with ``paths`` (and a baseline route), atomically.

    Args:
        path: image file to write (the suffix picks the format: .png, .svg, ...).
        workplace: the scene (floor, clearance shading, obstacles, sites).
        paths: the planned walks.
        baseline: a grid-A* route to draw beside them, or None.
        title: the figure's title (default: the scene's name).
        footprints: also draw the walks' footprints.
    """
    xmin, ymin, xmax, ymax = workplace.floor_bounds
    width = 10.0
    fig, ax = plt.subplots(figsize=(width, width * (ymax - ymin) / (xmax - xmin) * 0.9 + 0.6))
    try:
        draw_floor(ax, workplace)
        draw_paths(
            ax,
            paths,
            color="tab:purple",
            label=f"{len(paths)} planned walk(s)",
            footprints=footprints,
            alpha=0.7 if len(paths) > 1 else 1.0,
        )
        if baseline is not None:
            draw_paths(ax, [baseline], color="tab:orange", label="grid A* baseline", lw=2)
        if paths or baseline is not None:
            ax.legend(loc="upper right", fontsize=8)
        ax.set_title(title or workplace.name)
        fig.tight_layout()
        with atomic_path(path) as tmp:
            fig.savefig(tmp, dpi=120)
    finally:
        plt.close(fig)


# ---------------------------------------------------------------- report charts
def route_colors(labels: Sequence[str]) -> dict[str, tuple]:
    """A tab10 colour per route label, in order.

    Args:
        labels: the route labels.

    Returns:
        ``{label: RGBA tuple}``, tab10's colours in order, repeating after ten.
    """
    cmap = matplotlib.colormaps["tab10"]
    return {label: cmap(k % 10) for k, label in enumerate(labels)}


#: The spaghetti plot draws at most this many walks of each route (runs evenly spaced over the
#: batch): beyond a few hundred faint lines a corridor looks the same, and drawing every walk
#: of 10 000 runs (70 000 paths at the station) took most of a minute and gigabytes.
MAX_DRAWN_PER_ROUTE = 500


def spaghetti_png(
    path: Path, results: Sequence[CycleResult], workplace: Workplace, baseline, rep: dict
) -> None:
    """The report's floor plan: the walks of ``results`` coloured by route (faint when there
    are many; at most :data:`MAX_DRAWN_PER_ROUTE` of each route, from runs evenly spaced over
    the batch), each drawn walk's own grid-A* route (between its two ends,
    ``WalkRecord.baseline``) dashed in the route's colour, written as a PNG to ``path``.
    ``baseline`` (a mapping, see :func:`mjwalk.report.write_report`) draws those routes
    instead of the walks' own; ``rep`` is :func:`mjwalk.report.report_dict`'s.

    Args:
        path: PNG file to write.
        results: the simulated cycles.
        workplace: their scene.
        baseline: routes to draw instead of the walks' own, or None.
        rep: the report's figures (its route labels).
    """

    labels = list(rep["routes"])
    colors = route_colors(labels)
    xmin, ymin, xmax, ymax = workplace.floor_bounds
    fig, ax = plt.subplots(figsize=(10, 10 * (ymax - ymin) / (xmax - xmin) * 0.9 + 0.6))
    try:
        draw_floor(ax, workplace, shade=False)
        capped = False
        routes: list[tuple[str, WalkPath]] = []  # (route label, grid-A* route) to draw
        for label in labels:
            walks = [w for r in results for w in r.walks if w.route == label]
            if len(walks) > MAX_DRAWN_PER_ROUTE:
                keep = np.linspace(0, len(walks) - 1, MAX_DRAWN_PER_ROUTE).round().astype(int)
                walks = [walks[k] for k in keep]
                capped = True
            paths = [w.path for w in walks]
            alpha = 0.8 if len(paths) < 5 else max(0.15, 4.0 / len(paths))
            _draw_lines(ax, paths, color=colors[label], lw=0.8, alpha=alpha)
            # the route's legend entry: a line in the walks' style, its caps as theirs (a
            # collection's legend line would take a dashed line's)
            ax.plot([], [], color=colors[label], lw=0.8, alpha=alpha, label=label)
            _mark_ends(ax, paths)  # as draw_paths marks them
            if baseline is None:
                routes += [(label, w.baseline) for w in walks if w.baseline is not None]
        if baseline is not None:
            leg_route = {(w.start_site, w.goal_site): w.route for r in results for w in r.walks}
            for key, value in baseline.items():
                label = leg_route.get(tuple(key), "") if isinstance(key, tuple) else key
                routes += [(label, p) for p in ([value] if isinstance(value, WalkPath) else value)]
        count: dict[str, int] = {}
        for label, _ in routes:
            count[label] = count.get(label, 0) + 1
        for label, group in itertools.groupby(routes, key=lambda lp: lp[0]):
            # many routes overlap on the grid's lines: fainter than the walks they go with
            alpha = 0.9 if count[label] < 5 else max(0.08, 3.0 / count[label])
            _draw_lines(ax, [p for _, p in group], color=colors.get(label, "k"), lw=1.0,
                        alpha=alpha, ls="--")  # fmt: skip
        if routes:  # one neutral legend entry for all grid-A* routes
            what = "each walk's own ends" if baseline is None else "given routes"
            ax.plot([], [], ls="--", lw=1.8, color="k", label=f"grid A* ({what}, route colour)")
        legend = ax.legend(loc="upper right", fontsize=8)
        for handle in legend.legend_handles:  # the runs are faint; their legend lines are not
            if handle is None:
                continue
            handle.set_alpha(1.0)
            handle.set_linewidth(2.0)  # type: ignore[attr-defined]  # lines and collections
        drawn_note = f" ({MAX_DRAWN_PER_ROUTE} per route drawn)" if capped else ""
        ax.set_title(
            f"{rep['name'] or workplace.name}: {len(results)} run(s), walks by route{drawn_note}"
        )
        fig.tight_layout()
        fig.savefig(path, dpi=110)
    finally:
        plt.close(fig)


def _draw_lines(ax, paths: Sequence[WalkPath], **style) -> None:
    """Draw walk paths on ``ax`` as one :class:`~matplotlib.collections.LineCollection` in
    a line's style (zorder, cap and join styles of :meth:`ax.plot`'s lines), in order.

    One artist instead of one line per walk: the spaghetti plot draws thousands (issue 50:
    most of the report's time over a few hundred runs went to making and drawing them).

    Args:
        ax: the matplotlib axes (world frame, metres).
        paths: the walks.
        **style: ``color``, ``lw``, ``alpha`` and ``ls`` of the lines.
    """
    if not paths:
        return
    ls = style.pop("ls", "-")
    rc = matplotlib.rcParams  # a line's caps and joins, solid or dashed
    cap, join = (
        (rc["lines.solid_capstyle"], rc["lines.solid_joinstyle"])
        if ls == "-"
        else (rc["lines.dash_capstyle"], rc["lines.dash_joinstyle"])
    )
    lines = LineCollection(
        [p.xy[:, :2] for p in paths],
        colors=[style.pop("color")],
        linewidths=style.pop("lw"),
        linestyles=ls,
        zorder=mlines.Line2D.zorder,
        capstyle=cap,
        joinstyle=join,
        **style,
    )
    ax.add_collection(lines, autolim=False)


def histograms_png(path: Path, results: Sequence[CycleResult], rep: dict) -> None:
    """The report's histograms: cycle time (stacked by operator group when the population has
    several, takt as a red line) and the walk length of every route, each direction (from ->
    to) in its own shade with its median dashed and the median of its walks' own grid-A*
    routes solid (the capture's median dotted), written as a PNG to ``path``.

    Args:
        path: PNG file to write.
        results: the simulated cycles.
        rep: the report's figures (:func:`mjwalk.report.report_dict`).
    """

    labels = list(rep["routes"])
    colors = route_colors(labels)
    n = 1 + len(labels)
    cols = min(3, n)
    rows = math.ceil(n / cols)
    fig, axes = plt.subplots(rows, cols, figsize=(4.2 * cols, 3.2 * rows), squeeze=False)
    try:
        axes = axes.ravel()
        ax = axes[0]
        times = np.array([r.cycle_time for r in results])
        groups = list(rep.get("groups") or {})
        if len(groups) > 1:  # stacked by operator group
            edges = np.histogram_bin_edges(times, bins="auto")
            by = [[r.cycle_time for r in results if r.group == g] for g in groups]
            cmap = matplotlib.colormaps["Set2"]
            group_colors = [cmap(k % 8) for k in range(len(groups))]
            ax.hist(by, bins=edges, stacked=True, color=group_colors, label=groups)
        else:
            ax.hist(times, bins="auto", color="0.4")
        ax.axvline(rep["cycle_time"]["median"], color="k", ls="--", lw=1, label="median")
        if rep.get("over_takt"):
            e = rep["over_takt"]
            ax.axvline(
                e["takt"], color="tab:red", lw=1.5, label=f"takt ({100 * e['share']:.0f} % over)"
            )
        ax.set_xlabel("cycle time [s]")
        ax.set_ylabel("runs")
        ax.set_title("cycle time" + (" by operator group" if len(groups) > 1 else ""))
        ax.legend(fontsize=7)
        for ax, label in zip(axes[1:], labels, strict=False):
            _route_histogram(ax, label, results, rep["routes"][label], colors[label])
        for ax in axes[n:]:
            ax.set_visible(False)
        fig.tight_layout()
        fig.savefig(path, dpi=100)
    finally:
        plt.close(fig)


def ergonomics_png(path: Path, records: Sequence) -> None:
    """The report's ergonomics chart. Top: RULA and REBA over one cycle's time (the run whose
    peak RULA is the median's) and the distributions of the cycles' peak RULA and REBA per
    operator group. Bottom, for runs scored for continuous exposure
    (:mod:`mjwalk.ergonomics.exposure`): that run's arm elevation and trunk flexion over the
    cycle against the zone limits, and each run's seconds above 60 deg of arm elevation and
    the arm's elevation at the highest grasp against its operator's stature (one point per
    run) with the smooth trend and its 95 % band
    (:func:`mjwalk.ergonomics.workforce.stature_trend`; ``records``:
    :class:`mjwalk.ergonomics.summary.RunRecord`).

    Args:
        path: PNG file to write.
        records: the scored runs, at least one.
    """
    exposed = [r for r in records if "exposure_trace" in r.ergo.extra]
    fig, axes = plt.subplots(2 if exposed else 1, 3, figsize=(14, 7.2 if exposed else 3.6))
    top = axes[0] if exposed else axes
    try:
        peaks = np.array([r.ergo.rula_peak for r in records])
        k = int(np.argsort(peaks)[len(peaks) // 2])
        _score_panels(top, records, k)
        if exposed:
            _exposure_panels(fig, axes[1], records[k], records)
        fig.tight_layout()
        fig.savefig(path, dpi=100)
    finally:
        plt.close(fig)


def _score_panels(axes, records: Sequence, k: int) -> None:
    """RULA/REBA over run ``k``'s cycle and the peaks' distributions per group."""
    e = records[k].ergo
    t = np.arange(len(e.rula)) / e.fps
    ax = axes[0]
    ax.step(t, e.rula, where="post", label="RULA", lw=1)
    ax.step(t, e.reba, where="post", label="REBA", lw=1, alpha=0.8)
    for task in e.tasks:
        if task.reach:
            ax.axvline(task.rula_time, color="0.8", lw=0.5, zorder=0)
    ax.set_xlabel("time in the cycle [s]")
    ax.set_ylabel("score")
    ax.set_title(f"run {records[k].run}: scores over the cycle")
    ax.legend(fontsize=7)
    groups = sorted({r.group for r in records})
    for ax, name, get, top in (
        (axes[1], "peak RULA", lambda r: r.ergo.rula_peak, 7),
        (axes[2], "peak REBA", lambda r: r.ergo.reba_peak, 15),
    ):
        data = [[get(r) for r in records if r.group == g] for g in groups]
        bins = np.arange(0.5, top + 1.5)
        ax.hist(data, bins=bins, label=[g or "all" for g in groups], stacked=True)
        ax.set_xlabel(name)
        ax.set_ylabel("cycles")
        ax.set_title(f"{name} per cycle" + (" by operator group" if len(groups) > 1 else ""))
        ax.legend(fontsize=7)


def _exposure_panels(fig, axes, rec, records: Sequence) -> None:
    """Run ``rec``'s exposure timeline (two panels wide) and, against stature, one point per
    run with the smooth trend and its 95 % band: the arm's seconds above 60 deg and its
    elevation at the highest grasp."""
    gs = axes[0].get_subplotspec().get_gridspec()
    axes[0].remove()
    axes[1].remove()
    ax = fig.add_subplot(gs[1, :2])
    tr = rec.ergo.extra["exposure_trace"]
    t = np.arange(len(tr)) / rec.ergo.fps
    ax.plot(t, tr[:, 0], lw=1, label="upper-arm elevation (higher arm)")
    ax.plot(t, tr[:, 1], lw=1, label="trunk flexion")
    for lim in (20, 60):
        ax.axhline(lim, color="0.5", ls="--", lw=0.7)
    ax.set_xlabel("time in the cycle [s]")
    ax.set_ylabel("deg")
    ax.set_title(
        f"run {rec.run}: exposure over the cycle (EN 1005-4 / ISO 11226 zones at 20 and 60 deg; "
        f"{rec.ergo.extra['exposure_verdict']})"
    )
    ax.legend(fontsize=7)
    axes[2].remove()
    sub = gs[1, 2].subgridspec(2, 1, hspace=0.08)
    pts = [r for r in records if r.stature is not None and "arm_over60_s" in r.ergo.extra]
    for i, (key, label) in enumerate(
        (
            ("arm_over60_s", "arm >60 deg\nper cycle [s]"),
            ("arm_top_deg", "arm at highest\ngrasp [deg]"),
        )
    ):
        ax = fig.add_subplot(sub[i])
        _stature_panel(ax, [r for r in pts if key in r.ergo.extra], key, legend=i == 0)
        ax.set_ylabel(label, fontsize=8)
        if i == 0:
            ax.set_title("exposure against stature (one point per run)")
            ax.tick_params(labelbottom=False)
        else:
            ax.set_xlabel("stature [m]")


def _stature_panel(ax, pts: Sequence, key: str, legend: bool) -> None:
    """One exposure figure of the runs against stature: a point per run by group, the smooth
    trend and its 95 % band."""
    for g in sorted({r.group for r in pts}):
        sel = [r for r in pts if r.group == g]
        ax.scatter([r.stature for r in sel], [r.ergo.extra[key] for r in sel], s=10,
                   label=g or "all")  # fmt: skip
    trend = stature_trend(
        np.array([r.stature for r in pts]), np.array([r.ergo.extra[key] for r in pts])
    )
    if trend:
        sm = trend["smooth"]
        at = [x["stature_m"] for x in sm]
        ax.fill_between(at, [x["low"] for x in sm], [x["high"] for x in sm], color="0.6",
                        alpha=0.3, lw=0, label="95 % band (bootstrap)")  # fmt: skip
        ax.plot(at, [x["value"] for x in sm], "k-", lw=1.5, label="trend (LOWESS)")
    if legend and pts:
        ax.legend(fontsize=6)


def _shade(color, k: int, n: int) -> tuple:
    """``color`` for direction ``k`` of ``n``: the first as it is, later ones darker."""
    rgb = np.asarray(matplotlib.colors.to_rgb(color))
    return tuple(rgb * (1.0 - 0.55 * k / max(1, n - 1))) if n > 1 else tuple(rgb)


def _route_histogram(ax, label: str, results: Sequence[CycleResult], e: dict, color) -> None:
    """One route's walk lengths on ``ax``, per direction (``e`` is the route's entry of
    :func:`mjwalk.report.report_dict`)."""
    walks = [w for r in results for w in r.walks if w.route == label]
    dirs = e.get("directions") or [{"from": None, "to": None, **e}]
    samples = [
        [
            w.length
            for w in walks
            if d["from"] is None or (w.start_site, w.goal_site) == (d["from"], d["to"])
        ]
        for d in dirs
    ]
    # shared bins as fine as the finest direction's own ("auto") bins: the directions' lengths
    # may lie far apart, and bins chosen for the pooled lengths would blur each of them
    pooled = np.concatenate([np.asarray(x, dtype=float) for x in samples])
    widths = [np.diff(np.histogram_bin_edges(x, bins="auto"))[0] for x in samples if len(x) > 1]
    lo, hi = float(pooled.min()), float(pooled.max())
    width = min(widths, default=0.0)
    if width > 0 and (hi - lo) / width <= 200:
        n = max(1, math.ceil((hi - lo) / width))
        edges = lo + width * np.arange(n + 1)
        edges[-1] = max(edges[-1], hi)
    else:
        edges = np.histogram_bin_edges(pooled, bins="auto")
    for k, (d, lengths) in enumerate(zip(dirs, samples, strict=True)):
        shade = _shade(color, k, len(dirs))
        name = "" if d["from"] is None else f"{d['from']} -> {d['to']}"
        ax.hist(lengths, bins=edges, color=shade, alpha=0.6, label=f"{name} ({len(lengths)})")
        ax.axvline(d["length"]["median"], color=shade, ls="--", lw=1.2)
        if not math.isnan(d["baseline_length"]):
            ax.axvline(d["baseline_length"], color=shade, lw=1.5)
    ax.plot([], [], color="k", ls="--", lw=1.2, label="median")
    ax.plot([], [], color="k", lw=1.5, label="grid A* (own ends, median)")
    if "reference" in e:
        ax.axvline(e["reference"]["median"], color="k", ls=":", lw=1.5, label="capture (pooled)")
    ax.set_xlabel("walk length [m]")
    ax.set_title(f"route {label} ({e['walks']} walks, {len(dirs)} direction(s))")
    ax.legend(fontsize=6)
