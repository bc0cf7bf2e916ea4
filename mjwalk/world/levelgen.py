"""Generated workplaces on several levels, from a seed (issue 47: scenes nobody has seen).

A hall (metres, z up, floor at z = 0) with a mezzanine reached by a stair (one flight, two with
a landing, or two turned 90 deg at a landing), a platform reached by one or two steps, one by a
ramp (and a step where its height allows), sometimes a pedestal no one can climb and a pit with
a stair down, a low beam, obstacles by each flight's foot and head, clutter; any yaw (a pit
along the axes). Sites stand on every level. :class:`LevelHall` holds the MJCF, sites, true
levels and links, and scanner spots.

**Legal** (what every drawn dimension keeps to):

- stairs: one riser height and one tread depth per flight, riser in [``MIN_RISER``,
  ``MAX_RISER``], tread in [``MIN_TREAD``, ``MAX_TREAD``], step rule 2 s + a in ``STEP_RULE``, at
  least ``MIN_STAIR_RISERS`` risers a flight and at most :data:`MAX_FLIGHT_RISERS` (DIN 18065 /
  ASR A1.8 as :mod:`mjwalk.world.norms` cites them), as the MJCF is written, not only as drawn
  (:mod:`mjwalk.world.levelgendims`); a landing at least as deep as the stair is wide
  (:data:`LANDING_DEPTH`);
- single steps: one or two risers in the stair range (DIN 18065: one or two risers are steps);
- ramps: slope at most ``MAX_RAMP_SLOPE``, run at most :data:`MAX_RAMP_RUN`;
- widths: stairs, ramps and every walkway between structures at least :data:`WALKWAY` wide
  (ASR A1.8 Table 2); a clear approach :data:`APPROACH` deep before the foot and head of each
  flight, step and ramp, as wide as it;
- headroom: ``CLEAR_HEADROOM`` over every stair, ramp and raised level; the one exception is the
  low beam over the floor (:data:`BEAM_UNDERSIDE`), an obstacle to walk round for tall walkers;
- standing room: raised levels at least ``STAND_WIDTH`` wide; sites at least :data:`SITE_ROOM`
  from a level's edge and from obstacles.

A pedestal's site (:data:`PEDESTAL_HEIGHT`, no step or ramp) is one no walk reaches.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np
import shapely
from shapely.geometry import Polygon, box

from mjwalk._args import as_generator
from mjwalk.world.levelgendims import WRITE_DECIMALS, draw_riser, stair_dims
from mjwalk.world.norms import (
    MAX_RAMP_SLOPE,
    MAX_RISER,
    MAX_TREAD,
    MIN_RISER,
    MIN_STAIR_RISERS,
    MIN_TREAD,
)

#: Narrowest walkway, stair or ramp, metres: ASR A1.8 "Verkehrswege" (2022 edition) §4.2
#: Table 2, clear width of walkways used by up to 20 persons, 1.00 m (up to 5: 0.90 m); table as
#: quoted on haufe.de ("ASR A1.8 Verkehrswege / 4.2 Wege für den Fußgängerverkehr"), verified
#: there, not in the ASR itself.
WALKWAY = 1.0
#: Clear approach before a flight's foot and head, metres: ASSUMPTION, one walkway width
#: (:data:`WALKWAY`) so a walker can line up with the flight; not a cited figure.
APPROACH = 1.0
#: Most risers in one flight: DIN 18065, a landing after at most 18 (from memory, unverified).
MAX_FLIGHT_RISERS = 18
#: Risers a generated flight has (a flight below a landing, or the one flight).
FLIGHT_RISERS = (MIN_STAIR_RISERS, 8)
#: A landing's depth along the walk, at least the stair's width: DIN 18065 (from memory: the
#: landing as deep as the flight's usable width, not verified here).
LANDING_DEPTH = (1.0, 1.5)
#: Longest ramp run without a landing, metres: DIN 18040-1 §4.3.8 (from memory: a landing after
#: at most 6 m of ramp, not verified here).
MAX_RAMP_RUN = 6.0
#: Ramp slopes drawn, radians: from 3 deg to the cited largest ramp slope.
RAMP_SLOPE = (math.radians(3.0), MAX_RAMP_SLOPE)
#: The low beam's underside above the floor, metres: below :data:`CLEAR_HEADROOM` on purpose, above
#: the 1.2 m under which free heights are obstacles for everyone (``norms.OVERHEAD_MIN``).
BEAM_UNDERSIDE = (1.70, 1.95)
#: A pedestal's height, metres: above the highest riser (``MAX_RISER``), so no one steps onto it.
PEDESTAL_HEIGHT = (0.25, 0.45)
#: A site's least distance from its level's edges and from obstacles, metres: the planners'
#: body radius 0.25 m (``mjwalk.conventions.BODY_RADIUS``) plus the cycle's start margin
#: (0.04 m, ``mjwalk.cycle.levelsite.START_MARGIN``) plus room to turn, rounded up.
SITE_ROOM = 0.55
#: The height above its level a scanner stands at, metres (a terrestrial scanner on a tripod);
#: one stands at each flight's head too, looking down it (a deck's edge hides the top treads).
SCANNER_HEIGHT = 1.6


@dataclass(frozen=True)
class GenSite:
    """A named site: world position (metres), facing yaw (radians) and the level it stands on."""

    name: str
    pos: tuple[float, float, float]
    yaw: float
    level: str
    reachable: bool = True


@dataclass(frozen=True)
class GenLink:
    """A link a walker takes between two heights: "step", "stair" or "ramp" (metres)."""

    kind: str
    lower: float
    upper: float
    risers: int
    riser: float
    tread: float


@dataclass(frozen=True)
class LevelHall:
    """A generated hall on several levels.

    Attributes:
        xml: the MJCF text.
        size: the floor's (x, y) extent, metres (centred on the origin).
        seed: the seed it was drawn from.
        sites: every named site.
        heights: the true heights of the levels a walker reaches (no stair treads), metres.
        treads: the heights of every stair tread, metres (horizontal surfaces a scan may show).
        links: the steps, stairs and ramps.
        scanners: (x, y, z) scanner positions in free space, metres.
        features: what the hall holds ("stair-turn", "pit", "pedestal", ...).
    """

    xml: str
    size: tuple[float, float]
    seed: int
    sites: tuple[GenSite, ...]
    heights: tuple[float, ...]
    treads: tuple[float, ...]
    links: tuple[GenLink, ...]
    scanners: tuple[tuple[float, float, float], ...]
    features: tuple[str, ...]

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

    def site(self, name: str) -> GenSite:
        """A site by name.

        Args:
            name: the site's name.

        Returns:
            The site (StopIteration when none has that name).
        """
        return next(s for s in self.sites if s.name == name)


@dataclass
class _Part:
    """One structure in world coordinates while the hall is drawn."""

    geoms: list[str] = field(default_factory=list)
    solid: list[Polygon] = field(default_factory=list)  # footprints of everything standing
    keep: list[Polygon] = field(default_factory=list)  # approaches that must stay clear
    tops: list[tuple[Polygon, float, str]] = field(default_factory=list)  # raised levels
    heights: list[float] = field(default_factory=list)
    treads: list[float] = field(default_factory=list)
    links: list[GenLink] = field(default_factory=list)
    scanners: list[tuple[float, float, float]] = field(default_factory=list)
    features: list[str] = field(default_factory=list)

    def area(self):
        return shapely.union_all(self.solid + self.keep)


class _Frame:
    """A structure's local frame: origin (x, y) and yaw; boxes and points placed in it."""

    def __init__(self, x: float, y: float, yaw: float, tag: str):
        self.x, self.y, self.yaw, self.tag = x, y, yaw, tag
        self.c, self.s = math.cos(yaw), math.sin(yaw)

    def pt(self, u: float, v: float) -> tuple[float, float]:
        return self.x + self.c * u - self.s * v, self.y + self.s * u + self.c * v

    def rect(self, u0: float, u1: float, v0: float, v1: float) -> Polygon:
        return Polygon([self.pt(u0, v0), self.pt(u1, v0), self.pt(u1, v1), self.pt(u0, v1)])

    def box(self, part: _Part, name: str, u, v, z, mat: str, solid: bool = True) -> Polygon:
        """A box spanning local u (u0, u1), v (v0, v1), world z (z0, z1)."""
        (u0, u1), (v0, v1), (z0, z1), d = u, v, z, WRITE_DECIMALS
        cx, cy = self.pt(0.5 * (u0 + u1), 0.5 * (v0 + v1))
        part.geoms.append(
            f'<geom name="{self.tag}_{name}" type="box" '
            f'pos="{cx:.{d}f} {cy:.{d}f} {0.5 * (z0 + z1):.{d}f}" '
            f'size="{0.5 * (u1 - u0):.{d}f} {0.5 * (v1 - v0):.{d}f} {0.5 * (z1 - z0):.{d}f}" '
            f'euler="0 0 {math.degrees(self.yaw):.4f}" material="{mat}"/>'
        )
        poly = self.rect(u0, u1, v0, v1)
        if solid:
            part.solid.append(poly)
        return poly


