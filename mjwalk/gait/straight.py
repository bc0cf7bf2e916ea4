"""Straight walks, of a capture and of a step model, timed alike.

Every captured take whose steps turn the heading by less than
``straight_deg`` in total is a straight walk; its distance D is the distance between the pelvis
at the start of its first and the end of its last (consecutive) step, its time the sum of the
step durations and its path length the pelvis path length (each step sampled at 25 instants,
as for the model). The model walks each D with a greedy, one-step version of the planner's
A* cost: start from 10 KDE starters, then repeatedly draw 10 GP successors of the chosen step
and take the candidate with the least *detour* (its pelvis path length minus the distance it
gains towards the goal, which lies D straight ahead) plus 0.05 m/rad times its end-heading
error to the goal bearing; stop before a step that would not bring the walker closer to the
goal (the walk ends within about half a step of it). The model's time is when its progress
along the line reached D (interpolated within the step that crossed it: a captured walk is cut
at D itself, so the half step the greedy walker stops short or long would add up to a quarter
of a second either way). Medians and IQRs of time and path length are reported, capture beside
model.
"""

from __future__ import annotations

import itertools
from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike

from mjwalk.gait.features import StepBatch, concat_batches
from mjwalk.gait.sampler import StepSampler
from mjwalk.gait.step import Step

#: Samples per step used for sway and path length (model and capture alike).
PATH_SAMPLES = 25


def resample_step(step: Step, m: int = PATH_SAMPLES) -> np.ndarray:
    """Pelvis positions of ``step`` at ``m`` evenly spaced instants.

    Args:
        step: the step.
        m: samples.

    Returns:
        (m, 2) pelvis x, y, metres (step frame).
    """
    t = np.arange(step.n_samples) / step.fps
    tm = np.linspace(0.0, t[-1], m)
    return np.column_stack(
        [np.interp(tm, t, step.pelvis[:, 0]), np.interp(tm, t, step.pelvis[:, 1])]
    )


def path_length(pelvis: np.ndarray) -> np.ndarray:
    """Polyline lengths.

    Args:
        pelvis: (n, m, 2) paths, metres.

    Returns:
        (n,) lengths, metres.
    """
    return np.linalg.norm(np.diff(pelvis, axis=1), axis=2).sum(axis=1)


def compose(pos, phi, local_xy, local_yaw):
    """Append steps given in local frames (x right, y forward) to world states.

    Args:
        pos: (..., 2) world positions, metres.
        phi: (...) headings, radians CCW from +y.
        local_xy: (..., 2) step end positions in the local frames.
        local_yaw: (...) heading changes of the steps, radians.

    Returns:
        (world (..., 2), phi + local_yaw).
    """
    c, s = np.cos(phi), np.sin(phi)
    x, y = local_xy[..., 0], local_xy[..., 1]
    world = pos + np.stack([c * x - s * y, s * x + c * y], axis=-1)
    return world, phi + local_yaw


def step_widths(end_xy: np.ndarray, footprint: np.ndarray, stance: np.ndarray) -> np.ndarray:
    """The step width: lateral distance between the landing and the stance foot across each
    step's walking direction (the pelvis chord, start -> end). The step frame's own x axis turns
    with the transverse pelvic rotation (about +-6 deg), the chord does not.

    Args:
        end_xy: (n, 2) pelvis at the end of each step, metres (step frame).
        footprint: (n, 3) landing foot x, y (m), yaw.
        stance: (n, 3) stance foot x, y (m), yaw.

    Returns:
        (n,) widths, metres.
    """
    end_xy = np.asarray(end_xy, dtype=float).reshape(-1, 2)
    d = np.asarray(footprint, dtype=float)[:, :2] - np.asarray(stance, dtype=float)[:, :2]
    u = end_xy / np.maximum(np.hypot(end_xy[:, 0], end_xy[:, 1]), 1e-9)[:, None]
    return np.abs(u[:, 0] * d[:, 1] - u[:, 1] * d[:, 0])


