"""Decode, check and score sampled successor steps in one compiled loop (the hybrid A*'s hot path).

:func:`check_steps` does for every sampled step what :mod:`mjwalk.plan.hybrid` describes: the
affine decode of its features (:class:`~mjwalk.plan.hybrid._Decoder`) into pelvis samples, the
landing ankle and toes and the swing-knee probes in the step's local frame (x right, y forward,
as x + iy; metres), the turn into the world, the clearance test of every point against its own
limit (bilinear lookup in the workplace's walk field), the landing leg's probes from the ankle
towards the hip (:func:`landing_leg_clear`), the leg-reach tests, the stance-leg
lean test (:func:`stance_lean_ok`: the stance leg must follow the pelvis within the ankle's and
the hip's sideways ranges; :func:`stance_lean` is its NumPy form), the closing-step test (a
closing step must end in the goal area), and for the accepted steps the walked length
g, f = g + weight·h (plus far weight·(h - far from) beyond far from), the closed-list key,
heading and landing foot. As NumPy code this was some 60 small array operations per call; here
it is one loop over the rows (numba, see :mod:`mjwalk._jit`), with the same arithmetic.

Rows are grouped by predecessor: row r belongs to node r // per and is a closing step when
r % per >= n_walk. Per-row ``frame``/``left`` arrays (a start node's starters each turn their
own way) or per-node ones (length b) are both accepted.
"""

from __future__ import annotations

import functools
import math

import numpy as np

from mjwalk._jit import njit
from mjwalk.gait.features import MIN_DURATION
from mjwalk.world.clearance import bilinear_at

# Slots of the float parameter vector (see :func:`params`).
(
    P_KNEE_LEAD,
    P_KNEE_SIDE,
    P_FOOT_LENGTH,
    P_FOOT_REACH,
    P_LIFT_REACH,
    P_STRIDE,
    P_GOAL_X,
    P_GOAL_Y,
    P_TOLERANCE,
    P_GOAL_YAW,
    P_YAW_TOLERANCE,
    P_WEIGHT,
    P_CORNER_X,
    P_CORNER_Y,
    P_CELL,
    P_FIELD_X0,
    P_FIELD_Y0,
    P_FIELD_RES,
    P_DIST_X0,
    P_DIST_Y0,
    P_DIST_CELL,
    P_DIST_TOP_X,
    P_DIST_TOP_Y,
    P_KNEE_SHARE0,
    P_KNEE_SHARE1,
    P_STOP_REACH,
    P_POOL_SHARPNESS,
    P_HIP_Y,
    P_LEG_SPAN,
    P_EVERSION,
    P_INVERSION,
    P_ADDUCTION,
    P_ABDUCTION,
    P_FAR_WEIGHT,
    P_FAR_FROM,
    P_LEG_STEP,
    P_LEG_CLEARANCE,
    P_DIST_OFFSET,  # subtracted from the grid bound: a walk's spot lies this far from the goal
    P_PACE,  # the walker's preferred speed (m/s) of the energy cost; nan: length cost only
    P_HEADING_WEIGHT,  # weight of the squared heading error (heading_factor); nan or 0: none
    P_HEADING_FROM,  # the heading term stops this close (m) to the goal point
    P_START_YAW,  # the walker's heading (world radians) before a turn on the spot
    P_TURN_COST,  # cost (m per radian) of a starter's turn on the spot from it; nan: none
    P_DISC0,  # goal discs: x, y, radius of disc k at P_DISC0 + 3k (see in_goal)
) = range(44)
#: Most discs the goal area can be cut by (:func:`in_goal`); their count is I_N_DISCS. A
#: planner takes one fewer (``goal_within``): a walk to a spot keeps the planner's own goal
#: area as one more disc (:meth:`~mjwalk.plan.hybrid.HybridPlanner.plan`).
MAX_GOAL_DISCS = 7
N_PARAMS = P_DISC0 + 3 * MAX_GOAL_DISCS
# Slots of the integer parameter vector.
(
    I_M,
    I_Q,
    I_KNEE_COL0,
    I_KNEE_COL1,
    I_SPAN,
    I_BINS,
    I_FIELD_NX,
    I_FIELD_NY,
    I_DIST_NX,
    I_DIJKSTRA,
    I_CHORD,
    I_N_SUCCESSORS,
    I_N_STOPS,
    I_MAX_EXPANSIONS,
    I_NEAR_GOAL_EXPANSIONS,
    I_N_DISCS,
    N_IPARAMS,
) = range(17)


