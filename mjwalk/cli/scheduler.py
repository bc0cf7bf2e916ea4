"""``mjwalk simulate --scheduler ADDRESS``: a Dask scheduler's client, or a one-line reason why
not, within :data:`SCHEDULER_TIMEOUT_S` of wall-clock time.

``distributed.Client(address, timeout=10)`` alone cannot keep that promise: its timeout bounds
the TCP connect, not the handshake after it, so a peer that accepts and never answers (an HTTP
server waits for a request line) holds it forever; a peer that answers anything else has its
first 8 bytes read as a frame length (``HTTP/1.1`` asks for 3.07 EiB); a refused connection is
retried for the whole timeout and then called a time-out; a malformed address is reported as
"no scheduler answered". So the address is parsed here first, and the peer must greet with a
Dask handshake on a socket of our own before the Client is made: a Dask server sends its
handshake as soon as it accepts a connection (``distributed.comm.core.Listener.on_connection``),
one TCP message of ``distributed.comm.tcp``'s framing (an 8-byte byte count, then
``distributed.protocol.utils.pack_frames`` of ``distributed.protocol.dumps`` of a small dict
naming its Python and pickle protocol). The probe sends its own handshake, as distributed's
client does, reads the peer's, and closes. Every step has the time left of one deadline.
"""

from __future__ import annotations

import pickle
import queue
import socket
import struct
import sys
import threading
import time

from mjwalk.errors import InputError

#: Seconds within which ``--scheduler`` either connects or says why not (the README's promise).
SCHEDULER_TIMEOUT_S = 10.0
#: Largest greeting read from the peer, bytes: a Dask handshake is a msgpack dict of three short
#: entries (58 bytes from distributed 2026.8); a larger first message is not a handshake.
MAX_HANDSHAKE_BYTES = 1 << 16
#: The keys every Dask handshake carries (``distributed.comm.core.Comm.handshake_info``).
HANDSHAKE_KEYS = ("python", "pickle-protocol")
HINT = "give the scheduler's address as tcp://HOST:PORT, as dask scheduler prints it"
_LENGTH = struct.Struct("Q")  # distributed.comm.tcp: the message's byte count, native order


class SchedulerError(InputError):
    """``--scheduler`` names no Dask scheduler that answers: a malformed address, a host not
    found, a refused connection, a time-out, or a peer that does not speak Dask."""


def parse_scheduler_address(address: str) -> tuple[str, int]:
    """``tcp://HOST:PORT`` (or ``HOST:PORT``; ``[v6]:PORT`` for IPv6) as (host, port).

    Args:
        address: the ``--scheduler`` text (surrounding blanks ignored; scheme case-insensitive).

    Returns:
        ``(host, port)``: the host without IPv6 brackets, the port in 1-65535.

    Raises:
        SchedulerError: naming what is malformed (no port, a port that is not 1-65535, another
            scheme than tcp://, a path after the port).
    """
    text = address.strip()
    where = f"--scheduler {address!r}: malformed address"
    rest = text
    if "://" in text:
        scheme, rest = text.split("://", 1)
        if scheme.lower() != "tcp":
            raise SchedulerError(
                f"--scheduler {address!r}: mjwalk reaches a scheduler over tcp:// only, not "
                f"{scheme}://; {HINT}"
            )
    if "/" in rest:
        raise SchedulerError(f"{where}: nothing may follow the port ({rest!r}); {HINT}")
    host, sep, port_text = rest.rpartition(":")
    if not sep or "]" in port_text:
        raise SchedulerError(f"{where}: no port; {HINT}")
    host = host[1:-1] if host.startswith("[") and host.endswith("]") else host
    if not host:
        raise SchedulerError(f"{where}: no host; {HINT}")
    try:
        port = int(port_text)
    except ValueError:
        raise SchedulerError(f"{where}: port {port_text!r} is not a number; {HINT}") from None
    if not 1 <= port <= 65535:
        raise SchedulerError(f"{where}: port {port} is not a port number (1 to 65535); {HINT}")
    return host, port


