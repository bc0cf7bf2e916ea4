"""The ``mjwalk`` command line."""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

from mjwalk.errors import MjwalkError


def _cmd_plan(args: argparse.Namespace) -> int:
    from mjwalk.plan.grid import plan_grid
    from mjwalk.plot import save_plan_png
    from mjwalk.world import load_workplace

    workplace = load_workplace(args.scene)
    baseline = plan_grid(workplace, args.start, args.goal, radius=args.radius)
    print(
        f"grid A*  {args.start} -> {args.goal}: length {baseline.length:.3f} m, "
        f"{baseline.meta['expansions']} expansions, {1000 * baseline.meta['seconds']:.1f} ms"
    )
    if args.png:
        save_plan_png(
            args.png,
            workplace,
            [],
            baseline=baseline,
            title=f"{workplace.name}: {args.start} -> {args.goal}",
        )
        print(f"wrote {args.png}")
    return 0


def build_parser() -> argparse.ArgumentParser:
    parser = argparse.ArgumentParser(
        prog="mjwalk",
        description="Statistically varied human walking and reaching in MuJoCo workplaces.",
    )
    sub = parser.add_subparsers(dest="command", required=True)

    p = sub.add_parser("plan", help="plan a walk between two points or sites of a scene")
    p.add_argument("scene", type=Path, help="MJCF scene file")
    p.add_argument("--from", dest="start", required=True, help="start: X,Y (metres) or a site name")
    p.add_argument("--to", dest="goal", required=True, help="goal: X,Y (metres) or a site name")
    p.add_argument("--radius", type=float, default=0.25, help="body radius in metres (0.25)")
    p.add_argument("--png", type=Path, help="write a top-view PNG of the plan here")
    p.set_defaults(func=_cmd_plan)
    return parser


def main(argv: list[str] | None = None) -> int:
    parser = build_parser()
    args = parser.parse_args(argv)
    try:
        return args.func(args)
    except MjwalkError as exc:
        print(f"mjwalk: error: {exc}", file=sys.stderr)
        return 2
    except KeyboardInterrupt:
        print("mjwalk: interrupted", file=sys.stderr)
        return 130


if __name__ == "__main__":
    sys.exit(main())
