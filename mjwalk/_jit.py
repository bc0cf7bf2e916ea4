"""Compiled inner loops: numba's ``njit`` with mjwalk's settings.

The hybrid A* spends its time in a few dozen small array operations per sampled step (GP
successor draws, decoding, collision and reach checks): in NumPy each costs more in call
overhead than in arithmetic. numba compiles those loops once per machine (``cache=True``: the
machine code is kept beside the module, or in numba's user-wide cache where that is read-only;
a fresh checkout compiles in a few seconds on first use). Compiled functions take
``numpy.random.Generator`` arguments and draw from the same bit generator with NumPy's own
algorithms, so a seed gives the same numbers inside and outside them.
"""

from __future__ import annotations

import hashlib
import os
from collections.abc import Callable
from pathlib import Path
from typing import cast

import numba
import numba.core.compiler_lock
import numba.core.event
import numba.extending
from numba.core import sigutils

from mjwalk._log import claim_notice, log

try:
    import fcntl
except ImportError:  # not POSIX (Windows): each process compiles what it misses, as numba does
    fcntl = None  # type: ignore[assignment]

#: Where the digest of mjwalk's sources that the cached machine code was compiled from is kept.
SOURCES_MARK = Path(__file__).resolve().parent / "__pycache__" / "numba-sources.sha1"


def clear_stale_caches(package: Path = SOURCES_MARK.parent.parent) -> bool:
    """Delete numba's cached machine code beside mjwalk's modules (``__pycache__/*.nbi``,
    ``*.nbc``) when any of the package's sources changed since it was cached; True if it did.

    numba keys a compiled function's cache by its own file's stamp only, and compiles the
    module-level constants it reads from other files (the search's parameter slots, say) into
    the machine code: an edit to such a file alone would leave stale code that reads the wrong
    slots. The digest of every source file's path, size and modification time, kept in
    :data:`SOURCES_MARK`, tells an unchanged checkout (nothing to do: one ``stat`` per file)
    from an edited one. Folders that cannot be written are left alone (an installed package
    is replaced whole, and numba's stamps then differ anyway)."""
    files = sorted(package.rglob("*.py"))
    h = hashlib.sha1()
    for f in files:
        st = f.stat()
        h.update(f"{f.relative_to(package)}:{st.st_size}:{st.st_mtime_ns}\n".encode())
    digest = h.hexdigest()
    mark = package / "__pycache__" / SOURCES_MARK.name
    try:
        if mark.read_text() == digest:
            return False
    except OSError:
        pass
    try:
        for cached in (*package.rglob("__pycache__/*.nbi"), *package.rglob("__pycache__/*.nbc")):
            cached.unlink(missing_ok=True)
        mark.parent.mkdir(exist_ok=True)
        tmp = mark.with_name(f"{mark.name}.{os.getpid()}")
        tmp.write_text(digest)
        tmp.replace(mark)
    except OSError:
        return False
    return True


clear_stale_caches()

_njit = numba.njit(cache=True, nogil=True, fastmath=False)
_njit_sum = numba.njit(cache=True, nogil=True, fastmath={"reassoc", "contract"})
_njit_inline = numba.njit(cache=True, nogil=True, fastmath=False, inline="always")
_njit_gil = numba.njit(cache=True, fastmath=False)


def _cache_failures_warn(dispatcher):
    """``dispatcher`` with its on-disk cache's writes made non-fatal: a full disk or a file
    size limit (``ulimit -f``) while numba saves the machine code it compiled is a warning
    (the code runs; it compiles again next time), not a traceback out of the first plan."""
    cache = getattr(dispatcher, "_cache", None)
    save = getattr(cache, "save_overload", None)
    if cache is None or save is None:
        return dispatcher

    def save_overload(sig, data):
        try:
            save(sig, data)
        except OSError as exc:
            log.warning(
                "could not cache the compiled %s (%s): it runs, and compiles again next time",
                getattr(dispatcher, "__name__", "kernel"),
                exc.strerror or exc,
            )

    cache.save_overload = save_overload
    return dispatcher


#: The compile locks (paths) this process holds, with how deep: a kernel whose compile compiles
#: it again (another signature, or itself through a callee) must not wait for its own lock.
#: Read and changed only under numba's compiler lock (:func:`_compile_once`), one thread at a time.
_HELD: dict[str, int] = {}


def _hold(path: str) -> int | None:
    """The descriptor of ``path`` locked exclusively (``flock``, waiting for another process
    that holds it), or None when this process holds it already or it cannot be opened."""
    if path in _HELD:
        _HELD[path] += 1
        return None
    _HELD[path] = 1
    try:
        os.makedirs(os.path.dirname(path), exist_ok=True)
        fd = os.open(path, os.O_RDWR | os.O_CREAT, 0o666)
    except OSError:
        return None
    try:
        fcntl.flock(fd, fcntl.LOCK_EX)
    except OSError:
        os.close(fd)
        return None
    return fd


def _release(path: str, fd: int | None) -> None:
    """Undoes :func:`_hold` (unlocks and closes ``fd`` if it holds one)."""
    _HELD[path] -= 1
    if not _HELD[path]:
        del _HELD[path]
    if fd is not None:
        fcntl.flock(fd, fcntl.LOCK_UN)
        os.close(fd)


