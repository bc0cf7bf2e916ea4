"""Handled parts in a timeline: scene geoms the hands pick, carry and put down, for videos.

A pick at site ``S`` takes the part lying there. The part is drawn with a scene geom: at the
start, the geom named ``S_geom`` (:data:`PART_GEOM_SUFFIX`; the shipped scenes name the screws,
the tool and the box so, e.g. ``rack2_screw1_geom`` under the site ``rack2_screw1``); later,
the geom a place or fasten left at ``S``. A pick without such a geom handles a part that is not
drawn, as before.

Frames (world: metres, z up):

* until the grasp the geom stays where the scene puts it;
* from the grasp -- the frame of the pick in which the grip point (the palm's centre; for a
  two-handed part, half way between the palms) comes nearest the site -- it moves rigidly
  with the hand body that took it (``hand_l`` / ``hand_r``), or, for a two-handed part, with
  the frame of both palms (origin half way between them, y along the line from the right palm
  to the left one, z up), from where it lies at the grasp: the hand's end, which the reach
  brings onto the part, holds it, so it does not jump onto the palm;
* from the release -- the frame of the place or fasten in which the grip point comes nearest
  its site -- it lies at that site as it lay at the site it was picked from: the same offset
  from the site, the same orientation (a fastening hand stops in front of the surface; the
  screw goes in).

A hand holding several parts (two screws) puts them down in the order it picked them. The
collision model is unchanged: the geoms are moved in the drawn scene only
(:func:`mjwalk.render.render_frames` and :func:`~mjwalk.render.render_video`).
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass
from typing import Literal

import mujoco
import numpy as np
from scipy.spatial.transform import Rotation

from mjwalk._jit import njit
from mjwalk.arms.chain import min_jerk
from mjwalk.body.humanoid import JointMap
from mjwalk.boundedmemo import Memo
from mjwalk.timeline.chainkin import chain_poses, supported

try:  # scipy's compiled quaternion functions behind Rotation (scipy >= 1.15's layout)
    from scipy.spatial.transform import _rotation_cy
except ImportError:  # another layout: Rotation's methods
    _rotation_cy = None

#: Name suffix of the scene geom that shows the part lying at a pick site.
PART_GEOM_SUFFIX = "_geom"


@dataclass
class PartTrack:
    """Where one scene geom is drawn in every frame of a timeline.

    Attributes:
        geom: the scene geom's name.
        pos: (F, 3) world position of the geom's centre, metres.
        mat: (F, 3, 3) world orientation (columns: the geom's axes).
        grasp: frame of the pick.
        release: frame of the place or fasten, or None (still in the hand at the end).
    """

    geom: str
    pos: np.ndarray
    mat: np.ndarray
    grasp: int
    release: int | None


@dataclass
class Handling:
    """One reach that handles a part (a pick, place or fasten) as :func:`part_tracks` needs
    it: ``part`` "take" (the hand takes the part at the site) or "put" (it puts down the part
    it took first), the target ``site``, the ``hand`` ("left", "right" or "both") and its
    frames ``[start, end)``. The cycle's task kinds table says which kinds take or put."""

    part: Literal["take", "put"]
    site: str
    hand: str
    start: int
    end: int


def hand_poses(
    model: mujoco.MjModel,
    jm: JointMap,
    qpos: np.ndarray,
    data: mujoco.MjData | None = None,
    frames: np.ndarray | None = None,
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The hands' poses by forward kinematics (``mj_kinematics``), once per distinct pose: a
    frame whose pose is bit-for-bit its predecessor's copies its results (a hold repeats one
    pose), which are then the same bits. Where :func:`mjwalk.timeline.chainkin.supported`
    holds, MuJoCo's arithmetic runs compiled on the hands' chain alone (the same bits, a
    fraction of the cost); a frame it cannot match, and any other model, calls
    ``mj_kinematics``.

    Args:
        model: the compiled scene with the humanoid.
        jm: the humanoid's joint map.
        qpos: (F, nq) poses (or one (nq,)).
        data: an MjData of ``model`` to compute in (a new one when None; its pose is the last
            frame's afterwards).
        frames: (F,) bool, the frames to compute (all when None); the others are NaN.

    Returns:
        ``(pos, mat, palm)``: (F, 2, 3) world positions (m) and (F, 2, 3, 3) orientations of the
        hand bodies (left, right), and (F, 2, 3) their palms' centres (each hand's first geom).
    """
    data = mujoco.MjData(model) if data is None else data
    bodies = [model.body(f"{jm.prefix}hand_{p}").id for p in ("l", "r")]
    palms = [int(np.flatnonzero(model.geom_bodyid == b)[0]) for b in bodies]
    qpos = np.atleast_2d(qpos)
    n = len(qpos)
    need = np.ones(n, dtype=bool) if frames is None else np.asarray(frames, dtype=bool)
    todo = _distinct(qpos, need)
    k = len(todo)
    xpos, xmat, gpos = np.empty((k, 2, 3)), np.empty((k, 2, 9)), np.empty((k, 2, 3))
    slow = todo
    hands, centres = np.array(bodies), np.array(palms)
    if k and supported(model, hands, centres):
        # MuJoCo's arithmetic on the hands' chain alone, compiled (the same bits)
        xpos, xmat, gpos, exact = chain_poses(model, qpos, todo, hands, centres)
        slow = todo[~exact]
    q = data.qpos
    for i, f in zip(np.searchsorted(todo, slow).tolist(), slow.tolist(), strict=True):
        q[:] = qpos[f]
        mujoco.mj_kinematics(model, data)
        xpos[i], xmat[i], gpos[i] = data.xpos[bodies], data.xmat[bodies], data.geom_xpos[palms]
    if n and (len(slow) == 0 or slow[-1] != n - 1):  # leave data at the last frame's pose
        q[:] = qpos[-1]
        mujoco.mj_kinematics(model, data)
    # each needed frame takes the results of the last computed frame at or before it
    pos, mat, palm = np.empty((n, 2, 3)), np.empty((n, 2, 3, 3)), np.empty((n, 2, 3))
    _spread(need, todo, xpos, xmat, gpos, pos, mat.reshape(n, 2, 9), palm)
    return pos, mat, palm


def _distinct(qpos: np.ndarray, need: np.ndarray) -> np.ndarray:
    """The frames of ``need`` (F,) bool whose pose ``qpos`` (F, nq) is not bit-for-bit that of
    the frame before, when that frame is needed too (sorted ints)."""
    bits = np.ascontiguousarray(qpos, dtype=np.float64).view(np.uint64)
    return np.flatnonzero(_fresh(bits, np.ascontiguousarray(need, dtype=np.bool_)))


@njit
def _fresh(bits, need):
    """(F,) bool: ``need`` and not the bits ``bits`` (F, nq) of the frame before, when that
    frame is needed (row by row, stopping at the first word that differs)."""
    n, m = bits.shape
    out = need.copy()
    for f in range(1, n):
        if not (need[f] and need[f - 1]):
            continue
        same = True
        for i in range(m):
            if bits[f, i] != bits[f - 1, i]:
                same = False
                break
        out[f] = not same
    return out


@njit
def _spread(need, todo, xpos, xmat, gpos, pos, mat, palm):
    """Fill ``pos`` (F, 2, 3), ``mat`` (F, 2, 9) and ``palm`` (F, 2, 3): a frame of ``need``
    (F,) bool takes the rows ``xpos``, ``xmat``, ``gpos`` of the last frame of ``todo`` (K,)
    at or before it (copied), the others NaN."""
    j = -1
    for f in range(need.shape[0]):
        while j + 1 < todo.shape[0] and todo[j + 1] <= f:
            j += 1
        for s in range(2):
            for i in range(3):
                pos[f, s, i] = xpos[j, s, i] if need[f] else np.nan
                palm[f, s, i] = gpos[j, s, i] if need[f] else np.nan
            for i in range(9):
                mat[f, s, i] = xmat[j, s, i] if need[f] else np.nan


#: A grip point moving less than this (m) from where it was at the release is holding still:
#: the part goes onto its site over those frames. Millimetres: the hold is one repeated pose.
HOLD_STILL = 1e-3


def _slerp(a: np.ndarray, b: np.ndarray, w: np.ndarray) -> np.ndarray:
    """Rotation matrices (n, 3, 3) from ``a`` to ``b`` (3, 3) at shares ``w`` (n,) in [0, 1]
    (SLERP): ``a`` composed with the rotation vector of ``a^-1 b`` scaled by ``w``, the
    operations scipy's ``Slerp([0, 1], ...)(w)`` makes (its share ``(w - 0) / 1`` is ``w``),
    without its per-call set-up (a third of the time; tests compare the two bit for bit).
    With scipy's compiled quaternion functions (:data:`_QUATS`) they are called on the arrays
    directly, as :class:`~scipy.spatial.transform.Rotation`'s methods call them (no
    ``Rotation`` objects: two thirds of the rest)."""
    w = np.asarray(w, dtype=float)
    cy = _quat_functions()
    if cy is not None:
        return _slerp_cy(cy, a, b, w)
    return _slerp_rotation(a, b, w)


def _slerp_cy(cy, a: np.ndarray, b: np.ndarray, w: np.ndarray) -> np.ndarray:
    """:func:`_slerp` by scipy's compiled quaternion functions ``cy`` on the arrays."""
    q = cy.from_matrix(np.stack([a, b]), assume_valid=False)
    # Rotation's product: compose_quat, then its constructor's normalisation
    rel = cy.from_quat(cy.compose_quat(cy.inv(q[:1]), q[1:]), normalize=True, copy=False)
    step = cy.from_rotvec(cy.as_rotvec(rel, degrees=False) * w[:, None], degrees=False)
    if _compose_agrees(cy):  # the same products, compiled (scipy's took 1.2 us a frame)
        both = _compose_rows(np.asarray(q[:1]), np.asarray(step))
    else:
        both = cy.compose_quat(np.take(q, np.zeros(len(w), dtype=np.intp), axis=0), step)
    return np.asarray(cy.as_matrix(cy.from_quat(both, normalize=True, copy=False)))


