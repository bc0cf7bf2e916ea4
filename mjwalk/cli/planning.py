"""The ``mjwalk plan`` and ``mjwalk render`` commands: walks planned in a scene
(:mod:`mjwalk.plan`) and a saved walk played back as video (:mod:`mjwalk.render`)."""

from __future__ import annotations

import argparse
from pathlib import Path

from mjwalk._args import (
    arg_count,
    arg_fps,
    arg_point,
    arg_positive_float,
    arg_seed,
    arg_video_side,
    check_output_file,
    image_suffixes,
)
from mjwalk.cli._common import QUIET_HELP, SCENES
from mjwalk.cli.models import add_walker_args, walker_from_args
from mjwalk.conventions import BODY_RADIUS, DEFAULT_STATURE
from mjwalk.errors import PlanningError

#: Video files ``mjwalk render`` writes (H.264 in MP4).
VIDEO_SUFFIXES = (".mp4",)


def cmd_plan(args: argparse.Namespace) -> int:
    """``mjwalk plan``: the grid-A* route and ``--n`` hybrid-A* walks between two points.

    Prints the route's length and the walks' medians and IQRs; writes the walks (``--save``)
    and a top view (``--png``) when asked.

    Args:
        args: the parsed ``plan`` options.

    Returns:
        The exit status, 0.
    """
    if args.png:
        check_output_file(args.png, "--png", image_suffixes())
    if args.save:
        check_output_file(args.save.with_suffix(".npz"), "--save")
    walker = walker_from_args(args)
    # deferred: mujoco/numba load only for the command that needs them
    from mjwalk.gait.training import load_model
    from mjwalk.plan.grid import plan_grid  # deferred: mujoco/numba, as above
    from mjwalk.plan.levelplan import needs_levels  # deferred: numba, as above
    from mjwalk.plan.occupancy import check_endpoint  # deferred: mujoco/numba, as above
    from mjwalk.shipped import scene_file  # deferred: mujoco/numba, as above
    from mjwalk.world import load_workplace  # deferred: mujoco/numba, as above

    workplace = load_workplace(scene_file(args.scene))
    levels = needs_levels(workplace, args.start, args.goal, args.radius)
    baseline = None
    if not levels:  # a walk over levels: the level planner places and checks both ends
        for where, what in ((args.start, "start"), (args.goal, "goal")):
            # unknown sites, points off the floor or in an obstacle fail here, before planning
            check_endpoint(workplace, workplace.point(where), args.radius, what)
    # a bad model file (or an unwritable cache for the default one) is refused before planning
    model = load_model(args.model).for_walker(walker) if args.n > 0 else None
    if levels:
        print(_level_summary(workplace, args.start, args.goal))
        baseline = _level_baseline(workplace, args, walker)
    else:
        baseline = plan_grid(workplace, args.start, args.goal, radius=args.radius)
        print(
            f"grid A*  {args.start} -> {args.goal}: length {baseline.length:.3f} m, "
            f"{baseline.meta['expansions']} expansions, {1000 * baseline.meta['seconds']:.1f} ms"
        )
    paths = [] if model is None else _hybrid_walks(args, workplace, model, walker)
    if levels and paths:
        print(_level_walk_summary(paths))
    if args.png:
        from mjwalk.render.plot import save_plan_png  # deferred: matplotlib, only when drawing

        save_plan_png(
            args.png,
            workplace,
            paths,
            baseline=baseline,
            footprints=args.footprints,
            title=f"{workplace.name}: {args.start} -> {args.goal}",
        )
        print(f"wrote {args.png}")
    return 0


def _level_summary(workplace, start, goal) -> str:
    """The levels of the scene (:func:`mjwalk.world.levels.describe_levels`) and where the
    walk's ends stand."""
    from mjwalk.plan.levelplan import endpoint  # deferred: numba, only when planning
    from mjwalk.world.levels import describe_levels  # deferred: mujoco, as above

    a, b = endpoint(workplace, start, "start"), endpoint(workplace, goal, "goal")
    return (
        f"{describe_levels(workplace.levels)}\n"
        f"walk over levels  {start} (L{a.level}) -> {goal} (L{b.level})"
    )


