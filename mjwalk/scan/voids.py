"""Unseen floor as a policy the user chooses, reported in figures and a top-view picture.

A scanner sees no floor behind furniture, under itself, or beyond the last station; the floor
plan (:mod:`.obstacles`) counts small holes as floor and makes the rest *void*: a box the
planner walks around. ``--voids`` chooses what void means:

- ``blocked`` (the default): nobody walks where no floor was seen. An unseen region can hide
  an obstacle (a pallet, a step down) that no point shows, so a plan through it is a guess;
  the remedy is more stations (``mjwalk scan A B C``), not trust.
- ``fill``: a void enclosed by the walkable floor and obstacles (touching no edge of the floor
  rectangle) whose inscribed radius is at most :data:`FILL_RADIUS` is floor; larger ones stay
  blocked.
- ``free``: all unseen floor inside the floor rectangle is walkable.
"""

from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass
from pathlib import Path

import numpy as np
from scipy import ndimage

from mjwalk._io import atomic_path
from mjwalk.errors import ScanError
from mjwalk.scan.levelboxes import LevelPlan, draw_levels
from mjwalk.scan.obstacles import HOLE_RADIUS, FloorPlan
from mjwalk.scan.scanpits import ScanPit

#: The choices of ``--voids``.
POLICIES = ("blocked", "fill", "free")
#: ``fill`` makes enclosed voids up to this inscribed radius walkable, metres: twice the blind
#: disc under a tripod scanner (:data:`~mjwalk.scan.obstacles.HOLE_RADIUS`, always floor),
#: the shadow a bench-height occluder casts on the floor a few metres from the scanner.
FILL_RADIUS = 2 * HOLE_RADIUS


@dataclass(frozen=True)
class FloorCover:
    """Floor areas of a plan, square metres: ``seen`` (floor points), ``unseen_walkable``
    (holes and voids counted as floor), ``blocked`` (void boxes), ``obstacles``."""

    seen: float
    unseen_walkable: float
    blocked: float
    obstacles: float

    def line(self) -> str:
        """One line for the report.

        Returns:
            The four areas, square metres.
        """
        return (
            f"floor seen {self.seen:.1f} m², unseen but walkable {self.unseen_walkable:.1f} m², "
            f"unseen and blocked (void boxes) {self.blocked:.1f} m², obstacles "
            f"{self.obstacles:.1f} m²"
        )


def check_policy(policy: str) -> str:
    """Refuse an unknown unseen-floor policy.

    Args:
        policy: one of :data:`POLICIES`.

    Returns:
        ``policy``.

    Raises:
        ScanError: naming the choices.
    """
    if policy not in POLICIES:
        raise ScanError(f"unknown --voids {policy!r} (one of {', '.join(POLICIES)})")
    return policy


def apply_policy(plan: FloorPlan, policy: str) -> FloorPlan:
    """The plan with its voids walkable as ``policy`` says (module docstring).

    Args:
        plan: the floor plan.
        policy: blocked (unchanged), fill (enclosed voids up to :data:`FILL_RADIUS` inscribed
            radius become floor) or free (every void becomes floor).

    Returns:
        The plan, a new one when voids changed.
    """
    check_policy(policy)
    if policy == "blocked" or not plan.void.any():
        return plan
    walk = plan.void.copy()
    if policy == "fill":
        lab, n = ndimage.label(plan.void, np.ones((3, 3), bool))
        edge = np.unique(np.concatenate([lab[0], lab[-1], lab[:, 0], lab[:, -1]]))
        radius = ndimage.distance_transform_edt(np.pad(plan.void, 1))[1:-1, 1:-1]
        inscribed = np.asarray(ndimage.maximum(radius, lab, np.arange(1, n + 1))) * plan.resolution
        ok = (inscribed <= FILL_RADIUS) & ~np.isin(np.arange(1, n + 1), edge)
        walk = np.isin(lab, np.flatnonzero(ok) + 1)
    return dataclasses.replace(plan, floor=plan.floor | walk, void=plan.void & ~walk)


def cover(plan: FloorPlan) -> FloorCover:
    """The areas of :class:`FloorCover` for a plan.

    Args:
        plan: the floor plan.

    Returns:
        Its floor seen, unseen but walkable, blocked and obstacle areas, square metres.
    """
    a = plan.resolution**2
    seen = plan.seen if plan.seen is not None else plan.floor
    return FloorCover(
        float(seen.sum() * a),
        float((plan.floor & ~seen).sum() * a),
        float(plan.void.sum() * a),
        float((plan.obstacles > 0).sum() * a),
    )


