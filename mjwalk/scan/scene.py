"""A scan becomes a plain MJCF scene: floor plane, obstacle and void boxes, named sites.

``scan_to_scene`` runs the whole pipeline: read (:mod:`.read`), find and level the floor
(:mod:`.level`), floor plan and boxes (:mod:`.obstacles`), then write the MJCF atomically after
MuJoCo has compiled it. The levelling transform is written into the scene twice: in its header
comment and as ``<custom><numeric name="mjwalk_scan_transform">``: the 16 numbers (row-major) of
the 4 x 4 matrix taking a point of the scan file (its units, its axes) to the scene (metres,
z up, floor at z = 0).

Sites TOML (``sites=``): one table per site under ``[site]``, in metres::

    [site.door]
    xy = [1.20, 0.40]        # scene x, y (the scan's x, y for a z-up scan in metres)
    yaw = 90                 # optional: the direction faced, degrees from +x, CCW

    [site.bench]
    scan = [3.1, 1.0, -1.2]  # or a point picked in the scan file (its units and axes)
"""

from __future__ import annotations

import dataclasses
import time
import tomllib
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field
from pathlib import Path

import mujoco
import numpy as np

from mjwalk._args import check_output_file
from mjwalk._io import atomic_path, read_toml
from mjwalk.errors import ScanError
from mjwalk.scan.level import BELOW_FLOOR, Levelling, check_upright, find_floor
from mjwalk.scan.levelboxes import LEVEL_MATERIAL, LevelPlan, levels_at, scan_levels
from mjwalk.scan.limits import check_plan_size
from mjwalk.scan.merge import merge_scans, read_poses
from mjwalk.scan.obstacles import FLOOR_TOL, FloorPlan, floor_plan, rectangles
from mjwalk.scan.pitscene import PitFloor, pit_floor
from mjwalk.scan.read import Station, to_metres_z_up
from mjwalk.scan.scanoptions import ScanOptions
from mjwalk.scan.scanpits import PIT_MATERIAL, ScanPit, describe_pits, find_pits, gap_boxes
from mjwalk.scan.scanramps import RAMP_MATERIAL
from mjwalk.scan.sight import View, check_station, ray_agreement
from mjwalk.scan.voids import apply_policy
from mjwalk.world.floor import OBSTACLE_Z_RANGE

#: Sites are written this far above the floor (a stand site on the floor, as in the shipped
#: scenes: ``mjwalk.render.plot`` draws sites below 0.05 m as stand positions).
SITE_Z = 0.0


@dataclass
class ScanScene:
    """The result of :func:`build_scene`: the MJCF text and what it was made from.

    ``matrix`` (4, 4) takes scan-file points to the scene; ``timings`` holds wall-clock seconds
    per stage; ``sight`` says how the floor seen was decided (by which stations' rays, or by
    floor points alone and why); ``levels`` the raised walk-surface levels written as boxes
    (:mod:`~mjwalk.scan.levelboxes`; None: one level, the floor); ``site_z`` each site's
    height, metres (the height of the level it stands on); ``pits`` the gaps in the floor
    (:mod:`~mjwalk.scan.scanpits`), written as guard-rail boxes, or as levels below the floor
    when a stair reaches them (:mod:`~mjwalk.scan.pitscene`).
    """

    xml: str
    plan: FloorPlan
    levelling: Levelling
    matrix: np.ndarray
    n_points: int
    n_obstacle_boxes: int
    n_void_boxes: int
    sites: dict[str, tuple[float, float, float]]
    timings: dict[str, float] = field(default_factory=dict)
    sight: str = ""
    levels: LevelPlan | None = None
    site_z: dict[str, float] = field(default_factory=dict)
    pits: list[ScanPit] = field(default_factory=list)


@dataclass(frozen=True)
class _Site:
    name: str
    xy: tuple[float, float] | None
    scan: tuple[float, float, float] | None
    yaw_deg: float


