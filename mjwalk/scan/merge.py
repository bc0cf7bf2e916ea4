"""Several scans of one hall as one cloud (the seed paper's pipeline starts from the merged,
registered scans, §3 A1).

Each file is read on its own (:func:`~mjwalk.scan.read.read_scan`: metres, z up, the same
``units``, ``up`` and ``offset`` for every file), then brought into the first file's frame:

- already registered scans (one frame, as scanner software exports them; an E57 file's own
  scans are moved by their poses when read) are merged as they are;
- known poses (``poses``: a 4 x 4 matrix per file, metres, z up, taking that file's points into
  the first file's frame; a JSON file ``{"B.ply": [[...4 rows...]], ...}`` for the command
  line, :func:`read_poses`) are applied.

- unregistered scans (``register=True``, ``mjwalk scan --register``): each scan after the
  first that has no known pose is aligned to the merged scans before it
  (:func:`~mjwalk.scan.register.align`: levelling, Open3D FPFH + RANSAC, ICP, verified
  by free space), and refused by name when that alignment cannot be trusted.

Registration is not automatic: merging scans already in one frame stays the fast path, and a
scan whose alignment is refused must not be merged by guesswork.

Registration attempts that failed (kept for whoever improves it): on two ray-cast stations of
the shipped station, (0.2, -1.2) and (0.0, 2.75), 1.5 m high, the second moved by 25° and
(1.2, -0.7, 0.1) m, Open3D's FPFH + RANSAC + point-to-plane ICP and a heading search over
top-view correlation verified by ICP both merged it 2.3-3.0 m wrong with 73-87 % of its points
matched within 3 cm, while at the true pose only 3.6 % match (the two views share almost no
surface): fitness cannot tell a wrong merge from a right one. The free-space check of
:mod:`~mjwalk.scan.register` refutes those placements (22-25 % of their low points on floor
the other station saw empty) but passed one 1.80 m off (the car's far side laid on its near
side from behind, 6.3 %), which the refuted ones outmatch, so the pair is refused as not
fixing the pose (``register`` module docstring, 4); the heading search also missed the true
heading of the shared PCL room scan split into two views overlapping by 60°, where FPFH +
RANSAC found it.
"""

from __future__ import annotations

import json
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from mjwalk.errors import ScanError
from mjwalk.scan.read import ScanCloud, Station, read_scan
from mjwalk.scan.register import Alignment, align

#: A pose's rotation part must be orthonormal with determinant +1 to this tolerance.
POSE_TOL = 1e-6


@dataclass
class MergedCloud:
    """The merged cloud: ``points`` (N, 3) metres, z up, in the first file's frame; ``clouds``
    the files as read; ``poses`` the 4 x 4 pose applied to each file's points (metres, z up);
    ``stations`` the scanner positions the files state, moved into that frame with their rows
    of ``points`` (a file that states none adds none).
    """

    points: np.ndarray
    clouds: list[ScanCloud]
    poses: list[np.ndarray]
    alignments: list[Alignment] = field(default_factory=list)
    stations: list[Station] = field(default_factory=list)

    @property
    def first(self) -> ScanCloud:
        return self.clouds[0]


def check_pose(matrix, where: str) -> np.ndarray:
    """A pose, checked.

    Args:
        matrix: a 4 x 4 matrix of numbers (nested lists or an array).
        where: the pose's name in errors.

    Returns:
        (4, 4) float64 rigid transform.

    Raises:
        ScanError: not 4 x 4 numbers, a non-finite entry (named by row and column), or not rigid
            (rotation orthonormal with determinant 1 within :data:`POSE_TOL`, last row 0 0 0 1).
    """
    try:
        m = np.asarray(matrix, dtype=np.float64)
    except (TypeError, ValueError):
        raise ScanError(f"{where}: a pose is a 4 x 4 matrix of numbers") from None
    if m.shape != (4, 4):
        raise ScanError(f"{where}: a pose is a 4 x 4 matrix of numbers, got shape {m.shape}")
    if not np.isfinite(m).all():
        i, j = (int(k) for k in np.argwhere(~np.isfinite(m))[0])
        raise ScanError(
            f"{where}: entry {m[i, j]} at row {i + 1}, column {j + 1} (counting from 1; JSON "
            "null reads as nan) is not a finite number"
        )
    r = m[:3, :3]
    if (
        not np.allclose(r.T @ r, np.eye(3), atol=POSE_TOL)
        or abs(np.linalg.det(r) - 1) > POSE_TOL
        or not np.allclose(m[3], [0, 0, 0, 1])
    ):
        raise ScanError(
            f"{where}: not a rigid pose (the rotation must be orthonormal with determinant 1 "
            "and the last row 0 0 0 1)"
        )
    return m


