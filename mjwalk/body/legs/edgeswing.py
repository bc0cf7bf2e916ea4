"""The swing foot over step edges (issue 47, deliverable 4): where a step's footprints stand at
different heights (a step or a stair), the swing foot rises, travels and lowers so that its sole
clears every edge (nosing) between them by :data:`STAIR_TOE_CLEARANCE` (:func:`edge_swing`);
:class:`StepSurfaces` holds the heights a step touches. Used by :mod:`.legheights`. World frame,
metres, radians."""

from __future__ import annotations

import itertools
import math
from dataclasses import dataclass

import numpy as np

from mjwalk.body.humanoid import LegGeometry
from mjwalk.body.legs.curves import smoothstep, spread
from mjwalk.body.legs.footpivot import ball_offset
from mjwalk.body.legs.solecorners import corner_lift, corner_shortfall, rising_risers
from mjwalk.body.legs.steps import StepFrames
from mjwalk.world.norms import STAIR_TOE_CLEARANCE

#: Height differences below this between a step's surfaces are one level, metres (the
#: surfaces' own tolerance, :data:`mjwalk.world.norms.LEVEL_TOLERANCE`, with room for rounding).
LEVEL_STEP = 0.01
#: A surface pitch (radians) below this is level (0.3 deg: under norms.HORIZONTAL_SLOPE's 1 %).
FLAT_PITCH = math.radians(0.3)
#: Least height (m) a swing sole point keeps over the surface under it where no cited
#: clearance applies (:func:`edge_swing`'s sole heights, :func:`sole_rise`'s default): 2 mm,
#: a margin against grazing the surface, no measured figure (the legs' descent swings keep
#: :data:`mjwalk.world.norms.DESCENT_LOW_CLEARANCE` instead).
SOLE_MARGIN = 0.002


@dataclass(frozen=True)
class StepSurfaces:
    """The surfaces one step of a walk touches (metres above the floor, radians).

    Attributes:
        lift: height under the swing foot before it lifts.
        stance: height under the stance foot.
        land: height under the swing foot where it lands.
        lift_pitch: the lift surface's slope along the swing foot's heading (+ uphill).
        stance_pitch: the stance surface's slope along the stance foot's heading.
        land_pitch: the landing surface's slope along the landing heading.
        risers: the walk's riser edge lines, each (x, y, normal x, normal y, low, high,
            half width) (:func:`riser_lines`); empty: unknown, each edge may lie anywhere
            between the feet either side of it (:func:`_step_edges`).
        lift_ramp, stance_ramp, land_ramp: that footprint stands on a ramp's plane, pitched
            or level (:func:`~mjwalk.body.legs.rampreach.level_feet_on_ramps`), on no tread.
    """

    lift: float
    stance: float
    land: float
    lift_pitch: float = 0.0
    stance_pitch: float = 0.0
    land_pitch: float = 0.0
    risers: tuple[tuple[float, ...], ...] = ()
    lift_ramp: bool = False
    stance_ramp: bool = False
    land_ramp: bool = False

    @property
    def edged(self) -> bool:
        """Whether the step crosses a step edge: the surfaces of its footprints that stand on
        no ramp's plane differ in height, and neither its lift nor its landing surface is a
        ramp (on a ramp the heights change without an edge). A foot level on a ramp's plane
        beside its foot, centimetres up, was swung off it as down a stair: held over its
        footprint until its toes cleared a nosing there is not while the pelvis walked on,
        the leg stretched to its knee's limit put the foot 3.1 / 1.1 cm into the floor
        (generated halls 518 and 700, ``benchmarks/bench_unseen.py``)."""
        zs = [z for z, on in ((self.lift, self.lift_ramp), (self.stance, self.stance_ramp),
                              (self.land, self.land_ramp)) if not on]  # fmt: skip
        ramp = any(abs(p) > FLAT_PITCH for p in (self.lift_pitch, self.land_pitch))
        return len(zs) > 1 and (max(zs) - min(zs)) > LEVEL_STEP and not ramp

    @property
    def descends(self) -> bool:
        """Whether the step goes down a stair: its stance and landing surfaces both lower than
        the lift's (the trailing foot leaves a tread above the stance foot's; it lands lower
        still, or beside the stance foot where the flight ends). The last step off a stair,
        one riser down, was swung as a step up (held behind the nosing it leaves until its toes
        cleared it): knee peak 101.3 deg at 1.75 m, 95.4-95.6 on the flight (cited 80-100)."""
        return self.stance < self.lift - LEVEL_STEP and self.land < self.lift - LEVEL_STEP

    def pelvis_level(self) -> tuple[float, float]:
        """The pelvis's surface height at the step's start and end (double support).

        Returns:
            (start, end), metres: the lower foot's surface on steps and stairs, the mean of
            the feet's on ramps and level ground.
        """
        if self.edged:
            return min(self.lift, self.stance), min(self.stance, self.land)
        return 0.5 * (self.lift + self.stance), 0.5 * (self.stance + self.land)


