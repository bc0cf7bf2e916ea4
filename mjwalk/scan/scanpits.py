"""Pits and gaps of a levelled scan: where the floor is missing (issue 47).

The floor plan (:mod:`mjwalk.scan.obstacles`) keeps, as its ``gaps``, the unscanned regions of
the floor that hold or border points lower than the obstacle band's foot below the floor and
can hold a foot. Each connected gap is one :class:`ScanPit`:

- its **bottom**: the largest horizontal walk-surface region below the floor inside it, found
  as the raised levels are (:func:`mjwalk.scan.scanlevels.candidate_heights` over the heights
  below the floor, :func:`~mjwalk.scan.scanlevels.regions_at`), or none when no ray reached a
  bottom (an open shaft, a trench seen only at its far wall);
- its **link**: the bottom is reached from the floor when a chain of such regions joins them by
  risers of at most ``norms.MAX_RISER`` along touching edges (as the raised levels); a chain of
  at least ``norms.MIN_STAIR_RISERS`` risers over treads that fits a regular flight
  (:func:`mjwalk.scan.stairfit.fit_stair`) is a stair (a riser measured within
  ``planefit.RISER_TOL`` over ``MAX_RISER`` written at it, :func:`within_norm`). Such a pit is a
  level of the scan (its
  bottom's height below the floor, printed with its link); one that nothing reaches, and a gap
  with no bottom, is an obstacle: a hole nobody may walk into.

The scene (:func:`gap_boxes`) writes every gap nothing reaches as a box from the floor up to a
guard rail's height (:data:`GUARD_HEIGHT`): an obstacle the planners see. A pit that is a level is
written as a level below the floor with its stair (:mod:`mjwalk.scan.pitscene`: the floor plane
at its bottom, the floor as boxes round the opening). A pit no step reaches is looked at for a
ramp down to its bottom (:func:`mjwalk.scan.scanramps.find_ramps` below the floor): a bottom a
ramp runs down to is found where most of each cell's points lie at its height
(:func:`_flat_layer`), and the ramp is its link.
Metres, scene frame (floor at z = 0).
"""

from __future__ import annotations

import dataclasses
import itertools
import math
from dataclasses import dataclass

import numpy as np
from scipy import ndimage

from mjwalk.scan.level import MAX_SURFACE_HEIGHT
from mjwalk.scan.obstacles import FLOOR_TOL, FloorPlan, rectangles
from mjwalk.scan.planefit import RISER_TOL, flat_cells
from mjwalk.scan.regionsteps import touching
from mjwalk.scan.scanlevels import (
    PEAK_SEPARATION,
    ScanLevel,
    ScanLink,
    candidate_heights,
    keep_reachable,
    min_rectangle,
    rasterize_layers,
    rectangle_size,
    regions_at,
)
from mjwalk.scan.scanramps import ScanRamp, find_ramps, renumber
from mjwalk.scan.stairfit import fit_stair, written_riser
from mjwalk.world.norms import MAX_RISER, MAX_TREAD, MIN_STAIR_RISERS

#: Height of the box a gap is written as, metres: the least height of a guard rail round an
#: opening, 1.1 m (EN ISO 14122-3:2016, 7.2.1); any height in the obstacle band makes it an
#: obstacle to the planners.
GUARD_HEIGHT = 1.1
#: Material of the gap boxes.
PIT_MATERIAL = "scan_pit"


@dataclass(frozen=True)
class ScanPit:
    """A gap in the floor of a scan.

    Attributes:
        cells: (ny, nx) bool, its cells on the floor plan's grid.
        area: the cells' area, square metres.
        centre: (x, y) of its cells' centroid, metres.
        size: (depth, width) of its cells' minimum-area rectangle, metres.
        lowest: the lowest point in or at it, metres (negative: below the floor).
        bottom: the walk surface at its bottom (height negative), None when none was scanned.
        link: how the floor reaches the bottom (``lower``: the bottom's index in ``levels``,
            ``upper``: 0, the floor), None when nothing reaches it.
        levels: the scan's levels below the floor that the floor reaches, the floor first,
            then by height; ``link`` indexes them (empty without a link).
        ramp: the ramp down to the bottom when ``link`` is one (its levels indexing
            ``levels``), else None.
    """

    cells: np.ndarray
    area: float
    centre: tuple[float, float]
    size: tuple[float, float]
    lowest: float
    bottom: ScanLevel | None
    link: ScanLink | None
    levels: tuple[ScanLevel, ...] = ()
    ramp: ScanRamp | None = None

    @property
    def kind(self) -> str:
        """ "level" (a link reaches its bottom), "pit" (a bottom nothing reaches) or "gap" (no
        bottom scanned)."""
        if self.link is not None:
            return "level"
        return "gap" if self.bottom is None else "pit"


