"""Compiled geometric tests of one sampled step: clearance lookups, distance tests, the
closed-list key, the goal test, the landing leg's probes and the landing foot's approach.

Points are complex numbers x + iy (metres; world or a step's local frame, x right, y
forward); angles are radians. The helpers are numba-compiled (:mod:`mjwalk._jit`) and called
from :func:`~mjwalk.plan.stepcheck.check_into` and :func:`~mjwalk.plan.search.search`.
"""

from __future__ import annotations

import math

from mjwalk._jit import njit, njit_inline
from mjwalk.plan.slots import (
    I_BINS,
    I_N_DISCS,
    I_SPAN,
    P_CELL,
    P_CORNER_X,
    P_CORNER_Y,
    P_DISC0,
    P_FIELD_LIP,
    P_GOAL_X,
    P_GOAL_Y,
    P_GOAL_YAW,
    P_HIP_Y,
    P_LEG_CLEARANCE,
    P_LEG_STEP,
    P_TOE_SHARE,
    P_TOE_STEP,
    P_TOLERANCE,
    P_YAW_TOLERANCE,
)


@njit
def field_clearance(coef, x0, y0, res, nx, ny, x, y):
    """:meth:`ClearanceField.__call__` at one point (x, y) (metres) from the field's node
    values ``coef`` (ny, nx): bilinear clearance, metres, as value = a + b·tx + c·ty + d·tx·ty
    with the cell's coefficients a = v00, b = v01 - v00, c = v10 - v00,
    d = v11 - v10 - v01 + v00 formed on the fly (a table of them held four times the field).

    Args:
        coef: the field's node values (ny, nx), metres.
        x0: its origin x, metres, world frame.
        y0: its origin y, metres.
        res: its spacing, metres.
        nx: its number of columns.
        ny: its number of rows.
        x: the point's x, metres.
        y: the point's y, metres.
    """
    fx = (x - x0) / res
    fx = min(max(fx, 0.0), nx - 1.000001)
    fy = (y - y0) / res
    fy = min(max(fy, 0.0), ny - 1.000001)
    ix = int(fx)
    iy = int(fy)
    fx -= ix
    fy -= iy
    v00 = coef[iy, ix]
    v01 = coef[iy, ix + 1]
    v10 = coef[iy + 1, ix]
    v11 = coef[iy + 1, ix + 1]
    return ((v11 - v10 - v01 + v00) * fy + (v01 - v00)) * fx + v00 + fy * (v10 - v00)


#: The Lipschitz constant of the bilinear lookup of nodes that hold a distance (each node
#: difference at most the spacing): the x- and y-derivatives within a cell are each at most 1,
#: and a cell whose nodes hold 0, 1, 1, sqrt(2) spacings (an obstacle's corner) has the
#: gradient (1, 1) at its corner (:attr:`mjwalk.world.clearance.ClearanceField.lipschitz`).
DISTANCE_LIPSCHITZ = math.sqrt(2.0)


@njit_inline
def field_lipschitz(par):
    """The Lipschitz constant the probe rules use for the walk field: its own
    (``P_FIELD_LIP``, :attr:`~mjwalk.world.clearance.ClearanceField.lipschitz`), at least 1
    (a constant taken larger than the true one stays a bound; at 1 the probes are never
    sparser than their nominal spacing); nan: :data:`DISTANCE_LIPSCHITZ`.

    Args:
        par: the float slots (P_FIELD_LIP).
    """
    lip = par[P_FIELD_LIP]
    if math.isnan(lip):
        return DISTANCE_LIPSCHITZ
    return max(lip, 1.0)


@njit
def beyond(v, r):
    """``abs(v) > r`` for a complex ``v``, without the hypot where the squares decide it (r > 0):
    |v|² beyond r² by more than 1e-12 relative is beyond r, and short of it by as much is
    not, whatever the roundings (a few ulp); only the band between (and nan) takes abs(v).

    Args:
        v: a complex number (x + iy, metres).
        r: the radius, metres.
    """
    if not r > 0.0:
        return abs(v) > r
    sq = v.real * v.real + v.imag * v.imag
    r2 = r * r
    if sq > r2 * (1.0 + 1e-12):
        return True
    if sq < r2 * (1.0 - 1e-12):
        return False
    return abs(v) > r