def straight_runs(steps: Sequence[Step], straight_deg: float = 20.0) -> list[list[Step]]:
    """The capture's straight walks as step lists: per take, its longest run of consecutive
    steps (alternating sides), kept when it has at least 2 steps and its total heading change
    is below ``straight_deg`` degrees.

    Args:
        steps: segmented steps.
        straight_deg: largest total heading change, degrees.

    Returns:
        One step list per straight take, in index order.
    """
    by_take: dict[str, list[Step]] = {}
    for s in steps:
        by_take.setdefault(s.take, []).append(s)
    out = []
    for take_steps in by_take.values():
        take_steps = sorted(take_steps, key=lambda s: s.index)
        runs, cur = [], [take_steps[0]]
        for a, b in itertools.pairwise(take_steps):
            if b.index == a.index + 1 and b.side != a.side:
                cur.append(b)
            else:
                runs.append(cur)
                cur = [b]
        runs.append(cur)
        run = max(runs, key=len)
        if len(run) < 2:
            continue
        if abs(float(sum(s.end_yaw for s in run))) > np.radians(straight_deg):
            continue
        out.append(run)
    return out


#: A captured walk starts from standing when the pelvis moves slower than this at the start
#: of its first step (m/s, mean over the first :data:`REST_WINDOW` s), not merely when the
#: segmenter flags that step a gait initiation (both feet on the floor since the take's first
#: frame): a clip cut in double support starts so while walking, and walked from standing it
#: would add a gait initiation the captured walker never made (about 0.4 s). 0.2 m/s: the
#: shared capture's README calls a clip starting below it one starting from a stand; a standing
#: person's pelvis sways at a few cm/s. (On the Bandai straight walks, 17 of 91 first steps are
#: flagged initiations, 16 of them with the pelvis at 0.90-1.56 m/s.)
REST_SPEED = 0.2
REST_WINDOW = 0.1


def starts_at_rest(step: Step) -> bool:
    """Whether a captured ``step`` starts from standing: a gait initiation (``Step.meta``)
    whose pelvis moves slower than :data:`REST_SPEED` over its first :data:`REST_WINDOW` s.

    Args:
        step: the first step of a walk.

    Returns:
        True when the walk starts from standing.
    """
    if not step.meta.get("initiation"):
        return False
    k = max(1, min(len(step.pelvis) - 1, round(REST_WINDOW * step.fps)))
    speed = float(np.hypot(*(step.pelvis[k] - step.pelvis[0]))) * step.fps / k
    return speed < REST_SPEED


def captured_straight_walks(
    steps: Sequence[Step], straight_deg: float = 20.0
) -> list[dict[str, float]]:
    """Straight walks of the capture (:func:`straight_runs`).

    Args:
        steps: segmented steps.
        straight_deg: largest total heading change, degrees.

    Returns:
        Per walk: ``distance`` (m), ``time`` (s), ``path_length`` (m), ``n_steps`` and
        ``in_motion`` (1.0 unless the walk starts from standing, :func:`starts_at_rest`).
    """
    walks = []
    for run in straight_runs(steps, straight_deg):
        pos, phi = np.zeros(2), 0.0
        for s in run:
            pos, phi = compose(pos, phi, s.pelvis[-1], s.end_yaw)
        paths = np.stack([resample_step(s) for s in run])
        walks.append(
            {
                "distance": float(np.hypot(*pos)),
                "time": float(sum(s.duration for s in run)),
                "path_length": float(path_length(paths).sum()),
                "n_steps": len(run),
                "in_motion": float(not starts_at_rest(run[0])),
            }
        )
    return walks


