"""The one-line notice while numba compiles mjwalk's planner (logged once per command), the
stale-cache clearing, and one compile of a kernel when two processes miss the cache at once."""

from __future__ import annotations

import logging
import os
import subprocess
import sys
import time
from pathlib import Path

import numba
import pytest

from mjwalk import _jit, _log

ROOT = Path(__file__).resolve().parents[1]


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


#: A kernel that takes numba a while to compile (0.5-1 s here): two processes that call it at
#: once are both still compiling when the other looks in the cache, unless one waits.
_KERNEL = """
import numpy as np

from mjwalk._jit import njit


@njit
def busy(n):
    a = np.zeros((n, n))
    for i in range(n):
        for j in range(n):
            a[i, j] = np.sin(i) * np.cos(j) + np.sqrt(i + j + 1.0)
    s = np.sort(a.ravel())
    c = np.cumsum(s)
    return c[-1] + np.linalg.norm(a) + np.median(s) + np.std(a)
"""

#: One racer: imports the kernel, waits for the ``go`` file, calls it, prints its cache misses
#: and hits.
_RACER = """
import os, sys, time
import kernel
while not os.path.exists(sys.argv[1]):
    time.sleep(0.001)
kernel.busy(4)
s = kernel.busy.stats
print(sum(s.cache_misses.values()), sum(s.cache_hits.values()))
"""


@pytest.mark.slow  # two fresh interpreters importing numba and mjwalk: 5-15 s wall
def test_two_processes_missing_the_cache_at_once_compile_a_kernel_once(tmp_path):
    """On a fresh install two processes (pytest's workers, ``simulate --jobs 2``) that need a
    kernel at the same moment: one compiles it, the other waits and loads the cached machine
    code (without the compile lock both compile it: two misses)."""
    (tmp_path / "kernel.py").write_text(_KERNEL)
    (tmp_path / "racer.py").write_text(_RACER)
    go = tmp_path / "go"
    env = dict(os.environ, PYTHONPATH=os.pathsep.join([str(ROOT), str(tmp_path)]))
    racers = [
        subprocess.Popen(
            [sys.executable, "racer.py", str(go)],
            cwd=tmp_path,
            env=env,
            stdout=subprocess.PIPE,
            text=True,
        )
        for _ in range(2)
    ]
    time.sleep(0.5)  # both import numba and mjwalk (they poll for the go file meanwhile)
    go.write_text("")
    counts = [tuple(map(int, r.communicate(timeout=120)[0].split())) for r in racers]
    assert all(r.returncode == 0 for r in racers)
    assert sorted(counts) == [(0, 1), (1, 0)]  # one compiled (a miss), one loaded (a hit)
