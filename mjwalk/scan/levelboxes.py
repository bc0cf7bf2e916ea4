"""Scan levels as MJCF boxes: stairs fitted as regular flights, each level a walkable box.

:func:`scan_levels` takes the levels of :func:`mjwalk.scan.scanlevels.find_levels` to the scene:

- **Stairs.** A chain from a level over single treads to a level, with at least
  ``norms.MIN_STAIR_RISERS`` risers, is fitted as one regular flight
  (:func:`mjwalk.scan.stairfit.fit_stair`); a stair's top tread the level above hides is
  inferred from the flight (:mod:`mjwalk.scan.hiddentread`). A flight's treads become exact
  boxes, and the top level's edge is put on the last riser. Other chains are steps.
- **Boxes.** Every level but the floor is a solid box standing on the floor up to its height
  (as the shipped multi-level scene builds them), over its cells' minimum-area rectangle; a
  level reached by a step from below reaches under the higher one by the cells that touch it,
  so the two edges meet (``norms.CONTACT_GAP``). What stands on a level higher than
  ``OBSTACLE_Z_RANGE[0]`` above it is an obstacle box on it; the sides of a higher level
  (points no higher than its top, within a few cells of it) are not obstacles of the lower one.

Then ``mjwalk.world.find_walk_surfaces`` and ``level_graph`` on the written scene find the same
levels and links. Metres, scene frame (floor at z = 0), yaw from +x CCW.
"""

from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass

import numpy as np
from scipy import ndimage

from mjwalk.scan.hiddentread import hidden_treads
from mjwalk.scan.levelparts import level_parts
from mjwalk.scan.obstacles import FLOOR_TOL, MIN_BAND_POINTS, TOP_STEP, FloorPlan, rectangles
from mjwalk.scan.scanlevels import (
    Layers,
    ScanLevel,
    ScanLink,
    find_regions,
    keep_reachable,
    min_rectangle,
    rectangle_size,
    seen_in_part,
)
from mjwalk.scan.scanramps import ScanRamp, find_ramps, ramp_box, renumber
from mjwalk.scan.stairfit import fit_stair
from mjwalk.scan.writtennorm import ramps_to_levels, stairs_within_norm, steps_within_norm
from mjwalk.world.floor import OBSTACLE_Z_RANGE
from mjwalk.world.norms import CONTACT_GAP, MIN_STAIR_RISERS

#: Material of the level boxes.
LEVEL_MATERIAL = "scan_level"


@dataclass
class LevelPlan:
    """The levels of a scan ready to write.

    Attributes:
        levels: the levels, the floor first (:class:`~mjwalk.scan.scanlevels.ScanLevel`).
        links: steps and stairs between them, steps first.
        heights: each level's box height, metres (a stair's treads: the regular flight's).
        rects: each level's box outline (4, 2) counter-clockwise, metres (None for the floor).
        plan: the floor plan with the levels and their sides taken out of its obstacles and
            voids.
        boxes: the boxes on the levels: (name, centre (3,), half sizes (3,), material, yaw
            radians or, for a tilted ramp, xyaxes (6,)).
        n_level_boxes: how many of ``boxes`` are the levels and ramps themselves (they come
            first, the levels' before the ramps').
        ramps: the ramps between levels (:mod:`~mjwalk.scan.scanramps`), in the order of their
            links.
        parts: per level, the rectangles (4, 2) its box is written as when its outline holds
            air a walker could stand on (:mod:`~mjwalk.scan.levelparts`); empty: the outline.
    """

    levels: list[ScanLevel]
    links: list[ScanLink]
    heights: list[float]
    rects: list[np.ndarray | None]
    plan: FloorPlan
    boxes: list[tuple]
    n_level_boxes: int
    ramps: list[ScanRamp] = dataclasses.field(default_factory=list)
    parts: list[list[np.ndarray]] = dataclasses.field(default_factory=list)

    def outlines(self, i: int) -> list[np.ndarray]:
        """Level ``i``'s box outlines: its parts, or its one outline (none for the floor).

        Args:
            i: the level's index.

        Returns:
            The rectangles (4, 2), metres.
        """
        if i < len(self.parts) and len(self.parts[i]) > 1:
            return self.parts[i]
        rect = self.rects[i]
        return [] if rect is None else [rect]


