"""The swing sole's corners over a slanted step edge (issue 47, winder stairs): a foot turned
against the nosing ahead (a winder's treads turn under a foot set along the walk line, up to
~35 deg) has a toe corner nearer the riser than its centre line. The sole is taken as the
humanoid's foot and toe boxes at the foot's width (:func:`sole_outline`: heel, ball, toe tip
and the toe block's top front, each at both sides); each known riser the step's chord crosses
going up (:func:`rising_risers`) is a line in the floor plane with its normal up the stair. A
point past that line is over the upper tread and keeps a margin over it; each side of the sole
crosses the line with the nosing's clearance under it (:func:`corner_need`). What the corners need
beyond what the sole's centre line needs at the same risers is the sole's width's cost: the
ankle is raised by it (:func:`corner_shortfall`, :func:`corner_lift`), so every corner keeps the
clearance the centre-line plan (``edgeswing``) gives its centre line, and a foot set along a
riser's normal (a straight flight) is left exactly as that plan made it.
Used by :mod:`mjwalk.body.legs.edgeswing`. World frame, z up, yaw from +x; metres, radians.
"""

from __future__ import annotations

import itertools

import numpy as np

from mjwalk.body.humanoid import LegGeometry
from mjwalk.body.legs.footpivot import ball_offset

#: Height of the toe block over the sole, in ankle heights: the humanoid's toe box is 0.2
#: ankle heights half-deep (:mod:`mjwalk.body.humanoid`), so 0.4 deep.
TOE_BLOCK_DEPTH = 0.4
#: Height differences (m) within which a riser's low and high sides are the step's surfaces:
#: the surfaces' own 1 cm (:data:`mjwalk.body.legs.edgeswing.LEVEL_STEP`, not imported: that
#: module imports this one).
HEIGHT_MATCH = 0.01
#: How far (m) beside a riser's half width the chord may cross its edge line and still cross
#: that riser (:data:`mjwalk.body.legs.edgeswing.RISER_SIDE_SLACK`'s reasoning: a walk crosses a
#: flight inside its width; the slack only keeps a riser in line with it from being taken).
SIDE_SLACK = 0.5
#: Least cosine between the chord and a riser's normal for the chord to go up over it (72 deg):
#: a walk line meets a winder's nosing at up to ~35 deg (the winder plan's walk line); the
#: same bound as edgeswing's riser search.
MIN_COS = 0.3
#: A corner within this (m) of the height it needs has it: 0.1 mm, the tolerance within which
#: the centre-line plan counts its sole as settled (``edgeswing.edge_swing`` stops raising a
#: swing short by at most 0.1 mm, ``legheights`` stops its sole passes once no rise exceeds
#: it).
REACHED = 1e-4


def sole_outline(
    pitch, toe, yaw, geom: LegGeometry, width: float = 1.0
) -> tuple[np.ndarray, np.ndarray]:
    """The foot's outline relative to its ankle: heel, ball, toe tip and the toe block's top
    front, at both sides of the sole (half the foot's width left and right of its centre line).

    Args:
        pitch: (m,) the foot's pitch, radians, + toes up.
        toe: (m,) the toe angle, radians (+ up).
        yaw: (m,) the foot's heading, radians from +x CCW.
        geom: the foot's lengths and width, metres.
        width: the share of the foot's width taken (0: its centre line).

    Returns:
        (xy (m, 2, 4, 2), z (m, 2, 4)): each side's (left, right) four points in the floor
        plane and their heights, metres relative to the ankle.
    """
    ah, back, front = geom.ankle_height, geom.foot_back, geom.foot_front
    ball = ball_offset(geom)
    cp, sp = np.cos(pitch), np.sin(pitch)
    ct, st = np.cos(pitch + toe), np.sin(pitch + toe)
    # the foot's vertical plane (forward, up) pitched: x cos p - z sin p, x sin p + z cos p
    bx, bz = ball * cp + ah * sp, ball * sp - ah * cp
    tx, tz = bx + (front - ball) * ct, bz + (front - ball) * st
    d = TOE_BLOCK_DEPTH * ah
    fw = np.stack([-back * cp + ah * sp, bx, tx, tx - d * st], -1)  # (m, 4)
    up = np.stack([-back * sp - ah * cp, bz, tz, tz + d * ct], -1)
    f = np.stack([np.cos(yaw), np.sin(yaw)], -1)  # (m, 2) forward
    left = np.stack([-np.sin(yaw), np.cos(yaw)], -1)
    half = 0.5 * geom.foot_width * width
    xy = np.empty((len(fw), 2, 4, 2))
    for k, s in enumerate((half, -half)):
        xy[:, k] = fw[..., None] * f[:, None, :] + s * left[:, None, :]
    return xy, np.repeat(up[:, None, :], 2, axis=1)