def _flight(f: _Frame, p: _Part, u0: float, v, z0: float, rise: tuple[int, float, float], name):
    """A flight's n - 1 treads on the ground at ``z0``, rising along +u from its first riser at
    ``u0`` (``rise``: n, riser, tread); returns the u of its last riser."""
    n, r, a = rise
    for k in range(1, n):
        top = round(z0 + k * r, 4)
        f.box(p, f"{name}t{k}", (u0 + (k - 1) * a, u0 + k * a), v, (z0 - 0.0, top), "step")
        p.treads.append(top)
    return u0 + (n - 1) * a


def _beside(rng: np.random.Generator, f: _Frame, p: _Part, u, v, z0: float, name: str) -> Polygon:
    """A box 0-0.4 m to one side of a clear zone (local ``u``, ``v``), 0.4-0.8 m wide and deep,
    0.8-1.8 m tall, standing at ``z0``."""
    side = float(rng.choice([-1.0, 1.0]))
    gap = float(rng.uniform(0.0, 0.4))
    size = rng.uniform(0.4, 0.8, 2)
    h = float(rng.uniform(0.8, 1.8))
    edge = v[1] if side > 0 else v[0]
    vv = sorted((edge + side * gap, edge + side * (gap + size[1])))
    uu = (u[0] + 0.5 * (u[1] - u[0]) - size[0] / 2, u[0] + 0.5 * (u[1] - u[0]) + size[0] / 2)
    return f.box(p, name, uu, tuple(vv), (z0, z0 + h), "rack")


