"""Step segmentation: cut takes into aligned left/right steps at foot-contact key frames.

agethen2018 §3.3: the speed and elevation of both feet approach zero while a foot is loaded;
key frames are where that changes, found with an adaptive threshold built from
``scipy.ndimage.gaussian_filter1d`` of the signal plus an offset above its 5th percentile.

Definitions used throughout (all frames are indices into the take, 120 Hz):

* **contact** of a foot: its ankle *or* its toe is on the ground, i.e. slow (smoothed speed
  below the adaptive speed threshold) *and* low (smoothed height below the 5th percentile of
  that marker's height plus ``height_offset``). The heel (ankle) lands first and the toe leaves
  last, so a foot is in contact from heel strike to toe-off.
* **heel strike** (HS) of a foot: the first frame of a contact interval (not at frame 0).
* **toe-off** (TO) of a foot: the first frame after a contact interval (the first swing frame).
* **key frames**: all heel strikes and toe-offs of both feet.
* **step** ``k``: from the heel strike ``HS[k-1]`` of one foot to the next heel strike ``HS[k]``
  of the other foot, i.e. one double-support phase followed by the swing of the *swing foot*
  (``Step.side``), which lands at the step's last frame. The other foot is the stance foot.
  The first step of a take that starts standing (both feet in contact since frame 0) is the
  gait *initiation*: it starts one median double-support time before the toe-off of its swing
  foot (``Step.meta["initiation"] = True``). The last step of a take that ends standing (both
  feet in contact from its last frame on) is a gait *termination* (``meta["termination"]``).
* ``Step.index`` is ``k``, the position of its landing heel strike in the take's sequence of
  heel strikes, so steps ``k`` and ``k + 1`` of the same take are a captured transition; a
  dropped step leaves a gap.
* footprints are ankle positions projected on the floor, foot yaw is the ankle->toe direction,
  both medians over the first 0.1 s of the foot's contact.
"""

from __future__ import annotations

import itertools
from collections import Counter
from collections.abc import Iterable
from dataclasses import dataclass, field

import numpy as np
from scipy.ndimage import binary_closing, binary_opening, gaussian_filter1d

from mjwalk.conventions import SIDES, Side
from mjwalk.errors import CaptureError
from mjwalk.gait.step import Step
from mjwalk.mocap.take import Take

#: Reasons a candidate step is dropped (keys of ``SegmentationSummary.dropped``).
DROP_REASONS = ("too_short", "too_long", "no_alternation", "absurd_length")


@dataclass
class Segmentation:
    """Result of :func:`segment_take`.

    Attributes:
        take: name of the take.
        fps: frames per second of the take.
        contact: (T, 2) bool, foot contact of the left (column 0) and right (column 1) foot.
        heel_strikes: side -> (n,) int frames where that foot's contact starts.
        toe_offs: side -> (n,) int frames where that foot's contact ends (first swing frame).
        steps: the plausible steps, in take order.
        dropped: reason -> number of candidate steps dropped (see ``DROP_REASONS``).
    """

    take: str
    fps: float
    contact: np.ndarray
    heel_strikes: dict[Side, np.ndarray]
    toe_offs: dict[Side, np.ndarray]
    steps: list[Step]
    dropped: dict[str, int] = field(default_factory=dict)

    @property
    def key_frames(self) -> np.ndarray:
        """Sorted frames of all contact changes (heel strikes and toe-offs of both feet)."""
        parts = [*self.heel_strikes.values(), *self.toe_offs.values()]
        return np.sort(np.concatenate(parts)) if parts else np.zeros(0, int)


@dataclass
class SegmentationSummary:
    """Counts over many segmented takes (see :func:`segment_takes`)."""

    n_takes: int = 0
    n_frames: int = 0
    n_key_frames: int = 0
    n_candidates: int = 0
    n_steps: int = 0
    n_transitions: int = 0
    n_initiations: int = 0
    dropped: dict[str, int] = field(default_factory=dict)

    def __str__(self) -> str:
        drops = ", ".join(f"{k} {v}" for k, v in sorted(self.dropped.items()) if v) or "none"
        return (
            f"{self.n_takes} takes ({self.n_frames} frames): {self.n_key_frames} key frames, "
            f"{self.n_candidates} candidate steps -> {self.n_steps} steps "
            f"({self.n_initiations} gait initiations), {self.n_transitions} transitions; "
            f"dropped: {drops}"
        )


