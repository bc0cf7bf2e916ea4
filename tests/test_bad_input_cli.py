# ruff: noqa: F811  (the fixtures imported from test_bad_input are pytest arguments)
"""Bad input of issue 45, deliverable 4, on the command line: a ``--scheduler`` that is not
Dask (an HTTP server, a peer that resets or answers garbage), malformed scheduler addresses, a
takt no cycle can meet, a model cache that is a file or read-only, and argument-parser errors.
Each is refused with exit status 2 and ONE line on stderr naming the cause, before any work and
within a bounded time (the scheduler's: :data:`~mjwalk.cli.scheduler.SCHEDULER_TIMEOUT_S`).

The servers are real sockets on free local ports, started by each test in a thread.
"""

from __future__ import annotations

import argparse
import http.server
import os
import socket
import struct
import threading
import time
from contextlib import contextmanager, suppress

import pytest
from test_bad_input import no_work, refused  # noqa: F401 (fixtures)

from mjwalk import cli
from mjwalk.cli.scheduler import SCHEDULER_TIMEOUT_S
from mjwalk.errors import CycleSpecError, WriteError

#: Slack over the scheduler's time limit for a refusal (s): parsing the command and importing
#: distributed on a loaded 2-core machine.
SLACK = 3.0


def one_line_refusal(argv, capsys, limit: float) -> tuple[str, float]:
    """Run the CLI on ``argv``: assert exit status 2 within ``limit`` seconds and exactly one
    line on stderr; return that line and the seconds taken."""
    t0 = time.perf_counter()
    try:
        code = cli.main([str(a) for a in argv])
    except SystemExit as exc:  # the parser's refusals
        code = exc.code
    seconds = time.perf_counter() - t0
    err = capsys.readouterr().err
    lines = err.strip().splitlines()
    assert code == 2, err
    assert len(lines) == 1, err
    assert lines[0].startswith("mjwalk: error: "), err
    assert seconds < limit, f"refused after {seconds:.1f} s: {err}"
    return lines[0], seconds


def _free_port() -> int:
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


@contextmanager
def _peer(answer: bytes | None):
    """A TCP server on a free local port. ``answer`` None: it accepts each connection and
    resets it at once (SO_LINGER 0: an RST, not a FIN); else it reads what the client sends
    first, answers ``answer`` and closes (as a proxy or an HTTP server answers a request it
    cannot parse). Yields its tcp:// address."""
    server = socket.socket()
    server.bind(("127.0.0.1", 0))
    server.listen(8)
    server.settimeout(0.2)
    stop = threading.Event()

    def serve() -> None:
        while not stop.is_set():
            try:
                conn, _ = server.accept()
            except TimeoutError:
                continue
            if answer is None:
                conn.setsockopt(socket.SOL_SOCKET, socket.SO_LINGER, struct.pack("ii", 1, 0))
            else:
                conn.settimeout(2.0)
                with suppress(OSError):
                    conn.recv(1 << 16)
                    conn.sendall(answer)
            conn.close()

    thread = threading.Thread(target=serve, daemon=True)
    thread.start()
    try:
        yield f"tcp://127.0.0.1:{server.getsockname()[1]}"
    finally:
        stop.set()
        thread.join(5)
        server.close()


def _simulate(address: str, tmp_path):
    return ["simulate", "station", "--runs", "2", "--out", tmp_path / "out", "--scheduler", address]


# ------------------------------------------------------------------ --scheduler


@pytest.mark.slow  # among the fast tier's longest in a quiet warm run (9-10 s): its 5 min budget
def test_http_server_is_not_a_scheduler(capsys, no_work, tmp_path):
    """An HTTP server accepts and waits for a request line forever: before, mjwalk hung past
    120 s; now it names the peer as not Dask once the time promised is up."""
    pytest.importorskip("distributed")

    class Quiet(http.server.SimpleHTTPRequestHandler):
        def log_message(self, *args) -> None:
            pass

    server = http.server.ThreadingHTTPServer(("127.0.0.1", 0), Quiet)
    server.daemon_threads = True
    thread = threading.Thread(target=server.serve_forever, daemon=True)
    thread.start()
    try:
        address = f"tcp://127.0.0.1:{server.server_address[1]}"
        line, seconds = one_line_refusal(
            _simulate(address, tmp_path), capsys, SCHEDULER_TIMEOUT_S + SLACK
        )
    finally:
        server.shutdown()
        server.server_close()
    assert f"--scheduler {address} is not a Dask scheduler" in line
    assert f"no Dask handshake within {SCHEDULER_TIMEOUT_S:.0f} s" in line
    assert seconds >= SCHEDULER_TIMEOUT_S - 0.5  # it waited for the greeting, not less
    assert not (tmp_path / "out").exists()


