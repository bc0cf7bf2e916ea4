"""The legs on walk surfaces of several heights (issue 47, deliverable 4): the flat leg
synthesis's tracks lifted onto platforms, steps, stairs and ramps.

:func:`~mjwalk.body.legs.synthesis.legs_from_walk` synthesises every walk as if on the floor;
a walk that leaves the floor (:attr:`WalkPath.is_flat <mjwalk.plan.walkpath.WalkPath.is_flat>`
false) then passes through :func:`lift_to_levels`:

* **Feet on their surfaces.** A grounded foot stands on the height of its footprint's surface
  (``PathStep.foot_z`` / ``stance_z``); on a ramp it is pitched to the slope (turned about its
  footprint point in the vertical plane of its heading), as the slope's pitch along the foot.
* **Swing over step edges.** Where a step's footprints stand at different heights (a step or a
  stair), the swing foot rises, travels and lowers (:func:`edge_swing`): it moves forward only
  once its sole clears the first edge by :data:`STAIR_TOE_CLEARANCE`, and lowers below the
  last edge only once past it; the edges lie between the footprints' surfaces (the toe of the
  foot behind, the heel of the foot ahead: on a stair with footprints on the treads' centres,
  the nosings). Steps whose surfaces are a ramp or level keep the flat swing, carried on the
  heights of its ends.
* **The pelvis follows the level.** Its height is the flat synthesis's plus the lower of the
  two feet's surfaces in double support (on a ramp their mean), changing over the single
  support of each step (smoothstep): up a stair the pelvis rises while the leading leg pulls up
  (a riser per step), down a stair it lowers while the stance leg yields. Where a grounded leg
  then cannot reach its foot, the pelvis lowers (smoothly).
* **Joint angles** by the same leg IK as the flat synthesis, clipped to the joint ranges.

The knee and hip flexion this gives on a stair is not prescribed: it follows from the geometry
(a leg that lands one riser up flexes its knee and hip by the riser). The published peaks are
:data:`KNEE_PEAK_UP` and the others below; ``tests/body/test_legheights.py`` and
``benchmarks/bench_levels.py`` hold the synthesis to them. World frame, metres, radians.
"""

from __future__ import annotations

import itertools
import math
from dataclasses import dataclass

import numpy as np

from mjwalk.body.humanoid import ROM_DEG, LegGeometry
from mjwalk.body.legs.curves import smoothstep, spread
from mjwalk.body.legs.ik import KNEE_MIN, generic_joint, leg_ik_world
from mjwalk.body.legs.stance import reach_deficit
from mjwalk.body.legs.steps import FootTracks, StepFrames
from mjwalk.plan.walkpath import WalkPath
from mjwalk.world.norms import MAX_RAMP_SLOPE

#: Least vertical clearance of the swing foot's sole over a step edge (nosing), metres. Young
#: adults' minimum foot clearance over stair nosings is a few centimetres: Hamel, Okita,
#: Higginson & Cavanagh, "Foot clearance during stair descent: effects of age and
#: illumination", Gait Posture 21:135-140 (2005) count clearances under 5 mm as the risky ones
#: (abstract verified here); Francksen et al., "Negotiating stairs with an inconsistent riser",
#: Applied Ergonomics (2022) report that a 10 mm higher riser cuts ascent clearance by ~9 mm
#: (highlights verified here), a trip risk, so the usual clearance is not much larger; the
#: group means of 3-4 cm usually quoted from these studies are NOT verified here. 3 cm.
STAIR_TOE_CLEARANCE = 0.03
#: Height differences below this between a step's surfaces are one level, metres (the
#: surfaces' own tolerance, :data:`mjwalk.world.norms.LEVEL_TOLERANCE`, with room for rounding).
LEVEL_STEP = 0.01
#: A surface pitch (radians) below this is level (0.3 deg: under norms.HORIZONTAL_SLOPE's 1 %).
FLAT_PITCH = math.radians(0.3)
#: Footprint neighbourhood (m) over which the walk's ground slope under a foot is estimated.
SLOPE_REACH = 0.3