def _sole_points(ankle, pitch, toe, yaw, geom: LegGeometry) -> np.ndarray:
    """(m, 3, 3) the heel, ball and toe tip of the foot (world x, y, z, metres) for ankles
    ``ankle`` (m, 3), pitches, toe angles and headings (m,) (radians, pitch + toes up)."""
    ah, back, front = geom.ankle_height, geom.foot_back, geom.foot_front
    ball = ball_offset(geom)
    cp, sp = np.cos(pitch), np.sin(pitch)
    # foot frame (forward, up) rotated by the pitch: x' = x cos p - z sin p, z' = x sin p + z cos p
    heel = (-back * cp + ah * sp, -back * sp - ah * cp)
    bl = (ball * cp + ah * sp, ball * sp - ah * cp)
    tip = (
        bl[0] + (front - ball) * np.cos(pitch + toe),
        bl[1] + (front - ball) * np.sin(pitch + toe),
    )
    f = np.stack([np.cos(yaw), np.sin(yaw)], -1)
    pts = np.empty((len(ankle), 3, 3))
    for k, (fw, up) in enumerate((heel, bl, tip)):
        pts[:, k, :2] = ankle[:, :2] + fw[:, None] * f
        pts[:, k, 2] = ankle[:, 2] + up
    return pts


@dataclass(frozen=True)
class _Edges:
    """The step edges a swing crosses, along its chord from the lift footprint (metres):
    ``lo``/``hi`` (e,) where each edge may lie, ``z`` (e,) its height; ``cut`` (r - 1,) the
    boundaries between the surfaces ``zr`` (r,) under the chord; ``known`` (e,) whether an
    edge lies where its riser is (:func:`_true_edge`)."""

    lo: np.ndarray
    hi: np.ndarray
    z: np.ndarray
    cut: np.ndarray
    zr: np.ndarray
    known: tuple[bool, ...] = ()


def riser_lines(meta: dict | None) -> tuple[tuple[float, ...], ...]:
    """A walk's riser edge lines from its ``meta["edges"]`` (the level planner's crossings,
    :meth:`mjwalk.plan.levelroute.Crossing.riser_lines`, or a synthetic stair's).

    Args:
        meta: the walk's meta (or None).

    Returns:
        each edge as (x, y, normal x, normal y, low, high, half width), metres; () without.
    """
    return tuple(
        (*e["xy"], *e["normal"], e["low"], e["high"], e.get("half_width", 0.0))
        for e in (meta or {}).get("edges") or ()
    )


#: How far (m) beside a riser's known width, or from its point when the width is unknown, a
#: chord may cross its edge line and still cross that riser: the planner walks a crossing
#: inside its width; the margin only keeps another stair's riser of the same heights, in line
#: with this one, from being taken for it.
RISER_SIDE_SLACK = 0.5


def _true_edge(span: tuple[float, float], pair: tuple[float, float], fr: StepFrames,
               risers) -> float | None:  # fmt: skip
    """Where along the chord (m from the lift footprint) a riser between surfaces ``pair``
    (heights, metres) crosses it: the riser of those heights (within :data:`LEVEL_STEP`)
    whose edge line the chord crosses inside ``span`` (the footprints either side, metres),
    the nearest to the span's middle; None when no known riser fits."""
    seg = fr.land[:2] - fr.lift[:2]
    e = seg / max(float(np.hypot(*seg)), 1e-9)
    lo_z, hi_z = min(pair), max(pair)
    best, key = None, math.inf
    for x, y, nx, ny, low, high, half in risers:
        cos = float(e @ (n := np.array([nx, ny])))
        if abs(low - lo_z) > LEVEL_STEP or abs(high - hi_z) > LEVEL_STEP or abs(cos) < 0.3:
            continue
        t = float((np.array([x, y]) - fr.lift[:2]) @ n) / cos
        side = abs(float((fr.lift[:2] + t * e - (x, y)) @ (-ny, nx)))
        reach = (half if half > 0 else 0.0) + RISER_SIDE_SLACK * (1.0 if half > 0 else 4.0)
        if span[0] <= t <= span[1] and side <= reach and abs(t - sum(span) / 2) < key:
            best, key = t, abs(t - sum(span) / 2)
    return best