def params(**values) -> np.ndarray:
    """The float parameter vector from keyword slots (``knee_lead=...``, names as P_* lower)."""
    slots = [_slot("P_", name) for name in values]
    out = np.full(N_PARAMS, np.nan)
    out[slots] = list(values.values())
    return out


def iparams(**values) -> np.ndarray:
    """The integer parameter vector from keyword slots (names as I_* lower)."""
    slots = [_slot("I_", name) for name in values]
    out = np.zeros(N_IPARAMS, dtype=np.int64)
    out[slots] = list(values.values())
    return out


@functools.lru_cache(maxsize=256)
def _slot(prefix: str, name: str) -> int:
    """The slot of keyword ``name`` (P_/I_ constants; KeyError for an unknown name)."""
    return globals()[prefix + name.upper()]


@njit
def _clearance(coef, x0, y0, res, nx, ny, x, y):
    """:meth:`ClearanceField.__call__` at one point (x, y) (metres) from the field's node
    values ``coef`` (ny, nx): bilinear clearance, metres, as value = a + b·tx + c·ty + d·tx·ty
    with the cell's coefficients a = v00, b = v01 - v00, c = v10 - v00,
    d = v11 - v10 - v01 + v00 formed on the fly (a table of them held four times the field)."""
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


@njit
def _beyond(v, r):
    """``abs(v) > r`` for a complex ``v``, without the hypot where the squares decide it (r > 0):
    |v|² beyond r² by more than 1e-12 relative is beyond r, and short of it by as much is
    not, whatever the roundings (a few ulp); only the band between (and nan) takes abs(v)."""
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
def _turn(angle):
    """exp(i·angle) for a real angle (radians): (cos, sin), as the complex exp computes it
    (exp(0) = 1 times each), without the exp."""
    return complex(math.cos(angle), math.sin(angle))


@njit
def _within(v, r):
    """``abs(v) <= r`` for a complex ``v``, as :func:`_beyond` decides it (nan: False)."""
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
    cell (i · span + j) and, with heading bins, times bins plus its heading bin."""
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
    P_DISC0 + 3k: e.g. the places from which the work there is within reach) and, with a goal
    yaw, facing it within its tolerance."""
    if _beyond(p - complex(par[P_GOAL_X], par[P_GOAL_Y]), par[P_TOLERANCE]):
        return False
    for k in range(ipar[I_N_DISCS]):
        j = P_DISC0 + 3 * k
        if _beyond(p - complex(par[j], par[j + 1]), par[j + 2]):
            return False
    goal_yaw = par[P_GOAL_YAW]
    if math.isnan(goal_yaw):
        return True
    diff = (heading - goal_yaw + math.pi) % (2.0 * math.pi) - math.pi
    return abs(diff) <= par[P_YAW_TOLERANCE]