@njit
def _compose_rows(p, q):
    """(n, 4) products ``p * q`` of scalar-last quaternions, ``p`` (1, 4) times each row of
    ``q`` (n, 4): the vector part ``p_w q_v + q_w p_v + p_v x q_v``, the scalar ``p_w q_w -
    p_v . q_v``, summed left to right (scipy's ``compose_quat`` gives these bits:
    :func:`_compose_agrees`)."""
    n = q.shape[0]
    out = np.empty((n, 4))
    p0, p1, p2, p3 = p[0, 0], p[0, 1], p[0, 2], p[0, 3]
    for i in range(n):
        q0, q1, q2, q3 = q[i, 0], q[i, 1], q[i, 2], q[i, 3]
        c0 = p1 * q2 - p2 * q1
        c1 = p2 * q0 - p0 * q2
        c2 = p0 * q1 - p1 * q0
        out[i, 0] = p3 * q0 + q3 * p0 + c0
        out[i, 1] = p3 * q1 + q3 * p1 + c1
        out[i, 2] = p3 * q2 + q3 * p2 + c2
        out[i, 3] = p3 * q3 - p0 * q0 - p1 * q1 - p2 * q2
    return out


#: Seeded quaternion rows on which :func:`_compose_rows` is compared with scipy's
#: ``compose_quat`` once per process (another operation order differs in the last bit of about
#: 30 % of rows: 134-188 of these 512 for three other orders; 512 rows miss it with odds far
#: below 1e-9; scipy's compose of 4096 took some 5 ms of the first animated cycle).
COMPOSE_CHECK_ROWS = 512
_COMPOSE: list = []  # (scipy's functions, whether _compose_rows gives their bits)