def _level_baseline(workplace, args, walker):
    """The grid-A* route over levels (:func:`mjwalk.plan.levelgrid.level_grid_route`), printed;
    None (and why, printed) when the grid finds none: the hybrid walks may still be planned."""
    from mjwalk.plan.levelgrid import level_grid_route  # deferred: numba, as above

    try:
        base = level_grid_route(workplace, args.start, args.goal, walker=walker, radius=args.radius)
    except PlanningError as e:
        print(f"grid A*  over levels: none ({e})")
        return None
    print(
        f"grid A*  {args.start} -> {args.goal} over levels: length {base.length:.3f} m, "
        f"route {' -> '.join(base.meta['levels'])}"
    )
    return base


def _level_walk_summary(paths: list) -> str:
    """The first walk's route over levels and the walks' mean seconds and steps per kind."""
    route = paths[0].meta["levels"]["route"]
    names = [
        f"L{r['level']}" if r["kind"] == "level" else f"{r['kind']} {r['direction']}" for r in route
    ]
    kinds: dict[str, list[float]] = {}
    for p in paths:
        for kind, row in p.meta["levels"]["per_kind"].items():
            kinds.setdefault(kind, [0.0, 0.0])
            kinds[kind][0] += row["seconds"] / len(paths)
            kinds[kind][1] += row["steps"] / len(paths)
    per_kind = ", ".join(f"{k} {v[0]:.2f} s / {v[1]:.1f} steps" for k, v in kinds.items())
    return f"route (walk 0): {' -> '.join(names)}\nmean per kind: {per_kind}"


def _hybrid_walks(args: argparse.Namespace, workplace, model, walker) -> list:
    """Plan, summarise and (``--save``) write ``args.n`` hybrid-A* walks; returns them."""
    from mjwalk.plan.options import PlannerOptions  # deferred: numba, only when planning
    from mjwalk.plan.walks import plan_walks  # deferred: numba, only when planning
    from mjwalk.report.figures import walks_summary  # deferred: loads mjwalk.cycle (numba)

    options = PlannerOptions(radius=args.radius, cost=args.cost)
    paths = plan_walks(
        workplace, args.start, args.goal, model, n=args.n, seed=args.seed, options=options
    )
    s = walks_summary(paths)
    if walker is not None:
        print(
            f"walker {walker.group}: {walker.speed:.2f} m/s, {walker.cadence:.0f} steps/min, "
            f"stature {walker.stature:.2f} m"
        )
    print(
        f"hybrid A* {len(paths)} walks: length median {s['length']['median']:.3f} m "
        f"(IQR {s['length']['iqr']:.3f}), duration median {s['duration']['median']:.2f} s "
        f"(IQR {s['duration']['iqr']:.2f}), planning median {s['planning_ms']['median']:.1f} ms"
    )
    if args.save:
        for k, p in enumerate(paths):
            p.save(args.save.with_name(f"{args.save.stem}_{k:03d}.npz"))
        print(f"wrote {len(paths)} walk files {args.save.stem}_NNN.npz")
    return paths