def _step_edges(fr: StepFrames, surf: StepSurfaces, geom: LegGeometry) -> _Edges:
    """The edges of an edged step: between the surfaces of the lift, stance and landing footprints
    in their order along the chord, each where its riser's edge line crosses the chord
    (:func:`_true_edge`) on a step down, or where the riser is not known and on a step up, anywhere
    from the toe of the foot behind to the heel of the foot ahead (their midpoint where those
    overlap). That span held a first step down off a stair's landing, whose landing heel lay just
    past it, at the landing's height to the last samples (hip 48.9 deg, then the knee 72 -> 8 deg in
    one frame: gait47), and the last step off a flight likewise (its ankle fell 18.6 cm in one frame
    at 1.55-1.95 m). Steps up keep the span: with the true edge the closing step onto a stair's top
    landing, its toes held behind the nosing until they clear it (:func:`_keep_behind_edges`),
    jumped 23-26 cm forward in one frame at 1.55 and 1.75 m (landing47, not solved)."""
    seg = fr.land[:2] - fr.lift[:2]
    length = max(float(np.hypot(*seg)), 1e-9)
    e = seg / length
    x_s = float((fr.stance[:2] - fr.lift[:2]) @ e)
    regions = [(0.0, surf.lift)]
    if 0.0 < x_s < length:
        regions.append((x_s, surf.stance))
    regions.append((length, surf.land))
    merged = [regions[0]]
    for x, z in regions[1:]:
        if abs(z - merged[-1][1]) > LEVEL_STEP:
            merged.append((x, z))
    lo, hi, ze, cut, known = [], [], [], [], []
    down = surf.land < surf.lift - LEVEL_STEP  # steps up keep the span (docstring)
    for (x0, z0), (x1, z1) in itertools.pairwise(merged):
        a, b = x0 + geom.foot_front, x1 - geom.foot_back
        if a > b:
            a = b = 0.5 * (x0 + x1)
        t = _true_edge((x0, x1), (z0, z1), fr, surf.risers) if down else None
        a, b = (a, b) if t is None else (t, t)
        known.append(t is not None)
        lo.append(a)
        hi.append(b)
        ze.append(max(z0, z1))
        cut.append(0.5 * (a + b))
    zr = np.array([z for _, z in merged])
    return _Edges(np.array(lo), np.array(hi), np.array(ze), np.array(cut), zr, tuple(known))


def _edges_off_grounded(edges: _Edges, ends: np.ndarray, fr: StepFrames) -> _Edges:
    """The edges moved off the grounded feet: the foot at lift-off stands on its surface, so the
    first edge lies ahead of its sole's foremost point (its toe tip in the toe-off pose, which
    reaches past the toe of the flat foot), and the landed foot stands on its surface, so the last
    edge lies behind its sole's rearmost point; an edge whose riser is known stays where it is (a
    tall walker's toes hang over the nosing ahead, in the air: moved past them, the last step off a
    flight held its foot up and dropped it 18.6 cm in one frame at 1.95 m). ``ends`` (2, 3, 3): the
    sole's heel, ball and toe at the last grounded sample before lift-off and at landing."""
    seg = fr.land[:2] - fr.lift[:2]
    e = seg / max(float(np.hypot(*seg)), 1e-9)
    x = (ends[..., :2] - fr.lift[:2]) @ e  # (2, 3)
    lo, hi = edges.lo.copy(), edges.hi.copy()
    known = edges.known or (False,) * len(lo)
    if not known[0]:
        lo[0] = max(lo[0], float(x[0].max()) + 1e-3)
        hi[0] = max(hi[0], lo[0])
    if not known[-1]:
        hi[-1] = min(hi[-1], float(x[1].min()) - 1e-3)
        lo[-1] = min(lo[-1], hi[-1])
    return _Edges(lo, hi, edges.z, 0.5 * (lo + hi), edges.zr, edges.known)


