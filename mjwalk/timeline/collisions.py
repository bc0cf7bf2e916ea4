"""Humanoid-vs-scene contacts of a timeline by MuJoCo's collision detection, and playback.

:func:`collision_report` runs MuJoCo collision detection on the frames of a
:class:`~mjwalk.timeline.timeline.Timeline` where a contact can be reported (a broad phase by
bounding volumes, :func:`candidate_frames`, measured on station cycles: about a tenth of the
frames, 3-4x faster than every frame, the same contacts); :func:`check_collisions` does the
same for a simulated cycle, a timeline or a walk played in a scene. World frame: metres,
seconds, z up.
"""

from __future__ import annotations

import math
import weakref
from dataclasses import dataclass
from pathlib import Path

import mujoco
import numpy as np

from mjwalk._jit import njit
from mjwalk.body.humanoid import HUMAN_GROUP
from mjwalk.errors import MjwalkError
from mjwalk.plan.walkpath import WalkPath
from mjwalk.timeline.frames import timeline_from_walk
from mjwalk.timeline.geomposes import GeomTable, geom_poses, supported
from mjwalk.timeline.timeline import Timeline
from mjwalk.timeline.walktops import level_heights, walk_tops
from mjwalk.world.floor import floor_planes, flush_geoms, slab_floor_mask
from mjwalk.world.norms import MAX_RAMP_SLOPE, ROUNDING_SLACK
from mjwalk.world.workplace import shared_workplace


@dataclass
class Contact:
    """One humanoid-vs-scene contact in one frame.

    Attributes:
        time: frame time in seconds.
        body_part: the humanoid geom (unprefixed name, e.g. ``"forearm_r"``).
        scene_geom: the scene geom's name (or ``"geom#<id>"`` when unnamed).
        depth: penetration depth in metres (>= 0 means overlapping).
        pos: (3,) contact point in world coordinates, metres.
    """

    time: float
    body_part: str
    scene_geom: str
    depth: float
    pos: np.ndarray


#: Slack (m) of the broad phase's bounding-volume tests: a pair this close is handed to MuJoCo.
BROAD_SLACK = 1e-3
#: Capsules are covered by spheres of at most (1 + 1/this) their radius (:class:`StaticScene`;
#: station candidate frames a cycle by this: 1: 127, 4: 75, 16: 60; measured over 8 cycles).
SUB_PER_RADIUS = 4


