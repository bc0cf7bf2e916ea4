"""simulate_cycles on a real dask.distributed cluster equals the local joblib run (issue 17,
item 4). Needs the ``cluster`` extra (in ``test`` too); skips cleanly without it."""

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
