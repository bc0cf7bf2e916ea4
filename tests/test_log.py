"""mjwalk's messages go through the ``mjwalk`` logger: silent as a library unless the program
configures logging; the command shows INFO, ``--quiet`` only warnings."""

from __future__ import annotations

import logging
import os
import subprocess
import sys

from mjwalk import _log


def test_library_is_silent_until_configured():
    code = "import logging, mjwalk._log as L; L.log.info('progress'); L.log.warning('careful')"
    env = {k: v for k, v in os.environ.items() if k not in (_log.LEVEL_ENV, _log.NOTICE_ENV)}
    res = subprocess.run(
        [sys.executable, "-c", code], capture_output=True, text=True, check=True, env=env
    )
    assert res.stdout == ""
    assert res.stderr.strip() == "careful"  # Python's own last-resort handler: warnings only


def test_command_shows_info_and_quiet_hides_it(capsys, monkeypatch):
    monkeypatch.delenv(_log.LEVEL_ENV, raising=False)
    try:
        _log.configure(quiet=False)
        _log.log.info("building the default model")
        assert capsys.readouterr().err == "[mjwalk] building the default model\n"
        _log.configure(quiet=True)
        _log.log.info("building the default model")
        _log.log.warning("3 runs failed")
        assert capsys.readouterr().err == "[mjwalk] 3 runs failed\n"
    finally:
        for h in list(_log.log.handlers):
            _log.log.removeHandler(h)
        _log.log.setLevel(logging.NOTSET)


def test_worker_processes_inherit_the_command_level():
    code = "import mjwalk._log as L; L.log.info('from a worker')"
    env = {"MJWALK_LOG_LEVEL": "INFO", "PATH": ""}
    res = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, env=env)
    assert res.stderr == "[mjwalk] from a worker\n"
    env["MJWALK_LOG_LEVEL"] = "WARNING"
    res = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, env=env)
    assert res.stderr == ""