def collision_report(
    timeline: Timeline,
    floor_tolerance: float = 0.01,
    broad_phase: bool = True,
    data: mujoco.MjData | None = None,
    table: GeomTable | None = None,
) -> list[Contact]:
    """Humanoid-vs-scene contacts of every frame by MuJoCo collision detection.

    Only pairs of one humanoid geom (group 5) and one scene geom count. Contacts with the floor
    (the geom named ``"floor"``, any plane, and geoms flush with it or with a level such as
    tape, :func:`~mjwalk.world.floor.flush_geoms`,
    :func:`~mjwalk.timeline.walktops.level_heights`) no deeper than ``floor_tolerance`` metres
    are ordinary foot contact, not reported. In a scene on several levels
    (:func:`~mjwalk.timeline.walktops.walk_tops`) a sole (``foot_*``, ``toes_*``) on the top
    face of a walk surface (platform, tread, ramp) stands too: no deeper than
    ``floor_tolerance``, its normal within :data:`TOP_NORMAL_TILT` of vertical or no depth
    (``norms.ROUNDING_SLACK``); a foot against a riser is reported. Flat: as before.

    With ``broad_phase`` (default) MuJoCo's collision detection runs only on the frames where
    a contact can be reported (:func:`candidate_frames`: some humanoid geom's bounding sphere
    within reach of a scene geom's box, or some humanoid geom deeper than
    ``floor_tolerance`` below a floor plane), and a frame equal to the one before takes that
    frame's contacts; the contacts are the same as those of the full check
    (``broad_phase=False``: every frame through MuJoCo).

    ``data``: an MjData of the timeline's model to work in (default: a new one).

    Returns:
        contacts in time order (one per geom pair and frame), depth in metres.

    Args:
        timeline: the timeline to check.
        floor_tolerance: floor contacts shallower than this (metres) are left out.
        broad_phase: skip the frames without a candidate contact (same result, faster).
        data: an MjData of the timeline's model to work in (default: a new one).
        table: the humanoid's geom poses in every frame, if already computed (the same
            numbers as the broad phase's own, :class:`~mjwalk.timeline.geomposes.GeomTable`).

    Raises:
        MjwalkError: a frame's pose is not finite (NaN or inf).
    """
    model = timeline.model
    data = data if data is not None else mujoco.MjData(model)
    human = model.geom_group == HUMAN_GROUP
    plen = len(timeline.jointmap.prefix)
    names, floorish = _geom_names(model)
    tops = walk_tops(timeline)
    soles = human & _soles(model, plen)
    qpos = np.asarray(timeline.qpos)
    bad = np.flatnonzero(~np.isfinite(qpos).all(axis=1))
    if len(bad):  # MuJoCo finds no contact at a non-finite pose: it would pass unchecked
        raise MjwalkError(
            f"timeline frame {bad[0]} (t = {timeline.t[bad[0]]:.3f} s) and {len(bad) - 1} "
            "more have a non-finite pose: their contacts cannot be checked"
        )
    same = repeats(qpos) if broad_phase else np.zeros(len(qpos), dtype=bool)
    check = ~same  # every pose but a repeat; with the broad phase, only its candidates
    if broad_phase and len(qpos) > 1:
        fresh = np.flatnonzero(~same)
        check[fresh] = candidate_frames(
            model, qpos[fresh], human, floorish, floor_tolerance, data, table, fresh
        )
    out: list[Contact] = []
    t = timeline.t
    mujoco.mj_kinematics(model, data)  # the scene's geoms placed: those flush with the floor
    flat = (floorish | flush_geoms(model, data, level_heights(timeline))).tolist()
    masks = (human.tolist(), flat, tops if tops is None else tops.tolist(), soles)
    for i in np.flatnonzero(check).tolist():  # (a repeated pose is never checked itself)
        data.qpos[:] = qpos[i]
        mujoco.mj_kinematics(model, data)
        mujoco.mj_collision(model, data)
        if data.ncon == 0:
            continue
        best = _kept(data.contact, data.ncon, masks, floor_tolerance)
        found = [(names[h][plen:], names[s_], d, pos) for (h, s_), (d, pos) in best.items()]
        j = i
        while True:  # the frame, then the frames after it that repeat its pose: its contacts
            out += [Contact(float(t[j]), h, s_, d, p.copy()) for h, s_, d, p in found]
            j += 1
            if j >= len(qpos) or not same[j]:
                break
    return out


def _kept(con, n: int, masks: tuple, floor_tolerance: float) -> dict:
    """:func:`collision_report`'s contacts of the first ``n`` of ``con`` (MjData's), the deepest a
    pair: ``{(humanoid geom, scene geom): (depth m, (3,) point)}``; ``masks``: its masks as lists
    (humanoid, floor, walk tops or None, soles; a few contacts: plain Python, not numpy)."""
    human, floorish, tops, soles = masks  # (soles: an array, read only on walk tops)
    up = [] if tops is None else (np.abs(np.asarray(con.frame[:n])[:, 2]) >= UPRIGHT).tolist()
    best: dict[tuple[int, int], tuple[float, np.ndarray]] = {}  # pairs in order of first kept
    pairs, dists = con.geom[:n].tolist(), con.dist[:n].tolist()
    for k, ((a, b), dist) in enumerate(zip(pairs, dists, strict=True)):
        if human[a] == human[b]:
            continue
        hg, sg = (a, b) if human[a] else (b, a)
        depth = -dist
        shallow = depth <= floor_tolerance
        if floorish[sg] and shallow:
            continue
        on_top = tops is not None and tops[sg] and soles[hg]  # standing: as upright as a ramp,
        if on_top and shallow and (up[k] or depth <= ROUNDING_SLACK):  # or no depth at all
            continue
        if depth > best.get((hg, sg), (-math.inf,))[0]:
            best[(hg, sg)] = (depth, np.array(con.pos[k]))
    return best