@njit
def unit_turn(angle):
    """exp(i·angle) for a real angle (radians): (cos, sin), as the complex exp computes it
    (exp(0) = 1 times each), without the exp.

    Args:
        angle: the angle, radians.
    """
    return complex(math.cos(angle), math.sin(angle))


@njit
def out_of_reach(v, heading, reach, roll):
    """Whether the pelvis lies beyond a planted foot's reach: ``v`` (x + iy, metres) from the
    foot's ankle, the foot's heading ``heading`` (a unit complex in the same frame), farther
    than ``reach - roll·(1 - |cos θ|)`` for the angle θ between the heading and ``v``
    (:func:`mjwalk.plan.options.foot_reach`: the foot's roll about its ball or heel reaches
    along its heading only). Nan (no foot) is never beyond; without a heading (nan) or with a
    nan ``roll`` the reach is ``reach`` every way.

    Args:
        v: the pelvis from the ankle, x + iy, metres.
        heading: the foot's heading as a unit complex.
        reach: the reach along the foot's heading, metres.
        roll: what the roll adds there, metres (nan: 0).
    """
    if math.isnan(roll):
        roll = 0.0
    d = abs(v)
    if not d > reach - roll:  # within the least reach (or nan): within
        return False
    along = abs((v * heading.conjugate()).real) / d
    if math.isnan(along):  # no heading: the reach alone
        return d > reach
    return d > reach - roll * (1.0 - along)


@njit
def passes_stance(ankle, landed, p, rot, advance):
    """Whether a walking step's swing foot passes its stance foot: its landing ankle lies at
    least ``advance`` metres ahead of the stance ankle along the step's start heading (the step
    frame's y; :data:`~mjwalk.plan.options.MIN_STEP_ADVANCE`). True without a stance foot (a
    starter's, nan) or with a nan ``advance`` (no test).

    Args:
        ankle: the landing ankle, step frame (x + iy, metres).
        landed: the stance ankle, world x + iy, metres (nan: none).
        p: the step frame's origin, world x + iy, metres.
        rot: the step frame's turn into the world (a unit complex).
        advance: the least advance, metres (nan: no test).
    """
    return not (ankle.imag - ((landed - p) * rot.conjugate()).imag < advance)


@njit
def swing_yaw(lift, land, turned):
    """The swing foot's yaw once it has ``turned`` (0 to 1) of its way from its lift-off yaw
    ``lift`` to its landing yaw ``land`` (radians, one frame), the short way round.

    Args:
        lift: the lift-off yaw, radians.
        land: the landing yaw, radians.
        turned: the share of the turn made, 0 to 1.

    Returns:
        The yaw, radians.
    """
    d = land - lift
    return lift + turned * math.atan2(math.sin(d), math.cos(d))


@njit
def within(v, r):
    """``abs(v) <= r`` for a complex ``v``, as :func:`beyond` decides it (nan: False).

    Args:
        v: a complex number (x + iy, metres).
        r: the radius, metres.
    """
    if not r > 0.0:
        return abs(v) <= r
    sq = v.real * v.real + v.imag * v.imag
    r2 = r * r
    if sq < r2 * (1.0 - 1e-12):
        return True
    if sq > r2 * (1.0 + 1e-12):
        return False
    return abs(v) <= r


@njit
def cell_key(p, heading, par, ipar):
    """Closed-list key of a node at world x + iy ``p`` facing ``heading`` (radians): its grid
    cell (i · span + j) and, with heading bins, times bins plus its heading bin.

    Args:
        p: the node's point, x + iy, metres, world frame.
        heading: its heading, radians from +x CCW.
        par: the float slots (:func:`~mjwalk.plan.slots.params`: the grid's origin and cell).
        ipar: the integer slots (:func:`~mjwalk.plan.slots.iparams`: span, heading bins).
    """
    cell = par[P_CELL]
    key = math.floor((p.real - par[P_CORNER_X]) / cell + 0.5) * ipar[I_SPAN] + math.floor(
        (p.imag - par[P_CORNER_Y]) / cell + 0.5
    )
    bins = ipar[I_BINS]
    if bins > 1:
        two_pi = 2.0 * math.pi
        key = key * bins + math.floor((heading % two_pi) / two_pi * bins) % bins
    return key


