"""ASF/AMC import (Acclaim format, as in the CMU Graphics Lab database) to a 120 Hz Take.

Forward kinematics follows the Acclaim/CMU convention:

* every bone has a rest direction (unit vector, ASF world frame), a length and an ``axis``
  (three angles plus an order, e.g. ``0 0 20 XYZ``) giving the bone's local frame C;
* its rotation relative to the parent is ``L = C · M · C⁻¹`` with ``M = Rz·Ry·Rx`` of the AMC
  channels (missing dofs are zero), i.e. x applied first (scipy extrinsic ``"xyz"``);
* ``R_w(bone) = R_w(parent) · L`` and the bone's end is ``start + R_w(bone) · direction · length``;
  its start is the parent's end (the root's position for the root's children);
* the root is translated by its TX/TY/TZ channels (plus the ASF ``position``) and rotated by its
  RX/RY/RZ channels composed in the root's ``axis`` order, conjugated by the ASF ``orientation``.

``Take.joints[bone]`` is the position of the joint a bone *starts* at (``lfemur`` = hip,
``lfoot`` = ankle, ``ltoes`` = ball of the foot), ``joints["root"]`` the root, and
``joints[f"{leaf}_end"]`` the end of every leaf bone.
"""

from __future__ import annotations

import os
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np
from scipy.spatial.transform import Rotation

from mjwalk.errors import CaptureError
from mjwalk.mocap.skeletons import SkeletonMap, check_joints, get_skeleton, take_from_positions
from mjwalk.mocap.take import TAKE_FPS, Take

#: Frame rate of CMU AMC files (Hz); AMC files do not record their rate.
CMU_AMC_FPS = 120.0

_ROT_DOFS = ("rx", "ry", "rz")


@dataclass
class AsfBone:
    """One ASF bone: rest ``direction`` (unit, ASF frame), ``length`` (ASF units), ``axis``."""

    name: str
    direction: np.ndarray
    length: float
    axis: np.ndarray  # (3,) angles in the ASF angle unit
    axis_order: str  # e.g. "XYZ"
    dof: list[str] = field(default_factory=list)
    parent: str | None = None
    line: int = 0


@dataclass
class Asf:
    """A parsed ASF skeleton.

    Attributes:
        path: the file read.
        length_unit: the ``:units length`` value (CMU: 0.45).
        degrees: True when ``:units angle deg`` (the default), False for radians.
        root_order: the root's channel order in AMC lines, e.g. ``["tx", ..., "rz"]``.
        root_axis: the root's rotation order, e.g. ``"XYZ"``.
        root_position, root_orientation: (3,) rest translation (length units) and rotation angles.
        bones: bones by name, in file order; ``parent`` is ``"root"`` or another bone's name.
    """

    path: Path
    length_unit: float
    degrees: bool
    root_order: list[str]
    root_axis: str
    root_position: np.ndarray
    root_orientation: np.ndarray
    bones: dict[str, AsfBone]


def _read_lines(path: Path, kind: str) -> list[str]:
    try:
        return path.read_text(encoding="utf-8", errors="replace").splitlines()
    except OSError as exc:
        raise CaptureError(f"{path}: cannot read {kind} file ({exc.strerror or exc})") from None


def _floats(parts: list[str], n: int, path, lineno: int, what: str) -> np.ndarray:
    if len(parts) < n:
        raise CaptureError(f"{path}, line {lineno}: {what} needs {n} values, found {len(parts)}")
    try:
        return np.array([float(p) for p in parts[:n]])
    except ValueError:
        raise CaptureError(f"{path}, line {lineno}: {what}: {parts[:n]} are not numbers") from None


def _order(token: str, path, lineno: int) -> str:
    order = token.upper()
    if len(order) != 3 or sorted(order) != ["X", "Y", "Z"]:
        raise CaptureError(f"{path}, line {lineno}: bad rotation order {token!r}")
    return order


