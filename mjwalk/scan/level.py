"""Find the floor of a scan and level it: the floor plane becomes z = 0.

The steps of the seed paper (mocap-based DHM walking in as-built environments, §3 A1-A2):

1. Local PCA normals. The paper down-samples to about 1000 points/m² and fits a plane to each
   point's k nearest neighbours. Here the neighbourhood is a cubic voxel of :data:`VOXEL` metres
   (k = 30 neighbours at 1000 points/m² span a disc of radius sqrt(30 / 1000 / pi) = 0.098 m):
   the covariance of the points in each voxel comes from nine ``numpy.bincount`` sums, its
   smallest eigenvector is the normal. This is independent of the scan's density and streams
   7 million points in well under a second (Open3D's ``voxel_down_sample`` + ``estimate_normals``
   took 17 s on 1 million points on the 2-core build machine, measured with
   ``OMP_NUM_THREADS=1``; the voxel sums 0.6 s).
2. Walk-surface voxels: normal within :data:`HORIZONTAL_DEG` (20°, the paper's epsilon) of up.
3. Region growing: walk-surface voxels that touch (26-neighbourhood) form one walk surface.
4. The floor is the lowest large horizontal layer of the walk surfaces (at least
   :data:`MIN_FLOOR_AREA` and :data:`FLOOR_SHARE` of the largest), so table tops, pads and the
   ceiling are not the floor. Heights are taken along the walk surfaces' common normal (the
   median of their voxels' normals, one vote per voxel, :func:`up_normal`; then the fitted
   floor's own normal, :data:`UP_ROUNDS`), and layers, not surfaces, are compared
   (:func:`floor_layer`): region growing joins the floor to every deck its steps, stairs and
   ramps reach (0.1 m voxels touch across a riser up to 0.2 m), and a plane through that union
   is tilted by the raised parts (``levelgen`` hall 111, a 0.91 m mezzanine and its stairs off
   the middle of a 17 m hall: 1.5° off, 54 % of the points then "below the floor").
5. A least-squares plane through the floor layer's voxels (voxels farther than
   :data:`PLANE_TOL` from it dropped, refit) gives the tilt; the cloud is rotated about the
   floor point below the floor's median x, y so the plane becomes z = 0. x and y keep the
   scan's meaning: points on the floor move horizontally by at most d·(1 - cos tilt) (0.6 mm
   at 10 m for a 2° tilt).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy.sparse import coo_matrix
from scipy.sparse.csgraph import connected_components

from mjwalk.errors import ScanError
from mjwalk.world.norms import FLOOR_SHARE, MIN_FLOOR_AREA

#: Edge of the voxel whose points give one local-PCA normal, metres (see the module docstring).
VOXEL = 0.10
#: Walk surfaces: normal within this angle of up, degrees (the seed paper's epsilon, §3 A2).
HORIZONTAL_DEG = 20.0
#: Voxels whose centroid is farther than this from the fitted floor plane are refit outliers,
#: metres (6 sigma of a 5 mm range noise).
PLANE_TOL = 0.03
#: Smallest horizontal surface reported as one a person could stand on, square metres: a
#: 0.6 m square, the shoulder breadth of a 95th-percentile man (about 0.52 m, DIN 33402-2)
#: rounded up.
STAND_AREA = 0.36
#: Surfaces higher above the floor than this are not reported (ceilings, lamps, overhead
#: pipework: the top of the obstacle band, ``OBSTACLE_Z_RANGE``), metres.
MAX_SURFACE_HEIGHT = 2.0
#: Rounds of layers re-cut along the fitted floor's normal (:func:`find_floor`): the median
#: of noisy voxel normals (:func:`up_normal`) is a start, the plane fitted on the floor layer's
#: points is the floor's own normal; the layers are cut again along it until it turns by less
#: than :data:`UP_CONVERGED_DEG`.
UP_ROUNDS = 3
#: The floor's normal has settled when a round turns it by less than this, degrees (the
#: flatness a 0.1 m voxel's layer holds: 0.01 deg over a 50 m hall is 9 mm, under
#: :data:`PLANE_TOL`).
UP_CONVERGED_DEG = 0.01
#: Points a voxel needs for its local-PCA normal (a plane through fewer is noise).
MIN_VOXEL_POINTS = 5
#: A levelled cloud is upside down when more of its points lie this far below the floor than
#: above it, metres (the lower edge of the obstacle band, ``OBSTACLE_Z_RANGE``).
BELOW_FLOOR = 0.05
#: Clouds farther than this from the origin are levelled about a nearby point (metres): the
#: summed second moments of points 1e6 m out lose the millimetres a plane fit needs.
LOCAL_FRAME = 1000.0
#: At most this many points feed the normals; larger clouds are thinned by a regular stride
#: (the voxel PCA needs tens of points per voxel, not thousands; a sparse large scan falls
#: back to larger voxels, see :func:`find_floor`).
MAX_NORMAL_POINTS = 1_000_000


@dataclass(frozen=True)
class Surface:
    """A horizontal surface other than the floor: ``height`` above the floor (metres, median
    of its voxels), ``area`` (square metres) and its middle ``x``, ``y`` (the cloud's frame,
    metres)."""

    height: float
    area: float
    x: float
    y: float


@dataclass(frozen=True)
class Levelling:
    """The rigid transform that levels a scan: ``p_scene = rotation @ (p - pivot) + target``.

    Attributes:
        rotation: (3, 3), takes the floor's normal onto +z.
        pivot: (3,) the floor point the rotation turns about, input frame, metres.
        target: (3,) where the pivot lands: its x, y unchanged, z = 0.
        normal: (3,) the floor's unit normal in the input frame (z component > 0).
        tilt_deg: angle between the floor's normal and +z, degrees.
        floor_area: area of the floor's walk surface found, square metres.
        rms: rms distance of the floor voxels' centroids from the plane, metres.
        surfaces: the other walk surfaces of at least :data:`STAND_AREA` up to the top of the
            obstacle band (platforms, steps, pits, table tops), largest first; levels stay
            single, so they are reported, not walked on.
    """

    rotation: np.ndarray
    pivot: np.ndarray
    target: np.ndarray
    normal: np.ndarray
    tilt_deg: float
    floor_area: float
    rms: float
    surfaces: tuple[Surface, ...] = ()

    @property
    def matrix(self) -> np.ndarray:
        """The 4 x 4 homogeneous form of the transform."""
        m = np.eye(4)
        m[:3, :3] = self.rotation
        m[:3, 3] = self.target - self.rotation @ self.pivot
        return m

    def apply(self, points: np.ndarray) -> np.ndarray:
        """Levelled copies of points.

        Args:
            points: (..., 3) points in the input frame, metres.

        Returns:
            (..., 3) ``rotation @ (p - pivot) + target`` per point: scene frame, floor at z = 0.
        """
        out = np.asarray(points) @ self.rotation.T  # one (N, 3) array, shifted in place
        out += self.target - self.rotation @ self.pivot
        return out


@dataclass
class VoxelNormals:
    """Per occupied voxel: integer index (M, 3), point count, centroid (M, 3), unit normal (M, 3)
    and the covariance eigenvalues (M, 3, ascending); metres."""

    ijk: np.ndarray
    count: np.ndarray
    centroid: np.ndarray
    normal: np.ndarray
    eigval: np.ndarray
    moments: np.ndarray  # (M, 10): n, sx, sy, sz, sxx, sxy, sxz, syy, syz, szz


def voxel_normals(
    points: np.ndarray, voxel: float = VOXEL, min_points: int = MIN_VOXEL_POINTS
) -> VoxelNormals:
    """Local-PCA normals of a cloud on a voxel grid.

    Args:
        points: (N, 3) points, metres.
        voxel: the voxel edge, metres.
        min_points: voxels with fewer points are left out.

    Returns:
        Per occupied voxel: index, count, centroid, unit normal (z >= 0), covariance eigenvalues
        and moments.
    """
    origin = points.min(axis=0)
    ijk = np.floor((points - origin) / voxel).astype(np.int64)
    dims = ijk.max(axis=0) + 1
    lin = (ijk[:, 0] * dims[1] + ijk[:, 1]) * dims[2] + ijk[:, 2]
    cells_total = int(dims[0]) * int(dims[1]) * int(dims[2])  # Python ints: no overflow
    if cells_total <= 4 * len(points) + 1_000_000:
        counts = np.bincount(lin, minlength=cells_total)
        cells = np.flatnonzero(counts >= min_points)
        remap = np.full(len(counts), -1, dtype=np.int64)
        remap[cells] = np.arange(len(cells))
        idx = remap[lin]
    else:  # a sparse cloud over a large extent: compact the keys by sorting
        cells, idx, counts = np.unique(lin, return_inverse=True, return_counts=True)
        keep = counts >= min_points
        remap = np.full(len(cells), -1, dtype=np.int64)
        remap[keep] = np.arange(int(keep.sum()))
        cells, idx = cells[keep], remap[idx]
    sel = idx >= 0
    idx, p = idx[sel], points[sel] - origin
    m = len(cells)
    x, y, z = p[:, 0], p[:, 1], p[:, 2]
    cols = [None, x, y, z, x * x, x * y, x * z, y * y, y * z, z * z]
    mom = np.stack(
        [
            np.bincount(idx, weights=c, minlength=m)
            if c is not None
            else np.bincount(idx, minlength=m)
            for c in cols
        ],
        axis=1,
    ).astype(np.float64)
    n = mom[:, 0]
    mean = mom[:, 1:4] / n[:, None]
    cov = np.empty((m, 3, 3))
    k = 4
    for a in range(3):
        for b in range(a, 3):
            cov[:, a, b] = cov[:, b, a] = mom[:, k] / n - mean[:, a] * mean[:, b]
            k += 1
    eigval, eigvec = np.linalg.eigh(cov)
    normal = eigvec[:, :, 0]
    normal *= np.where(normal[:, 2:3] < 0, -1.0, 1.0)
    ci = np.stack([cells // (dims[1] * dims[2]), (cells // dims[2]) % dims[1], cells % dims[2]], 1)
    # Moments about the cloud's origin: shift them back to absolute coordinates for plane fits.
    mom_abs = _shift_moments(mom, origin)
    return VoxelNormals(ci, n.astype(np.int64), mean + origin, normal, eigval, mom_abs)


def _shift_moments(mom: np.ndarray, o: np.ndarray) -> np.ndarray:
    n, s = mom[:, 0], mom[:, 1:4]
    out = mom.copy()
    out[:, 1:4] = s + n[:, None] * o
    k = 4
    for a in range(3):
        for b in range(a, 3):
            out[:, k] = mom[:, k] + o[b] * s[:, a] + o[a] * s[:, b] + n * o[a] * o[b]
            k += 1
    return out


def walk_surfaces(vn: VoxelNormals, max_angle_deg: float = HORIZONTAL_DEG) -> np.ndarray:
    """Region growing over the walk-surface voxels.

    A voxel is a walk surface when its normal is within ``max_angle_deg`` of up and its points
    spread in two directions (middle eigenvalue at least a tenth of the largest: a single scan
    line crossing a voxel gives no plane). Walk-surface voxels sharing a face, edge or corner are
    one surface.

    Args:
        vn: the voxel normals (:func:`voxel_normals`).
        max_angle_deg: the largest angle of a walk surface's normal from +z, degrees.

    Returns:
        (M,) a surface label per voxel (0, 1, ...; -1: not a walk surface).
    """
    ev = vn.eigval
    flat = (vn.normal[:, 2] >= np.cos(np.radians(max_angle_deg))) & (ev[:, 1] >= 0.1 * ev[:, 2])
    sel = np.flatnonzero(flat)
    labels = np.full(len(vn.count), -1, dtype=np.int64)
    if len(sel) == 0:
        return labels
    ijk = vn.ijk[sel] + 1
    dims = ijk.max(axis=0) + 2
    key = (ijk[:, 0] * dims[1] + ijk[:, 1]) * dims[2] + ijk[:, 2]
    order = np.argsort(key)
    skey = key[order]
    rows, cols = [], []
    for di in (-1, 0, 1):
        for dj in (-1, 0, 1):
            for dk in (-1, 0, 1):
                if (di, dj, dk) <= (0, 0, 0):
                    continue  # each neighbour pair once
                nk = key + (di * dims[1] + dj) * dims[2] + dk
                pos = np.clip(np.searchsorted(skey, nk), 0, len(skey) - 1)
                hit = skey[pos] == nk
                rows.append(np.flatnonzero(hit))
                cols.append(order[pos[hit]])
    r, c = np.concatenate(rows), np.concatenate(cols)
    graph = coo_matrix((np.ones(len(r)), (r, c)), shape=(len(sel), len(sel)))
    _, lab = connected_components(graph, directed=False)
    labels[sel] = lab
    return labels


def _plane(mom: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Least-squares plane through the points whose summed moments are ``mom`` (10,):
    (centroid, unit normal with z > 0)."""
    n = mom[0]
    mean = mom[1:4] / n
    cov = np.empty((3, 3))
    k = 4
    for a in range(3):
        for b in range(a, 3):
            cov[a, b] = cov[b, a] = mom[k] / n - mean[a] * mean[b]
            k += 1
    normal = np.linalg.eigh(cov)[1][:, 0]
    return mean, normal if normal[2] >= 0 else -normal


