"""The Dask scheduler check of ``mjwalk simulate --scheduler`` (mjwalk.cli.scheduler); the
refusals of servers that are not Dask are in tests/test_bad_input_cli.py."""

from __future__ import annotations

import time

import pytest

from mjwalk.cli.scheduler import SCHEDULER_TIMEOUT_S, SchedulerError, parse_scheduler_address


@pytest.mark.parametrize(
    ("address", "expected"),
    [
        ("tcp://10.0.0.5:8786", ("10.0.0.5", 8786)),
        ("  node1:8786 ", ("node1", 8786)),
        ("TCP://[::1]:8786", ("::1", 8786)),
    ],
)
def test_parse_scheduler_address(address, expected):
    assert parse_scheduler_address(address) == expected


@pytest.mark.parametrize(
    ("address", "cause"),
    [
        ("http://node1:8786", "over tcp:// only"),
        ("node1", "no port"),
        ("node1:0", "not a port number"),
        ("node1:x", "is not a number"),
        (":8786", "no host"),
        ("node1:8786/x", "nothing may follow the port"),
    ],
)
def test_malformed_addresses_are_refused(address, cause):
    with pytest.raises(SchedulerError, match=cause):
        parse_scheduler_address(address)


def test_a_real_scheduler_passes_the_check():
    """The check accepts what a real scheduler sends (in-process, no workers), at once."""
    distributed = pytest.importorskip("distributed")
    from mjwalk.cli.scheduler import dask_client, probe_scheduler

    with distributed.LocalCluster(
        n_workers=0, processes=False, protocol="tcp", host="127.0.0.1", dashboard_address=None
    ) as cluster:
        t0 = time.perf_counter()
        left = probe_scheduler(cluster.scheduler_address)
        assert time.perf_counter() - t0 < 2.0
        assert left > SCHEDULER_TIMEOUT_S - 2.0
        client = dask_client(cluster.scheduler_address)
        try:
            assert client.scheduler_info()["type"] == "Scheduler"
        finally:
            client.close()