@pytest.mark.parametrize(
    ("answer", "cause"),
    [
        (None, "the connection without a Dask handshake"),  # reset, or closed
        # what distributed read as a 3.07 EiB frame (a proxy's answer)
        (b"HTTP/1.1 400 Bad Request\r\n\r\n", "it answered 'HTTP/1.1 400 Bad Request'"),
        (b"\x10\x00\x00\x00\x00\x00\x00\x00garbage!garbage!", "not a Dask handshake"),
    ],
)
def test_peer_that_resets_or_answers_garbage(answer, cause, capsys, no_work, tmp_path):
    pytest.importorskip("distributed")
    with _peer(answer) as address:
        line, _ = one_line_refusal(_simulate(address, tmp_path), capsys, SLACK + 2.0)
    assert f"--scheduler {address} is not a Dask scheduler" in line
    assert cause in line
    assert "MemoryError" not in line and "EiB" not in line


@pytest.mark.parametrize(
    ("address", "cause"),
    [
        ("localhost", "malformed address: no port"),
        ("tcp://127.0.0.1", "malformed address: no port"),
        ("tcp://127.0.0.1:port", "malformed address: port 'port' is not a number"),
        ("tcp://127.0.0.1:99999", "malformed address: port 99999 is not a port number"),
        ("tcp://:8786", "malformed address: no host"),
        ("tcp://127.0.0.1:8786/x", "malformed address: nothing may follow the port"),
        ("tls://127.0.0.1:8786", "over tcp:// only, not tls://"),
        ("tcp://no-such-host.invalid:8786", "host 'no-such-host.invalid' not found"),
    ],
)
def test_malformed_addresses_say_what_is_wrong(address, cause, capsys, no_work, tmp_path):
    """Before, each said "no Dask scheduler answered within 10 s" with the cause in brackets."""
    pytest.importorskip("distributed")
    line, _ = one_line_refusal(_simulate(address, tmp_path), capsys, SCHEDULER_TIMEOUT_S + SLACK)
    assert cause in line
    assert "answered within" not in line


def test_refused_connection_is_named_at_once(capsys, no_work, tmp_path):
    """Nothing listens: "connection refused" at once (distributed retried for the whole 10 s
    and then called it a time-out)."""
    pytest.importorskip("distributed")
    port = _free_port()
    line, _ = one_line_refusal(_simulate(f"tcp://127.0.0.1:{port}", tmp_path), capsys, SLACK)
    assert f"connection refused: nothing listens on port {port}" in line


# ------------------------------------------------------------------ takt


@pytest.mark.parametrize(
    ("takt", "extra", "cause"),
    [
        ("1e-9", "", "1e-09 s is shorter than any cycle can be (at least 1 s"),
        ("0.5", "", "0.5 s is shorter than any cycle can be"),
        ("20.0", '[[task]]\nkind = "wait"\nduration = 30.0\n', "the cycle's waits alone (30 s)"),
    ],
)
def test_takt_no_cycle_can_meet(takt, extra, cause, scenes_dir, tmp_path, capsys, no_work):
    """Before, ``takt = 1e-9`` ran and reported 100 % of cycles over takt."""
    text = (scenes_dir / "assembly_station.toml").read_text()
    text = text.replace(
        'scene = "assembly_station.xml"', f'scene = "{scenes_dir}/assembly_station.xml"'
    )
    lines = text.splitlines()
    at = next(i for i, t in enumerate(lines) if t.startswith("takt = "))
    lines[at] = f"takt = {takt}"
    spec = tmp_path / "cycle.toml"
    spec.write_text("\n".join(lines) + "\n" + extra)
    err = refused(["simulate", spec, "--out", tmp_path / "out", "--dry-run"], capsys, tmp_path)
    assert err.count("\n") == 1
    assert f"{spec}:{at + 1}: key 'takt' at the top level: " in err and cause in err


def test_takt_of_a_second_is_accepted(scenes_dir, tmp_path):
    from mjwalk.cycle.spec import load_cycle_spec

    text = (scenes_dir / "assembly_station.toml").read_text()
    text = text.replace(
        'scene = "assembly_station.xml"', f'scene = "{scenes_dir}/assembly_station.xml"'
    )
    path = tmp_path / "cycle.toml"
    path.write_text(text.replace("takt = 90.0", "takt = 1.0"))
    assert load_cycle_spec(path).takt == 1.0
    path.write_text(text.replace("takt = 90.0", "takt = 0.99"))
    with pytest.raises(CycleSpecError, match="takt"):
        load_cycle_spec(path)


# ------------------------------------------------------------------ model cache


class TrainingStarted(AssertionError):
    pass