class _AsfReader:
    """An ASF file's sections as they are read line by line (:func:`parse_asf`): the units, the
    root, the bones and the hierarchy. Every error names the file and the line."""

    def __init__(self, path: Path) -> None:
        self.path = path
        self.length_unit, self.degrees = 1.0, True
        self.root_order = ["tx", "ty", "tz", "rx", "ry", "rz"]
        self.root_axis = "XYZ"
        self.root_pos, self.root_ori = np.zeros(3), np.zeros(3)
        self.bones: dict[str, AsfBone] = {}
        self.current: dict | None = None  # the bone between begin and end
        self.in_hierarchy = False
        self.seen_hierarchy = False

    def _error(self, lineno: int, msg: str) -> CaptureError:
        return CaptureError(f"{self.path}, line {lineno}: {msg}")

    def read(self, lines: list[str]) -> Asf:
        """Read ``lines`` (the whole file) and check the skeleton is complete."""
        path = self.path
        section = None
        for lineno, raw in enumerate(lines, start=1):
            line = raw.split("#", 1)[0].strip()
            if not line:
                continue
            parts = line.split()
            key = parts[0].lower()
            if key.startswith(":"):
                if self.current is not None:
                    raise self._error(lineno, f"{parts[0]} inside an unfinished bone")
                section = key
                if section == ":units" and len(parts) > 1:
                    parts = parts[1:]
                    key = parts[0].lower()
                else:
                    continue
            if section == ":units":
                self._units(key, parts, lineno)
            elif section == ":root":
                self._root(key, parts, lineno)
            elif section == ":bonedata":
                self._bonedata(key, parts, lineno)
            elif section == ":hierarchy":
                self._hierarchy(key, parts, lineno)
        if self.current is not None:
            raise self._error(
                len(lines), f"file ends inside bone begun at line {self.current['line']}"
            )
        if not self.seen_hierarchy:
            raise CaptureError(f"{path}: no :hierarchy section")
        orphans = [b.name for b in self.bones.values() if b.parent is None]
        if orphans:
            raise CaptureError(f"{path}: bone {orphans[0]!r} is missing from :hierarchy")
        _check_acyclic(self.bones, path)
        return Asf(
            path, self.length_unit, self.degrees, self.root_order, self.root_axis,
            self.root_pos, self.root_ori, self.bones,
        )  # fmt: skip

    def _units(self, key: str, parts: list[str], lineno: int) -> None:
        if key == "length":
            self.length_unit = float(_floats(parts[1:], 1, self.path, lineno, "units length")[0])
            if self.length_unit <= 0:
                raise self._error(lineno, "units length must be positive")
        elif key == "angle":
            self.degrees = not (len(parts) > 1 and parts[1].lower().startswith("rad"))

    def _root(self, key: str, parts: list[str], lineno: int) -> None:
        path = self.path
        if key == "order":
            self.root_order = [p.lower() for p in parts[1:]]
            bad = [p for p in self.root_order if p not in ("tx", "ty", "tz", "rx", "ry", "rz")]
            if bad:
                raise self._error(lineno, f"unknown root channel {bad[0]!r}")
        elif key == "axis":
            self.root_axis = _order(parts[1] if len(parts) > 1 else "", path, lineno)
        elif key == "position":
            self.root_pos = _floats(parts[1:], 3, path, lineno, "root position")
        elif key == "orientation":
            self.root_ori = _floats(parts[1:], 3, path, lineno, "root orientation")

    def _bonedata(self, key: str, parts: list[str], lineno: int) -> None:
        path, current = self.path, self.current
        if key == "begin":
            if current is not None:
                raise self._error(lineno, "'begin' inside a bone")
            self.current = {"line": lineno}
        elif key == "end":
            if current is None:
                raise self._error(lineno, "'end' without 'begin'")
            bone = _finish_bone(current, path, lineno)
            if bone.name in self.bones or bone.name == "root":
                raise self._error(lineno, f"bone {bone.name!r} defined twice")
            self.bones[bone.name] = bone
            self.current = None
        elif current is None:
            raise self._error(lineno, f"{parts[0]!r} outside begin/end")
        elif key == "name":
            current["name"] = parts[1] if len(parts) > 1 else ""
        elif key == "direction":
            current["direction"] = _floats(parts[1:], 3, path, lineno, "direction")
        elif key == "length":
            current["length"] = float(_floats(parts[1:], 1, path, lineno, "length")[0])
        elif key == "axis":
            current["axis"] = _floats(parts[1:], 3, path, lineno, "axis")
            current["axis_order"] = _order(parts[4] if len(parts) > 4 else "XYZ", path, lineno)
        elif key == "dof":
            dof = [p.lower() for p in parts[1:]]
            bad = [d for d in dof if d not in _ROT_DOFS]
            if bad:
                raise self._error(
                    lineno,
                    f"unsupported dof {bad[0]!r} (only rotations rx/ry/rz are supported)",
                )
            current["dof"] = dof
        # id, limits and their continuation lines, bodymass, cofmass: not needed

    def _hierarchy(self, key: str, parts: list[str], lineno: int) -> None:
        bones = self.bones
        if key == "begin":
            self.in_hierarchy, self.seen_hierarchy = True, True
        elif key == "end":
            self.in_hierarchy = False
        elif self.in_hierarchy:
            parent = parts[0]
            if parent != "root" and parent not in bones:
                raise self._error(lineno, f"unknown parent bone {parent!r}")
            for child in parts[1:]:
                if child not in bones:
                    raise self._error(lineno, f"unknown bone {child!r}")
                if bones[child].parent is not None:
                    raise self._error(
                        lineno,
                        f"bone {child!r} has two parents ({bones[child].parent!r} and {parent!r})",
                    )
                bones[child].parent = parent


