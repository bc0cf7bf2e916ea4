"""Write a :class:`~mjwalk.mocap.Take` as a BVH file in a chosen naming convention, length
unit, up axis and frame rate: capture of mjwalk's own walks for other tools, and the files the
import's invariance tests read back (:mod:`mjwalk.mocap.naming`).

Every joint gets six channels (positions, then zero Z/X/Y rotations), so the file's forward
kinematics returns the written positions exactly, as in the Bandai dataset's files. Joints a
take lacks are placed from anthropometry (Winter 2009, Fig. 4.1, :data:`mjwalk.anthropometry.SEG`):
the hip joint centres beside the pelvis across its heading, the knee where a leg of constant
length bends forward, a spine and head above the pelvis.
"""

from __future__ import annotations

import os
from pathlib import Path

import numpy as np
from scipy.interpolate import CubicSpline

from mjwalk.anthropometry import SEG
from mjwalk.errors import CaptureError
from mjwalk.mocap.naming import CONVENTIONS
from mjwalk.mocap.take import Take

#: Knee joint names by convention (the import does not need them; the files look complete).
KNEES = {
    "bandai": ("LowerLeg_L", "LowerLeg_R"),
    "humanik": ("LeftLeg", "RightLeg"),
    "lafan1": ("LeftLeg", "RightLeg"),
    "xsens_mvn": ("LeftLowerLeg", "RightLowerLeg"),
    "rokoko": ("LeftShin", "RightShin"),
}


def _body(take: Take, stature: float) -> dict[str, np.ndarray]:
    """Role -> (T, 3) world positions (metres, z up) of every joint written."""
    yaw = take.pelvis_yaw
    left = np.stack([-np.sin(yaw), np.cos(yaw), np.zeros_like(yaw)], axis=1)
    fwd = np.stack([np.cos(yaw), np.sin(yaw), np.zeros_like(yaw)], axis=1)
    half = 0.25 * SEG["hip_width"] * stature  # hip joint centres ~ half the trochanteric width
    up = np.array([0.0, 0.0, 1.0])
    out = {
        "pelvis": take.pelvis,
        "hip_l": take.pelvis + half * left,
        "hip_r": take.pelvis - half * left,
        "ankle_l": take.ankle_l,
        "ankle_r": take.ankle_r,
        "toe_l": take.toe_l,
        "toe_r": take.toe_r,
        "spine": take.pelvis + 0.15 * stature * up,
        "head": take.pelvis + 0.40 * stature * up,
    }
    for s in ("_l", "_r"):
        d = out["ankle" + s] - out["hip" + s]
        chord = np.linalg.norm(d, axis=1)
        leg = max(float(chord.max()), (SEG["thigh"] + SEG["shank"]) * stature)
        bend = np.sqrt(np.maximum(0.0, (0.5 * leg) ** 2 - (0.5 * chord) ** 2))
        out["knee" + s] = out["hip" + s] + 0.5 * d + bend[:, None] * fwd
    return out


def _tree(convention: str, prefix: str) -> list[tuple[str, str, str | None]]:
    """(role, joint name, parent role) in file order, parents first."""
    conv = {c.name: c for c in CONVENTIONS}.get(convention)
    if conv is None:
        known = ", ".join(c.name for c in CONVENTIONS)
        raise CaptureError(f"unknown convention {convention!r}; known: {known}")
    j = dict(conv.joints)
    j["knee_l"], j["knee_r"] = KNEES[convention]
    j["spine"], j["head"] = "Spine", "Head"
    rows: list[tuple[str, str, str | None]] = [("pelvis", j["pelvis"], None)]
    for s in ("_l", "_r"):
        rows += [
            ("hip" + s, j["hip" + s], "pelvis"),
            ("knee" + s, j["knee" + s], "hip" + s),
            ("ankle" + s, j["ankle" + s], "knee" + s),
            ("toe" + s, j["toe" + s], "ankle" + s),
        ]
    rows += [("spine", "Spine", "pelvis"), ("head", "Head", "spine")]
    return [(r, prefix + n, p) for r, n, p in rows]