#: Largest tilt of a contact normal from vertical (radians) for a sole's contact with a walk
#: surface to count as standing on its top face: the steepest walkable ramp
#: (``mjwalk.world.norms.MAX_RAMP_SLOPE``) plus 10 deg for the contact normal of a box corner
#: on a face (MuJoCo's box-box normals follow the faces).
TOP_NORMAL_TILT = MAX_RAMP_SLOPE + math.radians(10.0)
UPRIGHT = math.cos(TOP_NORMAL_TILT)  # a contact normal's least vertical part, standing


#: :func:`_soles` per model, by the length of the humanoid's name prefix.
_SOLES: weakref.WeakKeyDictionary = weakref.WeakKeyDictionary()


def _soles(model: mujoco.MjModel, plen: int) -> np.ndarray:
    """(ngeom,) read-only mask of the geoms whose names, after ``plen`` characters of prefix,
    start with ``foot_`` or ``toes_`` (the soles), kept per model."""
    kept = _SOLES.setdefault(model, {})
    if plen not in kept:
        names = _geom_names(model)[0]
        kept[plen] = np.array([n[plen:].startswith(("foot_", "toes_")) for n in names])
        kept[plen].setflags(write=False)
    return kept[plen]


#: :func:`_geom_names` of the models seen (a cycle checks its frames in a few models, again
#: and again: 80 name look-ups each time cost about 0.1 ms).
_NAMES: weakref.WeakKeyDictionary = weakref.WeakKeyDictionary()


def _geom_names(model: mujoco.MjModel) -> tuple[list[str], np.ndarray]:
    """The geoms' names (``"geom#<id>"`` when unnamed) and the floor mask (the geom named
    ``"floor"``, every plane, a slab floor) of ``model``, kept per model (fixed once compiled)."""
    hit = _NAMES.get(model)
    if hit is None or len(hit[0]) != model.ngeom:
        names = [
            mujoco.mj_id2name(model, mujoco.mjtObj.mjOBJ_GEOM, g) or f"geom#{g}"
            for g in range(model.ngeom)
        ]
        plane = mujoco.mjtGeom.mjGEOM_PLANE
        floorish = np.array(
            [n == "floor" or model.geom_type[g] == plane for g, n in enumerate(names)]
        )
        floorish |= slab_floor_mask(model)  # a floor modelled as a slab
        floorish.setflags(write=False)
        hit = _NAMES[model] = (names, floorish)
    return hit


def repeats(qpos: np.ndarray) -> np.ndarray:
    """(F,) whether each pose of ``qpos`` equals the one before it (a hold): its
    contacts, and its distances, are those of that pose.

    Args:
        qpos: (F, nq) poses.

    Returns:
        (F,) bool; the first frame is never a repeat.
    """
    qpos = np.asarray(qpos)
    if qpos.ndim != 2 or qpos.dtype != np.float64:  # (the kernel's one layout)
        same = np.zeros(len(qpos), dtype=bool)
        if len(qpos) > 1:
            same[1:] = np.all(qpos[1:] == qpos[:-1], axis=1)
        return same
    return _repeats(qpos)


@njit
def _repeats(qpos):
    """:func:`repeats` of a (F, nq) float array, compiled: a row is compared with the one
    before only up to its first differing number (NumPy compared every number of every row:
    about 25 us of a station cycle's 22 calls each). NaN equals nothing, as in NumPy."""
    n_f, n_q = qpos.shape
    same = np.zeros(n_f, dtype=np.bool_)
    for f in range(1, n_f):
        eq = True
        for i in range(n_q):
            if qpos[f, i] != qpos[f - 1, i]:
                eq = False
                break
        same[f] = eq
    return same


def floor_geoms(model: mujoco.MjModel) -> np.ndarray:
    """The floors of ``model``: the geom named ``"floor"``, every plane, a slab floor
    (:func:`~mjwalk.world.floor.slab_floor_mask`): their shallow contacts are standing.

    Args:
        model: the compiled scene (with or without the humanoid).

    Returns:
        (ngeom,) read-only bool mask.
    """
    return _geom_names(model)[1]


