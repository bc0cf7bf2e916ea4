"""The ``mjwalk`` command line."""

from __future__ import annotations

import argparse
import os
import sys
import tempfile
import time
from pathlib import Path
from typing import Any

from mjwalk import _log
from mjwalk._args import (
    OneLineParser,
    arg_count,
    arg_fps,
    arg_fraction,
    arg_jobs,
    arg_point,
    arg_positive_float,
    arg_positive_int,
    arg_seed,
    arg_video_side,
    check_output_dir,
    check_output_file,
    image_suffixes,
    join_negative_values,
)
from mjwalk._version import __version__
from mjwalk.cli.scenes import add_scan_parser, add_scene_import_parser
from mjwalk.cli.scheduler import dask_client
from mjwalk.conventions import BODY_RADIUS, DEFAULT_STATURE
from mjwalk.errors import InputError, MjwalkError

#: Video files ``mjwalk render`` writes (H.264 in MP4).
VIDEO_SUFFIXES = (".mp4",)
_SCENES = "station, corridor, open_floor"
QUIET_HELP = "no progress messages or bars (warnings and errors only)"


def _load_model(path: Path | None):
    if path is None:
        from mjwalk.gait.default import default_model

        return default_model()
    from mjwalk.gait.model import StepModel

    return StepModel.load(path)


def _add_walker_args(p: argparse.ArgumentParser) -> None:
    """The walker options shared by ``plan`` and ``validate`` (:class:`mjwalk.Walker`)."""
    g = p.add_argument_group(
        "walker",
        "the operator the steps are sampled for (default: the model's own pace); a preset's "
        "figures are overridden by --speed/--cadence/--stature/--step-width",
    )
    g.add_argument(
        "--walker", metavar="PRESET", help="adult, older_adult, elderly, fatigued, brisk"
    )
    g.add_argument("--speed", type=arg_positive_float, help="preferred walking speed, m/s")
    g.add_argument("--cadence", type=arg_positive_float, help="preferred cadence, steps/min")
    g.add_argument("--stature", type=arg_positive_float, help="body height, metres")
    g.add_argument("--step-width", type=arg_positive_float, help="step width, metres")


def _walker_from_args(args: argparse.Namespace):
    """The :class:`~mjwalk.gait.walker.Walker` the options describe, or None (checked here,
    before any work: a bad figure raises WalkerError naming it)."""
    from mjwalk.gait.walker import Walker

    given = {
        k: getattr(args, k)
        for k in ("speed", "cadence", "stature", "step_width")
        if getattr(args, k, None) is not None
    }
    if args.walker:
        return Walker.preset(args.walker, **given)
    return Walker(**given) if given else None


def _quartiles(x) -> tuple[float, float]:
    import numpy as np

    q25, q50, q75 = np.percentile(x, [25, 50, 75])
    return float(q50), float(q75 - q25)


def _cmd_plan(args: argparse.Namespace) -> int:
    if args.png:
        check_output_file(args.png, "--png", image_suffixes())
    if args.save:
        check_output_file(args.save.with_suffix(".npz"), "--save")
    walker = _walker_from_args(args)
    from mjwalk.plan.grid import plan_grid
    from mjwalk.plan.occupancy import check_endpoint
    from mjwalk.shipped import scene_file
    from mjwalk.world import load_workplace

    workplace = load_workplace(scene_file(args.scene))
    for where, what in ((args.start, "start"), (args.goal, "goal")):
        # unknown sites, points off the floor or in an obstacle fail here, before planning
        check_endpoint(workplace, workplace.point(where), args.radius, what)
    model = _load_model(args.model).for_walker(walker) if args.n > 0 else None
    baseline = plan_grid(workplace, args.start, args.goal, radius=args.radius)
    print(
        f"grid A*  {args.start} -> {args.goal}: length {baseline.length:.3f} m, "
        f"{baseline.meta['expansions']} expansions, {1000 * baseline.meta['seconds']:.1f} ms"
    )
    paths = []
    if args.n > 0:
        from mjwalk.plan.options import PlannerOptions
        from mjwalk.plan.walks import plan_walks

        options = PlannerOptions(radius=args.radius, cost=args.cost)
        paths = plan_walks(
            workplace, args.start, args.goal, model, n=args.n, seed=args.seed, options=options
        )
        lm, li = _quartiles([p.length for p in paths])
        dm, di = _quartiles([p.duration for p in paths])
        tm, _ = _quartiles([1000 * p.meta["seconds"] for p in paths])
        if walker is not None:
            print(
                f"walker {walker.group}: {walker.speed:.2f} m/s, {walker.cadence:.0f} steps/min, "
                f"stature {walker.stature:.2f} m"
            )
        print(
            f"hybrid A* {len(paths)} walks: length median {lm:.3f} m (IQR {li:.3f}), "
            f"duration median {dm:.2f} s (IQR {di:.2f}), planning median {tm:.1f} ms"
        )
        if args.save:
            for k, p in enumerate(paths):
                p.save(args.save.with_name(f"{args.save.stem}_{k:03d}.npz"))
            print(f"wrote {len(paths)} walk files {args.save.stem}_NNN.npz")
    if args.png:
        from mjwalk.render.plot import save_plan_png  # matplotlib: imported only when drawing

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


