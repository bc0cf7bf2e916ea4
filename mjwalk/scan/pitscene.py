"""A scan's pits that a stair reaches, written as levels below the floor (issue 47).

A MuJoCo plane has no hole, so a scene with a reached pit (:class:`~mjwalk.scan.scanpits.ScanPit`
of kind "level") is written as a floor with openings (:mod:`mjwalk.world.floorholes`): the floor
plane at the deepest reached pit's bottom, the floor level as boxes named
:data:`~mjwalk.world.floorholes.FLOOR_BOX_PREFIX`... from the plane up to z = 0 over every cell of
the floor plan but the openings (boxes of one extent that meet joined into one, so a flight's
top riser meets one floor box along its width), each reached pit's stair as its regular flight
(:func:`mjwalk.scan.stairfit.fit_stair`: its treads' boxes from the plane up, the floor's edge
moved onto the flight's last riser when the flight runs along x or y; a flight turned off the
axes gets a floor box turned to it at its top, :func:`_landing`), a pit's ramp as its tilted
box (:func:`mjwalk.scan.scanramps.ramp_box`) with a floor box along its top end one least tread
(``norms.MIN_TREAD``) deep, and a shallower pit's
bottom as a box. A gap nothing reaches stays a guard-rail box
(:func:`mjwalk.scan.scanpits.gap_boxes`). A scan without a reached pit is written as before.
Metres, scene frame (floor at z = 0).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace

import numpy as np
from scipy import ndimage

from mjwalk.scan.levelboxes import LEVEL_MATERIAL
from mjwalk.scan.obstacles import FloorPlan, rectangles
from mjwalk.scan.scanpits import ScanPit, gap_boxes
from mjwalk.scan.scanramps import ramp_box
from mjwalk.scan.stairfit import fit_stair
from mjwalk.world.floorholes import FLOOR_BOX_PREFIX
from mjwalk.world.norms import MIN_TREAD

#: Material of the floor boxes round the openings (the floor plane's).
FLOOR_MATERIAL = "floor"
#: A flight runs along an axis when its direction is within this of it, radians (1 deg): the
#: floor's edge is then moved onto its last riser, so the top tread keeps the flight's depth.
AXIS_TOL = math.radians(1.0)


@dataclass(frozen=True)
class PitFloor:
    """The scene's floor when a stair reaches a pit.

    Attributes:
        plane_z: the floor plane's height, the deepest reached pit's bottom, metres (negative).
        boxes: (name, centre (3,), half sizes (3,), material[, yaw radians]) per box: the floor
            boxes, the treads and the shallower bottoms, then the guard-rail boxes of the gaps
            nothing reaches.
        reached: the reached pits.
    """

    plane_z: float
    boxes: list
    reached: tuple[ScanPit, ...]

    def heights_at(self, xy: np.ndarray, plan: FloorPlan) -> list[float]:
        """The bottom heights of the reached pits a point lies in.

        Args:
            xy: scene (x, y), metres.
            plan: the floor plan (its grid).

        Returns:
            Heights, metres (empty when the point is in no reached pit).
        """
        ix = int(np.floor((xy[0] - plan.x0) / plan.resolution))
        iy = int(np.floor((xy[1] - plan.y0) / plan.resolution))
        out = []
        for p in self.reached:
            ny, nx = p.cells.shape
            assert p.bottom is not None
            if 0 <= ix < nx and 0 <= iy < ny and p.cells[iy, ix] and p.bottom.cells[iy, ix]:
                out.append(float(p.bottom.height))
        return out


def _box(name: str, lo, hi, material: str, yaw: float = 0.0) -> tuple:
    lo, hi = np.asarray(lo, dtype=float), np.asarray(hi, dtype=float)
    return (name, 0.5 * (lo + hi), 0.5 * (hi - lo), material, yaw)


def _flight(pit: ScanPit, plan: FloorPlan, plane_z: float, k0: int) -> tuple[list, dict | None]:
    """A reached pit's tread boxes (named ``scan_pit_tread_<k>``) and its stair fit (None when
    its link is steps: each step's region written as its rectangles)."""
    link = pit.link
    assert link is not None
    levels = list(pit.levels)
    chain = [link.lower, *link.via, link.upper]
    fit = fit_stair(chain, levels, plan) if link.kind == "stair" else None
    out: list = []
    if fit is not None:
        run = fit["run"]
        yaw = float(math.atan2(run[1], run[0]))
        for rect, h in zip(fit["rects"], fit["heights"], strict=True):
            c = rect.mean(axis=0)
            along = float(np.ptp(rect @ run))
            across = float(np.ptp(rect @ np.array([-run[1], run[0]])))
            half = np.array([along / 2, across / 2, (h - plane_z) / 2])
            pos = np.array([c[0], c[1], (h + plane_z) / 2])
            out.append((f"scan_pit_tread_{k0 + len(out)}", pos, half, LEVEL_MATERIAL, yaw))
        return out, fit
    r = plan.resolution
    for i in link.via:
        h = levels[i].height
        for iy0, iy1, ix0, ix1, _ in rectangles(levels[i].cells.astype(np.int32)):
            lo = (plan.x0 + ix0 * r, plan.y0 + iy0 * r, plane_z)
            hi = (plan.x0 + ix1 * r, plan.y0 + iy1 * r, h)
            out.append(_box(f"scan_pit_tread_{k0 + len(out)}", lo, hi, LEVEL_MATERIAL))
    return out, None