def stance_lean(
    pelvis: np.ndarray, yaw: np.ndarray, stance: np.ndarray, stance_left: bool, par: np.ndarray
) -> tuple[np.ndarray, np.ndarray]:
    """The stance leg's sideways lean at pelvis samples, as :func:`stance_lean_ok` takes it
    (NumPy; the reference of the compiled check, and for walks already planned).

    Args:
        pelvis: (k, 2) pelvis positions, yaw: (k,) pelvis headings (radians), stance: the stance
            foot (x, y, heading), all in one frame (metres, radians from +x).
        stance_left: whether the stance foot is the left one.
        par: :func:`params` with the P_HIP_Y and P_LEG_SPAN slots.

    Returns:
        (ankle inversion, hip abduction) (k,) each, radians, anatomical signs (negative:
        eversion, adduction), of a straight leg keeping the sole level sideways.
    """
    s = 1.0 if stance_left else -1.0
    yaw = np.asarray(yaw, float)
    left = np.stack([-np.sin(yaw), np.cos(yaw)], -1)
    v = np.asarray(stance[:2], float) - (np.asarray(pelvis, float) + s * par[P_HIP_Y] * left)
    span = par[P_LEG_SPAN]
    h = np.sqrt(np.maximum(span**2 - (v**2).sum(-1), 1e-12))
    foot_left = np.array([-math.sin(stance[2]), math.cos(stance[2])])
    inv = s * np.arctan2(v @ foot_left, h)
    abd = s * np.arcsin(np.clip((v * left).sum(-1) / span, -1.0, 1.0))
    return inv, abd


def lean_in_range(inv: np.ndarray, abd: np.ndarray, par: np.ndarray) -> bool:
    """Whether every lean of :func:`stance_lean` is within the P_EVERSION .. P_ABDUCTION ranges."""
    return bool(
        np.all((inv >= -par[P_EVERSION]) & (inv <= par[P_INVERSION]))
        and np.all((abd >= -par[P_ADDUCTION]) & (abd <= par[P_ABDUCTION]))
    )


@njit
def _grid_bound(dist, x0, y0, cell, top_x, top_y, nx, x, y):
    """:meth:`GoalDistance.__call__`'s grid bound at (``x``, ``y``) (metres) on the flat field
    ``dist`` (origin ``x0``, ``y0``, spacing ``cell``, last column/row ``top_x``/``top_y``,
    ``nx`` columns): the nearest node's distance to the goal less the way to that node."""
    gi = min(max(np.rint((x - x0) / cell), 0.0), top_x)
    gj = min(max(np.rint((y - y0) / cell), 0.0), top_y)
    off = math.hypot(x - (x0 + gi * cell), y - (y0 + gj * cell))
    return dist[int(gj) * nx + int(gi)] - off


@njit
def _grid_sight(dist, x0, y0, cell, top_x, top_y, nx, x, y):
    """Whether the goal is in sight from (``x``, ``y``): the sight flag of the nearest node of
    the flat field ``dist`` (:meth:`GoalDistance.flat_bound`: the bounds, then the flags)."""
    gi = min(max(np.rint((x - x0) / cell), 0.0), top_x)
    gj = min(max(np.rint((y - y0) / cell), 0.0), top_y)
    return dist[int((top_y + 1.0) * nx) + int(gj) * nx + int(gi)] > 0.5


@njit
def downhill_costs(xy, probes, clear, cx0, cy0, cres, floor, radius, dist, gx0, gy0, gcell,
                   top_x, top_y, goal_x, goal_y, offset):  # fmt: skip
    """:meth:`~mjwalk.plan.hybrid.HybridPlanner.default_heading`'s costs at ``xy + probes``
    (k, 2), with NumPy's arithmetic of :meth:`ClearanceField.__call__` on the obstacle field
    ``clear`` (origin cx0, cy0, spacing cres), :meth:`Workplace.edge_distance` on ``floor``
    (xmin, ymin, xmax, ymax), and :meth:`GoalDistance.__call__` on the flat grid bound
    ``dist`` (origin gx0, gy0, cell gcell, last column/row top_x, top_y) less ``offset``, or
    the straight line to (``goal_x``, ``goal_y``) where longer: the distance to the goal,
    plus 1e3 where the walking clearance is short of ``radius`` (metres)."""
    n = probes.shape[0]
    out = np.empty(n)
    for k in range(n):
        x = xy[0] + probes[k, 0]
        y = xy[1] + probes[k, 1]
        c = bilinear_at(clear, cx0, cy0, cres, x, y)
        edge = min(min(min(x - floor[0], floor[2] - x), y - floor[1]), floor[3] - y)
        free = min(c, edge) >= radius
        bound = _grid_bound(dist, gx0, gy0, gcell, top_x, top_y, int(top_x) + 1, x, y) - offset
        euclid = math.hypot(x - goal_x, y - goal_y)
        out[k] = max(euclid, bound) + (0.0 if free else 1e3)
    return out


