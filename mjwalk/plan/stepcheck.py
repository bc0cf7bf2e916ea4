"""Decode, check and score sampled successor steps in one compiled loop (the hybrid A*'s hot path).

:func:`check_steps` does for every sampled step what :mod:`mjwalk.plan.hybrid` describes: the
affine decode of its features (:class:`~mjwalk.plan.decoder.StepDecoder`) into pelvis samples,
the landing ankle and toes and the swing-knee probes in the step's local frame (x right, y
forward, as x + iy; metres), the turn into the world, the clearance test of every point
against its own limit (bilinear lookup in the workplace's walk field), the landing leg's probes
from the ankle towards the hip (:func:`~mjwalk.plan.stepgeom.landing_leg_clear`), the leg-reach
tests, the forward tests (a step's end pelvis and landing ankle ahead of its start pelvis; a
walking step's landing ankle ahead of its stance ankle,
:func:`~mjwalk.plan.stepgeom.passes_stance`), the stance-leg lean test
(:func:`~mjwalk.plan.lean.stance_lean_ok`: the stance leg must follow the pelvis within the
ankle's and the hip's sideways ranges), the closing-step test (a
closing step must end in the goal area; tested first, from its end and heading alone: most
closing draws end outside it), and for the accepted steps the walked length g
(:mod:`mjwalk.plan.stepcost`), f = g + weight·h (plus far weight·(h - far from) beyond far
from), the closed-list key, heading and landing foot. It is one loop over the rows (numba, see
:mod:`mjwalk._jit`).

Rows are grouped by predecessor: row r belongs to node r // per and is a closing step when
r % per >= n_walk. Per-row ``frame``/``left`` arrays (a start node's starters each turn their
own way) or per-node ones (length b) are both accepted.

numba's on-disk cache of :func:`check_into` is keyed by this file's text only, not by the
compiled functions it calls or the constants it reads from other modules: mjwalk clears its
cached machine code whenever any of its sources changes (:func:`mjwalk._jit.clear_stale_caches`).

The parameter vectors' slots live in :mod:`mjwalk.plan.slots`; this module re-exports what
callers of the check use (:func:`~mjwalk.plan.slots.params`, the stance-lean and energy
functions, ...).
"""

from __future__ import annotations

import math

import numpy as np

from mjwalk._jit import njit
from mjwalk.plan.guide import guide_aim, guide_aim_at, guide_nearest
from mjwalk.plan.lean import lean_in_range, lean_limits, lean_ok, stance_lean, stance_lean_ok
from mjwalk.plan.slots import (
    I_CHORD,
    I_DIJKSTRA,
    I_DIST_NX,
    I_FIELD_NX,
    I_FIELD_NY,
    I_KNEE_COL0,
    I_KNEE_COL1,
    I_KNEE_COL2,
    I_M,
    I_Q,
    MAX_GOAL_DISCS,
    N_IPARAMS,
    N_PARAMS,
    P_DISC0,
    P_DIST_CELL,
    P_DIST_OFFSET,
    P_DIST_TOP_X,
    P_DIST_TOP_Y,
    P_DIST_X0,
    P_DIST_Y0,
    P_FAR_FROM,
    P_FAR_WEIGHT,
    P_FIELD_RES,
    P_FIELD_X0,
    P_FIELD_Y0,
    P_FOOT_LENGTH,
    P_FOOT_REACH,
    P_FOOT_ROLL,
    P_GOAL_X,
    P_GOAL_Y,
    P_GUIDE0,
    P_GUIDE_LEN0,
    P_HEADING_FROM,
    P_HEADING_WEIGHT,
    P_HIP_Y,
    P_KNEE_LEAD,
    P_KNEE_PIVOT,
    P_KNEE_SHARE0,
    P_KNEE_SHARE1,
    P_KNEE_SHARE2,
    P_KNEE_SIDE,
    P_KNEE_TURN0,
    P_KNEE_TURN1,
    P_KNEE_TURN2,
    P_LIFT_REACH,
    P_PACE,
    P_START_YAW,
    P_STEP_ADVANCE,
    P_STRIDE,
    P_SWING_LIFT_TURN,
    P_TOE_CLEARANCE,
    P_TOE_FRONT,
    P_TOE_SIDE,
    P_TURN_COST,
    P_WEIGHT,
    iparams,
    params,
)
from mjwalk.plan.stepcost import (
    downhill_costs,
    grid_bound,
    grid_sight,
    guide_rest,
    heading_factor,
    step_energy,
)
from mjwalk.plan.stepgeom import (
    beyond,
    cell_key,
    decode_col,
    decode_real,
    field_clearance,
    in_goal,
    landing_leg_clear,
    out_of_reach,
    passes_stance,
    swing_yaw,
    toe_approach_clear,
    unit_turn,
)

