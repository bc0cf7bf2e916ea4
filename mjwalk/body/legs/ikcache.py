"""The leg IK over the same samples again and again (the leg synthesis's correction loops): a
sample whose inputs are bit for bit those of the previous call keeps its angles
(:class:`LegIKCache`), and the sines and cosines of a sample's pelvis and foot yaws, which those
loops leave unchanged, are kept per sample (:func:`yaw_trig_row`). The numbers are those of
:func:`~mjwalk.body.legs.ik.leg_ik_world`, bit for bit. World frame, metres, radians.
"""

from __future__ import annotations

import functools
import math

import numpy as np

from mjwalk._jit import njit, njit_inline
from mjwalk.body.humanoid import ROM_DEG, LegGeometry
from mjwalk.body.legs.footpivot import ball_offset
from mjwalk.body.legs.ik import (
    LEG_JOINTS,
    foot_boxes,
    foot_lowest_row,
    generic_joint,
    hip_rel,
    ik_lengths,
    leg_ik_cs,
    named_angles,
)
from mjwalk.conventions import side_of_prefix


class LegIKCache:
    """:func:`leg_ik_world` for one leg over the same samples again and again (the synthesis's
    correction loops): a sample whose inputs (ankle target, foot yaw and pitch, pelvis
    position and yaw) are bit for bit those of the previous call keeps its angles, the others
    are solved again; the results are those of :func:`leg_ik_world`."""

    def __init__(self, side: str, geom: LegGeometry):
        """An empty cache (the first call solves every sample).

        Args:
            side: "l" or "r".
            geom: the leg lengths.
        """
        self.side, self.geom = side, geom
        self.inputs: np.ndarray | None = None  # (n, 9) of the previous call
        self.out: np.ndarray | None = None  # (n, 6) its angles
        self.flex: tuple[np.ndarray, np.ndarray] | None = None  # see flex_buffers
        self.trig: tuple[np.ndarray, np.ndarray] | None = None  # see trig_buffers

    def buffers(self, n: int) -> tuple[np.ndarray, np.ndarray]:
        """The previous call's inputs and angles, for compiled callers of
        ``leg_ik_world_cached`` (new ones, every row to be solved, for another ``n``).

        Args:
            n: the number of samples.

        Returns:
            inputs (n, 9) (ankle, foot yaw, pitch, root, yaw per row) and angles (n, 6), radians.
        """
        if self.inputs is None or self.out is None or len(self.inputs) != n:
            self.inputs = np.full((n, 9), np.nan)  # nan: never equal, every row is solved
            self.out = np.empty((n, 6))
        return self.inputs, self.out

    def flex_buffers(self, n: int) -> tuple[np.ndarray, np.ndarray]:
        """A second cache beside :meth:`buffers` for compiled callers that need only the ankle
        flexion (:func:`~mjwalk.body.legs.pitchfit.fit_ankle_range`'s rounds), over the same
        samples (new ones, every row to be solved, for another ``n``).

        Args:
            n: the number of samples.

        Returns:
            inputs (n, 9) (as :meth:`buffers`') and the ankle flexions (n,) they give, radians.
        """
        if self.flex is None or len(self.flex[1]) != n:
            self.flex = (np.full((n, 9), np.nan), np.empty(n))
        return self.flex

    def trig_buffers(self, n: int) -> tuple[np.ndarray, np.ndarray]:
        """The yaws' sines and cosines kept per sample for the compiled solvers
        (:func:`yaw_trig_row`; new ones, none kept, for another ``n``).

        Args:
            n: the number of samples.

        Returns:
            the yaws they were taken of (n, 2) and the numbers (n, 7).
        """
        if self.trig is None or len(self.trig[0]) != n:
            self.trig = (np.full((n, 2), np.nan), np.empty((n, 7)))
        return self.trig

    def share_trig(self, other: LegIKCache, foot_yaw, other_yaw, yaw) -> None:
        """Fill both legs' yaw sines and cosines (:meth:`trig_buffers`) for their feet's
        headings ``foot_yaw`` and ``other_yaw`` (n,) under the pelvis yaws ``yaw`` (n,) in one
        compiled pass that takes the pelvis yaw's four once per sample for both legs: the
        numbers :func:`yaw_trig_row` keeps (a row whose yaws change later is taken again).

        Args:
            other: the other leg's cache over the same samples.
            foot_yaw: (n,) this leg's foot headings, radians from +x CCW.
            other_yaw: (n,) the other leg's.
            yaw: (n,) pelvis yaws, radians from +x CCW.
        """
        n = len(yaw)
        _trig_pair(
            np.ascontiguousarray(foot_yaw, dtype=float),
            np.ascontiguousarray(other_yaw, dtype=float),
            np.ascontiguousarray(yaw, dtype=float),
            *self.trig_buffers(n),
            *other.trig_buffers(n),
        )

    def __call__(self, ankle, foot_yaw, pitch, root, yaw) -> dict:
        ankle = np.ascontiguousarray(ankle, dtype=float)
        self.buffers(len(ankle))
        assert self.out is not None
        sgn = 1.0 if self.side == "l" else -1.0
        leg_ik_world_cached(
            ankle,
            np.ascontiguousarray(foot_yaw, dtype=float),
            np.ascontiguousarray(pitch, dtype=float),
            np.ascontiguousarray(root, dtype=float),
            np.ascontiguousarray(yaw, dtype=float),
            sgn,
            float(self.geom.hip_y),
            *ik_lengths(self.geom),
            self.inputs,
            self.out,
            *self.trig_buffers(len(ankle)),
        )
        return named_angles(self.out.copy(), side_of_prefix(self.side), clip=False)

    def floor_round(self, ankle, foot_yaw, pitch, toe, root, yaw) -> tuple[np.ndarray, np.ndarray]:
        """One round of the synthesis's floor clearance for this leg in one compiled call:
        the leg solved as :meth:`__call__` solves it (its angles kept in :attr:`out`,
        unclipped), its :data:`~mjwalk.body.legs.ik.LEG_JOINTS` angles (the toes' from ``toe``)
        clipped to the humanoid's ranges as ``np.clip`` clips them, and the foot's lowest point
        above the floor (the hip's height plus :func:`~mjwalk.body.legs.ik.foot_lowest`) --
        the numbers of those calls, bit for bit.

        Args:
            ankle: (n, 3) ankle targets, metres, world frame.
            foot_yaw: (n,) foot headings, radians from +x CCW.
            pitch: (n,) foot pitches to the floor, radians, + toes up.
            toe: (n,) toe angles, radians.
            root: (n, 3) pelvis (root) positions, metres.
            yaw: (n,) pelvis yaws, radians from +x CCW.

        Returns:
            the clipped angles (7, n) in :data:`~mjwalk.body.legs.ik.LEG_JOINTS` order, radians,
            and the foot's lowest point (n,), metres above the floor (z = 0).
        """
        ankle = np.ascontiguousarray(ankle, dtype=float)
        n = len(ankle)
        self.buffers(n)
        geom = self.geom
        foot, toes = foot_boxes(geom)
        lo, hi = _leg_ranges()
        q, low = np.empty((7, n)), np.empty(n)
        _floor_rows(
            ankle,
            np.ascontiguousarray(foot_yaw, dtype=float),
            np.ascontiguousarray(pitch, dtype=float),
            np.ascontiguousarray(toe, dtype=float),
            np.ascontiguousarray(root, dtype=float),
            np.ascontiguousarray(yaw, dtype=float),
            1.0 if self.side == "l" else -1.0,
            float(geom.hip_y),
            *ik_lengths(geom),
            self.inputs,
            self.out,
            *self.trig_buffers(n),
            lo,
            hi,
            (foot, toes, ball_offset(geom), geom.ankle_height),
            q,
            low,
        )
        return q, low