def pit_regions(levelled: np.ndarray, plan: FloorPlan) -> tuple[list[ScanLevel], list]:
    """The horizontal walk-surface regions below the floor that lie in the plan's gaps.

    Args:
        levelled: (N, 3) points, metres, floor at z = 0.
        plan: its floor plan (with ``gaps``).

    Returns:
        The regions (the floor first, ``index`` not yet set) and the steps between them as
        (lower, upper) index pairs (a riser of at most ``norms.MAX_RISER``, measured: within
        ``planefit.RISER_TOL`` of it, along touching edges).
    """
    res = plan.resolution
    gaps = plan.gaps if plan.gaps is not None else np.zeros_like(plan.floor)
    a_floor = float(plan.floor.sum()) * res * res
    found = [ScanLevel(0, "floor", 0.0, 0.0, 0.0, plan.floor, a_floor, 0.0, 0.0, -1)]
    heights = candidate_heights(levelled, (-MAX_SURFACE_HEIGHT, -PEAK_SEPARATION))
    if len(heights):
        layers = rasterize_layers(levelled, heights, plan)
        for k in range(1, len(layers.heights)):
            for cells, (h, rms, slope, _) in _regions(levelled, layers, k, plan, gaps):
                depth, width = rectangle_size(min_rectangle(cells, plan.x0, plan.y0, res))
                kind = "tread" if depth <= MAX_TREAD + res else "platform"
                area = float(cells.sum()) * res * res
                level = ScanLevel(0, kind, h, rms, math.atan(slope), cells, area, depth, width, k)
                found.append(level)
    steps = [
        (i, j)
        for i, a in enumerate(found)
        for j, b in enumerate(found)
        if 0 < b.height - a.height <= MAX_RISER + RISER_TOL and touching(a.cells, b.cells, res)
    ]
    return found, steps


def _regions(levelled: np.ndarray, layers, k: int, plan: FloorPlan, gaps: np.ndarray) -> list:
    """The regions at candidate ``k`` (:func:`~mjwalk.scan.scanlevels.regions_at`) that lie in
    the gaps; when none does, those of :func:`_flat_layer` (a bottom a ramp runs down to)."""
    inside = [
        r for r in regions_at(levelled, layers, k, plan) if 2 * (r[0] & gaps).sum() >= r[0].sum()
    ]
    if inside:
        return inside
    flat = _flat_layer(levelled, layers, k, plan)
    return [r for r in regions_at(levelled, flat, k, plan) if 2 * (r[0] & gaps).sum() >= r[0].sum()]


def _flat_layer(levelled: np.ndarray, layers, k: int, plan: FloorPlan):
    """``layers`` with candidate ``k``'s cells kept only where its points lie flat
    (:func:`mjwalk.scan.planefit.flat_cells`): a ramp running down to a pit's bottom crosses
    the candidate's band over some 0.2-0.3 m, enough to tilt the bottom's plane fit past a
    level's slope; its cells leave."""
    h0 = float(layers.heights[k])
    p = levelled[np.abs(levelled[:, 2] - h0) <= FLOOR_TOL]
    near = layers.near.copy()
    if len(p):
        near[k] = np.where(flat_cells(p, plan, h0), near[k], 0)
    return dataclasses.replace(layers, near=near)


def _ramp_link(
    bottom: int, found: list[ScanLevel], steps: list, ramps: list[ScanRamp]
) -> tuple[ScanLink, tuple[ScanLevel, ...], ScanRamp] | None:
    """The ramp from the floor down to region ``bottom`` (of ``found``), its link and levels
    (:func:`~mjwalk.scan.scanlevels.keep_reachable` with it), or None when no ramp joins them."""
    for r in ramps:
        if (r.lower, r.upper) == (bottom, 0):
            levels, _, new = keep_reachable(found, steps, [(r.lower, r.upper)])
            ramp = renumber(r, new)
            link = ScanLink("ramp", new[bottom], 0, (), slope=ramp.slope, run=ramp.length)
            return link, tuple(levels), ramp
    return None


