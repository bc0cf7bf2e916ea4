"""BVH import: parse any hierarchy, forward kinematics for every joint, convert to a 120 Hz Take.

BVH conventions used here (those of the Biovision format as written by Motionbuilder, Bandai and
the CMU conversions):

* Rotation channels are intrinsic Euler angles in degrees, in the order they are listed:
  ``Zrotation Xrotation Yrotation`` means ``R = Rz · Rx · Ry`` (a vector in the joint frame is
  rotated about y first). Any count (0–3) and order of rotation channels is accepted.
* Position channels *replace* the OFFSET component they name (Bandai writes the OFFSET again in
  the position channels of every joint below ``Hips``, and its ``Hips`` channels carry the absolute
  pelvis position while the OFFSET holds a rest pose). Joints without position channels use their
  OFFSET.
* A joint's world pose: ``R_w = R_w(parent) · R_local``, ``p_w = p_w(parent) + R_w(parent) · t``.
* ``End Site`` blocks become joints named ``<parent>_end``.

Units and axes come from the :class:`~mjwalk.mocap.skeletons.SkeletonMap` (e.g. Bandai:
centimetres, y up); the :class:`Take` is in metres with z up, resampled to ``fps``.
"""

from __future__ import annotations

import os
from dataclasses import dataclass
from pathlib import Path

import numpy as np
from scipy.spatial.transform import Rotation

from mjwalk.errors import CaptureError
from mjwalk.mocap.bodycheck import MIN_FPS, body_frame, repair_frames
from mjwalk.mocap.naming import resolve_skeleton
from mjwalk.mocap.skeletons import SkeletonMap, check_joints, take_from_positions
from mjwalk.mocap.take import TAKE_FPS, Take

_CHANNEL_NAMES = {
    f"{axis}{kind}": (kind, axis) for axis in "xyz" for kind in ("position", "rotation")
}


@dataclass
class Bvh:
    """A parsed BVH file, in file units and file axes.

    Attributes:
        path: the file read.
        names: joint names in file order (``End Site`` as ``<parent>_end``).
        parents: index of each joint's parent, -1 for a root.
        offsets: (J, 3) OFFSET of each joint in file units.
        channels: per joint, its channel names in file order, lower case (e.g. ``"zrotation"``).
        frame_time: seconds between frames as written in the file.
        motion: (T, C) channel values, C = total channel count, joints in file order.
    """

    path: Path
    names: list[str]
    parents: list[int]
    offsets: np.ndarray
    channels: list[list[str]]
    frame_time: float
    motion: np.ndarray

    @property
    def fps(self) -> float:
        """Frame rate (Hz), snapped to the nearest integer when the file rounds ``Frame Time``."""
        fps = 1.0 / self.frame_time
        return float(round(fps)) if abs(fps - round(fps)) < 1e-3 * fps else fps


def _tokens(lines: list[str]):
    for lineno, line in enumerate(lines, start=1):
        for tok in line.split():
            yield tok, lineno


def _float(tok: str, path, lineno: int, what: str) -> float:
    try:
        return float(tok)
    except ValueError:
        raise CaptureError(f"{path}, line {lineno}: {what}: {tok!r} is not a number") from None