def _clearance_deficit(pts: np.ndarray, fr: StepFrames, edges: _Edges, clearance: float) -> float:
    """How far (m) the sole ``pts`` (m, 3, 3) dips below ``clearance`` over an edge it spans
    or below the surface under a sole point, at worst (0 if nowhere)."""
    seg = fr.land[:2] - fr.lift[:2]
    e = seg / max(float(np.hypot(*seg)), 1e-9)
    x = (pts[..., :2] - fr.lift[:2]) @ e  # (m, 3) chord coordinates
    z = pts[..., 2]
    worst = 0.0
    # a sole point over a surface stays above it (the landing foot sinks into nothing)
    zr = edges.zr[np.searchsorted(edges.cut, x)]
    worst = max(worst, float(np.max(zr - 1e-3 - z)))
    for lo, hi, ze in zip(edges.lo, edges.hi, edges.z, strict=True):
        for a, b in ((0, 1), (1, 2)):  # the heel-ball and ball-toe segments of the sole
            xa, xb, za, zb = x[:, a], x[:, b], z[:, a], z[:, b]
            for xe in (lo, hi):
                over = (np.minimum(xa, xb) < xe - 1e-3) & (xe + 1e-3 < np.maximum(xa, xb))
                if not over.any():
                    continue
                dx = np.where(xb[over] != xa[over], xb[over] - xa[over], 1.0)
                zs = za[over] + np.clip((xe - xa[over]) / dx, 0, 1) * (zb[over] - za[over])
                worst = max(worst, float(np.max(ze + clearance - zs)))
    return worst


def edge_swing(ankle, pitch, toe, yaw, fr: StepFrames, surf: StepSurfaces, geom: LegGeometry,
               clearance: float = STAIR_TOE_CLEARANCE):  # fmt: skip
    """The swing foot of an edged step (a step or a stair) over its airborne samples. A step up
    (:func:`_swing_path`) rises until its toes clear the first edge, then travels forward (the flat
    swing's path, re-timed; its pitch, toes and heading kept) rising on to reach each further edge
    ``clearance`` above it, and lowers once its heel is past the last; raised further where the sole
    would still come closer to an edge, or its corners need more than its centre line over a slanted
    riser (:mod:`.solecorners`). A step down (:func:`_swing_path`) the same way for its foot hanging
    toes down, planned once (the clearance returned is that plan's): :func:`sole_rise` then lifts
    the sole where the foot, pitched again to what its ankle holds, would dip into a tread.

    Args:
        ankle: (m, 3) the flat swing's ankle from the last grounded sample before lift-off
            to the landing, metres, world frame (with the surfaces' heights added at both ends).
        pitch: (m,) the foot's pitch, radians, + toes up.
        toe: (m,) the toe angle, radians.
        yaw: (m,) the foot's heading, radians from +x CCW.
        fr: the step (lift, stance and landing footprints).
        surf: the step's surfaces.
        geom: the leg and foot lengths.
        clearance: the least clearance over an edge, metres.

    Returns:
        (m, 3) the new ankle positions, metres, and the least clearance over the edges
        reached (metres; ``clearance`` or more where the design holds; its centre line's).
    """
    m = len(ankle)
    tau = np.arange(m) / max(m - 1, 1)
    ends = [0, m - 1]
    edges = _step_edges(fr, surf, geom)
    if not len(edges.lo):  # no edge between lift-off and landing: the flat swing
        return ankle.copy(), clearance
    edges = _edges_off_grounded(
        edges, _sole_points(ankle[ends], pitch[ends], toe[ends], yaw[ends], geom), fr
    )
    seg = fr.land[:2] - fr.lift[:2]
    length = max(float(np.hypot(*seg)), 1e-9)
    e = seg / length
    u_f = np.maximum.accumulate(np.clip((ankle[:, :2] - fr.lift[:2]) @ e / length, 0, 1))
    u_f[-1] = max(u_f[-1], u_f[-2] + 1e-9) if m > 1 else u_f[-1]
    u_f = u_f + np.arange(m) * 1e-12  # strictly increasing for np.interp
    extra, out, need, foot = 0.0, ankle.copy(), 0.0, (pitch, toe, yaw, geom)
    descent = surf.descends
    lines = rising_risers(fr.lift, fr.land, edges.zr, () if descent else surf.risers)
    for _ in range(3):
        # a step down moves forward as long as its heel can still be lowered in time
        end = 1.0 if descent else ASCENT_CLEARANCE_END
        out = _swing_path(ankle, (u_f, tau), (pitch, toe), edges, fr, geom,
                          (clearance + extra, end))  # fmt: skip
        if not descent:
            out[:, 2] = rise_held(out[:, 2], _toe_heel(pitch, toe, geom)[1])
            _keep_behind_edges(out, out[:, 2], clearance, pitch, toe, edges, fr, geom)
            out[:, 2] = corner_lift(out, foot, lines, (SOLE_MARGIN, clearance), RISE_SHARE)
        out[0], out[-1] = ankle[0], ankle[-1]
        need = _clearance_deficit(_sole_points(out[1:-1], pitch[1:-1], toe[1:-1], yaw[1:-1], geom),
                                  fr, edges, clearance)  # fmt: skip
        if need <= 1e-4 or descent:  # a descent's sole is lifted by sole_rise instead
            break
        extra += need + 0.005
    return out, clearance - need