def parse_asf(path: str | os.PathLike) -> Asf:
    """Read an ASF skeleton; malformed files raise :class:`CaptureError` naming file and line.

    Args:
        path: the ``.asf`` file.

    Returns:
        The skeleton: units, the root's channel order, axis and rest pose, and its bones
        (rest direction, length in the file's length units, axis, rotation dofs, parent).
    """
    path = Path(path)
    return _AsfReader(path).read(_read_lines(path, "ASF"))


def _finish_bone(current: dict, path, lineno: int) -> AsfBone:
    for key in ("name", "direction", "length"):
        if key not in current or (key == "name" and not current[key]):
            raise CaptureError(
                f"{path}, line {lineno}: bone begun at line {current['line']} has no {key!r}"
            )
    direction = current["direction"]
    norm = np.linalg.norm(direction)
    return AsfBone(
        name=current["name"],
        direction=direction / norm if norm > 0 else direction,
        length=current["length"],
        axis=current.get("axis", np.zeros(3)),
        axis_order=current.get("axis_order", "XYZ"),
        dof=current.get("dof", []),
        line=current["line"],
    )


def _check_acyclic(bones: dict[str, AsfBone], path) -> None:
    for bone in bones.values():
        seen, b = set(), bone
        while b.parent != "root":
            assert b.parent is not None  # parse_asf refuses bones missing from :hierarchy
            if b.name in seen:
                raise CaptureError(f"{path}: :hierarchy has a cycle through bone {b.name!r}")
            seen.add(b.name)
            b = bones[b.parent]


def parse_amc(path: str | os.PathLike, asf: Asf) -> tuple[dict[str, np.ndarray], bool]:
    """Read an AMC motion for ``asf``: per bone (and ``"root"``) a (T, n_dof) array of values.

    Every frame must list every bone that has dofs, with exactly its dof count.

    Args:
        path: the ``.amc`` file.
        asf: the skeleton it was captured with (:func:`parse_asf`).

    Returns:
        The (T, n_dof) arrays by bone name (root: its ``root_order`` channels, translations in
        ASF length units), and whether angles are in degrees (``:DEGREES``, else the ASF unit).
    """
    path = Path(path)
    lines = _read_lines(path, "AMC")
    counts = {"root": len(asf.root_order)}
    counts.update({b.name: len(b.dof) for b in asf.bones.values() if b.dof})
    degrees = asf.degrees
    rows: dict[str, list[list[str]]] = {name: [] for name in counts}
    frame_line = None
    n_frames = 0
    for lineno, raw in enumerate(lines, start=1):
        line = raw.strip()
        if not line or line.startswith("#"):
            continue
        if line.startswith(":"):
            if line.upper().startswith(":DEGREES"):
                degrees = True
            elif line.upper().startswith(":RADIANS"):
                degrees = False
            continue
        parts = line.split()
        if len(parts) == 1 and parts[0].isdigit():
            if n_frames:
                _check_frame(rows, n_frames, path, frame_line, lineno - 1)
            n_frames += 1
            frame_line = lineno
            continue
        name = parts[0]
        if name not in counts:
            where = f"bone {name!r}" if name in asf.bones else f"unknown bone {name!r}"
            raise CaptureError(f"{path}, line {lineno}: {where} has no dofs in {asf.path.name}")
        if n_frames == 0:
            raise CaptureError(f"{path}, line {lineno}: bone values before the first frame number")
        if len(parts) - 1 != counts[name]:
            raise CaptureError(
                f"{path}, line {lineno}: bone {name!r} has {len(parts) - 1} values, "
                f"{asf.path.name} declares {counts[name]} dofs"
            )
        if len(rows[name]) >= n_frames:
            raise CaptureError(f"{path}, line {lineno}: bone {name!r} twice in frame {n_frames}")
        rows[name].append(parts[1:])
    if n_frames == 0:
        raise CaptureError(f"{path}: no frames")
    _check_frame(rows, n_frames, path, frame_line, len(lines))
    out = {}
    for name, r in rows.items():
        try:
            out[name] = np.array(r, dtype=float).reshape(n_frames, counts[name])
        except ValueError:
            raise CaptureError(f"{path}: bone {name!r} has a value that is not a number") from None
    return out, degrees


def _check_frame(rows, n_frames: int, path, frame_line, last_line: int) -> None:
    missing = [name for name, r in rows.items() if len(r) < n_frames]
    if missing:
        raise CaptureError(
            f"{path}, line {last_line}: frame {n_frames} (from line {frame_line}) is truncated: "
            f"bone {missing[0]!r} missing"
        )