def _cmd_train(args: argparse.Namespace) -> int:
    from mjwalk.gait.fidelity import train_main

    if args.amc and not args.asf:
        raise MjwalkError("train: --amc needs --asf")
    check_output_file(args.output, "-o/--output")
    train_main(
        args.output,
        bvh=args.bvh,
        amc=args.amc,
        asf=args.asf,
        virtual=args.virtual,
        seed=args.seed,
        skeleton=args.skeleton,
        variance=args.pca_variance,
    )
    print(f"wrote {args.output}")
    return 0


def _cmd_validate(args: argparse.Namespace) -> int:
    from mjwalk.gait.fidelity import format_fidelity_table, validate_main
    from mjwalk.plan.walktimes import planned_straight_walks

    if args.json:
        check_output_file(args.json, "--json")
    walker = _walker_from_args(args)
    report = validate_main(
        args.model,
        args.against,
        args.json,
        amc_asf=args.asf,
        seed=args.seed,
        skeleton=args.skeleton,
        walker=walker,
        planned_walks=planned_straight_walks,
    )
    print(format_fidelity_table(report))
    return 0


def _cmd_simulate(args: argparse.Namespace) -> int:
    import json

    check_output_dir(args.out, "--out")
    if args.only_run is not None and args.only_run >= args.runs:
        raise InputError(
            f"--only-run {args.only_run}: runs are numbered 0 to {args.runs - 1} "
            f"(--runs {args.runs})"
        )
    from mjwalk.cycle.context import context_of
    from mjwalk.cycle.simulate import simulate_cycles
    from mjwalk.cycle.spec import load_cycle_spec
    from mjwalk.report import format_summary, report_dict, write_report
    from mjwalk.shipped import cycle_file

    # the scheduler answers (or is refused by name) within 10 s, before the cycle is checked
    client = None if args.scheduler is None else dask_client(args.scheduler)
    try:
        spec = load_cycle_spec(cycle_file(args.spec))
        only = None if args.only_run is None else [args.only_run]
        which = f"run {args.only_run} of {args.runs}" if only else f"{args.runs} runs"
        print(
            f"mjwalk simulate: {spec.name or spec.path.name}: {len(spec.tasks)} tasks, "
            f"{which}, seed {args.seed}",
            flush=True,
        )
        if args.dry_run:
            print(f"  {spec.path} and --out {args.out} checked; nothing simulated (--dry-run)")
            return 0
        # builds (or loads) the default models once, with progress; this process reuses them
        ctx = context_of(spec)
        batch: dict[str, Any] = dict(
            seed=args.seed,
            n_jobs=args.jobs,
            progress=not args.quiet,
            only=only,
            on_error="record",  # one unplannable run does not end a long batch; the report lists it
        )
        if client is None:
            results = simulate_cycles(spec, args.runs, **batch)
        else:
            import joblib

            # the spec goes to the workers in memory; its scene and model files must be at the
            # same paths there (a shared file system), as for any Dask job reading files
            with joblib.parallel_config(backend="dask"):
                results = simulate_cycles(spec, args.runs, **{**batch, "n_jobs": -1})
    finally:
        if client is not None:
            client.close()
    files = write_report(results, args.out, workplace=ctx.workplace)
    print(format_summary(report_dict(results)))
    for name, path in files.items():
        print(f"  wrote {name}: {path}")
    replayed: dict = {}  # runs simulated again with their timelines, by run index
    if args.video:
        from mjwalk.render import render_video

        first = next(r for r in results if r.error is None)  # report_dict: at least one
        run0 = _replay(ctx, args.seed, first.run)
        replayed[first.run] = run0
        video = args.out / "cycle.mp4"
        assert run0.timeline is not None  # keep_timeline=True
        render_video(
            run0.timeline,
            video,
            camera=args.camera,
            size=(640, 480),
            fps=30,
            progress=not args.quiet,
        )
        print(f"  wrote video: {video}")
    if args.export:
        _export_runs(args, ctx, results, replayed)
    if args.json_summary:
        print(json.dumps(report_dict(results)["cycle_time"]))
    return 0


