"""Independent 3-D clearance checks with MuJoCo's own geometry (``mj_geomDistance``).

A thin vertical capsule spanning the obstacle height band is placed at floor points and its
distance to every obstacle geom is asked of MuJoCo. This does not use the clearance field, so tests
and users can check planned paths against the scene geometry itself.
"""

from __future__ import annotations

from collections.abc import Sequence
from pathlib import Path

import mujoco
import numpy as np

from mjwalk.errors import SceneError
from mjwalk.world.floor import find_floor, floor_top
from mjwalk.world.workplace import Workplace

_PROBE_RADIUS = 1e-3


class ClearanceProbe:
    """Distance from vertical floor probes to scene geoms, by ``mujoco.mj_geomDistance``.

    Args:
        scene: MJCF path of the scene (or a Workplace loaded from one).
        geoms: names of the geoms to measure against (default: the workplace's obstacles).
        z_range: the probe's height band above the floor (metres).
    """

    def __init__(
        self,
        scene: str | Path | Workplace,
        geoms: Sequence[str] | None = None,
        z_range: tuple[float, float] = (0.05, 2.0),
    ):
        names: Sequence[str] | None
        if isinstance(scene, Workplace):
            if scene.source is None:
                raise SceneError("ClearanceProbe needs a workplace loaded from an MJCF file")
            names = (
                geoms if geoms is not None else list(dict.fromkeys(f.name for f in scene.obstacles))
            )
            path, floor_z, z_range = scene.source, scene.floor_z, scene.z_range
        else:
            path, floor_z = Path(scene), None  # the floor's: found in the model below
            names = geoms
        spec = mujoco.MjSpec.from_file(str(path))
        half = 0.5 * (z_range[1] - z_range[0])
        body = spec.worldbody.add_body(name="mjwalk_probe", mocap=True)
        body.add_geom(
            name="mjwalk_probe_geom",
            type=mujoco.mjtGeom.mjGEOM_CAPSULE,
            size=[_PROBE_RADIUS, half, 0],
            contype=0,
            conaffinity=0,
        )
        self.model = spec.compile()
        self.data = mujoco.MjData(self.model)
        mujoco.mj_kinematics(self.model, self.data)
        self._probe = self.model.geom("mjwalk_probe_geom").id
        try:
            floor = find_floor(self.model, self.data, str(path))
        except SceneError:  # no floor: the band is above z = 0
            floor = -1
        if floor_z is None:
            floor_z = 0.0 if floor < 0 else floor_top(self.model, self.data, floor)
        self._z = floor_z + z_range[0] + half
        if names is None:  # every geom but the probe, planes and a slab floor
            names = [
                self.model.geom(g).name
                for g in range(self.model.ngeom)
                if g not in (self._probe, floor)
                and self.model.geom_type[g] != mujoco.mjtGeom.mjGEOM_PLANE
            ]
        self.geoms = [self.model.geom(n).id for n in names]
        self.names = list(names)
        self._fromto = np.zeros(6)

    def distances(self, xy: np.ndarray, distmax: float = 20.0) -> np.ndarray:
        """Distances from probes to each geom.

        Args:
            xy: (N, 2) probe positions, world metres.
            distmax: distances are searched up to this, metres.

        Returns:
            (N, G) metres from each probe to each of :attr:`geoms`; negative when the probe line
            passes through a geom (MuJoCo's penetration depth).
        """
        xy = np.atleast_2d(np.asarray(xy, dtype=float))
        out = np.empty((len(xy), len(self.geoms)))
        m, d = self.model, self.data
        for i, (x, y) in enumerate(xy):
            d.geom_xpos[self._probe] = (x, y, self._z)
            for j, g in enumerate(self.geoms):
                out[i, j] = mujoco.mj_geomDistance(m, d, self._probe, g, distmax, self._fromto)
        return out + _PROBE_RADIUS

    def clearance(self, xy: np.ndarray, distmax: float = 20.0) -> np.ndarray:
        """Distance from probes to the nearest geom.

        Args:
            xy: (N, 2) probe positions, world metres.
            distmax: distances are searched up to this, metres (returned when there are no geoms).

        Returns:
            (N,) metres.
        """
        if not self.geoms:
            return np.full(len(np.atleast_2d(xy)), distmax)
        return self.distances(xy, distmax).min(axis=1)


def path_clearance(probe: ClearanceProbe, points: np.ndarray, spacing: float = 0.01) -> np.ndarray:
    """Clearance along a polyline.

    Args:
        probe: the probe.
        points: (N, 2) the polyline's vertices, world metres.
        spacing: the largest step between samples, metres.

    Returns:
        (M,) metres at the first vertex and at even steps of at most ``spacing`` along each
        segment.
    """
    points = np.asarray(points, dtype=float)
    seg = np.diff(points, axis=0)
    lengths = np.linalg.norm(seg, axis=1)
    samples = [points[:1]]
    for p, s, n in zip(points[:-1], seg, np.ceil(lengths / spacing).astype(int), strict=True):
        if n > 0:
            samples.append(p + np.outer(np.arange(1, n + 1) / n, s))
    return probe.clearance(np.vstack(samples))


def _ray(m: mujoco.MjModel, d: mujoco.MjData, g: int, pnt: np.ndarray, vec: np.ndarray) -> float:
    if m.geom_type[g] == mujoco.mjtGeom.mjGEOM_MESH:
        return mujoco.mj_rayMesh(m, d, g, pnt, vec)
    return mujoco.mju_rayGeom(
        d.geom_xpos[g], d.geom_xmat[g], m.geom_size[g], pnt, vec, int(m.geom_type[g])
    )


def covered(probe: ClearanceProbe, xy: np.ndarray, z_range: tuple[float, float] = (0.05, 2.0)):
    """Whether the vertical line at each floor point meets a geom inside the height band.

    Uses ``mju_rayGeom``/``mj_rayMesh``: a ray up from far below and a ray down from far above give
    the interval of the line inside each (convex) geom.

    Args:
        probe: the probe (its model and geoms).
        xy: (N, 2) floor points, world metres.
        z_range: the band, world z, metres (low, high).

    Returns:
        (N,) bool.
    """
    xy = np.atleast_2d(np.asarray(xy, dtype=float))
    m, d = probe.model, probe.data
    up, down = np.array([0.0, 0.0, 1.0]), np.array([0.0, 0.0, -1.0])
    out = np.zeros(len(xy), dtype=bool)
    far = 1000.0
    for i, (x, y) in enumerate(xy):
        for g in probe.geoms:
            t_in = _ray(m, d, g, np.array([x, y, -far]), up)
            if t_in < 0:
                continue
            t_out = _ray(m, d, g, np.array([x, y, far]), down)
            z_in, z_out = -far + t_in, far - t_out
            if z_in <= z_range[1] and z_out >= z_range[0]:
                out[i] = True
                break
    return out