def _up_hint(vn: VoxelNormals) -> str:
    """Which axis most planar voxels face, to suggest an up axis when no floor is found."""
    planar = vn.eigval[:, 0] < 0.1 * vn.eigval[:, 1]
    if not planar.any():
        return ""
    cos20 = np.cos(np.radians(HORIZONTAL_DEG))
    share = [(np.abs(vn.normal[planar, a]) >= cos20).mean() for a in range(3)]
    best = int(np.argmax(share))
    if best == 2:
        return ""
    return f"; most flat surfaces face the {'xyz'[best]} axis: is the up axis {'xyz'[best]}?"


def _largest_area(vn: VoxelNormals, labels: np.ndarray, voxel: float) -> float:
    """Area of the largest walk surface (distinct x, y columns of its voxels), square metres."""
    ok = labels >= 0
    if not ok.any():
        return 0.0
    cols = np.unique(np.column_stack([labels[ok], vn.ijk[ok, :2]]), axis=0)
    return float(np.bincount(cols[:, 0]).max()) * voxel**2


def _sparse_hint(points: np.ndarray) -> str:
    """Why no voxel size gave a floor, when the cause is too few points per voxel."""
    parts = []
    for voxel in (VOXEL, 4 * VOXEL):
        ijk = np.floor((points - points.min(axis=0)) / voxel).astype(np.int64)
        _, counts = np.unique(ijk, axis=0, return_counts=True)
        parts.append((voxel, float(np.mean(counts < MIN_VOXEL_POINTS)), float(np.median(counts))))
    (v0, share0, med0), (v1, share1, med1) = parts
    if share0 < 0.5:
        return ""
    return (
        f"; the scan is too sparse for local-PCA normals: {100 * share0:.0f} % of the occupied "
        f"{v0:g} m voxels hold fewer than the {MIN_VOXEL_POINTS} points a normal needs (median "
        f"{med0:g} points; {100 * share1:.0f} % of {v1:g} m voxels, median {med1:g}): scan at a "
        "finer angular step, or merge more stations into the cloud"
    )