def read_sites(path: str | Path) -> list[_Site]:
    """Parse a sites TOML (format in the module docstring).

    Args:
        path: the TOML file.

    Returns:
        The sites, in file order.

    Raises:
        ScanError: a malformed file or site, naming the key.
    """
    path = Path(path)
    try:  # missing, oversized, non-UTF-8 or too deeply nested: ScanError naming the key
        doc, _ = read_toml(path, "sites", ScanError)
    except tomllib.TOMLDecodeError as exc:
        raise ScanError(f"{path}: not a valid TOML sites file: {exc}") from exc
    extra = set(doc) - {"site"}
    if extra:
        raise ScanError(f"{path}: unknown top-level key(s) {sorted(extra)} (expected [site.NAME])")
    out = []
    for name, spec in doc.get("site", {}).items():
        where = f"{path}: [site.{name}]"
        if not isinstance(spec, dict):
            raise ScanError(f"{where} must be a table with xy or scan")
        unknown = set(spec) - {"xy", "scan", "yaw"}
        if unknown:
            raise ScanError(f"{where}: unknown key(s) {sorted(unknown)} (xy, scan, yaw)")
        if ("xy" in spec) == ("scan" in spec):
            raise ScanError(f"{where} needs exactly one of xy = [x, y] or scan = [x, y, z]")
        key, n = ("xy", 2) if "xy" in spec else ("scan", 3)
        val = spec[key]
        if (
            not isinstance(val, list)
            or len(val) != n
            or not all(isinstance(v, int | float) and np.isfinite(v) for v in val)
        ):
            raise ScanError(f"{where}: {key} must be {n} finite numbers, got {val!r}")
        yaw = spec.get("yaw", 0.0)
        if not isinstance(yaw, int | float):
            raise ScanError(f"{where}: yaw must be a number of degrees, got {yaw!r}")
        xy = tuple(float(v) for v in val) if key == "xy" else None
        scan = tuple(float(v) for v in val) if key == "scan" else None
        out.append(_Site(str(name), xy, scan, float(yaw)))  # type: ignore[arg-type]
    return out


def _matrix(
    levelling: Levelling, scale: float, axes: np.ndarray, offset: np.ndarray | None = None
) -> np.ndarray:
    """Scan-file point -> scene: subtract ``offset`` (file units), scale, turn the up axis
    onto +z, level."""
    pre = np.eye(4)
    pre[:3, :3] = scale * axes
    if offset is not None:
        pre[:3, 3] = -(scale * axes) @ np.asarray(offset, dtype=np.float64)
    return levelling.matrix @ pre


def _fmt(v) -> str:
    return " ".join(f"{x:.10g}" for x in np.ravel(v))  # georeferenced x, y keep mm


def _mjcf(
    plan: FloorPlan,
    boxes: list[tuple],
    sites: dict[str, tuple[float, float, float]],
    header: str,
    matrix: np.ndarray,
    model_name: str,
    site_z: dict[str, float],
    plane_z: float = 0.0,
) -> str:
    xmin, ymin, xmax, ymax = plan.bounds
    cx, cy = 0.5 * (xmin + xmax), 0.5 * (ymin + ymax)
    hx, hy = 0.5 * (xmax - xmin), 0.5 * (ymax - ymin)
    lines = [
        "<!--",
        *[f"  {ln}" for ln in header.splitlines()],
        "-->",
        f'<mujoco model="{model_name}">',
        '  <visual><headlight ambient="0.45 0.45 0.45" diffuse="0.5 0.5 0.5"/></visual>',
        "  <custom>",
        f'    <numeric name="mjwalk_scan_transform" data="{_fmt(matrix)}"/>',
        "  </custom>",
        "  <asset>",
        '    <texture name="grid" type="2d" builtin="checker" rgb1="0.82 0.82 0.80" '
        'rgb2="0.74 0.74 0.72" width="300" height="300"/>',
        f'    <material name="floor" texture="grid" texrepeat="{max(1, round(2 * hx))} '
        f'{max(1, round(2 * hy))}"/>',
        '    <material name="scan_obstacle" rgba="0.62 0.58 0.52 1"/>',
        '    <material name="scan_void" rgba="0.55 0.25 0.25 0.25"/>',
        *(
            [f'    <material name="{LEVEL_MATERIAL}" rgba="0.50 0.58 0.50 1"/>']
            if any(b[3] == LEVEL_MATERIAL for b in boxes)
            else []
        ),
        *(
            [f'    <material name="{RAMP_MATERIAL}" rgba="0.56 0.62 0.48 1"/>']
            if any(b[3] == RAMP_MATERIAL for b in boxes)
            else []
        ),
        *(
            [f'    <material name="{PIT_MATERIAL}" rgba="0.85 0.55 0.10 0.6"/>']
            if any(b[3] == PIT_MATERIAL for b in boxes)
            else []
        ),
        "  </asset>",
        "  <worldbody>",
        f'    <light pos="{cx:.4f} {cy:.4f} 6" dir="0 0 -1"/>',
        f'    <geom name="floor" type="plane" pos="{cx:.4f} {cy:.4f} {_fmt([plane_z])}" '
        f'size="{hx:.4f} {hy:.4f} '
        '0.05" material="floor"/>',
    ]
    for box in boxes:  # (name, centre, half sizes, material[, yaw radians or xyaxes (6,)])
        name, pos, half, material = box[:4]
        turn = ""
        if len(box) > 4 and np.ndim(box[4]):  # a tilted box (a ramp)
            turn = f' xyaxes="{_fmt(np.round(box[4], 8))}"'
        elif len(box) > 4 and box[4]:
            turn = f' euler="0 0 {np.degrees(float(box[4])):.8g}"'
        group = ' group="3"' if material == "scan_void" else ""
        lines.append(
            f'    <geom name="{name}" type="box" pos="{_fmt(np.round(pos, 5))}" '
            f'size="{_fmt(np.round(half, 5))}" material="{material}"{group}{turn}/>'
        )
    for name, (x, y, yaw) in sites.items():
        z = site_z.get(name, SITE_Z)
        zs = f"{z:.4f}" if z != SITE_Z else f"{SITE_Z}"
        lines.append(
            f'    <site name="{name}" pos="{x:.4f} {y:.4f} {zs}" size="0.05" '
            f'euler="0 0 {np.degrees(yaw):.6g}"/>'  # MJCF angles are degrees by default
        )
    lines += ["  </worldbody>", "</mujoco>", ""]
    return "\n".join(lines)