def _chains(levels: list[ScanLevel], pairs: list[tuple[int, int]]) -> list[list[int]]:
    """Chains of levels from a non-tread over single treads to a non-tread, bottom up."""
    up: dict[int, list[int]] = {}
    for i, j in pairs:
        up.setdefault(i, []).append(j)
    out = []
    for i, j in pairs:
        if levels[i].kind == "tread" or levels[j].kind != "tread":
            continue
        chain = [i, j]
        while levels[chain[-1]].kind == "tread":
            nxt = [k for k in up.get(chain[-1], []) if k not in chain]
            if len(nxt) != 1:
                break
            chain.append(nxt[0])
        if levels[chain[-1]].kind != "tread" and len(chain) - 1 >= MIN_STAIR_RISERS:
            out.append(chain)
    return out


def square_to_flight(rect: np.ndarray, run: np.ndarray, res: float) -> np.ndarray:
    """A flight's top level's rectangle (4, 2) turned about its centre onto the flight's axes
    when the two differ by less than the floor plan can tell apart: the angle one cell subtends
    over the rectangle's edge across the climb (``atan(res / edge)``). The level's rectangle is
    the minimum-area one of its cells and those it joins (:func:`_rects`), the flight's axes
    are its top level's own rectangle's (:func:`~mjwalk.scan.stairfit.fit_stair`): a landing
    turned 0.14 deg from its flight put the riser's contact with the last tread 2 mm deeper
    than the fitted tread, over DIN 18065's step rule, and the written flight read as single
    steps (generated hall 1068 of ``benchmarks/bench_unseen.py``). A top turned further is a
    level turned from its flight and is kept as it is.

    Args:
        rect: (4, 2) corners, metres.
        run: the flight's unit climb direction.
        res: the floor plan's cell edge, metres.

    Returns:
        (4, 2) corners, metres.
    """
    e = rect[1] - rect[0]
    a = math.atan2(float(e[1]), float(e[0])) - math.atan2(float(run[1]), float(run[0]))
    turn = (a + math.pi / 4) % (math.pi / 2) - math.pi / 4  # to the nearest of run's axes
    edges = (rect[1] - rect[0], rect[3] - rect[0])
    side = min(edges, key=lambda d: abs(float(d @ run)) / max(float(np.linalg.norm(d)), 1e-12))
    width = float(np.linalg.norm(side))  # the edge across the climb, metres
    if turn == 0.0 or abs(turn) >= math.atan2(res, max(width, res)):
        return rect
    c, s = math.cos(-turn), math.sin(-turn)
    mid = rect.mean(axis=0)
    return (rect - mid) @ np.array([[c, s], [-s, c]]) + mid


def _snap_edge(rect: np.ndarray, run: np.ndarray, at: float) -> np.ndarray:
    """A rectangle (4, 2) whose edge facing ``-run`` (an axis of it) is moved to ``at`` along
    ``run``; its far edge stays."""
    q = rect @ run
    lo, hi = float(q.min()), float(q.max())
    out = rect.copy()
    near = np.abs(q - lo) < 0.5 * (hi - lo)
    out[near] += (at - lo) * run
    return out


def _covers(rects: list[np.ndarray | None], plan: FloorPlan) -> list[np.ndarray]:
    """Per rectangle, the grid cells whose centre lies inside it (bool (ny, nx))."""
    ny, nx = plan.floor.shape
    r = plan.resolution
    gx, gy = np.meshgrid(plan.x0 + (np.arange(nx) + 0.5) * r, plan.y0 + (np.arange(ny) + 0.5) * r)
    out = []
    for rect in rects:
        if rect is None:
            out.append(np.zeros((ny, nx), bool))
            continue
        e1, e2 = rect[1] - rect[0], rect[3] - rect[0]
        u = (gx - rect[0, 0]) * e1[0] + (gy - rect[0, 1]) * e1[1]
        v = (gx - rect[0, 0]) * e2[0] + (gy - rect[0, 1]) * e2[1]
        out.append((u >= 0) & (u <= e1 @ e1) & (v >= 0) & (v <= e2 @ e2))
    return out