@njit
def in_goal(p, heading, par, ipar):
    """Whether a node at world x + iy ``p`` facing ``heading`` (radians) ends the walk: within
    the tolerance of the goal, within each of the I_N_DISCS goal discs (x, y, radius at
    P_DISC0 + 3k, after the guide's slots: e.g. the places from which the work there is
    within reach) and, with a goal yaw, facing it within its tolerance.

    Args:
        p: the node's point, x + iy, metres, world frame.
        heading: its heading, radians from +x CCW.
        par: the float slots (goal point, tolerance, discs, goal yaw).
        ipar: the integer slots (I_N_DISCS).
    """
    if beyond(p - complex(par[P_GOAL_X], par[P_GOAL_Y]), par[P_TOLERANCE]):
        return False
    for k in range(ipar[I_N_DISCS]):
        j = P_DISC0 + 3 * k
        if beyond(p - complex(par[j], par[j + 1]), par[j + 2]):
            return False
    goal_yaw = par[P_GOAL_YAW]
    if math.isnan(goal_yaw):
        return True
    diff = (heading - goal_yaw + math.pi) % (2.0 * math.pi) - math.pi
    return abs(diff) <= par[P_YAW_TOLERANCE]


@njit
def closing_ends_miss(mean, rows, eps, pool, sd_cap, matrix, offset, m, frame, p, par, ipar):
    """Whether no closing step of one draw can end in the goal area (:func:`in_goal`'s discs:
    the tolerance about the goal and each goal disc), whatever its posterior standard
    deviation between 0 and ``sd_cap``: then the draw needs no variance.

    A step's features are ε·sd + μ + r (:func:`mjwalk.gait.gpdraw.compose`), so its end point
    (decoder column m - 1, turned into the world) is A + sd·B, affine in sd; the step misses
    when, for some disc, the segment sd in [0, sd_cap] stays farther from the disc's centre
    than its radius by more than :data:`END_MARGIN` (far beyond the roundings of the decode).
    Any nan decides nothing (False).

    Args:
        mean: (1, d) the posterior mean of the draw's predecessor.
        rows: (n,) each step's residual row of ``pool``.
        eps: (n·d,) each step's normal deviates.
        pool: (m·k, d) the flattened residual pools.
        sd_cap: the largest standard deviation the draw can have (``kernel[9]``'s root).
        matrix: (d, 2m + 3) the decoder's complex matrix.
        offset: (2m + 3,) its complex offset.
        m: pelvis samples per step.
        frame: the steps' frame heading, radians from +x CCW.
        p: the steps' start point, world x + iy, metres.
        par: the float slots (goal, tolerance, discs).
        ipar: the integer slots (I_N_DISCS).
    """
    d = mean.shape[1]
    rot = complex(math.sin(frame), -math.cos(frame))  # as check_into turns a frame
    col = m - 1
    for r in range(rows.shape[0]):
        a_ = offset[col]
        b_ = 0j
        for a in range(d):
            a_ += (mean[0, a] + pool[rows[r], a]) * matrix[a, col]
            b_ += eps[r * d + a] * matrix[a, col]
        if not _ends_off(a_ * rot + p, b_ * rot, sd_cap, 0.0, par, ipar):
            return False
    return True