def _replay(ctx, seed: int, run: int, **kwargs):
    """Run ``run`` of the batch of ``seed`` again, keeping its timeline (the same cycle: it
    draws from ``SeedSequence([seed, run])`` as in the batch)."""
    from mjwalk.cycle.seeding import run_generator
    from mjwalk.cycle.simulate import simulate_cycle

    rng = run_generator(seed, run)
    # the video and the exports need the motion only: no collision check, no scoring
    return simulate_cycle(
        ctx, rng, run=run, keep_timeline=True, collisions=False, ergonomics=False, **kwargs
    )


def _export_runs(args: argparse.Namespace, ctx, results, replayed: dict) -> None:
    """--export bvh/csv: each simulated run's humanoid motion (again, with its timeline) as
    ``run_KKK.bvh`` / ``run_KKK_angles.csv`` in --out (mjwalk.ergonomics.export); ``replayed``
    holds runs already simulated again (the video's), by run index."""
    from mjwalk.ergonomics.export import write_angles_csv, write_bvh

    for r in results:
        if r.error is not None:
            continue
        run = replayed.get(r.run) or _replay(ctx, args.seed, r.run)
        for kind in dict.fromkeys(args.export):
            if kind == "bvh":
                out = write_bvh(run.timeline, args.out / f"run_{r.run:03d}.bvh")
            else:
                out = write_angles_csv(run.timeline, args.out / f"run_{r.run:03d}_angles.csv")
            print(f"  wrote {kind}: {out}")


def _cmd_render(args: argparse.Namespace) -> int:
    check_output_file(args.output, "-o/--output", VIDEO_SUFFIXES)
    from mjwalk.plan.walkpath import WalkPath
    from mjwalk.render import render_video
    from mjwalk.shipped import scene_file
    from mjwalk.timeline import timeline_from_walk
    from mjwalk.world.workplace import shared_workplace

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


