"""The H.264 writer of mjwalk's videos: frames go down a pipe into imageio-ffmpeg's ffmpeg.

Frames arrive bottom-up (as OpenGL reads them) in RGB; the file is H.264 in an mp4 at
:data:`VIDEO_QUALITY` and :data:`VIDEO_PRESET`. A write that fails anywhere, while frames are
sent or while ffmpeg finishes the file, raises ``BrokenPipeError`` saying why ffmpeg stopped
(the caller's :func:`mjwalk._io.atomic_path` names the file and removes it).
"""

from __future__ import annotations

import contextlib
import errno
import re
import signal
import subprocess
import tempfile
from fractions import Fraction

import imageio_ffmpeg
import numpy as np

#: H.264 settings of the videos: imageio-ffmpeg's quality 7 (x264 CRF 15) at x264's
#: ``veryfast`` preset, which halves the encoder's CPU time against the default ``medium``
#: (300 station frames: 1.9 s vs 4.1 s of CPU) for 50.8 dB PSNR against the rendered frames
#: (medium: 54.8 dB) and a file of the same size (763 vs 810 kB). Measured with ffmpeg 9.0.2
#: of imageio-ffmpeg 0.8.1 on frames from benchmarks/bench_render.py
#: (``ffmpeg -f rawvideo ... -crf 15 -preset P``, ``-lavfi psnr``).
VIDEO_CODEC = "libx264"
VIDEO_QUALITY = 7
VIDEO_PRESET = "veryfast"

#: Seconds to wait for an ffmpeg that stopped reading frames to exit, so that its exit status
#: or last message can name why (it exits at once after a failed write; a choice, not a norm).
WAIT_AFTER_PIPE_S = 10.0


class FfmpegWriter:
    """ffmpeg (imageio-ffmpeg's binary) writing H.264 from top-down RGB frames; no per-frame
    allocation: each frame is flipped into one reused buffer, whose bytes go down the pipe
    (the write releases the GIL; ffmpeg encodes in its own process).

    The process is started here, not through ``imageio_ffmpeg.write_frames``, because that
    generator never looks at ffmpeg's exit status: an ffmpeg that fails or is killed after it
    has read the last frame (a file size limit reached while the encoder flushes, with
    ``SIGXFSZ`` back at its default in the child) left a cut file that was renamed into place
    as a finished video. The command line is the one ``write_frames`` builds for these
    options (``-crf`` from imageio-ffmpeg's quality mapping), so the bytes written are the same.
    """

    def __init__(self, path, size: tuple[int, int], fps: float):
        w, h = int(size[0]), int(size[1])
        self._flip = np.empty((h, w, 3), np.uint8)
        crf = int((1 - VIDEO_QUALITY / 10.0) * 51)  # imageio-ffmpeg: quality 0-10 -> crf 51-0
        cmd = [
            imageio_ffmpeg.get_ffmpeg_exe(),
            "-y",
            "-f", "rawvideo", "-vcodec", "rawvideo",
            "-s", f"{w}x{h}", "-pix_fmt", "rgb24",
            "-r", str(Fraction(fps).limit_denominator()),
            "-i", "-", "-an",
            "-vcodec", VIDEO_CODEC, "-pix_fmt", "yuv420p", "-crf", str(crf),
            "-v", "warning", "-preset", VIDEO_PRESET,
            str(path),
        ]  # fmt: skip
        self._log = tempfile.TemporaryFile()  # ffmpeg's messages: the last line names a failure
        self._proc = subprocess.Popen(
            cmd,
            stdin=subprocess.PIPE,
            stdout=subprocess.DEVNULL,
            stderr=self._log,
            start_new_session=True,  # a Ctrl-C stops mjwalk, which then stops ffmpeg
        )

    def write_bottom_up(self, buf: np.ndarray) -> None:
        """Append a frame stored bottom-up (as OpenGL reads it)."""
        np.copyto(self._flip, buf[::-1])
        assert self._proc.stdin is not None
        try:
            self._proc.stdin.write(self._flip.data)
        except OSError as exc:
            raise BrokenPipeError(errno.EPIPE, self._stopped(WAIT_AFTER_PIPE_S)) from exc

    def _stopped(self, timeout: float | None) -> str:
        """Why ffmpeg stopped: its last message, the signal that killed it or its exit code.

        Args:
            timeout: Seconds to wait for ffmpeg to exit (None: as long as it takes). An ffmpeg
                still running after it closed its input is killed and named as such.
        """
        proc, log = self._proc, self._log
        try:
            code = proc.wait(timeout)
        except subprocess.TimeoutExpired:
            proc.kill()
            proc.wait()
            return "ffmpeg stopped writing it: it closed its input and did not exit"
        log.seek(0)
        lines = log.read().decode(errors="replace").strip().splitlines()
        why = (
            f"killed by {signal.Signals(-code).name}"
            if code < 0
            else re.sub(r"^\[[^]]*\]\s*", "", lines[-1])
            if lines
            else f"exit code {code}"
        )
        return f"ffmpeg stopped writing it: {why}"

    def close(self, ok: bool = True) -> None:
        """Let ffmpeg finish the file (``ok``), or stop it (the write failed elsewhere).

        Raises:
            BrokenPipeError: ``ok`` and ffmpeg exited with an error or was killed by a signal.
        """
        proc, log = self._proc, self._log
        try:
            if not ok:
                proc.kill()
                proc.wait()
                return
            assert proc.stdin is not None
            with contextlib.suppress(OSError):  # a dead ffmpeg: its exit status says why
                proc.stdin.close()
            if proc.wait() != 0:
                raise BrokenPipeError(errno.EPIPE, self._stopped(None))
        finally:
            if proc.poll() is None:  # interrupted while waiting for it
                proc.kill()
                proc.wait()
            log.close()