class _Hierarchy:
    """The joints of a BVH file's HIERARCHY section as it is read token by token: names,
    parents, offsets, channels, and the open blocks (``stack``; ``pending``: a joint named but
    its ``{`` not yet read). Every error names the file and the line."""

    def __init__(self, path: Path, toks) -> None:
        self.path, self.toks = path, toks
        self.names: list[str] = []
        self.parents: list[int] = []
        self.offsets: list[list[float] | None] = []
        self.channels: list[list[str]] = []
        self.is_end: list[bool] = []
        self.opened_at: list[int] = []
        self.stack: list[int] = []
        self.pending: int | None = None

    def _error(self, lineno: int, msg: str) -> CaptureError:
        return CaptureError(f"{self.path}, line {lineno}: {msg}")

    def take(self, expect: str) -> tuple[str, int]:
        """The next token and its line; the file's end here raises CaptureError."""
        try:
            return next(self.toks)
        except StopIteration:
            raise CaptureError(
                f"{self.path}: file ends inside HIERARCHY (expected {expect})"
            ) from None

    def read(self) -> int | None:
        """Read up to ``MOTION``; return its line (None: the file ended first)."""
        for tok, lineno in self.toks:
            key = tok.upper()
            if key in ("ROOT", "JOINT", "END"):
                self._joint(tok, key, lineno)
            elif tok == "{":
                if self.pending is None:
                    raise self._error(lineno, "'{' without ROOT/JOINT/End Site")
                self.stack.append(self.pending)
                self.pending = None
            elif tok == "}":
                if not self.stack:
                    raise self._error(lineno, "unmatched '}'")
                j = self.stack.pop()
                if self.offsets[j] is None:
                    raise self._error(lineno, f"joint {self.names[j]!r} has no OFFSET")
            elif key == "OFFSET":
                self._offset(lineno)
            elif key == "CHANNELS":
                self._channels(lineno)
            elif key == "MOTION":
                return lineno
            else:
                raise self._error(lineno, f"unexpected {tok!r} in HIERARCHY")
        return None

    def _joint(self, tok: str, key: str, lineno: int) -> None:
        """A ``ROOT``, ``JOINT`` or ``End Site`` and its name."""
        names, stack = self.names, self.stack
        if self.pending is not None:
            raise self._error(lineno, f"{tok} before the '{{' of joint {names[self.pending]!r}")
        if key == "ROOT" and stack:
            raise self._error(lineno, f"ROOT inside joint {names[stack[-1]]!r}")
        if key != "ROOT" and not stack:
            raise self._error(lineno, f"{tok} outside any ROOT")
        name, nl = self.take("a joint name")
        if key == "END":
            if name.upper() != "SITE":
                raise self._error(nl, f"expected 'End Site', found {name!r}")
            name = f"{names[stack[-1]]}_end"
        elif name in ("{", "}"):
            raise self._error(lineno, f"{tok} without a name")
        if name in names:
            raise self._error(lineno, f"joint {name!r} defined twice")
        names.append(name)
        self.parents.append(stack[-1] if stack else -1)
        self.offsets.append(None)
        self.channels.append([])
        self.is_end.append(key == "END")
        self.opened_at.append(lineno)
        self.pending = len(names) - 1

    def _offset(self, lineno: int) -> None:
        """An ``OFFSET`` of the open joint: three numbers."""
        if not self.stack or self.pending is not None:
            raise self._error(lineno, "OFFSET outside a joint block")
        j = self.stack[-1]
        self.offsets[j] = [
            _float(
                self.take("an OFFSET value")[0], self.path, lineno, f"OFFSET of {self.names[j]!r}"
            )
            for _ in range(3)
        ]

    def _channels(self, lineno: int) -> None:
        """A ``CHANNELS`` line of the open joint: its count and names."""
        if not self.stack or self.pending is not None:
            raise self._error(lineno, "CHANNELS outside a joint block")
        j = self.stack[-1]
        name = self.names[j]
        if self.is_end[j]:
            raise self._error(lineno, f"End Site of {name!r} has CHANNELS")
        ntok, _ = self.take("the channel count")
        try:
            n = int(ntok)
        except ValueError:
            n = -1
        if n < 0:
            raise self._error(lineno, f"joint {name!r}: bad channel count {ntok!r}")
        for _ in range(n):
            ch, cl = self.take("a channel name")
            if ch.lower() not in _CHANNEL_NAMES:
                raise self._error(
                    cl,
                    f"joint {name!r}: unknown channel {ch!r} "
                    f"(CHANNELS {n} but only {len(self.channels[j])} channel names?)",
                )
            self.channels[j].append(ch.lower())

    def check_complete(self, motion_line: int | None, n_lines: int) -> int:
        """Check that MOTION was found after every block closed and a joint; return its line."""
        if motion_line is None:
            raise CaptureError(f"{self.path}: no MOTION section (file ends at line {n_lines})")
        if self.pending is not None or self.stack:
            j = self.pending if self.pending is not None else self.stack[-1]
            raise self._error(
                motion_line,
                f"MOTION before joint {self.names[j]!r} (opened at line {self.opened_at[j]}) "
                "is closed",
            )
        if not self.names:
            raise self._error(motion_line, "HIERARCHY defines no joint")
        return motion_line