def _top(p: _Part, deck: Polygon, z: float, label: str, clear: list[Polygon]) -> None:
    """A raised level's standing room: its deck less ``clear`` zones and obstacles on it."""
    free = deck.buffer(-SITE_ROOM)
    if clear:  # obstacles standing on it
        free = free.difference(shapely.union_all(clear).buffer(SITE_ROOM))
    p.tops.append((free, z, label))


def _mezzanine(rng: np.random.Generator, f: _Frame) -> _Part:
    """A mezzanine reached by a stair (one flight, two with a landing, or two turned 90 deg),
    obstacles beside its foot's and head's approaches, walls along it half the time."""
    p = _Part()
    r, a = stair_dims(rng)
    w = round(float(rng.uniform(WALKWAY, 1.5)), 3)
    form = str(rng.choice(["straight", "landing", "turn"]))
    v = (-w / 2, w / 2)
    p.keep.append(f.rect(-APPROACH, 0.0, *v))
    p.scanners.append((*f.pt(-APPROACH - 0.5, 0.0), SCANNER_HEIGHT))
    _beside(rng, f, p, (-APPROACH, 0.0), v, 0.0, "foot_obst")
    g = f
    if form == "straight":
        n = int(rng.integers(FLIGHT_RISERS[0], FLIGHT_RISERS[1] + 1))
        u1 = u = _flight(f, p, 0.0, v, 0.0, (n, r, a), "s")
        top = round(n * r, 4)
        p.links.append(GenLink("stair", 0.0, top, n, r, a))
    else:
        n1, n2 = (int(k) for k in rng.integers(FLIGHT_RISERS[0], 6, 2))
        u1 = u = _flight(f, p, 0.0, v, 0.0, (n1, r, a), "s")
        zl, top = round(n1 * r, 4), round((n1 + n2) * r, 4)
        depth = round(float(rng.uniform(max(LANDING_DEPTH[0], w), max(LANDING_DEPTH[1], w))), 3)
        p.heights.append(zl)
        p.links += [GenLink("stair", 0.0, zl, n1, r, a), GenLink("stair", zl, top, n2, r, a)]
        if form == "landing":
            land = f.box(p, "landing", (u, u + depth), v, (0.0, zl), "deck")
            u = _flight(f, p, u + depth, v, zl, (n2, r, a), "s2")
        else:  # a quarter landing; the second flight rises along +v (side 1) or -v
            side = float(rng.choice([-1.0, 1.0]))
            lv = (-w / 2, depth - w / 2) if side > 0 else (w / 2 - depth, w / 2)
            land = f.box(p, "landing", (u, u + depth), lv, (0.0, zl), "deck")
            o = f.pt(u + depth - w / 2, side * (depth - w / 2))
            g = _Frame(*o, f.yaw + side * math.pi / 2, f.tag)
            u = _flight(g, p, 0.0, v, zl, (n2, r, a), "s2")
        _top(p, land, zl, "landing", [])
        p.scanners.append((land.centroid.x, land.centroid.y, zl + SCANNER_HEIGHT))
    p.features.append(f"stair-{form}")
    if rng.uniform() < 0.5:  # walls beside the first flight, 1 m above its top tread
        for s, name in ((-1.0, "wall_r"), (1.0, "wall_l")):
            vv = sorted((s * w / 2, s * (w / 2 + 0.05)))
            f.box(p, name, (0.0, u1), tuple(vv), (0.0, p.links[0].upper + 1.0), "guard")
        p.features.append("stair-walls")
    du = round(float(rng.uniform(2.2, 3.5)), 3)
    dv = round(float(rng.uniform(max(2.2, w + 1.2), 3.5)), 3)
    off = float(rng.uniform(-(dv - w) / 2, (dv - w) / 2))
    deck = g.box(p, "deck", (u, u + du), (off - dv / 2, off + dv / 2), (0.0, top), "deck")
    p.heights.append(top)
    room = [hv for hv in ((v[1], off + dv / 2), (off - dv / 2, v[0])) if hv[1] - hv[0] > 0.5]
    obst = []
    if room:  # an obstacle on the mezzanine beside the head's approach, where there is room
        hv = room[int(rng.integers(len(room)))]
        lo = hv[0] + float(rng.uniform(0.0, 0.3)) if hv[0] == v[1] else hv[0]
        hi = min(lo + float(rng.uniform(0.3, 0.6)), hv[1])
        if hv[0] != v[1]:
            lo = max(hv[1] - float(rng.uniform(0.3, 0.6)) - float(rng.uniform(0.0, 0.3)), hv[0])
            hi = min(lo + 0.5, hv[1] - 0.0)
        obst.append(g.box(p, "head_obst", (u + 0.1, u + 0.7), (lo, hi), (top, top + 1.6), "rack"))
    _top(p, deck, top, "mezz", obst)
    c = deck.centroid
    p.scanners += [(c.x, c.y, top + SCANNER_HEIGHT), (*g.pt(u + 0.5, 0.0), top + SCANNER_HEIGHT)]
    return p