def model_straight_walks(
    model: StepSampler,
    distances: np.ndarray,
    rng: np.random.Generator,
    *,
    n_candidates: int = 10,
    heading_weight: float = 0.05,
    record_steps: bool = False,
    in_motion: ArrayLike | None = None,
) -> list[dict]:
    """Walk the model straight to a goal at each distance with the greedy steering rule of
    the module docstring; all walks advance together (vectorized).

    Args:
        model: the step sampler.
        distances: (w,) goal distances, metres (goal straight ahead, +y).
        rng: random generator.
        n_candidates: candidates drawn per walk and step.
        heading_weight: weight of the end-heading error to the goal bearing, m/rad.
        record_steps: each walk's dict also holds its steps' ``lengths`` (m), ``durations``
            (s) and ``widths`` (m: lateral distance of the landing foot from the stance foot),
            in walking order, and its ``track`` ((n + 1, 3): time s, progress along the
            start-goal line m, lateral offset m, at the start and after every step).
        in_motion: (w,) bool, that walk starts already walking, like a captured walk that does
            not start from standing (:func:`starts_at_rest`): its first candidates are the
            third steps of chains (a KDE starter and one successor before them, not counted)
            instead of starters.

    Returns:
        Per walk: ``distance``, ``time`` (:func:`time_at`), ``step_time``, ``path_length``,
        ``n_steps``, ``end_error`` (m to the goal), and the recorded steps when asked.
    """
    distances = np.asarray(distances, dtype=float)
    w = len(distances)
    walks = _Walks.start(distances)
    current: StepBatch | None = None
    max_steps = int(np.ceil(distances.max() / 0.2)) + 10 if w else 0
    for it in range(max_steps):
        idx = np.flatnonzero(walks.active)
        if idx.size == 0:
            break
        if it == 0:
            cand = _first_candidates(model, w, n_candidates, in_motion, rng)
        else:
            assert current is not None  # set by the first iteration
            cand = model.sample_next(current, n_candidates, rng)
        current = walks.advance(idx, cand, n_candidates, heading_weight, record_steps)
    return [walks.record(i, record_steps) for i in range(w)]


def _first_candidates(
    model: StepSampler,
    w: int,
    n_candidates: int,
    in_motion: ArrayLike | None,
    rng: np.random.Generator,
) -> StepBatch:
    """The first ``n_candidates`` candidates of each of ``w`` walks (rows walk-major): KDE
    starters in a random order; for the walks ``in_motion``, the third steps of chains."""
    cand = model.sample_first(n_candidates * w, rng)
    order = rng.permuted(np.arange(n_candidates * w)).reshape(w, n_candidates)
    cand = cand.take(order.ravel())
    moving = np.zeros(w, bool) if in_motion is None else np.asarray(in_motion, bool)
    if moving.any():
        rows_m = (np.flatnonzero(moving)[:, None] * n_candidates + np.arange(n_candidates)).ravel()
        warm = model.sample_next(model.sample_next(cand.take(rows_m), 1, rng), 1, rng)
        cand = concat_batches([cand.take(np.setdiff1d(np.arange(len(cand)), rows_m)), warm])
        back = np.concatenate([np.setdiff1d(np.arange(len(cand)), rows_m), rows_m])
        cand = cand.take(np.argsort(back))
    return cand


