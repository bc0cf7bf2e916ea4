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


def test_cached_machine_code_goes_when_any_source_changes(tmp_path):
    """numba keys a cache by its own file only: an edit to another module whose constants the
    code compiled in must clear it too. A package's cached .nbi/.nbc files are deleted when its
    sources' digest changes, and kept while it does not."""
    from mjwalk._jit import clear_stale_caches

    pkg = tmp_path / "pkg"
    (pkg / "sub" / "__pycache__").mkdir(parents=True)
    (pkg / "a.py").write_text("X = 1\n")
    (pkg / "sub" / "b.py").write_text("Y = 2\n")
    cached = [
        pkg / "sub" / "__pycache__" / "b.f-1.py311.nbi",
        pkg / "sub" / "__pycache__" / "b.f-1.py311.1.nbc",
    ]
    for f in cached:
        f.write_bytes(b"stale")
    assert clear_stale_caches(pkg)  # no digest yet: cleared
    assert not any(f.exists() for f in cached)
    for f in cached:
        f.write_bytes(b"fresh")
    assert not clear_stale_caches(pkg)  # unchanged sources: kept
    assert all(f.exists() for f in cached)
    (pkg / "a.py").write_text("X = 10\n")  # a constant another module compiles in
    assert clear_stale_caches(pkg)
    assert not any(f.exists() for f in cached)