def _platform(rng: np.random.Generator, f: _Frame, ramp: bool) -> _Part:
    """A platform reached by one riser (any side) or two (a tread before one side), or by a
    ramp along local +u (and then also by a step where its height allows)."""
    p = _Part()
    du, dv = (round(float(x), 3) for x in rng.uniform([1.6, 1.4], [3.5, 3.0]))
    wr = round(float(rng.uniform(WALKWAY, min(1.5, dv))), 3)
    if ramp:
        slope = float(rng.uniform(*RAMP_SLOPE))
        h = round(float(rng.uniform(0.15, min(0.8, MAX_RAMP_RUN * math.tan(slope)))), 4)
        run = h / math.tan(slope)
        _ramp(f, p, run, h, wr)
        p.keep.append(f.rect(-run - APPROACH, -run, -wr / 2, wr / 2))
        p.links.append(GenLink("ramp", 0.0, h, 0, 0.0, 0.0))
        p.features.append("ramp")
        p.scanners.append((*f.pt(-run - APPROACH, 0.0), SCANNER_HEIGHT))
    elif rng.uniform() < 0.5:  # one riser
        h = draw_riser(rng)
    else:  # two risers
        h = round(2 * draw_riser(rng), WRITE_DECIMALS)
    if h <= MAX_RISER:
        p.links.append(GenLink("step", 0.0, h, 1, h, 0.0))
        p.features.append("step-1")
    elif MIN_RISER <= h / 2 <= MAX_RISER:  # two risers: a tread before the side at u = du
        a = round(float(rng.uniform(MIN_TREAD, MAX_TREAD)), 4)
        f.box(p, "tread", (du, du + a), (-wr / 2, wr / 2), (0.0, round(h / 2, 4)), "step")
        p.keep.append(f.rect(du + a, du + a + APPROACH, -wr / 2, wr / 2))
        p.heights.append(round(h / 2, 4))
        p.links.append(GenLink("step", 0.0, h, 2, h / 2, a))
        p.features.append("step-2")
        p.scanners.append((*f.pt(du + a + APPROACH, 0.0), SCANNER_HEIGHT))
    deck = f.box(p, "deck", (0.0, du), (-dv / 2, dv / 2), (0.0, h), "deck")
    p.heights.append(h)
    _top(p, deck, h, "platform", [])
    c = deck.centroid
    p.scanners.append((c.x, c.y, h + SCANNER_HEIGHT))
    return p