def _rects(
    levels: list[ScanLevel], pairs: list[tuple[int, int]], plan: FloorPlan
) -> tuple[list[np.ndarray | None], list[np.ndarray]]:
    """Each level's box outline: its cells, and the cells of the levels a step above it that
    touch it, in a minimum-area rectangle (None for the floor); and those cells."""
    d = math.ceil(CONTACT_GAP / plan.resolution) + 2
    out: list[np.ndarray | None] = [None]
    grid = [levels[0].cells]
    for lv in levels[1:]:
        cells = lv.cells.copy()
        near = ndimage.binary_dilation(lv.cells, np.ones((3, 3), bool), iterations=d)
        for i, j in pairs:
            if i == lv.index:
                cells |= near & levels[j].cells
        out.append(min_rectangle(cells, plan.x0, plan.y0, plan.resolution))
        grid.append(cells)
    return out, grid


def _links_and_stairs(
    levels: list[ScanLevel], pairs: list[tuple[int, int]], plan: FloorPlan
) -> tuple[list[ScanLink], list[tuple[list[int], dict]]]:
    """The step and stair links, and each stair's chain with its fit."""
    stairs = []
    for chain in _chains(levels, pairs):
        fit = fit_stair(chain, levels, plan)
        if fit is not None:
            stairs.append((chain, fit))
    in_stair = {(c[k], c[k + 1]) for c, _ in stairs for k in range(len(c) - 1)}
    links = [
        ScanLink("step", i, j, (levels[j].height - levels[i].height,))
        for i, j in pairs
        if (i, j) not in in_stair
    ]
    for chain, fit in stairs:
        n = len(chain) - 1
        links.append(
            ScanLink("stair", chain[0], chain[-1], (fit["riser"],) * n, fit["tread"],
                     tuple(chain[1:-1]))
        )  # fmt: skip
    return links, stairs


def band_top(top: np.ndarray, base: float) -> float:
    """An obstacle's top: its highest band point rounded up to the band's bins
    (``TOP_STEP`` from ``base + OBSTACLE_Z_RANGE[0]``, as the floor plan's), within the band;
    the lowest bin when it holds no band point (cells the floor plan closed between points,
    left apart when a level's cells leave it: as ``obstacles._obstacle_tops``).

    Args:
        top: the highest band point, metres (-inf: none).
        base: the height of the surface the obstacle stands on, metres.

    Returns:
        The top, metres.
    """
    z0, z1 = base + OBSTACLE_Z_RANGE[0], base + OBSTACLE_Z_RANGE[1]
    t = float(top)
    b = max(0, int((t - z0) / TOP_STEP)) if math.isfinite(t) else 0
    return min(z0 + (b + 1) * TOP_STEP, z1)


def _obstacle_boxes(
    mask: np.ndarray, top: np.ndarray, base: float, plan: FloorPlan, prefix: str
) -> list[tuple[str, np.ndarray, np.ndarray, str, float]]:
    """Boxes over the obstacle cells ``mask`` standing on height ``base``, each connected
    obstacle up to its highest band point (``top`` per cell)."""
    lab, n = ndimage.label(mask, np.ones((3, 3), bool))
    if n == 0:
        return []
    tops = ndimage.maximum(top, lab, np.arange(1, n + 1))
    r = plan.resolution
    out: list[tuple[str, np.ndarray, np.ndarray, str, float]] = []
    for iy0, iy1, ix0, ix1, k in rectangles(lab):
        z1 = band_top(tops[k - 1], base)
        lo = np.array([plan.x0 + ix0 * r, plan.y0 + iy0 * r, base])
        hi = np.array([plan.x0 + ix1 * r, plan.y0 + iy1 * r, z1])
        out.append((f"{prefix}_{len(out)}", 0.5 * (lo + hi), 0.5 * (hi - lo), "scan_obstacle", 0.0))
    return out


def _level_box(
    i: int, rect: np.ndarray, h: float, part: str = ""
) -> tuple[str, np.ndarray, np.ndarray, str, float]:
    e1, e2 = rect[1] - rect[0], rect[3] - rect[0]
    c = rect.mean(axis=0)
    half = np.array([0.5 * np.hypot(*e1), 0.5 * np.hypot(*e2), 0.5 * h])
    return (
        f"scan_level_{i}{part}",
        np.array([c[0], c[1], 0.5 * h]),
        half,
        LEVEL_MATERIAL,
        float(math.atan2(e1[1], e1[0])),
    )


