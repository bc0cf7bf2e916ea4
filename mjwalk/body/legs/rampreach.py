"""The feet on ramps: a grounded foot turned about a point of its sole, the trailing foot rising
on its ball to reach, the ground under a swing foot over a ramp's top edge (issue 47,
deliverable 4: the body on ramps).

On a ramp the two feet of a double support stand at different heights: walking up, the
trailing foot a half step's rise below the ground under the pelvis, the leading foot as much
above it (:meth:`~mjwalk.body.legs.edgeswing.StepSurfaces.pelvis_level` keeps the pelvis at
the mean of the two). Where the trailing leg then cannot reach its foot, the foot, already
rising on its ball in pre-swing, rises further (:func:`trailing_reach`) rather than the pelvis
lowering: lowering it folds the leading leg, nearly straight at heel strike, by 30 deg or more
(knee at heel strike on a 5.5 deg ramp, :func:`~mjwalk.plan.synthetic.synthetic_ramp_walk`:
34 deg with the pelvis lowered, 26 deg without; 2 deg on level ground). Uphill walking adds
plantarflexion at push-off (Lay et al., "The effects of sloped surfaces on locomotion: a
kinematic and kinetic analysis", J Biomech 39:1621-1628 (2006); NOT verified here beyond the
title). A swing between a ramp and a level is carried on the ground under its foot
(:func:`~mjwalk.body.legs.crest.crest_ground`), not below a ramp's top edge. World frame,
metres, radians; a pitch is + toes up.
"""

from __future__ import annotations

import functools
import math
from dataclasses import replace

import numpy as np

from mjwalk.anthropometry import leg_geometry
from mjwalk.body.humanoid import ROM_DEG, LegGeometry
from mjwalk.body.legs.curves import spread
from mjwalk.body.legs.edgeswing import StepSurfaces
from mjwalk.body.legs.footpivot import ball_offset
from mjwalk.body.legs.ik import leg_ik_world
from mjwalk.body.legs.lowtreads import low_treads
from mjwalk.body.legs.stance import reach_deficit
from mjwalk.body.legs.steps import HEEL_RISE_MAX, FootTracks, StepFrames
from mjwalk.plan.rampside import LOW_KEY, SOLE_GRID, head_heights, over_ramp, surface_plane
from mjwalk.plan.rampside import META_KEY as BESIDE_KEY

#: Passes of :func:`trailing_reach` (raise the heel by the deficit over the ball's lever,
#: measure again); the deficit falls below a millimetre by the third on a 5.5 deg ramp.
REACH_PASSES = 4


def plane_pitch(plane: dict, print_: np.ndarray) -> float:
    """The slope along a footprint's heading of the ramp a route crosses, from the ramp's plane
    as the level planner records it (``meta["levels"]["route"]`` entries' ``plane``:
    :func:`mjwalk.plan.levelstitch.level_meta`), for a footprint whose point lies on the ramp's
    surface (between its foot and its head along its axis and, its width known, between its
    sides: :func:`plane_heights` of :func:`~mjwalk.plan.rampside.surface_plane`); 0 for one on
    a level beyond either end or beside it (generated hall 510: a ramp crossing's turn on the
    floor 1.3 m beside the ramp's foot stood pitched 3.4 deg toes down, 1.2 cm into the floor).

    Args:
        plane: ``slope`` (radians), ``uphill`` (heading up the ramp, radians), ``foot`` (world
            xy of the middle of its foot, metres) and ``run`` (horizontal length, metres).
        print_: (3,) the footprint (x, y, yaw), metres and radians.

    Returns:
        the slope, radians, + uphill along the footprint's heading.
    """
    up = float(plane["uphill"])
    if plane_heights(surface_plane(plane), np.asarray(print_[:2], float)) == -math.inf:
        return 0.0
    return math.atan(math.tan(float(plane["slope"])) * math.cos(float(print_[2]) - up))


