"""A stair tread no scanner saw: inferred from its flight's regular rise and run (issue 47).

A tall flight's top tread lies under the edge of the level above: a scanner below sees little of
it over the treads' nosings, one on the level above not at all over its edge (a generated hall's
seven 0.188 m risers: 0.10 of its 0.27 m seen). Such a region is shallower than even a tread
seen in part (``scanlevels.SHADOWED_DEPTH``) and is no region; the treads below it then end one
tread short of a level two risers higher, and neither the flight nor the level is found.

Stairs are built regular (DIN 18065 allows ``norms.STAIR_TOLERANCE`` between any two risers or
treads of a flight), so the missing treads are where the flight puts them. A chain from a level
up over at least two single treads whose last tread has no step up (:func:`hidden_treads`) gets
``n`` treads (fewer than it has: the flight is seen more than it is inferred), each a riser
above the one before from the last tread's height by the chain's riser and one fitted tread
depth further (a least-squares line through the treads' front edges: a tread's back may be in
a shadow, its front is not), across the treads' width, when:

- a region lies ``n + 1`` risers above the last tread (within :data:`~mjwalk.scan.stairfit.
  HEIGHT_TOL`) and its first cells within the flight's width lie where the flight puts the next
  riser (within ``STAIR_TOLERANCE`` and :data:`~mjwalk.scan.stairfit.EDGE_CELLS` cells): the
  flight is pinned at both ends, the treads between follow from its regularity;
- the chain is a regular flight of treads itself (heights within ``HEIGHT_TOL`` of the chain's
  riser, front edges within the edge tolerance of the line, riser and tread in the norms);
- nothing stands on an inferred tread (its cells inside its rim have fewer than
  ``MIN_BAND_POINTS`` points in its obstacle band, as a region's cells must) and no other region
  lies inside it.

Each inferred tread is one more region; the flight is then fitted and checked as any other
(:func:`mjwalk.scan.stairfit.fit_stair`). Metres, scene frame (floor at z = 0).
"""

from __future__ import annotations

from collections import defaultdict

import numpy as np
from scipy import ndimage

from mjwalk.scan.obstacles import MIN_BAND_POINTS, FloorPlan
from mjwalk.scan.planefit import RISER_TOL
from mjwalk.scan.scanlevels import Layers, ScanLevel, rasterize_layers
from mjwalk.scan.stairfit import (
    EDGE_CELLS,
    HEIGHT_TOL,
    axis_near,
    cell_centres,
    cell_span,
    near_edge,
    tread_rect,
)
from mjwalk.world.norms import MAX_RISER, MAX_TREAD, MIN_RISER, MIN_TREAD, STAIR_TOLERANCE


def hidden_treads(
    found: list[ScanLevel],
    steps: list[tuple[int, int]],
    levelled: np.ndarray,
    plan: FloorPlan,
    layers: Layers,
) -> tuple[list[ScanLevel], list[tuple[int, int]], Layers]:
    """The regions with each flight's hidden tread added, and the steps to and from it.

    Args:
        found: the regions (:func:`mjwalk.scan.scanlevels.find_regions`), the floor first.
        steps: (lower, upper) pairs of regions a step apart.
        levelled: (N, 3) points, metres, floor at z = 0.
        plan: the floor plan (its grid).
        layers: the rasterised layers the regions were found at.

    Returns:
        ``found`` with the inferred treads appended (their ``peak`` a new layer at their height),
        ``steps`` with (last tread, inferred) and (inferred, level above) appended, and the layers
        with one layer per inferred tread appended.
    """
    up: dict[int, list[int]] = defaultdict(list)
    for i, j in steps:
        up[i].append(j)
    out, pairs = list(found), list(steps)
    for chain in _open_chains(found, up):
        guess = _hidden_tread(chain, found, levelled, plan)
        if guess is None:
            continue
        hidden, tread, width, top = guess
        below = chain[-1]
        for cells, height in hidden:
            more = rasterize_layers(levelled, np.array([height]), plan)
            layers = Layers(
                np.append(layers.heights, height),
                np.concatenate([layers.near, more.near[1:]]),
                np.concatenate([layers.band, more.band[1:]]),
                np.concatenate([layers.top, more.top[1:]]),
                layers.lowest,
            )
            area = float(cells.sum()) * plan.resolution**2
            k = len(layers.heights) - 1
            out.append(ScanLevel(0, "tread", height, 0.0, 0.0, cells, area, tread, width, k))
            pairs.append((below, len(out) - 1))
            below = len(out) - 1
        pairs.append((below, top))
    return out, pairs, layers