def _bone_frame(bone: AsfBone, degrees: bool) -> np.ndarray:
    return Rotation.from_euler(bone.axis_order.lower(), bone.axis, degrees=degrees).as_matrix()


def amc_forward_kinematics(
    asf: Asf, motion: dict[str, np.ndarray], degrees: bool
) -> tuple[np.ndarray, list[str]]:
    """World joint positions in ASF units and axes, and their names (see module doc).

    Args:
        asf: the skeleton (:func:`parse_asf`).
        motion: its motion by bone name, (T, n_dof) each (:func:`parse_amc`).
        degrees: whether the motion's angles are in degrees (else radians).

    Returns:
        (T, J, 3) joint positions (ASF length units, ASF axes) and the J joint names
        (``"root"``, each bone's start, ``<leaf>_end`` for leaf bones' ends).
    """
    n = motion["root"].shape[0]
    root = motion["root"]
    trans = np.tile(asf.root_position, (n, 1))
    angles = np.zeros((n, 3))
    for k, ch in enumerate(asf.root_order):
        if ch[0] == "t":
            trans[:, "xyz".index(ch[1])] += root[:, k]
        else:
            angles[:, "xyz".index(ch[1])] = root[:, k]
    seq = asf.root_axis.lower()
    ordered = angles[:, ["xyz".index(c) for c in seq]]
    c_root = Rotation.from_euler(seq, asf.root_orientation, degrees=degrees).as_matrix()
    m_root = Rotation.from_euler(seq, ordered, degrees=degrees).as_matrix()
    rot = {"root": c_root @ m_root @ c_root.T}
    end = {"root": trans}
    names, columns = ["root"], [trans]
    children = {b.parent for b in asf.bones.values()}
    for bone in _topological(asf.bones):
        assert bone.parent is not None  # parse_asf refuses bones missing from :hierarchy
        c = _bone_frame(bone, asf.degrees)
        parent_r = rot[bone.parent]
        if bone.dof:
            angles = np.zeros((n, 3))
            values = motion[bone.name]
            for k, d in enumerate(bone.dof):
                angles[:, _ROT_DOFS.index(d)] = values[:, k]
            m = Rotation.from_euler("xyz", angles, degrees=degrees).as_matrix()
            r = parent_r @ (c @ m @ c.T)
        else:
            r = parent_r
        start = end[bone.parent]
        vec = bone.direction * bone.length
        end[bone.name] = start + r @ vec
        rot[bone.name] = r
        names.append(bone.name)
        columns.append(start)
        if bone.name not in children:
            names.append(f"{bone.name}_end")
            columns.append(end[bone.name])
    return np.stack(columns, axis=1), names


def _topological(bones: dict[str, AsfBone]) -> list[AsfBone]:
    done, order = {"root"}, []
    pending = list(bones.values())
    while pending:
        rest = []
        for b in pending:
            if b.parent in done:
                order.append(b)
                done.add(b.name)
            else:
                rest.append(b)
        pending = rest
    return order


def load_amc(
    amc_path: str | os.PathLike,
    asf_path: str | os.PathLike,
    skeleton: SkeletonMap | str = "cmu",
    fps: float = TAKE_FPS,
    amc_fps: float = CMU_AMC_FPS,
) -> Take:
    """Load an ASF skeleton and AMC motion as a :class:`Take` (metres, z up, ``fps`` Hz).

    Args:
        amc_path: the ``.amc`` motion.
        asf_path: the ``.asf`` skeleton it was captured with.
        skeleton: a :class:`SkeletonMap` or preset name (default ``"cmu"``); its ``scale`` is
            metres per ASF unit, adjusted by ``asf_length / (:units length)`` when set.
        fps: output sampling rate (Hz).
        amc_fps: the AMC's own rate (Hz); AMC files do not record it (CMU: 120).

    Raises:
        CaptureError: missing/malformed files, wrong value counts, a truncated last frame, or
            a joint named by ``skeleton`` that the ASF lacks.

    Returns:
        The take at ``fps`` Hz: metres, z up, yaw from +x CCW.
    """
    skel = get_skeleton(skeleton)
    asf = parse_asf(asf_path)
    motion, degrees = parse_amc(amc_path, asf)
    positions, names = amc_forward_kinematics(asf, motion, degrees)
    check_joints(skel, names, asf.path)
    scale = skel.scale
    if skel.asf_length is not None:
        scale *= skel.asf_length / asf.length_unit
    return take_from_positions(
        positions,
        names,
        skel,
        src_fps=amc_fps,
        fps=fps,
        name=Path(amc_path).name,
        scale=scale,
        meta={"file": str(amc_path), "asf": str(asf.path)},
    )
