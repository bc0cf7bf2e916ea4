"""How planned walks bend between two headings in free space, against their guide and against
the published smooth-path models (issue 48).

Run: python3 benchmarks/bench_freebend.py [--seeds 6] [--lengths 4,6,8] [--angles 10,20,30]

Synthetic free walks on the open floor (scenes/open_floor.xml, no obstacle; nothing here is
THOR data): a walker already walking at start yaw = chord + a, meaning to arrive along
``goal_heading`` = chord - a (a C-shaped bow), chord + a (an S) or with no goal heading
(none). Per case: the paths between the two poses of the three smooth-path models
(:func:`figures`, :func:`middle_excess`), and the median over ``--seeds`` planned walks of
the pelvis path, raw and after THOR's 800 ms moving average. Each path is measured by its
largest lateral offset from the chord (m), its excess over the chord (m), the excess of its
middle (more than 1 m from both ends, as THOR's zones cut a track) over its own chord, and
the directions of its first and last 10 % (deg from the chord). The models:

- guide: mjwalk's guide (:func:`mjwalk.plan.guide.minimum_jerk_guide`): the minimum-jerk path
  of Pham et al. 2007 with zero end accelerations and end tangents of the chord's length;
- free-end (:func:`free_end_path`): the same with the end accelerations free (the natural
  boundary condition, zero jerk at the ends), which to first order in the heading is also
  the least-curvature-variation path of Arechavaleta et al. 2008 with free end curvatures;
- arc-T (:func:`arc_timed_path`): the guide with end tangents of the path's own length
  (Pham's tangents are the end speed times the duration; at a steady pace that is the walked
  length).

Printed per case, then the medians over the cases of the ratios to the guide.
"""

from __future__ import annotations

import argparse
import math
import time
from pathlib import Path

import numpy as np
from scipy.ndimage import uniform_filter1d

from mjwalk.conventions import SAMPLE_RATE_HZ
from mjwalk.gait.default import default_model
from mjwalk.plan.guide import minimum_jerk_guide
from mjwalk.plan.hybrid import HybridPlanner
from mjwalk.plan.request import WalkRequest
from mjwalk.world import load_workplace

ROOT = Path(__file__).resolve().parents[1]
#: THOR's tracks: an 800 ms moving average (benchmarks/bench_thor.py).
TRACK_SMOOTH_S = 0.8


def figures(xy: np.ndarray, s: np.ndarray, g: np.ndarray, side: float) -> dict:
    """Largest lateral offset (m) from the chord s -> g, excess over the chord (m) and the
    directions (deg from the chord, signed to ``side``) of the first and last 10 % of the
    path ``xy``."""
    c = g - s
    length = float(np.hypot(*c))
    u = c / length
    rel = xy - s
    lat = (u[0] * rel[:, 1] - u[1] * rel[:, 0]) * side
    along = rel @ u
    walked = float(np.hypot(*np.diff(xy, axis=0).T).sum())
    chord = float(np.hypot(*(xy[-1] - xy[0])))

    def direction(a: float, b: float) -> float:
        i = int(np.searchsorted(along, a * length))
        j = min(int(np.searchsorted(along, b * length)), len(xy) - 1)
        d = xy[j] - xy[min(i, j - 1)]
        return math.degrees(math.atan2(u[0] * d[1] - u[1] * d[0], d @ u)) * side

    return {
        "lat": float(np.abs(lat).max()),
        "excess": walked - chord,
        "head0": direction(0.0, 0.1),
        "head1": direction(0.9, 1.0),
    }