def _marker_contact(
    pos: np.ndarray,
    fps: float,
    sigma: float,
    threshold_sigma: float,
    speed_offset: float,
    min_speed: float,
    height_offset: float,
) -> np.ndarray:
    """(T,) bool: the marker (T, 3 metres) is slow and low, by adaptive thresholds."""
    speed = np.linalg.norm(np.gradient(pos, axis=0), axis=1) * fps
    speed = gaussian_filter1d(speed, sigma, mode="nearest")
    base = np.percentile(speed, 5)
    level = gaussian_filter1d(speed, threshold_sigma, mode="nearest")
    thr_v = base + np.maximum(speed_offset * (level - base), min_speed)
    height = gaussian_filter1d(pos[:, 2], sigma, mode="nearest")
    thr_h = np.percentile(height, 5) + height_offset
    return (speed < thr_v) & (height < thr_h)


@dataclass(frozen=True)
class ContactOptions:
    """How :func:`foot_contact` detects foot contact (the defaults are agethen2018 §3.3's
    scheme tuned on the 120 Hz Bandai and virtual captures).

    Attributes:
        sigma: Gaussian smoothing of speed and height, frames.
        threshold_sigma: Gaussian window of the adaptive speed level, frames (0.5 s at 120 Hz).
        speed_offset: the speed threshold sits this fraction of the way from the 5th percentile
            of the smoothed speed to its local level (about the walking speed).
        min_speed: lower bound of the threshold's offset above the 5th percentile, m/s.
        height_offset: height threshold above the 5th percentile of the marker height, metres.
        min_phase: contact and swing phases shorter than this (seconds) are removed.
    """

    sigma: float = 1.0
    threshold_sigma: float = 60.0
    speed_offset: float = 0.5
    min_speed: float = 0.08
    height_offset: float = 0.05
    min_phase: float = 0.08


def foot_contact(take: Take, options: ContactOptions = ContactOptions()) -> np.ndarray:
    """(T, 2) bool foot contact (left, right) of a take; see the module docstring.

    Args:
        take: the take (metres, z up).
        options: the contact detection's smoothing, thresholds and shortest phase.

    Returns:
        (T, 2) bool array, column 0 the left foot, column 1 the right, True while in contact.
    """
    o = options
    n = max(1, round(o.min_phase * take.fps))
    out = np.zeros((take.n_frames, 2), bool)
    for j, (ankle, toe) in enumerate(((take.ankle_l, take.toe_l), (take.ankle_r, take.toe_r))):
        c = np.zeros(take.n_frames, bool)
        for marker in (ankle, toe):
            c |= _marker_contact(
                marker,
                take.fps,
                o.sigma,
                o.threshold_sigma,
                o.speed_offset,
                o.min_speed,
                o.height_offset,
            )
        if n > 1:
            structure = np.ones(n, bool)
            # Pad with contact on both ends so the opening/closing does not eat the borders.
            padded = np.concatenate([np.ones(n, bool), c, np.ones(n, bool)])
            padded = binary_closing(binary_opening(padded, structure), structure)
            c = padded[n:-n]
        out[:, j] = c
    return out