#: Peak knee flexion over a stride on a stair of about 30 deg, degrees, ascent and descent.
#: Protopapadaki et al., "Hip, knee, ankle kinematics and kinetics during stair ascent and
#: descent in healthy young individuals", Clin Biomech 22:203-210 (2007), 18/28.5 cm stair:
#: knee flexion greater in ascent than descent by 3.4 deg (SD 7.2) (abstract verified here);
#: a single 20.3 cm step is ascended with 90.5 deg lead-knee flexion ("Hip and knee flexion of
#: lead and trail limbs during ascent of a step of different heights by normal adults",
#: abstract verified here). The ranges span the peaks reported by Riener, Rabuffetti & Frigo,
#: Gait Posture 15:32-44 (2002) at 24-42 deg, McFadyen & Winter, J Biomech 21:733-744 (1988)
#: and Protopapadaki et al. (2007) (about 83-105 deg up, 80-100 deg down; NOT verified here
#: beyond the abstracts).
KNEE_PEAK_UP = (83.0, 105.0)
KNEE_PEAK_DOWN = (80.0, 100.0)
#: Peak hip flexion, degrees: greater up than down by 28.1 deg (SD 4.1) (Protopapadaki et al.
#: 2007, abstract verified here); 66.3 deg lead-hip flexion up a 20.3 cm step (abstract above,
#: verified); ranges as those studies report them (NOT verified beyond the abstracts).
HIP_PEAK_UP = (55.0, 75.0)
HIP_PEAK_DOWN = (20.0, 45.0)


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
    """

    lift: float
    stance: float
    land: float
    lift_pitch: float = 0.0
    stance_pitch: float = 0.0
    land_pitch: float = 0.0

    @property
    def edged(self) -> bool:
        """Whether the step crosses a step edge: its surfaces differ in height and none is a
        ramp (on a ramp the heights change without an edge)."""
        zs = (self.lift, self.stance, self.land)
        ramp = any(abs(p) > FLAT_PITCH for p in (self.lift_pitch, self.land_pitch))
        return (max(zs) - min(zs)) > LEVEL_STEP and not ramp

    def pelvis_level(self) -> tuple[float, float]:
        """The pelvis's surface height at the step's start and end (double support).

        Returns:
            (start, end), metres: the lower foot's surface on steps and stairs, the mean of
            the feet's on ramps and level ground.
        """
        if self.edged:
            return min(self.lift, self.stance), min(self.stance, self.land)
        return 0.5 * (self.lift + self.stance), 0.5 * (self.stance + self.land)


def surface_pitch(walk: WalkPath, print_: np.ndarray) -> float:
    """The slope of the walk's ground along a footprint's heading, from the walk's ground
    heights (:attr:`WalkPath.z <mjwalk.plan.walkpath.WalkPath.z>`) near the footprint: the
    median of the height's gradient along the path there, projected on the foot's heading. A
    stair's ground is level between its risers (median 0) and a gradient steeper than a ramp
    (:data:`~mjwalk.world.norms.MAX_RAMP_SLOPE`, plus 2 deg) is a stair's pitch line, not a
    slope to stand on: both give 0.

    Args:
        walk: the walk.
        print_: (3,) the footprint (x, y, yaw), metres and radians.

    Returns:
        the slope, radians, + uphill along the heading.
    """
    if walk.z is None:
        return 0.0
    xy, z = np.asarray(walk.xy, float), np.asarray(walk.z, float)
    d = np.diff(xy, axis=0)
    ds = np.hypot(d[:, 0], d[:, 1])
    mid = 0.5 * (xy[1:] + xy[:-1])
    near = (np.hypot(*(mid - print_[:2]).T) < SLOPE_REACH) & (ds > 1e-5)
    if not near.any():
        return 0.0
    heading = np.array([math.cos(print_[2]), math.sin(print_[2])])
    along = (d[near] @ heading) / ds[near]  # cos of the path's angle to the heading
    grad = float(np.median(np.diff(z)[near] / ds[near] * along))
    pitch = math.atan(grad)
    if abs(pitch) < FLAT_PITCH or abs(pitch) > MAX_RAMP_SLOPE + math.radians(2.0):
        return 0.0
    return pitch


def step_surfaces(walk: WalkPath) -> list[StepSurfaces]:
    """Per step of ``walk`` its surfaces' heights and slopes (the first step lifts its foot from
    the stance foot's surface: a standing start).

    Args:
        walk: a walk with steps.

    Returns:
        one :class:`StepSurfaces` per step.
    """
    out = []
    pitches = [
        (
            surface_pitch(walk, np.asarray(s.foot, float)),
            surface_pitch(walk, np.asarray(s.stance, float)),
        )
        for s in walk.steps
    ]
    for k, s in enumerate(walk.steps):
        prev = walk.steps[k - 1] if k else None
        out.append(
            StepSurfaces(
                lift=float(prev.stance_z if prev else s.stance_z),
                stance=float(s.stance_z),
                land=float(s.foot_z),
                lift_pitch=pitches[k - 1][1] if k else pitches[k][1],
                stance_pitch=pitches[k][1],
                land_pitch=pitches[k][0],
            )
        )
    return out


def _sole_points(ankle, pitch, toe, yaw, geom: LegGeometry) -> np.ndarray:
    """(m, 3, 3) the heel, ball and toe tip of the foot (world x, y, z, metres) for ankles
    ``ankle`` (m, 3), pitches, toe angles and headings (m,) (radians, pitch + toes up)."""
    ah, back, front = geom.ankle_height, geom.foot_back, geom.foot_front
    ball = geom.foot_front - 0.2 * (geom.foot_front + geom.foot_back)  # footpivot.ball_offset
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
    boundaries between the surfaces ``zr`` (r,) under the chord."""

    lo: np.ndarray
    hi: np.ndarray
    z: np.ndarray
    cut: np.ndarray
    zr: np.ndarray


