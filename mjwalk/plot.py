"""Top-view plots of a workplace: floor plan, obstacles, clearance shading, walk paths."""

from __future__ import annotations

from collections.abc import Sequence
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np
from matplotlib.patches import Circle, Polygon, Rectangle

from mjwalk._io import atomic_path
from mjwalk.plan.walkpath import WalkPath
from mjwalk.world.workplace import Workplace


def draw_floor(ax, workplace: Workplace, *, shade: bool = True, sites: bool = True) -> None:
    """Draw the floor outline, clearance shading, obstacle footprints and stand sites on ``ax``."""
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
    """Draw walk paths (and optionally their footprints) on ``ax``."""
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
    """Write a top-view PNG of ``workplace`` with ``paths`` (and a baseline route), atomically."""
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
