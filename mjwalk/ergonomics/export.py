"""The humanoid's motion for other tools: a timeline as BVH, or as a joint-angle CSV.

BVH (:func:`write_bvh`): one BVH joint per humanoid body, named as the body (``pelvis``,
``lumbar``, ``thorax``, ``upper_arm_l`` ...), the root with its world position and rotation, every
other joint with one rotation channel per hinge of its body, in the body's order, so a channel
holds the hinge's angle (degrees; negated where the hinge turns about a negative axis). Axes: Y
up, the character facing +Z in its rest pose, X to its left (the convention of most BVH tools:
humanoid x -> BVH Z, y -> X, z -> Y); lengths in centimetres. MuJoCo composes the hinges of a
body in order about axes turned by the ones before, exactly as a BVH channel list (``Zrotation
Xrotation`` is R = Rz Rx), so mjwalk's own reader (:func:`mjwalk.mocap.bvh.parse_bvh`) gives back
the hinge angles (:func:`bvh_hinge_angles`) and its forward kinematics the bodies' positions.

CSV (:func:`write_angles_csv`): one row per frame, time (s), the root's position (m) and
quaternion (w, x, y, z), every hinge's angle in degrees, then the ergonomic body angles of
:mod:`mjwalk.ergonomics.angles` (degrees).
"""

from __future__ import annotations

import csv
from dataclasses import dataclass
from pathlib import Path

import mujoco
import numpy as np
from scipy.spatial.transform import Rotation

from mjwalk._io import atomic_path
from mjwalk.ergonomics.angles import angles_from_timeline
from mjwalk.errors import MjwalkError

#: Humanoid frame -> BVH frame (rows: BVH X, Y, Z in humanoid coordinates).
P = np.array([[0.0, 1.0, 0.0], [0.0, 0.0, 1.0], [1.0, 0.0, 0.0]])
#: Humanoid axis index -> BVH channel axis letter.
_AXIS = {0: "Z", 1: "X", 2: "Y"}
#: Metres -> BVH units (centimetres).
CM = 100.0
#: The root's rotation channels (intrinsic, BVH axes).
ROOT_ORDER = "ZXY"


@dataclass
class _Joint:
    name: str
    parent: int  # index in the joint list, -1 root
    offset: np.ndarray  # BVH units and axes
    hinges: list[tuple[str, int, str, float]]  # (hinge name, qpos adr, axis letter, sign)


def _skeleton(model, jointmap) -> list[_Joint]:
    """The humanoid's bodies as BVH joints, in tree (depth-first) order."""
    prefix = jointmap.prefix
    root = mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_BODY, prefix + "pelvis")
    if root < 0:
        raise MjwalkError("BVH export: the model has no humanoid (no body 'pelvis')")
    children: dict[int, list[int]] = {}
    for b in range(model.nbody):
        children.setdefault(int(model.body_parentid[b]), []).append(b)
    out: list[_Joint] = []

    def visit(b: int, parent: int) -> None:
        if b != root and not np.allclose(model.body_quat[b], [1, 0, 0, 0]):
            raise MjwalkError("BVH export: a humanoid body is rotated in its parent")
        hinges = []
        for j in range(model.body_jntadr[b], model.body_jntadr[b] + model.body_jntnum[b]):
            if model.jnt_type[j] != mujoco.mjtJoint.mjJNT_HINGE:
                continue
            ax = model.jnt_axis[j]
            k = int(np.argmax(np.abs(ax)))
            if abs(abs(ax[k]) - 1.0) > 1e-9:
                raise MjwalkError("BVH export: a hinge axis is not a body axis")
            name = mujoco.mj_id2name(model, mujoco.mjtObj.mjOBJ_JOINT, j)[len(prefix) :]
            hinges.append((name, int(model.jnt_qposadr[j]), _AXIS[k], float(np.sign(ax[k]))))
        name = mujoco.mj_id2name(model, mujoco.mjtObj.mjOBJ_BODY, b)[len(prefix) :]
        offset = np.zeros(3) if b == root else P @ model.body_pos[b] * CM
        out.append(_Joint(name, parent, offset, hinges))
        me = len(out) - 1
        for c in children.get(b, []):
            visit(c, me)

    visit(root, -1)
    return out