def _resolve(host: str, port: int, seconds: float, where: str) -> list:
    """``socket.getaddrinfo`` of ``host`` within ``seconds`` (it takes no timeout of its own,
    so it runs in a daemon thread that is left behind when it overruns)."""
    answer: queue.Queue = queue.Queue(maxsize=1)

    def run() -> None:
        try:
            answer.put(socket.getaddrinfo(host, port, type=socket.SOCK_STREAM))
        except OSError as exc:
            answer.put(exc)

    threading.Thread(target=run, name="mjwalk-resolve", daemon=True).start()
    try:
        result = answer.get(timeout=seconds)
    except queue.Empty:
        raise SchedulerError(
            f"{where}: host name {host!r} not resolved within {SCHEDULER_TIMEOUT_S:.0f} s"
        ) from None
    if isinstance(result, OSError):
        why = getattr(result, "strerror", None) or str(result)
        raise SchedulerError(f"{where}: host {host!r} not found ({why}); {HINT}")
    return result


def _connect(host: str, port: int, where: str, deadline: float) -> socket.socket:
    """A TCP connection to ``host:port`` (its first address that accepts) before ``deadline``."""
    infos = _resolve(host, port, deadline - time.monotonic(), where)
    refused: OSError | None = None
    other: OSError | None = None
    for family, kind, proto, _, sockaddr in infos:
        left = deadline - time.monotonic()
        if left <= 0:
            break
        sock = socket.socket(family, kind, proto)
        sock.settimeout(left)
        try:
            sock.connect(sockaddr)
            return sock
        except TimeoutError:
            sock.close()
            break
        except ConnectionRefusedError as exc:
            refused = exc
        except ConnectionError as exc:  # accepted, then reset before connect() returned
            sock.close()
            raise SchedulerError(
                f"{where} is not a Dask scheduler: it reset the connection without a Dask "
                f"handshake ({exc.strerror})"
            ) from None
        except OSError as exc:
            other = exc
        sock.close()
    if refused is not None:
        raise SchedulerError(
            f"{where}: connection refused: nothing listens on port {port} of {host} (is the "
            "scheduler running, and is that its port? dask scheduler prints its address)"
        )
    if other is not None:
        raise SchedulerError(f"{where}: cannot connect ({other.strerror or other})")
    raise SchedulerError(
        f"{where}: timed out: the connection was not accepted within "
        f"{SCHEDULER_TIMEOUT_S:.0f} s (a wrong host, or a firewall between)"
    )


def _recv_exactly(sock: socket.socket, n: int, deadline: float) -> bytes:
    """``n`` bytes from ``sock`` before ``deadline``; raises TimeoutError, or EOFError when the
    peer closes first (with the bytes it did send as ``args[0]``)."""
    data = bytearray()
    while len(data) < n:
        left = deadline - time.monotonic()
        if left <= 0:
            raise TimeoutError
        sock.settimeout(left)
        chunk = sock.recv(n - len(data))
        if not chunk:
            raise EOFError(bytes(data))
        data += chunk
    return bytes(data)


def _shown(data: bytes) -> str:
    """The first bytes a peer sent, as text to quote in a message."""
    text = data[:24].decode("ascii", "replace")
    return repr("".join(c if c.isprintable() else "." for c in text))


def _more(sock: socket.socket, n: int = 16) -> bytes:
    """Up to ``n`` more bytes the peer has already sent (nothing when it sent no more)."""
    try:
        sock.settimeout(0.2)
        return sock.recv(n)
    except OSError:
        return b""


