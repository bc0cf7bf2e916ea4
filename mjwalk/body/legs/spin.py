"""Spin turns: a grounded foot whose hip would rotate past its range as the pelvis turns turns
about its ball (or heel) instead (see :func:`spin_turns`). World frame, metres, radians.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from mjwalk._jit import njit
from mjwalk.body.humanoid import ROM_DEG, LegGeometry
from mjwalk.body.legs.curves import smoothstep, soft_excess1
from mjwalk.body.legs.footpivot import ball_offset, pivot_rows
from mjwalk.body.legs.ik import ik_lengths, leg_ik_world_row
from mjwalk.body.legs.ikcache import LegIKCache, leg_ik_world_cached_where
from mjwalk.body.legs.steps import SWING_TURNED, FootTracks

#: Spin turns (degrees): a grounded foot whose hip would rotate past its range less
#: ``SPIN_MARGIN`` turns about its ball by the excess (softly: from ``SPIN_SOFT`` before that),
#: its heel raised ``SPIN_HEEL`` over the last ``SPIN_RAMP`` of hip rotation before the turn.
SPIN_MARGIN, SPIN_SOFT, SPIN_HEEL, SPIN_RAMP = 2.0, 4.0, 4.0, 6.0

#: Rounds of a contact's turn corrected by its hip rotation's error (the hip follows the foot's
#: yaw one to one, so a round leaves only what the pivot's move changes).
SPIN_ROUNDS = 6

#: The hip rotation's range (radians, ``ROM_DEG``) and :data:`SPIN_MARGIN`, :data:`SPIN_SOFT`,
#: :data:`SPIN_RAMP` in radians, as ``np.deg2rad`` gives them.
_HIP_ROT = tuple(np.deg2rad(ROM_DEG["hip_rot"]))
_SPIN_RAD = tuple(np.deg2rad([SPIN_MARGIN, SPIN_SOFT, SPIN_RAMP]))


@dataclass(frozen=True)
class _Spin:
    """What every contact's spin turn shares: the pelvis track (``root`` (n, 3), ``yaw``
    (n,)), the leg geometry and the hip-rotation range ``lo``..``hi`` with the margins of
    :data:`SPIN_MARGIN` etc. (radians)."""

    root: np.ndarray
    yaw: np.ndarray
    geom: LegGeometry
    lo: float
    hi: float
    margin: float
    soft: float
    ramp: float


def spin_turns(
    feet: FootTracks, root, yaw, geom: LegGeometry, ik: dict[str, LegIKCache] | None = None
) -> dict:
    """Spin turns, in place: a grounded foot (stance, then pre-swing on the same footprint)
    whose hip rotation would pass its range as the pelvis turns (a sharp turning step) turns
    by the excess about the point it stands on, so that point stays put and the hip stays
    in range, instead of the clipped hip dragging the foot round:

    * flat or heel up: about the ball, the heel raised a little (:data:`SPIN_HEEL`, in
      smoothly before the turn starts, kept up until lift-off);
    * toes up after heel strike (the foot landed turned further than the hip allows): about
      the heel, the toes kept up a little until the turn is undone.

    The turned footprint carries into the swings before and after: the ankle, yaw and pitch
    offsets at toe-off fade out over the next swing (gone at 90 % of it, where the swing foot
    takes its landing heading), those at heel strike fade in over the second half of the
    swing before.

    Args:
        feet: both feet's tracks over the walk's n samples; ``ankle``, ``fyaw``, ``pitch``,
            ``toe`` and ``prints`` are updated in place.
        root: (n, 3) pelvis position, metres, world frame.
        yaw: (n,) pelvis yaw, radians from +x CCW.
        geom: the leg lengths.
        ik: per side ("l"/"r") an IK cache over the n samples that keeps the grounded
            samples' solutions (the leg's later corrections start from them); None: not kept.

    Returns:
        per side ("l"/"r") the largest turn of a footprint (radians) and the number of
        contacts that turned.
    """
    n = len(yaw)
    sp = _Spin(root, yaw, geom, *_HIP_ROT, *_SPIN_RAD)
    stats = {}
    root_c, yaw_c = np.ascontiguousarray(root, dtype=float), np.ascontiguousarray(yaw, dtype=float)
    for s_ in "lr":
        # the hip rotation of every grounded sample at once (the rows are independent: as
        # per contact), and where it passes its range; the other contacts are left as they are
        bufs = (
            (*ik[s_].buffers(n), *ik[s_].trig_buffers(n))
            if ik is not None
            else (np.full((n, 9), np.nan), np.empty((n, 6)), np.full((n, 2), np.nan),
                  np.empty((n, 7)))
        )  # fmt: skip
        r_all, up_all, down_all = _hip_rotation(feet, s_, root_c, yaw_c, sp, bufs)
        need_all = (up_all > 0) | (down_all > 0)
        worst, count = 0.0, 0
        if not need_all.any():  # no contact turns (most walks' feet: ~9 in 10 of a station's)
            stats[s_] = (worst, count)
            continue
        starts, ends = _contacts(feet.ground[s_], feet.prints[s_], n)
        # (the contacts with a sample that needs a turn, found at once by a running count)
        seen = np.concatenate([[0], np.cumsum(need_all)])
        after = np.asarray(ends, dtype=np.int64) + 1
        for i in np.flatnonzero(seen[after] > seen[starts]).tolist():
            j0, j1 = starts[i], ends[i]
            run = np.arange(j0, j1 + 1)
            hip = (r_all[run], up_all[run], down_all[run], need_all[run])
            turned, offsets = _turn_contact(feet, s_, run, hip, sp)
            worst, count = max(worst, turned), count + 1
            # the swings around start from / land on the turned foot; the offsets fade
            j_prev = ends[i - 1] if i else None
            j_next = starts[i + 1] if i + 1 < len(starts) else n
            _fade_offsets(feet, s_, offsets, (j_prev, j0, j1, j_next))
        stats[s_] = (worst, count)
    return stats


def _contacts(g: np.ndarray, prints: np.ndarray, n: int) -> tuple[np.ndarray, list[int]]:
    """First and last samples of each contact of a foot on the floor (``g`` (n,) bool) on one
    footprint of ``prints`` (n, 3): a contact ends before the next sample off the floor or on
    another print (compiled: :func:`_contact_bounds`)."""
    starts, ends = _contact_bounds(
        np.ascontiguousarray(g, dtype=np.bool_), np.ascontiguousarray(prints, dtype=float), n
    )
    return starts, ends.tolist()


@njit
def _contact_bounds(g, prints, n):
    """:func:`_contacts` in one pass: a contact starts on a grounded sample after one off the
    floor (or the first) or on a new print, and ends before the next sample off the floor or
    on a new print (or at the last sample); (starts, ends) as int arrays."""
    starts = np.empty(n, np.int64)
    ends = np.empty(n, np.int64)
    m = 0
    open_ = False
    for i in range(n):
        new_print = i == 0
        if i > 0:
            for k in range(3):
                if prints[i, k] != prints[i - 1, k]:
                    new_print = True
        if open_ and (new_print or not g[i]):
            ends[m - 1] = i - 1
            open_ = False
        if g[i] and not open_:
            starts[m] = i
            m += 1
            open_ = True
    if open_:
        ends[m - 1] = n - 1
    return starts[:m].copy(), ends[:m].copy()


def _hip_rotation(feet: FootTracks, s_: str, root_c, yaw_c, sp: _Spin, bufs):
    """The ``s_`` leg's hip rotation (n,) at every grounded sample and its soft excess over
    the range's top and under its bottom (:func:`_hip_rotation_excess`), radians; ``bufs``:
    an IK cache's inputs (n, 9) and angles (n, 6), updated on the grounded samples, and its
    yaws' sines and cosines (:func:`~mjwalk.body.legs.ik.yaw_trig_row`)."""
    n = len(yaw_c)
    lo, hi, margin, soft = sp.lo, sp.hi, sp.margin, sp.soft
    r_all, up_all, down_all = (np.zeros(n) for _ in range(3))
    _hip_rotation_excess(
        np.ascontiguousarray(feet.ground[s_], dtype=np.bool_),
        np.ascontiguousarray(feet.ankle[s_], dtype=float),
        np.ascontiguousarray(feet.fyaw[s_], dtype=float),
        np.ascontiguousarray(feet.pitch[s_], dtype=float),
        root_c,
        yaw_c,
        1.0 if s_ == "l" else -1.0,
        float(sp.geom.hip_y),
        *ik_lengths(sp.geom),
        float(hi - margin - soft),
        float(lo + margin + soft),
        float(soft / 2),
        r_all,
        up_all,
        down_all,
        *bufs,
    )
    return r_all, up_all, down_all