def _boxes(plan: FloorPlan) -> tuple[list, int, int]:
    """Obstacle boxes, then void boxes. An obstacle's outermost cells hold its surface at an
    unknown place inside them, on average at their centre: each box side facing a cell that
    is not part of the same obstacle is moved in by half a cell (an unbiased outline)."""
    r = plan.resolution
    out: list = []
    lab_grid = np.pad(plan.obstacles, 1)
    for iy0, iy1, ix0, ix1, lab in rectangles(plan.obstacles):
        top = float(plan.tops[lab])
        inset = (
            0.5
            * r
            * np.array(
                [
                    True,  # left and right ends of row runs always face another label or none
                    True,
                    not (lab_grid[iy0, ix0 + 1 : ix1 + 1] == lab).any(),  # the row below
                    not (lab_grid[iy1 + 1, ix0 + 1 : ix1 + 1] == lab).any(),  # the row above
                ]
            )
        )
        lo = np.array([plan.x0 + ix0 * r + inset[0], plan.y0 + iy0 * r + inset[2]])
        hi = np.array([plan.x0 + ix1 * r - inset[1], plan.y0 + iy1 * r - inset[3]])
        mid = 0.5 * (lo + hi)
        lo, hi = np.minimum(lo, mid - 0.25 * r), np.maximum(hi, mid + 0.25 * r)  # >= r/2 wide
        pos = np.array([*(0.5 * (lo + hi)), 0.5 * top])
        out.append(
            (
                f"scan_obstacle_{len(out)}",
                pos,
                np.array([*(0.5 * (hi - lo)), 0.5 * top]),
                "scan_obstacle",
            )
        )
    n_obst = len(out)
    top = OBSTACLE_Z_RANGE[1]
    for iy0, iy1, ix0, ix1, _ in rectangles(plan.void.astype(np.int32)):
        lo = np.array([plan.x0 + ix0 * r, plan.y0 + iy0 * r])
        hi = np.array([plan.x0 + ix1 * r, plan.y0 + iy1 * r])
        pos = np.array([*(0.5 * (lo + hi)), 0.5 * top])
        out.append(
            (
                f"scan_void_{len(out) - n_obst}",
                pos,
                np.array([*(0.5 * (hi - lo)), 0.5 * top]),
                "scan_void",
            )
        )
    return out, n_obst, len(out) - n_obst


def _views(
    levelled: np.ndarray, stations: Sequence[Station], levelling: Levelling
) -> tuple[list[View], str]:
    """The stations the cloud agrees with (:func:`~mjwalk.scan.sight.check_station`) in
    the levelled frame, and one line saying how the floor seen is decided."""
    views, refused = [], []
    for k, st in enumerate(stations):
        vp = levelling.apply(np.asarray(st.viewpoint, dtype=np.float64)[None])[0]
        step, why = check_station(levelled[st.start : st.stop], vp, FLOOR_TOL)
        if why:
            refused.append(f"station {k + 1} ({st.origin}): {why}")
        else:
            views.append(View(vp, st.start, st.stop, step, st.origin))
    fallback = "by floor points alone (sparse floor far from a scanner may be void)"
    if not views:
        why = "; ".join(refused) if refused else "the scan states no scanner position"
        return views, f"floor seen decided {fallback}: {why}"
    origins = ", ".join(sorted({v.origin for v in views}))
    steps = ", ".join(f"{np.degrees(v.step):.2f}" for v in views)
    line = (
        f"floor seen decided by ray support from {len(views)} scanner position(s) ({origins}; "
        f"angular step {steps} deg)"
    )
    if refused:
        line += f"; not used: {'; '.join(refused)}"
    return views, line