def build_parser() -> argparse.ArgumentParser:
    parser = OneLineParser(
        prog="mjwalk",
        description="Statistically varied human walking and reaching in MuJoCo workplaces.",
    )
    parser.add_argument("--version", action="version", version=f"mjwalk {__version__}")
    sub = parser.add_subparsers(dest="command", required=True)

    p = sub.add_parser("plan", help="plan a walk between two points or sites of a scene")
    p.add_argument("scene", type=Path, help=f"MJCF scene file, or a shipped scene: {_SCENES}")
    p.add_argument(
        "--from",
        dest="start",
        required=True,
        type=arg_point,
        help="start: a site, or X,Y (metres); a site whose name reads as X,Y wins",
    )
    p.add_argument(
        "--to",
        dest="goal",
        required=True,
        type=arg_point,
        help="goal: a site, or X,Y (metres); a site whose name reads as X,Y wins",
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
    _add_walker_args(p)
    p.set_defaults(func=_cmd_plan)

    p = sub.add_parser("simulate", help="simulate assembly cycles (Monte Carlo) and report")
    p.add_argument("spec", type=Path, help="cycle specification (TOML), or 'station' (shipped)")
    p.add_argument("--runs", type=arg_positive_int, default=50, help="cycles to simulate (50)")
    p.add_argument("--out", type=Path, default=Path("out"), help="report folder (out/)")
    p.add_argument(
        "--seed",
        type=arg_seed,
        default=0,
        help="random seed, a whole number >= 0 (same seed, same report)",
    )
    p.add_argument("--jobs", type=arg_jobs, default=-1, help="parallel processes (-1: all cores)")
    p.add_argument(
        "--only-run",
        type=arg_count,
        metavar="K",
        help="simulate only run K of the --runs (the same cycle as in the full batch)",
    )
    p.add_argument(
        "--dry-run", action="store_true", help="check the cycle and --out, simulate nothing"
    )
    p.add_argument(
        "--scheduler",
        metavar="ADDRESS",
        help="run the batch on an existing Dask cluster (tcp://HOST:PORT of its scheduler; the "
        "workers need mjwalk and the scene's files at the same paths); same results as a local run",
    )
    p.add_argument("--video", action="store_true", help="also render one cycle to cycle.mp4")
    p.add_argument("--camera", choices=["track", "top"], default="track")
    p.add_argument(
        "--export",
        choices=["bvh", "csv"],
        action="append",
        help="also write each run's (or --only-run K's) humanoid motion as run_KKK.bvh or "
        "run_KKK_angles.csv (joint angles); repeat for both",
    )
    p.add_argument("--quiet", action="store_true", help=QUIET_HELP)
    p.add_argument("--json-summary", action="store_true", help=argparse.SUPPRESS)
    p.set_defaults(func=_cmd_simulate)

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
    p.set_defaults(func=_cmd_render)

    p = sub.add_parser("train", help="train a step model from capture or virtual subjects")
    p.add_argument("--bvh", help="glob of BVH files")
    p.add_argument("--amc", help="glob of AMC files (with --asf)")
    p.add_argument("--asf", help="the ASF skeleton of the AMC files")
    p.add_argument(
        "--virtual", type=arg_positive_int, help="N virtual subjects from the built-in generator"
    )
    p.add_argument(
        "--pca-variance",
        type=arg_fraction,
        metavar="SHARE",
        help="share of the step features' variance the PCA keeps, in (0, 1] (default 0.99; "
        "the paper keeps >= 0.95, better for small captures)",
    )
    p.add_argument("--skeleton", help="skeleton preset: bandai, cmu, cmu_bvh")
    p.add_argument("--seed", type=arg_seed, default=0)
    p.add_argument("-o", "--output", type=Path, required=True, help="model file to write")
    p.set_defaults(func=_cmd_train)

    p = sub.add_parser("validate", help="compare a step model with captured walking")
    p.add_argument("model", type=Path, nargs="?", help="model file (default: built-in model)")
    p.add_argument("--against", required=True, help="glob of BVH (or AMC, with --asf) files")
    p.add_argument("--asf", help="ASF skeleton for AMC files")
    p.add_argument("--skeleton", help="skeleton preset: bandai, cmu, cmu_bvh")
    p.add_argument("--json", type=Path, help="write the report as JSON here")
    p.add_argument("--seed", type=arg_seed, default=0)
    _add_walker_args(p)
    p.set_defaults(func=_cmd_validate)
    add_scan_parser(sub)
    add_scene_import_parser(sub)
    for cmd in sub.choices.values():
        if not any("--quiet" in a.option_strings for a in cmd._actions):
            cmd.add_argument("--quiet", action="store_true", help=QUIET_HELP)
    return parser


def main(argv: list[str] | None = None) -> int:
    parser = build_parser()
    argv = sys.argv[1:] if argv is None else argv
    args = parser.parse_args(join_negative_values(argv, ("--from", "--to")))
    _log.configure(quiet=args.quiet)
    # one compile notice for the command, whichever of its processes compiles first
    mark = Path(tempfile.gettempdir()) / f"mjwalk-notice-{os.getpid()}-{time.time_ns()}"
    os.environ[_log.NOTICE_ENV] = str(mark)
    try:
        return args.func(args)
    except MjwalkError as exc:
        print(f"mjwalk: error: {exc}", file=sys.stderr)
        return 2
    except KeyboardInterrupt:
        print("mjwalk: interrupted", file=sys.stderr)
        return 130
    finally:
        os.environ.pop(_log.NOTICE_ENV, None)
        mark.unlink(missing_ok=True)


if __name__ == "__main__":
    sys.exit(main())