def _compose_agrees(cy) -> bool:
    """Whether :func:`_compose_rows` gives ``cy.compose_quat``'s bits (of a quaternion
    repeated, times :data:`COMPOSE_CHECK_ROWS` seeded ones), checked once per process."""
    for seen, agrees in _COMPOSE:
        if seen is cy:
            return agrees
    rng = np.random.default_rng(2)
    p, q = rng.normal(size=(1, 4)), rng.normal(size=(COMPOSE_CHECK_ROWS, 4))
    try:
        want = np.asarray(cy.compose_quat(np.repeat(p, len(q), axis=0), q), dtype=float)
        agrees = bool(np.array_equal(_compose_rows(p, q).view(np.uint64), want.view(np.uint64)))
    except Exception:  # another signature: scipy's own serves
        agrees = False
    _COMPOSE.append((cy, agrees))
    return agrees


def _slerp_rotation(a: np.ndarray, b: np.ndarray, w: np.ndarray) -> np.ndarray:
    """:func:`_slerp` by :class:`~scipy.spatial.transform.Rotation`'s public methods."""
    r = Rotation.from_matrix(np.stack([a, b]))
    turn = (r[:1].inv() * r[1:]).as_rotvec()
    return (
        r[np.zeros(len(w), dtype=np.intp)] * Rotation.from_rotvec(turn * w[:, None])
    ).as_matrix()


