"""The ``mjwalk scan`` and ``mjwalk scene-import`` commands: scenes from laser scans and from
concave CAD meshes (:mod:`mjwalk.scan`, :mod:`mjwalk.world.meshimport`)."""

from __future__ import annotations

import argparse
from pathlib import Path
from typing import TYPE_CHECKING

import numpy as np

from mjwalk._args import (
    check_output_file,
    image_suffixes,
)
from mjwalk.errors import MjwalkError

if TYPE_CHECKING:
    from mjwalk.scan.scanoptions import ScanOptions


def scan_options(args: argparse.Namespace) -> ScanOptions:
    """The :class:`~mjwalk.scan.scanoptions.ScanOptions` of ``mjwalk scan``'s flags: the one
    place the command's flags become the pipeline's options.

    Args:
        args: the parsed ``mjwalk scan`` command line.

    Returns:
        The options (units, up axis, invalid points, resolution, offset, voids, register,
        gaps).
    """
    from mjwalk.scan.scanoptions import ScanOptions  # deferred: mjwalk.scan loads mujoco and numba

    return ScanOptions(
        units=args.units,
        up=args.up,
        drop_invalid=args.drop_invalid,
        resolution=args.resolution,
        offset=args.offset,
        voids=args.voids,
        register=args.register,
        gaps=args.gaps,
    )


def cmd_scan(args: argparse.Namespace) -> int:
    """``mjwalk scan``: a scene from laser scans (:func:`mjwalk.scan.scan_to_scene`); prints
    the floor found, the voids' cover, what the scanners saw and the transform.

    Args:
        args: the parsed ``scan`` options.

    Returns:
        The exit status, 0.
    """
    # deferred: mjwalk.scan loads numba and the cloud readers (~2 s), only for `mjwalk scan`
    from mjwalk.scan import scan_to_scene
    from mjwalk.scan.levelboxes import describe  # deferred: as the line above
    from mjwalk.scan.obstacles import FLOOR_TOL  # deferred: as the line above
    from mjwalk.scan.scanpits import describe_pits  # deferred: as the line above
    from mjwalk.scan.voids import cover, save_top_view  # deferred: as the line above

    check_output_file(args.output, "-o/--output")
    if args.png is not None:
        check_output_file(args.png, "--png", image_suffixes())
    scene = scan_to_scene(
        args.scan,
        args.output,
        scan_options(args),
        poses=args.poses,
        report=print,
        sites=args.sites,
    )
    lv = scene.levelling
    b = scene.plan.bounds
    print(
        f"{' + '.join(map(str, args.scan))}: {scene.n_points} points; "
        f"floor tilt {lv.tilt_deg:.3f} deg removed, "
        f"floor x [{b[0]:.2f}, {b[2]:.2f}] y [{b[1]:.2f}, {b[3]:.2f}] m; "
        f"{scene.n_obstacle_boxes} obstacle boxes, {scene.n_void_boxes} void boxes, "
        f"{len(scene.sites)} sites"
    )
    print(f"--voids {args.voids}: {cover(scene.plan).line()}")
    print(scene.sight)
    levels = scene.levels
    if levels is not None:
        print(describe(levels))
    heights = [] if levels is None else levels.heights
    others = [s for s in lv.surfaces if all(abs(s.height - h) > FLOOR_TOL for h in heights)]
    pits = [s for s in others if s.height < -FLOOR_TOL]
    others = [s for s in others if s.height >= -FLOOR_TOL]
    if scene.pits:
        print(describe_pits(scene.pits))
    elif pits:
        shown = ", ".join(
            f"{s.height:+.2f} m ({s.area:.1f} m² at {s.x:.1f}, {s.y:.1f})" for s in pits
        )
        print(
            f"surfaces below the floor (pits) that are no gap (--gaps {args.gaps}): {shown}; "
            "the scene has no walk surface there and unscanned cells of it may be filled as "
            "floor (small holes are): check the top view (--png) and fence the pit before "
            "planning near it"
        )
    if others:
        shown = ", ".join(
            f"{s.height:+.2f} m ({s.area:.1f} m² at {s.x:.1f}, {s.y:.1f})" for s in others[:8]
        )
        more = f" and {len(others) - 8} more" if len(others) > 8 else ""
        print(
            f"other horizontal surfaces one could stand on (not reached by steps from the "
            f"floor: they stay obstacles or floor): {shown}{more}"
        )
    if args.png is not None:
        save_top_view(scene.plan, args.png, levels=levels, pits=scene.pits)
        what = "" if levels is None else ", levels with heights and links"
        print(f"wrote {args.png} (top view: floor seen, unseen, obstacles, voids{what})")
    print(f"{args.scan[0]} -> scene transform (4x4, row-major):")
    for row in scene.matrix:
        print("  " + " ".join(f"{v:10.6f}" for v in row))
    print(" ".join(f"{k} {v:.2f} s" for k, v in scene.timings.items()))
    print(f"wrote {args.output}")
    return 0


def _scan_resolution(text: str) -> float:
    """``--resolution``: a number of metres within the floor plan's stated range."""
    from mjwalk.scan.limits import check_resolution  # deferred: mjwalk.scan loads numba (~2 s)

    try:
        return check_resolution(text, "")
    except MjwalkError as exc:
        raise argparse.ArgumentTypeError(str(exc).strip()) from None