def _edges(c: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Rising (heel strike) and falling (toe-off, first swing frame) edges of a bool signal."""
    d = np.diff(c.astype(np.int8))
    return np.flatnonzero(d == 1) + 1, np.flatnonzero(d == -1) + 1


def _check_take(take: Take) -> None:
    t = take.n_frames
    for name in ("pelvis", "ankle_l", "ankle_r", "toe_l", "toe_r"):
        a = np.asarray(getattr(take, name))
        if a.shape != (t, 3):
            raise CaptureError(f"take {take.name!r}: {name} has shape {a.shape}, expected ({t}, 3)")
        if not np.all(np.isfinite(a)):
            raise CaptureError(f"take {take.name!r}: {name} contains non-finite values")
    if np.shape(take.pelvis_yaw) != (t,):
        raise CaptureError(
            f"take {take.name!r}: pelvis_yaw has shape {np.shape(take.pelvis_yaw)}, expected ({t},)"
        )
    if not take.fps > 0:
        raise CaptureError(f"take {take.name!r}: fps must be positive, got {take.fps}")


def _foot_pose(
    ankle: np.ndarray, toe: np.ndarray, frame: int, n_avg: int, origin: np.ndarray, yaw0: float
) -> np.ndarray:
    """(3,) ankle x, y and ankle->toe yaw in the step frame (origin, yaw0): medians over the
    ``n_avg`` frames from ``frame`` on (the foot is planted there; robust to a late key frame)."""
    sl = slice(frame, min(frame + n_avg, ankle.shape[0]))
    a = np.median(ankle[sl, :2], axis=0)
    d = np.median(toe[sl, :2] - ankle[sl, :2], axis=0)
    foot_yaw = np.arctan2(d[1], d[0]) - yaw0
    return np.array([*_to_local(a[None] - origin, yaw0)[0], _wrap(foot_yaw)])


def _wrap(a):
    return (np.asarray(a) + np.pi) % (2 * np.pi) - np.pi


def _to_local(d: np.ndarray, yaw0: float) -> np.ndarray:
    """World xy offsets (N, 2) -> step frame (x right, y along the heading ``yaw0``)."""
    c, s = np.cos(yaw0), np.sin(yaw0)
    return np.stack([d[:, 0] * s - d[:, 1] * c, d[:, 0] * c + d[:, 1] * s], axis=1)


def segment_take(
    take: Take,
    *,
    contact: ContactOptions = ContactOptions(),
    min_duration: float = 0.25,
    max_duration: float = 1.5,
    max_length: float = 1.2,
) -> Segmentation:
    """Find the foot-contact key frames of a take and cut it into aligned steps.

    See the module docstring for the exact definitions of contact, key frames and steps.

    Args:
        take: a :class:`~mjwalk.mocap.take.Take` (metres, z up, any fps; 120 Hz expected).
        contact: contact detection options, see :func:`foot_contact`.
        min_duration: shortest plausible step, seconds; shorter ones are dropped as
            ``too_short``.
        max_duration: longest plausible step, seconds; longer ones are dropped as ``too_long``.
        max_length: steps whose pelvis displacement or swing-foot-to-stance-foot distance
            exceeds this many metres are dropped as ``absurd_length``.

    Returns:
        A :class:`Segmentation`; its ``steps`` are :class:`~mjwalk.gait.step.Step` in the local
        frame of their first sample (pelvis at the origin heading +y).

    Raises:
        CaptureError: the take's arrays are inconsistent or non-finite.
    """
    _check_take(take)
    fps = float(take.fps)
    in_contact = foot_contact(take, contact)
    hs, to = {}, {}
    for j, side in enumerate(SIDES):
        hs[side], to[side] = _edges(in_contact[:, j])
    events = sorted((int(f), j) for j, side in enumerate(SIDES) for f in hs[side])
    n_avg = max(1, round(0.1 * fps))
    dropped: Counter[str] = Counter({r: 0 for r in DROP_REASONS})
    ds_med = _median_double_support(events, to, fps)
    steps: list[Step] = []
    for a, b, j, k, init in _candidates(events, to, in_contact, ds_med):
        if not init and events[k - 1][1] == j:
            dropped["no_alternation"] += 1
            continue
        dur = (b - a) / fps
        if dur < min_duration:
            dropped["too_short"] += 1
            continue
        if dur > max_duration:
            dropped["too_long"] += 1
            continue
        # Termination: the last heel strike of a take that ends standing (both feet in contact).
        term = k == len(events) - 1 and bool(in_contact[b:].all())
        step = _cut_step(take, (a, b, j, k, init), n_avg, term, max_length)
        if step is None:
            dropped["absurd_length"] += 1
            continue
        steps.append(step)
    return Segmentation(
        take=take.name,
        fps=fps,
        contact=in_contact,
        heel_strikes=hs,
        toe_offs=to,
        steps=steps,
        dropped=dict(dropped),
    )


def _median_double_support(
    events: list[tuple[int, int]], to: dict[Side, np.ndarray], fps: float
) -> int:
    """Median double-support time, frames: the toe-off of the swing foot minus the previous
    heel strike (of the other foot), over the take; 0.12 s when no such pair exists."""
    ds = []
    for (f0, j0), (f1, j1) in itertools.pairwise(events):
        if j0 != j1:
            t_off = to[SIDES[j1]]
            t_off = t_off[(t_off > f0) & (t_off < f1)]
            if t_off.size:
                ds.append(t_off[0] - f0)
    return int(np.median(ds)) if ds else round(0.12 * fps)


def _candidates(
    events: list[tuple[int, int]],
    to: dict[Side, np.ndarray],
    contact: np.ndarray,
    ds_med: int,
) -> list[tuple[int, int, int, int, bool]]:
    """Candidate steps as (start frame, end frame, swing foot, index, initiation): a gait
    initiation before the first heel strike of a take that starts standing, then one step
    between every two consecutive heel strikes (``events``: sorted (frame, foot))."""
    cands: list[tuple[int, int, int, int, bool]] = []
    if events:
        f1, j1 = events[0]
        other = 1 - j1
        t_off = to[SIDES[j1]]
        t_off = t_off[t_off < f1]
        if t_off.size and contact[: f1 + 1, other].all() and contact[: t_off[-1], j1].all():
            cands.append((max(0, int(t_off[-1]) - ds_med), f1, j1, 0, True))
    for k in range(1, len(events)):
        (f0, _), (f1, j1) = events[k - 1], events[k]
        cands.append((f0, f1, j1, k, False))
    return cands


def _cut_step(
    take: Take,
    cand: tuple[int, int, int, int, bool],
    n_avg: int,
    term: bool,
    max_length: float,
) -> Step | None:
    """The :class:`Step` of candidate ``cand`` (see :func:`_candidates`) in the local frame of
    its first sample, or None when it is longer than ``max_length`` metres (pelvis displacement
    or swing-foot-to-stance-foot distance)."""
    a, b, j, k, init = cand
    ankles = (take.ankle_l, take.ankle_r)
    toes = (take.toe_l, take.toe_r)
    origin = take.pelvis[a, :2]
    yaw0 = float(take.pelvis_yaw[a])
    pelvis = _to_local(take.pelvis[a : b + 1, :2] - origin, yaw0)
    foot = _foot_pose(ankles[j], toes[j], b, n_avg, origin, yaw0)
    stance = _foot_pose(ankles[1 - j], toes[1 - j], a, n_avg, origin, yaw0)
    if np.hypot(*pelvis[-1]) > max_length or np.hypot(*(foot[:2] - stance[:2])) > max_length:
        return None
    meta = {k2: v for k2, v in take.meta.items() if isinstance(v, (str, int, float, bool))}
    meta.update(start_frame=a, end_frame=b, initiation=init, termination=term)
    return Step(
        side=SIDES[j],
        fps=float(take.fps),
        pelvis=pelvis,
        yaw=np.asarray(take.pelvis_yaw[a : b + 1], float) - yaw0,
        footprint=foot,
        stance=stance,
        take=take.name,
        index=k,
        meta=meta,
    )


def count_transitions(steps: list[Step]) -> int:
    """Number of captured transitions: pairs of steps ``k``, ``k + 1`` of the same take.

    Args:
        steps: steps in take order.

    Returns:
        The count of consecutive pairs with alternating sides.
    """
    n = 0
    for s0, s1 in itertools.pairwise(steps):
        n += s0.take == s1.take and s1.index == s0.index + 1 and s0.side != s1.side
    return n


def segment_takes(takes: Iterable[Take], **kwargs) -> tuple[list[Step], SegmentationSummary]:
    """Segment many takes (:func:`segment_take` keyword arguments pass through).

    Args:
        takes: the takes.
        **kwargs: :func:`segment_take` options.

    Returns:
        All plausible steps in take order, and a :class:`SegmentationSummary` with the counts
        of key frames, steps, transitions and drops by reason.
    """
    steps: list[Step] = []
    summary = SegmentationSummary(dropped={r: 0 for r in DROP_REASONS})
    for take in takes:
        seg = segment_take(take, **kwargs)
        summary.n_takes += 1
        summary.n_frames += take.n_frames
        summary.n_key_frames += int(seg.key_frames.size)
        summary.n_candidates += len(seg.steps) + sum(seg.dropped.values())
        summary.n_initiations += sum(bool(s.meta.get("initiation")) for s in seg.steps)
        for r, v in seg.dropped.items():
            summary.dropped[r] = summary.dropped.get(r, 0) + v
        summary.n_transitions += count_transitions(seg.steps)
        steps.extend(seg.steps)
    summary.n_steps = len(steps)
    return steps, summary


def step_sway(step: Step) -> float:
    """Lateral pelvis sway of a step: the largest distance of the pelvis path from the chord
    joining its first and last sample (the pelvis swings over the stance foot).

    Args:
        step: the step.

    Returns:
        The sway, metres.
    """
    p = step.pelvis
    chord = p[-1] - p[0]
    n = np.hypot(*chord)
    if n < 1e-9:
        return float(np.max(np.hypot(p[:, 0], p[:, 1])))
    return float(np.max(np.abs(chord[0] * p[:, 1] - chord[1] * p[:, 0])) / n)


def step_width(step: Step) -> float:
    """Step width: lateral distance between the landing footprint and the stance foot across
    the line of progression, whose direction is the mean of the two foot yaws (toe-out of the
    left and right foot cancels).

    Args:
        step: the step.

    Returns:
        The width, metres.
    """
    yaw = step.stance[2] + 0.5 * _wrap(step.footprint[2] - step.stance[2])
    d = step.footprint[:2] - step.stance[:2]
    return float(abs(d[0] * np.cos(yaw) + d[1] * np.sin(yaw)))