def read_poses(path: str | Path, scans: Sequence[Path]) -> dict[Path, np.ndarray]:
    """Poses from a JSON file keyed by the scan files' names.

    ``{"B.ply": [[r00, r01, r02, tx], ..., [0, 0, 0, 1]]}``, metres, z up. Files not named keep
    the identity (they are in the first file's frame).

    Args:
        path: the JSON file.
        scans: the scan files given; keys name them as given or by their base names.

    Returns:
        The (4, 4) pose of each named scan.

    Raises:
        ScanError: a missing or malformed file, a key naming no scan, a bad pose.
    """
    path = Path(path)
    if path.is_dir():
        raise ScanError(f"{path} is a folder, not a poses file")
    try:
        doc = json.loads(path.read_text())
    except FileNotFoundError:
        raise ScanError(f"{path}: poses file not found") from None
    except (json.JSONDecodeError, UnicodeDecodeError, RecursionError) as exc:
        raise ScanError(f"{path}: not a JSON poses file: {exc}") from None
    if not isinstance(doc, dict):
        raise ScanError(f"{path}: a poses file is a JSON object {{scan name: 4x4 matrix}}")
    by_name = {str(s): s for s in scans} | {s.name: s for s in scans}
    out = {}
    for key, matrix in doc.items():
        if key not in by_name:
            names = ", ".join(sorted({s.name for s in scans}))
            raise ScanError(f"{path}: pose for {key!r}, which is not a scan given ({names})")
        out[by_name[key]] = check_pose(matrix, f"{path}: pose of {key!r}")
    return out


def apply_pose(points: np.ndarray, pose: np.ndarray) -> np.ndarray:
    """Points moved by a pose.

    Args:
        points: (N, 3) points, metres.
        pose: (4, 4) rigid transform.

    Returns:
        (N, 3) ``R p + t``.
    """
    return points @ pose[:3, :3].T + pose[:3, 3]


def merge_scans(
    scans: Sequence[str | Path],
    *,
    units: str = "m",
    up: str = "+z",
    drop_invalid: bool = False,
    offset=None,
    poses: dict[Path, np.ndarray] | None = None,
    register: bool = False,
    report: Callable[[str], None] | None = None,
) -> MergedCloud:
    """Read scans and merge them into the first file's frame (module docstring).

    Args:
        scans: the scan files of one hall, the first one's frame the merge's.
        units: the files' length unit when they do not say.
        up: the files' up axis when they do not say.
        drop_invalid: leave out NaN or infinite points instead of refusing them.
        offset: (3,) subtracted from every file's points first, file units and axes (None: none).
        poses: (4, 4) pose per file (metres, z up) into the first one's frame; others identity.
        register: align the scans after the first without a pose to the scans before them.
        report: called with each alignment's line (fitness, RMSE).

    Returns:
        The merged cloud (metres, z up, first file's frame), its clouds, alignments and stations.

    Raises:
        ScanError: any file's reading errors, a file given twice, a bad pose, a scan that
            could not be aligned (naming it).
    """
    paths = [Path(s) for s in scans]
    if not paths:
        raise ScanError("no scan files given")
    dup = {p for p in paths if paths.count(p) > 1}
    if dup:
        raise ScanError(f"{sorted(map(str, dup))[0]}: the same scan is given twice")
    poses = poses or {}
    clouds = [
        read_scan(p, units=units, up=up, drop_invalid=drop_invalid, offset=offset) for p in paths
    ]
    placed: list[np.ndarray] = []
    applied = []
    alignments = []
    for i, cloud in enumerate(clouds):
        pose = poses.get(cloud.source, np.eye(4))
        if register and i and cloud.source not in poses:
            found = align(cloud.points, np.concatenate(placed), source=str(cloud.source))
            alignments.append(found)
            if report is not None:
                report(found.line())
            pose = found.matrix
        identity = np.array_equal(pose, np.eye(4))
        placed.append(cloud.points if identity else apply_pose(cloud.points, pose))
        applied.append(pose)
    points = placed[0] if len(placed) == 1 else np.concatenate(placed)
    stations = []
    shift = 0
    for cloud, pose, part in zip(clouds, applied, placed, strict=True):
        stations += [s.moved(pose, shift) for s in cloud.stations]
        shift += len(part)
    return MergedCloud(points, clouds, applied, alignments, stations)
