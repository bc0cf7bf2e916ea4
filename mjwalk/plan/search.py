"""The hybrid A*'s search loop, compiled (:mod:`mjwalk._jit`).

:func:`search` is Algorithm 1 of agethen2018 as :class:`~mjwalk.plan.hybrid.HybridPlanner`
describes it: an open list (binary heap by f = g + weight·h, ties by push order), a closed set of
cell keys, and for every expanded node ``n_successors`` GP successors of its step
(:func:`mjwalk.gait.gpdraw.sample`), plus ``n_stops`` closing steps when it lies within the stop
reach of the goal, decoded, checked and scored by :func:`~mjwalk.plan.stepcheck.check_steps`
(its buffered form :func:`~mjwalk.plan.stepcheck.check_into`).
Near the goal a cell closes after ``near_goal_expansions`` expansions, and a node popped in a
closed cell there still draws its closing steps. The first expansion (the start node) takes the
starters drawn by the caller (the KDE lives in SciPy).

A successor whose pelvis and ankle keep their clearances is scored and pushed at once; the
checks of its legs and feet (:func:`~mjwalk.plan.stepcheck.legs_clear`: toes, landing leg,
knees, reach, the foot's way in, stance lean) run when it is popped to be taken up
(:func:`~mjwalk.plan.stepcheck.legs_recheck`), and one that fails them is dropped there,
before anything depends on it. Most pushed successors are never popped (the search ends
first), so most of those checks are never needed. The walk is the same as with every check
at the push: the steps the legs refuse change neither the other nodes' f nor their push order
(ties go by push order, which the dropped steps only skip), so the others pop in the same
order; only the count of rejected steps is smaller (it counts the checks that ran).

Everything is in one compiled function because an expansion is small: ten successors, twenty
checked points each. As Python, the loop's bookkeeping (heap, closed set, node lists) cost as
much as the draws. Nodes live in growing arrays; node 0 is the start. Random numbers come from
the caller's Generator in the order the Python loop drew them.

numba's on-disk cache of :func:`search` is keyed by this file's text only, not by the compiled
functions it calls from other modules (:func:`~mjwalk.plan.stepcheck.check_into` and its helpers
in :mod:`~mjwalk.plan.stepgeom`, :mod:`~mjwalk.plan.lean` and :mod:`~mjwalk.plan.stepcost`;
:func:`~mjwalk.gait.gpdraw.sample`): a change there must come with a change to this file's text,
or processes keep running the old machine code (touching the file is not enough). The record of
such changes is ``docs/decisions/106-planner-compiled-loop.md`` (last: check_into tests the
end pelvis and the ankle before the other pelvis samples, and a node keeps its closed-list key
from the push; before it, the legs' checks
deferred to the pop, :func:`~mjwalk.plan.stepcheck.legs_recheck`; before it, the GP draws into
work arrays kept for the whole search and into ``feats`` itself,
:func:`~mjwalk.gait.gpdraw.sample_into`, and closing draws whose mean cannot end the walk
left undrawn, :func:`~mjwalk.plan.stepgeom.closing_ends_far`, issue 50; before it, the step
decode inlined by numba, the step decoded column by column as the clearance test needs it
and the lifting foot's turn once per node).
"""

from __future__ import annotations

import heapq
import math

import numpy as np
from numba import types
from numba.typed import Dict

from mjwalk._jit import njit
from mjwalk.gait.gpdraw import (
    choose_rows,
    compose_into,
    draw_numbers,
    exp_rows_into,
    half_sq_into,
    new_work,
    sample_into,
    variance,
)
from mjwalk.plan.slots import (
    I_M,
    I_MAX_EXPANSIONS,
    I_N_STOPS,
    I_N_SUCCESSORS,
    I_NEAR_GOAL_EXPANSIONS,
    P_GOAL_X,
    P_GOAL_Y,
    P_POOL_SHARPNESS,
    P_STOP_REACH,
)
from mjwalk.plan.stepcheck import check_into, legs_recheck, new_buffers
from mjwalk.plan.stepgeom import cell_key, closing_ends_far, closing_ends_miss, in_goal, within

#: :func:`search` outcomes.
FOUND, EXHAUSTED, BUDGET = 0, 1, 2


@njit
def _grow1(a, n):
    out = np.empty(n, dtype=a.dtype)
    out[: a.shape[0]] = a
    return out


@njit
def _grow2(a, n):
    out = np.empty((n, a.shape[1]), dtype=a.dtype)
    out[: a.shape[0]] = a
    return out