def _scan_offset(text: str) -> np.ndarray:
    """``--offset X,Y,Z``: three finite numbers in the scan file's units and axes."""
    try:
        values = np.array([float(v) for v in text.split(",")])
    except ValueError:
        values = np.array([])
    if values.shape != (3,) or not np.isfinite(values).all():
        raise argparse.ArgumentTypeError(
            f"{text!r}: expected X,Y,Z, three finite numbers in the file's units "
            "(write --offset=-1,2,3 when it starts with a minus)"
        )
    return values


def add_scan_parser(sub) -> None:
    """Add the ``scan`` sub-command.

    Args:
        sub: the main parser's sub-parsers (``add_subparsers()``).
    """
    from mjwalk.scan.limits import RESOLUTION_RANGE  # deferred: mjwalk.scan loads numba (~2 s)
    from mjwalk.scan.scanoptions import ScanOptions  # deferred: as the line above

    p = sub.add_parser("scan", help="turn a laser scan (PLY/PCD/LAS/LAZ/E57/XYZ/PTS) into a scene")
    p.add_argument(
        "scan",
        type=Path,
        nargs="+",
        help="point-cloud file(s); several scans of one hall are merged in the first one's "
        "frame (already registered, placed by --poses, or aligned by --register)",
    )
    p.add_argument(
        "--register",
        action="store_true",
        help="align the scans after the first that --poses does not place (levelled, Open3D "
        "FPFH + RANSAC, ICP, checked against the free space each scan saw); prints fitness "
        "and RMSE, refuses a scan it cannot align unambiguously",
    )
    p.add_argument(
        "--poses",
        type=Path,
        metavar="JSON",
        help='known poses: {"B.ply": 4x4 matrix} taking each named scan (metres, z up) into '
        "the first scan's frame; scans not named are already in it",
    )
    p.add_argument("-o", "--output", type=Path, required=True, help="MJCF scene to write")
    defaults = ScanOptions()
    p.add_argument(
        "--units", default=defaults.units, help="file units when it does not say: m cm mm in ft"
    )
    p.add_argument(
        "--up",
        default=defaults.up,
        help="file up axis when it does not say: +z, -z, +y, ... (--up=-z)",
    )
    p.add_argument("--sites", type=Path, help="TOML of named sites ([site.NAME] xy = [x, y])")
    p.add_argument(
        "--resolution",
        type=_scan_resolution,
        default=defaults.resolution,
        help=f"floor-plan grid, metres ({RESOLUTION_RANGE[0]}-{RESOLUTION_RANGE[1]}; "
        f"default {defaults.resolution})",
    )
    p.add_argument(
        "--offset",
        type=_scan_offset,
        metavar="X,Y,Z",
        help="subtract this point (file units and axes) from every point first, for a "
        "georeferenced cloud far from its origin (write --offset=-X,Y,Z when negative)",
    )
    p.add_argument(
        "--drop-invalid", action="store_true", help="leave out NaN/infinite points (else error)"
    )
    p.add_argument(
        "--voids",
        choices=("blocked", "fill", "free"),
        default=defaults.voids,
        help="unseen floor: blocked (default: nobody walks where no floor was seen), fill "
        "(enclosed voids up to 2 m inscribed radius are walkable), free (all walkable)",
    )
    p.add_argument(
        "--gaps",
        choices=("obstacle", "floor"),
        default=defaults.gaps,
        help="unscanned floor over points below it (a pit, a trench): obstacle (default: "
        "written as a guard-rail box, a hazard the planner sees), floor (filled like any hole)",
    )
    p.add_argument("--png", type=Path, help="top view of the floor plan (seen, unseen, voids)")
    p.set_defaults(func=cmd_scan)


def cmd_scene_import(args: argparse.Namespace) -> int:
    """``mjwalk scene-import``: a mesh or MJCF scene with its concave meshes decomposed
    (:func:`mjwalk.world.meshimport.import_scene`); prints the parts of each.

    Args:
        args: the parsed ``scene-import`` options.

    Returns:
        The exit status, 0.
    """
    # deferred: mujoco loads only for `mjwalk scene-import` (trimesh/CoACD when it runs)
    from mjwalk.world.meshimport import check_threshold, import_scene

    check_threshold(args.threshold, "--threshold")
    check_output_file(args.output, "-o/--output", (".xml",))
    result = import_scene(
        args.source, args.output, units=args.units, up=args.up, threshold=args.threshold
    )
    for name, parts in result.parts.items():
        print(f"  {name}: concave, {parts} convex parts for MuJoCo's collision")
    print(
        f"wrote {args.output} ({sum(result.parts.values())} convex parts of "
        f"{len(result.parts)} concave meshes, inline)"
    )
    return 0


def add_scene_import_parser(sub) -> None:
    """Add the ``scene-import`` sub-command.

    Args:
        sub: the main parser's sub-parsers (``add_subparsers()``).
    """
    p = sub.add_parser(
        "scene-import", help="import a mesh or MJCF: concave meshes get convex decompositions"
    )
    p.add_argument("source", type=Path, help="mesh (STL/OBJ/PLY/GLB/OFF) or MJCF scene")
    p.add_argument("-o", "--output", type=Path, required=True, help="MJCF scene to write")
    p.add_argument("--units", default="m", help="mesh file units: m cm mm in ft")
    p.add_argument("--up", default="+z", help="mesh file up axis: +z +y ...")
    p.add_argument(
        "--threshold",
        type=float,
        default=None,
        help="CoACD concavity threshold (0.02; 0.01 for a mesh with walk faces under its hull)",
    )
    p.set_defaults(func=cmd_scene_import)