def write_bvh(timeline, path: str | Path) -> Path:
    """Write the humanoid's motion of a Timeline as BVH (see the module docstring); atomic.

    Args:
        timeline: the humanoid's timeline.
        path: the BVH file to write.

    Returns:
        ``path`` as a Path.
    """
    model, jm = timeline.model, timeline.jointmap
    joints = _skeleton(model, jm)
    q = np.asarray(timeline.qpos, dtype=float)
    r = jm.root
    pos = q[:, r : r + 3] @ P.T * CM
    quat = q[:, r + 3 : r + 7]
    rot = Rotation.from_quat(quat[:, [1, 2, 3, 0]]).as_matrix()  # scipy: x, y, z, w
    euler = Rotation.from_matrix(P @ rot @ P.T).as_euler(ROOT_ORDER, degrees=True)
    cols = [pos, euler]
    lines = ["HIERARCHY"]
    depth_of = {-1: -1}
    open_stack: list[int] = []
    for i, jt in enumerate(joints):
        depth = depth_of[jt.parent] + 1
        depth_of[i] = depth
        while open_stack and depth_of[open_stack[-1]] >= depth:
            k = open_stack.pop()
            lines.append("\t" * depth_of[k] + "}")
        ind = "\t" * depth
        lines.append(f"{ind}{'ROOT' if jt.parent < 0 else 'JOINT'} {jt.name}")
        lines.append(ind + "{")
        lines.append(f"{ind}\tOFFSET {jt.offset[0]:.6f} {jt.offset[1]:.6f} {jt.offset[2]:.6f}")
        if jt.parent < 0:
            chans = ["Xposition", "Yposition", "Zposition"] + [f"{a}rotation" for a in ROOT_ORDER]
        else:
            chans = [f"{a}rotation" for _, _, a, _ in jt.hinges]
            for _, adr, _, sign in jt.hinges:
                cols.append((np.degrees(q[:, adr]) * sign)[:, None])
        lines.append(f"{ind}\tCHANNELS {len(chans)} {' '.join(chans)}".rstrip())
        open_stack.append(i)
    while open_stack:
        k = open_stack.pop()
        lines.append("\t" * depth_of[k] + "}")
    motion = np.hstack(cols)
    lines += ["MOTION", f"Frames: {len(q)}", f"Frame Time: {1.0 / timeline.fps:.8f}"]
    body = "\n".join(" ".join(f"{v:.6f}" for v in row) for row in motion)
    path = Path(path)
    with atomic_path(path) as tmp:
        tmp.write_text("\n".join(lines) + "\n" + body + "\n")
    return path


def bvh_hinge_angles(bvh, model, jointmap) -> dict[str, np.ndarray]:
    """The humanoid's hinge angles in a BVH file written by :func:`write_bvh`.

    Args:
        bvh: the file as read by :func:`mjwalk.mocap.bvh.parse_bvh`.
        model: the compiled model with the humanoid.
        jointmap: the humanoid's joint map.

    Returns:
        Each hinge's (F,) angles, radians, by unprefixed joint name.

    Raises:
        MjwalkError: a joint's channel is not the one :func:`write_bvh` writes.
    """
    joints = {jt.name: jt for jt in _skeleton(model, jointmap)}
    out: dict[str, np.ndarray] = {}
    col = 0
    for name, chans in zip(bvh.names, bvh.channels, strict=True):
        jt = joints.get(name)
        if jt is not None and jt.parent >= 0:
            for k, (hinge, _, axis, sign) in enumerate(jt.hinges):
                if chans[k] != f"{axis.lower()}rotation":
                    raise MjwalkError(f"{bvh.path}: joint {name!r} channel {chans[k]!r} unexpected")
                out[hinge] = np.radians(bvh.motion[:, col + k]) * sign
        col += len(chans)
    return out


def write_angles_csv(timeline, path: str | Path, walking: np.ndarray | None = None) -> Path:
    """Write the motion of a Timeline as a joint-angle CSV (see the module docstring); atomic.

    Args:
        timeline: the humanoid's timeline.
        path: the CSV file to write.
        walking: (F,) frames of a walk (for the body angles, :func:`angles_from_timeline`).

    Returns:
        ``path`` as a Path.
    """
    model, jm = timeline.model, timeline.jointmap
    q = np.asarray(timeline.qpos, dtype=float)
    hinges = [
        (n, jm.adr(n))
        for n in jm.names
        if model.jnt_type[mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_JOINT, jm.prefix + n)]
        == mujoco.mjtJoint.mjJNT_HINGE
    ]
    ang = angles_from_timeline(timeline, walking)
    body = {
        "trunk_flexion": ang.trunk_flexion, "trunk_side_bend": ang.trunk_side_bend,
        "trunk_twist": ang.trunk_twist, "neck_flexion": ang.neck_flexion,
        "upper_arm_l": ang.upper_arm_angle[:, 0], "upper_arm_r": ang.upper_arm_angle[:, 1],
        "upper_arm_elevation_l": ang.upper_arm_elevation[:, 0],
        "upper_arm_elevation_r": ang.upper_arm_elevation[:, 1],
        "elbow_l": ang.elbow_flexion[:, 0], "elbow_r": ang.elbow_flexion[:, 1],
        "knee_l": ang.knee_flexion[:, 0], "knee_r": ang.knee_flexion[:, 1],
    }  # fmt: skip
    r = jm.root
    head = ["time_s", "root_x_m", "root_y_m", "root_z_m", "root_qw", "root_qx", "root_qy"]
    head += ["root_qz", *(f"{n}_deg" for n, _ in hinges), *(f"body_{k}_deg" for k in body)]
    path = Path(path)
    with atomic_path(path) as tmp, open(tmp, "w", newline="") as fh:
        w = csv.writer(fh)
        w.writerow(head)
        for f in range(len(q)):
            w.writerow(
                [f"{timeline.t[f]:.4f}", *(f"{v:.6f}" for v in q[f, r : r + 7])]
                + [f"{np.degrees(q[f, a]):.4f}" for _, a in hinges]
                + [f"{v[f]:.4f}" for v in body.values()]
            )
    return path
