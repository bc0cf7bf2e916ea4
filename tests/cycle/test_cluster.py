"""simulate_cycles on a real dask.distributed cluster equals the local joblib run, from Python
and from ``mjwalk simulate --scheduler``. Needs the ``cluster`` extra (in ``test`` too); skips
cleanly without it."""

from __future__ import annotations

import os

import pytest

distributed = pytest.importorskip("distributed", reason="the 'cluster' extra is not installed")


@pytest.mark.slow
def test_local_cluster_equals_local_run(scenes_dir):
    import joblib

    from mjwalk.cycle.simulate import simulate_cycles

    spec = scenes_dir / "assembly_station.toml"
    runs, seed = 3, 3
    local = simulate_cycles(spec, runs, seed=seed, n_jobs=1, collisions=False)
    with (
        distributed.LocalCluster(
            n_workers=2,
            threads_per_worker=1,
            processes=True,
            host="127.0.0.1",
            dashboard_address=None,
        ) as cluster,
        distributed.Client(cluster) as client,
    ):
        workers = set(client.scheduler_info()["workers"])
        pids = set(client.run(os.getpid).values())
        assert len(pids) == 2 and os.getpid() not in pids  # two worker processes
        with (
            distributed.get_task_stream(client) as stream,
            joblib.parallel_config(backend="dask"),
        ):
            remote = simulate_cycles(spec, runs, seed=seed, n_jobs=-1, collisions=False)
    # the runs went to the cluster's workers...
    assert len(workers) == 2
    assert {t["worker"] for t in stream.data} <= workers
    assert len(stream.data) >= 1
    # ... and gave the local run's cycles exactly
    assert [r.run for r in remote] == list(range(runs))
    assert [r.entropy for r in remote] == [[seed, k] for k in range(runs)]
    assert [r.cycle_time for r in remote] == [r.cycle_time for r in local]
    assert [[w.length for w in r.walks] for r in remote] == [
        [w.length for w in r.walks] for r in local
    ]


@pytest.mark.slow
def test_cli_scheduler_option_equals_local_run(scenes_dir, tmp_path, capsys):
    """``mjwalk simulate --scheduler ADDRESS`` sends the runs to an existing cluster and writes
    the same cycles and walks as the local run of the same seed."""
    from mjwalk.cli import main

    spec = str(scenes_dir / "assembly_station.toml")
    common = ["simulate", spec, "--runs", "2", "--seed", "5", "--quiet"]
    assert main([*common, "--jobs", "1", "--out", str(tmp_path / "local")]) == 0
    with distributed.LocalCluster(
        n_workers=2, threads_per_worker=1, processes=True, host="127.0.0.1", dashboard_address=None
    ) as cluster:
        address = cluster.scheduler_address
        argv = [*common, "--scheduler", address, "--out", str(tmp_path / "remote")]
        assert main(argv) == 0
    for name in ("cycles.csv", "walks.csv"):
        assert (tmp_path / "remote" / name).read_text() == (tmp_path / "local" / name).read_text()


def test_cli_scheduler_that_does_not_answer_is_one_line_before_work(scenes_dir, tmp_path, capsys):
    """Nothing listens at the address: one line naming the refused connection, at once (the
    other refusals, a peer that is not Dask among them: tests/test_bad_input_cli.py)."""
    import time

    from mjwalk.cli import main
    from mjwalk.cli.scheduler import SCHEDULER_TIMEOUT_S

    spec = str(scenes_dir / "assembly_station.toml")
    out = tmp_path / "out"
    argv = ["simulate", spec, "--runs", "2", "--out", str(out), "--scheduler", "tcp://127.0.0.1:9"]
    t0 = time.perf_counter()
    assert main(argv) == 2
    assert time.perf_counter() - t0 < SCHEDULER_TIMEOUT_S
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and "--scheduler tcp://127.0.0.1:9: connection refused" in err[0], err
    assert not out.exists() or not any(out.iterdir())