def candidate_frames(
    model: mujoco.MjModel,
    qpos: np.ndarray,
    human: np.ndarray,
    floorish: np.ndarray,
    floor_tolerance: float,
    data: mujoco.MjData | None = None,
    table: GeomTable | None = None,
    rows: np.ndarray | None = None,
) -> np.ndarray:
    """(F,) True for the poses ``qpos`` (F, nq) in which a humanoid geom (``human`` (ngeom,)
    mask) may touch a scene geom, by bounding volumes (conservative: every contact MuJoCo can
    report lies in a True frame; world frame, metres):

    * a scene geom other than a floor (``floorish`` mask): its world box (MuJoCo's
      ``geom_aabb``, rotated into the world) within a humanoid geom's bounding sphere
      (``geom_rbound``) plus both margins and :data:`BROAD_SLACK`;
    * a floor plane: a humanoid geom's lowest point (exact for spheres, capsules, cylinders
      and boxes; the bounding sphere otherwise) deeper than ``floor_tolerance`` less the
      slack below it (shallower floor contacts are not reported; a contact's distance is the
      geometry's whatever the margins, which only decide whether a pair apart is reported, so
      the arms' clearance margin of :class:`~mjwalk.cycle.standoff.ArmClearance` does not
      make every frame with a foot on the floor a candidate).

    Scene geoms on moving bodies, and floors that are not planes, make every frame a
    candidate. Forward kinematics of every pose, compiled over all frames
    (:func:`mjwalk.timeline.geomposes.geom_poses`; with mocap bodies by ``mj_kinematics``
    in ``data``, default a new MjData, frame by frame).

    Args:
        model: the compiled scene with the humanoid.
        qpos: (F, nq) poses.
        human: (ngeom,) bool mask of the humanoid's geoms.
        floorish: (ngeom,) bool mask of the floors (:func:`floor_geoms`).
        floor_tolerance: floor contacts shallower than this (metres) are not reported.
        data: an MjData of ``model`` for models the compiled kinematics does not support.
        table: the geom poses of a timeline whose frames ``rows`` (F,) are ``qpos`` (used
            when it holds the humanoid's geoms; a row of it is what :func:`geom_poses` gives
            for that frame alone, so the result is the same).
        rows: see ``table``.

    Returns:
        (F,) bool: True where MuJoCo's collision detection must run.
    """
    n = len(qpos)
    scene = _static_scene(
        model, np.asarray(human, dtype=bool), np.asarray(floorish, dtype=bool), data
    )
    if n == 0 or scene is None:
        return np.ones(n, dtype=bool)
    hid = scene.hid
    if len(hid) == 0:  # no humanoid: nothing to report
        return np.zeros(n, dtype=bool)
    shared = table.columns(hid) if table is not None and rows is not None else None
    if shared is not None:  # the timeline's own table: its rows of these frames
        xpos, xmat = shared
    elif supported(model):  # compiled over all frames
        xpos, xmat = geom_poses(model, qpos, hid)
    else:
        data = data if data is not None else mujoco.MjData(model)
        lo, hi = int(hid.min()), int(hid.max()) + 1  # the humanoid's geoms are one block
        xpos = np.empty((n, hi - lo, 3))
        xmat = np.empty((n, hi - lo, 9))
        q, gx, gm = data.qpos, data.geom_xpos[lo:hi], data.geom_xmat[lo:hi]  # views
        for f in range(n):
            q[:] = qpos[f]
            mujoco.mj_kinematics(model, data)
            xpos[f] = gx
            xmat[f] = gm
        if hi - lo != len(hid):  # not one block after all: keep the humanoid's rows
            xpos, xmat = xpos[:, hid - lo], xmat[:, hid - lo]
    centre, half, reach_solid = scene.centre, scene.half, scene.reach_solid
    normals, origins = scene.normals, scene.origins
    # a floor contact's distance is the geometry's, margins do not enter it (they only let
    # MuJoCo report pairs that are apart): a contact deeper than floor_tolerance needs the
    # lowest point that deep, less the slack for round-off
    depth = floor_tolerance - BROAD_SLACK
    rows = np.arange(n) if shared is None else np.asarray(rows, dtype=np.int64)
    return _touching(
        rows, xpos, xmat, scene.types, scene.size, scene.rbound, reach_solid, scene.n_sub,
        scene.sub_reach, centre, half, normals, origins, depth, scene.low,
    )  # fmt: skip