@functools.lru_cache(maxsize=1)
def _leg_ranges() -> tuple[np.ndarray, np.ndarray]:
    """The humanoid's ranges (radians) of the :data:`~mjwalk.body.legs.ik.LEG_JOINTS`, lower
    and upper bounds (7,) each, as ``np.deg2rad`` gives them (kept: not to be changed)."""
    rad = np.array([np.deg2rad(ROM_DEG[generic_joint(k.format("l"))]) for k in LEG_JOINTS])
    return np.ascontiguousarray(rad[:, 0]), np.ascontiguousarray(rad[:, 1])


@njit_inline
def clip1(x, lo, hi):
    """``np.clip`` of one float with float bounds, as NumPy 2 clips: a NaN stays, and a value
    equal to a bound stays itself (``-0.0`` clipped to 0.0..1.0 is ``-0.0``; tested against
    ``np.clip``, signed zeros, NaN and infinities included).

    Args:
        x: the value (any unit, e.g. radians).
        lo: the lower bound, same unit.
        hi: the upper bound, same unit.

    Returns:
        ``x`` clipped to ``lo``..``hi``.
    """
    t = x if (x != x or x >= lo) else lo
    return t if (t != t or t <= hi) else hi


@njit
def _floor_rows(ankle, foot_yaw, pitch, toe, root, yaw, sgn, hip_y, L1, L2, rmin, rmax, inputs,
                out, key, vals, lo, hi, feet, q, low):  # fmt: skip
    """:meth:`LegIKCache.floor_round` per row: :func:`leg_ik_world_cached`'s row, the seven
    angles clipped to ``lo``..``hi`` into ``q`` (7, n), the lowest point of the foot's boxes
    (``feet``: sole and toes corners, the ball's offset, the ankle height) above the floor into
    ``low`` (the hip's height as ``ik.hip_world`` gives it, plus
    ``ik.foot_lowest``'s row)."""
    foot, toes, ball, ah = feet
    off = sgn * hip_y
    for i in range(ankle.shape[0]):
        _update_row(ankle, foot_yaw, pitch, root, yaw, i, sgn, hip_y, L1, L2, rmin, rmax, inputs,
                    out, key, vals)  # fmt: skip
        for k in range(6):
            q[k, i] = clip1(out[i, k], lo[k], hi[k])
        q[6, i] = clip1(toe[i], lo[6], hi[6])
        fl = foot_lowest_row(q[0, i], q[1, i], q[2, i], q[3, i], q[4, i], q[5, i], q[6, i], sgn,
                             L1, L2, foot, toes, ball, ah)  # fmt: skip
        low[i] = (root[i, 2] + off * 0.0) + fl


