"""The ``mjwalk`` command line: parses the arguments, calls the library and prints.

One module per command group: :mod:`.planning` (``plan``, ``render``), :mod:`.cycles`
(``simulate``), :mod:`.models` (``train``, ``validate``), :mod:`.scenes` (``scan``,
``scene-import``); :mod:`.scheduler` connects to a Dask cluster.
"""

from __future__ import annotations

import argparse
import os
import sys
import tempfile
import time
from pathlib import Path

from mjwalk import _log
from mjwalk._args import OneLineParser, join_negative_values
from mjwalk._version import __version__
from mjwalk.cli._common import QUIET_HELP
from mjwalk.cli.cycles import add_simulate_parser
from mjwalk.cli.models import add_train_parser, add_validate_parser
from mjwalk.cli.planning import VIDEO_SUFFIXES, add_plan_parser, add_render_parser
from mjwalk.cli.scenes import add_scan_parser, add_scene_import_parser
from mjwalk.errors import MjwalkError

__all__ = ["QUIET_HELP", "VIDEO_SUFFIXES", "build_parser", "main"]


def build_parser() -> argparse.ArgumentParser:
    """The ``mjwalk`` argument parser with all its sub-commands.

    Returns:
        The parser; each sub-command sets ``func``, the function that runs it, and every one
        takes ``--quiet``.
    """
    parser = OneLineParser(
        prog="mjwalk",
        description="Statistically varied human walking and reaching in MuJoCo workplaces.",
    )
    parser.add_argument("--version", action="version", version=f"mjwalk {__version__}")
    sub = parser.add_subparsers(dest="command", required=True)
    add_plan_parser(sub)
    add_simulate_parser(sub)
    add_render_parser(sub)
    add_train_parser(sub)
    add_validate_parser(sub)
    add_scan_parser(sub)
    add_scene_import_parser(sub)
    for cmd in sub.choices.values():
        if not any("--quiet" in a.option_strings for a in cmd._actions):
            cmd.add_argument("--quiet", action="store_true", help=QUIET_HELP)
    return parser


def main(argv: list[str] | None = None) -> int:
    """Run the ``mjwalk`` command.

    Args:
        argv: the arguments after the program name (None: ``sys.argv[1:]``).

    Returns:
        The exit status: 0 on success, 2 for an :class:`~mjwalk.errors.MjwalkError` (printed
        as ``mjwalk: error: ...`` on stderr, as argparse's own errors), 130 when interrupted.
    """
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
        # one line, whatever the message carries (MuJoCo's compiler messages span two)
        text = "; ".join(part.strip() for part in str(exc).splitlines() if part.strip())
        print(f"mjwalk: error: {text}", file=sys.stderr)
        return 2
    except KeyboardInterrupt:
        print("mjwalk: interrupted", file=sys.stderr)
        return 130
    finally:
        os.environ.pop(_log.NOTICE_ENV, None)
        mark.unlink(missing_ok=True)


if __name__ == "__main__":
    sys.exit(main())
