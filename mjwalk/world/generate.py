"""Generated factory halls: a rectangular floor cluttered with random primitives, from a seed.

For scale tests and benchmarks (``benchmarks/bench_scale.py``, ``tests/world/test_scale.py``): the
halls a planner meets are 50-200 m long with about 0.4 obstacles per square metre (issue 18).
Obstacles are boxes (yaw-rotated), vertical cylinders and capsules (standing, or lying on the
floor at any yaw), placed by random sequential addition so that the bounding circles of any two
keep ``gap`` metres between them (a walker of body radius 0.25 m fits through every gap) and
none comes closer than ``margin`` to the floor's edge. Metres, z up, floor at z = 0, centred on
the origin.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from mjwalk._args import as_generator
from mjwalk.errors import SceneError

#: Obstacle kinds and their default shares.
KINDS = ("box", "cylinder", "capsule")
#: Obstacle footprint size range: radius of the bounding circle, metres.
SIZE_RANGE = (0.1, 0.3)
#: Clear space between the bounding circles of two obstacles (m): twice the planners' default
#: body radius (0.25, mjwalk.conventions.BODY_RADIUS) plus 0.2 m, so that every gap is passable
#: (the bounding circles are conservative: a box's sides lie inside its circle).
GAP = 0.7
#: Clear band along the floor's edges (m): more than the body radius.
MARGIN = 0.6


@dataclass(frozen=True)
class Hall:
    """A generated hall: its MJCF text and the obstacles' bounding circles (x, y, r) in metres."""

    xml: str
    size: tuple[float, float]
    circles: np.ndarray

    def write(self, path: str | Path) -> Path:
        """Write the MJCF (through a temporary file, then rename).

        Args:
            path: the file to write.

        Returns:
            ``path`` as a path.
        """
        path = Path(path)
        tmp = path.with_name(path.name + ".tmp")
        tmp.write_text(self.xml)
        tmp.replace(path)
        return path


def _place(
    rng: np.random.Generator, w: float, d: float, n: int, gap: float, margin: float
) -> np.ndarray:
    """Random sequential addition of ``n`` circles (x, y, r) with ``gap`` between them."""
    lo, hi = SIZE_RANGE
    cell = 2 * hi + gap  # a spatial hash: neighbours lie in the 3 x 3 cells around
    buckets: dict[tuple[int, int], list[int]] = {}
    out = np.empty((n, 3))
    k = 0
    tries = 0
    max_tries = 200 * n + 1000
    while k < n and tries < max_tries:
        tries += 1
        r = rng.uniform(lo, hi)
        x = rng.uniform(-w / 2 + margin + r, w / 2 - margin - r)
        y = rng.uniform(-d / 2 + margin + r, d / 2 - margin - r)
        ci, cj = math.floor(x / cell), math.floor(y / cell)
        ok = True
        for a in range(ci - 1, ci + 2):
            for b in range(cj - 1, cj + 2):
                for o in buckets.get((a, b), ()):
                    ox, oy, orad = out[o]
                    if math.hypot(x - ox, y - oy) < r + orad + gap:
                        ok = False
                        break
                if not ok:
                    break
            if not ok:
                break
        if ok:
            out[k] = (x, y, r)
            buckets.setdefault((ci, cj), []).append(k)
            k += 1
    if k < n:
        raise SceneError(
            f"cannot place {n} obstacles with {gap} m gaps on a {w:g} x {d:g} m floor "
            f"(placed {k}); lower the density"
        )
    return out