def rise_held(z: np.ndarray, tip: np.ndarray) -> np.ndarray:
    """A step up's swing held from lift-off to its highest: its toe tip never lower than it
    was before. The least height that keeps the sole over the edges (:func:`_swing_path`)
    can fall after lift-off where the toes, flexing back from toe-off, leave the span where
    the edge may lie while the foot still hangs behind the riser; and the toes flexing back
    lower the tip of a foot hanging toes down. The foot then sank back along the riser, its
    toe block's front (leading the tip of a foot hanging toes down) into the riser's top (the
    platform cycle's 1.5 mm toe contact on a 0.17 m step up).

    Args:
        z: (m,) the swing ankle's heights from lift-off to landing, metres.
        tip: (m,) the toe tip's height relative to the ankle, metres (:func:`_toe_heel`).

    Returns:
        (m,) the ankle heights, up to the highest one raised so that the toe tip stays as high
        as it was at any sample before, metres.
    """
    top = int(np.argmax(z))
    out = np.array(z, dtype=float)
    held = np.maximum.accumulate(out[: top + 1] + tip[: top + 1]) - tip[: top + 1]
    out[: top + 1] = np.maximum(out[: top + 1], held)
    return out


#: Share of a step up's swing time over which its ankle would rise from lift-off to its
#: highest: it bounds the ankle's vertical speed (the old flat-apex profile's 0.45).
RISE_SHARE = 0.45
#: Share of a step up's swing time by which the foot is over its landing tread (its heel past
#: the last edge); the rest it lowers onto it. McFadyen & Winter (1988, J Biomech
#: 21:733-744) divide the ascent swing into foot clearance and foot placement; the share is
#: this module's choice, not a published figure. Measured
#: on the 0.17/0.28 stair at 1.75 m: 0.6 gives knee 104.5 / hip 58.3 deg peaks, 0.7 gives
#: 99.2 / 54.4, 0.75 gives 100.8 / 53.2 (0.65: 102.3 / 57.0, but 104.9 knee at 1.55 m).
ASCENT_CLEARANCE_END = 0.7
#: Depth of the toes over the sole, in ankle heights (the humanoid's toe block,
#: :mod:`mjwalk.body.humanoid`).
TOE_DEPTH = 0.4
#: A sole point planned at a clearance (:func:`_clear_at_turns`) reaches it within this (m):
#: a heel 1e-16 m short of it on one tread of a regular stair had its swing raised 32 cm.
REACHED = 1e-6


def _sole_need(px, pz, edges: _Edges, margin: float, edge_margin: float,
               slack: float = 1e-3) -> np.ndarray:  # fmt: skip
    """The least ankle height (or rise) per sample that keeps every sole point over the
    surface under it by ``margin`` (over the span where an edge may lie, the higher of its
    two surfaces) and the sole between heel and ball, ball and toe tip, over an edge it spans
    by ``edge_margin``. ``px`` (m, 3): the heel's, ball's and toe tip's chord coordinates;
    ``pz`` (m, 3): their heights (above the ankle for a height, absolute for a rise: the
    result is then the rise); metres. ``slack``: how far (m) past an edge's span a point
    still counts as over it (the grounded feet stand 1 mm off the spans)."""
    under = edges.zr[np.searchsorted(edges.cut, px)]
    for lo, hi, ze in zip(edges.lo, edges.hi, edges.z, strict=True):
        under = np.where((px >= lo - slack) & (px <= hi + slack), np.maximum(under, ze), under)
    need = (under + margin - pz).max(axis=1)
    for lo, hi, ze in zip(edges.lo, edges.hi, edges.z, strict=True):
        for a, b in ((0, 1), (1, 2)):  # the sole between heel and ball, ball and toe tip
            for xe in (lo, hi):
                lo_x, hi_x = np.minimum(px[:, a], px[:, b]), np.maximum(px[:, a], px[:, b])
                over = (lo_x < xe) & (xe < hi_x)
                w = np.clip((xe - px[:, a]) / np.where(over, px[:, b] - px[:, a], 1.0), 0.0, 1.0)
                zs = pz[:, a] + w * (pz[:, b] - pz[:, a])
                need = np.where(over, np.maximum(need, ze + edge_margin - zs), need)
    return need