@dataclass(frozen=True)
class StaticScene:
    """What :func:`candidate_frames` needs of a model besides the poses, the same for every
    call (the scene geoms are welded to the world): the humanoid's geoms and their bounds, and
    the scene's boxes and floor planes in world axes (metres).

    Attributes:
        hid: (G,) the humanoid's geom ids.
        types: (G,) their MuJoCo geom types.
        size: (G, 3) their sizes.
        rbound: (G,) their bounding-sphere radii.
        reach_solid: (G,) how near (m) each may come to a scene box before a frame counts.
        n_sub: (G,) how many spheres along a capsule's axis cover it, ceil(
            :data:`SUB_PER_RADIUS` half-length / radius) (1 for other geoms: the bounding
            sphere alone), each of the capsule's radius plus a piece's half-length.
        sub_reach: (G,) how near (m) those spheres' centres may come to a scene box.
        centre: (S, 3) the scene boxes' centres.
        half: (S, 3) their half-extents along the world axes.
        normals: (P, 3) the floor planes' normals.
        origins: (P, 3) points on them.
        low: (G,) a bound on each geom's extent along any unit normal (m, +1e-6 round-off).
    """

    hid: np.ndarray
    types: np.ndarray
    size: np.ndarray
    rbound: np.ndarray
    reach_solid: np.ndarray
    n_sub: np.ndarray
    sub_reach: np.ndarray
    centre: np.ndarray
    half: np.ndarray
    normals: np.ndarray
    origins: np.ndarray
    low: np.ndarray


#: :func:`_static_scene` per model, by the masks and the geoms' margins it was built for.
_STATIC: weakref.WeakKeyDictionary = weakref.WeakKeyDictionary()


def _static_scene(
    model: mujoco.MjModel,
    human: np.ndarray,
    floorish: np.ndarray,
    data: mujoco.MjData | None = None,
) -> StaticScene | None:
    """The :class:`StaticScene` of ``model`` for the ``human`` and ``floorish`` masks, kept per
    model (the margins in the key: a clearance check inflates its copy's); None when every
    frame is a candidate (scene geoms on moving bodies, a floor that is not a plane).

    ``data`` (an MjData of the model's layout, whatever its pose; None: a new one) is where
    the scene's geoms are placed when the model is new: they are welded to the world, so any
    pose places them at the same numbers, and making an MjData of the station's humanoid cost
    about 0.7 ms, twice a cycle (each operator's stature is a model of its own: the contact
    check's and the clearance check's copy). Its kinematics are left at its own qpos."""
    key = (human.tobytes(), floorish.tobytes(), model.geom_margin.tobytes())
    kept = _STATIC.setdefault(model, {})
    if key in kept:
        return kept[key]
    hid = np.flatnonzero(human)
    sid = np.flatnonzero(~human & (model.geom_contype | model.geom_conaffinity).astype(bool))
    floors = sid[floorish[sid]]
    solids = sid[~floorish[sid]]
    data = data if data is not None else mujoco.MjData(model)
    mujoco.mj_kinematics(model, data)  # the scene's geoms are static: any pose places them
    moving = (model.body_weldid[model.geom_bodyid[sid]] != 0).any()
    planes = None if moving else floor_planes(model, data, floors)  # (slab floors: their tops)
    if planes is None:  # scene geoms on moving bodies, or a floor neither a plane nor a slab
        kept[key] = None
        return None
    slack = model.geom_margin[hid].max(initial=0.0) + BROAD_SLACK
    reach = model.geom_rbound[hid] + model.geom_margin[hid] + slack
    # the scene's boxes (static: welded to the world) in world axes
    R = data.geom_xmat[solids].reshape(-1, 3, 3)
    aabb = model.geom_aabb[solids]
    # a capsule within its bounding sphere's reach is looked at closer: the spheres along its
    # axis that cover it (n of them, radius r + h / n), with the same margins and slack
    types, size = model.geom_type[hid].astype(np.int64), model.geom_size[hid]
    capsule = (types == _CAPSULE) & (size[:, 0] > 0.0)
    n_sub = np.ones(len(hid), dtype=np.int64)
    n_sub[capsule] = np.ceil(SUB_PER_RADIUS * size[capsule, 1] / size[capsule, 0]).clip(1)
    margins = model.geom_margin[hid] + slack + model.geom_margin[solids].max(initial=0.0)
    tube = np.isin(types, (_CAPSULE, _CYLINDER))  # extent <= half length + radius (a box's: sizes)
    ext = np.where(types == _BOX, size.sum(axis=1), size[:, 0] + size[:, 1] * tube)
    kept[key] = StaticScene(
        hid=hid,
        types=types,
        size=size,
        rbound=model.geom_rbound[hid],
        reach_solid=reach + model.geom_margin[solids].max(initial=0.0),
        n_sub=n_sub,
        sub_reach=size[:, 0] + size[:, 1] / n_sub + margins,
        centre=data.geom_xpos[solids] + np.einsum("gij,gj->gi", R, aabb[:, :3]),
        half=np.einsum("gij,gj->gi", np.abs(R), aabb[:, 3:]),
        normals=planes[0],
        origins=planes[1],
        low=np.maximum(ext, model.geom_rbound[hid]) * (1.0 + 1e-6),  # (other types: rbound)
    )
    return kept[key]