def _ramp(f: _Frame, p: _Part, run: float, h: float, width: float) -> None:
    """A 0.1 m slab, its top rising along +u from the floor at u = -run to ``h`` at u = 0."""
    t, a = 0.05, math.atan2(h, run)
    half = 0.5 * math.hypot(run, h)
    cu, cz = -run / 2 + t * math.sin(a), h / 2 - t * math.cos(a)
    cx, cy = f.pt(cu, 0.0)
    # R = Rz(yaw) Ry(-a): the slab's +x runs up the ramp
    qz, qy = (math.cos(f.yaw / 2), math.sin(f.yaw / 2)), (math.cos(-a / 2), math.sin(-a / 2))
    q = (qz[0] * qy[0], -qz[1] * qy[1], qz[0] * qy[1], qy[0] * qz[1])
    p.geoms.append(
        f'<geom name="{f.tag}_ramp" type="box" pos="{cx:.4f} {cy:.4f} {cz:.4f}" '
        f'size="{half:.4f} {width / 2:.4f} {t:.4f}" '
        f'quat="{q[0]:.6f} {q[1]:.6f} {q[2]:.6f} {q[3]:.6f}" material="deck"/>'
    )
    p.solid.append(f.rect(-run, 0.0, -width / 2, width / 2))


def _pedestal(rng: np.random.Generator, f: _Frame) -> _Part:
    """A pedestal higher than any riser with nothing to climb it by."""
    p = _Part()
    du, dv = (float(x) for x in rng.uniform(1.3, 2.0, 2))
    h = round(float(rng.uniform(*PEDESTAL_HEIGHT)), 4)
    deck = f.box(p, "deck", (0.0, du), (0.0, dv), (0.0, h), "deck")
    p.tops.append((deck.buffer(-SITE_ROOM), h, "pedestal"))
    p.features.append("pedestal")
    return p