def roll_foot(
    feet: FootTracks, s: str, idx: np.ndarray, turn: np.ndarray, fwd: np.ndarray, geom: LegGeometry
) -> None:
    """Turn the ``s`` foot toes down by ``turn`` about a sole point ``fwd`` metres ahead of the
    ankle (the ball: :func:`~mjwalk.body.legs.footpivot.ball_offset`; the heel:
    ``-geom.foot_back``), that point kept where it is; ``feet`` updated in place.

    Args:
        feet: the foot tracks (``ankle``, ``pitch`` and ``fyaw`` per side).
        s: the side ("l"/"r").
        idx: (m,) the samples to turn.
        turn: (m,) the turn, radians (+ toes down).
        fwd: (m,) the pivot's distance ahead of the ankle along the sole, metres.
        geom: the foot's ``ankle_height``.
    """
    ah, p = geom.ankle_height, feet.pitch[s][idx]
    p2 = p - turn
    f = np.stack([np.cos(feet.fyaw[s][idx]), np.sin(feet.fyaw[s][idx])], -1)
    # the pivot's place in the foot's (forward, up) plane, kept while the pitch changes
    dx = fwd * (np.cos(p) - np.cos(p2)) + ah * (np.sin(p) - np.sin(p2))
    dz = fwd * (np.sin(p) - np.sin(p2)) - ah * (np.cos(p) - np.cos(p2))
    feet.ankle[s][idx, :2] += dx[:, None] * f
    feet.ankle[s][idx, 2] += dz
    feet.pitch[s][idx] = p2


def print_tracks(frames: list[StepFrames], n: int) -> dict[str, np.ndarray]:
    """Per side ("l"/"r") the footprint (x, y) each sample's foot stands on or lifts from, as
    :func:`~mjwalk.body.legs.legheights.level_tracks` assigns the surfaces: the stance foot's
    during a step, the swing foot's lift footprint until it lands, its landing one from then.

    Args:
        frames: the walk's steps as the leg synthesis sees them.
        n: the number of samples.

    Returns:
        per side (n, 2) footprint positions, metres.
    """
    out = {s: np.zeros((n, 2)) for s in "lr"}
    f0, fl = frames[0], frames[-1]
    out[f0.side][: f0.start + 1] = f0.lift[:2]
    out[f0.other][: f0.start + 1] = f0.stance[:2]
    for fr in frames:
        out[fr.other][fr.start : fr.end + 1] = fr.stance[:2]
        out[fr.side][fr.start : fr.end + 1] = fr.lift[:2]
        out[fr.side][fr.end] = fr.land[:2]
    out[fl.side][fl.end :] = fl.land[:2]
    out[fl.other][fl.end :] = fl.stance[:2]
    return out


def tilt(ankle: np.ndarray, yaw: np.ndarray, slope: np.ndarray, prints: np.ndarray) -> np.ndarray:
    """Flat-ground ankles (m, 3) put on a slope: turned by ``slope`` about their footprints'
    points on the floor, in the vertical plane of the headings ``yaw``. An ankle ahead of its
    footprint (the heel rising over the ball in pre-swing, 5-6 cm by toe-off) rises with the
    ramp's plane under it; turned about the point under itself instead, the ball and toes of
    a foot walking up a 5.5 deg ramp sank 6 mm into it by toe-off (the multi-level platform
    cycle's runs 15 and 18: the toes into the platform's edge at the ramp's top). On level
    ground (slope 0) the ankles are returned unchanged, bit for bit.

    Args:
        ankle: (m, 3) the flat synthesis's ankle positions, metres (z over its ground).
        yaw: (m,) the feet's headings, radians from +x CCW.
        slope: (m,) the surface's slope along the heading, radians (+ toes up).
        prints: (m, 2) the footprints the feet stand on (:func:`print_tracks`), metres.

    Returns:
        (m, 3) the ankles on the slope, z over the footprint's surface height, metres.
    """
    f = np.stack([np.cos(yaw), np.sin(yaw)], -1)
    h = ankle[:, 2]
    along = np.einsum("ij,ij->i", ankle[:, :2] - prints, f)
    out = ankle.copy()
    out[:, :2] += (along * (np.cos(slope) - 1.0) - h * np.sin(slope))[:, None] * f
    out[:, 2] = h * np.cos(slope) + along * np.sin(slope)
    return out


