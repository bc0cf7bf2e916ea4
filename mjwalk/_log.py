"""mjwalk's messages: one :mod:`logging` logger, ``"mjwalk"``.

The library never prints its progress; it logs to ``logging.getLogger("mjwalk")`` (INFO for
progress, WARNING for what a user should act on). A program that uses mjwalk decides what to
show, as with any library: with no logging configured, Python shows warnings and drops
progress. The ``mjwalk`` command shows INFO by default (``--quiet``: warnings only) through
:func:`configure`, which also hands the same choice to the worker processes a batch starts
(joblib's workers import mjwalk afresh and read :data:`LEVEL_ENV`).
"""

from __future__ import annotations

import logging
import os
import sys

log = logging.getLogger("mjwalk")

#: Environment variable carrying the command's log level to worker processes.
LEVEL_ENV = "MJWALK_LOG_LEVEL"
#: Environment variable naming a marker file: the first process of one command that creates it
#: shows a once-per-command notice (the numba compile notice), the others stay quiet.
NOTICE_ENV = "MJWALK_NOTICE_MARK"

_FORMAT = "[mjwalk] %(message)s"


class _StderrHandler(logging.StreamHandler):
    """Writes to whatever ``sys.stderr`` is at the time of each message (a handler holding the
    stream of its creation would write to a closed or replaced stream later)."""

    def __init__(self) -> None:
        super().__init__(sys.stderr)

    @property
    def stream(self):
        return sys.stderr

    @stream.setter
    def stream(self, value) -> None:
        pass


def _install_handler(level: int) -> None:
    handler = next((h for h in log.handlers if isinstance(h, _StderrHandler)), None)
    if handler is None:
        handler = _StderrHandler()
        handler.setFormatter(logging.Formatter(_FORMAT))
        log.addHandler(handler)
    handler.setLevel(level)
    log.setLevel(level)


def configure(quiet: bool = False) -> None:
    """Show mjwalk's messages on stderr: INFO and above, or WARNING and above when ``quiet``;
    worker processes started after this call show the same."""
    level = logging.WARNING if quiet else logging.INFO
    os.environ[LEVEL_ENV] = logging.getLevelName(level)
    _install_handler(level)


def claim_notice() -> bool:
    """True for the first caller in this command (all its processes) when :data:`NOTICE_ENV`
    names a marker file, else True once per process (the caller keeps that state)."""
    mark = os.environ.get(NOTICE_ENV)
    if not mark:
        return True
    try:
        fd = os.open(mark, os.O_CREAT | os.O_EXCL | os.O_WRONLY)
    except FileExistsError:
        return False
    except OSError:
        return True
    os.close(fd)
    return True


# A worker process of a configured command: show what the command shows.
if os.environ.get(LEVEL_ENV) in ("INFO", "WARNING") and not log.handlers:
    _install_handler(logging.getLevelName(os.environ[LEVEL_ENV]))
