"""Synthetic terrestrial laser scans of an MJCF scene, by MuJoCo's own ray casting.

For tests and benchmarks of the scan import on known geometry: each scanner casts a regular
azimuth x elevation grid of rays (``mujoco.mj_multiRay``), keeps the hits, adds Gaussian range
noise, and the merged cloud is then tilted about a floor point and lifted, as a real registered
scan arrives (floor at an arbitrary height, 1-2° off level).
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass

import mujoco
import numpy as np

#: Elevation range of the rays, degrees above horizontal: a 300° vertical field of view
#: (FARO Focus-class phase scanners) leaves a 30° half-angle blind cone below the scanner.
ELEVATION_DEG = (-60.0, 90.0)


@dataclass
class SyntheticScan:
    """A merged synthetic scan: ``points`` (N, 3) metres in the tilted, lifted frame;
    ``to_scene`` (4, 4) maps those points back to the scene the rays were cast in."""

    points: np.ndarray
    to_scene: np.ndarray
    scanners: np.ndarray


def cast(
    model: mujoco.MjModel,
    position: np.ndarray,
    step_deg: float = 0.25,
    *,
    rng: np.random.Generator,
    noise: float = 0.005,
    cutoff: float = 30.0,
) -> np.ndarray:
    """The hits of one scanner.

    Args:
        model: the scene.
        position: (3,) the scanner's position, metres, world frame.
        step_deg: the angular step in azimuth and elevation, degrees.
        rng: draws the range noise.
        noise: the range noise's standard deviation, metres (normal, zero mean).
        cutoff: the rays' range, metres.

    Returns:
        (K, 3) hit points, metres; rays that hit nothing are lost.
    """
    data = mujoco.MjData(model)
    mujoco.mj_kinematics(model, data)
    az = np.radians(np.arange(0.0, 360.0, step_deg))
    el = np.radians(np.arange(ELEVATION_DEG[0], ELEVATION_DEG[1], step_deg))
    a, e = np.meshgrid(az, el)
    vec = np.stack([np.cos(e) * np.cos(a), np.cos(e) * np.sin(a), np.sin(e)], -1).reshape(-1, 3)
    n = len(vec)
    geomid = np.zeros(n, dtype=np.int32)
    dist = np.zeros(n)
    pnt = np.asarray(position, dtype=float)
    mujoco.mj_multiRay(model, data, pnt, vec.ravel(), None, 1, -1, geomid, dist, None, n, cutoff)
    hit = (geomid >= 0) & (dist >= 0)
    r = dist[hit] + rng.normal(0.0, noise, int(hit.sum()))
    return pnt + vec[hit] * r[:, None]


def synthetic_scan(
    model: mujoco.MjModel,
    scanners: Sequence[Sequence[float]],
    *,
    step_deg: float = 0.25,
    noise: float = 0.005,
    tilt_deg: float = 1.5,
    tilt_axis_deg: float = 30.0,
    floor_height: float = -1.37,
    seed: int = 0,
) -> SyntheticScan:
    """Scan a scene from several positions, merge, tilt and lift the cloud.

    The cloud is tilted by ``tilt_deg`` about a horizontal axis at ``tilt_axis_deg`` from +x
    through the origin on the floor, and the floor moved to z = ``floor_height``.

    Args:
        model: the scene.
        scanners: scanner positions (x, y, z), metres.
        step_deg: the angular step, degrees.
        noise: range noise, metres.
        tilt_deg: the tilt, degrees.
        tilt_axis_deg: the tilt axis's direction from +x, CCW, degrees.
        floor_height: where the floor ends up, metres.
        seed: seeds the range noise.

    Returns:
        The merged points, the (4, 4) transform back to the scene and the scanner positions.
    """
    rng = np.random.default_rng(seed)
    pts = np.vstack([cast(model, np.asarray(p), step_deg, rng=rng, noise=noise) for p in scanners])
    ax = np.radians(tilt_axis_deg)
    k = np.array([np.cos(ax), np.sin(ax), 0.0])
    t = np.radians(tilt_deg)
    kx = np.array([[0, -k[2], k[1]], [k[2], 0, -k[0]], [-k[1], k[0], 0]])
    rot = np.eye(3) + np.sin(t) * kx + (1 - np.cos(t)) * kx @ kx
    m = np.eye(4)
    m[:3, :3] = rot
    m[2, 3] = floor_height
    out = pts @ rot.T + m[:3, 3]
    return SyntheticScan(out, np.linalg.inv(m), np.asarray(scanners, dtype=float))