def trailing_reach(
    feet: FootTracks,
    root: np.ndarray,
    yaw: np.ndarray,
    grounded: dict[str, np.ndarray],
    slope: dict[str, np.ndarray],
    reach_sq: dict[str, np.ndarray],
    geom: LegGeometry,
) -> bool:
    """Where a grounded foot on a ramp (``slope`` not 0) is already rising on its ball (its
    pitch below its surface's slope) and its leg cannot reach it from the pelvis, its heel
    rises further about the ball (the toes kept on the surface) until it reaches, up to
    :data:`~mjwalk.body.legs.steps.HEEL_RISE_MAX` from the surface; ``feet`` updated in place.
    Feet on level surfaces (steps, stairs, landings) are left alone.

    Args:
        feet: the foot tracks on their surfaces.
        root: (n, 3) the pelvis positions, metres.
        yaw: (n,) the pelvis yaw, radians from +x CCW.
        grounded: per side ("l"/"r") whether the foot is on its surface, (n,).
        slope: per side the surface's slope along the foot, (n,) radians (+ uphill).
        reach_sq: per side the leg's squared hip-to-ankle span, (n,) m².
        geom: the leg geometry.

    Returns:
        whether any sample changed.
    """
    ball, moved = ball_offset(geom), False
    for s in "lr":
        ramp = grounded[s] & (np.abs(slope[s]) > 1e-6)
        if not ramp.any():
            continue
        only = {o: ramp if o == s else np.zeros(len(yaw), bool) for o in "lr"}
        for _ in range(REACH_PASSES):
            short = reach_deficit(root, yaw, feet.ankle, only, reach_sq, geom)
            lo = slope[s] - HEEL_RISE_MAX
            up = feet.pitch[s] < slope[s] - 1e-4
            idx = np.flatnonzero(ramp & up & (short > 1e-4) & (feet.pitch[s] > lo + 1e-4))
            if not len(idx):
                break
            p = feet.pitch[s][idx]
            lever = np.maximum(ball * np.cos(p - slope[s][idx]), 0.25 * ball)
            turn = np.minimum(short[idx] / lever, p - lo[idx])
            roll_foot(feet, s, idx, turn, np.full(len(idx), ball), geom)
            feet.toe[s][idx] += turn
            moved = True
    return moved


def _on_plane(plane: dict, print_) -> tuple[float, float] | None:
    """The height above the floor (m) and pitch (rad) of a ramp's plane under a footprint
    (x, y, yaw), or None off the ramp (beyond its ends or, its width known, its sides)."""
    h = float(plane_heights(plane, np.asarray(print_[:2], float)))
    if h == -math.inf:
        return None
    return h, plane_pitch(plane, np.asarray(print_, float))


def _widened(planes: list[dict], geom: LegGeometry) -> list[dict]:
    """Ramp planes over their surfaces' whole width (:func:`~mjwalk.plan.rampside.
    surface_plane`), those of known width widened on each side by the gap between two
    :data:`SOLE_GRID` points across the sole, so a sole edge between two tested points still
    meets the ramp's side (the swings' checks over ramps)."""
    side = geom.foot_width / (SOLE_GRID[1] - 1)
    return [{**p, "half_width": p["half_width"] + side} if p.get("half_width", 0.0) > 0.0
            else p for p in map(surface_plane, planes)]  # fmt: skip


def level_planes(walk, n: int) -> tuple[list[dict], list[bool]]:
    """The ramp planes a walk's level steps may stand or swing over, and which steps are level.

    The planes are those of the ramps its route crosses (``meta["levels"]["route"]``) and of
    the ramps beside it (``meta["ramps_beside"]``, :mod:`mjwalk.plan.rampside`: a floor walk
    cutting past a ramp's low end). A walk over levels has its route's level parts' steps
    level, and the steps of a crossing (a step, a stair, a ramp) that lift, stand and land
    at one height (the walk up to the first riser: on generated hall 153, ``benchmarks/
    bench_unseen.py``, such a step turned past a ramp's foot, its toes 2.3 cm into the
    ramp; the turn into a ramp on the floor before its foot: on hall 511's stress cycle,
    run 0, such a swing cut the ramp's low corner, its toes 0.74 mm into the ramp's side);
    a walk without a route (a floor walk) has every step level.

    Args:
        walk: the walk (:class:`~mjwalk.plan.walkpath.WalkPath`).
        n: its number of steps.

    Returns:
        the planes (each as :func:`plane_pitch` takes it) and per step whether it is level
        walking; no planes when the walk has none or its route does not count ``n`` steps.
    """
    meta = walk.meta or {}
    route = meta.get("levels", {}).get("route") or []
    planes = [e["plane"] for e in route if e.get("kind") == "ramp" and "plane" in e]
    planes += [p for p in meta.get(BESIDE_KEY, []) if p not in planes]
    if not route:
        return planes, [True] * n
    if not planes or sum(int(e.get("steps", 0)) for e in route) != n:
        return [], []
    kinds = [e.get("kind") for e in route for _ in range(int(e.get("steps", 0)))]
    return planes, [k == "level" or (k in ("step", "stair", "ramp") and _flat(walk, i))
                    for i, k in enumerate(kinds)]  # fmt: skip


