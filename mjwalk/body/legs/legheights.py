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
  the nosings), on a step down where its riser is (the walk's ``meta["edges"]``). Steps whose
  surfaces are a ramp or level keep the flat swing, on its ends' heights or a ramp's crest.
* **The swing foot as its ankle holds it** (steps up): where the leg IK would ask the swing
  ankle for more dorsiflexion than its range (the shank leaning back behind a flexed knee),
  the foot hangs toes down by the excess and the swing is planned again with that pitch
  (:func:`_swing_pitch`); a step up, or down by less than :data:`FOREFOOT_DROP`, lands flat
  (:func:`flat_landing`), not on the heel.
* **The pelvis follows the level.** Its height is the flat synthesis's plus the lower of the
  two feet's surfaces in double support (on a ramp their mean), changing over the single
  support of each step (smoothstep): up a stair the pelvis rises in weight acceptance and
  pull-up (by :data:`ASCENT_PULL_UP_END` of the step, a riser per step), down a stair it
  lowers while the stance leg yields. Where a grounded leg then cannot reach its foot, a
  foot on a ramp already rising on its ball rises further
  (:func:`~mjwalk.body.legs.rampreach.trailing_reach`), elsewhere the pelvis lowers (smoothly;
  with the flat synthesis's, over :data:`~mjwalk.body.legs.stance.REACH_DROP_MAX`: an error).
* **Stepping down** (a stair descended, a drop of :data:`FOREFOOT_DROP` or more) the foot
  lands on its forefoot (:data:`DESCENT_CONTACT_PITCH`) and lowers its heel in weight
  acceptance (:func:`forefoot_landing`); the pelvis holds its height through forward
  continuance and lowers in late single support (:data:`DESCENT_LOWER_FROM`).
* **Joint angles** by the same leg IK as the flat synthesis, clipped to the joint ranges;
  where a grounded ankle would dorsiflex past its range, the heel rises about the ball
  (:func:`heel_rise`) instead of the ball sinking into the surface.

The knee and hip flexion on a stair follows from the geometry, not prescribed; the published
peaks (:data:`KNEE_PEAK_UP`, ...) hold it in ``tests/body/test_legheights.py`` and
``benchmarks/bench_levels.py``. World frame, metres, radians.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

import mjwalk.body.legs.rampreach as ramps
from mjwalk.body.humanoid import ROM_DEG, LegGeometry
from mjwalk.body.legs.crest import crest_ground
from mjwalk.body.legs.curves import smoothstep
from mjwalk.body.legs.edgeswing import (
    FLAT_PITCH,
    LEVEL_STEP,
    SOLE_MARGIN,
    StepSurfaces,
    edge_swing,
    riser_lines,
    sole_rise,
    swing_clearance,
)
from mjwalk.body.legs.footpivot import ball_offset
from mjwalk.body.legs.ik import KNEE_MIN, generic_joint, leg_ik_world
from mjwalk.body.legs.rampreach import roll_foot, trailing_reach
from mjwalk.body.legs.rampstance import uphill_stance_raise
from mjwalk.body.legs.stance import lower_to_reach
from mjwalk.body.legs.steps import FootTracks, StepFrames
from mjwalk.plan.walkpath import WalkPath
from mjwalk.world.norms import DESCENT_LOW_CLEARANCE, MAX_RAMP_SLOPE

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
#: beyond the abstracts). One descent figure was verified (abstract only, SafetyLit record
#: citjournalarticle_703263_26; authors and journal not read here): 101 adults aged 18-35
#: walking down an unconstrained 13-step staircase outside a laboratory (wearable sensors)
#: flexed the knee up to 85 deg and the hip 30 deg (joint ranges; no SD of the peak and no
#: riser or tread in the abstract), inside the descent range below but near its low end.
KNEE_PEAK_UP = (83.0, 105.0)
KNEE_PEAK_DOWN = (80.0, 100.0)
#: Peak hip flexion, degrees: greater up than down by 28.1 deg (SD 4.1) (Protopapadaki et al.
#: 2007, abstract verified here); 66.3 deg lead-hip flexion up a 20.3 cm step (abstract above,
#: verified); ranges as those studies report them (NOT verified beyond the abstracts).
HIP_PEAK_UP = (55.0, 75.0)
HIP_PEAK_DOWN = (20.0, 45.0)

#: Foot pitch at initial contact on a step down onto a lower tread, radians (toes down): stair
#: descent lands on the forefoot with the ankle plantarflexed and lowers the heel in weight
#: acceptance (McFadyen & Winter, J Biomech 21:733-744 (1988); Riener et al. 2002; forefoot and
#: rearfoot strikes in stair descent compared by Jeon et al., J Mech Med Biol 19:1940031
#: (2019), abstract verified here). About 20 deg plantarflexion at contact is read from the
#: ankle curves of those studies as usually reproduced (NOT verified here): -20 deg.
DESCENT_CONTACT_PITCH = math.radians(-20.0)
#: A swing foot lands forefoot first where it lands this much (m) or more below where it lifted
#: off: single steps down are landed rearfoot first at 5 and 15 cm and forefoot first at 25 and
#: 35 cm (Frontiers Bioeng Biotechnol 12:1431988 (2024), "Evaluating plantar biomechanics
#: while descending a single step with different heights", abstract verified here); a stair's
#: swing foot drops two risers (0.34 m on a 0.17 m stair). 0.2 m: between 15 and 25 cm.
FOREFOOT_DROP = 0.20
#: Share of a step down's time (double support at its start, then the stance leg's single
#: support) before the pelvis lowers onto the next tread. Stair descent's stance divides into
#: weight acceptance (to ~14 % of the cycle), forward continuance (the body moves forward over
#: the stance foot, to ~34 %) and controlled lowering (the stance knee flexes and lowers the
#: body) (McFadyen & Winter 1988; the phase names are verified in secondary sources, the
#: percentages as usually quoted are NOT verified here). A step is half a cycle from the stance
#: foot's landing, so lowering starts at 34 / 50 = 0.68 of the step and ends at the next
#: landing (late single support).
DESCENT_LOWER_FROM = 0.68
#: Share of a step up's time (from the stance foot's landing) by which the pelvis has risen
#: onto the stance foot's tread. Stair ascent's stance divides into weight acceptance, pull-up
#: (the stance leg extends and lifts the body a riser) and forward continuance (McFadyen &
#: Winter 1988; the phase names are verified in secondary sources, the boundaries quoted
#: there, pull-up ending at about 32 % of the cycle, are NOT verified here): a step is half a
#: cycle from the stance foot's landing, so the rise ends at 32 / 50 = 0.64 of the step, and
#: the swing foot passes the nosing with the stance leg extended beneath the pelvis.
ASCENT_PULL_UP_END = 0.64


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


def _on_ramp(walk: WalkPath) -> list[bool | dict]:
    """Per step of ``walk`` whether its footfall may stand on a ramp: from the level planner's
    route (``meta["levels"]["route"]``: its parts' kinds and step counts, in order), only the
    steps of a ramp crossing (as its recorded plane, if any); without that route, every step
    (:func:`surface_pitch` judges). The walk's height eases over a stair's first and last
    steps and would read as a slope there (a foot on a level landing pitched 7 deg toes down)."""
    route = (walk.meta or {}).get("levels", {}).get("route") if walk.meta else None
    n = len(walk.steps)
    if not route or sum(int(part.get("steps", 0)) for part in route) != n:
        return [True] * n
    out: list[bool | dict] = []
    for part in route:
        ramp = part.get("plane", True) if part.get("kind") == "ramp" else False
        out += [ramp] * int(part.get("steps", 0))
    return out


def _pitch(walk: WalkPath, ramp: bool | dict, print_) -> float:
    """A footprint's surface pitch, radians: on a ramp's recorded plane, else estimated."""
    if isinstance(ramp, dict):
        return ramps.plane_pitch(ramp, np.asarray(print_, float))
    return surface_pitch(walk, np.asarray(print_, float)) if ramp else 0.0


def step_surfaces(walk: WalkPath, geom: LegGeometry | None = None,
                  land_p: list[float] | None = None) -> list[StepSurfaces]:  # fmt: skip
    """Per step of ``walk`` its surfaces' heights and slopes (the first step lifts its foot from
    the stance foot's surface: a standing start).

    Args:
        walk: a walk with steps.
        geom: the feet's lengths (a level foot over a ramp's corner; None: default stature's).
        land_p: per step its landing pitch, radians (a heel strike beside a ramp; None: flat).

    Returns:
        one :class:`StepSurfaces` per step.
    """
    out, lines = [], riser_lines(walk.meta)
    on_ramp = _on_ramp(walk)
    pitches = [
        (_pitch(walk, on_ramp[k], s.foot), _pitch(walk, on_ramp[max(k - 1, 0)], s.stance))
        for k, s in enumerate(walk.steps)
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
                risers=lines,
            )
        )
    return ramps.level_feet_on_ramps(walk, out, geom, land_p)


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
        u = np.linspace(0.0, 1.0, b - a + 1)
        if sf.edged and l1 < l0 - LEVEL_STEP:  # down: forward continuance, then lowering
            u = (u - DESCENT_LOWER_FROM) / (1.0 - DESCENT_LOWER_FROM)
        elif sf.edged and l1 > l0 + LEVEL_STEP:  # up: weight acceptance and pull-up
            u = u / ASCENT_PULL_UP_END
        level[ids] = l0 + (l1 - l0) * smoothstep(u)
    fl, sl = frames[-1], surfs[-1]
    tail = slice(fl.end, n)
    z[fl.side][tail], p[fl.side][tail] = sl.land, sl.land_pitch
    z[fl.other][tail], p[fl.other][tail] = sl.stance, sl.stance_pitch
    level[tail] = sl.pelvis_level()[1]
    return LevelTracks(z, p, air, level)


def forefoot_landing(feet: FootTracks, fr: StepFrames, air: np.ndarray, geom: LegGeometry) -> None:
    """A step down landed forefoot first: the landing foot touches its tread with the ball,
    pitched :data:`DESCENT_CONTACT_PITCH` (toes down, the toes flat on the tread), and turns
    about the ball onto its heel over the double support after landing (weight acceptance);
    ``feet`` updated in place from the landing sample on.

    Args:
        feet: the foot tracks, their grounded samples already on their surfaces.
        fr: the step (its swing side lands at ``fr.end``).
        air: (n,) whether the landing foot is in the air; the other foot leaves the ground
            at the end of the double support.
        geom: the foot's lengths.
    """
    s, b = fr.side, fr.end
    other_air = np.flatnonzero(air[b:])
    w = b + (int(other_air[0]) if len(other_air) else max(len(air) - 1 - b, 0))
    if w <= b:
        return
    idx = np.arange(b, w + 1)
    p = DESCENT_CONTACT_PITCH * (1.0 - smoothstep((idx - b) / (w - b)))
    flat = feet.ankle[s][w].copy()
    ball = ball_offset(geom)
    ah = geom.ankle_height
    yaw = feet.fyaw[s][idx]
    f = np.stack([np.cos(yaw), np.sin(yaw)], -1)
    fw = ball - ball * np.cos(p) - ah * np.sin(p)  # the ankle's offset from its flat place
    feet.ankle[s][idx, :2] = flat[:2] + fw[:, None] * f
    feet.ankle[s][idx, 2] = flat[2] - ah - ball * np.sin(p) + ah * np.cos(p)
    feet.pitch[s][idx] = p
    feet.toe[s][idx] = -p


def heel_rise(feet: FootTracks, s: str, dorsi: np.ndarray, grounded: np.ndarray,
              geom: LegGeometry, surface: np.ndarray | None = None) -> bool:  # fmt: skip
    """Where a grounded foot's ankle would dorsiflex past its range (the stance leg flexed
    over a foot on a stair or a ramp), the heel rises instead: the foot turns toes down about
    its ball by the excess (the toes kept on the surface), so that clipping the ankle does not
    push the ball below the surface. ``feet`` updated in place.

    Args:
        feet: the foot tracks.
        s: the side ("l"/"r").
        dorsi: (n,) the IK's ankle flexion, radians (+ dorsiflexion), before clipping.
        grounded: (n,) whether the foot is on its surface.
        geom: the foot's lengths.
        surface: (n,) the slope of the surface under the foot, radians (+ uphill), or None:
            where the foot is toes up from it (on its heel after heel strike) it turns about
            its heel instead, its toes lowering sooner (up a ramp the ball about which it
            turned was in the air and the heel rose 7-9 cm off the ramp) until its sole is on
            it, then about its ball (further, its toes went 1.2 cm into the platform's ramp).

    Returns:
        whether any sample changed.
    """
    excess = np.where(grounded, dorsi - math.radians(ROM_DEG["ankle_flex"][1]), 0.0)
    idx = np.flatnonzero(excess > 1e-4)
    if not len(idx):
        return False
    # on its heel (toes up from its surface) its toes lower only onto it, the rest on its ball
    up = np.zeros(len(idx)) if surface is None else feet.pitch[s][idx] - surface[idx]
    on_heel = np.where(up > 1e-4, np.minimum(excess[idx], up), 0.0)
    roll_foot(feet, s, idx, on_heel, np.full(len(idx), -geom.foot_back), geom)
    roll_foot(feet, s, idx, excess[idx] - on_heel, np.full(len(idx), ball_offset(geom)), geom)
    feet.toe[s][idx] += excess[idx] - on_heel
    return True


def flat_landing(feet: FootTracks, fr: StepFrames, air: np.ndarray) -> None:
    """A step up, or down by less than :data:`FOREFOOT_DROP`, onto a surface a riser from the
    stance foot's, landed flat: the whole sole touches its tread where and as it stands once flat
    (a heel strike with the toes up would leave the foot pitched over the riser edge up a stair,
    and down a step tip the foot's back into the riser: measured on the first step off a stair's
    top landing and off the platform's step); ``feet`` updated in place from the landing sample
    until the foot is flat in the flat synthesis, or the other foot lifts off. Stair ascent is
    landed on the forefoot or the whole foot (McFadyen & Winter, J Biomech 21:733-744 (1988);
    Riener et al., Gait Posture 15:32-44 (2002): the ankle dorsiflexed at initial contact; NOT
    verified here beyond the abstracts); single steps down of 5 and 15 cm rearfoot first (the
    study at :data:`FOREFOOT_DROP`), for which the whole sole stands in. A step onto the stance
    foot's own level (off a flight's last riser, either way) lands on its heel as on the level:
    landed flat, 4 cm ahead and 2 cm below the heel strike, it took the pelvis 3.5 cm lowered
    (generated halls 201 and 510, ``benchmarks/bench_unseen.py``).

    Args:
        feet: the foot tracks, their grounded samples already on their surfaces.
        fr: the step (its swing side lands at ``fr.end``).
        air: (n,) whether the other foot is in the air.
    """
    s, b = fr.side, fr.end
    flat = np.flatnonzero(np.abs(feet.pitch[s][b:]) < 1e-4)
    other_air = np.flatnonzero(air[b:])
    ends = [int(v[0]) for v in (flat, other_air) if len(v)]
    w = b + (min(ends) if ends else 0)
    if w <= b:
        return
    for track in (feet.ankle[s], feet.pitch[s], feet.toe[s]):
        track[b:w] = track[w]


def _place_swings(frames, surfs, tr: LevelTracks, feet: FootTracks, flat_ankle,
                  geom: LegGeometry) -> list:  # fmt: skip
    """The swing feet on their surfaces (in place): a swing between level or ramp surfaces is
    the flat swing carried on its ends' heights; a step down by :data:`FOREFOOT_DROP` or more
    is landed on the forefoot, other steps up or down flat; the pitch of a swing over step
    edges starts level (down a stair: toes down throughout). Returns the edged swings to
    plan, as (step, surfaces, samples from the last grounded one to the landing, the flat
    swing's ankles there (k, 3))."""
    plans = []
    for fr, sf in zip(frames, surfs, strict=True):
        s = fr.side
        j = np.flatnonzero(tr.air[s][fr.start : fr.end]) + fr.start
        if not len(j):
            continue
        k = np.r_[j[0] - 1, j, fr.end]
        if sf.edged:
            if sf.lift - sf.land >= FOREFOOT_DROP:
                forefoot_landing(feet, fr, tr.air[fr.other], geom)
            elif abs(sf.land - sf.stance) > LEVEL_STEP:  # up, or down < FOREFOOT_DROP, a riser
                flat_landing(feet, fr, tr.air[fr.other])  # from the stance (else: heel strike)
            # the foot levelled after lift-off (toes and sole straighten), the landing pitch
            # taken at the end; :func:`_swing_pitch` then turns it toes down where the ankle
            # cannot dorsiflex that far. Down a stair the foot is not levelled: it stays toes
            # down from toe-off to its forefoot landing (the ankle plantarflexed in swing:
            # McFadyen & Winter 1988; Riener et al. 2002)
            tau = np.arange(len(k)) / (len(k) - 1)
            ease = 1.0 - smoothstep(tau / 0.25)
            land = smoothstep((tau - 0.8) / 0.2)
            if sf.descends:
                ease, land = 1.0 - smoothstep(tau), smoothstep(tau)
            feet.pitch[s][k] = feet.pitch[s][k[0]] * ease + feet.pitch[s][k[-1]] * land
            feet.toe[s][k] = feet.toe[s][k[0]] * ease + feet.toe[s][k[-1]] * land
            plans.append((fr, sf, k, feet.ankle[s][k].copy()))
            continue
        seg = fr.land[:2] - fr.lift[:2]
        u = np.clip((flat_ankle[s][j, :2] - fr.lift[:2]) @ seg / max(float(seg @ seg), 1e-12), 0, 1)
        base = sf.lift + (sf.land - sf.lift) * u
        added = sf.lift_pitch + (sf.land_pitch - sf.lift_pitch) * u
        crest = crest_ground(flat_ankle[s][j], feet.fyaw[s][j], fr, sf, geom, added,
                             (feet.pitch[s][j], feet.toe[s][j]))  # fmt: skip
        feet.ankle[s][j, 2] += np.maximum(base, crest)
        feet.pitch[s][j] += added
    return plans


def _plan_edged(plans: list, feet: FootTracks, geom: LegGeometry) -> float:
    """The edged swings of ``plans`` (:func:`_place_swings`) over their edges with the feet's
    current pitch (:func:`edge_swing`), in place; returns the least clearance, metres."""
    least = math.inf
    for fr, sf, k, ankle in plans:
        s = fr.side
        out, clear = edge_swing(ankle, feet.pitch[s][k], feet.toe[s][k], feet.fyaw[s][k], fr, sf,
                                geom)  # fmt: skip
        feet.ankle[s][k[1:-1]] = out[1:-1]
        least = min(least, clear)
    return least


#: Passes of :func:`_swing_pitch` (plan the swing, solve the leg, pitch the foot to what the
#: ankle reaches, plan again); the pitch settles within a few tenths of a degree by the third.
SWING_PASSES = 8


def _swing_pitch(plans: list, feet: FootTracks, root: np.ndarray, yaw: np.ndarray,
                 geom: LegGeometry) -> float:  # fmt: skip
    """The edged swings planned with the foot pitch the ankle can hold: where the leg IK asks
    the swing ankle for more dorsiflexion than its range (the shank leaning back behind a
    flexed knee while the foot would be level), the foot hangs toes down by the excess, and the
    swing is planned again so that the toes and the heel of that pitched foot clear the edges
    (the swing rises where they would not). In place; returns the least clearance, metres."""
    up = [p for p in plans if p[1].land > p[1].lift + LEVEL_STEP]
    down = [p for p in plans if p[1].descends]
    _plan_edged(down, feet, geom)  # their clearance is :func:`_soles_clear`'s
    rest = [p for p in plans if p[1].land <= p[1].lift + LEVEL_STEP and not p[1].descends]
    least = min(_plan_edged(rest, feet, geom), _plan_edged(up, feet, geom))
    top = math.radians(ROM_DEG["ankle_flex"][1])
    for _ in range(SWING_PASSES if up else 0):
        moved = False
        for s in "lr":
            mine = [k[1:-1] for fr, _, k, _ in up if fr.side == s]
            if not mine:
                continue
            j = np.concatenate(mine)
            raw = leg_ik_world(feet.ankle[s][j], feet.fyaw[s][j], feet.pitch[s][j], root[j],
                               yaw[j], s, geom)  # fmt: skip
            excess = raw[f"ankle_{s}_flex"] - top
            if excess.max() > 1e-3:
                feet.pitch[s][j] -= np.maximum(excess, 0.0)
                moved = True
        if not moved:
            break
        least = _plan_edged(up, feet, geom)
    return least


#: Passes of :func:`_soles_clear` (lift the soles over their surfaces, pitch the foot to what
#: the ankle reaches at the new height).
SOLE_PASSES = 3


def _ankle_pitch(plans: list, feet: FootTracks, root: np.ndarray, yaw: np.ndarray,
                 geom: LegGeometry) -> None:  # fmt: skip
    """The airborne samples of the swings ``plans`` pitched toes down by whatever dorsiflexion
    the leg IK asks of the ankle beyond its range (in place)."""
    top = math.radians(ROM_DEG["ankle_flex"][1])
    for s in "lr":
        mine = [k[1:-1] for fr, _, k, _ in plans if fr.side == s]
        if not mine:
            continue
        j = np.concatenate(mine)
        raw = leg_ik_world(feet.ankle[s][j], feet.fyaw[s][j], feet.pitch[s][j], root[j], yaw[j],
                           s, geom)  # fmt: skip
        feet.pitch[s][j] -= np.maximum(raw[f"ankle_{s}_flex"] - top, 0.0)


def _soles_clear(plans: list, feet: FootTracks, root: np.ndarray, yaw: np.ndarray,
                 geom: LegGeometry) -> float:  # fmt: skip
    """The swing feet of the edged swings ``plans`` kept above their surfaces at the pitch the
    ankle holds: where a sole point (heel, ball, toe tip) of the foot so pitched would lie
    below the tread under it (the toes of a foot hanging toes down as it lowers onto a tread),
    the ankle rises by the depth (:func:`~mjwalk.body.legs.edgeswing.sole_rise`; down a stair
    by the depth plus :data:`~mjwalk.world.norms.DESCENT_LOW_CLEARANCE`, the clearance below
    which descent studies count a clearance as low), and the foot is pitched again to what
    the ankle reaches there; in place. Down a stair the swing is planned once, 3 cm over the
    nosings for the foot's pitch then (:func:`edge_swing`), and only this keeps the foot,
    pitched further toes down, off the treads: planning it again at each new pitch (as up a
    stair) kept 3 cm but gave knee peaks of 101-102 deg against :data:`KNEE_PEAK_DOWN`.
    Returns the least clearance over the descents' edges, metres (inf without descents)."""
    for _ in range(SOLE_PASSES):
        _ankle_pitch(plans, feet, root, yaw, geom)
        moved = False
        for fr, sf, k, _ in plans:
            s = fr.side
            margin = DESCENT_LOW_CLEARANCE if sf.descends else SOLE_MARGIN
            rise = sole_rise(feet.ankle[s][k], feet.pitch[s][k], feet.toe[s][k], feet.fyaw[s][k],
                             fr, sf, geom, margin)  # fmt: skip
            feet.ankle[s][k, 2] += rise
            moved = moved or bool(rise.max() > 1e-4)
        if not moved:
            break
    least = math.inf
    for fr, sf, k, _ in plans:
        if sf.descends:
            s = fr.side
            gap = swing_clearance(feet.ankle[s][k], feet.pitch[s][k], feet.toe[s][k],
                                  feet.fyaw[s][k], fr, sf, geom)  # fmt: skip
            least = min(least, gap)
    return least


def lift_to_levels(walk: WalkPath, frames: list[StepFrames], feet: FootTracks, root: np.ndarray,
                   yaw: np.ndarray, geom: LegGeometry, lowered: np.ndarray):  # fmt: skip
    """The flat leg synthesis of a walk that leaves the floor, put on its surfaces: feet on
    their footprints' heights (pitched to a ramp), the swing over step edges with the foot
    pitch its ankle can hold (:func:`edge_swing`, :func:`_swing_pitch`), the pelvis on the
    level (:meth:`StepSurfaces.pelvis_level`), lowered where a grounded leg cannot reach; the
    leg IK again.

    Args:
        walk: the walk (its steps' ``foot_z``/``stance_z`` and ground heights ``z``).
        frames: its steps as the flat synthesis saw them.
        feet: the flat synthesis's foot tracks (``ankle`` and ``pitch`` are updated in place).
        root: (n, 3) the flat synthesis's pelvis positions, metres.
        yaw: (n,) the pelvis yaw, radians from +x CCW.
        geom: the leg geometry.
        lowered: (n,) the flat synthesis's lowering of ``root``, metres (bounded with this one's).

    Returns:
        the pelvis positions (n, 3, metres), the joint angles (name -> (n,) radians, clipped
        to their ranges) and the least clearance over a step edge (metres; inf without edges).
    """
    n = len(root)
    surfs = step_surfaces(walk, geom, [fr.land_p for fr in frames])
    tr = level_tracks(frames, surfs, feet.ground, n)
    flat_ankle = {s: feet.ankle[s].copy() for s in "lr"}
    flat = (flat_ankle, {s: feet.pitch[s].copy() for s in "lr"}, root)
    prints = ramps.print_tracks(frames, n)
    for s in "lr":
        on = ~tr.air[s]
        a = ramps.tilt(flat_ankle[s][on], feet.fyaw[s][on], tr.pitch[s][on], prints[s][on])
        a[:, 2] += tr.z[s][on]
        feet.ankle[s][on] = a
        feet.pitch[s][on] = feet.pitch[s][on] + tr.pitch[s][on]
    plans = _place_swings(frames, surfs, tr, feet, flat_ankle, geom)
    ramps.swing_over_ramps(walk, frames, tr.air, feet, flat_ankle, geom)
    new_root = root.copy()
    new_root[:, 2] += tr.level
    win = max(3, round(0.05 * n / max(float(walk.t[-1] - walk.t[0]), 1e-9)))
    new_root[:, 2] += uphill_stance_raise(feet, flat, new_root, yaw, tr.air, tr.pitch, geom, win)
    reach_sq = {s: np.full(n, geom.span(KNEE_MIN) ** 2) for s in "lr"}
    grounded = {s: ~tr.air[s] for s in "lr"}
    trailing_reach(feet, new_root, yaw, grounded, tr.pitch, reach_sq, geom)
    lower_to_reach(new_root, yaw, feet.ankle, grounded, reach_sq, geom, win, lowered)  # or raises
    least = _swing_pitch(plans, feet, new_root, yaw, geom) if plans else math.inf
    least = min(least, _soles_clear(plans, feet, new_root, yaw, geom)) if plans else least
    ramps.swings_clear_ramps(walk, plans, frames, tr.air, feet, new_root, yaw, geom)
    raw = {s: _heel_rises(feet, s, new_root, yaw, grounded[s], tr.pitch[s], geom) for s in "lr"}
    angles: dict[str, np.ndarray] = {}
    for s in "lr":
        angles.update(
            {k: np.clip(v, *np.deg2rad(ROM_DEG[generic_joint(k)])) for k, v in raw[s].items()}
        )
        angles[f"toe_{s}"] = np.clip(feet.toe[s], *np.deg2rad(ROM_DEG["toe"]))
    return new_root, angles, least


#: Passes of :func:`heel_rise` and the leg IK: each turn about the ball moves the ankle and
#: leaves part of the excess; after 3 passes up to 0.4 deg was clipped (the toes 1 mm into a
#: ramp's top edge, the multi-level platform cycle's run 15), after 10 at most 0.03 deg.
HEEL_RISE_PASSES = 10


def _heel_rises(feet: FootTracks, s: str, root: np.ndarray, yaw: np.ndarray,
                grounded: np.ndarray, surface: np.ndarray, geom: LegGeometry) -> dict:  # fmt: skip
    """The ``s`` leg's unclipped IK angles after :func:`heel_rise` (up to :data:`HEEL_RISE_PASSES`;
    ``feet`` updated in place), for the pelvis ``root`` (n, 3, metres) and ``yaw`` (n,, rad)."""
    raw = leg_ik_world(feet.ankle[s], feet.fyaw[s], feet.pitch[s], root, yaw, s, geom)
    for _ in range(HEEL_RISE_PASSES):
        if not heel_rise(feet, s, raw[f"ankle_{s}_flex"], grounded, geom, surface):
            break
        raw = leg_ik_world(feet.ankle[s], feet.fyaw[s], feet.pitch[s], root, yaw, s, geom)
    return raw