__all__ = [
    "MAX_GOAL_DISCS",
    "N_IPARAMS",
    "N_PARAMS",
    "cell_key",
    "check_into",
    "check_steps",
    "downhill_costs",
    "heading_factor",
    "in_goal",
    "iparams",
    "landing_leg_clear",
    "lean_in_range",
    "lean_limits",
    "new_buffers",
    "params",
    "stance_lean",
    "stance_lean_ok",
    "step_energy",
]


@njit
def check_steps(
    z, matrix, offset, per, n_walk, frame, left, near, node, thr, par, ipar, coef, dist
):
    """Decode, check and score the sampled steps ``z`` (n, d) of b = n // per predecessors.

    Args:
        z: (n, d) standardized features.
        matrix: (d, 2m + 3) the complex affine decode
            (:class:`~mjwalk.plan.decoder.StepDecoder`; the pelvis-yaw columns only with the
            stance-lean slots set, the duration column only with P_PACE set).
        offset: (2m + 3,) the decode's complex offset.
        per: rows per predecessor.
        n_walk: how many of them are walking steps (the rest are closing steps).
        frame: heading (radians) of each step's local frame, per row (n,) or per
            predecessor (b,).
        left: whether each step's swing foot is the left one, per row or per predecessor.
        near: (b,) whether the predecessor may stop (else its closing rows are dropped
            uncounted).
        node: (b, 4) or (b, 5) complex per predecessor: end point p, the foot its step
            landed and the foot behind that (world x + iy; nan: none yet), g (real part) and,
            in column 4, the landed foot's heading (real part, world radians; nan: none) and
            the foot behind's (imaginary part: the swing foot's lift-off heading, which the
            knee probes turn from; nan: none).
            The landed foot is the stance foot of the step drawn from the predecessor: with
            its heading, and the decoder's pelvis-yaw columns, and the P_HIP_Y .. P_ABDUCTION
            slots set, a step whose stance leg cannot follow it is rejected
            (:func:`stance_lean_ok`).
        thr: (m + 5,) clearance limits of the pelvis samples, ankle, toes and the three knees
            (the landing leg's probes keep P_LEG_CLEARANCE: :func:`landing_leg_clear`).
        par: the float slots (:func:`params`).
        ipar: the integer slots (:func:`iparams`).
        coef: the walk field's node values (ny, nx) (:meth:`Workplace.walk_field`).
        dist: the goal distance's flat grid bound (:class:`~mjwalk.plan.heuristic.GoalDistance`).

    Returns:
        rows, keys, f, g, end, heading, frame, foot, foot heading (world radians), left of the
        accepted steps (row order), and per predecessor the accepted and drawn (not dropped)
        counts.
    """
    n = z.shape[0]
    b = n // per if per > 0 else 0
    out = new_buffers(n, ipar[I_M])
    accepted = np.zeros(b, dtype=np.int64)
    drawn = np.zeros(b, dtype=np.int64)
    cnt = check_into(
        z, matrix, offset, per, n_walk, frame, left, near, node, thr, par, ipar, coef, dist,
        out, accepted, drawn, False,
    )  # fmt: skip
    out_rows, out_keys, out_f, out_g, out_end, out_th, out_frame, out_foot, out_fhead = out[:9]
    return (
        out_rows[:cnt],
        out_keys[:cnt],
        out_f[:cnt],
        out_g[:cnt],
        out_end[:cnt],
        out_th[:cnt],
        out_frame[:cnt],
        out_foot[:cnt],
        out_fhead[:cnt],
        out[9][:cnt],
        accepted,
        drawn,
    )