def _greeting(sock: socket.socket, where: str, deadline: float) -> None:
    """Read the peer's first message and raise SchedulerError unless it is a Dask handshake."""
    # deferred: dask.distributed is optional (the cluster extra) and slow to import
    from distributed.protocol import loads
    from distributed.protocol.utils import unpack_frames  # deferred: optional dask.distributed

    not_dask = f"{where} is not a Dask scheduler:"
    try:
        head = _recv_exactly(sock, _LENGTH.size, deadline)
        (size,) = _LENGTH.unpack(head)
        if not 0 < size <= MAX_HANDSHAKE_BYTES:
            raise SchedulerError(
                f"{not_dask} it answered {_shown(head + _more(sock))}, not a Dask handshake "
                "(the dashboard, an HTTP server or another service listens on that port?)"
            )
        body = _recv_exactly(sock, size, deadline)
    except TimeoutError:
        raise SchedulerError(
            f"{not_dask} it accepted the connection but sent no Dask handshake within "
            f"{SCHEDULER_TIMEOUT_S:.0f} s (a Dask scheduler greets at once)"
        ) from None
    except EOFError as exc:
        got = f" after {_shown(exc.args[0])}" if exc.args and exc.args[0] else ""
        raise SchedulerError(
            f"{not_dask} it closed the connection{got} without a Dask handshake"
        ) from None
    except ConnectionError as exc:
        raise SchedulerError(
            f"{not_dask} it reset the connection without a Dask handshake ({exc.strerror})"
        ) from None
    try:
        message = loads(unpack_frames(body))
    except Exception as exc:  # an untrusted peer's bytes: whatever the decoder makes of them
        raise SchedulerError(
            f"{not_dask} its first message, {_shown(body)}, is not a Dask handshake "
            f"({type(exc).__name__})"
        ) from None
    if not (isinstance(message, dict) and all(k in message for k in HANDSHAKE_KEYS)):
        raise SchedulerError(f"{not_dask} its first message is not a Dask handshake")


def _answer(sock: socket.socket) -> None:
    """Send a client's handshake: a scheduler then sees a complete connection (it logs none
    closed before its handshake), and many other servers answer it at once with an error
    (an HTTP server's ``400 Bad Request``), which the greeting's check quotes."""
    # deferred: dask.distributed is optional (the cluster extra) and slow to import
    from distributed.protocol import dumps
    from distributed.protocol.utils import pack_frames  # deferred: optional dask.distributed

    mine = {
        "compression": None,
        "python": tuple(sys.version_info)[:3],
        "pickle-protocol": pickle.HIGHEST_PROTOCOL,
    }
    body = pack_frames(dumps(mine))
    sock.sendall(_LENGTH.pack(len(body)) + body)


def probe_scheduler(address: str) -> float:
    """Check that a Dask scheduler answers at ``address`` within :data:`SCHEDULER_TIMEOUT_S`.

    Args:
        address: the scheduler's address, as :func:`parse_scheduler_address` reads it.

    Returns:
        The seconds left of the time allowed (for the Client's own connection).

    Raises:
        SchedulerError: one line naming the cause (malformed address, host not found,
            connection refused, timed out, or a peer that is not Dask).
    """
    deadline = time.monotonic() + SCHEDULER_TIMEOUT_S
    host, port = parse_scheduler_address(address)
    where = f"--scheduler {address}"
    sock = _connect(host, port, where, deadline)
    try:
        try:
            _answer(sock)  # first, as distributed's own client does
        except OSError:
            pass  # a peer that closed at once: the greeting's read says so
        _greeting(sock, where, deadline)
    finally:
        sock.close()
    return max(deadline - time.monotonic(), 1.0)


def dask_client(address: str):
    """A client of the Dask scheduler at ``address``, checked before any work.

    Args:
        address: the scheduler's address (``tcp://HOST:PORT``).

    Returns:
        A connected ``distributed.Client``.

    Raises:
        InputError: dask.distributed (the ``cluster`` extra) is not installed.
        SchedulerError: one line naming why no client could be made (the causes of
            :func:`probe_scheduler`), within :data:`SCHEDULER_TIMEOUT_S`.
    """
    try:
        from distributed import Client  # deferred: optional dask.distributed, slow to import
    except ImportError:
        raise InputError(
            f"--scheduler {address}: Dask is not installed here; "
            'pip install "mjwalk[cluster]" (and mjwalk on the workers)'
        ) from None
    left = probe_scheduler(address)
    try:
        return Client(address.strip(), timeout=left)
    except Exception as exc:  # whatever the peer's answers make the client raise
        why = " ".join(str(exc).split())[:200]
        raise SchedulerError(
            f"--scheduler {address}: a Dask server greeted, but no client could be made "
            f"({type(exc).__name__}: {why}); a worker's address instead of the scheduler's?"
        ) from None