def _step_edges(fr: StepFrames, surf: StepSurfaces, geom: LegGeometry) -> _Edges:
    """The edges of an edged step: between the surfaces of the lift, stance and landing
    footprints in their order along the chord, each from the toe of the foot behind to the
    heel of the foot ahead (their midpoint where those overlap)."""
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
    lo, hi, ze, cut = [], [], [], []
    for (x0, z0), (x1, z1) in itertools.pairwise(merged):
        a, b = x0 + geom.foot_front, x1 - geom.foot_back
        if a > b:
            a = b = 0.5 * (x0 + x1)
        lo.append(a)
        hi.append(b)
        ze.append(max(z0, z1))
        cut.append(0.5 * (a + b))
    return _Edges(
        np.array(lo), np.array(hi), np.array(ze), np.array(cut), np.array([z for _, z in merged])
    )


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
                w = np.clip(
                    (xe - xa[over]) / np.where(xb[over] != xa[over], xb[over] - xa[over], 1.0), 0, 1
                )
                zs = za[over] + w * (zb[over] - za[over])
                worst = max(worst, float(np.max(ze + clearance - zs)))
    return worst


def _profile(tau: np.ndarray, z_a: float, z_b: float, apex: float) -> np.ndarray:
    """The swing ankle's height over ``tau`` (0 at the last grounded sample, 1 at landing):
    up from ``z_a`` to ``apex``, held, down to ``z_b`` (smoothsteps); the rise and the fall
    take time in proportion to their heights (at least 15 % of the swing each)."""
    r1, r2 = apex - z_a, apex - z_b
    big = max(r1, r2, 1e-9)
    t1 = max(0.15, 0.45 * r1 / big)
    t2 = 1.0 - max(0.15, 0.45 * r2 / big)
    up = z_a + r1 * smoothstep(tau / t1)
    down = apex - r2 * smoothstep((tau - t2) / (1.0 - t2))
    return np.where(tau <= t1, up, np.where(tau >= t2, down, apex))