#: MuJoCo's geom type codes the floor test handles exactly (others: the bounding sphere).
_SPHERE, _CAPSULE, _CYLINDER, _BOX = (
    int(mujoco.mjtGeom.mjGEOM_SPHERE),
    int(mujoco.mjtGeom.mjGEOM_CAPSULE),
    int(mujoco.mjtGeom.mjGEOM_CYLINDER),
    int(mujoco.mjtGeom.mjGEOM_BOX),
)


@njit
def _touching(
    rows, xpos, xmat, types, size, rbound, reach, n_sub, sub_reach, centre, half, normals, origins,
    depth, low,
):  # fmt: skip
    """(R,) which frames ``rows`` (R,) have a humanoid geom (centres ``xpos`` (F, G, 3), rotations
    ``xmat`` (F, G, 9), MuJoCo ``types``/``size``/``rbound`` (G,)) within ``reach`` (G,) of a
    scene box (``centre``, ``half`` (S, 3), world axes), a capsule's bounding sphere only
    where one of its ``n_sub`` spheres along the axis comes within ``sub_reach`` of it
    (:func:`_sub_spheres_reach`), or its lowest point lies more than ``depth`` below a floor
    plane (``normals``, ``origins`` (P, 3); not tested closer when centred over ``low`` (G,)
    less ``depth`` above it: its extent is below ``low``, rounding is monotone). Metres."""
    n, g_n, s_n, p_n = rows.shape[0], xpos.shape[1], centre.shape[0], normals.shape[0]
    hit = np.zeros(n, dtype=np.bool_)
    near = np.empty(s_n, dtype=np.int64)  # this frame's near boxes (the first m of them)
    lo, hi = np.empty(3), np.empty(3)
    for r in range(n):
        f = rows[r]
        # the scene boxes that overlap the box around all the humanoid's reach spheres
        lo[:] = np.inf
        hi[:] = -np.inf
        for g in range(g_n):
            for j in range(3):
                lo[j] = min(lo[j], xpos[f, g, j] - reach[g])
                hi[j] = max(hi[j], xpos[f, g, j] + reach[g])
        m = 0
        for k in range(s_n):
            apart = False
            for j in range(3):
                if lo[j] > centre[k, j] + half[k, j] or hi[j] < centre[k, j] - half[k, j]:
                    apart = True
            if not apart:
                near[m] = k
                m += 1
        for g in range(g_n):
            for i in range(m):
                k = near[i]
                d2 = 0.0
                for j in range(3):
                    e = abs(xpos[f, g, j] - centre[k, j]) - half[k, j]
                    if e > 0.0:
                        d2 += e * e
                if d2 <= reach[g] * reach[g] and (
                    n_sub[g] == 1
                    or _sub_spheres_reach(xpos, xmat, f, g, k, centre, half, size, n_sub, sub_reach)
                ):
                    hit[r] = True
                    break
            if hit[r]:
                break
            for k in range(p_n):
                nx, ny, nz = normals[k, 0], normals[k, 1], normals[k, 2]
                h = (
                    (xpos[f, g, 0] - origins[k, 0]) * nx
                    + (xpos[f, g, 1] - origins[k, 1]) * ny
                    + (xpos[f, g, 2] - origins[k, 2]) * nz
                )
                if h - low[g] >= -depth:  # high above the plane: the test below is False
                    continue
                # the plane normal in the geom's frame: R^T n (xmat row-major)
                a0 = abs(xmat[f, g, 0] * nx + xmat[f, g, 3] * ny + xmat[f, g, 6] * nz)
                a1 = abs(xmat[f, g, 1] * nx + xmat[f, g, 4] * ny + xmat[f, g, 7] * nz)
                a2 = abs(xmat[f, g, 2] * nx + xmat[f, g, 5] * ny + xmat[f, g, 8] * nz)
                t = types[g]
                if t == _BOX:
                    ext = a0 * size[g, 0] + a1 * size[g, 1] + a2 * size[g, 2]
                elif t == _SPHERE:
                    ext = size[g, 0]
                elif t == _CAPSULE:
                    ext = a2 * size[g, 1] + size[g, 0]
                elif t == _CYLINDER:
                    ext = a2 * size[g, 1] + math.sqrt(max(1.0 - a2 * a2, 0.0)) * size[g, 0]
                else:
                    ext = rbound[g]
                if h - ext < -depth:
                    hit[r] = True
                    break
            if hit[r]:
                break
    return hit