@njit
def new_buffers(n, m):
    """:func:`check_into`'s output buffers for up to ``n`` steps of ``m`` pelvis samples: rows,
    keys, f, g, end, heading, frame, foot, foot heading, left (n,) and the decode row (m + 2,).

    Args:
        n: the most steps the buffers take.
        m: pelvis samples per step.
    """
    return (
        np.empty(n, dtype=np.int64),
        np.empty(n, dtype=np.int64),
        np.empty(n),
        np.empty(n),
        np.empty(n, dtype=np.complex128),
        np.empty(n),
        np.empty(n),
        np.empty(n, dtype=np.complex128),
        np.empty(n),
        np.empty(n, dtype=np.bool_),
        np.empty(m + 2, dtype=np.complex128),
    )


@njit
def _lift_turn(node, i, fr, par):
    """The lifting foot's heading relative to the frame heading ``fr`` (radians), within
    +-P_SWING_LIFT_TURN (past the hip's rotation range the grounded foot spins); nan when
    ``node`` (as for :func:`check_steps`) has no column 4 or the foot is unknown.

    Args:
        node: as for :func:`check_steps`.
        i: the predecessor's row of ``node``.
        fr: the step's frame heading, radians.
        par: the float slots.
    """
    lift_yaw = node[i, 4].imag - fr if node.shape[1] > 4 else math.nan
    if not math.isnan(lift_yaw):
        lim = par[P_SWING_LIFT_TURN]
        lift_yaw = min(max(math.atan2(math.sin(lift_yaw), math.cos(lift_yaw)), -lim), lim)
    return lift_yaw