#: scipy's compiled quaternion functions (``from_matrix``, ``inv``, ``compose_quat``,
#: ``from_quat``, ``as_rotvec``, ``from_rotvec``, ``as_matrix``), the ones
#: :class:`~scipy.spatial.transform.Rotation` calls on NumPy arrays, for :func:`_slerp`; None
#: when this scipy has no such module (:func:`_slerp` goes through ``Rotation``).
_QUAT_FUNCTIONS = "from_matrix inv compose_quat from_quat as_rotvec from_rotvec as_matrix"
_QUATS: list = []  # [the functions, or None], decided by the first _quat_functions call


def _quat_functions():
    """scipy's compiled quaternion functions when this scipy has them and they give
    :func:`_slerp_rotation`'s numbers bit for bit on 16 seeded rotation pairs (checked once per
    process: a private module may change its arguments or arithmetic with any scipy release);
    otherwise None (``Rotation``'s public methods serve)."""
    if not _QUATS:
        cy = _rotation_cy
        if cy is not None and all(hasattr(cy, n) for n in _QUAT_FUNCTIONS.split()):
            rng = np.random.default_rng(1)
            w = np.linspace(0.0, 1.0, 7)
            try:
                for _ in range(16):
                    a, b = Rotation.from_rotvec(rng.normal(0.0, 1.5, (2, 3))).as_matrix()
                    if not np.array_equal(_slerp_cy(cy, a, b, w), _slerp_rotation(a, b, w)):
                        cy = None
                        break
            except Exception:  # another signature: Rotation serves
                cy = None
        else:
            cy = None
        _QUATS.append(cy)
    return _QUATS[0]