def _flat(walk, k: int) -> bool:
    """Whether step ``k`` of a walk lifts, stands and lands at one height, to 1 um (its lift
    footprint is the previous step's stance)."""
    if k >= len(walk.steps):
        return False
    s = walk.steps[k]
    z = [s.foot_z, s.stance_z, walk.steps[k - 1].stance_z if k else s.stance_z]
    return bool(max(z) - min(z) <= 1e-6)


#: The most a ramp's plane can rise between the sole points checked under a level foot
#: (:data:`~mjwalk.plan.rampside.SOLE_GRID`, along and across, the same grid the walk's
#: ramps beside are found with), metres: a 0.27 m foot's points 3.4 cm apart on a 5.5 deg
#: ramp (MAX_RAMP_SLOPE 6 deg: 3.5 mm); a ramp's side edge crossing the sole lies between them.
SOLE_GRID_SAG = 0.004


def ramp_support(planes: list[dict], print_, geom: LegGeometry) -> tuple[float, float] | None:
    """The surface a footprint (x, y, yaw) stands on when a ramp's plane carries its heel, its
    ball (the sole's two supports in stance; :func:`~mjwalk.body.legs.footpivot.ball_offset`)
    and its toe tip (the toes lie flat in stance: pitched down a ramp past its foot they were
    1.8 cm into the floor, generated hall 500): the plane's height under the footprint point
    raised by the rise of the plane across half the foot's width (the foot is pitched to the
    slope along it, not rolled across it: it stands on its uphill edge), and the slope along it.

    Args:
        planes: ramp planes (as :func:`plane_pitch` takes them).
        print_: (3,) the footprint (x, y, yaw), metres and radians.
        geom: the foot's lengths and width.

    Returns:
        (height above the floor, metres; slope along the foot, radians, + uphill), or None
        when no one plane carries all three (the foot stands level on the highest point under it).
    """
    yaw = float(print_[2])
    f = np.array([math.cos(yaw), math.sin(yaw)])
    xy = np.asarray(print_[:2], float)
    sole = (-geom.foot_back, ball_offset(geom), geom.foot_front)
    for plane in planes:
        if all(_on_plane(plane, (*(xy + d * f), 0.0)) for d in sole):
            hit = _on_plane(plane, (*xy, yaw))
            if hit is None:
                continue
            across = math.tan(float(plane["slope"])) * abs(math.sin(yaw - float(plane["uphill"])))
            return hit[0] + 0.5 * geom.foot_width * across, hit[1]
    return None


def _set_foot(out: list[StepSurfaces], k: int, h: float, pitch: float, landing: bool) -> None:
    """Step ``k``'s landing (``landing``) or stance footprint on the surface (``h`` m above the
    floor, slope ``pitch`` rad) in ``out``, and the later steps on or lifting from it (in place)."""
    if landing:
        out[k] = replace(out[k], land=h, land_pitch=pitch, land_ramp=True)
        if k + 1 < len(out):  # the next step's stance foot
            out[k + 1] = replace(out[k + 1], stance=h, stance_pitch=pitch, stance_ramp=True)
        if k + 2 < len(out):
            out[k + 2] = replace(out[k + 2], lift=h, lift_pitch=pitch, lift_ramp=True)
    else:  # the first step's lifting foot stands beside it (a standing start: step_surfaces)
        sf = out[k]
        lift = (h, pitch, True) if k == 0 else (sf.lift, sf.lift_pitch, sf.lift_ramp)
        out[k] = replace(sf, stance=h, stance_pitch=pitch, stance_ramp=True, lift=lift[0],
                         lift_pitch=lift[1], lift_ramp=lift[2])  # fmt: skip
        if k + 1 < len(out):  # it swings next
            out[k + 1] = replace(out[k + 1], lift=h, lift_pitch=pitch, lift_ramp=True)