@njit
def leg_ik_world_cached(
    ankle, foot_yaw, pitch, root, yaw, sgn, hip_y, L1, L2, rmin, rmax, inputs, out, key, vals
):
    """:func:`_leg_ik_world_rows` for the rows whose inputs differ from ``inputs``, which
    are updated; the other rows of ``out`` are kept.

    Args:
        ankle: (n, 3) ankle targets, metres, world frame.
        foot_yaw: (n,) foot headings, radians from +x CCW.
        pitch: (n,) foot pitches to the floor, radians, + toes up.
        root: (n, 3) pelvis (root) positions, metres.
        yaw: (n,) pelvis yaws, radians from +x CCW.
        sgn: +1 for the left leg, -1 for the right.
        hip_y: the hip joint centre's lateral offset from the pelvis centre, metres.
        L1: thigh length, metres.
        L2: shank length, metres.
        rmin: the shortest hip-to-ankle distance, metres (:func:`ik_lengths`).
        rmax: the longest hip-to-ankle distance, metres.
        inputs: (n, 9) the inputs of the previous call per row, updated.
        out: (n, 6) unclipped angles, radians, updated where the inputs changed.
        key: (n, 2) and
        vals: (n, 7) the yaws' sines and cosines kept per row (:func:`yaw_trig_row`).
    """
    for i in range(ankle.shape[0]):
        _update_row(ankle, foot_yaw, pitch, root, yaw, i, sgn, hip_y, L1, L2, rmin, rmax, inputs,
                    out, key, vals)  # fmt: skip