@njit
def _predecessor_row(nid, pos, foot, fhead, g, parent, out):
    """Node ``nid``'s row for :func:`~mjwalk.plan.stepcheck.check_into` (its ``node``, (1, 5))
    into ``out``: its end point, the foot its step landed and the foot behind that, g, and
    their headings (the landed foot's, the lifting foot's); nan where there is none (the
    start node, node 0, has no feet)."""
    nan_c = complex(np.nan, np.nan)
    out[0, 0] = pos[nid]
    out[0, 3] = g[nid]
    if nid == 0:
        out[0, 1] = nan_c
        out[0, 2] = nan_c
        out[0, 4] = nan_c
    else:
        out[0, 1] = foot[nid]
        out[0, 2] = foot[parent[nid]]
        # the landed foot's heading, and the lifting foot's (the knee probes')
        out[0, 4] = complex(fhead[nid], fhead[parent[nid]])


@njit
def _closing_draws(x, n, rng, gp, reach, sharp, matrix, offset, frame, p, par, ipar, work, rows,
                   z, o0):  # fmt: skip
    """``n`` closing steps drawn from the predecessor ``x`` (1, d) by the closing-step GP
    ``gp``, as :func:`~mjwalk.gait.gpdraw.sample` draws them (the same random numbers), for
    a node at ``p`` (world x + iy) whose steps turn by ``frame`` (radians), into the rows
    ``o0`` .. ``o0`` + n - 1 of ``z`` (``work``, ``rows``: as for
    :func:`~mjwalk.gait.gpdraw.sample_into`). Returns False, with the random numbers drawn
    and ``z`` untouched, when none of the steps can end the walk.

    Most closing draws near the goal cannot end the walk wherever their variance puts them.
    Where even their mean cannot put them in the goal area, they are not drawn at all
    (:func:`~mjwalk.plan.stepgeom.closing_ends_far`): the mean's decoded end lies within
    ``reach`` ((r, spread) and f_z of
    :meth:`~mjwalk.plan.decoder.StepDecoder.closing_reach`) of its value at the nearest
    inducing input, which needs h but no kernel row. The others
    (:func:`~mjwalk.plan.stepgeom.closing_ends_miss`, with the variance's cap ``gp[9]``)
    skip the dense variance (:func:`~mjwalk.gait.gpdraw.variance`) and come out at their
    mean and residual (sd 0), which ends outside the goal area as well, so
    :func:`~mjwalk.plan.stepcheck.check_into` rejects them as it would the true draws (their
    features are never read: only accepted steps become nodes).
    """
    mean, h, e = work[:3]
    half_sq_into(x, gp, h)
    u, member, eps = draw_numbers(rng, 1, n, gp)
    m = ipar[I_M]
    sd_cap = math.sqrt(gp[9])
    near = 0
    for j in range(1, h.shape[1]):
        if h[0, j] < h[0, near]:
            near = j
    # h's roundings (far below 1e-12 of its terms) taken against the bound
    xx = 0.0
    for a in range(x.shape[1]):
        xx += x[0, a] * gp[2][a] * x[0, a]
    h_up = h[0, near] + 1e-12 * (1.0 + xx + gp[1][near])
    grow = reach[0][0] * math.sqrt(-2.0 * math.expm1(-h_up)) + reach[0][1]
    if closing_ends_far(reach[1][near], grow, eps, n, sd_cap, matrix, offset, m, frame, p, par,
                        ipar):  # fmt: skip
        return False
    exp_rows_into(gp, h, mean, e)
    choose_rows(h, e, u, member, n, gp, sharp, work, rows)
    if closing_ends_miss(mean, rows[:n], eps, gp[7], sd_cap, matrix, offset, m, frame, p, par,
                         ipar):  # fmt: skip
        var = 0.0
    else:
        var = variance(e, gp)[0]
    compose_into(mean, var, rows, eps, n, gp[7], z, o0)
    return True