def scan_levels(levelled: np.ndarray, plan: FloorPlan) -> LevelPlan | None:
    """The levels of a levelled scan as boxes, or None for a scan with one level.

    Args:
        levelled: (N, 3) points, metres, floor at z = 0.
        plan: its floor plan (after the void policy).

    Returns:
        None when no raised level is reachable from the floor (the scene is written as
        before); else the levels, links, boxes and the floor plan without them.
    """
    found, steps, layers = find_regions(levelled, plan)
    found, steps, layers = hidden_treads(found, steps, levelled, plan, layers)
    res = plan.resolution
    ramps = [
        r for r in find_ramps(levelled, plan, found)
        if not (seen_in_part(found[r.lower], res) or seen_in_part(found[r.upper], res))
    ]  # fmt: skip
    joins = [(r.lower, r.upper) for r in ramps]
    levels, pairs, new = keep_reachable(found, steps, joins)
    links, stairs = _links_and_stairs(levels, pairs, plan)
    in_stair = {i for chain, _ in stairs for i in chain[1:-1]}
    old = {n: o for o, n in new.items()}
    gone = {old[lv.index] for lv in levels if seen_in_part(lv, res) and lv.index not in in_stair}
    if gone:  # a region shallower than a tread is a level only in a flight
        steps = [(i, j) for i, j in steps if i not in gone and j not in gone]
        levels, pairs, new = keep_reachable(found, steps, joins)
        links, stairs = _links_and_stairs(levels, pairs, plan)
    ramps = [renumber(r, new) for r in ramps if r.lower in new and r.upper in new]
    if len(levels) == 1:
        return None
    links += [ScanLink("ramp", r.lower, r.upper, (), slope=r.slope, run=r.length) for r in ramps]
    heights = [lv.height for lv in levels]
    rects, cells = _rects(levels, pairs, plan)
    built = list(rects)
    for chain, fit in stairs:
        for k, i in enumerate(chain[1:-1]):
            rects[i], heights[i] = fit["rects"][k], fit["heights"][k]
        top = rects[chain[-1]]
        if top is not None:
            top = square_to_flight(top, fit["run"], plan.resolution)
            rects[chain[-1]] = _snap_edge(top, fit["run"], fit["top_edge"])
    for r in ramps:  # a level's edge where a ramp's end meets it
        if (up := rects[r.upper]) is not None:
            rects[r.upper] = _snap_edge(up, r.run, r.s_hi)
        if (down := rects[r.lower]) is not None:
            rects[r.lower] = _snap_edge(down, -r.run, -r.s_lo)
    treads = {i for chain, _ in stairs for i in chain[1:-1]}
    parts = [
        [] if (rect := rects[i]) is None or i in treads else level_parts(cells[i], rect, plan,
                                                                         built[i])
        for i in range(len(levels))
    ]  # fmt: skip
    for chain, fit in stairs:  # a flight's top in parts: its landing strip is one of them
        if len(parts[chain[-1]]) > 1:
            parts[chain[-1]].append(fit["rects"][-1] + fit["tread"] * fit["run"])
    before = list(heights)
    links = steps_within_norm(stairs_within_norm(links, heights), heights)
    ramps, links = ramps_to_levels(ramps, links, before, heights)
    return _assemble(levels, links, heights, rects, plan, layers, ramps, parts)