@njit
def legs_clear(z, r, matrix, offset, loc, rot, node, i, fr, lf, v, v_end, lift_yaw, lean, limits,
               thr, par, ipar, coef):  # fmt: skip
    """Whether the legs and feet of a step whose pelvis samples and ankle keep their
    clearances (:func:`check_into`'s first test) pass the rest of the checks: the landing
    toes and toe corners, the landing leg, the swing knees, the legs' reach, the step going
    forward (:data:`~mjwalk.plan.options.MIN_STEP_ADVANCE`), the landing foot's way in and the
    stance leg's lean. The order does not matter: each refuses alone.

    Args:
        z: (n, d) standardized features.
        r: the step's row of ``z``.
        matrix: the decoder's complex matrix (:func:`check_steps`).
        offset: its complex offset.
        loc: the step's decoded columns 0 .. m + 1 (step frame).
        rot: the step frame's turn into the world, complex(sin fr, -cos fr).
        node: as for :func:`check_steps`.
        i: the predecessor's row of ``node``.
        fr: the step's frame heading, radians.
        lf: whether the swing foot is the left one.
        v: the walk field at the landing ankle, metres.
        v_end: the walk field at the end pelvis, metres.
        lift_yaw: :func:`_lift_turn` of the predecessor and ``fr``.
        lean: whether the stance lean is checked (:func:`check_into`).
        limits: :func:`lean_limits` of ``par``.
        thr: as for :func:`check_steps`.
        par: the float slots.
        ipar: the integer slots.
        coef: the walk field's node values (ny, nx), metres.
    """
    m = ipar[I_M]
    q = ipar[I_Q]
    fnx = ipar[I_FIELD_NX]
    fny = ipar[I_FIELD_NY]
    fx0 = par[P_FIELD_X0]
    fy0 = par[P_FIELD_Y0]
    fres = par[P_FIELD_RES]
    p = node[i, 0]
    yaws = loc[m + 1]
    ankle = loc[m] * rot + p
    land = unit_turn(yaws.real)  # the landing yaw's turn, once (the toe probes below)
    toe = ankle + (par[P_FOOT_LENGTH] * 1j) * rot * land
    v_toe = field_clearance(coef, fx0, fy0, fres, fnx, fny, toe.real, toe.imag)
    if v_toe < thr[m + 1]:
        return False
    v_toe = min(v, v_toe)  # the landing's ankle and toes (the approach probes start there)
    # the toes' front corners for the walker's stature (a tall walker's wide toes reach
    # past the probe above: options.toe_corners)
    if not math.isnan(par[P_TOE_FRONT]):
        turn = rot * land
        for side in (-par[P_TOE_SIDE], par[P_TOE_SIDE]):
            toe = ankle + complex(side, par[P_TOE_FRONT]) * turn
            if (
                field_clearance(coef, fx0, fy0, fres, fnx, fny, toe.real, toe.imag)
                < par[P_TOE_CLEARANCE]
            ):
                return False
    # the landing leg, from the ankle towards its hip at the step's end (heel strike: the
    # shin leans back over the heel, the toes-up heel reaches behind the flat footprint),
    # probed from the ankle's clearance out to where the end pelvis's covers it
    if not landing_leg_clear(loc, m, lf, yaws.imag, rot, p, v, v_end, par, coef, fx0, fy0,
                             fres, fnx, fny):  # fmt: skip
        return False
    # the swing knee, ahead along the swing foot's yaw at the probe's phase (it bends in
    # the foot's plane) from the swing hip (to the swing side along the pelvis's);
    # without the lifting foot's heading (the first steps), ahead along the pelvis's
    # from KNEE_SIDE to the swing side; at half and three quarters of the step, and with
    # the lifting foot's heading at a third (the early swing, the foot still along its
    # lift-off yaw: options.KNEE_LEAD)
    lat = (1j if lf else -1j) * par[P_KNEE_SIDE]
    hip = (1j if lf else -1j) * par[P_KNEE_PIVOT]
    for kk in range(2 if math.isnan(lift_yaw) else 3):
        col = ipar[I_KNEE_COL0 if kk == 0 else (I_KNEE_COL1 if kk == 1 else I_KNEE_COL2)]
        share = par[P_KNEE_SHARE0 if kk == 0 else (P_KNEE_SHARE1 if kk == 1 else P_KNEE_SHARE2)]
        fwd = 1j * unit_turn(yaws.imag * share)
        if math.isnan(lift_yaw):
            knee = (loc[col] + fwd * (par[P_KNEE_LEAD] + lat)) * rot + p
        else:
            turned = par[P_KNEE_TURN0 if kk == 0 else (P_KNEE_TURN1 if kk == 1 else P_KNEE_TURN2)]
            foot = swing_yaw(lift_yaw, yaws.real, turned)
            knee = (loc[col] + 1j * unit_turn(foot) * par[P_KNEE_LEAD] + fwd * hip) * rot + p
        if field_clearance(coef, fx0, fy0, fres, fnx, fny, knee.real, knee.imag) < thr[m + 2 + kk]:
            return False
    # leg reach, in the local frame (nan feet: comparisons with nan are False)
    # (the planted feet's reach shrinks as the foot turns across it: options.foot_reach)
    rc = rot.conjugate()
    landed = (node[i, 1] - p) * rc
    behind = (node[i, 2] - p) * rc
    reach = par[P_FOOT_REACH]
    roll = par[P_FOOT_ROLL]
    stand = 1j * unit_turn(node[i, 4].real - fr)  # the landed foot's heading (step frame)
    for j in range(m):
        if out_of_reach(loc[j] - landed, stand, reach, roll):
            return False
    lift = par[P_LIFT_REACH]
    for j in range(q):
        if beyond(loc[j] - behind, lift):
            return False
    if beyond(loc[m] - behind, par[P_STRIDE]) or out_of_reach(loc[m - 1] - loc[m], 1j * land,
                                                              reach, roll):  # fmt: skip
        return False
    # a walking step goes forward: its end pelvis and landing ankle ahead of its start pelvis
    # (the step frame's y; options.MIN_STEP_ADVANCE; a nan slot: no test)
    if loc[m - 1].imag < par[P_STEP_ADVANCE] or loc[m].imag < par[P_STEP_ADVANCE]:
        return False
    # the landing foot's way in along the chord from the foot behind, turned to its
    # landing yaw: a curved walk's step comes in obliquely, the toes sweeping sideways
    toe_off = (par[P_FOOT_LENGTH] * 1j) * land
    if not toe_approach_clear(loc[m], behind, toe_off, thr[m + 1], v_toe, rot, p, par, coef,
                              fx0, fy0, fres, fnx, fny):  # fmt: skip
        return False
    # the stance leg's sideways lean (the landed foot is this step's stance foot)
    if lean and not (math.isnan(landed.real) or math.isnan(node[i, 4].real)):
        if not lean_ok(z, r, matrix, offset, loc, m, landed, node[i, 4].real - fr,
                        not lf, par, limits):  # fmt: skip
            return False
    return True