def edge_swing(ankle, pitch, toe, yaw, fr: StepFrames, surf: StepSurfaces, geom: LegGeometry,
               clearance: float = STAIR_TOE_CLEARANCE):  # fmt: skip
    """The swing foot of an edged step (a step or a stair) over its airborne samples: it rises
    to clear the highest edge by ``clearance``, travels forward only while its sole clears the
    first edge and is past the last before it lowers (the flat swing's path, re-timed, for the
    horizontal motion; its pitch, toes and heading kept); raised further where the sole would
    still come closer to an edge than ``clearance``.

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
        reached (metres; ``clearance`` or more where the design holds).
    """
    m = len(ankle)
    tau = np.arange(m) / max(m - 1, 1)
    edges = _step_edges(fr, surf, geom)
    seg = fr.land[:2] - fr.lift[:2]
    length = max(float(np.hypot(*seg)), 1e-9)
    e = seg / length
    u_f = np.maximum.accumulate(np.clip((ankle[:, :2] - fr.lift[:2]) @ e / length, 0, 1))
    u_f[-1] = max(u_f[-1], u_f[-2] + 1e-9) if m > 1 else u_f[-1]
    u_f = u_f + np.arange(m) * 1e-12  # strictly increasing for np.interp
    z_a, z_b = float(ankle[0, 2]), float(ankle[-1, 2])
    lift_sole = geom.ankle_height + 0.005
    extra, out, need = 0.0, ankle.copy(), 0.0
    for _ in range(3):
        first = edges.z[0] + clearance + lift_sole
        last = edges.z[-1] + clearance + lift_sole
        apex = max(float(edges.z.max()) + clearance + lift_sole, z_a, z_b) + extra
        z = _profile(tau, z_a, z_b, apex)
        t_a = float(tau[np.argmax(z >= first - 1e-9)]) if first > z_a else 0.0
        t_b = float(tau[m - 1 - np.argmax(z[::-1] >= last - 1e-9)]) if last > z_b else 1.0
        u = smoothstep((tau - t_a) / max(t_b - t_a, 1e-9))
        out = np.column_stack([np.interp(u, u_f, ankle[:, 0]), np.interp(u, u_f, ankle[:, 1]), z])
        _keep_behind_edges(out, z, (first, last), pitch, toe, edges, fr, geom)
        out[0], out[-1] = ankle[0], ankle[-1]
        need = _clearance_deficit(_sole_points(out[1:-1], pitch[1:-1], toe[1:-1], yaw[1:-1], geom),
                                  fr, edges, clearance)  # fmt: skip
        if need <= 1e-4:
            break
        extra += need + 0.005
    return out, clearance - need


def _keep_behind_edges(out, z, levels, pitch, toe, edges: _Edges, fr: StepFrames,
                       geom: LegGeometry) -> None:  # fmt: skip
    """Hold the swing foot's toe tip behind the first edge while the ankle is below
    ``levels[0]``, and its heel past the last edge once it is below ``levels[1]`` on the way
    down (the ankles ``out`` (m, 3) moved along the chord, in place): a foot flattening after
    lift-off turns about its toes instead of pushing them into the riser."""
    seg = fr.land[:2] - fr.lift[:2]
    e = seg / max(float(np.hypot(*seg)), 1e-9)
    ball = geom.foot_front - 0.2 * (geom.foot_front + geom.foot_back)
    ah = geom.ankle_height
    tip = ball * np.cos(pitch) + ah * np.sin(pitch) + (geom.foot_front - ball) * np.cos(pitch + toe)
    heel = -geom.foot_back * np.cos(pitch) + ah * np.sin(pitch)
    x = (out[:, :2] - fr.lift[:2]) @ e
    top = int(np.argmax(z))
    rising = (np.arange(len(z)) <= top) & (z < levels[0])
    falling = (np.arange(len(z)) > top) & (z < levels[1])
    x_new = np.where(rising, np.minimum(x, edges.lo[0] - tip), x)
    x_new = np.where(falling, np.maximum(x_new, edges.hi[-1] - heel), x_new)
    out[:, :2] += (x_new - x)[:, None] * e