@njit
def closing_ends_far(centre, grow, eps, n, sd_cap, matrix, offset, m, frame, p, par, ipar):
    """Whether no closing step of one draw can end in the goal area (as
    :func:`closing_ends_miss`) whatever its mean, residual and standard deviation, given only
    that the mean and residual move the end (decoder column m - 1, step frame) at most
    ``grow`` metres from ``centre`` (:meth:`~mjwalk.gait.transition.TransitionGP.mean_reach`
    bounds the mean; the residual pools' largest move is known): then the draw needs no
    kernel row. A step's end is A + sd·B (:func:`closing_ends_miss`) with A within ``grow``
    of offset + ``centre``; it misses when, for some disc, the segment sd in [0, sd_cap]
    stays farther from the disc's centre than its radius + ``grow`` + :data:`END_MARGIN`.
    Any nan decides nothing (False).

    Args:
        centre: the end's centre (complex, step frame, metres) before the decoder's offset.
        grow: how far the mean and residual can move the end from it, metres.
        eps: (n·d,) each step's normal deviates.
        n: steps.
        sd_cap: the largest standard deviation the draw can have.
        matrix: (d, 2m + 3) the decoder's complex matrix.
        offset: (2m + 3,) its complex offset.
        m: pelvis samples per step.
        frame: the steps' frame heading, radians from +x CCW.
        p: the steps' start point, world x + iy, metres.
        par: the float slots (goal, tolerance, discs).
        ipar: the integer slots (I_N_DISCS).
    """
    d = matrix.shape[0]
    rot = complex(math.sin(frame), -math.cos(frame))  # as check_into turns a frame
    col = m - 1
    a_ = (offset[col] + centre) * rot + p
    for r in range(n):
        b_ = 0j
        for a in range(d):
            b_ += eps[r * d + a] * matrix[a, col]
        if not _ends_off(a_, b_ * rot, sd_cap, grow, par, ipar):
            return False
    return True


@njit
def _ends_off(a, b, s_max, grow, par, ipar):
    """Whether the segment a + s·b, s in [0, s_max] (world, metres), stays farther than
    ``grow`` + :data:`END_MARGIN` beyond one of :func:`in_goal`'s discs (the tolerance about
    the goal, each goal disc); nan: False."""
    if _segment_off(a, b, s_max, complex(par[P_GOAL_X], par[P_GOAL_Y]), par[P_TOLERANCE] + grow):
        return True
    for k in range(ipar[I_N_DISCS]):
        j = P_DISC0 + 3 * k
        if _segment_off(a, b, s_max, complex(par[j], par[j + 1]), par[j + 2] + grow):
            return True
    return False


#: How much farther than a goal disc's radius (m) :func:`closing_ends_miss` wants a closing
#: step's end: the decode's roundings are about 1e-15 m.
END_MARGIN = 1e-6


@njit
def _segment_off(a, b, s_max, centre, radius):
    """Whether every point a + s·b, s in [0, s_max], lies more than ``radius`` +
    :data:`END_MARGIN` from ``centre`` (complex x + iy, metres); nan: False."""
    v = a - centre
    bb = b.real * b.real + b.imag * b.imag
    s = 0.0
    if bb > 0.0:
        s = min(max(-(v.real * b.real + v.imag * b.imag) / bb, 0.0), s_max)
    return abs(v + s * b) > radius + END_MARGIN


@njit_inline
def decode_col(z, r, matrix, offset, col):
    """Decoder column ``col`` for feature row ``r`` (``z[r] @ matrix + offset`` there): real
    features times complex columns, the real and imaginary sums apart in feature order (the
    products a complex product with 0j would add as ±0); :func:`~mjwalk.plan.stepcheck.check_into`
    decodes every column with it. Inlined into its callers (:func:`mjwalk._jit.njit_inline`):
    as a call it cost 3.6 times the inline loop (12 against 3.4 ns a column).

    Args:
        z: (n, d) standardized features.
        r: the row.
        matrix: (d, 2m + 3) the decoder's complex matrix.
        offset: (2m + 3,) its complex offset.
        col: the column.
    """
    sr = offset[col].real
    si = offset[col].imag
    for a in range(z.shape[1]):
        za = z[r, a]
        w = matrix[a, col]
        sr += za * w.real
        si += za * w.imag
    return complex(sr, si)


