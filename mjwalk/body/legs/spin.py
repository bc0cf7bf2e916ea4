"""Spin turns: a grounded foot whose hip would rotate past its range as the pelvis turns turns
about its ball (or heel) instead (see :func:`spin_turns`). World frame, metres, radians.
"""

from __future__ import annotations

import numpy as np

from mjwalk._jit import njit
from mjwalk.body.humanoid import ROM_DEG, LegGeometry
from mjwalk.body.legs.curves import smoothstep, soft_excess1
from mjwalk.body.legs.ik import (
    ball_offset,
    ik_lengths,
    leg_ik_world,
    leg_ik_world_row,
    pivot_ankle,
    spin_print,
)
from mjwalk.body.legs.steps import SWING_TURNED

#: Spin turns (degrees): a grounded foot whose hip would rotate past its range less
#: ``SPIN_MARGIN`` turns about its ball by the excess (softly: from ``SPIN_SOFT`` before that),
#: its heel raised ``SPIN_HEEL`` over the last ``SPIN_RAMP`` of hip rotation before the turn.
SPIN_MARGIN, SPIN_SOFT, SPIN_HEEL, SPIN_RAMP = 2.0, 4.0, 4.0, 6.0


def spin_turns(ankle, fyaw, pitch, toe, ground, print_, root, yaw, geom: LegGeometry) -> dict:
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

    Arrays are per side ("l"/"r") over the walk's samples: ankle (n, 3) m, fyaw (n,) rad, pitch
    and toe (n,) rad, ground (n,) bool, print_ (n, 3) footprints; root (n, 3) pelvis
    position, yaw (n,) pelvis yaw. Returns per side the largest turn (radians) and the number
    of contacts that turned."""
    n = len(yaw)
    lo, hi = np.deg2rad(ROM_DEG["hip_rot"])
    margin, soft, ramp = np.deg2rad([SPIN_MARGIN, SPIN_SOFT, SPIN_RAMP])
    heel = np.deg2rad(SPIN_HEEL)
    ball, back = ball_offset(geom), -geom.foot_back
    stats = {}
    root_c, yaw_c = np.ascontiguousarray(root, dtype=float), np.ascontiguousarray(yaw, dtype=float)
    for s_ in "lr":
        sgn = 1.0 if s_ == "l" else -1.0
        g = ground[s_]
        new_print = np.r_[True, np.any(print_[s_][1:] != print_[s_][:-1], axis=1)]
        starts = np.flatnonzero(g & (new_print | ~np.r_[False, g[:-1]]))
        # each contact ends before the next sample off the floor or on another print
        breaks = np.flatnonzero(~g | new_print)
        nxt = np.searchsorted(breaks, starts, side="right")
        ends = [int(breaks[k]) - 1 if k < len(breaks) else n - 1 for k in nxt]
        # the hip rotation of every grounded sample at once (the rows are independent: as
        # per contact), and where it passes its range; the other contacts are left as they are
        r_all, up_all, down_all = (np.zeros(n) for _ in range(3))
        _hip_rotation_excess(
            np.ascontiguousarray(g, dtype=np.bool_),
            np.ascontiguousarray(ankle[s_], dtype=float),
            np.ascontiguousarray(fyaw[s_], dtype=float),
            np.ascontiguousarray(pitch[s_], dtype=float),
            root_c,
            yaw_c,
            sgn,
            float(geom.hip_y),
            *ik_lengths(geom),
            float(hi - margin - soft),
            float(lo + margin + soft),
            float(soft / 2),
            r_all,
            up_all,
            down_all,
        )
        need_all = (up_all > 0) | (down_all > 0)
        worst, count = 0.0, 0
        for i, (j0, j1) in enumerate(zip(starts, ends, strict=True)):
            if not need_all[j0 : j1 + 1].any():
                continue
            run = np.arange(j0, j1 + 1)
            foot = print_[s_][j0].copy()

            def rot(a_, y_, p_, run=run, side=s_):
                return leg_ik_world(a_, y_, p_, root[run], yaw[run], side, geom)[f"hip_{side}_rot"]

            p0 = pitch[s_][run].copy()
            r0, up, down = r_all[run], up_all[run], down_all[run]
            need = need_all[run]
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
            spin = np.zeros(len(run))

            def prints(spin, foot=foot, heel_ph=heel_ph, k_h=k_h):
                fp = np.empty((len(spin), 3))
                fp[heel_ph] = spin_print(foot, spin[heel_ph], geom, back)
                base = fp[k_h - 1] if k_h else foot
                rest = spin[~heel_ph] - (spin[k_h - 1] if k_h else 0.0)
                fp[~heel_ph] = spin_print(base, rest, geom, ball)
                return fp

            for _ in range(6):  # the hip rotation follows the foot's yaw one to one (-s)
                fp = prints(spin)
                err = rot(pivot_ankle(fp, p, geom), fp[:, 2], p) - target
                spin = spin + np.where(need, sgn * err, 0.0)
                # without need the foot keeps its turn (relative to its phase's pivot)
                spin = np.where(need, spin, 0.0)
            fp = prints(spin)
            a_ = pivot_ankle(fp, p, geom)
            worst, count = max(worst, float(np.abs(fp[:, 2] - foot[2]).max())), count + 1
            offsets = [
                (a_[k] - ankle[s_][j], fp[k, 2] - foot[2], p[k] - p0[k])
                for k, j in ((0, j0), (-1, j1))
            ]
            ankle[s_][run], fyaw[s_][run], print_[s_][run] = a_, fp[:, 2], fp
            pitch[s_][run], toe[s_][run] = p, -np.minimum(p, 0.0)
            # the swings around start from / land on the turned foot; the offsets fade
            j_prev = ends[i - 1] if i else None
            j_next = starts[i + 1] if i + 1 < len(starts) else n
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
                ankle[s_][sw] += w[:, None] * d_a
                fyaw[s_][sw] += w * d_y
                pitch[s_][sw] += w * d_p
                toe[s_][sw] -= w * d_p
        stats[s_] = (worst, count)
    return stats


@njit
def _hip_rotation_excess(ground, ankle, fyaw, pitch, root, yaw, sgn, hip_y, L1, L2, rmin, rmax,
                         top, bottom, w, rot, up, down):  # fmt: skip
    """Per grounded sample (``ground`` (n,)): the leg's hip rotation ``rot`` (unclipped IK,
    :func:`~mjwalk.body.legs.ik.leg_ik_world_row`) and how far it passes ``top`` and
    falls short of ``bottom`` (``up``, ``down``: :func:`~mjwalk.body.legs.curves.soft_excess`
    over ``w``), radians; the other samples are left as they are."""
    out = np.empty((ground.shape[0], 6))
    for i in range(ground.shape[0]):
        if not ground[i]:
            continue
        leg_ik_world_row(ankle, fyaw, pitch, root, yaw, i, sgn, hip_y, L1, L2, rmin, rmax, out)
        rot[i] = out[i, 0]
        up[i] = soft_excess1(out[i, 0] - top, w)
        down[i] = soft_excess1(bottom - out[i, 0], w)