@njit
def stance_lean_ok(z, r, matrix, offset, loc, m, ankle, foot_heading, stance_left, par):
    """Whether the stance leg can follow the pelvis samples of one step without leaving the
    ankle's eversion/inversion or the hip's adduction/abduction range.

    The leg synthesis (:mod:`mjwalk.body.legs`) keeps the stance sole level sideways, so the
    ankle takes the whole sideways lean of the hip-to-ankle line in the stance foot's frame,
    ``atan2(u_y, h)`` (its inversion, :func:`~mjwalk.body.legs.leg_ik`), and the upright pelvis
    leaves the hip the sideways lean of that line in the pelvis frame. Both are taken with the
    leg stretched straight (``P_LEG_SPAN``: the hip as high above the ankle as it can be), so a
    step refused here cannot be followed at any pelvis height: the check is a necessary
    condition, not a model of the synthesis's pelvis height. The hip's lean is that of a
    straight, unrotated leg, ``asin(p_y / span)``.

    Args:
        z, r: the standardized features and the row of the step.
        matrix, offset: the decoder, with the pelvis yaw at the m samples in columns
            m + 2 .. 2m + 1 (real parts, radians relative to the step's frame).
        loc: the decoded pelvis samples (m,) of the row, step frame (x right, y forward).
        ankle: the stance foot (the point under its ankle), step frame, x + iy.
        foot_heading: the stance foot's heading relative to the step's frame (radians).
        stance_left: whether the stance foot is the left one.
        par: :func:`params` with the P_HIP_Y .. P_ABDUCTION slots (metres, radians).
    """
    return _lean_ok(
        z, r, matrix, offset, loc, m, ankle, foot_heading, stance_left, par, lean_limits(par)
    )


@njit
def lean_limits(par):
    """The stance-lean limits of ``par`` as slopes (atan2(y, h) and asin(y / span) are
    monotonic in y): tan of the eversion and inversion, sin of the adduction and abduction."""
    return (
        math.tan(par[P_EVERSION]),
        math.tan(par[P_INVERSION]),
        math.sin(par[P_ADDUCTION]),
        math.sin(par[P_ABDUCTION]),
    )


@njit
def _decode_real(z, r, matrix, offset, col):
    """The real part of decoder column ``col`` for feature row ``r`` (``z[r] @ matrix + offset``
    there, summed in feature order): the columns only some steps need (pelvis yaws, duration)."""
    v = offset[col].real
    for a in range(z.shape[1]):
        v += z[r, a] * matrix[a, col].real
    return v


@njit
def _lean_ok(z, r, matrix, offset, loc, m, ankle, foot_heading, stance_left, par, limits):
    """:func:`stance_lean_ok` with :func:`lean_limits` made once per batch of steps."""
    s = 1.0 if stance_left else -1.0
    hip_y = par[P_HIP_Y]
    span = par[P_LEG_SPAN]
    foot = complex(math.cos(-foot_heading), math.sin(-foot_heading))
    tan_ev, tan_inv, sin_add, sin_abd = limits
    for j in range(m):
        psi = _decode_real(z, r, matrix, offset, m + 2 + j)
        turn = complex(math.cos(psi), math.sin(psi))
        # the hip joint centre: the left one is hip_y to the pelvis's left (-x turned by psi)
        v = ankle - (loc[j] - s * hip_y * turn)  # hip to ankle, step frame
        h = math.sqrt(max(span * span - (v.real * v.real + v.imag * v.imag), 1e-12))
        # ankle: the sideways lean atan2(s u_y, h) in the stance foot's frame (left = -x
        # turned by its heading)
        inv = -s * (v * foot).real
        if inv < -tan_ev * h or inv > tan_inv * h:
            return False
        # hip: the sideways lean asin(s p_y / span) of a straight leg in the pelvis frame
        abd = -s * (v * turn.conjugate()).real
        if abd < -sin_add * span or abd > sin_abd * span:
            return False
    return True


