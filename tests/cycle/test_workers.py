"""Warm workers: when a batch forks its workers, that they keep the order, run the first item in
this process and raise a worker's error, and that a batch gives the same cycles forked, in one
job and under a backend the caller chose."""

from __future__ import annotations

import os
import sys

import joblib
import pytest

from mjwalk.cycle.simulate import simulate_cycles
from mjwalk.cycle.workers import forked_workers, map_forked, user_backend

linux = pytest.mark.skipif(not sys.platform.startswith("linux"), reason="forked workers: Linux")


def _pid_and_square(x: int) -> tuple[int, int]:
    return os.getpid(), x * x


def _fail_on_three(x: int) -> int:
    if x == 3:
        raise ValueError("three")
    return x


def test_user_backend_is_seen():
    assert not user_backend()
    with joblib.parallel_config(n_jobs=3):  # a job count alone chooses no backend
        assert not user_backend()
    with joblib.parallel_config(backend="threading"):
        assert user_backend()
        assert forked_workers(2, 10) == 0
    assert not user_backend()


@linux
def test_how_many_workers_fork():
    assert forked_workers(1, 10) == 0  # one job: joblib runs it here
    assert forked_workers(2, 1) == 0  # a single run: no worker
    assert forked_workers(2, 10) == 2
    assert forked_workers(4, 3) == 2  # the first run is this process's: two left
    assert forked_workers(-1, 100) == joblib.cpu_count() or joblib.cpu_count() == 1


@linux
def test_map_forked_keeps_order_and_runs_the_first_here():
    out = list(map_forked(_pid_and_square, list(range(7)), 2))
    assert [sq for _, sq in out] == [x * x for x in range(7)]
    assert out[0][0] == os.getpid()  # the first warms this process
    assert all(pid != os.getpid() for pid, _ in out[1:])


@linux
def test_map_forked_raises_a_workers_error():
    with pytest.raises(ValueError, match="three"):
        list(map_forked(_fail_on_three, list(range(6)), 2))


@linux
def test_forked_batch_equals_one_job_and_a_chosen_backend(scenes_dir):
    spec = scenes_dir / "assembly_station.toml"
    forked = simulate_cycles(spec, runs=3, seed=7, n_jobs=2, collisions=False)
    one = simulate_cycles(spec, runs=3, seed=7, n_jobs=1, collisions=False)
    with joblib.parallel_config(backend="threading"):
        chosen = simulate_cycles(spec, runs=3, seed=7, n_jobs=2, collisions=False)
    for other in (one, chosen):
        assert [r.cycle_time for r in forked] == [r.cycle_time for r in other]
        assert [[w.length for w in r.walks] for r in forked] == [
            [w.length for w in r.walks] for r in other
        ]
    assert [r.run for r in forked] == [0, 1, 2]


def test_runs_sharing_a_process_through_threads_take_turns(scenes_dir, monkeypatch):
    """Under a thread backend the runs share this process (its compiled kernels run without the
    GIL over per-process state): one cycle at a time, the same cycles as one job."""
    import threading
    import time

    import mjwalk.cycle.simulate as sim

    inside, most, lock = [0], [0], threading.Lock()
    real = sim.simulate_cycle

    def counted(*args, **kwargs):
        with lock:
            inside[0] += 1
            most[0] = max(most[0], inside[0])
        try:
            time.sleep(0.05)  # room for another thread to come in, if it could
            return real(*args, **kwargs)
        finally:
            with lock:
                inside[0] -= 1

    monkeypatch.setattr(sim, "simulate_cycle", counted)
    spec = scenes_dir / "assembly_station.toml"
    with joblib.parallel_config(backend="threading"):
        threaded = simulate_cycles(spec, runs=4, seed=3, n_jobs=4, collisions=False)
    assert most[0] == 1
    one = simulate_cycles(spec, runs=4, seed=3, n_jobs=1, collisions=False)
    assert [r.cycle_time for r in threaded] == [r.cycle_time for r in one]