@dataclass
class _Walks:
    """State of the greedy straight walks of :func:`model_straight_walks`, one row per walk:
    goal and position (m, start frame: goal straight ahead on +y), heading (rad from +y CCW),
    time (s), pelvis path length (m), steps taken, per-step records and the track."""

    distances: np.ndarray
    goal: np.ndarray
    pos: np.ndarray
    phi: np.ndarray
    time_: np.ndarray
    plen: np.ndarray
    n_steps: np.ndarray
    per_step: list[list[tuple[float, float, float]]]
    # (time, progress along the start -> goal line) after every step of every walk
    track: list[list[tuple[float, float]]]
    lateral: list[list[float]]  # x after every step (m)
    active: np.ndarray

    @classmethod
    def start(cls, distances: np.ndarray) -> _Walks:
        w = len(distances)
        return cls(
            distances=distances,
            goal=np.column_stack([np.zeros(w), distances]),
            pos=np.zeros((w, 2)),
            phi=np.zeros(w),
            time_=np.zeros(w),
            plen=np.zeros(w),
            n_steps=np.zeros(w, dtype=int),
            per_step=[[] for _ in range(w)],
            track=[[(0.0, 0.0)] for _ in range(w)],
            lateral=[[0.0] for _ in range(w)],
            active=np.ones(w, dtype=bool),
        )

    def advance(
        self,
        idx: np.ndarray,
        cand: StepBatch,
        n_candidates: int,
        heading_weight: float,
        record_steps: bool,
    ) -> StepBatch:
        """Each active walk ``idx`` takes its best candidate (``n_candidates`` rows per walk)
        or stops when it would not get closer; returns the steps taken (order of ``idx``)."""
        pos, phi, goal = self.pos, self.phi, self.goal
        k = len(idx)
        end, phi_new = compose(
            pos[idx, None, :],
            phi[idx, None],
            cand.end_xy.reshape(k, n_candidates, 2),
            cand.end_yaw.reshape(k, n_candidates),
        )
        to_goal = goal[idx, None, :] - end
        bearing = np.arctan2(-to_goal[..., 0], to_goal[..., 1])
        err = np.abs(np.angle(np.exp(1j * (phi_new - bearing))))
        d_now = np.hypot(*(goal[idx] - pos[idx]).T)
        d_cand = np.hypot(to_goal[..., 0], to_goal[..., 1])
        cand_pelvis, _ = cand.resample(PATH_SAMPLES)
        cand_len = path_length(cand_pelvis).reshape(k, n_candidates)
        # detour of the step (path length minus progress to the goal) + heading error
        score = cand_len - (d_now[:, None] - d_cand) + heading_weight * err
        best = np.argmin(score, axis=1)
        rows = np.arange(k) * n_candidates + best
        d_new = d_cand[np.arange(k), best]
        go = (d_new < d_now) | (self.n_steps[idx] == 0)
        chosen = cand.take(rows)
        pelvis = cand_pelvis[rows]
        g = idx[go]
        pos[g] = end[np.arange(k), best][go]
        phi[g] = phi_new[np.arange(k), best][go]
        self.time_[g] += chosen.duration[go]
        for j in g:
            self.track[j].append((float(self.time_[j]), float(pos[j, 1])))
            self.lateral[j].append(float(pos[j, 0]))
        self.plen[g] += path_length(pelvis)[go]
        self.n_steps[g] += 1
        if record_steps:
            widths = step_widths(chosen.end_xy, chosen.footprint, chosen.stance)
            for j in np.flatnonzero(go):
                self.per_step[idx[j]].append(
                    (float(chosen.length[j]), float(chosen.duration[j]), float(widths[j]))
                )
        self.active[idx[~go]] = False
        self.active[idx[go]] = True
        # the chosen steps of the walks still going are the next predecessors (order of idx)
        return chosen.take(np.flatnonzero(go))

    def record(self, i: int, record_steps: bool) -> dict:
        """Walk ``i``'s dict (see :func:`model_straight_walks`)."""
        distance = float(self.distances[i])
        walk: dict = {
            "distance": distance,
            "time": time_at(self.track[i], distance),
            "step_time": float(self.time_[i]),
            "path_length": float(self.plen[i]),
            "n_steps": int(self.n_steps[i]),
            "end_error": float(np.hypot(*(self.goal[i] - self.pos[i]))),
        }
        if record_steps:
            rec = np.asarray(self.per_step[i], dtype=float).reshape(-1, 3)
            walk.update(lengths=rec[:, 0], durations=rec[:, 1], widths=rec[:, 2])
            track = np.asarray(self.track[i], dtype=float)
            walk["track"] = np.column_stack([track, self.lateral[i]])
        return walk


def time_at(track: list[tuple[float, float]], distance: float) -> float:
    """When a walk's progress along its line reached ``distance``: interpolated within the step
    that crossed it, or extrapolated at the last step's pace when the walk stopped short (it
    stops within half a step of the goal, a captured walk is cut at the distance itself).

    Args:
        track: (time s, progress m) at the start and after every step.
        distance: metres.

    Returns:
        The time, seconds.
    """
    t = np.array([a for a, _ in track])
    x = np.array([b for _, b in track])
    if len(t) < 2:
        return float(t[-1])
    if x[-1] >= distance:
        k = int(np.argmax(x >= distance))
        return float(np.interp(distance, x[k - 1 : k + 1], t[k - 1 : k + 1]))
    pace = (t[-1] - t[-2]) / max(x[-1] - x[-2], 1e-9)
    return float(t[-1] + (distance - x[-1]) * pace)