def rising_risers(lift, land, heights, risers) -> list[tuple[np.ndarray, np.ndarray, float]]:
    """The known risers a step's chord crosses going up: for each pair of successive surface
    heights under the chord that rises, the riser of those heights (within
    :data:`HEIGHT_MATCH`) whose edge line the chord crosses between its footprints, within the
    riser's half width plus :data:`SIDE_SLACK`, its normal up the stair along the chord.

    Args:
        lift: the lift footprint's x, y, metres.
        land: the landing footprint's x, y, metres.
        heights: the surfaces under the chord in its order, metres.
        risers: riser edge lines (x, y, normal x, normal y, low, high, half width), metres
            (:func:`mjwalk.body.legs.edgeswing.riser_lines`).

    Returns:
        Each crossed riser as (a point of its edge line (2,), its unit normal up the stair
        (2,), its top's height), metres.
    """
    lift, land = np.asarray(lift[:2], float), np.asarray(land[:2], float)
    seg = land - lift
    length = float(np.hypot(*seg))
    if length < 1e-9:
        return []
    e = seg / length
    out = []
    for z0, z1 in itertools.pairwise(heights):
        if z1 <= z0 + HEIGHT_MATCH:
            continue
        best, key = None, np.inf
        for x, y, nx, ny, low, high, half in risers:
            n = np.array([nx, ny], float) / max(float(np.hypot(nx, ny)), 1e-12)
            cos = float(e @ n)
            if abs(low - z0) > HEIGHT_MATCH or abs(high - z1) > HEIGHT_MATCH or cos < MIN_COS:
                continue
            q = np.array([x, y], float)
            t = float((q - lift) @ n) / cos
            side = abs(float((lift + t * e - q) @ np.array([-n[1], n[0]])))
            if 0.0 <= t <= length and side <= max(half, 0.0) + SIDE_SLACK:
                if side < key:
                    best, key = (q, n, float(high)), side
        if best is not None:
            out.append(best)
    return out


def corner_need(ankle_xy, outline, lines, margin: float, edge_margin: float) -> np.ndarray:
    """The least ankle height per sample that keeps the sole's corners off the risers
    ``lines``: every outline point past a riser's line (on its upper side) at least ``margin``
    over its top, and each side of the sole (heel, ball, toe tip, toe top front) crossing the
    line at least ``edge_margin`` over it.

    Args:
        ankle_xy: (m, 2) the ankle in the floor plane, metres.
        outline: :func:`sole_outline`'s (xy, z) for the same samples.
        lines: :func:`rising_risers`' risers.
        margin: least height of a point over the tread past the riser, metres.
        edge_margin: least height of the sole where it crosses the riser's line, metres.

    Returns:
        (m,) ankle heights, metres (-inf where no corner is past or over a riser).
    """
    rel_xy, rel_z = outline
    need = np.full(len(ankle_xy), -np.inf)
    pts = ankle_xy[:, None, None, :] + rel_xy  # (m, 2, 4, 2)
    for q, n, top in lines:
        d = (pts - q) @ n  # (m, 2, 4) signed distance past the riser's line
        past = np.where(d > 0.0, top + margin - rel_z, -np.inf).max(axis=(1, 2))
        need = np.maximum(need, past)
        da, db, za, zb = d[..., :-1], d[..., 1:], rel_z[..., :-1], rel_z[..., 1:]
        cross = (da > 0.0) != (db > 0.0)
        w = np.clip(da / np.where(cross, da - db, 1.0), 0.0, 1.0)
        zs = za + w * (zb - za)
        need = np.maximum(need, np.where(cross, top + edge_margin - zs, -np.inf).max(axis=(1, 2)))
    return need


def corner_shortfall(ankle, foot, lines, margins: tuple[float, float]) -> np.ndarray:
    """How far (m) the swing ankle lies below what the sole's corners need (:func:`corner_need`)
    beyond what its centre line needs at the same risers, or beyond where it is, whichever is
    higher, per sample: the clearance the sole's width costs, so its corners keep the clearance
    its centre line has (the centre-line plan's, ``edgeswing``); 0 where the shortfall is within
    :data:`REACHED`, and at the grounded ends (a foot along a riser's normal: 0 everywhere).

    Args:
        ankle: (m, 3) the swing ankle from the last grounded sample to the landing, metres.
        foot: (pitch, toe, yaw, geom): the foot's angles (m,) each, radians, and its lengths.
        lines: :func:`rising_risers`' risers.
        margins: (over a tread past a riser, over a riser's line), metres.

    Returns:
        (m,) the shortfall, metres (>= 0).
    """
    m = len(ankle)
    if not lines or m < 3:
        return np.zeros(m)
    pitch, toe, yaw, geom = foot
    need = corner_need(ankle[:, :2], sole_outline(pitch, toe, yaw, geom), lines, *margins)
    centre = corner_need(ankle[:, :2], sole_outline(pitch, toe, yaw, geom, 0.0), lines, *margins)
    short = need - np.maximum(centre, ankle[:, 2])
    short[[0, m - 1]] = 0.0
    return np.where(short > REACHED, short, 0.0)


def corner_lift(ankle, foot, lines, margins: tuple[float, float], rise_share: float) -> np.ndarray:
    """A step up's swing ankle heights raised where its corners need it (:func:`corner_need`),
    each raise reached ahead and left behind at the swing's own rise speed: its rise from its
    lower end to its highest in ``rise_share`` of the swing (the upper envelope of cones, as the
    centre-line plan rises, ``edgeswing.RISE_SHARE``); the grounded ends and, where no corner
    falls short, every height unchanged.

    Args:
        ankle: (m, 3) the swing ankle from the last grounded sample to the landing, metres.
        foot: (pitch, toe, yaw, geom): the foot's angles (m,) each, radians, and its lengths.
        lines: :func:`rising_risers`' risers.
        margins: (over a tread past a riser, over a riser's line), metres.
        rise_share: the share of the swing over which the ankle would rise to its highest.

    Returns:
        (m,) the ankle heights, metres.
    """
    z = np.array(ankle[:, 2], dtype=float)
    gap = corner_shortfall(ankle, foot, lines, margins)
    short = np.flatnonzero(gap)
    if not len(short):
        return z
    m = len(z)
    tau = np.arange(m) / (m - 1)
    speed = (z.max() - min(z[0], z[-1])) / rise_share  # metres per whole swing
    need = z[short] + gap[short]
    cone = (need[None, :] - speed * np.abs(tau[:, None] - tau[short][None, :])).max(axis=1)
    cone[[0, m - 1]] = -np.inf
    return np.maximum(z, cone)
