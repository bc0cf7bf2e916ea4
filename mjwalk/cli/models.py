"""The ``mjwalk train`` and ``mjwalk validate`` commands: step models from capture
(:mod:`mjwalk.gait.training`), and the walker options ``plan`` and ``validate`` share."""

from __future__ import annotations

import argparse
from pathlib import Path

from mjwalk._args import (
    arg_fraction,
    arg_positive_float,
    arg_positive_int,
    arg_seed,
    check_output_file,
)
from mjwalk.errors import MjwalkError


def add_walker_args(p: argparse.ArgumentParser) -> None:
    """Add the walker options shared by ``plan`` and ``validate`` (:class:`mjwalk.Walker`).

    Args:
        p: the sub-command's parser.
    """
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


def walker_from_args(args: argparse.Namespace):
    """The walker the options describe, checked before any work.

    Args:
        args: parsed options with ``walker``, ``speed``, ``cadence``, ``stature``, ``step_width``.

    Returns:
        The :class:`~mjwalk.gait.walker.Walker`, or None when no option is given.

    Raises:
        WalkerError: a figure is out of range or the preset is unknown (naming it).
    """
    from mjwalk.gait.walker import Walker  # deferred: keeps `mjwalk --help` from loading gait

    given = {
        k: getattr(args, k)
        for k in ("speed", "cadence", "stature", "step_width")
        if getattr(args, k, None) is not None
    }
    if args.walker:
        return Walker.preset(args.walker, **given)
    return Walker(**given) if given else None


def cmd_train(args: argparse.Namespace) -> int:
    """``mjwalk train``: train a step model and save it
    (:func:`mjwalk.gait.training.train_model_file`).

    Args:
        args: the parsed ``train`` options.

    Returns:
        The exit status, 0.
    """
    # deferred: scipy/numba load only for the command that needs them
    from mjwalk.gait.training import CaptureFiles, train_model_file

    if args.amc and not args.asf:
        raise MjwalkError("train: --amc needs --asf")
    check_output_file(args.output, "-o/--output")
    train_model_file(
        args.output,
        CaptureFiles(bvh=args.bvh, amc=args.amc, asf=args.asf, skeleton=args.skeleton),
        virtual=args.virtual,
        seed=args.seed,
        variance=args.pca_variance,
    )
    print(f"wrote {args.output}")
    return 0


def cmd_validate(args: argparse.Namespace) -> int:
    """``mjwalk validate``: compare a step model with capture and print the table
    (:func:`mjwalk.gait.training.validate_model_file`).

    Args:
        args: the parsed ``validate`` options.

    Returns:
        The exit status, 0.
    """
    # deferred: scipy/numba load only for the command that needs them
    from mjwalk.gait.fidelity import format_fidelity_table
    from mjwalk.gait.training import CaptureFiles, validate_model_file  # deferred: numba
    from mjwalk.plan.walktimes import planned_straight_walks  # deferred: numba/mujoco

    if args.json:
        check_output_file(args.json, "--json")
    walker = walker_from_args(args)
    report = validate_model_file(
        args.model,
        CaptureFiles.of_glob(args.against, asf=args.asf, skeleton=args.skeleton),
        args.json,
        seed=args.seed,
        walker=walker,
        planned_walks=planned_straight_walks,
    )
    print(format_fidelity_table(report))
    return 0


def add_train_parser(sub) -> None:
    """Add the ``train`` sub-command.

    Args:
        sub: the main parser's sub-parsers (``add_subparsers()``).
    """
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
    p.add_argument(
        "--skeleton",
        help="bandai, cmu, cmu_bvh, a convention (humanik, lafan1, xsens_mvn, rokoko), or a "
        "map file .toml naming pelvis/hips/ankles/toes, units, up (default: detected from the "
        "joint names; units and up axis read from the body)",
    )
    p.add_argument("--seed", type=arg_seed, default=0)
    p.add_argument("-o", "--output", type=Path, required=True, help="model file to write")
    p.set_defaults(func=cmd_train)


def add_validate_parser(sub) -> None:
    """Add the ``validate`` sub-command.

    Args:
        sub: the main parser's sub-parsers (``add_subparsers()``).
    """
    p = sub.add_parser("validate", help="compare a step model with captured walking")
    p.add_argument("model", type=Path, nargs="?", help="model file (default: built-in model)")
    p.add_argument("--against", required=True, help="glob of BVH (or AMC, with --asf) files")
    p.add_argument("--asf", help="ASF skeleton for AMC files")
    p.add_argument(
        "--skeleton",
        help="bandai, cmu, cmu_bvh, a convention (humanik, lafan1, xsens_mvn, rokoko), or a "
        "map file .toml naming pelvis/hips/ankles/toes, units, up (default: detected from the "
        "joint names; units and up axis read from the body)",
    )
    p.add_argument("--json", type=Path, help="write the report as JSON here")
    p.add_argument("--seed", type=arg_seed, default=0)
    add_walker_args(p)
    p.set_defaults(func=cmd_validate)