@njit
def leg_ik_world_cached_where(
    rows, ankle, foot_yaw, pitch, root, yaw, sgn, hip_y, L1, L2, rmin, rmax, inputs, out, key,
    vals,
):  # fmt: skip
    """:func:`leg_ik_world_cached` on the rows where ``rows`` is True only: the other rows
    keep their ``inputs`` and ``out`` as a pair (a later call solves them if they changed).

    Args:
        rows: (n,) bool, the rows to bring up to date.
        ankle: (n, 3) ankle targets, metres, world frame.
        foot_yaw: (n,) foot headings, radians from +x CCW.
        pitch: (n,) foot pitches to the floor, radians, + toes up.
        root: (n, 3) pelvis (root) positions, metres.
        yaw: (n,) pelvis yaws, radians from +x CCW.
        sgn: +1 for the left leg, -1 for the right.
        hip_y: the hip joint centre's lateral offset from the pelvis centre, metres.
        L1: thigh length, metres.
        L2: shank length, metres.
        rmin: the shortest hip-to-ankle distance, metres (:func:`ik_lengths`).
        rmax: the longest hip-to-ankle distance, metres.
        inputs: (n, 9) the inputs of the previous call per row, updated on ``rows``.
        out: (n, 6) unclipped angles, radians, updated where a row of ``rows`` changed.
        key: (n, 2) and
        vals: (n, 7) the yaws' sines and cosines kept per row (:func:`yaw_trig_row`).
    """
    for i in range(ankle.shape[0]):
        if rows[i]:
            _update_row(ankle, foot_yaw, pitch, root, yaw, i, sgn, hip_y, L1, L2, rmin, rmax,
                        inputs, out, key, vals)  # fmt: skip


@njit_inline
def _update_row(ankle, foot_yaw, pitch, root, yaw, i, sgn, hip_y, L1, L2, rmin, rmax, inputs, out,
                key, vals):  # fmt: skip
    """Row ``i`` of :func:`leg_ik_world_cached`: solved by :func:`leg_ik_trig_row` and its
    inputs kept when they differ from ``inputs[i]``, else left as it is."""
    row = (ankle[i, 0], ankle[i, 1], ankle[i, 2], foot_yaw[i], pitch[i], root[i, 0],
           root[i, 1], root[i, 2], yaw[i])  # fmt: skip
    same = True
    for k in range(9):
        if row[k] != inputs[i, k]:
            same = False
            break
    if same:
        return
    for k in range(9):
        inputs[i, k] = row[k]
    leg_ik_trig_row(ankle, foot_yaw, pitch, root, yaw, i, sgn, hip_y, L1, L2, rmin, rmax, out,
                    key, vals)  # fmt: skip


