"""Where walk surfaces meet: the edges a walker crosses from one surface onto another.

Each surface's edges are sampled every :data:`EDGE_SPACING`; a point just beyond an edge (by the
contact gap) that lies on another surface, with room above it
(``mjwalk.world.norms.EXPOSED_MIN``), and whose height differs from the edge's by no more than
a limit, joins the two there. Consecutive such samples make one :class:`Contact`, kept when it
is at least a body wide (:data:`MIN_CROSSING`). A surface resting on another (a step on the
floor) meets it along its own edges; two boxes side by side (the treads of a stair) along the
shared edge, found from both. A ramp's ends meet levels, whichever of a level's surfaces lies
beyond them (:func:`level_contacts`). Metres, world xy.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np

from mjwalk.conventions import BODY_RADIUS
from mjwalk.errors import InputError
from mjwalk.world.norms import CONTACT_GAP, EXPOSED_MIN, MAX_RISER, ROUNDING_SLACK
from mjwalk.world.walksurface import Segment, WalkSurface

#: Spacing of the samples along an edge, metres (the clearance grid's 2 cm).
EDGE_SPACING = 0.02
#: Most samples along one edge (a hall's floor edge is sampled coarser).
MAX_EDGE_SAMPLES = 2000
#: Shortest crossing kept, metres: the planners' body disc (``conventions.BODY_RADIUS``) passes
#: through no narrower one.
MIN_CROSSING = 2.0 * BODY_RADIUS


@dataclass(frozen=True)
class Contact:
    """A stretch of surface ``a``'s edge beyond which surface ``b`` lies.

    Attributes:
        a: index of the surface whose edge it is.
        b: index of the surface beyond the edge.
        edge: the stretch of ``a``'s edge, world xy, metres.
        rise: median height of ``b`` above ``a`` across the stretch, metres (negative: down).
        rise_range: least and greatest rise along the stretch, metres (they differ along the
            side of a ramp).
    """

    a: int
    b: int
    edge: Segment
    rise: float
    rise_range: tuple[float, float]

    @property
    def length(self) -> float:
        """Length of the stretch, metres."""
        (x0, y0), (x1, y1) = self.edge
        return math.hypot(x1 - x0, y1 - y0)


def _edges(surface: WalkSurface) -> list[tuple[np.ndarray, np.ndarray]]:
    v = np.asarray(surface.footprint.vertices, dtype=float)
    return [(v[i], v[(i + 1) % len(v)]) for i in range(len(v))]


def _runs(ok: np.ndarray) -> list[tuple[int, int]]:
    """Index ranges [i, j) of consecutive True values."""
    padded = np.concatenate([[False], ok, [False]]).astype(np.int8)
    d = np.diff(padded)
    return list(zip(np.flatnonzero(d == 1), np.flatnonzero(d == -1), strict=True))


_Probe = tuple[float, int, np.ndarray, np.ndarray, tuple[float, float, float, float]]


def _edge_probe(sa: WalkSurface, a0: np.ndarray, a1: np.ndarray, gap: float) -> _Probe | None:
    """An edge a0-a1 (CCW) of ``sa`` sampled: its length, the number of samples, the points
    ``gap`` beyond it, the edge's heights at them and the points' box (x0, y0, x1, y1); None
    for an edge shorter than a body."""
    length = float(np.linalg.norm(a1 - a0))
    if length < MIN_CROSSING:
        return None
    n = int(min(MAX_EDGE_SAMPLES, max(1, math.ceil(length / EDGE_SPACING))))
    p = a0 + ((np.arange(n) + 0.5) / n)[:, None] * (a1 - a0)
    d = (a1 - a0) / length
    q = p + gap * np.array([d[1], -d[0]])  # the outward normal of a CCW edge
    qx0, qy0 = (float(v) for v in q.min(axis=0))
    qx1, qy1 = (float(v) for v in q.max(axis=0))
    return length, n, q, sa.height_at(p), (qx0, qy0, qx1, qy1)


def _beyond(
    sb: WalkSurface, probe: _Probe, gap: float, max_rise: float
) -> tuple[np.ndarray, np.ndarray] | None:
    """Which of an edge's probe points (:func:`_edge_probe`) land on ``sb`` within
    ``max_rise`` and open to step on, and the rise to it at each; None when ``sb`` is nowhere
    under them."""
    _, _, q, za, (qx0, qy0, qx1, qy1) = probe
    x0, y0, x1, y1 = sb.footprint.bounds()
    if qx1 < x0 - gap or qy1 < y0 - gap or qx0 > x1 + gap or qy0 > y1 + gap:
        return None
    on = sb.contains(q)
    if not np.any(on):
        return None
    rise = sb.height_at(q) - za
    ok = on & (np.abs(rise) <= max_rise + ROUNDING_SLACK)
    if np.any(ok):
        ok[ok] = sb.free_height(q[ok]) > EXPOSED_MIN
    return ok, rise


def _edge_contacts(
    surfaces: Sequence[WalkSurface],
    ia: int,
    a0: np.ndarray,
    a1: np.ndarray,
    gap: float,
    max_rise: float,
) -> list[Contact]:
    """The contacts along one edge a0-a1 (CCW) of surface ``ia``."""
    probe = _edge_probe(surfaces[ia], a0, a1, gap)
    if probe is None:
        return []
    length, n = probe[0], probe[1]
    out = []
    for ib, sb in enumerate(surfaces):
        if ib == ia:
            continue
        beyond = _beyond(sb, probe, gap, max_rise)
        if beyond is None:
            continue
        ok, rise = beyond
        for i, j in _runs(ok):
            if (j - i) * length / n < MIN_CROSSING:
                continue
            s, e = a0 + (i / n) * (a1 - a0), a0 + (j / n) * (a1 - a0)
            r = rise[i:j]
            edge = ((float(s[0]), float(s[1])), (float(e[0]), float(e[1])))
            out.append(Contact(ia, ib, edge, float(np.median(r)), (float(r.min()), float(r.max()))))
    return out


def level_contacts(
    surfaces: Sequence[WalkSurface],
    level_of: Sequence[int | None],
    gap: float = CONTACT_GAP,
    max_rise: float = MAX_RISER,
) -> list[Contact]:
    """The contacts of the edges of the surfaces in no level (the ramps) with levels rather
    than single surfaces: beyond an edge, consecutive samples on any surface of one level join
    one stretch, kept when it is a body wide (:data:`MIN_CROSSING`). A level written as
    several boxes (a scanned floor cut round a pit into strips, issue 47's hall 1243) meets a
    ramp's end along its width though no one box does; a walker crossing there does not care
    which box is under the foot.

    Args:
        surfaces: the walk surfaces.
        level_of: each surface's level (None: in none, a ramp: its edges are sampled).
        gap: how far beyond an edge the level is looked for, metres (> 0).
        max_rise: largest height difference across a contact, metres (>= 0).

    Returns:
        The contacts by surface ``a``, edge and level, ``b`` the surface under most of the
        stretch's samples; at each sample the rise is to the level's surface nearest in height.
    """
    out: list[Contact] = []
    edges = [(ia, e) for ia, sa in enumerate(surfaces) if level_of[ia] is None for e in _edges(sa)]
    for ia, (a0, a1) in edges:
        probe = _edge_probe(surfaces[ia], a0, a1, gap)
        if probe is None:
            continue
        length, n = probe[0], probe[1]
        best: dict[int, tuple[np.ndarray, np.ndarray]] = {}  # level -> (rise, surface)
        for ib, sb in enumerate(surfaces):
            lv = level_of[ib]
            if ib == ia or lv is None:
                continue
            beyond = _beyond(sb, probe, gap, max_rise)
            if beyond is None:
                continue
            ok, rise = beyond
            r, who = best.setdefault(lv, (np.full(n, np.inf), np.full(n, -1)))
            nearer = ok & (np.abs(rise) < np.abs(r))
            r[nearer], who[nearer] = rise[nearer], ib
        for r, who in best.values():
            for i, j in _runs(who >= 0):
                if (j - i) * length / n < MIN_CROSSING:
                    continue
                s, e = a0 + (i / n) * (a1 - a0), a0 + (j / n) * (a1 - a0)
                edge = ((float(s[0]), float(s[1])), (float(e[0]), float(e[1])))
                b = int(np.argmax(np.bincount(who[i:j])))
                rr = r[i:j]
                out.append(
                    Contact(ia, b, edge, float(np.median(rr)), (float(rr.min()), float(rr.max())))
                )
    return out


def surface_contacts(
    surfaces: Sequence[WalkSurface], gap: float = CONTACT_GAP, max_rise: float = MAX_RISER
) -> list[Contact]:
    """Every contact between the surfaces, sampled from each surface's edges.

    Args:
        surfaces: the walk surfaces (their overheads decide where a surface is open to step on).
        gap: how far beyond an edge the other surface is looked for, metres (> 0; default
            :data:`mjwalk.world.norms.CONTACT_GAP`): edges closer than this touch.
        max_rise: largest height difference across a contact, metres (>= 0; default
            :data:`mjwalk.world.norms.MAX_RISER`).

    Returns:
        The contacts, by surface ``a``, edge and surface ``b``; a shared edge is found from both
        sides (``a`` and ``b`` swapped, the rise negated).

    Raises:
        InputError: a gap not above 0 or a negative max_rise.
    """
    if not (math.isfinite(gap) and gap > 0):
        raise InputError(f"contact gap {gap} m must be > 0")
    if not (math.isfinite(max_rise) and max_rise >= 0):
        raise InputError(f"contact max_rise {max_rise} m must be >= 0")
    out: list[Contact] = []
    for ia, sa in enumerate(surfaces):
        for a0, a1 in _edges(sa):
            out.extend(_edge_contacts(surfaces, ia, a0, a1, gap, max_rise))
    return out


def reachable(n: int, contacts: Sequence[Contact], start: int = 0) -> set[int]:
    """The surfaces reachable from ``start`` across contacts (either way).

    Args:
        n: number of surfaces.
        contacts: the contacts joining them.
        start: index of the surface to start from (the floor).

    Returns:
        Indices of the surfaces reachable, ``start`` included.
    """
    nbrs: list[set[int]] = [set() for _ in range(n)]
    for c in contacts:
        nbrs[c.a].add(c.b)
        nbrs[c.b].add(c.a)
    seen, todo = {start}, [start]
    while todo:
        for k in nbrs[todo.pop()] - seen:
            seen.add(k)
            todo.append(k)
    return seen