@njit
def legs_recheck(z, r, matrix, offset, fr, lf, node, thr, par, ipar, coef, loc):
    """:func:`legs_clear` of a step that :func:`check_into` accepted with ``defer``: the same
    decode, turn and field lookups, so the same outcome as check_into without ``defer``.

    Args:
        z: (n, d) standardized features.
        r: the step's row of ``z``.
        matrix: the decoder's complex matrix (:func:`check_steps`).
        offset: its complex offset.
        fr: the step's frame heading, radians.
        lf: whether the swing foot is the left one.
        node: (1, 5) its predecessor's row, as check_into had it (:func:`check_steps`).
        thr: as for :func:`check_steps`.
        par: the float slots.
        ipar: the integer slots.
        coef: the walk field's node values (ny, nx), metres.
        loc: (m + 2,) complex work row; takes the step's decoded columns.
    """
    m = ipar[I_M]
    rot = complex(math.sin(fr), -math.cos(fr))
    p = node[0, 0]
    fnx = ipar[I_FIELD_NX]
    fny = ipar[I_FIELD_NY]
    for j in range(m + 2):
        loc[j] = decode_col(z, r, matrix, offset, j)
    w = loc[m - 1] * rot + p
    v_end = field_clearance(coef, par[P_FIELD_X0], par[P_FIELD_Y0], par[P_FIELD_RES], fnx, fny,
                            w.real, w.imag)  # fmt: skip
    w = loc[m] * rot + p
    v = field_clearance(coef, par[P_FIELD_X0], par[P_FIELD_Y0], par[P_FIELD_RES], fnx, fny,
                        w.real, w.imag)  # fmt: skip
    lean = node.shape[1] > 4 and matrix.shape[1] >= 2 * m + 2 and not math.isnan(par[P_HIP_Y])
    return legs_clear(z, r, matrix, offset, loc, rot, node, 0, fr, lf, v, v_end,
                      _lift_turn(node, 0, fr, par), lean, lean_limits(par), thr, par, ipar,
                      coef)  # fmt: skip