def _snap(lo: np.ndarray, hi: np.ndarray, fits: list[dict], res: float) -> None:
    """Move a floor box's face lying within 1.5 cells of a flight's last riser onto it (a flight
    along x or y), in place."""
    for fit in fits:
        run = fit["run"]
        for ax in (0, 1):
            if abs(run[ax]) < math.cos(AXIS_TOL):
                continue
            at = float(fit["top_edge"] * run[ax])  # the riser's line: coordinate ax
            for face in (lo, hi):
                if abs(face[ax] - at) <= 1.5 * res:
                    face[ax] = at


def _joined(faces: list[tuple[np.ndarray, np.ndarray]]) -> list[tuple[np.ndarray, np.ndarray]]:
    """Floor boxes (low, high corners) joined while two have the same extent across one axis and
    meet along it: the strips a cell-stepped pit edge cuts the floor into, once snapped onto a
    flight's last riser, become one box along it, so the top tread meets one floor box along
    its width (the world's contacts need a body's width of edge between two surfaces,
    :data:`mjwalk.world.contacts.MIN_CROSSING`: a scanned pit's stair in strips of 6-34 cm
    reached nothing, generated hall 1057). Boxes that meet nothing are kept as they are."""
    out = [(lo.copy(), hi.copy()) for lo, hi in faces]
    joined = True
    while joined:
        joined = False
        for i, (lo, hi) in enumerate(out):
            for j, (lo2, hi2) in enumerate(out):
                ax = next(
                    (a for a in (0, 1) if lo[1 - a] == lo2[1 - a] and hi[1 - a] == hi2[1 - a]),
                    None,
                )
                if i != j and ax is not None and hi[ax] == lo2[ax]:
                    hi[ax] = hi2[ax]
                    del out[j]
                    joined = True
                    break
            if joined:
                break
    return out


def _along_axis(run: np.ndarray) -> bool:
    """Whether a flight's climb direction lies within :data:`AXIS_TOL` of x or y."""
    return max(abs(float(run[0])), abs(float(run[1]))) >= math.cos(AXIS_TOL)


def _in_rects(plan: FloorPlan, rects: list[np.ndarray]) -> np.ndarray:
    """(ny, nx) bool: the plan's cells whose centres lie in any of the rectangles (4, 2)."""
    ny, nx = plan.floor.shape
    r = plan.resolution
    gx, gy = plan.x0 + (np.arange(nx) + 0.5) * r, plan.y0 + (np.arange(ny) + 0.5) * r
    xy = np.stack(np.meshgrid(gx, gy), axis=-1)
    out = np.zeros((ny, nx), bool)
    for rect in rects:
        e1, e2 = rect[1] - rect[0], rect[3] - rect[0]
        u, v = (xy - rect[0]) @ e1, (xy - rect[0]) @ e2
        out |= (u >= 0) & (u <= e1 @ e1) & (v >= 0) & (v <= e2 @ e2)
    return out


def _landing(fit: dict, plane_z: float, name: str) -> tuple:
    """The floor box at the top of a flight that runs along neither axis: as wide as its
    treads, one tread deep beyond its last riser, turned to the flight, from the plane up to the
    floor. The floor's boxes over the grid's cells meet that riser only in a staircase of cells;
    this box gives the top tread one straight edge to meet along its width (a stair's link needs
    a crossing a body wide, :data:`mjwalk.world.contacts.MIN_CROSSING`)."""
    run, rect = fit["run"], fit["rects"][-1]
    side = np.array([-run[1], run[0]])
    w0, w1 = float(rect[0] @ side), float(rect[2] @ side)
    s0 = float(fit["top_edge"])
    return _top_box(run, (s0, s0 + float(fit["tread"])), (w0, w1), plane_z, name)