def _scanners_if_low(
    levelled: np.ndarray, stations: Sequence[Station], levelling: Levelling
) -> np.ndarray:
    """(S, 3) the levelled positions of the stations whose returns agree they stood there
    (:func:`~mjwalk.scan.sight.ray_agreement`) when every station lies below the floor found
    (:func:`~mjwalk.scan.level.check_upright`; the rays are tested only then); else empty."""
    vps = [levelling.apply(np.asarray(st.viewpoint, dtype=np.float64)[None])[0] for st in stations]
    if not vps or max(vp[2] for vp in vps) >= -BELOW_FLOOR:
        return np.zeros((0, 3))
    ok = [
        vp
        for vp, st in zip(vps, stations, strict=True)
        if not ray_agreement(levelled[st.start : st.stop], vp)[1]
    ]
    return np.array(ok).reshape(-1, 3)


def build_scene(
    points: np.ndarray,
    options: ScanOptions | None = None,
    *,
    sites: list[_Site] | None = None,
    source: str = "cloud",
    model_name: str = "scan",
    stations: Sequence[Station] = (),
    _read: tuple[np.ndarray, float, np.ndarray] | None = None,
    clock: Callable[[], float] = time.perf_counter,
) -> ScanScene:
    """Make the MJCF scene of a point cloud.

    Everything is checked, and the MJCF compiled by MuJoCo, before anything is written.

    Args:
        points: (N, 3) points in the file's units and axes.
        options: units, up axis, invalid points, resolution, offset (file units, subtracted
            first) and unseen-floor policy (None: the defaults; ``register`` is not used here).
        sites: named sites to place (:func:`read_sites`); None: no sites.
        source: the cloud's name in errors and in the scene's header comment.
        model_name: the MJCF model's name.
        stations: where scanners stood and which rows of ``points`` each returned (viewpoints
            in the frame of ``points``); their rays decide which floor was seen
            (:mod:`~mjwalk.scan.sight`).
        _read: (points in metres z up, metres per file unit, (3, 3) up-axis rotation) when
            the points were already read and checked (:func:`scan_to_scene`); ``points`` and
            ``stations`` are then in metres, z up.
        clock: the wall clock the stage timings are taken with, seconds.

    Returns:
        The scene: MJCF text, floor plan, levelling, (4, 4) scan-to-scene matrix, counts,
        sites (x, y metres, yaw radians) and per-stage timings (seconds).

    Raises:
        ScanError: empty cloud, NaN points, stray points or coordinates beyond range,
            implausible units, a floor plan too large, no floor, an upside-down cloud, sites
            off the floor.
    """
    opts = ScanOptions() if options is None else options
    timings: dict[str, float] = {}
    t = clock()
    if _read is None:
        pts, scale, axes = to_metres_z_up(
            points,
            units=opts.units,
            up=opts.up,
            source=source,
            drop_invalid=opts.drop_invalid,
            offset=opts.offset,
        )
        timings["validate"] = clock() - t
        t = clock()
        stations = _file_stations(stations, len(pts) != len(points), scale, axes, opts.offset)
    else:
        pts, scale, axes = _read
    check_plan_size(pts, opts.resolution, source)
    levelling = find_floor(pts, source=source)
    timings["floor"] = clock() - t
    t = clock()
    levelled = levelling.apply(pts)
    check_upright(levelled, opts.up, source, _scanners_if_low(levelled, stations, levelling))
    timings["level"] = clock() - t
    t = clock()
    views, sight = _views(levelled, stations, levelling)
    timings["sight"] = clock() - t
    t = clock()
    gaps = opts.gaps == "obstacle"
    plan = floor_plan(levelled, resolution=opts.resolution, views=views, gaps=gaps)
    if plan is None or not plan.floor.any():
        raise ScanError(f"{source}: no floor found after levelling (no points at z = 0)")
    plan = apply_policy(plan, opts.voids)
    timings["floor plan"] = clock() - t
    t = clock()
    levels = scan_levels(levelled, plan)
    plan = plan if levels is None else levels.plan
    pits = find_pits(levelled, plan)
    below = pit_floor(plan, pits)
    timings["levels"] = clock() - t
    t = clock()
    offset = None if opts.offset is None else np.asarray(opts.offset)
    matrix = _matrix(levelling, scale, axes, offset)
    site_xyyaw, site_z = _place_sites(sites or [], plan, matrix, source, levels, below)
    boxes, n_obst, n_void = _boxes(plan)
    if levels is not None:
        boxes += levels.boxes
    boxes += gap_boxes(plan) if below is None else below.boxes
    header = _header(source, len(pts), levelling, matrix, (n_obst, n_void), plan, opts, sight)
    if pits:
        header += "\n" + describe_pits(pits, "ScanOptions(gaps='floor')")
    plane_z = 0.0 if below is None else below.plane_z
    xml = _mjcf(plan, boxes, site_xyyaw, header, matrix, model_name, site_z, plane_z)
    try:
        mujoco.MjModel.from_xml_string(xml)
    except ValueError as exc:  # a bug here, not bad input: say so plainly
        raise ScanError(f"{source}: the generated scene does not compile: {exc}") from exc
    timings["mjcf"] = clock() - t
    return ScanScene(
        xml, plan, levelling, matrix, len(pts), n_obst, n_void, site_xyyaw, timings, sight, levels,
        site_z, pits,
    )  # fmt: skip