def _beam(rng: np.random.Generator, f: _Frame) -> _Part:
    """A low beam on two posts, its underside below the clear headroom."""
    p = _Part()
    span = float(rng.uniform(2.5, 4.0))
    hb = round(float(rng.uniform(*BEAM_UNDERSIDE)), 3)
    for name, u in (("post_a", 0.0), ("post_b", span)):
        f.box(p, name, (u - 0.1, u + 0.1), (-0.1, 0.1), (0.0, hb + 0.2), "guard")
    f.box(p, "beam", (0.0, span), (-0.1, 0.1), (hb, hb + 0.2), "guard", solid=False)
    p.keep.append(f.rect(0.1, span - 0.1, -0.1, 0.1))  # nothing stands under it
    p.features.append(f"beam-{hb:.2f}")
    return p


def _clutter(rng: np.random.Generator, f: _Frame) -> _Part:
    """A box on the floor (a bin, a trolley), 0.4-1.0 m a side, 0.5-1.5 m tall."""
    p = _Part()
    du, dv = (float(x) for x in rng.uniform(0.4, 1.0, 2))
    f.box(
        p, "box", (-du / 2, du / 2), (-dv / 2, dv / 2), (0.0, float(rng.uniform(0.5, 1.5))), "rack"
    )
    return p


def _pit(rng: np.random.Generator, f: _Frame) -> tuple[_Part, Polygon, float]:
    """A pit along local +u (the frame's yaw a multiple of 90 deg), a stair going down from its
    rim at u = 0 as wide as the pit; returns the part, the opening and the depth."""
    p = _Part()
    r, a = stair_dims(rng)
    n = int(rng.integers(MIN_STAIR_RISERS, 6))  # at most 5 x 0.19 = 0.95 m deep
    depth = round(n * r, 4)
    wp = round(float(rng.uniform(1.3, 2.0)), 3)
    length = (n - 1) * a + float(rng.uniform(1.6, 2.5))
    opening = f.rect(0.0, length, -wp / 2, wp / 2)
    for k in range(1, n):  # tread k's top k risers below the floor, standing on the bottom
        top = round(-k * r, 4)
        f.box(p, f"t{k}", ((k - 1) * a, k * a), (-wp / 2, wp / 2), (-depth, top), "step")
        p.treads.append(top)
    p.solid.append(opening)
    p.keep.append(f.rect(-APPROACH, 0.0, -wp / 2, wp / 2))
    p.links.append(GenLink("stair", -depth, 0.0, n, r, a))
    p.heights.append(-depth)
    bottom = f.rect((n - 1) * a, length, -wp / 2, wp / 2)
    p.tops.append((bottom.buffer(-SITE_ROOM), -depth, "pit"))
    c = bottom.centroid
    p.scanners += [
        (c.x, c.y, -depth + SCANNER_HEIGHT),
        (*f.pt(-APPROACH - 0.5, 0.0), SCANNER_HEIGHT),
    ]
    p.features.append("pit")
    return p, opening, depth