def _swing_path(ankle, time, foot, edges: _Edges, fr: StepFrames, geom: LegGeometry,
                levels) -> np.ndarray:  # fmt: skip
    """The swing ankle of an edged step; for a step up (a stair or a step ascended): it rises until
    its toes clear the first edge, moves forward from then (the flat swing's path re-timed, over by
    :data:`ASCENT_CLEARANCE_END`) and rises on as it goes, its sole as pitched reaching each further
    edge ``clearance`` above it -- not first up to clear the highest edge with the foot held behind
    the body, which flexed the knee past its cited peak -- and lowers onto the landing tread once
    its heel is past the last edge. Its height is the least that keeps the sole over the surfaces
    and ``clearance`` over the edges it spans (:func:`_sole_need`), reached ahead of where it is
    needed at a bounded speed (the whole rise in :data:`RISE_SHARE` of the swing: the upper envelope
    of cones). The forward motion of the foot over the lower nosing early, with the foot
    dorsiflexed, is how stair ascent's swing clears the step (McFadyen & Winter 1988; Riener et al.
    2002). A step down the same way: its foot, hanging toes down for its forefoot landing, moves
    forward once its toes clear the lift tread's nosing and keeps on as long as its heel can still
    be lowered onto the landing tread in time, its sole ``clearance`` over the nosings it spans (leg
    pull-through, then foot placement: McFadyen & Winter 1988). ``time`` = (u_f, tau), ``foot`` =
    (pitch, toe) per sample, ``levels`` = (clearance, the share of the swing by which the forward
    motion is over at the latest); returns (m, 3) ankles, metres."""
    (u_f, tau), (pitch, toe), (clearance, end) = time, foot, levels
    m = len(ankle)
    tip_x, tip_z, heel_x, heel_z = _toe_heel(pitch, toe, geom)
    ball = ball_offset(geom)
    ball_x = ball * np.cos(pitch) + geom.ankle_height * np.sin(pitch)
    ball_z = ball * np.sin(pitch) - geom.ankle_height * np.cos(pitch)
    low = np.minimum(np.minimum(tip_z, heel_z), ball_z)  # the sole's lowest point
    z_a, z_b = float(ankle[0, 2]), float(ankle[-1, 2])
    v = max(float(edges.z.max() + clearance - low.min()) - min(z_a, z_b), 1e-9) / RISE_SHARE
    # forward once the toe tip can clear the first edge, over once the heel can drop
    up_ok = z_a + v * tau >= edges.z[0] + clearance - tip_z
    t_a = float(tau[np.argmax(up_ok)]) if up_ok.any() else RISE_SHARE
    down_ok = z_b + v * (1.0 - tau) >= edges.z[-1] + clearance - heel_z
    t_b = float(tau[m - 1 - np.argmax(down_ok[::-1])]) if down_ok.any() else 1.0 - RISE_SHARE
    t_b = max(min(t_b, end), t_a + 0.2)
    u = smoothstep((tau - t_a) / max(t_b - t_a, 1e-9))
    xy = np.column_stack([np.interp(u, u_f, ankle[:, 0]), np.interp(u, u_f, ankle[:, 1])])
    # onto the landing ankle (a forefoot landing's lies ahead of the footprint's)
    xy += u[:, None] * (ankle[-1, :2] - xy[-1])[None, :]
    seg = fr.land[:2] - fr.lift[:2]
    e = seg / max(float(np.hypot(*seg)), 1e-9)
    x = (xy - fr.lift[:2]) @ e
    if end < 1.0:  # a step up: its toe tip held behind the first edge until it can clear it
        back = _toes_back(x, tau < t_a, u, tip_x, edges.lo[0])
        x, xy = x + back, xy + back[:, None] * e
    px = x[:, None] + np.column_stack([heel_x, ball_x, tip_x])  # (m, 3) heel, ball, toe tip
    req = _sole_need(
        px, np.column_stack([heel_z, ball_z, tip_z]), edges, SOLE_MARGIN, clearance, 0.0
    )
    if end < 1.0:  # a step up: toes over the first edge when they start forward, heel over
        # the last when the foot is over its tread (the holds of _keep_behind_edges end there)
        _clear_at_turns(req, tau, (t_a, t_b), (tip_z, heel_z), edges, clearance)
    req[0], req[-1] = z_a, z_b
    z = (req[None, :] - v * np.abs(tau[:, None] - tau[None, :])).max(axis=1)
    if m > 8:  # the cones' corners rounded (running maximum, Gaussian), never lowered
        z = z_b - 1.0 + spread(z - (z_b - 1.0), 2)
    return np.column_stack([xy, z])