def _compile_once(dispatcher):
    """``dispatcher`` whose compiles hold a lock file of its own beside its cached machine code
    (``<module>.<function>.lock`` in numba's cache folder for it, ``flock``), so that of two
    processes that miss the cache at once (pytest's workers or ``simulate --jobs N`` on a fresh
    install) one compiles and saves it while the other waits, then loads what the first saved
    (numba's ``compile`` looks in the cache before it compiles) instead of compiling it again.
    The lock is taken inside numba's own compiler lock (one compile at a time in a process), one
    per function: a kernel's compile takes its callees' locks, never its callers', so two
    processes never wait for each other. Without ``fcntl`` (not POSIX), without a cache folder
    or where the lock file cannot be written, compiles go on unlocked as before. The machine
    code is the same either way."""
    folder = getattr(getattr(dispatcher, "_cache", None), "cache_path", None)
    compile_ = getattr(dispatcher, "compile", None)
    if fcntl is None or folder is None or compile_ is None:
        return dispatcher
    func = dispatcher.py_func
    path = os.path.join(folder, f"{func.__module__}.{func.__qualname__}.lock")

    def compile(sig):
        if tuple(sigutils.normalize_signature(sig)[0]) in dispatcher.overloads:
            return compile_(sig)  # compiled or loaded already: nothing to wait for
        with numba.core.compiler_lock.global_compiler_lock:
            fd = _hold(path)
            try:
                return compile_(sig)
            finally:
                _release(path, fd)

    dispatcher.compile = compile
    return dispatcher


def _kernel(dispatcher):
    """``dispatcher`` with its cache writes non-fatal and its compiles locked across processes."""
    return _compile_once(_cache_failures_warn(dispatcher))


def njit(func):
    """``numba.njit`` with mjwalk's settings (cached; ``fastmath`` off: the arithmetic stays
    that of the NumPy code it replaces), its cache writes non-fatal, one process at a time
    compiling it (:func:`_compile_once`)."""
    return _kernel(_njit(func))


def njit_inline(func):
    """:func:`njit` inlined into its compiled callers by numba itself (``inline="always"``):
    for a few-line helper called in a hot loop, where LLVM's own inlining leaves a call whose
    argument passing outweighs the helper's arithmetic (:func:`mjwalk.plan.stepgeom.decode_col`:
    six multiply-adds, 3.6x the cost as a call; issue 50). The arithmetic is the same."""
    return _kernel(_njit_inline(func))


def njit_gil(func):
    """:func:`njit` without ``nogil``: for a compiled loop that calls back into Python (numba's
    ``objmode``) for a value only NumPy computes bit for bit as the code it replaces needs
    (:func:`mjwalk.body.legs.synthloop.synth_steps`: NumPy's arccos). The callback takes the
    GIL anyway; a ``nogil`` function with one warns at every load."""
    return _kernel(_njit_gil(func))


def njit_sum(func):
    """:func:`njit` for long dot products: the sums may be reassociated (and multiply-adds
    fused), so they vectorize, as BLAS's do; nothing else of fastmath (NaN and inf stay IEEE)."""
    return _kernel(_njit_sum(func))


#: Logged (INFO, once per command: :func:`mjwalk._log.claim_notice`) when one of mjwalk's
#: compiled functions misses the cache and compiles: on the first plan or animation after an
#: install or upgrade (``benchmarks/bench_cold_start.py`` measures how long that takes).
COMPILE_NOTICE = (
    "compiling the planner and the animation kernels (numba, once after an install: "
    "about a minute idle, minutes on a busy machine; cached for later runs)..."
)


class _CompileNotice(numba.core.event.Listener):
    """Logs :data:`COMPILE_NOTICE` when the first ``mjwalk`` function starts compiling (numba
    emits "numba:compile" only on a cache miss, never when it loads cached machine code)."""

    shown = False

    def on_start(self, event) -> None:
        if self.shown:
            return
        func = getattr((event.data or {}).get("dispatcher"), "py_func", None)
        if (getattr(func, "__module__", None) or "").startswith("mjwalk"):
            self.shown = True
            if claim_notice():
                log.info(COMPILE_NOTICE)

    def on_end(self, event) -> None:
        pass


NOTICE = _CompileNotice()
numba.core.event.register("numba:compile", NOTICE)


@numba.extending.intrinsic
def _fma(typingctx, a, b, c):
    """``a * b + c`` rounded once (LLVM's ``llvm.fma``, a fused multiply-add instruction on
    x86-64 with FMA3), in compiled functions only. NumPy's matmul of an (m, 2) array by a
    2-vector and its dot of two 2-vectors go through OpenBLAS, whose kernels on FMA machines
    compute ``fma(r0, s0, r1 * s1)`` and ``fma(s1, s1, s0 * s0)`` (measured here on
    SkylakeX: equal bit for bit on 10^4 random rows); compiled replacements of such products use
    this to give the same numbers (on machines whose BLAS does not fuse them, the two differ
    by rounding only)."""
    sig = numba.types.float64(numba.types.float64, numba.types.float64, numba.types.float64)

    def codegen(context, builder, signature, args):
        return builder.fma(*args)

    return sig, codegen


#: ``fma(a, b, c)``: :func:`_fma` as compiled callers call it.
fma = cast(Callable[[float, float, float], float], _fma)