def _open_chains(found: list[ScanLevel], up: dict[int, list[int]]) -> list[list[int]]:
    """Chains from a region that is no tread up over single treads (at least two) whose last
    tread has no step up: [bottom, tread, ..., tread]."""
    out = []
    for i, a in enumerate(found):
        if a.kind == "tread":
            continue
        for j in up.get(i, []):
            if found[j].kind != "tread":
                continue
            chain = [i, j]
            while len(nxt := up.get(chain[-1], [])) == 1 and found[nxt[0]].kind == "tread":
                if nxt[0] in chain:
                    break
                chain.append(nxt[0])
            if not up.get(chain[-1]) and len(chain) >= 3:
                out.append(chain)
    return out


def _hidden_tread(
    chain: list[int], found: list[ScanLevel], levelled: np.ndarray, plan: FloorPlan
) -> tuple[list[tuple[np.ndarray, float]], float, float, int] | None:
    """The treads a chain's flight puts after its last tread, where a region ``n + 1`` risers
    higher begins ``n`` treads further (``n`` less than the chain's treads): ((cells, height)
    per tread, the tread depth, the width, that region's index), or None."""
    res = plan.resolution
    bottom, treads = found[chain[0]], [found[i] for i in chain[1:]]
    m = len(treads)
    riser = (treads[-1].height - bottom.height) / m
    if not MIN_RISER - RISER_TOL <= riser <= MAX_RISER + RISER_TOL:
        return None
    if any(
        abs(t.height - bottom.height - (k + 1) * riser) > HEIGHT_TOL for k, t in enumerate(treads)
    ):
        return None
    mids = [cell_centres(t.cells, plan).mean(axis=0) for t in treads]
    run = axis_near(tread_rect(treads[-1], plan), mids[-1] - mids[0])
    side = np.array([-run[1], run[0]])
    fronts, lefts, rights = [], [], []
    for t in treads:
        c = cell_centres(t.cells, plan)
        fronts.append(float((c @ run).min()))
        lefts.append(float((c @ side).min()))
        rights.append(float((c @ side).max()))
    k = np.arange(m, dtype=float)
    a = np.column_stack([np.ones(m), k])
    (first, tread), *_ = np.linalg.lstsq(a, np.array(fronts), rcond=None)
    tol = STAIR_TOLERANCE + EDGE_CELLS * cell_span(run, res)  # cells measured along the climb
    if np.abs(a @ np.array([first, tread]) - fronts).max() > tol:
        return None
    if not MIN_TREAD - tol <= tread <= MAX_TREAD + tol:
        return None
    span = (float(np.median(lefts)), float(np.median(rights)))
    last, start = treads[-1].height, first + m * tread
    for n in range(1, m):  # hidden treads, fewer than those seen
        tops = [
            i for i, lv in enumerate(found)
            if abs(lv.height - last - (n + 1) * riser) <= HEIGHT_TOL
            and abs(near_edge(lv, plan, run, side, span, start) - (start + n * tread)) <= tol
        ]  # fmt: skip
        if tops:
            break
    else:
        return None
    out = []
    for q in range(n):
        height, s0 = last + (q + 1) * riser, start + q * tread
        cells = _strip(plan, run, side, (s0, s0 + tread), span)
        inner = ndimage.binary_erosion(cells, np.ones((3, 3), bool), iterations=EDGE_CELLS)
        band = rasterize_layers(levelled, np.array([height]), plan).band[1]
        if (band[inner] >= MIN_BAND_POINTS).any() or any(
            (r.cells & inner).any() for r in found[1:]
        ):
            return None
        out.append((cells, height))
    return out, float(tread), span[1] - span[0], tops[0]


def _strip(
    plan: FloorPlan, run: np.ndarray, side: np.ndarray, along: tuple[float, float], span
) -> np.ndarray:
    """The grid cells whose centres lie ``along`` (from, to) ``run`` (from each edge's cell
    centre: the cell centres of a region start half a cell inside its edge) and within ``span``
    across ``side``, metres."""
    ny, nx = plan.floor.shape
    r = plan.resolution
    gx, gy = np.meshgrid(plan.x0 + (np.arange(nx) + 0.5) * r, plan.y0 + (np.arange(ny) + 0.5) * r)
    u = gx * run[0] + gy * run[1]
    v = gx * side[0] + gy * side[1]
    return (u >= along[0] - 1e-9) & (u < along[1] - 1e-9) & (v >= span[0]) & (v <= span[1])