@njit
def _sub_spheres_reach(xpos, xmat, f, g, k, centre, half, size, n_sub, sub_reach):
    """Whether one of the ``n_sub[g]`` spheres covering capsule ``g`` in frame ``f`` comes within
    ``sub_reach[g]`` of scene box ``k`` (world axes; metres). The spheres are centred on the
    capsule's axis (half-length ``size[g, 1]``, the geom's z axis: column 2 of ``xmat``) at
    the middles of ``n_sub`` equal pieces; each piece's points lie within its half-length of
    its centre, so the capsule lies within its radius plus that of some centre
    (:class:`StaticScene`)."""
    m = n_sub[g]
    h = size[g, 1]
    r2 = sub_reach[g] * sub_reach[g]
    for i in range(m):
        t = -h + (2 * i + 1) * h / m
        d2 = 0.0
        for j in range(3):
            e = abs(xpos[f, g, j] + t * xmat[f, g, 3 * j + 2] - centre[k, j]) - half[k, j]
            if e > 0.0:
                d2 += e * e
        if d2 <= r2:
            return True
    return False


def check_collisions(
    result_or_timeline, scene: str | Path | None = None, *, force: bool = False
) -> list[Contact]:
    """Every humanoid-vs-scene contact of a simulated cycle (or of a Timeline, or of a WalkPath
    played in ``scene``) by MuJoCo's collision detection (:func:`collision_report`).

    Args:
        result_or_timeline: a CycleResult simulated with ``keep_timeline=True``, a Timeline or
            a WalkPath.
        scene: the scene a WalkPath is played in (an MJCF file); not used otherwise.
        force: play a WalkPath planned in another scene (other obstacle geometry) instead of
            raising SceneError.

    Returns:
        The contacts in time order: time (s), body part, scene geom, depth (m), world point.

    Raises:
        MjwalkError: a result without a timeline, a WalkPath without a scene, or another type.
    """
    obj = result_or_timeline
    if not isinstance(obj, Timeline | WalkPath) and hasattr(obj, "timeline"):  # a CycleResult
        if obj.timeline is None:
            raise MjwalkError(
                "check_collisions: the result has no timeline; simulate with keep_timeline=True"
            )
        obj = obj.timeline
    if isinstance(obj, WalkPath):
        if scene is None:
            raise MjwalkError("check_collisions: a WalkPath needs the scene it is played in")
        obj.check_scene(shared_workplace(scene), force=force)
        obj = timeline_from_walk(obj, scene)
    if not isinstance(obj, Timeline):
        raise MjwalkError(f"check_collisions: cannot check a {type(obj).__name__}")
    return collision_report(obj)
