"""Skeleton presets: which joints of a capture file are the pelvis, hips, ankles and toes.

A :class:`SkeletonMap` tells the importers (:func:`mjwalk.mocap.load_bvh`,
:func:`mjwalk.mocap.load_amc`) how to turn a capture skeleton into a :class:`~mjwalk.mocap.Take`:
the names of the few joints the :class:`Take` needs, the factor from file units to metres, and the
file's up axis (files with y up are rotated to z up by world = (x, -z, y), a proper rotation of
+90 deg about x, so handedness is kept).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Literal

import numpy as np
from scipy.interpolate import CubicSpline

from mjwalk.errors import CaptureError
from mjwalk.mocap.take import Take


@dataclass(frozen=True)
class SkeletonMap:
    """Names of the joints an importer needs, plus units and up axis of the file.

    Attributes:
        name: preset name (for messages and ``Take.meta``).
        pelvis: joint whose world position is the pelvis (hip centre) trajectory.
        ankle_l, ankle_r: ankle joints (the joint the foot rotates about).
        toe_l, toe_r: toe joints (ball of the foot).
        hip_l, hip_r: hip joints (head of the femur); the pelvis yaw is taken from their line.
        scale: metres per file length unit (e.g. 0.01 for centimetres).
        up: the file's up axis, ``"y"`` or ``"z"``.
        guess_scale: read ``scale`` from the body's proportions instead of trusting it
            (:func:`mjwalk.mocap.bodycheck.body_frame`).
        guess_up: read ``up`` from the body (pelvis above the feet) instead of trusting it.
        verify: check the declared scale and up axis against the body, and repair frozen and
            leading/trailing outlier frames (:mod:`mjwalk.mocap.bodycheck`); off for toy
            skeletons whose proportions are not a person's.
        asf_length: for ASF skeletons only, the ``:units length`` value at which ``scale`` holds;
            a file declaring another ``length`` L gets ``scale * asf_length / L``. ``None``: use
            ``scale`` as is.
    """

    name: str
    pelvis: str
    ankle_l: str
    ankle_r: str
    toe_l: str
    toe_r: str
    hip_l: str
    hip_r: str
    scale: float = 1.0
    up: Literal["y", "z"] = "y"
    asf_length: float | None = None
    guess_scale: bool = False
    guess_up: bool = False
    verify: bool = False

    def __post_init__(self) -> None:
        if self.up not in ("y", "z"):
            raise CaptureError(
                f"skeleton {self.name!r}: up axis must be 'y' or 'z', got {self.up!r}"
            )
        if not self.scale > 0:
            raise CaptureError(
                f"skeleton {self.name!r}: scale must be positive, got {self.scale!r}"
            )

    def required_joints(self) -> dict[str, str]:
        """Role -> joint name for every joint the importers look up.

        Returns:
            The joint name by role (pelvis, ankle_l, ankle_r, toe_l, toe_r, hip_l, hip_r).
        """
        return {
            "pelvis": self.pelvis,
            "ankle_l": self.ankle_l,
            "ankle_r": self.ankle_r,
            "toe_l": self.toe_l,
            "toe_r": self.toe_r,
            "hip_l": self.hip_l,
            "hip_r": self.hip_r,
        }


#: Bandai Namco Research Motion Dataset (BVH, centimetres, y up; pelvis trajectory in ``Hips``).
BANDAI = SkeletonMap(
    name="bandai",
    pelvis="Hips",
    ankle_l="Foot_L",
    ankle_r="Foot_R",
    toe_l="Toes_L",
    toe_r="Toes_R",
    hip_l="UpperLeg_L",
    hip_r="UpperLeg_R",
    scale=0.01,
    up="y",
    verify=True,
)

#: CMU Graphics Lab ASF/AMC (y up). ASF bones are named after the bone that *starts* at a joint:
#: ``lfemur`` starts at the hip, ``lfoot`` at the ankle, ``ltoes`` at the ball of the foot.
#: Scale (1/0.45) * 2.54 / 100 m per unit for ``:units length 0.45`` (CMU documentation).
CMU = SkeletonMap(
    name="cmu",
    pelvis="root",
    ankle_l="lfoot",
    ankle_r="rfoot",
    toe_l="ltoes",
    toe_r="rtoes",
    hip_l="lfemur",
    hip_r="rfemur",
    scale=0.056444,
    up="y",
    asf_length=0.45,
)

#: BVH conversions of the CMU database (cgspeed / Bruderlin style names), same units as the ASF.
CMU_BVH = SkeletonMap(
    name="cmu_bvh",
    pelvis="Hips",
    ankle_l="LeftFoot",
    ankle_r="RightFoot",
    toe_l="LeftToeBase",
    toe_r="RightToeBase",
    hip_l="LeftUpLeg",
    hip_r="RightUpLeg",
    scale=0.056444,
    up="y",
    verify=True,
)

#: Presets by name, for ``skeleton="bandai"`` style arguments and the command line.
SKELETONS: dict[str, SkeletonMap] = {s.name: s for s in (BANDAI, CMU, CMU_BVH)}


def get_skeleton(skeleton: SkeletonMap | str) -> SkeletonMap:
    """Return ``skeleton`` itself or the preset of that name; unknown names raise CaptureError.

    Args:
        skeleton: a :class:`SkeletonMap`, or a preset name of :data:`SKELETONS` (any case).

    Returns:
        The skeleton map.
    """
    if isinstance(skeleton, SkeletonMap):
        return skeleton
    try:
        return SKELETONS[str(skeleton).lower()]
    except KeyError:
        raise CaptureError(
            f"unknown skeleton preset {skeleton!r}; known: {', '.join(sorted(SKELETONS))}"
        ) from None


def from_z_up(p, up: str):
    """Inverse of :func:`to_z_up`: z-up world vectors back to the file's frame.

    Args:
        p: (..., 3) world vectors.
        up: the file's up axis, ``"y"`` or ``"z"``.

    Returns:
        The vectors in the file's frame: (x, z, -y) for y up.
    """
    if up == "z":
        return p
    return np.stack([p[..., 0], p[..., 2], -p[..., 1]], axis=-1)


def to_z_up(p, up: str):
    """(..., 3) file-frame vectors -> z-up world; y up maps as world = (x, -z, y).

    Args:
        p: (..., 3) vectors in the file's frame.
        up: the file's up axis, ``"y"`` or ``"z"``.

    Returns:
        The vectors in the z-up world frame (same units).
    """
    if up == "z":
        return p
    if up == "y":
        return np.stack([p[..., 0], -p[..., 2], p[..., 1]], axis=-1)
    raise CaptureError(f"unsupported up axis {up!r} (use 'y' or 'z')")


def hip_line_yaw(hip_l: np.ndarray, hip_r: np.ndarray) -> np.ndarray:
    """Pelvis heading (radians, CCW from +x, unwrapped) from (T, 3) z-up hip positions.

    The forward direction is the right-to-left hip vector rotated by -90 deg in the xy plane:
    yaw = unwrap(atan2(-d_x, d_y)), d = hip_l - hip_r.

    Args:
        hip_l: (T, 3) left hip positions, metres, z up.
        hip_r: (T, 3) right hip positions, metres, z up.

    Returns:
        (T,) heading, radians from +x CCW, unwrapped.
    """
    d = hip_l - hip_r
    return np.unwrap(np.arctan2(-d[:, 0], d[:, 1]))


def take_from_positions(
    positions: np.ndarray,
    names: list[str],
    skeleton: SkeletonMap,
    src_fps: float,
    fps: float,
    name: str,
    scale: float | None = None,
    meta: dict | None = None,
) -> Take:
    """Build a :class:`Take` from forward-kinematics output in file units and file axes.

    Args:
        positions: (T, J, 3) joint positions in file units and the file's frame.
        names: the J joint names, in order.
        skeleton: the preset naming pelvis/hips/ankles/toes (assumed present in ``names``).
        src_fps: sampling rate of ``positions`` (Hz).
        fps: target rate (Hz); positions are resampled by a cubic spline, the pelvis yaw is
            computed at the source rate, unwrapped, then interpolated the same way.
        name: the Take's name (usually the file name).
        scale: metres per file unit; defaults to ``skeleton.scale``.
        meta: extra provenance for ``Take.meta``.

    Returns:
        The take at ``fps`` Hz: metres, z up, yaw from +x CCW.
    """
    scale = skeleton.scale if scale is None else scale
    world = to_z_up(np.asarray(positions, dtype=float), skeleton.up) * scale
    index = {n: i for i, n in enumerate(names)}
    yaw = hip_line_yaw(world[:, index[skeleton.hip_l]], world[:, index[skeleton.hip_r]])
    n_src = world.shape[0]
    if n_src >= 2 and abs(src_fps - fps) > 1e-9 * fps:
        t_src = np.arange(n_src) / src_fps
        n_out = int(np.floor(t_src[-1] * fps + 1e-6)) + 1
        t_out = np.arange(n_out) / fps
        world = CubicSpline(t_src, world, axis=0)(t_out)
        yaw = CubicSpline(t_src, yaw)(t_out)
    joints = {n: np.ascontiguousarray(world[:, i]) for n, i in index.items()}
    info = {"source_fps": float(src_fps), "skeleton": skeleton.name, "scale": float(scale)}
    info.update(meta or {})
    return Take(
        name=name,
        fps=float(fps),
        pelvis=joints[skeleton.pelvis].copy(),
        pelvis_yaw=yaw,
        ankle_l=joints[skeleton.ankle_l].copy(),
        ankle_r=joints[skeleton.ankle_r].copy(),
        toe_l=joints[skeleton.toe_l].copy(),
        toe_r=joints[skeleton.toe_r].copy(),
        joints=joints,
        meta=info,
    )


def check_joints(skeleton: SkeletonMap, names: list[str], path) -> None:
    """Raise CaptureError (file and joint named) if ``skeleton`` names a joint not in ``names``.

    Args:
        skeleton: the map whose :meth:`SkeletonMap.required_joints` must be present.
        names: the joint names the file defines.
        path: the file, for the message.
    """
    have = set(names)
    for role, joint in skeleton.required_joints().items():
        if joint not in have:
            raise CaptureError(
                f"{path}: skeleton preset {skeleton.name!r} needs joint {joint!r} ({role}) "
                f"which the file lacks; joints present: {', '.join(names)}"
            )