def _top_box(run: np.ndarray, s: tuple, w: tuple, plane_z: float, name: str) -> tuple:
    """A floor box turned to ``run`` over [s0, s1] along it and [w0, w1] across it (metres),
    from the plane up to the floor."""
    side = np.array([-run[1], run[0]])
    (s0, s1), (w0, w1) = s, w
    c = 0.5 * (s0 + s1) * run + 0.5 * (w0 + w1) * side
    centre = np.array([c[0], c[1], 0.5 * plane_z])
    half = np.array([0.5 * (s1 - s0), 0.5 * abs(w1 - w0), -0.5 * plane_z])
    return (name, centre, half, FLOOR_MATERIAL, float(math.atan2(run[1], run[0])))


def pit_floor(plan: FloorPlan, pits: list[ScanPit]) -> PitFloor | None:
    """The floor of a scan with reached pits (module docstring), or None without one.

    Args:
        plan: the floor plan (its grid, bounds and gaps).
        pits: the scan's pits (:func:`mjwalk.scan.scanpits.find_pits`).

    Returns:
        The plane's height and the boxes; None when no pit is reached (the scene is written as
        before).
    """
    reached = tuple(p for p in pits if p.kind == "level" and p.bottom is not None)
    if not reached:
        return None
    plane_z = min(float(p.bottom.height) for p in reached if p.bottom is not None)
    r = plan.resolution
    opening = np.zeros(plan.floor.shape, bool)
    boxes: list = []
    fits = []
    for p in reached:
        assert p.bottom is not None
        cells = ndimage.binary_closing(p.cells, np.ones((3, 3), bool), iterations=2) | p.cells
        opening |= cells
        treads, fit = _flight(p, plan, plane_z, len(boxes))
        boxes += treads
        fits += [fit] if fit is not None else []
        if fit is not None and not _along_axis(fit["run"]):  # no floor box over its treads
            opening |= _in_rects(plan, fit["rects"])
        if p.ramp is not None:  # a ramp down to it: its box, no floor box over it
            boxes.append(ramp_box(p.ramp, f"scan_pit_ramp_{len(boxes)}"))
            opening |= _in_rects(plan, [p.ramp.rect])
        if p.bottom.height > plane_z + 1e-6:  # a shallower pit: its bottom as a box
            for iy0, iy1, ix0, ix1, _ in rectangles(cells.astype(np.int32)):
                lo = (plan.x0 + ix0 * r, plan.y0 + iy0 * r, plane_z)
                hi = (plan.x0 + ix1 * r, plan.y0 + iy1 * r, p.bottom.height)
                boxes.append(_box(f"scan_pit_bottom_{len(boxes)}", lo, hi, LEVEL_MATERIAL))
    faces: list[tuple[np.ndarray, np.ndarray]] = []
    for iy0, iy1, ix0, ix1, _ in rectangles((~opening).astype(np.int32)):
        low = np.array([plan.x0 + ix0 * r, plan.y0 + iy0 * r, plane_z])
        high = np.array([plan.x0 + ix1 * r, plan.y0 + iy1 * r, 0.0])
        _snap(low, high, fits, r)
        if np.any(high[:2] <= low[:2]):  # a strip wholly within the snap of a riser: empty now
            continue
        faces.append((low, high))
    floor = [
        _box(f"{FLOOR_BOX_PREFIX}{k}", low, high, FLOOR_MATERIAL)
        for k, (low, high) in enumerate(_joined(faces))
    ]
    for fit in fits:
        if not _along_axis(fit["run"]):
            floor.append(_landing(fit, plane_z, f"{FLOOR_BOX_PREFIX}{len(floor)}"))
    for p in reached:  # the floor at a ramp's top: one straight edge along its width
        if p.ramp is not None:
            rp = p.ramp
            s = (rp.s_hi, rp.s_hi + MIN_TREAD)
            floor.append(
                _top_box(rp.run, s, (rp.w_lo, rp.w_hi), plane_z, f"{FLOOR_BOX_PREFIX}{len(floor)}")
            )
    gaps = plan.gaps & ~opening if plan.gaps is not None else None
    guards = gap_boxes(replace(plan, gaps=gaps))
    return PitFloor(plane_z, floor + boxes + guards, reached)