#: The foot box's height over its sole, a fraction of the ankle height (the humanoid's foot
#: geom, :func:`mjwalk.body.humanoid.humanoid_model`): how high its back face reaches.
FOOT_BOX_HEIGHT = 0.8

#: Spacing of the points behind the heel at which :func:`heel_face_need` meets a ramp's plane,
#: metres: the heel-strike foot's back face (26 deg toes up) rises 2 mm over 1 mm back.
HEEL_FACE_SPACING = 0.001


def heel_face_need(planes: list[dict], print_, pitch: float, geom: LegGeometry) -> float:
    """How high the ground under a footprint must be for its foot, landing on its heel pitched
    ``pitch`` toes up, to keep its back face above the ramp planes behind the heel: the box's
    back face, turned about the heel's edge, leans back ``z tan(pitch)`` at ``z`` over the
    sole, past the flat footprint a stance check tests (generated hall 511's stress cycle,
    run 5: a floor heel strike 7 mm from a ramp's side, pitched 26 deg, its back face 3.1 mm
    into the ramp's 2.5 cm side). A point ``d`` behind the heel is under the face at ``d /
    tan(pitch)`` over the ground; the plane's height there less that, plus
    :data:`SOLE_GRID_SAG` (the points lie :data:`HEEL_FACE_SPACING` apart), is the need.

    Args:
        planes: ramp planes (:func:`plane_heights`).
        print_: (3,) the footprint (x, y, yaw), metres and radians.
        pitch: the landing pitch, radians, + toes up (<= 0: the heel strikes flat, no need).
        geom: the foot's lengths, width and ankle height.

    Returns:
        the height above the floor, metres; -inf where the face passes over no plane.
    """
    if pitch <= 0.0 or not planes:
        return -math.inf
    reach = FOOT_BOX_HEIGHT * geom.ankle_height * math.sin(pitch)
    d = np.arange(1, math.ceil(reach / HEEL_FACE_SPACING) + 1) * HEEL_FACE_SPACING
    yaw = float(print_[2])
    f, left = np.array([math.cos(yaw), math.sin(yaw)]), np.array([-math.sin(yaw), math.cos(yaw)])
    across = np.linspace(-0.5, 0.5, SOLE_GRID[1]) * geom.foot_width
    xy = (np.asarray(print_[:2], float) - (geom.foot_back + d[:, None, None]) * f
          + across[None, :, None] * left)  # fmt: skip
    h = np.max([plane_heights(p, xy) for p in planes], axis=(0, 2))
    return float(np.max(h - d / math.tan(pitch))) + SOLE_GRID_SAG