def _hierarchy(rows: list[tuple[str, str, str | None]]) -> str:
    """The HIERARCHY section: every joint with 6 channels, leaves with an End Site."""
    children: dict[str | None, list[int]] = {}
    for k, (_, _, parent) in enumerate(rows):
        children.setdefault(parent, []).append(k)
    chans = "CHANNELS 6 Xposition Yposition Zposition Zrotation Xrotation Yrotation"
    lines = ["HIERARCHY"]

    def emit(k: int, depth: int) -> None:
        role, name, parent = rows[k]
        pad = "  " * depth
        lines.append(f"{pad}{'ROOT' if parent is None else 'JOINT'} {name}")
        lines.extend([f"{pad}{{", f"{pad}  OFFSET 0 0 0", f"{pad}  {chans}"])
        kids = children.get(role, [])
        for c in kids:
            emit(c, depth + 1)
        if not kids:
            lines.extend([f"{pad}  End Site", f"{pad}  {{", f"{pad}    OFFSET 0 0 1", f"{pad}  }}"])
        lines.append(f"{pad}}}")

    emit(0, 0)
    return "\n".join(lines) + "\n"


def write_bvh(
    take: Take,
    path: str | os.PathLike,
    convention: str = "humanik",
    *,
    scale: float = 0.01,
    up: str = "y",
    fps: float | None = None,
    prefix: str = "",
) -> Path:
    """Write ``take`` as a BVH file.

    Args:
        take: the take (metres, z up).
        path: the file to write.
        convention: joint names, a :data:`~mjwalk.mocap.naming.CONVENTIONS` name.
        scale: metres per file unit (0.01: centimetres, 0.0254: inches).
        up: the file's up axis, ``"y"`` (file = (x, z, -y) of the world) or ``"z"``.
        fps: the file's frame rate, Hz (resampled by a cubic spline); None keeps the take's.
        prefix: a namespace written before every joint name (``"mixamorig:"``).

    Returns:
        The path written.
    """
    if up not in ("y", "z"):
        raise CaptureError(f"up axis must be 'y' or 'z', got {up!r}")
    stature = float(take.meta.get("params", {}).get("stature", 0.0)) or float(
        np.median(take.pelvis[:, 2] - 0.5 * (take.ankle_l[:, 2] + take.ankle_r[:, 2]))
        / (SEG["hip_height"] - SEG["ankle_height"])
    )
    body = _body(take, stature)
    rows = _tree(convention, prefix)
    world = np.stack([body[r] for r, _, _ in rows], axis=1)  # (T, J, 3)
    if fps is not None and abs(fps - take.fps) > 1e-9:
        t_src = np.arange(world.shape[0]) / take.fps
        t_out = np.arange(int(np.floor(t_src[-1] * fps + 1e-6)) + 1) / fps
        world = CubicSpline(t_src, world, axis=0)(t_out)
    rate = take.fps if fps is None else fps
    index = {r: k for k, (r, _, _) in enumerate(rows)}
    local = world.copy()
    for k, (_, _, parent) in enumerate(rows):
        if parent is not None:
            local[:, k] = world[:, k] - world[:, index[parent]]
    f = local if up == "z" else np.stack([local[..., 0], local[..., 2], -local[..., 1]], -1)
    f = f / scale
    zeros = np.zeros(f.shape[:2] + (3,))
    values = np.concatenate([f, zeros], axis=2).reshape(f.shape[0], -1)
    body_text = "\n".join(" ".join(f"{v:.6f}" for v in row) for row in values)
    text = (
        _hierarchy(rows)
        + f"MOTION\nFrames: {values.shape[0]}\nFrame Time: {1.0 / rate:.8f}\n{body_text}\n"
    )
    out = Path(path)
    out.write_text(text, encoding="utf-8")
    return out