def _file_stations(
    stations: Sequence[Station],
    dropped: bool,
    scale: float,
    axes: np.ndarray,
    offset: tuple[float, float, float] | None,
) -> list[Station]:
    """Stations given in the file's units and axes, moved into metres z up like the points;
    none when rows were ``dropped`` (drop_invalid: no row ranges to trust)."""
    if dropped:
        stations = ()
    off = np.zeros(3) if offset is None else np.asarray(offset, dtype=np.float64)
    return [
        Station(scale * (axes @ (np.asarray(s.viewpoint) - off)), s.start, s.stop, s.origin)
        for s in stations
    ]


def _place_sites(
    sites: list[_Site],
    plan: FloorPlan,
    matrix: np.ndarray,
    source: str,
    levels: LevelPlan | None = None,
    below: PitFloor | None = None,
) -> tuple[dict[str, tuple[float, float, float]], dict[str, float]]:
    """Each site's scene (x, y, yaw radians) and height: on the scanned floor (z = 0) or on a
    raised level (its height; of several there, the highest, or for a site picked in the scan
    the one nearest the picked point's height); elsewhere a ScanError."""
    site_xyyaw: dict[str, tuple[float, float, float]] = {}
    site_z: dict[str, float] = {}
    for s in sites:
        z_pick = None
        if s.xy is not None:
            xy = np.array(s.xy)
        else:
            xyz = (matrix @ np.array([*(s.scan or ()), 1.0]))[:3]
            xy, z_pick = xyz[:2], float(xyz[2])
        ix = int(np.floor((xy[0] - plan.x0) / plan.resolution))
        iy = int(np.floor((xy[1] - plan.y0) / plan.resolution))
        ny, nx = plan.floor.shape
        on = [] if levels is None else levels_at(levels, xy)
        if 0 <= ix < nx and 0 <= iy < ny and plan.floor[iy, ix]:
            on.append((0, SITE_Z))
        if below is not None:  # the bottom of a pit a stair reaches
            on += [(-1, h) for h in below.heights_at(xy, plan)]
        if not on:
            b = plan.bounds
            raise ScanError(
                f"{source}: site {s.name!r} at ({xy[0]:.3f}, {xy[1]:.3f}) is not on the scanned "
                f"floor{' or a level' if levels is not None else ''} (x in [{b[0]:.2f}, "
                f"{b[2]:.2f}], y in [{b[1]:.2f}, {b[3]:.2f}] m, obstacles and voids excluded)"
            )
        heights = np.array([h for _, h in on])
        best = np.argmax(heights) if z_pick is None else np.argmin(np.abs(heights - z_pick))
        site_z[s.name] = float(heights[best])
        site_xyyaw[s.name] = (float(xy[0]), float(xy[1]), float(np.radians(s.yaw_deg)))
    return site_xyyaw, site_z