def parse_bvh(path: str | os.PathLike) -> Bvh:
    """Read a BVH file; malformed, truncated or inconsistent files raise :class:`CaptureError`.

    Every error message names the file and the line (or the joint) at fault.

    Args:
        path: the ``.bvh`` file.

    Returns:
        The parsed hierarchy (joint names, parents, offsets in the file's units, channels) and
        its motion: (frames, channels) values as written (positions in the file's units,
        rotations in degrees).
    """
    path = Path(path)
    try:
        text = path.read_text(encoding="utf-8", errors="replace")
    except OSError as exc:
        raise CaptureError(f"{path}: cannot read BVH file ({exc.strerror or exc})") from None
    lines = text.splitlines()
    toks = _tokens(lines)
    first = next(toks, None)
    if first is None or first[0].upper() != "HIERARCHY":
        where = f"line {first[1]}" if first else "line 1"
        got = first[0] if first else "an empty file"
        raise CaptureError(f"{path}, {where}: expected 'HIERARCHY', found {got!r}")
    joints = _Hierarchy(path, toks)
    motion_line = joints.check_complete(joints.read(), len(lines))
    n_frames, frame_time, data_start = _motion_header(lines, motion_line, path)
    n_channels = sum(len(c) for c in joints.channels)
    motion = _motion_data(lines, data_start, n_frames, n_channels, path)
    return Bvh(
        path=path,
        names=joints.names,
        parents=joints.parents,
        offsets=np.array(joints.offsets, dtype=float).reshape(-1, 3),
        channels=joints.channels,
        frame_time=frame_time,
        motion=motion,
    )


def _motion_header(lines: list[str], motion_line: int, path) -> tuple[int, float, int]:
    """Parse ``Frames:`` and ``Frame Time:``; return them and the 0-based index of the data."""
    i = motion_line  # 0-based index of the line after MOTION
    header = {}
    for label in ("frames:", "frame time:"):
        while i < len(lines) and not lines[i].strip():
            i += 1
        if i >= len(lines):
            raise CaptureError(f"{path}, line {i}: file ends before {label!r} in MOTION")
        line = lines[i].strip()
        if not line.lower().startswith(label):
            raise CaptureError(f"{path}, line {i + 1}: expected {label!r}, found {line[:40]!r}")
        header[label] = (line[len(label) :].strip(), i + 1)
        i += 1
    tok, ln = header["frames:"]
    try:
        n_frames = int(tok)
    except ValueError:
        n_frames = -1
    if n_frames < 0:
        raise CaptureError(f"{path}, line {ln}: bad frame count {tok!r}")
    tok, ln = header["frame time:"]
    frame_time = _float(tok, path, ln, "Frame Time")
    if not frame_time > 0:
        raise CaptureError(f"{path}, line {ln}: Frame Time must be positive, got {tok!r}")
    return n_frames, frame_time, i


def _motion_data(lines, start: int, n_frames: int, n_channels: int, path) -> np.ndarray:
    """(n_frames, n_channels) motion values; wrong counts raise CaptureError with the line."""
    rows: list[list[str]] = []
    linenos = []
    for k in range(start, len(lines)):
        parts = lines[k].split()
        if not parts:
            continue
        if len(parts) != n_channels:
            raise CaptureError(
                f"{path}, line {k + 1}: frame {len(rows) + 1} has {len(parts)} values, "
                f"the HIERARCHY declares {n_channels} channels"
            )
        rows.append(parts)
        linenos.append(k + 1)
    if len(rows) < n_frames:
        raise CaptureError(
            f"{path}, line {len(lines)}: truncated: 'Frames: {n_frames}' but the file ends "
            f"after {len(rows)} frames"
        )
    if len(rows) > n_frames:
        raise CaptureError(
            f"{path}, line {linenos[n_frames]}: 'Frames: {n_frames}' but more frame lines follow "
            f"({len(rows)} in all)"
        )
    try:
        motion = np.array(rows, dtype=float).reshape(n_frames, n_channels)
    except ValueError:
        for parts, ln in zip(rows, linenos, strict=True):
            for tok in parts:
                _float(tok, path, ln, "motion value")
        raise  # pragma: no cover - unreachable: some token must have failed
    bad = ~np.isfinite(motion)
    if bad.any():
        k, c = np.argwhere(bad)[0]
        raise CaptureError(
            f"{path}, line {linenos[k]}: frame {k + 1}, value {c + 1} is {motion[k, c]} "
            f"(not finite)"
        )
    return motion