def _link(bottom: int, levels: list[ScanLevel], pairs: list, plan: FloorPlan) -> ScanLink | None:
    """The link from the floor down to level ``bottom``: its single chain up to the floor, a
    stair when it fits a regular flight, steps otherwise; None when no single chain leads up."""
    up: dict[int, list[int]] = {}
    for i, j in pairs:
        up.setdefault(i, []).append(j)
    chain = [bottom]
    while chain[-1] != 0:
        nxt = [k for k in up.get(chain[-1], []) if k not in chain]
        if not nxt:
            return None
        chain.append(0 if 0 in nxt else max(nxt, key=lambda k: levels[k].height))
    risers = tuple(levels[b].height - levels[a].height for a, b in itertools.pairwise(chain))
    via = tuple(chain[1:-1])
    if len(risers) >= MIN_STAIR_RISERS and all(levels[i].kind == "tread" for i in via):
        fit = fit_stair(chain, levels, plan)
        if fit is not None:
            n = len(risers)
            return ScanLink("stair", bottom, 0, (fit["riser"],) * n, fit["tread"], via)
    return ScanLink("step", bottom, 0, risers, via=via)


def within_norm(
    link: ScanLink, levels: tuple[ScanLevel, ...]
) -> tuple[ScanLink, tuple[ScanLevel, ...]]:
    """A stair down from the floor whose riser was measured within ``planefit.RISER_TOL``
    outside the norm's range (``norms.MIN_RISER``-``MAX_RISER``), at the range's limit: the scan
    cannot tell the two apart, and the written scene's level graph (exact at the norm) links
    only the one within it. The limit is taken ``stairfit.WRITE_MARGIN`` inside, as a fitted
    tread is, so the written boxes' rounding cannot take the riser back over it (generated
    hall 108: a riser set to 0.19 m read 0.19001 m in the written scene, no link). Its treads
    and bottom move to that riser's multiples below the floor (by at most the riser count
    times ``RISER_TOL`` + ``WRITE_MARGIN``). A riser measured within ``WRITE_MARGIN`` inside a
    limit moves to the same place.

    Args:
        link: the stair (``upper`` the floor, ``via`` its treads, bottom up).
        levels: the levels ``link`` indexes.

    Returns:
        The link and the levels, unchanged when its riser is within the norm's range.
    """
    riser = written_riser(link.risers[0])
    if riser == link.risers[0]:
        return link, levels
    chain = [link.lower, *link.via]
    n = len(link.risers)
    out = list(levels)
    for k, i in enumerate(chain):
        out[i] = dataclasses.replace(levels[i], height=-(n - k) * riser)
    return dataclasses.replace(link, risers=(riser,) * n), tuple(out)


def find_pits(levelled: np.ndarray, plan: FloorPlan) -> list[ScanPit]:
    """The gaps of a floor plan, each with its bottom and how the floor reaches it.

    Args:
        levelled: (N, 3) points, metres, floor at z = 0.
        plan: its floor plan (:func:`mjwalk.scan.obstacles.floor_plan`).

    Returns:
        One pit per connected gap, largest first; none when the plan has no gaps.
    """
    if plan.gaps is None or not plan.gaps.any():
        return []
    found, steps = pit_regions(levelled, plan)
    levels, pairs, new = keep_reachable(found, steps)
    res = plan.resolution
    lab, n = ndimage.label(plan.gaps, np.ones((3, 3), bool))
    low = plan.drop if plan.drop is not None else np.zeros(plan.gaps.shape)
    out = []
    ramps: list[ScanRamp] | None = None
    for r in range(1, n + 1):
        cells = lab == r
        near = ndimage.binary_dilation(cells, np.ones((3, 3), bool), iterations=2)
        inside = [i for i in range(1, len(found)) if (found[i].cells & cells).any()]
        floors = [i for i in inside if found[i].kind == "platform"] or inside
        best = max(floors, key=lambda i: (found[i].cells & cells).sum(), default=None)
        link, pit_levels, ramp = None, tuple(levels), None
        if best is not None and best in new:
            link = _link(new[best], levels, pairs, plan)
            if link is not None and link.kind == "stair":
                link, pit_levels = within_norm(link, pit_levels)
        if best is not None and link is None:  # a ramp down to it (looked for once)
            ramps = find_ramps(levelled, plan, found, below=True) if ramps is None else ramps
            got = _ramp_link(best, found, steps, ramps)
            if got is not None:
                link, pit_levels, ramp = got
        iy, ix = np.nonzero(cells)
        centre = (plan.x0 + (ix.mean() + 0.5) * res, plan.y0 + (iy.mean() + 0.5) * res)
        size = rectangle_size(min_rectangle(cells, plan.x0, plan.y0, res))
        lowest = float(low[near].min(initial=0.0))
        bottom = None if best is None else found[best]
        if link is not None and link.kind == "stair":
            bottom = pit_levels[link.lower]
        out.append(
            ScanPit(
                cells, float(cells.sum()) * res * res, centre, size, lowest, bottom, link,
                pit_levels if link is not None else (), ramp,
            )
        )  # fmt: skip
    return sorted(out, key=lambda p: -p.area)