def _header(
    source: str,
    n_points: int,
    levelling: Levelling,
    matrix: np.ndarray,
    n_boxes: tuple[int, int],
    plan: FloorPlan,
    opts: ScanOptions,
    sight: str,
) -> str:
    """The scene's header comment: what the scan was, the transform, the boxes (``n_boxes``:
    obstacle and void boxes), the sight."""
    n_obst, n_void = n_boxes
    return (
        f"mjwalk scan of {source}: {n_points} points, metres, z up, floor at z = 0.\n"
        f"Floor tilt removed: {levelling.tilt_deg:.3f} deg (normal {_fmt(levelling.normal)} in "
        f"the scan), floor plane rms {1000 * levelling.rms:.1f} mm.\n"
        f"Scan file point -> scene point: 4x4 matrix (row-major, also in custom numeric "
        f"mjwalk_scan_transform):\n  {_fmt(matrix[0])}\n  {_fmt(matrix[1])}\n"
        f"  {_fmt(matrix[2])}\n  {_fmt(matrix[3])}\n"
        f"Obstacles: points {OBSTACLE_Z_RANGE[0]}-{OBSTACLE_Z_RANGE[1]} m above the floor, "
        f"{n_obst} boxes on a {opts.resolution} m grid; voids (unscanned or no floor): "
        f"{n_void} boxes (group 3, policy {opts.voids}); {plan.holes_filled} small unscanned "
        f"holes counted as floor.\n"
        f"{sight[0].upper()}{sight[1:]}."
    )


def write_scene(scene: ScanScene, output: str | Path) -> Path:
    """Write the scene's MJCF atomically (temporary file, then rename).

    Args:
        scene: the scene built.
        output: the file to write.

    Returns:
        ``output`` as a path. A failed write (full disk, file-size limit, permissions) is a
        WriteError naming the file (:func:`~mjwalk._io.atomic_path`); nothing is left.
    """
    output = Path(output)
    with atomic_path(output) as tmp:
        tmp.write_text(scene.xml)
    return output


def scan_to_scene(
    scan: str | Path | Sequence[str | Path],
    output: str | Path,
    options: ScanOptions | None = None,
    *,
    sites: str | Path | None = None,
    poses: str | Path | dict[Path, np.ndarray] | None = None,
    report: Callable[[str], None] | None = None,
) -> ScanScene:
    """Read a scan file, or several of one hall, and write its MJCF scene.

    Several files are merged in the first file's frame (:func:`~mjwalk.scan.merge.merge_scans`).
    The output path, the poses and the sites file are checked before any work; nothing is
    written unless the whole pipeline succeeded.

    Args:
        scan: the scan file, or the files of one hall (the first one's frame is the merge's).
        output: the MJCF file to write (atomically).
        options: how the scan becomes a scene (:class:`ScanOptions`; None: the defaults).
        sites: a sites TOML (format in the module docstring); None: no sites.
        poses: a JSON file or a dict of (4, 4) poses (metres, z up) taking each named scan into
            the first one's frame; scans not named are already in it.
        report: called with each alignment's line when ``options.register`` aligns scans.

    Returns:
        The scene written (its ``matrix`` maps the first file's points to the scene).

    Raises:
        ScanError: a reading, merging or scene error (see :func:`build_scene`).
    """
    opts = ScanOptions() if options is None else options
    scans = [Path(scan)] if isinstance(scan, str | Path) else [Path(s) for s in scan]
    check_output_file(output, "output")
    if isinstance(poses, str | Path):
        poses = read_poses(poses, scans)
    site_list = read_sites(sites) if sites is not None else None
    t = time.perf_counter()
    merged = merge_scans(
        scans,
        units=opts.units,
        up=opts.up,
        drop_invalid=opts.drop_invalid,
        offset=opts.offset,
        poses=poses,
        register=opts.register,
        report=report,
    )
    t_read = time.perf_counter() - t
    first = merged.first
    offset = (float(first.offset[0]), float(first.offset[1]), float(first.offset[2]))
    name = str(scans[0]) if len(scans) == 1 else f"{scans[0]} and {len(scans) - 1} more scans"
    scene = build_scene(
        merged.points,
        dataclasses.replace(opts, offset=offset),
        source=name,
        sites=site_list,
        model_name=scans[0].stem,
        stations=merged.stations,
        _read=(merged.points, first.scale, first.axes),
    )
    scene.timings = {"read": t_read, **scene.timings}
    t = time.perf_counter()
    write_scene(scene, output)
    scene.timings["write"] = time.perf_counter() - t
    return scene