@njit_inline
def decode_real(z, r, matrix, offset, col):
    """The real part of decoder column ``col`` for feature row ``r`` (``z[r] @ matrix + offset``
    there, summed in feature order): the columns only some steps need (pelvis yaws, duration).

    Args:
        z: (n, d) standardized features.
        r: the row.
        matrix: (d, 2m + 3) the decoder's complex matrix.
        offset: (2m + 3,) its complex offset.
        col: the column.
    """
    return decode_col(z, r, matrix, offset, col).real


@njit_inline
def _cover(v, target, lip):
    """How far (m) from a point of clearance ``v`` every point keeps ``target`` (metres), the
    field being ``lip``-Lipschitz: (v - target) / lip, 0 when v is short of it (or nan)."""
    c = (v - target) / lip
    return c if c > 0.0 else 0.0


@njit
def landing_leg_clear(
    loc, m, left, end_yaw, rot, p, ankle_clear, end_clear, par, coef, x0, y0, res, nx, ny
):
    """Whether the landing leg of one step keeps ``P_LEG_CLEARANCE - P_LEG_STEP / 2`` from
    obstacles at heel strike, every point of it, as its probes prove (True when the slots are
    nan: no leg check).

    The leg reaches from the landing ankle ``loc[m]`` up to the swing-side hip of the end
    pelvis ``loc[m - 1]`` (``P_HIP_Y`` to its side, turned by ``end_yaw``, radians relative to
    the step's frame); seen from above it is the segment between them. The walk field's
    lookup is L-Lipschitz (:func:`field_lipschitz`: its own constant, sqrt(2) for the shipped
    scenes' fields, not 1), so a point whose clearance is v keeps ``target = P_LEG_CLEARANCE -
    P_LEG_STEP / 2`` everywhere within ``(v - target) / L`` of it. The probes march from the
    ankle (clearance ``ankle_clear``) towards the hip, each where the last one's cover ends
    plus ``(P_LEG_CLEARANCE - target) / L``: a probe keeping ``P_LEG_CLEARANCE`` covers that
    much back, so the gap between two probes is covered. They stop where the cover reaches
    the hip or enters the end pelvis's own (clearance ``end_clear``: a ball of radius
    ``(end_clear - target) / L``, when the hip lies in it), and a probe short of
    ``P_LEG_CLEARANCE`` refuses the step. Next to an obstacle the probes lie
    ``P_LEG_STEP / L`` apart, as a fixed spacing for that guarantee would; where the leg is
    clear by more, fewer are needed: sphere tracing (Hart 1996, "Sphere tracing: a geometric
    method for the antialiased ray tracing of implicit surfaces", The Visual Computer 12(10),
    527-545: steps along a ray "guaranteed not to penetrate" the surface, from "only a bound
    on the magnitude of the derivative").

    Args:
        loc: the decoded step (step frame, x + iy, metres): pelvis samples, landing ankle.
        m: pelvis samples per step.
        left: whether the swing (landing) foot is the left one.
        end_yaw: the end pelvis yaw relative to the step's frame, radians.
        rot: the step frame's turn into the world (a unit complex).
        p: the step frame's origin, world x + iy, metres.
        ankle_clear: the walk field at the landing ankle, or a lower bound of it (metres;
            at least ``target`` for the guarantee to hold from the ankle on).
        end_clear: the walk field at the end pelvis, or a lower bound of it (metres).
        par: the float slots (P_LEG_CLEARANCE, P_HIP_Y, P_LEG_STEP, P_FIELD_LIP).
        coef: the walk field's node values (ny, nx), metres (:func:`field_clearance`).
        x0: the field's origin x, metres.
        y0: its origin y, metres.
        res: its spacing, metres.
        nx: its number of columns.
        ny: its number of rows.
    """
    step = par[P_LEG_STEP]
    clear = par[P_LEG_CLEARANCE]
    if math.isnan(step) or math.isnan(clear) or step <= 0.0:
        return True
    s = 1.0 if left else -1.0
    ankle = loc[m]
    end = loc[m - 1]
    hip = end - s * par[P_HIP_Y] * complex(math.cos(end_yaw), math.sin(end_yaw))
    span = abs(hip - ankle)
    if span <= 0.0:
        return True
    u = (hip - ankle) / span
    lip = field_lipschitz(par)
    target = clear - 0.5 * step
    half = 0.5 * step / lip  # the cover of a probe that keeps ``clear``, back towards the last
    ball = _cover(end_clear, target, lip)  # the end pelvis's cover
    hip_in = within(hip - end, ball)
    at = 0.0
    v = ankle_clear
    while True:
        reach = at + _cover(v, target, lip)  # covered from the ankle up to here
        if reach >= span:
            return True
        if hip_in and within(ankle + reach * u - end, ball):
            return True
        at = min(reach + half, span)
        w = (ankle + at * u) * rot + p
        v = field_clearance(coef, x0, y0, res, nx, ny, w.real, w.imag)
        if not v >= clear:  # (nan too)
            return False