def _geom(kind: str, i: int, x: float, y: float, r: float, rng: np.random.Generator) -> str:
    yaw = rng.uniform(0, 180)
    if kind == "box":  # half sizes whose diagonal is the bounding radius
        a = rng.uniform(0.3, 0.95)
        sx, sy = r * a / math.hypot(a, 1.0), r / math.hypot(a, 1.0)
        h = rng.uniform(0.4, 1.2)
        return (
            f'<geom name="box{i}" type="box" size="{sx:.4f} {sy:.4f} {h:.4f}" '
            f'pos="{x:.4f} {y:.4f} {h:.4f}" euler="0 0 {yaw:.3f}" rgba="0.6 0.55 0.45 1"/>'
        )
    if kind == "cylinder":
        h = rng.uniform(0.4, 1.5)
        return (
            f'<geom name="cyl{i}" type="cylinder" size="{r:.4f} {h:.4f}" '
            f'pos="{x:.4f} {y:.4f} {h:.4f}" rgba="0.45 0.5 0.6 1"/>'
        )
    # capsule: standing, or lying horizontally at any yaw on a low stand (wholly inside the
    # obstacle band above 0.05 m, so its footprint is an exact stadium)
    if rng.uniform() < 0.5:
        rad = r * rng.uniform(0.5, 1.0)
        h = rng.uniform(0.3, 0.8)
        return (
            f'<geom name="cap{i}" type="capsule" size="{rad:.4f} {h:.4f}" '
            f'pos="{x:.4f} {y:.4f} {h + rad:.4f}" rgba="0.5 0.6 0.45 1"/>'
        )
    rad = r * rng.uniform(0.25, 0.45)
    half = r - rad
    z = rad + 0.06
    dx, dy = half * math.cos(math.radians(yaw)), half * math.sin(math.radians(yaw))
    return (
        f'<geom name="cap{i}" type="capsule" size="{rad:.4f}" fromto="{x - dx:.4f} '
        f'{y - dy:.4f} {z:.4f} {x + dx:.4f} {y + dy:.4f} {z:.4f}" rgba="0.5 0.6 0.45 1"/>'
    )


def generate_hall(
    width: float,
    depth: float | None = None,
    *,
    density: float = 0.4,
    n: int | None = None,
    kinds: tuple[str, ...] = KINDS,
    seed: int = 0,
    gap: float = GAP,
    margin: float = MARGIN,
) -> Hall:
    """A random hall of separated obstacles; the same seed gives the same hall.

    Args:
        width: the floor's x extent, metres.
        depth: the floor's y extent, metres (None: ``width``).
        density: obstacles per square metre of floor, when ``n`` is None.
        n: the number of obstacles (None: from ``density``).
        kinds: obstacle kinds, drawn evenly (from :data:`KINDS`).
        seed: seeds the placement.
        gap: the smallest gap between obstacles' bounding circles, metres.
        margin: the clear band along the floor's edges, metres.

    Returns:
        The hall: its MJCF text (floor centred on the origin), size and bounding circles.

    Raises:
        SceneError: a bad size, density or kind, or more obstacles than fit with the gaps.
    """
    depth = width if depth is None else depth
    if not (width > 2 * margin and depth > 2 * margin):
        raise SceneError(f"hall {width} x {depth} m is too small for its {margin} m margins")
    bad = [k for k in kinds if k not in KINDS]
    if bad or not kinds:
        raise SceneError(f"obstacle kinds must be among {KINDS}, got {kinds!r}")
    if n is None:
        if density < 0:
            raise SceneError(f"density must be >= 0, got {density}")
        n = round(density * width * depth)
    rng = as_generator(seed, "generate_hall: seed")
    circles = _place(rng, width, depth, n, gap, margin)
    which = rng.integers(0, len(kinds), n)
    geoms = [
        _geom(kinds[w], i, x, y, r, rng)
        for i, ((x, y, r), w) in enumerate(zip(circles, which, strict=True))
    ]
    xml = "\n".join(
        [
            f'<mujoco model="hall_{width:g}x{depth:g}_{seed}">',
            "  <worldbody>",
            '    <light pos="0 0 10" dir="0 0 -1"/>',
            f'    <geom name="floor" type="plane" size="{width / 2:g} {depth / 2:g} 0.05"/>',
            *("    " + g for g in geoms),
            "  </worldbody>",
            "</mujoco>",
            "",
        ]
    )
    return Hall(xml, (float(width), float(depth)), circles)


def free_points(hall: Hall, n: int, rng: np.random.Generator, clearance: float = 0.5) -> np.ndarray:
    """Random floor points clear of every obstacle.

    Args:
        hall: the hall.
        n: how many points.
        rng: draws them (uniform over the floor less ``clearance``, rejected when too close).
        clearance: the least distance to every bounding circle and to the floor's edge, metres.

    Returns:
        (n, 2) points, metres.
    """
    w, d = hall.size
    out: list[np.ndarray] = []
    c = hall.circles
    while len(out) < n:
        p = rng.uniform(
            [-w / 2 + clearance, -d / 2 + clearance], [w / 2 - clearance, d / 2 - clearance]
        )
        if len(c) == 0 or np.min(np.hypot(c[:, 0] - p[0], c[:, 1] - p[1]) - c[:, 2]) >= clearance:
            out.append(p)
    return np.array(out)