def find_floor(points: np.ndarray, *, source: str = "cloud") -> Levelling:
    """Find the floor of a z-up cloud and the transform that levels it.

    Args:
        points: (N, 3) points, metres, z up roughly.
        source: the cloud's name in errors.

    Returns:
        The levelling: its floor is the lowest large horizontal layer of the walk surfaces
        (heights along their common normal, :func:`floor_layer`), fitted as a plane on every
        point near it; the other walk surfaces one could stand on are listed.

    Raises:
        ScanError: no walk surface of at least :data:`MIN_FLOOR_AREA` square metres.
    """
    step = max(1, len(points) // MAX_NORMAL_POINTS)
    sub = points[::step] if step > 1 else points
    ref = np.zeros(3)
    if np.abs(sub[0]).max() > LOCAL_FRAME:  # georeferenced: level about a nearby point
        ref = np.round(sub[0])
        sub = sub - ref
    vn, labels, voxel = _surfaces_at_some_voxel(sub)
    surf = np.flatnonzero(labels >= 0)
    if len(surf) == 0:
        raise ScanError(
            f"{source}: no floor found: no horizontal surface in the cloud"
            f"{_sparse_hint(sub) or _up_hint(vn)}"
        )
    lab = labels[surf]
    nlab = int(lab.max()) + 1
    # Area: distinct (i, j) columns of each surface.
    col = vn.ijk[surf, 0] * (int(vn.ijk[:, 1].max()) + 1) + vn.ijk[surf, 1]
    pair = np.unique(lab * (int(col.max()) + 1) + col)
    area = np.bincount(pair // (int(col.max()) + 1), minlength=nlab) * voxel**2
    if area.max() < MIN_FLOOR_AREA:
        raise ScanError(
            f"{source}: no floor found: the largest horizontal surface is {area.max():.2f} m², "
            f"a floor needs at least {MIN_FLOOR_AREA} m²{_sparse_hint(sub) or _up_hint(vn)}"
        )
    up = up_normal(vn.normal[surf])
    for _ in range(UP_ROUNDS):  # layers along the floor's own normal once it is fitted
        seed = floor_layer(vn.centroid[surf] @ up, col, voxel)
        vox, centre, normal = _floor_plane(vn, surf[seed], sub)
        turn, up = float(np.degrees(np.arccos(min(1.0, float(normal @ up))))), normal
        if turn < UP_CONVERGED_DEG:
            break
    floor = int(np.bincount(lab[seed]).argmax())  # the surface most of the floor lies on
    rms = float(np.sqrt(np.mean(((vn.centroid[vox] - centre) @ normal) ** 2)))
    on = np.abs((vn.centroid[surf] - centre) @ normal) <= PLANE_TOL
    floor_area = len(np.unique(col[on])) * voxel**2
    xy = np.median(vn.centroid[vox, :2], axis=0)
    # The plane point below (xy): solve n . (p - centre) = 0 for p_z.
    pz = centre[2] - (normal[0] * (xy[0] - centre[0]) + normal[1] * (xy[1] - centre[1])) / normal[2]
    pivot = np.array([xy[0], xy[1], pz]) + ref
    rotation = _rotation_onto_z(normal)
    tilt = float(np.degrees(np.arccos(np.clip(normal[2], -1.0, 1.0))))
    surfaces = _other_surfaces(vn, (surf, lab), area, floor, (centre, normal), ref)
    return Levelling(
        rotation=rotation,
        pivot=pivot,
        target=np.array([pivot[0], pivot[1], 0.0]),
        normal=normal,
        tilt_deg=tilt,
        floor_area=float(floor_area),
        rms=rms,
        surfaces=tuple(surfaces),
    )


def up_normal(normals: np.ndarray) -> np.ndarray:
    """The common normal of a cloud's walk surfaces: the median of their voxels' normals' x and
    y components, one vote per voxel.

    Every horizontal surface of a building (floor, decks, treads, table tops) shares one
    normal whatever its height, so the median of the local normals is the floor's tilt
    however much of the walk surface lies on raised levels, while ramps and the voxels on a
    surface's edge (a minority) cannot pull it. A least-squares plane through a walk surface
    that region growing joined across steps and stairs (0.1 m voxels touch across a riser up
    to 0.2 m) is tilted by its raised parts instead. Each voxel is an equal patch of surface,
    so each votes once: weighted by its points, the vote would go to whatever stands nearest a
    scanner (a terrestrial scanner's point density falls with the square of the range; in the
    PCL room scan six voxels of the stand under the scanner held 59 % of the walk-surface
    points and pulled a point-weighted median 11 deg off once the ceiling was cut away).

    Args:
        normals: (M, 3) unit normals (z > 0) of walk-surface voxels.

    Returns:
        (3,) the unit normal, z > 0.
    """
    nx, ny = np.median(normals[:, :2], axis=0)
    return np.array([nx, ny, np.sqrt(max(0.0, 1.0 - nx * nx - ny * ny))])


def floor_layer(height: np.ndarray, column: np.ndarray, voxel: float) -> np.ndarray:
    """The walk-surface voxels of the floor: the lowest large horizontal layer.

    The voxels' heights are cut into layers :data:`PLANE_TOL` thick; a window of two layers
    (room for a floor's residual tilt and undulation) holds a horizontal surface's area as the
    distinct (i, j) columns of its voxels. The floor is the lowest window of at least
    :data:`MIN_FLOOR_AREA` and :data:`FLOOR_SHARE` of the largest (seed paper §3: the large
    walkable region at the lowest level; pads and pit bottoms below it are small), followed up
    while the next window is larger (the floor's peak, not its lower flank).

    Args:
        height: (M,) the voxels' heights along the walk surfaces' normal (:func:`up_normal`),
            metres.
        column: (M,) each voxel's (i, j) column key.
        voxel: the voxel edge, metres.

    Returns:
        (M,) bool: the voxels in the floor's window (the seed of its plane: the floor's voxels
        under all its columns, not necessarily all of its voxels).
    """
    layer = np.floor((height - height.min()) / PLANE_TOL).astype(np.int64)
    ncol = int(column.max()) + 1
    # Each voxel counts in the window starting at its layer and in the one below.
    keys = np.unique(np.concatenate([layer * ncol + column, (layer - 1) * ncol + column]))
    area = np.bincount(keys // ncol + 1) * voxel**2  # window w at index w + 1
    big = np.flatnonzero(area >= max(MIN_FLOOR_AREA, FLOOR_SHARE * area.max()))
    w = int(big[0]) if len(big) else int(area.argmax())
    while w + 1 < len(area) and area[w + 1] > area[w]:
        w += 1
    return (layer == w - 1) | (layer == w)


def _surfaces_at_some_voxel(sub: np.ndarray) -> tuple[VoxelNormals, np.ndarray, float]:
    """Voxel normals and walk-surface labels of ``sub``, and the voxel edge they took.

    A sparse scan (fewer than ~500 points/m²) leaves too few points per voxel for a normal:
    the neighbourhood doubles until one walk surface as large as a floor shows (at most
    twice; scattered pieces of floor whose voxels between hold too few points are not one)."""
    for voxel in (VOXEL, 2 * VOXEL, 4 * VOXEL):
        vn = voxel_normals(sub, voxel)
        labels = walk_surfaces(vn)
        if _largest_area(vn, labels, voxel) >= MIN_FLOOR_AREA:
            break
    return vn, labels, voxel


def _floor_plane(
    vn: VoxelNormals, vox: np.ndarray, sub: np.ndarray
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The floor's voxels within :data:`PLANE_TOL` of their plane, and the plane (a point and
    its upward unit normal) refitted on every point of ``sub`` near it."""
    centre, normal = _plane(vn.moments[vox].sum(axis=0))
    for _ in range(2):
        dist = (vn.centroid[vox] - centre) @ normal
        keep = np.abs(dist) <= PLANE_TOL
        if keep.sum() < 3:
            break
        vox = vox[keep]
        centre, normal = _plane(vn.moments[vox].sum(axis=0))
    # Refit on every point near the plane: the walk surface found by region growing can be a
    # small part of a cluttered floor, and a real floor is not flat to the millimetre (the pump
    # room's undulates by +-8 mm), so the tilt of the whole visible floor is the one to remove.
    for tol in (PLANE_TOL, 0.5 * PLANE_TOL):
        near = sub[np.abs((sub - centre) @ normal) <= tol]
        if len(near) < 100:
            break
        centre = near.mean(axis=0)
        d = near - centre
        normal = np.linalg.eigh(d.T @ d)[1][:, 0]
        normal = normal if normal[2] >= 0 else -normal
    return vox, centre, normal


def _other_surfaces(
    vn: VoxelNormals,
    labelled: tuple[np.ndarray, np.ndarray],
    area: np.ndarray,
    floor: int,
    plane: tuple[np.ndarray, np.ndarray],
    ref: np.ndarray,
) -> list[Surface]:
    """The horizontal surfaces besides the floor one could stand on, largest first:
    ``labelled`` the surface voxels and their labels, ``plane`` the floor's point and normal,
    ``ref`` the local frame's origin added back to their positions."""
    surf, lab = labelled
    centre, normal = plane
    surfaces = []
    for k in np.argsort(-area):
        if k == floor or area[k] < STAND_AREA:
            continue
        members = surf[lab == k]
        h = float(np.median((vn.centroid[members] - centre) @ normal))
        if h > MAX_SURFACE_HEIGHT or abs(h) <= PLANE_TOL:
            continue
        mx, my = np.median(vn.centroid[members, :2], axis=0) + ref[:2]
        surfaces.append(Surface(h, float(area[k]), float(mx), float(my)))
    return surfaces


def check_upright(
    levelled: np.ndarray,
    up: str = "+z",
    source: str = "cloud",
    scanners: np.ndarray | None = None,
) -> None:
    """Refuse a levelled cloud that is upside down.

    A cloud with more points more than :data:`BELOW_FLOOR` below its floor than above it has
    its floor found at the top of its contents: its up axis is the opposite of ``up``. Counting
    points misses a cloud read upside down whose raised deck covers a quarter of its floor (the
    deck's top, then the lowest large layer, is taken for the floor and the floor's points lie
    above it); where the scanners stood is known, a scanner stands on the floor or on a level
    above it, its head at a tripod's height (sight's ``MIN_STATION_HEIGHT``), so a floor above
    every scanner is one read upside down.

    Args:
        levelled: (N, 3) levelled points, metres, floor at z = 0.
        up: the up axis the cloud was read with (the error suggests its opposite).
        source: the cloud's name in errors.
        scanners: (S, 3) levelled positions of the scanners whose returns agree they stood
            there (``mjwalk.scan.sight.ray_agreement``), metres; None or empty: not known.

    Raises:
        ScanError: the cloud is upside down.
    """
    flip = ("-" if up.startswith("+") or not up.startswith("-") else "+") + up.lstrip("+-")
    if scanners is not None and len(scanners) and float(np.max(scanners[:, 2])) < -BELOW_FLOOR:
        raise ScanError(
            f"{source}: the floor found is above every scanner ({len(scanners)} stood "
            f"{-float(np.max(scanners[:, 2])):.2f} m or more below it; a scanner stands on a "
            f"floor): the cloud is upside down for --up={up}; pass --up={flip}"
        )
    z = levelled[:, 2]
    below = int(np.count_nonzero(z < -BELOW_FLOOR))
    above = int(np.count_nonzero(z > BELOW_FLOOR))
    if below > above:
        n = len(z)
        raise ScanError(
            f"{source}: the floor found is above the cloud's contents ({100 * below / n:.0f} % "
            f"of the points lie over {BELOW_FLOOR} m below it, {100 * above / n:.0f} % above): "
            f"the cloud is upside down for --up={up}; pass --up={flip}"
        )


def _rotation_onto_z(n: np.ndarray) -> np.ndarray:
    """The smallest rotation taking the unit vector ``n`` onto +z (Rodrigues)."""
    z = np.array([0.0, 0.0, 1.0])
    axis = np.cross(n, z)
    s = float(np.linalg.norm(axis))
    c = float(n @ z)
    if s < 1e-12:
        return np.eye(3)
    k = axis / s
    kx = np.array([[0, -k[2], k[1]], [k[2], 0, -k[0]], [-k[1], k[0], 0]])
    return np.eye(3) + s * kx + (1 - c) * kx @ kx