def _turn_contact(feet: FootTracks, s_: str, run: np.ndarray, hip, sp: _Spin):
    """Turn the ``s_`` foot over one contact (samples ``run``) by its hip rotation's excess
    (``hip``: rotation, excess up and down, need, each over ``run``), in place; returns the
    largest turn (radians) and the (ankle, yaw, pitch) offsets at its first and last
    samples."""
    geom = sp.geom
    sgn = 1.0 if s_ == "l" else -1.0
    heel = np.deg2rad(SPIN_HEEL)
    lo, hi, margin, soft, ramp = sp.lo, sp.hi, sp.margin, sp.soft, sp.ramp
    j0, j1 = run[0], run[-1]
    foot = np.array(feet.prints[s_][j0], dtype=float)
    p0 = feet.pitch[s_][run].copy()
    r0, up, down, need = hip
    target = r0 - (up - down)
    rise = np.maximum(
        smoothstep((r0 - (hi - margin - soft - ramp)) / ramp),
        smoothstep(((lo + margin + soft + ramp) - r0) / ramp),
    )
    # heel phase: from heel strike while the toes are up or, turned, kept up; then
    # the ball phase (the heel rises at the latest where the reference raises it)
    free = (p0 <= 0) & (rise == 0)
    k_h = 0
    if p0[0] > 0:
        k_h = min(int(np.argmax(np.r_[free, True])), int(np.argmax(np.r_[p0 < 0, True])))
    heel_ph = np.arange(len(run)) < k_h
    lift = np.maximum.accumulate(np.where(heel_ph, 0.0, rise))
    p = np.where(
        heel_ph,
        np.maximum(p0, heel * rise),
        np.where(lift > 0, np.minimum(p0, -heel * lift), p0),
    )
    # the hip rotation follows the foot's yaw one to one (-s): SPIN_ROUNDS rounds of the turn
    # corrected by the hip's error; without need the foot keeps its turn (relative to its
    # phase's pivot); then the turned footprints and their ankles (compiled: _spin_rounds)
    m = len(run)
    fp, a_ = np.empty((m, 3)), np.empty((m, 3))
    _spin_rounds(
        np.zeros(m), foot, k_h, np.ascontiguousarray(p, dtype=float),
        np.ascontiguousarray(need, dtype=np.bool_), np.ascontiguousarray(target, dtype=float),
        np.ascontiguousarray(sp.root[j0 : j1 + 1], dtype=float),
        np.ascontiguousarray(sp.yaw[j0 : j1 + 1], dtype=float), sgn, float(geom.hip_y),
        ik_lengths(geom), (ball_offset(geom), float(geom.foot_back), float(geom.ankle_height)),
        SPIN_ROUNDS, fp, a_,
    )  # fmt: skip
    turned = float(np.abs(fp[:, 2] - foot[2]).max())
    offsets = [
        (a_[k] - feet.ankle[s_][j], fp[k, 2] - foot[2], p[k] - p0[k])
        for k, j in ((0, j0), (-1, j1))
    ]
    feet.ankle[s_][run], feet.fyaw[s_][run], feet.prints[s_][run] = a_, fp[:, 2], fp
    feet.pitch[s_][run], feet.toe[s_][run] = p, -np.minimum(p, 0.0)
    return turned, offsets