@dataclass
class LevelTracks:
    """Per side ("l"/"r") over a walk's n samples: the surface height under the foot (``z``,
    metres), its slope along the foot (``pitch``, radians) and whether the foot is in the air
    (``air``); ``level`` (n,) the pelvis's surface height, metres."""

    z: dict[str, np.ndarray]
    pitch: dict[str, np.ndarray]
    air: dict[str, np.ndarray]
    level: np.ndarray


def level_tracks(
    frames: list[StepFrames], surfs: list[StepSurfaces], ground, n: int
) -> LevelTracks:
    """The surfaces under the feet and the pelvis over a walk, from its steps.

    Args:
        frames: the walk's steps as the leg synthesis sees them.
        surfs: their surfaces (:func:`step_surfaces`).
        ground: per side the flat synthesis's (n,) foot-on-the-ground flags.
        n: the number of samples.

    Returns:
        the tracks (a swing foot's ``z``/``pitch`` are its lift surface's until it lands).
    """
    z = {s: np.zeros(n) for s in "lr"}
    p = {s: np.zeros(n) for s in "lr"}
    air = {s: np.zeros(n, bool) for s in "lr"}
    level = np.zeros(n)
    f0, s0 = frames[0], surfs[0]
    head = slice(0, f0.start + 1)
    z[f0.side][head], p[f0.side][head] = s0.lift, s0.lift_pitch
    z[f0.other][head], p[f0.other][head] = s0.stance, s0.stance_pitch
    level[head] = s0.pelvis_level()[0]
    for fr, sf in zip(frames, surfs, strict=True):
        a, b = fr.start, fr.end
        ids = slice(a, b + 1)
        z[fr.other][ids], p[fr.other][ids] = sf.stance, sf.stance_pitch
        z[fr.side][ids], p[fr.side][ids] = sf.lift, sf.lift_pitch
        air[fr.side][a:b] = ~np.asarray(ground[fr.side][a:b], bool)
        air[fr.other][ids] = False
        z[fr.side][b], p[fr.side][b] = sf.land, sf.land_pitch
        l0, l1 = sf.pelvis_level()
        level[ids] = l0 + (l1 - l0) * smoothstep(np.linspace(0.0, 1.0, b - a + 1))
    fl, sl = frames[-1], surfs[-1]
    tail = slice(fl.end, n)
    z[fl.side][tail], p[fl.side][tail] = sl.land, sl.land_pitch
    z[fl.other][tail], p[fl.other][tail] = sl.stance, sl.stance_pitch
    level[tail] = sl.pelvis_level()[1]
    return LevelTracks(z, p, air, level)


def _tilt(ankle: np.ndarray, yaw: np.ndarray, slope: np.ndarray) -> np.ndarray:
    """Ankles (m, 3) turned by ``slope`` (m,, radians, + toes up) about the point under them on
    the floor, in the vertical plane of the headings ``yaw`` (m,)."""
    f = np.stack([np.cos(yaw), np.sin(yaw)], -1)
    h = ankle[:, 2]
    out = ankle.copy()
    out[:, :2] -= (h * np.sin(slope))[:, None] * f
    out[:, 2] = h * np.cos(slope)
    return out


