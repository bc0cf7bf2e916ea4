"""Warm workers for a batch of cycles: processes forked from the one that prepared the cycle.

A joblib (loky) worker is a fresh interpreter: before its first run it imports mjwalk (numba,
scipy, scikit-learn, MuJoCo; about 2 s on a quiet machine, 4-10 s on a loaded one), prepares
the spec's context (scene, models, humanoid) and, in its first cycle, loads every compiled
kernel from numba's cache (1.3 s against 0.5 s for a later cycle). On two cores that start-up
is as long as a batch of dozens of cycles, so ``--jobs 2`` stayed far below twice one job's
rate. A worker forked from the process that already holds the prepared context and has
already run a cycle starts with all of it (copy-on-write pages, no import, no preparation, no
kernel loading): :func:`forked_workers` says when a batch can run that way, :func:`map_forked`
runs it.

Only where the user left joblib's backend alone (no ``joblib.parallel_config(backend=...)``:
a Dask or Ray cluster, or loky named on purpose, keeps its backend), where the platform forks
safely (Linux: macOS's system libraries are not fork-safe, Windows cannot fork) and where this
process may have children (not a daemonic worker itself). Results do not depend on it: run
``k`` draws from its own seed whichever process runs it.
"""

from __future__ import annotations

import multiprocessing
import sys
from collections.abc import Callable, Iterator, Sequence
from concurrent.futures import ProcessPoolExecutor
from typing import TypeVar

import joblib
import joblib.parallel
from joblib.parallel import ParallelBackendBase

T = TypeVar("T")
R = TypeVar("R")


def user_backend() -> bool:
    """Whether the caller chose joblib's backend (``joblib.parallel_config(backend=...)`` or
    ``joblib.parallel_backend(...)`` around the call: Dask, Ray, or loky named on purpose).

    Returns:
        True when a backend is configured in this thread, False for joblib's default.
    """
    config = getattr(joblib.parallel._backend, "config", None)  # joblib's thread-local config
    return isinstance(config, dict) and isinstance(config.get("backend"), ParallelBackendBase)


def forked_workers(n_jobs: int, runs: int) -> int:
    """How many forked workers run a batch of ``runs`` runs with ``n_jobs`` (joblib's meaning:
    -1 all cores, -2 all but one), or 0 when joblib runs it (one job, a single run, a backend
    the user chose, a platform without a safe fork, a daemonic process).

    Args:
        n_jobs: the batch's number of jobs, as joblib reads it.
        runs: how many runs the batch has.

    Returns:
        The number of worker processes to fork (>= 2), or 0.
    """
    if runs < 2 or user_backend() or not sys.platform.startswith("linux"):
        return 0
    if "fork" not in multiprocessing.get_all_start_methods():
        return 0
    if multiprocessing.current_process().daemon:  # a daemon may not have children
        return 0
    jobs = int(joblib.effective_n_jobs(n_jobs))
    return min(jobs, runs - 1) if jobs >= 2 else 0


def map_forked(fn: Callable[[T], R], items: Sequence[T], workers: int) -> Iterator[R]:
    """``fn`` of each item, in order: the first in this process (it loads what the later ones
    reuse: the compiled kernels, the caches of ``fn``), the others in ``workers`` processes
    forked after it, one item at a time (the runs' costs differ; a result is about 0.1 MB).

    Args:
        fn: a module-level function (sent to the workers by name).
        items: its arguments, one per call (sent pickled).
        workers: how many processes to fork (>= 1).

    Returns:
        An iterator over ``fn(item)`` in the order of ``items``; the first exception a call
        raises is raised when its result is reached (the other workers are stopped).
    """
    if not items:
        return
    yield fn(items[0])  # warms this process before the workers copy it
    if len(items) == 1:
        return
    context = multiprocessing.get_context("fork")
    pool = ProcessPoolExecutor(max_workers=workers, mp_context=context)
    try:
        yield from pool.map(fn, items[1:], chunksize=1)
    finally:
        pool.shutdown(wait=True, cancel_futures=True)