def _floor_boxes(size: tuple[float, float], opening: Polygon, depth: float) -> list[str]:
    """Four floor boxes round an opening, tops at 0, on the plane at ``-depth`` (floorholes)."""
    w, d = size
    x0, y0, x1, y1 = opening.bounds
    rects = [
        (-w / 2, w / 2, -d / 2, y0), (-w / 2, w / 2, y1, d / 2),
        (-w / 2, x0, y0, y1), (x1, w / 2, y0, y1),
    ]  # fmt: skip
    return [
        f'<geom name="floor_{i}" type="box" pos="{(a + b) / 2:.4f} {(c + e) / 2:.4f} '
        f'{-depth / 2:.4f}" size="{(b - a) / 2:.4f} {(e - c) / 2:.4f} {depth / 2:.4f}" '
        'material="slab"/>'
        for i, (a, b, c, e) in enumerate(rects)
    ]


def _place(rng: np.random.Generator, make, size, placed: list, axis: bool, tag: str):
    """Draw a structure's frame until its area and approaches, kept a walkway from the floor's
    edge and from every structure placed, fit (None after 300 draws)."""
    w, d = size
    hall = box(-w / 2 + WALKWAY, -d / 2 + WALKWAY, w / 2 - WALKWAY, d / 2 - WALKWAY)
    taken = shapely.union_all(placed).buffer(WALKWAY) if placed else None
    for _ in range(300):
        yaw = rng.integers(4) * math.pi / 2 if axis else rng.uniform(-math.pi, math.pi)
        x, y = rng.uniform(-w / 2, w / 2), rng.uniform(-d / 2, d / 2)
        frame = _Frame(float(x), float(y), float(yaw), tag)
        out = make(frame)
        part = out[0] if isinstance(out, tuple) else out
        area = part.area()
        if hall.contains(area) and (taken is None or not taken.intersects(area)):
            placed.append(area)
            return out
    return None


def _sites(rng: np.random.Generator, parts: list[_Part], size, n_floor: int) -> list[GenSite]:
    """Sites on the floor (clear of every structure) and one on each raised level's room."""
    w, d = size
    solid = shapely.union_all([g for q in parts for g in q.solid + q.keep])
    out: list[GenSite] = []
    tries = 0
    while sum(s.level == "floor" for s in out) < n_floor and tries < 5000:
        tries += 1
        x, y = rng.uniform([-w / 2 + 1.0, -d / 2 + 1.0], [w / 2 - 1.0, d / 2 - 1.0])
        pt = shapely.Point(x, y)
        near = [s for s in out if math.hypot(s.pos[0] - x, s.pos[1] - y) < 2.0]
        if solid.distance(pt) >= SITE_ROOM + 0.15 and not near:
            k = sum(s.level == "floor" for s in out)
            out.append(GenSite(f"floor_{k}", (float(x), float(y), 0.0), _yaw(rng), "floor"))
    counts: dict[str, int] = {}
    for q in parts:
        for room, z, label in q.tops:
            if room.is_empty or room.area < 1e-4:
                continue
            pt = _inside(rng, room)
            k = counts.get(label, 0)
            counts[label] = k + 1
            ok = label != "pedestal"
            out.append(GenSite(f"{label}_{k}", (pt[0], pt[1], z), _yaw(rng), label, ok))
    return out


def _yaw(rng: np.random.Generator) -> float:
    return round(float(rng.uniform(-math.pi, math.pi)), 4)


def _inside(rng: np.random.Generator, poly) -> tuple[float, float]:
    x0, y0, x1, y1 = poly.bounds
    for _ in range(2000):
        x, y = rng.uniform([x0, y0], [x1, y1])
        if poly.contains(shapely.Point(x, y)):
            return float(x), float(y)
    c = poly.representative_point()
    return float(c.x), float(c.y)