def free_end_path(start, goal, h0: float, h1: float | None, n: int = 2000) -> np.ndarray:
    """The minimum-jerk path between the two poses with its end accelerations left free
    (natural boundary: zero jerk at both ends) instead of zero: what the smoothness principle
    gives for ends defined by position and direction only (the porches of Hicheur et al.
    2007); to first order in the heading also the path of least curvature variation
    (Arechavaleta et al. 2008) with free end curvatures, y''' being dkappa/ds. A quintic per
    axis, (n, 2) points."""
    p0, p1 = np.asarray(start, float), np.asarray(goal, float)
    chord = p1 - p0
    length = float(np.hypot(*chord))

    def tangent(h: float | None) -> np.ndarray:
        return chord if h is None else length * np.array([math.cos(h), math.sin(h)])

    def row(k: int, x: float) -> np.ndarray:  # k-th derivative of 1, s, ..., s^5 at x
        return np.array([math.perm(m, k) * x ** (m - k) if m >= k else 0.0 for m in range(6)])

    a = np.stack([row(0, 0.0), row(1, 0.0), row(0, 1.0), row(1, 1.0), row(3, 0.0), row(3, 1.0)])
    rhs = np.stack([p0, tangent(h0), p1, tangent(h1), np.zeros(2), np.zeros(2)])
    coef = np.linalg.solve(a, rhs)  # (6, 2)
    s = np.linspace(0.0, 1.0, n)
    return np.stack([s**m for m in range(6)], axis=1) @ coef


def arc_timed_path(start, goal, h0: float, h1: float | None, n: int = 2000) -> np.ndarray:
    """mjwalk's guide with end tangents of the path's own length instead of the chord's
    (Pham et al. 2007's end tangents are the end speed times the walk's duration T; at a
    steady pace that is the walked length): three fixed-point rounds from the chord."""
    g = minimum_jerk_guide(start, goal, h0, h1, n)
    for _ in range(3):
        k = float(np.hypot(*np.diff(g, axis=0).T).sum()) / float(np.hypot(*(g[-1] - g[0])))
        g = _scaled_guide(start, goal, h0, h1, k, n)
    return g


#: The zero-end-acceleration quintic Hermite basis (mjwalk.plan.guide's _H).
_H = np.array(
    [[1, 0, 0, -10, 15, -6], [0, 1, 0, -6, 8, -3], [0, 0, 0, -4, 7, -3], [0, 0, 0, 10, -15, 6]],
    dtype=float,
)


def _scaled_guide(start, goal, h0: float, h1: float | None, k: float, n: int) -> np.ndarray:
    """The zero-end-acceleration quintic with end tangents k times the chord's length."""
    p0, p1 = np.asarray(start, float), np.asarray(goal, float)
    chord = p1 - p0
    length = float(np.hypot(*chord))
    t0 = k * length * np.array([math.cos(h0), math.sin(h0)])
    t1 = k * (chord if h1 is None else length * np.array([math.cos(h1), math.sin(h1)]))
    coef = _H.T @ np.stack([p0, t0, t1, p1])
    s = np.linspace(0.0, 1.0, n)
    return np.stack([s**m for m in range(6)], axis=1) @ coef


def middle_excess(xy: np.ndarray, s: np.ndarray, g: np.ndarray, cut: float = 1.0) -> float:
    """The excess (m) over its own chord of the part of ``xy`` more than ``cut`` m from both
    end points ``s`` and ``g`` (as THOR's zones cut a track, benchmarks/bench_thor.py)."""
    keep = (np.hypot(*(xy - s).T) > cut) & (np.hypot(*(xy - g).T) > cut)
    m = xy[keep]
    if len(m) < 2:
        return math.nan
    return float(np.hypot(*np.diff(m, axis=0).T).sum() - np.hypot(*(m[-1] - m[0])))