@njit
def check_into(
    z, matrix, offset, per, n_walk, frame, left, near, node, thr, par, ipar, coef, dist, out,
    accepted, drawn, defer,
):  # fmt: skip
    """:func:`check_steps` into buffers: ``out`` from :func:`new_buffers` (at least n rows)
    takes the accepted steps in its first rows, ``accepted`` and ``drawn`` (at least b, set
    to 0 here) the per-predecessor counts; returns the number of accepted steps. The search
    keeps one set of buffers instead of a dozen new arrays per expansion.

    With ``defer`` the legs' and feet's checks (:func:`legs_clear`) are left to the caller:
    the steps whose pelvis and ankle keep their clearances (and, walking steps, whose swing
    foot passes the stance foot: :func:`~mjwalk.plan.stepgeom.passes_stance`, one
    subtraction) are accepted and scored, and the
    caller runs :func:`legs_recheck` on a step before it takes the step up. The search does
    so: most accepted steps are never taken up (it ends first), and a step the legs refuse
    is then dropped where it would never have been pushed, so the walks are the same.

    Args:
        z: as for :func:`check_steps`.
        matrix: as for :func:`check_steps`.
        offset: as for :func:`check_steps`.
        per: as for :func:`check_steps`.
        n_walk: as for :func:`check_steps`.
        frame: as for :func:`check_steps`.
        left: as for :func:`check_steps`.
        near: as for :func:`check_steps`.
        node: as for :func:`check_steps`.
        thr: as for :func:`check_steps`.
        par: as for :func:`check_steps`.
        ipar: as for :func:`check_steps`.
        coef: as for :func:`check_steps`.
        dist: as for :func:`check_steps`.
        out: the buffers of :func:`new_buffers`.
        accepted: (>= b,) int, the accepted count per predecessor.
        drawn: (>= b,) int, the drawn (not dropped) count per predecessor.
        defer: whether to leave :func:`legs_clear` to the caller (:func:`legs_recheck`).
    """
    n = z.shape[0]
    b = n // per if per > 0 else 0
    m = ipar[I_M]
    fnx = ipar[I_FIELD_NX]
    fny = ipar[I_FIELD_NY]
    fx0 = par[P_FIELD_X0]
    fy0 = par[P_FIELD_Y0]
    fres = par[P_FIELD_RES]
    goal = complex(par[P_GOAL_X], par[P_GOAL_Y])
    per_row = frame.shape[0] == n
    lean = node.shape[1] > 4 and matrix.shape[1] >= 2 * m + 2 and not math.isnan(par[P_HIP_Y])
    limits = lean_limits(par)
    rot = complex(1.0, 0.0)
    fr_last = math.nan
    out_rows, out_keys, out_f, out_g, out_end, out_th, out_frame, out_foot, out_fhead = out[:9]
    out_left = out[9]
    loc = out[10]
    accepted[:b] = 0
    drawn[:b] = 0
    cnt = 0
    lift_i = -1
    lift_fr = math.nan
    lift_yaw = math.nan
    for r in range(n):
        i = r // per
        closing = r % per >= n_walk
        if closing and not near[i]:
            continue  # dropped uncounted
        drawn[i] += 1
        fr = frame[r] if per_row else frame[i]
        lf = left[r] if per_row else left[i]
        if fr != fr_last:  # the turn into the world, once per frame heading (rows share it)
            rot = complex(math.sin(fr), -math.cos(fr))
            fr_last = fr
        p = node[i, 0]
        if closing:
            # a closing step must end the walk: its end and heading first (most closing draws
            # end outside the goal area), the same sums as the full decode's columns below
            end = decode_col(z, r, matrix, offset, m - 1) * rot + p
            if not in_goal(end, fr + decode_col(z, r, matrix, offset, m + 1).imag, par, ipar):
                continue
        # decode (local = z @ matrix + offset, column by column: decode_col) and clearance of
        # pelvis samples and ankle (world), each column as its test needs it: a third of the
        # rows fail here. The end pelvis first, then the ankle, then the pelvis samples from
        # the end back: a step into an obstacle fails last where it ends (on
        # 10 station cycles' 124 600 walking rows 82 % of those that fail here fail at the end
        # pelvis; in sample order the first failure came at column 10 on average). Each
        # column refuses alone, so the order changes which rows pass in nothing.
        ok = True
        v = 0.0
        v_end = 0.0  # the field at the end pelvis and at the ankle
        for k in range(m + 1):
            j = m - 1 if k == 0 else (m if k == 1 else m - k)
            loc[j] = decode_col(z, r, matrix, offset, j)
            w = loc[j] * rot + p
            vj = field_clearance(coef, fx0, fy0, fres, fnx, fny, w.real, w.imag)
            if vj < thr[j]:
                ok = False
                break
            if k == 0:
                v_end = vj
            elif k == 1:
                v = vj
        if not ok:
            continue
        loc[m + 1] = decode_col(z, r, matrix, offset, m + 1)
        yaws = loc[m + 1]
        ankle = loc[m] * rot + p
        # a walking step's swing foot passes its stance foot (a closing step's comes beside it)
        if not closing and not passes_stance(loc[m], node[i, 1], p, rot, par[P_STEP_ADVANCE]):
            continue
        if not defer:  # else when the step is taken up (search: legs_recheck)
            if i != lift_i or fr != lift_fr:  # the same for a node's rows (one frame heading)
                lift_yaw = _lift_turn(node, i, fr, par)
                lift_i = i
                lift_fr = fr
            if not legs_clear(z, r, matrix, offset, loc, rot, node, i, fr, lf, v, v_end,
                              lift_yaw, lean, limits, thr, par, ipar, coef):  # fmt: skip
                continue
        end = loc[m - 1] * rot + p
        th = fr + yaws.imag
        # walked length and heuristic
        if ipar[I_CHORD]:
            seg = abs(loc[m - 1])
        else:
            seg = 0.0
            for j in range(1, m):
                seg += abs(loc[j] - loc[j - 1])
        pace = par[P_PACE]
        if not (math.isnan(pace) or closing or math.isnan(node[i, 1].real)):
            # energy cost (step_energy) of a walking step: not of a starter (its node has no
            # landed foot) nor of a closing step, which set off from and come to a stand;
            # the duration is the decoder's last column
            seg = step_energy(seg, decode_real(z, r, matrix, offset, 2 * m + 2), pace)
        if par[P_TURN_COST] > 0.0 and math.isnan(node[i, 1].real):
            # a starter set off after a turn on the spot from the walker's heading: its time
            turned = (fr - par[P_START_YAW] + math.pi) % (2.0 * math.pi) - math.pi
            seg += par[P_TURN_COST] * abs(turned)
        ex, ey = end.real, end.imag
        h = math.hypot(ex - goal.real, ey - goal.imag)
        if ipar[I_DIJKSTRA]:
            bound = grid_bound(
                dist, par[P_DIST_X0], par[P_DIST_Y0], par[P_DIST_CELL], par[P_DIST_TOP_X],
                par[P_DIST_TOP_Y], ipar[I_DIST_NX], ex, ey,
            ) - par[P_DIST_OFFSET]  # fmt: skip
            if bound > h:
                h = bound
        hw = par[P_HEADING_WEIGHT]
        guided = not math.isnan(par[P_GUIDE0])
        guide = par[P_GUIDE0:P_DISC0]
        if guided:  # the guide's point nearest the step's end, for its aim and the way left
            gk, gw, gd2 = guide_nearest(guide, end)
        else:
            gk, gw, gd2 = 0, 0.0, 0.0
        if hw > 0.0 and not closing and h > par[P_HEADING_FROM]:
            # along a guide (clear of obstacles: mjwalk.plan.guide) everywhere; else only
            # where the goal is in sight
            sight = guided or grid_sight(
                dist, par[P_DIST_X0], par[P_DIST_Y0], par[P_DIST_CELL], par[P_DIST_TOP_X],
                par[P_DIST_TOP_Y], ipar[I_DIST_NX], ex, ey,
            )  # fmt: skip
            if sight:
                if guided:  # steering for the guide's point two steps on (PURSUIT_AHEAD)
                    want = guide_aim_at(guide, end, goal, gk, gw)
                else:  # straight at the goal
                    want = guide_aim(guide, end, goal)
                seg *= heading_factor(fr + 0.5 * yaws.imag, want, hw)
        g = node[i, 3].real + seg
        if guided:  # along a guide: the way left along it, if longer
            h = max(h, guide_rest(par[P_GUIDE_LEN0:N_PARAMS], gk, gw, gd2))
        fh = par[P_WEIGHT] * h
        if h > par[P_FAR_FROM]:  # farther than FAR_FROM from the goal: the far weight too
            fh += par[P_FAR_WEIGHT] * (h - par[P_FAR_FROM])
        out_rows[cnt] = r
        out_keys[cnt] = cell_key(end, th, par, ipar)
        out_f[cnt] = g + fh
        out_g[cnt] = g
        out_end[cnt] = end
        out_th[cnt] = th
        out_frame[cnt] = fr
        out_foot[cnt] = ankle
        out_fhead[cnt] = fr + yaws.real
        out_left[cnt] = lf
        accepted[i] += 1
        cnt += 1
    return cnt