def _fade_offsets(feet: FootTracks, s_: str, offsets, bounds) -> None:
    """Carry a turned contact's ``offsets`` (at its first and last samples) into the swings
    around it, in place: the last's fading out over the swing after (samples ``j1 + 1`` to
    ``j_next``, gone at :data:`SWING_TURNED`), the first's fading in over the second half of
    the swing before (after ``j_prev``, the previous contact's end). ``bounds``: (j_prev,
    j0, j1, j_next)."""
    j_prev, j0, j1, j_next = bounds
    for (d_a, d_y, d_p), sw, fade in (
        (offsets[1], np.arange(j1 + 1, j_next), lambda x: 1 - smoothstep(x / SWING_TURNED)),
        (
            offsets[0],
            np.arange((j_prev if j_prev is not None else j0) + 1, j0),
            lambda x: smoothstep(2 * x - 1),
        ),
    ):
        if not len(sw):
            continue
        x = (sw - sw[0] + 1) / (len(sw) + 1)
        w = fade(x)
        feet.ankle[s_][sw] += w[:, None] * d_a
        feet.fyaw[s_][sw] += w * d_y
        feet.pitch[s_][sw] += w * d_p
        feet.toe[s_][sw] -= w * d_p


@njit
def _hip_rotation_excess(ground, ankle, fyaw, pitch, root, yaw, sgn, hip_y, L1, L2, rmin, rmax,
                         top, bottom, w, rot, up, down, inputs, out, key, vals):  # fmt: skip
    """Per grounded sample (``ground`` (n,)): the leg's hip rotation ``rot`` (unclipped IK,
    :func:`~mjwalk.body.legs.ik.leg_ik_world_cached_where` with the cache's ``inputs`` (n, 9)
    and angles ``out`` (n, 6), yaws' sines and cosines ``key``, ``vals``) and how far it passes
    ``top`` and falls short of ``bottom``
    (``up``, ``down``: :func:`~mjwalk.body.legs.curves.soft_excess` over ``w``), radians; the
    other samples are left as they are."""
    leg_ik_world_cached_where(ground, ankle, fyaw, pitch, root, yaw, sgn, hip_y, L1, L2, rmin,
                              rmax, inputs, out, key, vals)  # fmt: skip
    for i in range(ground.shape[0]):
        if not ground[i]:
            continue
        rot[i] = out[i, 0]
        up[i] = soft_excess1(out[i, 0] - top, w)
        down[i] = soft_excess1(bottom - out[i, 0], w)