def run_case(planner, s, g, a: float, end: float | None, seeds: int) -> dict:
    """The figures (:func:`figures` plus ``middle``: :func:`middle_excess`) of the guide, of
    the two other published paths and the medians over ``seeds`` planned walks, raw and after
    the tracks' moving average, for a walker leaving ``s`` along ``a`` for ``g``, arriving
    along ``end``."""
    out = {}
    for name, path in (
        ("guide", minimum_jerk_guide(s, g, a, end, 2000)),
        ("free_end", free_end_path(s, g, a, end)),
        ("arc_T", arc_timed_path(s, g, a, end)),
    ):
        out[name] = figures(path, s, g, 1.0) | {"middle": middle_excess(path, s, g)}
    raw, avg = [], []
    size = max(1, round(TRACK_SMOOTH_S * SAMPLE_RATE_HZ))
    for k in range(seeds):
        p = planner.plan(WalkRequest((*s, a), goal_heading=end), np.random.default_rng(k))
        smooth = uniform_filter1d(p.xy, size=size, axis=0, mode="nearest")
        raw.append(figures(p.xy, s, g, 1.0) | {"middle": middle_excess(p.xy, s, g)})
        avg.append(figures(smooth, s, g, 1.0) | {"middle": middle_excess(smooth, s, g)})
    out["raw"] = {k: float(np.median([r[k] for r in raw])) for k in raw[0]}
    out["avg"] = {k: float(np.median([r[k] for r in avg])) for k in avg[0]}
    return out


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--seeds", type=int, default=6)
    ap.add_argument("--lengths", default="4,6,8")
    ap.add_argument("--angles", default="10,20,30")
    ap.add_argument("--shapes", default="C,S,none")
    args = ap.parse_args(argv)
    wp = load_workplace(ROOT / "scenes" / "open_floor.xml")
    model = default_model(progress=False)
    t0 = time.perf_counter()
    rows = []
    print("case         guide lat/exc/mid | planned raw lat/exc | 800ms lat/exc/mid | ratios "
          "800ms/guide lat exc mid | ends deg guide | raw | mid: free-end arc-T")  # fmt: skip
    for length in (float(v) for v in args.lengths.split(",")):
        s = np.array((-0.5 * length, -1.0))
        g = np.array((0.5 * length, -1.0))
        planner = HybridPlanner(wp, tuple(g), model)
        for a_deg in (float(v) for v in args.angles.split(",")):
            a = math.radians(a_deg)
            for shape in args.shapes.split(","):
                end = {"C": -a, "S": a, "none": None}[shape]
                c = run_case(planner, s, g, a, end, args.seeds)
                rows.append(c)
                gd, rw, av = c["guide"], c["raw"], c["avg"]
                print(f"L{length:.0f} a{a_deg:.0f} {shape:4} {gd['lat']:+.3f}/{gd['excess']:.3f}/"
                      f"{gd['middle']:.3f} | {rw['lat']:+.3f}/{rw['excess']:.3f} | "
                      f"{av['lat']:+.3f}/{av['excess']:.3f}/{av['middle']:.3f} | "
                      f"{av['lat'] / gd['lat']:.2f} {av['excess'] / gd['excess']:.2f} "
                      f"{av['middle'] / gd['middle']:.2f} | {gd['head0']:+.0f}/{gd['head1']:+.0f}"
                      f" | {rw['head0']:+.0f}/{rw['head1']:+.0f} | "
                      f"{c['free_end']['middle']:.3f} {c['arc_T']['middle']:.3f}",
                      flush=True)  # fmt: skip

    def med(key: str, num: str, den: str = "guide") -> float:
        return float(np.nanmedian([r[num][key] / r[den][key] for r in rows]))

    print(f"median over cases of the ratio to the guide: planned (800 ms) lateral peak "
          f"{med('lat', 'avg'):.2f}, excess {med('excess', 'avg'):.2f}, middle excess "
          f"{med('middle', 'avg'):.2f}; raw excess {med('excess', 'raw'):.2f}; free-end path "
          f"excess {med('excess', 'free_end'):.2f}, middle {med('middle', 'free_end'):.2f}; "
          f"arc-timed path excess {med('excess', 'arc_T'):.2f}, middle "
          f"{med('middle', 'arc_T'):.2f} ({time.perf_counter() - t0:.0f} s)")  # fmt: skip
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
