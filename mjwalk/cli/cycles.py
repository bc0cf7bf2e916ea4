"""The ``mjwalk simulate`` command: a Monte-Carlo batch of assembly cycles
(:mod:`mjwalk.cycle`), its report (:mod:`mjwalk.report`), a video of one cycle and the runs'
motion files (:mod:`mjwalk.cycle.replay`)."""

from __future__ import annotations

import argparse
import json
from pathlib import Path
from typing import Any

from mjwalk._args import arg_count, arg_jobs, arg_positive_int, arg_seed, check_output_dir
from mjwalk.cli._common import QUIET_HELP
from mjwalk.cli.scheduler import dask_client
from mjwalk.errors import InputError


def cmd_simulate(args: argparse.Namespace) -> int:
    """``mjwalk simulate``: simulate the batch, write and print its report, then the video
    (``--video``) and motion files (``--export``) of its runs.

    Args:
        args: the parsed ``simulate`` options.

    Returns:
        The exit status, 0.
    """
    check_output_dir(args.out, "--out")
    if args.only_run is not None and args.only_run >= args.runs:
        raise InputError(
            f"--only-run {args.only_run}: runs are numbered 0 to {args.runs - 1} "
            f"(--runs {args.runs})"
        )
    # deferred: mujoco/numba load only for the command that needs them
    from mjwalk.report import format_summary, report_dict, write_report

    batch = _simulate_batch(args)
    if batch is None:
        return 0
    ctx, results = batch
    rep = report_dict(results)  # once: over thousands of runs it takes seconds
    files = write_report(results, args.out, workplace=ctx.workplace, report=rep)
    print(format_summary(rep))
    for name, path in files.items():
        print(f"  wrote {name}: {path}")
    _write_replays(args, ctx, results)
    if args.json_summary:
        print(json.dumps(rep["cycle_time"]))
    return 0


def _simulate_batch(args: argparse.Namespace) -> tuple[Any, list] | None:
    """Check the cycle and simulate its runs, locally or on ``--scheduler``'s Dask cluster;
    returns the cycle context and the results, or None after ``--dry-run``."""
    # deferred: mujoco/numba load only for the command that needs them
    from mjwalk.cycle.context import context_of
    from mjwalk.cycle.simulate import simulate_cycles  # deferred: mujoco/numba, as above
    from mjwalk.cycle.spec import load_cycle_spec  # deferred: mujoco/numba, as above
    from mjwalk.shipped import cycle_file  # deferred: mujoco/numba, as above

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
            return None
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
            return ctx, simulate_cycles(spec, args.runs, **batch)
        import joblib  # deferred: joblib's Dask backend, only with --scheduler

        # the spec goes to the workers in memory; its scene and model files must be at the
        # same paths there (a shared file system), as for any Dask job reading files
        with joblib.parallel_config(backend="dask"):
            return ctx, simulate_cycles(spec, args.runs, **{**batch, "n_jobs": -1})
    finally:
        if client is not None:
            client.close()


def _write_replays(args: argparse.Namespace, ctx, results) -> None:
    """``--video``: the first successful run as ``cycle.mp4``; ``--export bvh/csv``: each
    successful run's motion (:func:`mjwalk.cycle.replay.export_runs`); both in ``--out``."""
    if not (args.video or args.export):
        return
    # deferred: mujoco/numba load only for the command that needs them
    from mjwalk.cycle.replay import export_runs, replay_run

    replayed: dict = {}  # runs simulated again with their timelines, by run index
    if args.video:
        from mjwalk.render import render_video  # deferred: OpenGL, only with --video

        first = next(r for r in results if r.error is None)  # report_dict: at least one
        run0 = replay_run(ctx, args.seed, first.run)
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
        for kind, out in export_runs(ctx, args.seed, results, args.out, args.export, replayed):
            print(f"  wrote {kind}: {out}")


def add_simulate_parser(sub) -> None:
    """Add the ``simulate`` sub-command.

    Args:
        sub: the main parser's sub-parsers (``add_subparsers()``).
    """
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
    p.set_defaults(func=cmd_simulate)