def _clear_at_turns(req, tau, times, ends, edges: _Edges, clearance: float) -> None:
    """A step up's required ankle heights ``req`` (m,) raised (in place) so that the toe tip
    is ``clearance`` over the first edge at ``times[0]``, when the foot starts forward (before
    it, :func:`_toes_back` holds the tip behind that edge), and the heel ``clearance`` over the
    last edge at ``times[1]``, when the foot is over its tread; the rise at the bounded speed
    of :func:`_swing_path` reaches both heights in time (they define those times). Without
    them the sole's least height fell short there wherever the foot hung toes down, and
    :func:`_keep_behind_edges` then held the foot behind the edge past the time it should have
    moved forward and let it go all at once: the first step up off the floor jumped 7.9 / 10.9
    cm in one 1/120 s sample at 1.75 / 1.95 m, the last onto the landing 8.0 cm at 1.55 m
    (a88f200), and up to 26 cm with the pelvis midway between the feet at the walk's first
    step (``synthetic_stair_walk``). ``tau`` (m,) the swing's times, 0 to 1; ``ends`` the toe
    tip's and heel's heights relative to the ankle (m,) each; metres."""
    tip_z, heel_z = ends
    m = len(req)
    first, last = edges.z[0] + clearance - tip_z, edges.z[-1] + clearance - heel_z
    for t, z in ((times[0], first), (times[1], last)):
        i = int(np.searchsorted(tau, t - 1e-12))
        if 0 < i < m - 1:
            req[i] = max(req[i], float(z[i]))


def _toes_back(x, early, u, tip, edge: float) -> np.ndarray:
    """How far (m, <= 0) a step up's swing ankle at chord coordinates ``x`` (m,) moves back so
    that its toe tip (``tip`` (m,) ahead of it) stays 1 mm behind where it stood at lift-off
    (``edge``, m, the first edge's nearest place, lies 1 mm ahead of it:
    :func:`_edges_off_grounded`; :func:`sole_rise` counts the tip there as over it) in the
    samples ``early`` (m,) bool, before the tip can clear that edge; after them the shift
    fades with the forward motion ``u`` (m,, 0 to 1), so the ankle moves on without a jump.
    The foot flattening after lift-off turned its tip forward past that place, where the
    edge may lie, so the height it needs there (:func:`_sole_need`) rose by the riser in the
    first airborne sample: the ankle rose 6-12 cm in one 1/120 s sample up a 0.17 m stair
    (1.55-1.95 m), 34 cm in the first plan, whose foot, pitched toes down by what the ankle
    then lacked (``legheights._swing_pitch``, 24 -> 58 deg), kept it there."""
    back = np.where(early, np.minimum(edge - 2e-3 - tip - x, 0.0), 0.0)
    k = int(np.argmin(early)) if not early.all() else len(x)
    if 0 < k < len(x):
        back[k:] = back[k - 1] * (1.0 - u[k:])
    return back


def _toe_heel(pitch, toe, geom: LegGeometry):
    """The toe tip's and the heel's positions relative to the ankle in the foot's vertical
    plane (forward, up; metres) for pitches and toe angles (radians, + toes up): (tip_x,
    tip_z, heel_x, heel_z), as :func:`_sole_points` places them."""
    ball = ball_offset(geom)
    ah = geom.ankle_height
    cp, sp = np.cos(pitch), np.sin(pitch)
    tip_x = ball * cp + ah * sp + (geom.foot_front - ball) * np.cos(pitch + toe)
    tip_z = ball * sp - ah * cp + (geom.foot_front - ball) * np.sin(pitch + toe)
    return tip_x, tip_z, -geom.foot_back * cp + ah * sp, -geom.foot_back * sp - ah * cp


def _keep_behind_edges(out, z, clearance, pitch, toe, edges: _Edges, fr: StepFrames,
                       geom: LegGeometry) -> None:  # fmt: skip
    """Hold the swing foot's toe tip behind the first edge until it clears that edge by
    ``clearance`` on the way up, and its heel past the last edge once it is below that edge
    plus ``clearance`` on the way down (the ankles ``out`` (m, 3) at heights ``z`` moved along
    the chord, in place): a foot flattening after lift-off turns about its toes instead of
    pushing them into the riser or over the nosing."""
    seg = fr.land[:2] - fr.lift[:2]
    e = seg / max(float(np.hypot(*seg)), 1e-9)
    tip, tip_z, heel, heel_z = _toe_heel(pitch, toe, geom)
    x = (out[:, :2] - fr.lift[:2]) @ e
    # before the toe tip first clears the first edge; after the heel last clears the last
    first, last = edges.z[0] + clearance - REACHED, edges.z[-1] + clearance - REACHED
    rising = ~np.logical_or.accumulate(z + tip_z >= first)
    falling = ~np.logical_or.accumulate((z + heel_z >= last)[::-1])[::-1]
    # the toes' top front corner (the toe block 0.4 ankle heights deep: body.humanoid) leads
    # the toe tip of a foot pitched toes down
    front = tip + TOE_DEPTH * geom.ankle_height * np.maximum(-np.sin(pitch + toe), 0.0)
    x_new = np.where(rising, np.minimum(x, edges.lo[0] - front), x)
    x_new = np.where(falling, np.maximum(x_new, edges.hi[-1] - heel), x_new)
    out[:, :2] += (x_new - x)[:, None] * e