@njit_inline
def leg_ik_trig_row(ankle, foot_yaw, pitch, root, yaw, i, sgn, hip_y, L1, L2, rmin, rmax, out,
                    key, vals):  # fmt: skip
    """:func:`~mjwalk.body.legs.ik.leg_ik_world_row` with the yaws' sines and cosines kept per
    row (:func:`yaw_trig_row`): the same numbers.

    Args:
        ankle: (n, 3) ankle targets, metres, world frame.
        foot_yaw: (n,) foot headings, radians from +x CCW.
        pitch: (n,) foot pitches to the floor, radians, + toes up.
        root: (n, 3) pelvis (root) positions, metres.
        yaw: (n,) pelvis yaws, radians from +x CCW.
        i: the row to solve.
        sgn: +1 for the left leg, -1 for the right.
        hip_y: the hip joint centre's lateral offset from the pelvis centre, metres.
        L1: thigh length, metres.
        L2: shank length, metres.
        rmin: the shortest hip-to-ankle distance, metres.
        rmax: the longest hip-to-ankle distance, metres.
        out: (n, 6) unclipped angles, radians; row ``i`` is written.
        key: (n, 2) the yaws ``vals`` holds per row.
        vals: (n, 7) their sines and cosines.

    Returns:
        None (``out[i]`` is written).
    """
    cy, sy, c, sn, _, cz, sz = yaw_trig_row(foot_yaw, yaw, i, key, vals)
    u0, u1, u2 = hip_rel(ankle, root, i, sgn * hip_y, cy, sy, c, sn)
    leg_ik_cs(u0, u1, u2, cz, sz, pitch[i], sgn, L1, L2, rmin, rmax, out[i])


@njit_inline
def _same(a, b):
    """``a`` and ``b`` the same number, signed zeros told apart (NaN never the same)."""
    return a == b and math.copysign(1.0, a) == math.copysign(1.0, b)


@njit_inline
def yaw_trig_row(foot_yaw, yaw, i, key, vals):
    """The sines and cosines :func:`hip_frame_row` and :func:`_leg_ik_one` take of row ``i``'s
    pelvis yaw and of the foot's relative yaw, kept per row: computed when the row's pelvis and
    foot yaws are not those of ``key[i]`` (then kept in ``key[i]`` and ``vals[i]``), else read
    from ``vals[i]`` (the same numbers: the same functions of the same inputs). The synthesis's
    loops solve a row again and again with the same yaws (only the ankle target, pitch and
    pelvis height change).

    Args:
        foot_yaw: (n,) foot headings, radians from +x CCW.
        yaw: (n,) pelvis yaws, radians from +x CCW.
        i: the row.
        key: (n, 2) the yaws (pelvis, foot) ``vals`` holds per row (NaN: none yet).
        vals: (n, 7) cos and sin of the pelvis yaw, cos and sin of its negative, the foot's
            relative yaw in [-pi, pi] and its cos and sin.

    Returns:
        ``vals[i]``'s seven numbers as a tuple.
    """
    y, fy = yaw[i], foot_yaw[i]
    if not (_same(y, key[i, 0]) and _same(fy, key[i, 1])):
        dy = fy - y
        yrel = math.atan2(math.sin(dy), math.cos(dy))
        vals[i, 0], vals[i, 1] = math.cos(y), math.sin(y)
        vals[i, 2], vals[i, 3] = math.cos(-y), math.sin(-y)
        vals[i, 4], vals[i, 5], vals[i, 6] = yrel, math.cos(yrel), math.sin(yrel)
        key[i, 0], key[i, 1] = y, fy
    v = vals[i]
    return v[0], v[1], v[2], v[3], v[4], v[5], v[6]


@njit
def _trig_pair(fy_a, fy_b, yaw, key_a, vals_a, key_b, vals_b):
    """:meth:`LegIKCache.share_trig`: per row :func:`yaw_trig_row`'s seven numbers of both
    legs (its arithmetic, the pelvis yaw's cosines and sines taken once)."""
    for i in range(yaw.shape[0]):
        y = yaw[i]
        c0, s0, c1, s1 = math.cos(y), math.sin(y), math.cos(-y), math.sin(-y)
        for fy, key, vals in ((fy_a[i], key_a, vals_a), (fy_b[i], key_b, vals_b)):
            dy = fy - y
            yrel = math.atan2(math.sin(dy), math.cos(dy))
            vals[i, 0], vals[i, 1], vals[i, 2], vals[i, 3] = c0, s0, c1, s1
            vals[i, 4], vals[i, 5], vals[i, 6] = yrel, math.cos(yrel), math.sin(yrel)
            key[i, 0], key[i, 1] = y, fy