@njit
def landing_leg_clear(loc, m, left, end_yaw, rot, p, pelvis_thr, par, coef, x0, y0, res, nx, ny):
    """Whether the landing leg of one step keeps ``P_LEG_CLEARANCE`` from obstacles at heel
    strike (True when the slots are nan: no leg check).

    The leg reaches from the landing ankle ``loc[m]`` up to the swing-side hip of the end
    pelvis ``loc[m - 1]`` (``P_HIP_Y`` to its side, turned by ``end_yaw``, radians relative to
    the step's frame); seen from above it is the segment between them. Probes lie on it every
    ``P_LEG_STEP`` metres from the ankle (whose own check, FOOT_CLEARANCE, covers the first
    half spacing) until the end pelvis's check covers the rest: a probe within
    ``pelvis_thr - P_LEG_CLEARANCE`` of the end pelvis already has that clearance, since the
    clearance is 1-Lipschitz. For the same reason every point of the segment keeps
    ``P_LEG_CLEARANCE - P_LEG_STEP / 2`` when every probe keeps ``P_LEG_CLEARANCE``.

    Args:
        loc: the decoded step (step frame, x + iy, metres): pelvis samples, landing ankle.
        left: whether the swing (landing) foot is the left one.
        rot, p: the step frame's turn into the world and its origin (world x + iy).
        pelvis_thr: the clearance the pelvis samples keep (metres).
        coef, x0, y0, res, nx, ny: the walk field (:func:`_clearance`).
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
    covered = pelvis_thr - clear  # probes this close to the end pelvis need no check
    k = 1
    while k * step < span:
        q = ankle + (k * step) * u
        if _within(q - end, covered):
            break
        w = q * rot + p
        if _clearance(coef, x0, y0, res, nx, ny, w.real, w.imag) < clear:
            return False
        k += 1
    return True


@njit
def step_energy(length, duration, pace):
    """A step's cost in metres walked at the walker's preferred speed ``pace`` (m/s): its
    ``length`` (m) times c(v) = (pace / v + v / pace) / 2 at its speed v = length / duration
    (s; at least :data:`~mjwalk.gait.features.MIN_DURATION`), that is
    (pace·T + L² / (pace·T)) / 2. c is the metabolic cost of walking a metre at speed v
    relative to its least, at the preferred speed: Ralston's net power a + b·v² per kg
    (Ralston, "Energy-speed relation and optimal speed during level walking", Int Z angew
    Physiol 17:277-283, 1958: 29 + 0.0053 v² cal/kg/min, v in m/min) gives a/v + b·v per
    metre, least at v* = sqrt(a/b) (1.23 m/s there), and people walk at about that speed
    (ibid.; Zarrugh, Todd & Ralston, Eur J Appl Physiol 33:293-306, 1974); the walker's own
    preferred speed stands for v*. c >= 1, so the walked length is still a lower bound and the
    heuristic stays admissible; a step that stands still costs pace·T/2."""
    t = max(duration, MIN_DURATION) * pace
    return 0.5 * (t + length * length / t)


@njit
def heading_factor(heading, end, goal, weight):
    """A step's cost factor 1 + weight·ψ² for heading towards a goal in sight: ψ (radians) is
    the angle between the walker's ``heading`` (world radians; the search passes the mean of
    the step's start and end frame headings, which averages out the pelvis's yaw swing
    between left and right heel strikes) and the straight direction from the step's ``end``
    to the ``goal`` (complex world points). People walking to a goal keep their body turned
    towards it: in the inverse optimal control of human walking by Mombaur, Truong & Laumond
    ("From human to humanoid locomotion - an inverse optimal control approach", Auton Robot
    28:369-383, 2010) the cost per second is 1 (time) + ... + 5.2·ψ² (their weights α0 = 1,
    α4 = 5.2); a step's cost, its walked metres at the preferred pace, is its time times the
    pace, so the ratio carries over as this factor. The factor is >= 1: the heuristic stays
    admissible."""
    d = goal - end
    psi = math.atan2(d.imag, d.real) - heading
    psi = (psi + math.pi) % (2.0 * math.pi) - math.pi
    return 1.0 + weight * psi * psi


@njit
def check_steps(
    z, matrix, offset, per, n_walk, frame, left, near, node, thr, par, ipar, coef, dist
):
    """Decode, check and score the sampled steps ``z`` (n, d) of b = n // per predecessors.

    Args:
        z: standardized features; matrix (d, 2m + 3) and offset (2m + 3,): the complex affine
            decode (:class:`~mjwalk.plan.hybrid._Decoder`; the pelvis-yaw columns only with the
            stance-lean slots set, the duration column only with P_PACE set).
        per, n_walk: rows per predecessor, and how many of them are walking steps (the rest
            are closing steps).
        frame, left: heading (radians) of each step's local frame and whether its swing foot
            is the left one, per row (n,) or per predecessor (b,).
        near: (b,) whether the predecessor may stop (else its closing rows are dropped
            uncounted).
        node: (b, 4) or (b, 5) complex per predecessor: end point p, the foot its step
            landed and the foot behind that (world x + iy; nan: none yet), g (real part) and,
            in column 4, the landed foot's heading (real part, world radians; nan: none).
            The landed foot is the stance foot of the step drawn from the predecessor: with
            its heading, and the decoder's pelvis-yaw columns, and the P_HIP_Y .. P_ABDUCTION
            slots set, a step whose stance leg cannot follow it is rejected
            (:func:`stance_lean_ok`).
        thr: (m + 4,) clearance limits of the pelvis samples, ankle, toes and the two knees
            (the landing leg's probes keep P_LEG_CLEARANCE: :func:`landing_leg_clear`).
        par, ipar: :func:`params` / :func:`iparams`.
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
        out, accepted, drawn,
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
    keys, f, g, end, heading, frame, foot, foot heading, left (n,) and the decode row (m + 2,)."""
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
def check_into(
    z, matrix, offset, per, n_walk, frame, left, near, node, thr, par, ipar, coef, dist, out,
    accepted, drawn,
):  # fmt: skip
    """:func:`check_steps` into buffers: ``out`` from :func:`new_buffers` (at least n rows)
    takes the accepted steps in its first rows, ``accepted`` and ``drawn`` (at least b, set
    to 0 here) the per-predecessor counts; returns the number of accepted steps. The search
    keeps one set of buffers instead of a dozen new arrays per expansion."""
    n = z.shape[0]
    d = z.shape[1]
    b = n // per if per > 0 else 0
    m = ipar[I_M]
    q = ipar[I_Q]
    kc0 = ipar[I_KNEE_COL0]
    kc1 = ipar[I_KNEE_COL1]
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
    for r in range(n):
        i = r // per
        closing = r % per >= n_walk
        if closing and not near[i]:
            continue  # dropped uncounted
        drawn[i] += 1
        fr = frame[r] if per_row else frame[i]
        lf = left[r] if per_row else left[i]
        # decode: local = z @ matrix + offset (real features times complex columns: the real
        # and imaginary sums apart, the products a complex product with 0j would add as ±0)
        for c in range(m + 2):
            sr = offset[c].real
            si = offset[c].imag
            for a in range(d):
                za = z[r, a]
                w = matrix[a, c]
                sr += za * w.real
                si += za * w.imag
            loc[c] = complex(sr, si)
        if fr != fr_last:  # the turn into the world, once per frame heading (rows share it)
            rot = complex(math.sin(fr), -math.cos(fr))
            fr_last = fr
        p = node[i, 0]
        # clearance of pelvis samples, ankle, toes, knees (world)
        ok = True
        for j in range(m + 1):
            w = loc[j] * rot + p
            if _clearance(coef, fx0, fy0, fres, fnx, fny, w.real, w.imag) < thr[j]:
                ok = False
                break
        if not ok:
            continue
        yaws = loc[m + 1]
        ankle = loc[m] * rot + p
        toe = ankle + (par[P_FOOT_LENGTH] * 1j) * rot * _turn(yaws.real)
        if _clearance(coef, fx0, fy0, fres, fnx, fny, toe.real, toe.imag) < thr[m + 1]:
            continue
        # the landing leg, from the ankle towards its hip at the step's end (heel strike: the
        # shin leans back over the heel, the toes-up heel reaches behind the flat footprint),
        # probed every P_LEG_STEP out to where the end pelvis's own clearance covers it
        if not landing_leg_clear(loc, m, lf, yaws.imag, rot, p, thr[0], par, coef, fx0, fy0,
                                 fres, fnx, fny):  # fmt: skip
            continue
        lat = (1j if lf else -1j) * par[P_KNEE_SIDE]
        for kk in range(2):
            col = kc0 if kk == 0 else kc1
            share = par[P_KNEE_SHARE0] if kk == 0 else par[P_KNEE_SHARE1]
            fwd = 1j * _turn(yaws.imag * share)
            knee = (loc[col] + fwd * (par[P_KNEE_LEAD] + lat)) * rot + p
            if _clearance(coef, fx0, fy0, fres, fnx, fny, knee.real, knee.imag) < thr[m + 2 + kk]:
                ok = False
                break
        if not ok:
            continue
        # leg reach, in the local frame (nan feet: comparisons with nan are False)
        rc = rot.conjugate()
        landed = (node[i, 1] - p) * rc
        behind = (node[i, 2] - p) * rc
        reach = par[P_FOOT_REACH]
        for j in range(m):
            if _beyond(loc[j] - landed, reach):
                ok = False
                break
        if not ok:
            continue
        lift = par[P_LIFT_REACH]
        for j in range(q):
            if _beyond(loc[j] - behind, lift):
                ok = False
                break
        if not ok:
            continue
        if _beyond(loc[m] - behind, par[P_STRIDE]) or _beyond(loc[m] - loc[m - 1], reach):
            continue
        # the stance leg's sideways lean (the landed foot is this step's stance foot)
        if lean and not (math.isnan(landed.real) or math.isnan(node[i, 4].real)):
            if not _lean_ok(z, r, matrix, offset, loc, m, landed, node[i, 4].real - fr,
                            not lf, par, limits):  # fmt: skip
                continue
        end = loc[m - 1] * rot + p
        th = fr + yaws.imag
        if closing and not in_goal(end, th, par, ipar):  # a closing step must end the walk
            continue
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
            seg = step_energy(seg, _decode_real(z, r, matrix, offset, 2 * m + 2), pace)
        if par[P_TURN_COST] > 0.0 and math.isnan(node[i, 1].real):
            # a starter set off after a turn on the spot from the walker's heading: its time
            turned = (fr - par[P_START_YAW] + math.pi) % (2.0 * math.pi) - math.pi
            seg += par[P_TURN_COST] * abs(turned)
        ex, ey = end.real, end.imag
        h = math.hypot(ex - goal.real, ey - goal.imag)
        if ipar[I_DIJKSTRA]:
            bound = _grid_bound(
                dist, par[P_DIST_X0], par[P_DIST_Y0], par[P_DIST_CELL], par[P_DIST_TOP_X],
                par[P_DIST_TOP_Y], ipar[I_DIST_NX], ex, ey,
            ) - par[P_DIST_OFFSET]  # fmt: skip
            if bound > h:
                h = bound
        hw = par[P_HEADING_WEIGHT]
        if hw > 0.0 and not closing and h > par[P_HEADING_FROM]:
            sight = _grid_sight(
                dist, par[P_DIST_X0], par[P_DIST_Y0], par[P_DIST_CELL], par[P_DIST_TOP_X],
                par[P_DIST_TOP_Y], ipar[I_DIST_NX], ex, ey,
            )  # fmt: skip
            if sight:
                seg *= heading_factor(fr + 0.5 * yaws.imag, end, goal, hw)
        g = node[i, 3].real + seg
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