@pytest.fixture
def no_training(monkeypatch):
    """Fail the test if the default step or reach model starts to be built."""
    import mjwalk.arms.reachgen
    import mjwalk.gait.corpus

    def fail(*args, **kwargs):
        raise TrainingStarted("a default model was built before the cache was checked")

    monkeypatch.setattr(mjwalk.gait.corpus, "generate_corpus", fail)
    monkeypatch.setattr(mjwalk.arms.reachgen, "generate", fail)


def _unwritable(kind: str, tmp_path):
    if kind == "file":
        path = tmp_path / "f"
        path.write_text("not a folder")
        return path, "it is a file, not a folder"
    if kind == "under a file":
        (tmp_path / "f").write_text("not a folder")
        return tmp_path / "f" / "cache", f"{tmp_path / 'f'} is a file"
    if kind == "read-only folder":
        if os.geteuid() == 0:
            pytest.skip("root writes into read-only folders")
        locked = tmp_path / "locked"
        locked.mkdir()
        locked.chmod(0o500)
        return locked, f"{locked} is not writable"
    if not os.path.isdir("/proc/self"):
        pytest.skip("no /proc: no folder even root cannot write into")
    return "/proc/mjwalk-cache", "/proc is not writable"


@pytest.mark.parametrize("kind", ["file", "under a file", "read-only folder", "/proc"])
def test_cache_that_cannot_be_written_is_refused_before_training(
    kind, capsys, no_work, no_training, tmp_path, monkeypatch
):
    """Before: a cache path that is a file trained 24 s, then "File exists"; a read-only empty
    cache trained 26 s, then "Read-only file system"."""
    cache, cause = _unwritable(kind, tmp_path)
    monkeypatch.setenv("MJWALK_CACHE", str(cache))
    argv = ["plan", "station", "--from", "stand_rack2", "--to", "stand_car1", "--n", "1"]
    line, _ = one_line_refusal(argv, capsys, 10.0)
    assert f"$MJWALK_CACHE={cache}: cannot hold the default step model: " in line
    assert cause in line
    if kind == "read-only folder":
        (tmp_path / "locked").chmod(0o700)


def test_reach_model_cache_is_checked_before_building(no_training, tmp_path, monkeypatch):
    from mjwalk.arms.reachdefault import default_reach_model

    (tmp_path / "f").write_text("not a folder")
    monkeypatch.setenv("MJWALK_CACHE", str(tmp_path / "f"))
    with pytest.raises(WriteError, match="cannot hold the default reach model: it is a file"):
        default_reach_model(progress=False)


def test_writable_cache_is_accepted(tmp_path, monkeypatch):
    from mjwalk._io import check_cache_writable

    monkeypatch.setenv("MJWALK_CACHE", str(tmp_path / "new" / "cache"))
    assert check_cache_writable("a model") == tmp_path / "new" / "cache"
    assert not (tmp_path / "new").exists()  # created only when something is written
    assert list(tmp_path.iterdir()) == []


# ------------------------------------------------------------------ argument parser


@pytest.mark.parametrize(
    ("argv", "cause", "command"),
    [
        (["simulate", "station", "--seed", "-1"], "argument --seed: the seed must be", "simulate"),
        (["simulate", "station", "--export", "fbx"], "invalid choice: 'fbx'", "simulate"),
        (["scan", "a.pcd", "-o", "a.xml", "--voids", "sometimes"], "'sometimes'", "scan"),
        (["plan", "station", "--from", "stand_rack2"], "required: --to", "plan"),
        ([], "required: command", ""),
    ],
)
def test_parser_errors_are_one_line(argv, cause, command, capsys, no_work, tmp_path):
    """Before: a 4-6 line usage block, then the error line."""
    line, _ = one_line_refusal(argv, capsys, 5.0)
    assert cause in line
    see = f"mjwalk {command} --help" if command else "mjwalk --help"
    assert line.endswith(f"(see {see})")
    assert "usage:" not in line


def test_a_message_of_several_lines_is_printed_as_one(monkeypatch, capsys):
    """An MjwalkError carrying a message of several lines (MuJoCo's compiler errors, wrapped by
    the scene builders, span two: 'Error: size 1 must be positive in geom' and 'Element name
    ...') is printed as one line, its parts joined by '; '."""
    from mjwalk.errors import ScanError

    def fails(args):
        raise ScanError("x.ply: the generated scene does not compile: Error: bad\nElement 'a'\n")

    parser = cli.build_parser()
    monkeypatch.setattr(cli, "build_parser", lambda: parser)
    monkeypatch.setattr(
        parser, "parse_args", lambda argv=None: argparse.Namespace(func=fails, quiet=True)
    )
    assert cli.main(["scan", "x.ply"]) == 2
    err = capsys.readouterr().err
    assert err.splitlines() == [
        "mjwalk: error: x.ply: the generated scene does not compile: Error: bad; Element 'a'"
    ]