def level_feet_on_ramps(
    walk, surfs: list[StepSurfaces], geom: LegGeometry | None = None, land_p=None
) -> list[StepSurfaces]:
    """A walk's level steps whose foot stands over the plane of a ramp its route crosses (a
    turn off or onto the ramp's foot cutting its low corner, under the floor level's 0.05 m
    obstacle band: a flat foot was 1-2 cm into it, the multi-level platform cycle's
    barrier-free runs), put on that plane. Where the plane carries the whole sole
    (:func:`ramp_support`) the foot stands on it pitched to its slope, as a ramp's own steps
    do; elsewhere (only its toes or its heel over the ramp's foot or side, or over the strip
    of the ramp's surface beside the part of its foot the floor meets, :func:`~mjwalk.plan.
    rampside.surface_plane`: generated hall 159's right foot stood 10.8 mm in it) it stands level on
    the highest point of the plane under its sole (heel, ankle, toe tip; the sole's edges and
    centre line): its heel clear of the floor by that height, its toes on the ramp through
    toe-off. Before, every such foot stood level, its heel up to the plane's rise along the
    foot above the ramp (27 mm on a 5.5 deg ramp's 0.27 m foot). The ramps are
    :func:`level_planes`' (also those beside a floor walk that cuts past a ramp's low end,
    :mod:`mjwalk.plan.rampside`). A ramp's own step whose sole reaches past its foot or head
    stands so too (hall 500: a foot down a 9.8 deg ramp, its ankle 8 cm above the foot, had
    its toes 1.8 cm into the floor); a sole past its head stands on the level the head meets
    (hall 514: toes 1.2 mm under a deck's edge). A level landing's heel strike is its pitched
    foot, not the flat footprint: its back face, leaning back behind the heel, stays over a
    ramp's plane behind it (:func:`heel_face_need`; the foot stands level as high as that
    needs). Walks without such a footprint are unchanged.

    Args:
        walk: the walk (:class:`~mjwalk.plan.walkpath.WalkPath`, ``meta["levels"]["route"]``).
        surfs: its steps' surfaces (:func:`~mjwalk.body.legs.legheights.step_surfaces`).
        geom: the foot's lengths and width (None: the default stature's).
        land_p: per step the pitch its foot lands with, radians, + toes up (the leg
            synthesis's :attr:`~mjwalk.body.legs.steps.StepFrames.land_p`; None: flat).

    Returns:
        the steps' surfaces, those over a ramp's plane raised (and pitched).
    """
    planes, level = level_planes(walk, len(walk.steps))
    if not planes:
        return surfs
    geom = geom or leg_geometry()
    along = np.linspace(-geom.foot_back, geom.foot_front, SOLE_GRID[0])
    grid = [(d, w) for d in along for w in np.linspace(-0.5, 0.5, SOLE_GRID[1])]
    flat = [surface_plane(p) for p in planes]  # the ramps' whole surfaces, once per walk
    lows = [(p, f) for p, f in zip(planes, flat, strict=True) if LOW_KEY in p]

    def under(print_, planes=planes, whole=flat) -> tuple[float, float] | None:
        if not planes:
            return None
        on = ramp_support(planes, print_, geom)
        if on is not None:
            return on
        yaw = float(print_[2])
        f = np.array([math.cos(yaw), math.sin(yaw)])
        pts = [np.asarray(print_[:2], float) + d * f + w * geom.foot_width * f[::-1] * [-1, 1]
               for d, w in grid]  # fmt: skip
        hits = {i: [h[0] for q in pts if (h := _on_plane(p, (*q, 0.0))) is not None]
                for i, p in enumerate(whole)}  # fmt: skip
        if not any(hits.values()):
            return None
        # the level past a ramp's head under a sole reaching over that ramp's crest, not
        # under one standing on another plane (a mat 5.7 m beyond a ramp's head, in line with
        # it: the foot stood 0.34 m up in the air, the pelvis lowered 0.15 m to reach it)
        top = max(float(np.max(head_heights(whole[i], np.asarray(pts)))) for i, h in hits.items()
                  if h)  # fmt: skip
        return max(max(max(h) for h in hits.values() if h) + SOLE_GRID_SAG, top), 0.0

    low_under = functools.partial(under, planes=[p for p, _ in lows], whole=[f for _, f in lows])
    out = list(surfs)
    for k, s in enumerate(walk.steps):
        land, stance = under(s.foot), under(s.stance)
        face = heel_face_need(flat, s.foot, float(land_p[k]), geom) if land_p else -math.inf
        if level[k] and face > max(out[k].land, land[0] if land else -math.inf):
            land = (face, 0.0) if land is None or land[1] == 0.0 else land
        if not level[k]:  # a ramp's own foot, pitched, that the plane does not carry whole;
            # a riser's footfall on a low top (a mat before a step) stands on the low top
            land = land if out[k].land_pitch and land and not land[1] else low_under(s.foot)
            stance = (stance if out[k].stance_pitch and stance and not stance[1]
                      else low_under(s.stance))  # fmt: skip
        if land is not None and (land[1] != 0.0 or land[0] > out[k].land):
            _set_foot(out, k, *land, landing=True)
        if stance is not None and (stance[1] != 0.0 or stance[0] > out[k].stance):
            _set_foot(out, k, *stance, landing=False)
    return low_treads(walk, out, level, low_under)