def palms_frame(palm: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """The frame of a two-handed grip: half way between the palms, y from the right palm to the
    left one (horizontal), z up, x = y x z.

    Args:
        palm: (F, 2, 3) palm centres (left, right), world metres.

    Returns:
        ``(origin, axes)``: (F, 3) origins, metres, and (F, 3, 3) axes as columns.
    """
    y = palm[:, 0] - palm[:, 1]
    y[:, 2] = 0.0
    y /= np.maximum(np.linalg.norm(y, axis=1, keepdims=True), 1e-9)
    z = np.broadcast_to([0.0, 0.0, 1.0], y.shape)
    x = np.cross(y, z)
    return palm.mean(axis=1), np.stack([x, y, z], axis=2)


def _needed(handlings: Sequence[Handling], lying: set[str], n: int) -> np.ndarray:
    """(n,) bool: the frames whose hand poses :func:`part_tracks` reads -- every handling's
    frames, and a drawn part's from the start of the handling that takes it to the end of the
    one that puts it down (or the timeline's end): it is held in between. The same order of
    takes and puts per hand as :func:`part_tracks`; ``lying``: the sites with a part."""
    need = np.zeros(n, dtype=bool)
    held: dict[str, list[int | None]] = {"left": [], "right": [], "both": []}
    lying = set(lying)
    for h in handlings:
        lo, hi = max(h.start, 0), min(max(h.end, h.start + 1), n)
        if lo >= hi:
            continue
        need[lo:hi] = True
        if h.part == "take":
            held[h.hand].append(lo if h.site in lying else None)
            lying.discard(h.site)
        elif held[h.hand]:
            taken = held[h.hand].pop(0)
            if taken is not None:
                need[taken:hi] = True
                lying.add(h.site)
    for taken in (t for side in held.values() for t in side if t is not None):
        need[taken:] = True
    return need


def _lying_parts(model: mujoco.MjModel) -> dict[str, int]:
    """``{site name: id of the geom lying there}`` of the sites with a part geom
    (:data:`PART_GEOM_SUFFIX`), kept per model (names do not change after compiling; reading
    them costs about 0.5 ms a call). A copy: the caller's to change."""
    return dict(_LYING.get(model, lambda: _find_lying(model)))


def _find_lying(model: mujoco.MjModel) -> dict[str, int]:
    """:func:`_lying_parts` made: the model's geom and site names read once."""
    names = {model.geom(g).name: g for g in range(model.ngeom)}
    sites = (model.site(s).name for s in range(model.nsite))
    return {s: names[s + PART_GEOM_SUFFIX] for s in sites if s + PART_GEOM_SUFFIX in names}


#: :func:`_lying_parts` per model (a cycle's operators: a few models).
_LYING: Memo[mujoco.MjModel, dict[str, int]] = Memo(limit=8)


def _releases(
    handlings: Sequence[Handling], lying: set[str], grips: list[tuple[int, int, int] | None]
) -> dict[int, int]:
    """``{take's index: the frame its part is put down}`` for the takes of a drawn part that
    a later put releases: the same order of takes and puts per hand as :func:`part_tracks`
    (``lying``: the sites with a part; ``grips``: each handling's ``(lo, hi, frame)`` or
    None). From that frame on the put writes the whole track: what the take writes after
    it is never read."""
    held: dict[str, list[int | None]] = {"left": [], "right": [], "both": []}
    lying = set(lying)
    out = {}
    for i, (h, grip) in enumerate(zip(handlings, grips, strict=True)):
        if grip is None:
            continue
        if h.part == "take":
            held[h.hand].append(i if h.site in lying else None)
            lying.discard(h.site)
        elif held[h.hand]:
            taken = held[h.hand].pop(0)
            if taken is not None:
                out[taken] = grip[2]
                lying.add(h.site)
    return out


def part_tracks(
    model: mujoco.MjModel,
    jm: JointMap,
    qpos: np.ndarray,
    handlings: Sequence[Handling],
    data: mujoco.MjData | None = None,
) -> list[PartTrack]:
    """The tracks of the scene geoms handled in a timeline (see the module docstring).

    Args:
        model: the compiled scene with the humanoid.
        jm: the humanoid's joint map.
        qpos: (F, nq) poses of the timeline.
        handlings: the picks, places and fastens, in time order.
        data: an MjData of ``model`` to compute in (a new one when None).

    Returns:
        One :class:`PartTrack` per handled part.
    """
    lying = _lying_parts(model)  # site -> geom lying there
    if not lying or not any(h.part == "take" and h.site in lying for h in handlings):
        return []
    n = len(qpos)
    data = mujoco.MjData(model) if data is None else data
    # the scene's geoms and sites are welded to the world: any pose's kinematics places them
    need = _needed(handlings, set(lying), n)
    hand_pos, hand_mat, palm = hand_poses(model, jm, qpos, data, need)
    both_pos = both_mat = palm[:, 0]  # (read only for a two-handed grip)
    if any(h.hand not in ("left", "right") for h in handlings):
        both_pos, both_mat = palms_frame(palm)
    sites = [data.site_xpos[model.site(h.site).id] for h in handlings]
    grips: list[tuple[int, int, int] | None] = []
    for h, site_pos in zip(handlings, sites, strict=True):
        lo, hi = max(h.start, 0), min(max(h.end, h.start + 1), n)
        if lo >= hi:  # no frame of this task in the timeline
            grips.append(None)
            continue
        side = {"left": 0, "right": 1}.get(h.hand)
        grip = palm[lo:hi, side] if side is not None else both_pos[lo:hi]
        grips.append((lo, hi, lo + int(np.argmin(np.linalg.norm(grip - site_pos, axis=1)))))
    release = _releases(handlings, set(lying), grips)
    held: dict[str, list[int | None]] = {"left": [], "right": [], "both": []}
    tracks: dict[int, PartTrack] = {}
    lay: dict[int, tuple[np.ndarray, np.ndarray]] = {}  # offset from its site, orientation
    for i, (h, site_pos, span) in enumerate(zip(handlings, sites, grips, strict=True)):
        if span is None:
            continue
        lo, hi, f = span
        side = {"left": 0, "right": 1}.get(h.hand)
        if side is not None:
            origin, axes = hand_pos[:, side], hand_mat[:, side]
        else:
            origin, axes = both_pos, both_mat
        if h.part == "take":
            g = lying.pop(h.site, None)
            held[h.hand].append(g)
            if g is None:
                continue
            track = tracks.get(g)
            if track is None:
                pos = np.repeat(data.geom_xpos[g][None], n, axis=0)
                mat = np.repeat(data.geom_xmat[g].reshape(1, 3, 3), n, axis=0)
                track = tracks[g] = PartTrack(model.geom(g).name, pos, mat, f, None)
            lay[g] = (track.pos[f] - site_pos, track.mat[f].copy())
            track.grasp, track.release = f, None
            # its pose in the holding frame kept from the grasp on, where it lies then: the
            # hand's end, not its palm, comes onto the part (the palm centre stops 15-18 cm
            # from a screw's site; snapping the part onto it jumped it that far in one frame);
            # up to its release, from where the put writes the track (each frame's numbers
            # are those of the whole tail's products)
            end = max(release.get(i, n - 1) + 1, f)
            rel_mat = axes[f].T @ track.mat[f]
            rel_pos = axes[f].T @ (track.pos[f] - origin[f])
            track.pos[f:end] = origin[f:end] + np.einsum("fij,j->fi", axes[f:end], rel_pos)
            track.mat[f:end] = axes[f:end] @ rel_mat
        elif held[h.hand]:  # put down (place / fasten): the first part this hand took
            g = held[h.hand].pop(0)
            if g is None:
                continue
            grip = palm[lo:hi, side] if side is not None else both_pos[lo:hi]
            _put_down(tracks[g], lay[g], grip[f - lo :], f, site_pos)
            lying[h.site] = g
    return list(tracks.values())


def _put_down(
    track: PartTrack, lay: tuple[np.ndarray, np.ndarray], grip: np.ndarray, f: int, site_pos
) -> None:
    """Put ``track``'s part onto its site (world ``site_pos``, metres) from frame ``f`` on, as
    it lay where it was taken (``lay``: its offset from that site and its orientation), the
    grip point ``grip`` (k, 3) from frame ``f`` to the handling's end."""
    offset, mat0 = lay
    # while the hand holds still at the site (a fastening hand stops in front of the
    # surface) the part goes from the hand onto the site: a screw driven in, not
    # jumping there in one frame
    still = np.linalg.norm(grip - grip[0], axis=1) < HOLD_STILL
    n_in = int(np.argmin(still)) if not still.all() else len(still)
    if n_in > 1:
        w = min_jerk(np.linspace(0.0, 1.0, n_in))[:, None]
        track.pos[f : f + n_in] = (1 - w) * track.pos[f] + w * (site_pos + offset)
        track.mat[f : f + n_in] = _slerp(track.mat[f], mat0, w[:, 0])
    track.pos[f + max(n_in - 1, 0) :] = site_pos + offset
    track.mat[f + max(n_in - 1, 0) :] = mat0
    track.release = f
