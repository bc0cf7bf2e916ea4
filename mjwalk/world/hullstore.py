"""The edges of point sets' 3-D convex hulls, kept in memory and, by the workplace's cache policy,
on disk.

A geom's footprint in a height slab clips its convex hull (:mod:`mjwalk.world.footprint`), and a
tessellated round geom (a sphere or ellipsoid: 6 272 points, a sloped capsule 12 544) or a large
mesh costs qhull tens of milliseconds for that hull. A scene on several levels clips them again
for every level's view and head band, and every new process on the scene again. So the edges are
kept per process by the points' digest, and a set of at least :data:`DISK_HULL_POINTS` points
keeps them in the workplace cache too (:func:`mjwalk.world.cache.cached_array`, a file
``<key>-hulledges.npy``) when the caller's policy allows (``disk``; the workplace passes its
:attr:`~mjwalk.world.workplace.WorkplaceOptions.cache`: False never reads nor writes one).

A stored file is keyed by the points' bytes and scipy's version (another qhull may triangulate
otherwise) and holds a header row (the number of points, a 63-bit BLAKE2b checksum of the edges)
above the edges: a file whose header does not match is rebuilt over, so a stored hull gives the
edges qhull gives, bit for bit.
"""

from __future__ import annotations

import functools
import hashlib

import numpy as np

from mjwalk.boundedmemo import Memo
from mjwalk.world.cache import cached_array, content_key

#: Point sets of at least this many points keep their hull's edges on disk: the tessellated
#: round geoms (6 272 points a sphere or ellipsoid, 12 544 a sloped capsule: qhull 56-64 ms CPU
#: each, read back with its key and checksum in about 2 ms; files of 289 / 295 kB) and large
#: meshes. Boxes (8 points) and cylinders (256: 2-3 ms) are left to qhull, about a read's cost.
DISK_HULL_POINTS = 1000
#: Hull edges of point sets by the points' digest: a level's view and every walker's head band
#: clip the same tessellated geoms again.
_HULL_EDGES: Memo[bytes, np.ndarray] = Memo(limit=32)


def clear_memo() -> None:
    """Forget the hull edges kept in this process (a benchmark's cold start, a test)."""
    _HULL_EDGES.clear()


def point_digest(points: np.ndarray) -> bytes:
    """A digest of a point array's shape and bytes.

    Args:
        points: the points (any shape; read as float64).

    Returns:
        BLAKE2b, 16 bytes.
    """
    a = np.ascontiguousarray(points, dtype=float)
    h = hashlib.blake2b(str(a.shape).encode(), digest_size=16)
    h.update(a.tobytes())
    return h.digest()


def hull_edges(simplices: np.ndarray) -> np.ndarray:
    """A 3-D convex hull's edges, each once, in ascending order of the pair: the triangles'
    sides (i, i + 1 mod 3) sorted within each pair, de-duplicated and sorted lexicographically
    (as ``sorted`` of a set of pairs gives them), in one NumPy pass instead of a Python loop
    over the ~10^4 simplices of a tessellated capsule.

    Args:
        simplices: (f, 3) vertex indices of the hull's triangles (``ConvexHull.simplices``).

    Returns:
        (e, 2) int64 (low index, high index) pairs.
    """
    s = np.asarray(simplices, dtype=np.int64)
    pairs = np.concatenate([s[:, [0, 1]], s[:, [1, 2]], s[:, [2, 0]]])
    pairs.sort(axis=1)
    n = int(s.max()) + 1 if s.size else 1
    code = np.unique(pairs[:, 0] * n + pairs[:, 1])  # (a, b) -> a n + b keeps their order
    return np.column_stack([code // n, code % n])


def _qhull_edges(points: np.ndarray) -> np.ndarray:
    """The edges of the points' 3-D hull by qhull (:func:`hull_edges`); none when qhull refuses
    the points (flat or degenerate)."""
    from scipy.spatial import ConvexHull, QhullError  # deferred: scipy.spatial, ~1 s import

    try:
        return hull_edges(ConvexHull(points).simplices)
    except QhullError:
        return np.empty((0, 2), dtype=np.int64)


@functools.cache
def _qhull_version() -> str:
    """scipy's version, part of a stored hull's key."""
    import scipy  # deferred: only for a stored hull's key (scipy.spatial imports it anyway)

    return str(scipy.__version__)


def _checksum(key: str, edges: np.ndarray) -> int:
    """A 63-bit BLAKE2b checksum of a content key and an edge array's bytes (fits an int64)."""
    h = hashlib.blake2b(key.encode(), digest_size=8)
    h.update(np.ascontiguousarray(edges, dtype=np.int64).tobytes())
    return int.from_bytes(h.digest(), "little") >> 1


def pack(edges: np.ndarray, n_points: int, key: str) -> np.ndarray:
    """The stored form of a hull's edges: a header row (the number of points, a checksum of
    the content key and the edges) above the edges.

    Args:
        edges: (e, 2) int64 edges (:func:`hull_edges`).
        n_points: how many points they index.
        key: the points' content key (:func:`mjwalk.world.cache.content_key`).

    Returns:
        (e + 1, 2) int64.
    """
    head = np.array([[n_points, _checksum(key, edges)]], dtype=np.int64)
    return np.vstack([head, np.asarray(edges, dtype=np.int64).reshape(-1, 2)])


def unpack(stored: np.ndarray, n_points: int, key: str) -> np.ndarray | None:
    """The edges of a stored hull (:func:`pack`), or None when the array is not one for
    ``n_points`` points under ``key`` (a damaged file, or another hull's).

    Args:
        stored: the array read from the cache.
        n_points: how many points the hull is of.
        key: the points' content key.

    Returns:
        (e, 2) int64 edges (a copy), or None.
    """
    if stored.dtype != np.int64 or stored.ndim != 2 or stored.shape[1] != 2 or not len(stored):
        return None
    edges = np.array(stored[1:])
    if int(stored[0, 0]) != n_points or int(stored[0, 1]) != _checksum(key, edges):
        return None
    return edges


def point_hull_edges(points: np.ndarray, disk: bool = False) -> np.ndarray:
    """The edges of the points' 3-D convex hull: kept in this process, and on disk for at least
    :data:`DISK_HULL_POINTS` points when ``disk`` (module docstring).

    Args:
        points: (n, 3) world points, metres.
        disk: whether the workplace cache may be read and written for them (the workplace's
            policy; False: qhull or this process's memo only).

    Returns:
        (e, 2) int64 edges (:func:`hull_edges`), none when qhull refuses the points. The same
        bits whether qhull, the memo or a file gave them.
    """
    n = len(points)

    def build() -> np.ndarray:
        if not disk or n < DISK_HULL_POINTS:
            return _qhull_edges(points)
        key = content_key("hull-edges", _qhull_version(), arrays=[points])
        got: list[np.ndarray] = []  # the edges a valid file or qhull gave (checked once)

        def fresh() -> np.ndarray:
            got.append(_qhull_edges(points))
            return pack(got[-1], n, key)

        def valid(stored: np.ndarray) -> bool:
            edges = unpack(stored, n, key)
            if edges is not None:
                got.append(edges)
            return edges is not None

        cached_array(key, "hulledges", fresh, valid=valid)
        return got[-1]

    return _HULL_EDGES.get(point_digest(points), build)