def generate_levels(seed: int, *, pit: float = 0.4, pedestal: float = 0.3) -> LevelHall:
    """A hall on several levels drawn from ``seed`` (module docstring: what and within which
    norms); the same seed gives the same hall.

    Args:
        seed: the seed.
        pit: the chance the hall has a pit.
        pedestal: the chance it has a pedestal no one can climb (a site no walk reaches).

    Returns:
        The hall.
    """
    rng = as_generator(seed, "generate_levels: seed")
    size = (round(float(rng.uniform(16.0, 22.0)), 2), round(float(rng.uniform(12.0, 16.0)), 2))
    placed: list = []
    parts: list[_Part] = []
    hole = None
    makers: list[tuple[str, Callable[[_Frame], Any], bool]] = [
        ("mezz", lambda f: _mezzanine(rng, f), False)
    ]
    if rng.uniform() < pit:
        makers.insert(0, ("pit", lambda f: _pit(rng, f), True))
    makers += [
        ("plat", lambda f: _platform(rng, f, ramp=False), False),
        ("ramp", lambda f: _platform(rng, f, ramp=True), False),
    ]
    if rng.uniform() < pedestal:
        makers.append(("ped", lambda f: _pedestal(rng, f), False))
    makers.append(("beam", lambda f: _beam(rng, f), False))
    makers += [
        (f"box{i}", lambda f: _clutter(rng, f), False) for i in range(int(rng.integers(4, 10)))
    ]
    for tag, make, axis in makers:
        out = _place(rng, make, size, placed, axis, tag)
        if out is None:
            continue
        if tag == "pit":
            part, opening, depth = out
            hole = (opening, depth)
        else:
            part = out
        parts.append(part)
    sites = _sites(rng, parts, size, n_floor=3)
    return _assemble(seed, size, parts, sites, hole)


def _assemble(seed, size, parts: list[_Part], sites: list[GenSite], hole) -> LevelHall:
    w, d = size
    depth = hole[1] if hole else 0.0
    floor = [
        f'<geom name="floor" type="plane" pos="0 0 {-depth:.4f}" size="{w / 2:g} {d / 2:g} 0.05" '
        'material="floor"/>'
    ]
    if hole:
        floor += _floor_boxes(size, hole[0], depth)
    site_xml = [
        f'<site name="{s.name}" pos="{s.pos[0]:.4f} {s.pos[1]:.4f} {s.pos[2]:.4f}" '
        f'euler="0 0 {math.degrees(s.yaw):.3f}" size="0.05" rgba="0 0.8 0 0.6"/>'
        for s in sites
    ]
    mats = {
        "floor": "0.8 0.8 0.78 1", "slab": "0.78 0.78 0.76 1", "deck": "0.5 0.55 0.5 1",
        "step": "0.6 0.62 0.55 1", "rack": "0.85 0.55 0.15 1", "guard": "0.9 0.8 0.1 1",
    }  # fmt: skip
    xml = "\n".join(
        [
            f'<mujoco model="levels_{seed}">',
            "  <asset>",
            *(f'    <material name="{k}" rgba="{v}"/>' for k, v in mats.items()),
            "  </asset>",
            "  <worldbody>",
            '    <light pos="0 0 8" dir="0 0 -1"/>',
            *("    " + g for g in floor),
            *("    " + g for q in parts for g in q.geoms),
            *("    " + s for s in site_xml),
            "  </worldbody>",
            "</mujoco>",
            "",
        ]
    )
    floor_scanners = [(s.pos[0], s.pos[1], SCANNER_HEIGHT) for s in sites if s.level == "floor"]
    return LevelHall(
        xml=xml,
        size=(float(w), float(d)),
        seed=int(seed),
        sites=tuple(sites),
        heights=tuple(sorted({0.0, *(h for q in parts for h in q.heights)})),
        treads=tuple(sorted(h for q in parts for h in q.treads)),
        links=tuple(k for q in parts for k in q.links),
        scanners=tuple(floor_scanners + [s for q in parts for s in q.scanners]),
        features=tuple(x for q in parts for x in q.features),
    )