def swing_clearance(ankle, pitch, toe, yaw, fr: StepFrames, surf: StepSurfaces, geom: LegGeometry,
                    clearance: float = STAIR_TOE_CLEARANCE) -> float:  # fmt: skip
    """The least clearance of an edged step's swing sole over its edges (and of its sole points
    over the surfaces under them), as :func:`edge_swing` reports it, for a swing as it stands.

    Args:
        ankle: (m, 3) the swing ankle from the last grounded sample to the landing, metres.
        pitch: (m,) the foot's pitch, radians, + toes up.
        toe: (m,) the toe angle, radians.
        yaw: (m,) the foot's heading, radians from +x CCW.
        fr: the step.
        surf: its surfaces.
        geom: the leg and foot lengths.
        clearance: the clearance sought over an edge, metres.

    Returns:
        the least clearance, metres (``clearance`` where the swing keeps it everywhere).
    """
    ends = [0, len(ankle) - 1]
    edges = _step_edges(fr, surf, geom)
    if not len(edges.lo):  # no edge between lift-off and landing: the flat swing
        return clearance
    edges = _edges_off_grounded(
        edges, _sole_points(ankle[ends], pitch[ends], toe[ends], yaw[ends], geom), fr
    )
    pts = _sole_points(ankle[1:-1], pitch[1:-1], toe[1:-1], yaw[1:-1], geom)
    return clearance - _clearance_deficit(pts, fr, edges, clearance)


def sole_rise(ankle, pitch, toe, yaw, fr: StepFrames, surf: StepSurfaces, geom: LegGeometry,
              margin: float = SOLE_MARGIN) -> np.ndarray:  # fmt: skip
    """How far the swing ankle of an edged step must rise so that no point of its sole (heel,
    ball, toe tip, at the foot's pitch and toe angle) lies below the surface under it: over
    the span where an edge may lie (:func:`_step_edges`, moved off the grounded feet) the
    higher of its two surfaces counts, and the sole between heel and ball or ball and toe tip
    passes over an edge's ends no lower than that edge. The rise is smoothed over the samples
    around (a running maximum over +-2 samples, Gaussian) and is nil at both ends (grounded).

    Args:
        ankle: (m, 3) the swing ankle from the last grounded sample to the landing, metres.
        pitch: (m,) the foot's pitch, radians, + toes up.
        toe: (m,) the toe angle, radians.
        yaw: (m,) the foot's heading, radians from +x CCW.
        fr: the step.
        surf: its surfaces.
        geom: the leg and foot lengths.
        margin: the least height of a sole point over its surface, metres.

    Returns:
        (m,) the rise per sample, metres (>= 0).
    """
    m = len(ankle)
    if m < 3:
        return np.zeros(m)
    ends = [0, m - 1]
    edges = _step_edges(fr, surf, geom)
    if not len(edges.lo):  # no edge between lift-off and landing: the flat swing
        return np.zeros(m)
    edges = _edges_off_grounded(
        edges, _sole_points(ankle[ends], pitch[ends], toe[ends], yaw[ends], geom), fr
    )
    seg = fr.land[:2] - fr.lift[:2]
    e = seg / max(float(np.hypot(*seg)), 1e-9)
    pts = _sole_points(ankle, pitch, toe, yaw, geom)
    x = (pts[..., :2] - fr.lift[:2]) @ e  # (m, 3)
    need = np.maximum(_sole_need(x, pts[..., 2], edges, margin, margin), 0.0)
    lines = rising_risers(fr.lift, fr.land, edges.zr, () if surf.descends else surf.risers)
    need = np.maximum(need, corner_shortfall(ankle, (pitch, toe, yaw, geom), lines, (margin,) * 2))
    need[ends] = 0.0
    if not need.any():
        return need
    rise = np.maximum(spread(need, 2), need)
    rise[ends] = 0.0
    return rise