@njit
def _spin_prints_rows(spin, foot, k_h, ball, heel, fp):
    """The footprints ``fp`` (m, 3) of a foot on ``foot`` (x, y, yaw) turned by ``spin``
    (m,): about the heel (``heel``: its lever ahead of the ankle, < 0) over the first ``k_h``
    samples, then about the ball (``ball`` ahead of the ankle) from the print the heel phase
    ended on -- ``footpivot.spin_print``'s arithmetic, in its order, for each phase."""
    m = spin.shape[0]
    yaw = foot[2]
    px, py = foot[0] + heel * math.cos(yaw), foot[1] + heel * math.sin(yaw)
    for i in range(k_h):
        y = yaw + spin[i]
        fp[i, 0], fp[i, 1], fp[i, 2] = px - heel * math.cos(y), py - heel * math.sin(y), y
    bx, by, yaw, s0 = foot[0], foot[1], foot[2], 0.0
    if k_h:
        bx, by, yaw, s0 = fp[k_h - 1, 0], fp[k_h - 1, 1], fp[k_h - 1, 2], spin[k_h - 1]
    px, py = bx + ball * math.cos(yaw), by + ball * math.sin(yaw)
    for i in range(k_h, m):
        y = yaw + (spin[i] - s0)
        fp[i, 0], fp[i, 1], fp[i, 2] = px - ball * math.cos(y), py - ball * math.sin(y), y


@njit
def _spin_rounds(spin, foot, k_h, p, need, target, root, yaw, sgn, hip_y, lengths, sole, rounds,
                 fp, a_):  # fmt: skip
    """A contact's turn in ``rounds`` rounds, in place: each round the footprints turned by
    ``spin`` (m,) (:func:`_spin_prints_rows`: about the heel over the first ``k_h`` samples,
    then the ball), their ankles at the pitches ``p`` (``footpivot.pivot_rows``), the hip
    rotation there (``ik.leg_ik_world_row``, the pelvis at ``root`` (m, 3), ``yaw`` (m,))
    and the turn corrected by its error from ``target`` (times ``sgn``) where ``need``, else
    zero; then the final footprints into ``fp`` (m, 3) and their ankles into ``a_`` (m, 3).
    ``lengths``: the leg's ``ik_lengths``; ``sole``: the ball's and the heel's distances from
    the ankle and the ankle height, metres. The numbers of the NumPy rounds (``spin_print``,
    ``pivot_ankle``, ``leg_ik_world``) bit for bit; rows without need are not solved (their
    turn is zero whatever the hip does)."""
    L1, L2, rmin, rmax = lengths
    ball, back, ah = sole
    m = spin.shape[0]
    fy = np.empty(m)
    out = np.empty((m, 6))
    for _ in range(rounds):
        _spin_prints_rows(spin, foot, k_h, ball, -back, fp)
        pivot_rows(fp, p, ball, back, ah, a_)
        for i in range(m):
            fy[i] = fp[i, 2]
        for i in range(m):
            if need[i]:
                leg_ik_world_row(a_, fy, p, root, yaw, i, sgn, hip_y, L1, L2, rmin, rmax, out)
                spin[i] = spin[i] + sgn * (out[i, 0] - target[i])
            else:
                spin[i] = 0.0
    _spin_prints_rows(spin, foot, k_h, ball, -back, fp)
    pivot_rows(fp, p, ball, back, ah, a_)