def swing_over_ramps(walk, frames: list[StepFrames], air: dict, feet: FootTracks,
                     flat_ankle: dict, geom: LegGeometry) -> None:  # fmt: skip
    """The swing foot of a level step raised over a ramp's plane it passes above (a turn off or
    onto a ramp's foot crossing its low corner, under the floor level's 0.05 m obstacle band:
    the sole swept 1-2 cm through it on the multi-level platform cycle's barrier-free runs):
    each point of the sole's :data:`SOLE_GRID` (heel to toe tip, edge to edge), where the
    foot's pitch holds it (a toes-down foot after push-off has its toes 3-4 cm nearer the
    ankle than a flat one: run 7 of the multi-level platform cycle at 12 runs, its right toes
    10 mm into the ramp's low corner), kept :data:`SOLE_GRID_SAG` above the plane, the foot's
    own clearance above its ground kept; a ramp's sides are taken one grid spacing wider (a
    side edge crossing the sole between two points). Only the level steps, over the ramps of
    :func:`level_planes` (those the route crosses, those beside the walk); ``feet`` updated
    in place.

    Args:
        walk: the walk (``meta["levels"]["route"]`` with its ramps' ``plane``).
        frames: its steps as the leg synthesis sees them.
        air: per side ("l"/"r") the (n,) flags of the foot in the air.
        feet: the foot tracks, on their surfaces (ankle z updated in place).
        flat_ankle: per side the flat synthesis's (n, 3) ankle positions, metres.
        geom: the foot's lengths and width.

    Returns:
        None.
    """
    planes, level = level_planes(walk, len(frames))
    if not planes:
        return
    across = np.linspace(-0.5, 0.5, SOLE_GRID[1])
    grid = [(d, w) for d in np.linspace(-geom.foot_back, geom.foot_front, SOLE_GRID[0])
            for w in across]  # fmt: skip
    planes = _widened(planes, geom)
    for fr, on_level in zip(frames, level, strict=True):
        s = fr.side
        j = np.flatnonzero(air[s][fr.start : fr.end]) + fr.start
        if not on_level or not len(j):
            continue
        yaw, pitch = feet.fyaw[s][j], feet.pitch[s][j]
        f = np.stack([np.cos(yaw), np.sin(yaw)], -1)
        left = np.stack([-f[:, 1], f[:, 0]], -1)
        need = np.full(len(j), -np.inf)
        for d, w in grid:  # the sole point d ahead of the ankle as the pitched foot holds it
            ahead = d * np.cos(pitch) + geom.ankle_height * np.sin(pitch)
            p = feet.ankle[s][j, :2] + ahead[:, None] * f + w * geom.foot_width * left
            for plane in planes:
                hit = [_on_plane(plane, (x, y, 0.0)) for x, y in p]
                need = np.maximum(need, [-np.inf if h is None else h[0] for h in hit])
        offset = feet.ankle[s][j, 2] - flat_ankle[s][j, 2]
        feet.ankle[s][j, 2] += np.maximum(need + SOLE_GRID_SAG - offset, 0.0)


#: Passes of :func:`swings_clear_ramps` (pitch the foot to what the ankle holds, lift the
#: sole over the ramps' planes); on generated hall 8's edged floor step the lift is nil by the
#: third.
EDGED_RAMP_PASSES = 4


def plane_heights(plane: dict, xy: np.ndarray) -> np.ndarray:
    """The height of a ramp's plane under points.

    Args:
        plane: the ramp's plane (as :func:`plane_pitch` takes it, with ``half_width``, ``z``).
        xy: (..., 2) world points, metres.

    Returns:
        (...,) the height above the floor, metres; -inf off the ramp (beyond its ends or, its
        width known, its sides).
    """
    up = float(plane["uphill"])
    along = (xy - np.asarray(plane["foot"], float)) @ np.array([math.cos(up), math.sin(up)])
    h = float(plane.get("z", 0.0)) + math.tan(float(plane["slope"])) * along
    return np.where(over_ramp(plane, xy), h, -np.inf)


def _sole_grid(ankle, pitch, toe, yaw, geom: LegGeometry) -> np.ndarray:
    """(m, p, 3) the :data:`SOLE_GRID` points of the sole (heel to toe tip, edge to edge) for
    ankles (m, 3), pitches, toe angles and headings (m,), the toes turned about the ball by
    the toe angle; world metres, pitch + toes up."""
    ah, ball = geom.ankle_height, ball_offset(geom)
    along = np.linspace(-geom.foot_back, geom.foot_front, SOLE_GRID[0])
    across = np.linspace(-0.5, 0.5, SOLE_GRID[1]) * geom.foot_width
    p, t = pitch[:, None], toe[:, None]
    d = np.minimum(along, ball)[None, :]
    fw = d * np.cos(p) + ah * np.sin(p) + np.maximum(along - ball, 0.0) * np.cos(p + t)
    up = d * np.sin(p) - ah * np.cos(p) + np.maximum(along - ball, 0.0) * np.sin(p + t)
    f = np.stack([np.cos(yaw), np.sin(yaw)], -1)
    left = np.stack([-f[:, 1], f[:, 0]], -1)
    xy = ankle[:, None, None, :2] + fw[:, :, None, None] * f[:, None, None]
    xy = xy + across[None, None, :, None] * left[:, None, None]
    z = np.broadcast_to((ankle[:, 2:3] + up)[:, :, None], xy.shape[:3])
    return np.concatenate([xy, z[..., None]], -1).reshape(len(ankle), -1, 3)