def lift_to_levels(walk: WalkPath, frames: list[StepFrames], feet: FootTracks, root: np.ndarray,
                   yaw: np.ndarray, geom: LegGeometry):  # fmt: skip
    """The flat leg synthesis of a walk that leaves the floor, put on its surfaces: feet on
    their footprints' heights (pitched to a ramp), the swing over step edges
    (:func:`edge_swing`), the pelvis on the level (:meth:`StepSurfaces.pelvis_level`), lowered
    where a grounded leg cannot reach; the leg IK again.

    Args:
        walk: the walk (its steps' ``foot_z``/``stance_z`` and ground heights ``z``).
        frames: its steps as the flat synthesis saw them.
        feet: the flat synthesis's foot tracks (``ankle`` and ``pitch`` are updated in place).
        root: (n, 3) the flat synthesis's pelvis positions, metres.
        yaw: (n,) the pelvis yaw, radians from +x CCW.
        geom: the leg geometry.

    Returns:
        the pelvis positions (n, 3, metres), the joint angles (name -> (n,) radians, clipped
        to their ranges) and the least clearance over a step edge (metres; inf without edges).
    """
    n = len(root)
    surfs = step_surfaces(walk)
    tr = level_tracks(frames, surfs, feet.ground, n)
    flat_ankle = {s: feet.ankle[s].copy() for s in "lr"}
    for s in "lr":
        on = ~tr.air[s]
        a = _tilt(flat_ankle[s][on], feet.fyaw[s][on], tr.pitch[s][on])
        a[:, 2] += tr.z[s][on]
        feet.ankle[s][on] = a
        feet.pitch[s][on] = feet.pitch[s][on] + tr.pitch[s][on]
    least = math.inf
    for fr, sf in zip(frames, surfs, strict=True):
        s = fr.side
        j = np.flatnonzero(tr.air[s][fr.start : fr.end]) + fr.start
        if not len(j):
            continue
        k = np.r_[j[0] - 1, j, fr.end]
        if sf.edged:
            # the foot held level through the swing (toes and sole straighten after lift-off,
            # the landing pitch taken at the end), as stair gait does: a foot pitched toes
            # down would need the whole foot lifted by its toes' drop over every edge
            tau = np.arange(len(k)) / (len(k) - 1)
            ease = 1.0 - smoothstep(tau / 0.25)
            land = smoothstep((tau - 0.8) / 0.2)
            feet.pitch[s][k] = feet.pitch[s][k[0]] * ease + feet.pitch[s][k[-1]] * land
            feet.toe[s][k] = feet.toe[s][k[0]] * ease + feet.toe[s][k[-1]] * land
            out, clear = edge_swing(feet.ankle[s][k], feet.pitch[s][k], feet.toe[s][k],
                                    feet.fyaw[s][k], fr, sf, geom)  # fmt: skip
            feet.ankle[s][j] = out[1:-1]
            least = min(least, clear)
            continue
        seg = fr.land[:2] - fr.lift[:2]
        u = np.clip((flat_ankle[s][j, :2] - fr.lift[:2]) @ seg / max(float(seg @ seg), 1e-12), 0, 1)
        feet.ankle[s][j, 2] += sf.lift + (sf.land - sf.lift) * u
        feet.pitch[s][j] += sf.lift_pitch + (sf.land_pitch - sf.lift_pitch) * u
    new_root = root.copy()
    new_root[:, 2] += tr.level
    win = max(3, round(0.05 * n / max(float(walk.t[-1] - walk.t[0]), 1e-9)))
    reach_sq = {s: np.full(n, geom.span(KNEE_MIN) ** 2) for s in "lr"}
    grounded = {s: ~tr.air[s] for s in "lr"}
    for _ in range(4):
        deficit = reach_deficit(new_root, yaw, feet.ankle, grounded, reach_sq, geom)
        if deficit.max() <= 1e-3:
            break
        new_root[:, 2] -= spread(np.maximum(deficit, 0.0) + 2e-3, win)
    angles: dict[str, np.ndarray] = {}
    for s in "lr":
        raw = leg_ik_world(feet.ankle[s], feet.fyaw[s], feet.pitch[s], new_root, yaw, s, geom)
        angles.update(
            {k: np.clip(v, *np.deg2rad(ROM_DEG[generic_joint(k)])) for k, v in raw.items()}
        )
        angles[f"toe_{s}"] = np.clip(feet.toe[s], *np.deg2rad(ROM_DEG["toe"]))
    return new_root, angles, least
