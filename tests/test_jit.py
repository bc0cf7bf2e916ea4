"""The one-line notice while numba compiles mjwalk's planner (logged once per command)."""

from __future__ import annotations

import logging

import numba

from mjwalk import _jit, _log


def _fresh(module: str):
    def add_one(x):
        return x + 1

    add_one.__module__ = module
    return numba.njit(cache=False)(add_one)


def test_notice_once_when_mjwalk_code_compiles(caplog, monkeypatch):
    monkeypatch.setattr(_jit.NOTICE, "shown", False)
    monkeypatch.delenv(_log.NOTICE_ENV, raising=False)
    caplog.set_level(logging.INFO, logger="mjwalk")
    assert _fresh("someone_else")(1) == 2  # other packages' compilations: no notice
    assert caplog.messages == []
    assert _fresh("mjwalk.plan.probe")(1) == 2
    assert _fresh("mjwalk.plan.probe2")(2) == 3
    assert caplog.messages == [_jit.COMPILE_NOTICE]  # one message, once


def test_notice_once_per_command_across_processes(tmp_path, caplog, monkeypatch):
    """The worker processes of one command share a marker file: the first to compile shows the
    notice, the others (and later compilations) stay quiet."""
    monkeypatch.setenv(_log.NOTICE_ENV, str(tmp_path / "notice"))
    caplog.set_level(logging.INFO, logger="mjwalk")
    assert _log.claim_notice() is True
    assert _log.claim_notice() is False  # another process of the same command
    monkeypatch.setattr(_jit.NOTICE, "shown", False)
    assert _fresh("mjwalk.plan.probe3")(1) == 2
    assert caplog.messages == []