def swings_clear_ramps(
    walk,
    plans: list,
    frames: list[StepFrames],
    air: dict,
    feet: FootTracks,
    root: np.ndarray,
    yaw: np.ndarray,
    geom: LegGeometry,
) -> None:
    """The swings of a walk's level steps kept above the planes of the ramps it passes
    (:func:`level_planes`) at the foot pitch the ankle holds, last of the legs' lifts: the
    edged swings after they are planned over their edges, every other level step's airborne
    samples after :func:`swing_over_ramps` lifted them at the pitch the foot was given. A
    sharp turn beside a ramp's foot (generated hall 153, ``benchmarks/bench_unseen.py``, a
    floor walk's last turn to a step up) asks the ankle for more dorsiflexion than it has:
    the foot hung 45 deg toes down and its toes passed 2.3 cm into the ramp, though the
    ankle was lifted over it. A level step is edged
    where a foot beside it stands raised on a ramp's low end (:func:`level_feet_on_ramps`),
    and its swing, planned over that one height (the legs' edge swing), passed 11.7 mm into
    the ramp's side higher up its run (generated hall 8, ``benchmarks/bench_unseen.py``: the
    left toes, hanging 28 deg toes down where the ankle could not dorsiflex further). Each
    pass lifts the airborne ankle so that every :data:`SOLE_GRID` point of the sole at its
    pitch (its toes turned by the toe angle) is :data:`SOLE_GRID_SAG` above any plane under
    it, then pitches the foot toes down by the dorsiflexion the leg IK asks beyond the
    ankle's range there (as the edge swing does), until no point is below (a ramp's sides
    wider), the lift spread over the samples around (:func:`~mjwalk.body.legs.curves.spread`,
    +-2 samples). Swings already clear are left as they are. ``feet`` updated in place.

    Args:
        walk: the walk (its route's ramps' ``plane`` and those beside it).
        plans: the edged swings (step, surfaces, samples from the last grounded one to the
            landing, ankles), as the leg synthesis planned them.
        frames: the walk's steps as the leg synthesis sees them.
        air: per side ("l"/"r") the (n,) flags of the foot in the air.
        feet: the foot tracks (ankle z and pitch updated in place).
        root: (n, 3) the pelvis positions, metres.
        yaw: (n,) the pelvis yaw, radians from +x CCW.
        geom: the leg and foot lengths.
    """
    planes, level = level_planes(walk, len(frames))
    if not planes:
        return
    index = {id(fr): i for i, fr in enumerate(frames)}
    mine = [(fr.side, k[1:-1]) for fr, _, k, _ in plans if level[index[id(fr)]] and len(k) > 2]
    edged = {id(fr) for fr, *_ in plans}
    for fr, on_level in zip(frames, level, strict=True):
        j = np.flatnonzero(air[fr.side][fr.start : fr.end]) + fr.start
        if on_level and id(fr) not in edged and len(j):
            mine.append((fr.side, j))
    if not mine:
        return
    planes = _widened(planes, geom)
    top = math.radians(ROM_DEG["ankle_flex"][1])
    for _ in range(EDGED_RAMP_PASSES):
        moved = False
        for s, j in mine:
            pts = _sole_grid(feet.ankle[s][j], feet.pitch[s][j], feet.toe[s][j],
                             feet.fyaw[s][j], geom)  # fmt: skip
            under = np.max([plane_heights(p, pts[..., :2]) for p in planes], axis=0)
            need = np.maximum(np.max(under + SOLE_GRID_SAG - pts[..., 2], axis=1), 0.0)
            if need.max() <= 1e-4:
                continue
            feet.ankle[s][j, 2] += np.maximum(spread(need, 2), need)
            raw = leg_ik_world(feet.ankle[s][j], feet.fyaw[s][j], feet.pitch[s][j], root[j],
                               yaw[j], s, geom)  # fmt: skip
            feet.pitch[s][j] -= np.maximum(raw[f"ankle_{s}_flex"] - top, 0.0)
            moved = True
        if not moved:
            break