def cmd_render(args: argparse.Namespace) -> int:
    """``mjwalk render``: a walk saved by ``mjwalk plan --save`` as an MP4 video.

    Args:
        args: the parsed ``render`` options.

    Returns:
        The exit status, 0.
    """
    check_output_file(args.output, "-o/--output", VIDEO_SUFFIXES)
    # deferred: mujoco/OpenGL load only for the command that needs them
    from mjwalk.plan.walkpath import WalkPath
    from mjwalk.render import render_video  # deferred: mujoco/OpenGL, as above
    from mjwalk.shipped import scene_file  # deferred: mujoco/OpenGL, as above
    from mjwalk.timeline import timeline_from_walk  # deferred: mujoco/OpenGL, as above
    from mjwalk.world.workplace import shared_workplace  # deferred: mujoco/OpenGL, as above

    walk = WalkPath.load(args.walk)
    scene = scene_file(args.scene)
    walk.check_scene(shared_workplace(scene), force=args.force)
    timeline = timeline_from_walk(walk, scene, fps=args.fps, stature=args.stature)
    render_video(
        timeline,
        args.output,
        camera=args.camera,
        size=(args.width, args.height),
        fps=args.fps,
        progress=not args.quiet,
    )
    print(f"wrote {args.output} ({timeline.n_frames} frames)")
    return 0


def add_plan_parser(sub) -> None:
    """Add the ``plan`` sub-command.

    Args:
        sub: the main parser's sub-parsers (``add_subparsers()``).
    """
    p = sub.add_parser("plan", help="plan a walk between two points or sites of a scene")
    p.add_argument("scene", type=Path, help=f"MJCF scene file, or a shipped scene: {SCENES}")
    for flag, dest, what in (("--from", "start", "start"), ("--to", "goal", "goal")):
        p.add_argument(
            flag,
            dest=dest,
            required=True,
            type=arg_point,
            help=f"{what}: a site, or X,Y (metres); a site whose name reads as X,Y wins",
        )
    p.add_argument(
        "--radius",
        type=arg_positive_float,
        default=BODY_RADIUS,
        help="body radius in metres (0.25)",
    )
    p.add_argument(
        "--png", type=Path, help="write a top-view image of the plan here (.png, .svg...)"
    )
    p.add_argument(
        "--n",
        type=arg_count,
        default=15,
        help="walks to sample with the hybrid A* (15; 0: baseline only)",
    )
    p.add_argument("--model", type=Path, help="step model file (default: the built-in model)")
    p.add_argument(
        "--cost",
        choices=("energy", "chord", "path"),
        default="energy",
        help="step cost: length weighted by the energy of its pace (energy, default), the "
        "paper's straight length (chord) or the pelvis arc (path)",
    )
    p.add_argument(
        "--seed",
        type=arg_seed,
        default=0,
        help="random seed, a whole number >= 0 (same seed, same walks)",
    )
    p.add_argument("--footprints", action="store_true", help="draw the footprints too")
    p.add_argument("--save", type=Path, help="save each walk as NAME_NNN.npz (for mjwalk render)")
    add_walker_args(p)
    p.set_defaults(func=cmd_plan)


def add_render_parser(sub) -> None:
    """Add the ``render`` sub-command.

    Args:
        sub: the main parser's sub-parsers (``add_subparsers()``).
    """
    p = sub.add_parser("render", help="render a saved walk (mjwalk plan --save) to MP4")
    p.add_argument("walk", type=Path, help="walk file (.npz) written by mjwalk plan --save")
    p.add_argument(
        "--scene", type=Path, required=True, help="MJCF scene (or shipped scene) of the walk"
    )
    p.add_argument(
        "--force", action="store_true", help="play the walk even if planned in another scene"
    )
    p.add_argument("-o", "--output", type=Path, required=True, help="video file to write (.mp4)")
    p.add_argument("--camera", choices=["track", "top"], default="track")
    p.add_argument("--fps", type=arg_fps, default=30.0, help="frames per second, up to 240 (30)")
    p.add_argument("--width", type=arg_video_side, default=640, help="pixels, even (640)")
    p.add_argument("--height", type=arg_video_side, default=480, help="pixels, even (480)")
    p.add_argument(
        "--stature",
        type=arg_positive_float,
        default=DEFAULT_STATURE,
        help="humanoid stature in metres",
    )
    p.add_argument("--quiet", action="store_true", help=QUIET_HELP)
    p.set_defaults(func=cmd_render)