def gap_boxes(plan: FloorPlan) -> list[tuple[str, np.ndarray, np.ndarray, str]]:
    """The plan's gaps as boxes from the floor up to :data:`GUARD_HEIGHT`.

    Args:
        plan: the floor plan.

    Returns:
        (name ``scan_pit_<k>``, centre (3,), half sizes (3,), :data:`PIT_MATERIAL`) per box,
        metres; none without gaps.
    """
    if plan.gaps is None or not plan.gaps.any():
        return []
    r = plan.resolution
    out: list[tuple[str, np.ndarray, np.ndarray, str]] = []
    # the gap's ragged rim (floor points in some of its cells) closed: fewer, fuller boxes
    cells = ndimage.binary_closing(plan.gaps, np.ones((3, 3), bool), iterations=2) | plan.gaps
    for iy0, iy1, ix0, ix1, _ in rectangles(cells.astype(np.int32)):
        lo = np.array([plan.x0 + ix0 * r, plan.y0 + iy0 * r, 0.0])
        hi = np.array([plan.x0 + ix1 * r, plan.y0 + iy1 * r, GUARD_HEIGHT])
        out.append((f"scan_pit_{len(out)}", 0.5 * (lo + hi), 0.5 * (hi - lo), PIT_MATERIAL))
    return out


def describe_pits(pits: list[ScanPit], option: str = "--gaps floor") -> str:
    """The gaps of a scan, one line each (``mjwalk scan`` prints it).

    Args:
        pits: the pits (:func:`find_pits`).
        option: how the text names the choice that fills gaps as floor.

    Returns:
        The text, no trailing newline; empty without pits.
    """
    if not pits:
        return ""
    n_level = sum(p.kind == "level" for p in pits)
    levels = f"{n_level} written as levels below the floor, the rest " if n_level else ""
    lines = [
        f"gaps in the floor (unscanned, points below it): {len(pits)}, {levels}written as "
        f"obstacles ({GUARD_HEIGHT} m guard-rail boxes; {option} fills them as floor)"
    ]
    for k, p in enumerate(pits):
        where = (
            f"  gap {k + 1}: {p.area:.2f} m2 at ({p.centre[0]:.2f}, {p.centre[1]:.2f}), "
            f"{p.size[0]:.2f} x {p.size[1]:.2f} m, lowest point {p.lowest:+.2f} m: "
        )
        if p.bottom is None:
            lines.append(where + "no bottom scanned: obstacle")
            continue
        what = f"bottom {p.bottom.height:+.3f} m"
        if p.link is None:
            lines.append(where + f"pit, {what}, no step or stair reaches it: obstacle")
            continue
        k_ = p.link
        if k_.kind == "ramp" and p.ramp is not None:
            deg, pct = math.degrees(p.ramp.slope), 100 * math.tan(p.ramp.slope)
            how = (
                f"ramp {deg:.2f} deg ({pct:.1f} %), {p.ramp.length:.2f} m long, "
                f"{p.ramp.width:.2f} m wide"
            )
        elif k_.kind == "stair":
            how = f"stair {len(k_.risers)} risers x {k_.risers[0]:.3f} m, tread {k_.tread:.3f} m"
        else:
            how = (
                "step"
                + "s" * (len(k_.risers) > 1)
                + " "
                + " + ".join(f"{r:.3f}" for r in k_.risers)
                + " m"
            )
        lines.append(
            where + f"pit level, {what}, reached from the floor by {how} (a level of the scan; "
            f"written as a level below the floor with its {k_.kind}: mjwalk.scan.pitscene)"
        )
    return "\n".join(lines)