def _assemble(
    levels: list[ScanLevel],
    links: list[ScanLink],
    heights: list[float],
    rects: list[np.ndarray | None],
    plan: FloorPlan,
    layers: Layers,
    ramps: list[ScanRamp],
    parts: list[list[np.ndarray]],
) -> LevelPlan:
    """The boxes and the floor plan without the levels and ramps (see :func:`scan_levels`)."""
    covers = _covers(rects, plan)
    boxes: list[tuple] = []
    for i in range(1, len(levels)):
        if len(parts[i]) <= 1:
            boxes.append(_level_box(i, rects[i], heights[i]))  # type: ignore[arg-type]
            continue
        boxes += [_level_box(i, p, heights[i], f"_{k}") for k, p in enumerate(parts[i])]
        covers[i] = np.logical_or.reduce(_covers(list(parts[i]), plan))
    d = math.ceil(CONTACT_GAP / plan.resolution) + 2
    grown = [ndimage.binary_dilation(c, np.ones((3, 3), bool), iterations=d) for c in covers]
    boxes += [ramp_box(r, f"scan_ramp_{k}") for k, r in enumerate(ramps)]
    n_levels = len(boxes)
    on_ramps = _ramp_tops(ramps, plan)

    def free_of_higher(i: int, top: np.ndarray) -> np.ndarray:
        """Cells of level ``i``'s band that are a higher level or its sides, or a ramp."""
        out = np.isfinite(on_ramps) & (top <= on_ramps + FLOOR_TOL)
        for j in range(1, len(levels)):
            if heights[j] > heights[i] + OBSTACLE_Z_RANGE[0] - FLOOR_TOL:
                out |= covers[j] | (grown[j] & (top <= heights[j] + FLOOR_TOL))
        return out

    gone = free_of_higher(0, layers.top[0])
    obst = (plan.obstacles > 0) & ~gone
    olab, n = ndimage.label(obst, np.ones((3, 3), bool))
    tops = np.zeros(n + 1)
    if n:
        tops[1:] = [
            band_top(t, 0.0) for t in ndimage.maximum(layers.top[0], olab, np.arange(1, n + 1))
        ]
    void = plan.void & ~gone
    new_plan = dataclasses.replace(plan, obstacles=olab, tops=tops, void=void)
    for i in range(1, len(levels)):
        k = levels[i].peak
        mask = (layers.band[k] >= MIN_BAND_POINTS) & covers[i]
        mask &= ~free_of_higher(i, layers.top[k])
        boxes += _obstacle_boxes(mask, layers.top[k], heights[i], plan, f"scan_on_level{i}")
    return LevelPlan(levels, links, heights, rects, new_plan, boxes, n_levels, ramps, parts)


def _ramp_tops(ramps: list[ScanRamp], plan: FloorPlan) -> np.ndarray:
    """Per grid cell, the highest ramp surface over it or within ``CONTACT_GAP`` and two cells
    of it (its sides' points), metres; -inf: none."""
    ny, nx = plan.floor.shape
    r = plan.resolution
    gx, gy = np.meshgrid(plan.x0 + (np.arange(nx) + 0.5) * r, plan.y0 + (np.arange(ny) + 0.5) * r)
    out = np.full((ny, nx), -np.inf)
    d = CONTACT_GAP + 2 * r
    for rp in ramps:
        s = gx * rp.run[0] + gy * rp.run[1]
        w = -gx * rp.run[1] + gy * rp.run[0]
        near = (s >= rp.s_lo - d) & (s <= rp.s_hi + d) & (w >= rp.w_lo - d) & (w <= rp.w_hi + d)
        z = rp.h_lo + np.clip(s - rp.s_lo, 0.0, rp.length) * math.tan(rp.slope)
        out = np.where(near, np.maximum(out, z), out)
    return out


def levels_at(lp: LevelPlan, xy: np.ndarray) -> list[tuple[int, float]]:
    """The raised levels a point stands on: inside a level's box outline and outside the
    obstacle boxes standing on that level.

    Args:
        lp: the scan's levels.
        xy: (2,) scene x, y, metres.

    Returns:
        (level index, written height in metres) for each such level, lowest index first; empty
        when the point is on none (the floor is the caller's).
    """
    p = np.asarray(xy, dtype=np.float64)
    out = []
    for i in range(1, len(lp.levels)):
        if not any(_inside(rect, p) for rect in lp.outlines(i)):
            continue
        on = (b for b in lp.boxes[lp.n_level_boxes :] if b[0].startswith(f"scan_on_level{i}_"))
        if any((np.abs(p - b[1][:2]) <= b[2][:2]).all() for b in on):
            continue
        out.append((i, lp.heights[i]))
    return out


def _inside(rect: np.ndarray, p: np.ndarray) -> bool:
    """Whether a point (2,) lies in a rectangle (4, 2)."""
    e1, e2 = rect[1] - rect[0], rect[3] - rect[0]
    u, v = float((p - rect[0]) @ e1), float((p - rect[0]) @ e2)
    return 0 <= u <= e1 @ e1 and 0 <= v <= e2 @ e2