@njit
def toe_approach_clear(ankle, lift, toe, clear, start_clear, rot, p, par, coef, x0, y0, res,
                       nx, ny):  # fmt: skip
    """Whether the landing foot keeps ``clear - P_TOE_STEP / 2`` metres from obstacles on its
    way in, at the ankle and the toes, as its probes prove (True when the slots are nan or the
    lift-off foot is unknown: no check).

    The swing foot turns to its landing yaw by the step phase
    :data:`~mjwalk.body.legs.steps.SWING_TURNED` and then comes in along the chord from its
    lift-off footprint to its landing (:func:`mjwalk.body.legs.steps.swing_foot`). Where the
    chord is oblique to the foot (a curved walk's step: up to 55 degrees), the foot, turned,
    slides sideways on its way in, and its toes, 0.2 m ahead of the ankle, sweep beside the
    landing footprint that the ankle and toe checks passed. Over the chord's last
    ``P_TOE_SHARE``, back from the landing, probes of the ankle and the toes march as
    :func:`landing_leg_clear`'s do: from the landing (clearance ``start_clear``, the smaller
    of the ankle's and the toes'), each where the last one's cover ends plus
    ``(clear - target) / L`` (target ``clear - P_TOE_STEP / 2``, L the walk field's
    Lipschitz constant, :func:`field_lipschitz`), until the cover reaches the share's end; a
    probe of either point short of ``clear`` refuses the step. Every point of both paths then
    keeps the target; next to an obstacle the probes lie ``P_TOE_STEP / L`` apart.

    Args:
        ankle: the landing footprint (the step's local frame, x + iy, metres).
        lift: the lift-off footprint (same frame; nan: unknown).
        toe: the toe point's offset from the ankle at the landing yaw (same frame).
        clear: the clearance (metres) each probe keeps.
        start_clear: the walk field at the landing ankle and toes, the smaller, or a lower
            bound of it (metres).
        rot: the step frame's turn into the world (a unit complex).
        p: the step frame's origin, world x + iy, metres.
        par: the float slots (P_TOE_STEP, P_TOE_SHARE, P_FIELD_LIP).
        coef: the walk field's node values (ny, nx), metres (:func:`field_clearance`).
        x0: the field's origin x, metres.
        y0: its origin y, metres.
        res: its spacing, metres.
        nx: its number of columns.
        ny: its number of rows.
    """
    share = par[P_TOE_SHARE]
    step = par[P_TOE_STEP]
    if math.isnan(share) or math.isnan(step) or step <= 0.0 or math.isnan(lift.real):
        return True
    chord = ankle - lift
    length = abs(chord)
    span = share * length
    if span <= 0.0:
        return True
    u = chord / length
    lip = field_lipschitz(par)
    target = clear - 0.5 * step
    half = 0.5 * step / lip
    back = 0.0
    v = start_clear
    while True:
        reach = back + _cover(v, target, lip)
        if reach >= span:
            return True
        back = min(reach + half, span)
        a = ankle - back * u
        w = a * rot + p
        v = field_clearance(coef, x0, y0, res, nx, ny, w.real, w.imag)
        if not v >= clear:  # (nan too)
            return False
        w = (a + toe) * rot + p
        v = min(v, field_clearance(coef, x0, y0, res, nx, ny, w.real, w.imag))
        if not v >= clear:
            return False