@njit
def search(
    z0, frame0, left0, start, heading, f0, gps, stops, reaches, rng, matrix, offset, thr, par,
    ipar, coef, dist,
):  # fmt: skip
    """Search from ``start`` (world x + iy, facing ``heading``) to the goal of ``par``.

    Args:
        z0: (s, d) the starters' standardized features, for the first expansion.
        frame0: (s,) the starters' frame headings, radians from +x CCW.
        left0: (s,) whether each starter's swing foot is the left one.
        start: the start point, world x + iy, metres.
        heading: the start heading, radians from +x CCW.
        f0: the start node's f, metres.
        gps: :attr:`TransitionGP.kernel` of the walking GPs, for a left and a right predecessor.
        stops: the same of the closing-step GPs (unused when ``ipar`` has no stops).
        reaches: for each closing-step GP, the reach of its mean's decoded end
            (:meth:`~mjwalk.plan.decoder.StepDecoder.closing_reach`: (r, spread) and f_z).
        rng: numpy Generator.
        matrix: the decoder's complex matrix, as for :func:`~mjwalk.plan.stepcheck.check_steps`.
        offset: the decoder's complex offset.
        thr: the clearance limits, as for :func:`~mjwalk.plan.stepcheck.check_steps`.
        par: the float slots, the search's filled (the guide's among them:
            :mod:`mjwalk.plan.guide`).
        ipar: the integer slots, the search's filled.
        coef: the walk field's node values (ny, nx), metres.
        dist: the goal distance's flat grid bound (:meth:`GoalDistance.flat_bound`).

    Returns:
        (outcome, goal node, [expansions, generated, rejected (by the checks that ran: the
        legs' checks run only on steps taken up), stop draws], and per node:
        parent, feature row, end point, frame heading, swing foot is left; the feature rows
        and whether each is a closing step).
    """
    d = matrix.shape[0]
    gp_left, gp_right = gps
    stop_left, stop_right = stops
    reach_left, reach_right = reaches
    n_succ = ipar[I_N_SUCCESSORS]
    n_stop = ipar[I_N_STOPS]
    max_exp = ipar[I_MAX_EXPANSIONS]
    near_n = ipar[I_NEAR_GOAL_EXPANSIONS]
    stop_reach = par[P_STOP_REACH]
    sharp = par[P_POOL_SHARPNESS]
    goal = complex(par[P_GOAL_X], par[P_GOAL_Y])
    nan_c = complex(np.nan, np.nan)
    cap = 256
    parent = np.empty(cap, dtype=np.int64)
    row = np.empty(cap, dtype=np.int64)
    pos = np.empty(cap, dtype=np.complex128)
    head = np.empty(cap)
    frame = np.empty(cap)
    g = np.empty(cap)
    foot = np.empty(cap, dtype=np.complex128)  # where the node's step landed (nan: none)
    fhead = np.empty(cap)  # ... and the landed foot's heading (nan: none)
    left = np.empty(cap, dtype=np.bool_)
    legs_due = np.empty(cap, dtype=np.bool_)  # the legs' checks not run yet (check_into)
    nkey = np.empty(cap, dtype=np.int64)  # the node's closed-list key (check_into's, at push)
    parent[0] = -1
    row[0] = -1
    pos[0] = start
    head[0] = heading
    frame[0] = heading
    g[0] = 0.0
    foot[0] = nan_c
    fhead[0] = np.nan
    left[0] = False
    legs_due[0] = False
    nkey[0] = cell_key(start, heading, par, ipar)
    nn = 1
    fcap = 256
    feats = np.empty((fcap, d))
    closing = np.empty(fcap, dtype=np.bool_)
    nf = 0
    heap = [(f0, 0, 0)]
    closed = {-1}
    closed.discard(-1)
    near_expanded = Dict.empty(key_type=types.int64, value_type=types.int64)
    counter = 1
    expansions = 0
    generated = 0
    rejected = 0
    stop_draws = 0
    outcome = EXHAUSTED
    goal_node = -1
    one_near = np.zeros(1, dtype=np.bool_)
    one_frame = np.empty(1)
    one_left = np.empty(1, dtype=np.bool_)
    one_node = np.empty((1, 5), dtype=np.complex128)
    due_node = np.empty((1, 5), dtype=np.complex128)  # a due node's predecessor, as one_node
    # the step checks' outputs, one set for all expansions (the start node's starters or a
    # node's walking and closing steps)
    bufs = new_buffers(max(z0.shape[0], n_succ + n_stop), ipar[I_M])
    rows, keys, fs, gs, ends, ths, frames, feet, fheads = bufs[:9]
    lefts = bufs[9]
    due_loc = np.empty_like(bufs[10])
    accepted = np.zeros(1, dtype=np.int64)
    drawn = np.zeros(1, dtype=np.int64)
    # the draws' work arrays, one set per GP, and the successors drawn into feats itself
    work_left = new_work(1, gp_left)
    work_right = new_work(1, gp_right)
    work_stop_left = new_work(1, stop_left)
    work_stop_right = new_work(1, stop_right)
    draw_rows = np.empty(max(n_succ, n_stop, 1), dtype=np.intp)
    while len(heap) > 0:
        nid = heapq.heappop(heap)[2]
        p = pos[nid]
        hd = head[nid]
        key = nkey[nid]
        done = in_goal(p, hd, par, ipar)
        near = n_stop > 0 and within(p - goal, stop_reach)
        if key in closed and not done and not near:
            continue
        if legs_due[nid]:
            # the legs' checks of its step, left by check_into until the step is taken up
            # (most accepted steps never are): one that fails them is dropped, as check_into
            # would have dropped it, before anything depends on it
            _predecessor_row(parent[nid], pos, foot, fhead, g, parent, due_node)
            if not legs_recheck(feats, row[nid], matrix, offset, frame[nid], left[nid],
                                due_node, thr, par, ipar, coef, due_loc):  # fmt: skip
                rejected += 1
                continue
        if key in closed and not done:
            if not near:
                continue
            # closed for walking on, not for stopping (NEAR_GOAL_EXPANSIONS); one such draw
            # per node at most, and nodes come from expansions: bounded by them
            stop_draws += 1
            stop_only = True
        else:
            if done:
                outcome = FOUND
                goal_node = nid
                break
            if expansions >= max_exp:
                outcome = BUDGET
                break
            expansions += 1
            if near:
                c = near_expanded.get(key, 0) + 1
                near_expanded[key] = c
                if c >= near_n:
                    closed.add(key)
            else:
                closed.add(key)
            stop_only = False
        # draw this node's successors (the start node: the starters) into feats' next rows
        one_near[0] = near
        unchecked = 0
        if nid == 0:
            per = z0.shape[0]
            n_walk = per
            frm = frame0
            lft = left0
        else:
            on_left = left[nid]
            n_walk = 0 if stop_only else n_succ
            per = n_walk + n_stop if near else n_walk
        if nf + per > fcap:
            fcap = max(2 * fcap, nf + per)
            feats = _grow2(feats, fcap)
            closing = _grow1(closing, fcap)
        z = feats[nf : nf + per]
        if nid == 0:
            z[:] = z0
        else:
            x = feats[row[nid] : row[nid] + 1]
            if n_walk > 0:
                # (each GP by name, not a tuple picked at run time: that copies it)
                if on_left:
                    sample_into(x, n_walk, rng, gp_left, sharp, work_left, draw_rows, z, 0)
                else:
                    sample_into(x, n_walk, rng, gp_right, sharp, work_right, draw_rows, z, 0)
            if per > n_walk:  # near the goal: closing steps too, after the walking ones
                if on_left:
                    drew = _closing_draws(x, n_stop, rng, stop_left, reach_left, sharp, matrix,
                                          offset, hd, p, par, ipar, work_stop_left, draw_rows, z,
                                          n_walk)  # fmt: skip
                else:
                    drew = _closing_draws(x, n_stop, rng, stop_right, reach_right, sharp, matrix,
                                          offset, hd, p, par, ipar, work_stop_right, draw_rows,
                                          z, n_walk)  # fmt: skip
                if not drew:  # none can end the walk: not checked, counted as rejected
                    z[n_walk:] = np.nan
                    one_near[0] = False
                    unchecked = n_stop
            one_frame[0] = hd
            one_left[0] = not left[nid]
            frm = one_frame
            lft = one_left
        _predecessor_row(nid, pos, foot, fhead, g, parent, one_node)
        n_ok = check_into(
            z, matrix, offset, per, n_walk, frm, lft, one_near, one_node, thr, par, ipar, coef,
            dist, bufs, accepted, drawn, True,
        )  # fmt: skip
        for r in range(per):
            closing[nf + r] = r >= n_walk
        base = nf
        nf += per
        generated += drawn[0] + unchecked
        rejected += drawn[0] + unchecked - accepted[0]
        # open the successors outside closed cells, and those that may end or stop the walk
        # in any case (a cell reaching into a small goal area may have been closed by a node
        # just outside it)
        if nn + n_ok > cap:
            cap = max(2 * cap, nn + n_ok)
            parent = _grow1(parent, cap)
            row = _grow1(row, cap)
            pos = _grow1(pos, cap)
            head = _grow1(head, cap)
            frame = _grow1(frame, cap)
            g = _grow1(g, cap)
            foot = _grow1(foot, cap)
            fhead = _grow1(fhead, cap)
            left = _grow1(left, cap)
            legs_due = _grow1(legs_due, cap)
            nkey = _grow1(nkey, cap)
        for c in range(n_ok):
            e = ends[c]
            if (
                keys[c] in closed
                and not in_goal(e, ths[c], par, ipar)
                and not (n_stop > 0 and within(e - goal, stop_reach))
            ):
                continue
            parent[nn] = nid
            row[nn] = base + rows[c]
            pos[nn] = e
            head[nn] = ths[c]
            frame[nn] = frames[c]
            g[nn] = gs[c]
            foot[nn] = feet[c]
            fhead[nn] = fheads[c]
            left[nn] = lefts[c]
            legs_due[nn] = True
            nkey[nn] = keys[c]
            heapq.heappush(heap, (fs[c], counter, nn))
            counter += 1
            nn += 1
    stats = np.array([expansions, generated, rejected, stop_draws], dtype=np.int64)
    return (
        outcome,
        goal_node,
        stats,
        parent[:nn],
        row[:nn],
        pos[:nn],
        frame[:nn],
        left[:nn],
        feats[:nf],
        closing[:nf],
    )