def save_top_view(
    plan: FloorPlan,
    path: str | Path,
    title: str = "",
    levels: LevelPlan | None = None,
    pits: list[ScanPit] | None = None,
) -> Path:
    """A top view of the plan (floor seen, unseen but walkable, obstacles,
    voids) as an image, written atomically.

    Args:
        plan: the floor plan.
        path: the image file.
        title: the figure's title ("": a default naming the areas).
        levels: the raised levels drawn over it with their heights and links
            (:func:`mjwalk.scan.levelboxes.draw_levels`); None: none.
        pits: the gaps in the floor, each labelled with its bottom and how it is reached
            (:mod:`mjwalk.scan.scanpits`); None: none.

    Returns:
        ``path`` as a path. A failed write is a WriteError naming the file.
    """
    import matplotlib  # deferred: matplotlib is slow to import, only the top view needs it

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt  # deferred: after matplotlib.use('Agg')
    from matplotlib.colors import ListedColormap  # deferred: matplotlib is slow to import
    from matplotlib.patches import Patch  # deferred: matplotlib is slow to import

    seen = plan.seen if plan.seen is not None else plan.floor
    kind = np.where(seen, 0, np.where(plan.floor, 1, np.where(plan.obstacles > 0, 2, 3)))
    colours = ["#d9d9d4", "#f2d675", "#6b645a", "#c0392b", "#ffffff"]
    names = ["floor seen", "unseen, walkable", "obstacle", "void (unseen, blocked)"]
    if levels is not None:  # under the raised levels: neither floor, obstacle nor void
        kind = np.where((kind == 3) & ~plan.void, 4, kind)
        names.append("raised level")
    reached = np.zeros(kind.shape, bool)  # pits a stair or steps reach: levels below the floor
    for p in pits or []:
        if p.link is not None:
            reached |= p.cells
    if plan.gaps is not None and (plan.gaps & ~reached).any():  # the floor missing (scanpits)
        kind = np.where(plan.gaps & ~reached, len(names), kind)
        colours = [*colours[: len(names)], "#e67e22"]
        names.append("gap (floor missing): obstacle")
    if reached.any():
        kind = np.where(reached, len(names), kind)
        colours = [*colours[: len(names)], "#85c1e9"]
        names.append("pit level (below the floor)")
    ny, nx = kind.shape
    r = plan.resolution
    extent = (plan.x0, plan.x0 + nx * r, plan.y0, plan.y0 + ny * r)
    fig, ax = plt.subplots(figsize=(8, 8 * ny / max(nx, 1) + 0.8))
    ax.imshow(
        kind,
        origin="lower",
        extent=extent,
        cmap=ListedColormap(colours[: len(names)]),
        vmin=0,
        vmax=len(names) - 1,
        interpolation="nearest",
    )
    ax.set_xlabel("x (m)")
    ax.set_ylabel("y (m)")
    ax.set_aspect("equal")
    c = cover(plan)
    ax.set_title(title or c.line(), fontsize=8)
    if levels is not None:
        draw_levels(ax, levels)
    for k, p in enumerate(pits or []):
        what = "no bottom seen" if p.bottom is None else f"bottom {p.bottom.height:+.2f} m"
        if p.link is not None and p.link.risers:
            what += f", {p.link.kind} {len(p.link.risers)} x {p.link.risers[0]:.2f} m"
        elif p.link is not None:
            what += f", ramp {math.degrees(p.link.slope or 0.0):.1f}°"
            draw_pit_link(ax, p, plan)
            what = f"pit level, {what}"
        at = p.centre if p.link is None else (p.centre[0], p.centre[1] - 0.3)  # under the arrow
        ax.annotate(f"gap {k + 1}: {what}", at, fontsize=6, ha="center", va="center")
    ax.legend(
        handles=[Patch(color=k, label=n) for k, n in zip(colours, names, strict=False)],
        loc="upper right",
        fontsize=7,
    )
    path = Path(path)
    try:
        with atomic_path(path) as tmp:
            fig.savefig(tmp, dpi=120, bbox_inches="tight")
    finally:
        plt.close(fig)
    return path


def draw_pit_link(ax, pit: ScanPit, plan: FloorPlan) -> None:
    """Draw how the floor reaches a pit level: an arrow from its bottom up to the tread next to
    the floor (as :func:`mjwalk.scan.levelboxes.draw_levels` draws a link, from the lower level
    up), each tread's cells outlined (a ramp: hatched, the arrow up its middle); the pit's
    label, drawn by the caller, names the link.

    Args:
        ax: a matplotlib axes in world x, y metres.
        pit: a pit a link reaches (``pit.link`` not None).
        plan: the floor plan its cells lie on.

    Returns:
        None; draws on ``ax``.
    """
    if pit.link is None or pit.bottom is None:
        return
    if pit.ramp is not None:  # up the ramp's middle, its outline hatched
        rp = pit.ramp
        ax.fill(*rp.rect.T, fill=False, lw=0.8, ec="k", hatch="///")
        mid = 0.5 * (rp.w_lo + rp.w_hi) * np.array([-rp.run[1], rp.run[0]])
        p, q = rp.s_lo * rp.run + mid, rp.s_hi * rp.run + mid
        ax.annotate("", q, p, arrowprops={"arrowstyle": "->", "color": "#b03a2e", "lw": 1.0})
        return
    r = plan.resolution

    def centre(cells: np.ndarray) -> np.ndarray:
        iy, ix = np.nonzero(cells)
        return np.array([plan.x0 + (ix.mean() + 0.5) * r, plan.y0 + (iy.mean() + 0.5) * r])

    ny, nx = plan.floor.shape
    extent = (plan.x0, plan.x0 + nx * r, plan.y0, plan.y0 + ny * r)
    for i in pit.link.via:
        ax.contour(
            pit.levels[i].cells,
            levels=[0.5],
            colors="k",
            linewidths=0.6,
            extent=extent,
            origin="lower",
        )
    top = pit.levels[pit.link.via[-1]].cells if pit.link.via else pit.bottom.cells
    p, q = centre(pit.bottom.cells), centre(top)
    ax.annotate("", q, p, arrowprops={"arrowstyle": "->", "color": "#b03a2e", "lw": 1.0})