def draw_levels(ax, lp: LevelPlan) -> None:
    """Draw the levels on a top view: each box outline filled by its height, labelled
    ``L<i> +h m``, each ramp hatched, and each link as an arrow from the lower level up,
    labelled with its risers (a ramp's: along it, with its slope and rise).

    Args:
        ax: a matplotlib axes in world x, y metres.
        lp: the scan's levels.

    Returns:
        None; draws on ``ax``.
    """
    from matplotlib import colormaps  # deferred: matplotlib is slow to import, top view only

    cmap = colormaps["viridis"]
    top = max(lp.heights) or 1.0
    for lv, h, rect in zip(lp.levels, lp.heights, lp.rects, strict=True):
        if rect is None:
            continue
        for part in lp.outlines(lv.index):
            ax.fill(*part.T, color=cmap(h / top), alpha=0.55, lw=0.8, ec="k")
        c = rect.mean(axis=0)
        ax.annotate(f"L{lv.index} {h:+.2f} m", c, fontsize=6, ha="center", va="center")
    for rp in lp.ramps:
        ax.fill(*rp.rect.T, color=cmap(0.5 * (rp.h_lo + rp.h_hi) / top), alpha=0.55, lw=0.8,
                ec="k", hatch="///")  # fmt: skip
    ramps = iter(lp.ramps)
    for k in lp.links:
        if k.kind == "ramp":
            rp = next(ramps)
            side = np.array([-rp.run[1], rp.run[0]]) * 0.5 * (rp.w_lo + rp.w_hi)
            p, q = rp.s_lo * rp.run + side, rp.s_hi * rp.run + side
            ax.annotate("", q, p, arrowprops={"arrowstyle": "->", "color": "#b03a2e", "lw": 1.0})
            label = f"ramp {math.degrees(rp.slope):.1f}° {k.rise:.2f} m"
            ax.annotate(label, 0.5 * (p + q), fontsize=5, color="#b03a2e")
            continue
        a, b = (lp.rects[i] for i in (k.lower, k.upper))
        p = a.mean(axis=0) if a is not None else b.mean(axis=0) - 0.5  # type: ignore[union-attr]
        q = b.mean(axis=0) if b is not None else p
        ax.annotate("", q, p, arrowprops={"arrowstyle": "->", "color": "#b03a2e", "lw": 1.0})
        what = f"{len(k.risers)} x {k.risers[0]:.2f}" if k.kind == "stair" else f"{k.rise:.2f}"
        ax.annotate(f"{k.kind} {what} m", 0.5 * (p + q), fontsize=5, color="#b03a2e")


def describe(lp: LevelPlan) -> str:
    """The levels and links of a scan, one line each (``mjwalk scan`` prints it).

    Args:
        lp: the scan's levels.

    Returns:
        The text, no trailing newline.
    """
    lines = [f"levels: {len(lp.levels)}, links: {len(lp.links)} (heights fitted to the scan)"]
    for lv, h, rect in zip(lp.levels, lp.heights, lp.rects, strict=True):
        if rect is None:
            lines.append(f"  L{lv.index} floor    +0.000 m {lv.area:7.2f} m2")
            continue
        depth, width = rectangle_size(rect)
        c = rect.mean(axis=0)
        n = len(lp.outlines(lv.index))
        shape = f" (not rectangular: {n} boxes, {lv.area:.2f} m2 scanned)" if n > 1 else ""
        lines.append(
            f"  L{lv.index} {lv.kind:<8} {h:+.3f} m {depth * width:7.2f} m2  {depth:.2f} x "
            f"{width:.2f} m at ({c[0]:.2f}, {c[1]:.2f}), plane rms {1000 * lv.rms:.1f} mm{shape}"
        )
    ramps = iter(lp.ramps)
    for k in lp.links:
        if k.kind == "step":
            what = f"riser {k.rise:.3f} m"
        elif k.kind == "ramp":
            rp, deg = next(ramps), math.degrees(k.slope or 0.0)
            what = (
                f"rise {k.rise:.3f} m over {rp.length:.2f} m, slope {deg:.2f} deg "
                f"({100 * math.tan(k.slope or 0.0):.1f} %), {rp.width:.2f} m wide, plane rms "
                f"{1000 * rp.rms:.1f} mm"
            )
        else:
            r, g = k.risers[0], k.tread or 0.0
            what = f"{len(k.risers)} risers x {r:.3f} m, tread {g:.3f} m (2h+g {2 * r + g:.3f} m)"
        lines.append(f"  {k.kind:<5} L{k.lower} -> L{k.upper}  {what}")
    return "\n".join(lines)