def bvh_forward_kinematics(bvh: Bvh) -> np.ndarray:
    """World positions of every joint, (T, J, 3), in file units and the file's frame.

    Vectorized over frames: one Euler conversion and one batched matrix product per joint.

    Args:
        bvh: the parsed file (:func:`parse_bvh`).

    Returns:
        (T, J, 3) joint positions in the file's units and axes, joints in file order.
    """
    n = bvh.motion.shape[0]
    n_joints = len(bvh.names)
    pos = np.empty((n, n_joints, 3))
    rot: list[np.ndarray | None] = [None] * n_joints  # world rotation (T, 3, 3); None = identity
    col = 0
    for j in range(n_joints):
        chans = bvh.channels[j]
        values = bvh.motion[:, col : col + len(chans)]
        col += len(chans)
        local_t = np.broadcast_to(bvh.offsets[j], (n, 3)).copy()
        seq, angles = "", []
        for k, ch in enumerate(chans):
            kind, axis = _CHANNEL_NAMES[ch]
            if kind == "position":
                local_t[:, "xyz".index(axis)] = values[:, k]
            else:
                seq += axis.upper()
                angles.append(values[:, k])
        local_r = (
            Rotation.from_euler(seq, np.stack(angles, axis=1), degrees=True).as_matrix()
            if seq
            else None
        )
        p = bvh.parents[j]
        if p < 0:
            pos[:, j] = local_t
            rot[j] = local_r
            continue
        parent_r = rot[p]
        if parent_r is None:
            pos[:, j] = pos[:, p] + local_t
            rot[j] = local_r
        else:
            pos[:, j] = pos[:, p] + np.einsum("tij,tj->ti", parent_r, local_t)
            rot[j] = parent_r if local_r is None else parent_r @ local_r
    return pos


def load_bvh(
    path: str | os.PathLike,
    skeleton: SkeletonMap | str | None = "bandai",
    fps: float = TAKE_FPS,
) -> Take:
    """Load a BVH file as a :class:`Take` (metres, z up, ``fps`` Hz, every joint in ``joints``).

    Args:
        path: the ``.bvh`` file.
        skeleton: a :class:`SkeletonMap`, a preset name (``"bandai"``, ``"cmu_bvh"``, ...), a
            convention name (``"humanik"``, ``"lafan1"``, ...), a map file ``*.toml``, or None /
            ``"auto"`` to detect the convention from the joint names
            (:func:`mjwalk.mocap.naming.resolve_skeleton`). Units and up axis a convention
            or map leaves open are read from the body, declared ones checked against it
            (:mod:`mjwalk.mocap.bodycheck`).
        fps: output sampling rate (Hz); the file's rate is converted by cubic interpolation.

    Returns:
        A Take whose ``pelvis_yaw`` is the heading (radians, CCW from +x, unwrapped) of the
        right-to-left hip line rotated by -90 deg, and ``meta`` holding ``file``,
        ``source_fps``, ``skeleton`` and ``scale``.

    Raises:
        CaptureError: missing/unreadable file, malformed hierarchy, wrong value counts,
            truncated motion, a joint named by ``skeleton`` that the file lacks, no convention
            detected, a frame rate below 24 Hz, or units / up axis contradicting the body.
    """
    return take_from_bvh(parse_bvh(path), skeleton, fps)


def take_from_bvh(
    bvh: Bvh, skeleton: SkeletonMap | str | None = "bandai", fps: float = TAKE_FPS
) -> Take:
    """The :class:`Take` of a parsed BVH file (:func:`parse_bvh`): :func:`load_bvh` without
    reading the file again (for callers that also need the hierarchy, e.g. its OFFSETs).

    Args:
        bvh: the parsed file.
        skeleton: a :class:`SkeletonMap` or preset name naming the pelvis, hips, ankles, toes.
        fps: the take's sampling rate (Hz).

    Returns:
        The take at ``fps`` Hz: metres, z up, yaw from +x CCW.
    """
    skel = resolve_skeleton(skeleton, bvh.names, bvh.path)
    check_joints(skel, bvh.names, bvh.path)
    if bvh.motion.shape[0] == 0:
        raise CaptureError(f"{bvh.path}: 'Frames: 0', the file holds no motion")
    checked = skel.verify or skel.guess_scale or skel.guess_up
    if checked and bvh.fps < MIN_FPS:
        raise CaptureError(
            f"{bvh.path}: {bvh.fps:.3g} Hz is below {MIN_FPS:g} Hz, too coarse to place foot "
            "contacts; export the capture at 24 Hz or more"
        )
    positions = bvh_forward_kinematics(bvh)
    meta: dict = {"file": str(bvh.path)}
    if checked:
        skel = body_frame(positions, bvh.names, skel, bvh.path)
        positions, done = repair_frames(positions, bvh.names, skel, bvh.fps, bvh.path)
        meta.update(done)
    return take_from_positions(
        positions,
        bvh.names,
        skel,
        src_fps=bvh.fps,
        fps=fps,
        name=bvh.path.name,
        meta=meta,
    )
