"""A walker's pace, measured the same way on a step model and on capture.

The step model is conditioned on a :class:`~mjwalk.gait.walker.Walker` by stretching its
decoded steps (:meth:`mjwalk.gait.model.StepModel.for_walker`): forward distances by the ratio
of the walker's preferred step length to the model's, durations by the ratio of step
durations, lateral distances by the ratio of step widths (or statures). That needs the model's
own pace, measured like a person's: :func:`model_pace` walks the model straight ahead and
takes the *steady* steps (neither the first two, gait initiation and acceleration, nor the
closing one); :func:`capture_pace` takes the steady steps of a capture's straight walks
(neither gait initiations nor terminations, ``Step.meta``). Both report medians, so a step
model conditioned on :func:`capture_pace` of some capture has, by construction, that capture's
median steady step length and duration; its spread and the shape of its steps stay the model's.

Why a stretch: within a person, step length and cadence set the speed (speed = step length x
cadence), and the variability of both scales with them: the coefficient of variation of stride
length and time of healthy adults is roughly constant at 1.5-3 % over comfortable speeds
(Hausdorff, "Gait variability: methods, modeling and meaning", J NeuroEng Rehabil 2:19, 2005;
Beauchet et al., Gait Posture 30:492, 2009). Lateral sway scales with step width, which scales
with body size (Perry & Burnfield 2010, ch. 1: step width 7-10 cm for adults).
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass, replace

import numpy as np

from mjwalk.errors import MjwalkError
from mjwalk.gait.sampler import StepSampler
from mjwalk.gait.step import Step
from mjwalk.gait.straight import model_straight_walks, step_widths, straight_runs

#: Straight walks the model's pace is measured on: ``PACE_WALKS`` greedy straight walks of
#: ``PACE_DISTANCE`` metres (about 11 steps, 8 of them steady), seeded.
PACE_WALKS = 160
PACE_DISTANCE = 8.0
#: The centre of a figure is its interquartile mean (``scipy.stats.trim_mean`` cutting 25 % at
#: each end): as robust as the median, but not stuck on the 1/120 s grid of captured
#: durations (a median cadence jumps 109.1 -> 112.5 steps/min between neighbouring frames).
CENTRE_TRIM = 0.25
#: Version of the pace measurement: a model file whose saved pace has another is re-measured.
PACE_VERSION = 2
#: Steps left out at the start of a model walk (gait initiation, acceleration) and at its end.
#: The default model's chains settle from about the sixth step, so the steps counted are about
#: 2 % faster than its steady walking; skipping more costs step width on slow walkers
#: (docs/decisions/006-pace-skipped-steps.md).
SKIP_START, SKIP_END = 2, 1


@dataclass(frozen=True)
class Pace:
    """Steady straight-walking figures of a set of steps (interquartile means).

    Attributes:
        step_length: pelvis advance per step, metres.
        step_duration: heel strike to heel strike, seconds.
        step_width: lateral distance between the landing and the stance foot, metres.
        n_steps: steady steps measured.
    """

    step_length: float
    step_duration: float
    step_width: float
    n_steps: int

    @property
    def speed(self) -> float:
        """``step_length / step_duration``, metres per second."""
        return self.step_length / self.step_duration

    @property
    def cadence(self) -> float:
        """Steps per minute."""
        return 60.0 / self.step_duration

    def as_dict(self) -> dict[str, float]:
        """The pace as a JSON-ready dict.

        Returns:
            ``speed`` (m/s), ``cadence`` (steps/min), ``step_length`` (m), ``step_duration`` (s),
            ``step_width`` (m), all rounded, ``n_steps`` and ``version`` (:data:`PACE_VERSION`).
        """
        return {
            "speed": round(self.speed, 4),
            "cadence": round(self.cadence, 3),
            "step_length": round(self.step_length, 4),
            "step_duration": round(self.step_duration, 4),
            "step_width": round(self.step_width, 4),
            "n_steps": int(self.n_steps),
            "version": PACE_VERSION,
        }

    @classmethod
    def from_dict(cls, d: dict) -> Pace:
        """Inverse of :meth:`as_dict` (derived ``speed``, ``cadence`` and ``version`` ignored).

        Args:
            d: a dict with ``step_length``, ``step_duration``, ``step_width``, ``n_steps``.

        Returns:
            The pace.
        """
        return cls(
            float(d["step_length"]),
            float(d["step_duration"]),
            float(d["step_width"]),
            int(d["n_steps"]),
        )


def _pace(lengths, durations, widths) -> Pace:
    # deferred: scipy.stats costs ~1 s to import and only measuring a pace needs it
    from scipy.stats import trim_mean

    lengths, durations, widths = (np.asarray(x, dtype=float) for x in (lengths, durations, widths))
    if lengths.size < 3:
        raise MjwalkError(
            f"pace: only {lengths.size} steady straight steps to measure a pace on; need >= 3"
        )
    return Pace(
        float(trim_mean(lengths, CENTRE_TRIM)),
        float(trim_mean(durations, CENTRE_TRIM)),
        float(trim_mean(widths, CENTRE_TRIM)),
        int(lengths.size),
    )


def capture_pace(steps: Sequence[Step], straight_deg: float = 20.0) -> Pace:
    """Pace of captured ``steps``: interquartile means over the steady steps of its straight walks
    (:func:`mjwalk.gait.straight.straight_runs`; gait initiations and terminations left out).

    Args:
        steps: segmented captured steps.
        straight_deg: largest total heading change of a straight walk, degrees.

    Returns:
        The pace.

    Raises:
        MjwalkError: with fewer than 3 steady straight steps.
    """
    steady = [
        s
        for run in straight_runs(steps, straight_deg)
        for s in run
        if not (s.meta.get("initiation") or s.meta.get("termination"))
    ]
    return _pace(
        [s.length for s in steady],
        [s.duration for s in steady],
        step_widths(
            np.array([s.pelvis[-1] for s in steady]).reshape(-1, 2),
            np.array([s.footprint for s in steady]).reshape(-1, 3),
            np.array([s.stance for s in steady]).reshape(-1, 3),
        ),
    )


def model_pace(model: StepSampler, *, seed: int = 0) -> Pace:
    """Pace of ``model``: interquartile means over the steady steps (:data:`SKIP_START` and
    :data:`SKIP_END` left out) of :data:`PACE_WALKS` straight walks of :data:`PACE_DISTANCE`
    metres (the greedy walker of :func:`mjwalk.gait.straight.model_straight_walks`, seeded, so
    the figure is a property of the model).

    Args:
        model: the step sampler.
        seed: seed of the walks' generator.

    Returns:
        The pace.
    """
    walks = model_straight_walks(
        model,
        np.full(PACE_WALKS, PACE_DISTANCE),
        np.random.default_rng(seed),
        record_steps=True,
    )
    cols: list[list[float]] = [[], [], []]
    for w in walks:
        sl = slice(SKIP_START, len(w["lengths"]) - SKIP_END)
        for c, key in zip(cols, ("lengths", "durations", "widths"), strict=True):
            c.extend(w[key][sl])
    return _pace(*cols)


def stretch_step(step: Step, lateral: float, forward: float, time: float) -> Step:
    """``step`` stretched in its local frame; yaws stay.

    x (right) of the pelvis and both feet times ``lateral``, y (forward) times ``forward``; the
    samples stay and their rate becomes fps / ``time``, so the duration is multiplied by
    ``time``. The inverse of what :meth:`~mjwalk.gait.model.StepModel.for_walker` does to decoded
    steps.

    Args:
        step: the step.
        lateral: factor on x.
        forward: factor on y.
        time: factor on the duration.

    Returns:
        A new step (the other fields shared).
    """
    xy = np.array([lateral, forward])
    foot = np.asarray(step.footprint, dtype=float).copy()
    stance = np.asarray(step.stance, dtype=float).copy()
    foot[:2] *= xy
    stance[:2] *= xy
    return replace(
        step, pelvis=step.pelvis * xy, footprint=foot, stance=stance, fps=step.fps / time
    )


def normalize_paces(
    steps: Sequence[Step], key: str = "subject", min_steps: int = 20
) -> tuple[list[Step], dict]:
    """Steps of several walkers brought to one common pace, so that a model fitted on them
    holds the variance *within* a person only (the population supplies the rest: a walker's
    own pace, :meth:`~mjwalk.gait.model.StepModel.for_walker`).

    Steps are grouped by ``Step.meta[key]`` (a virtual subject; a captured subject or style);
    each group's :func:`capture_pace` is measured on its own straight walking and the group is
    stretched (:func:`stretch_step`) to the median of the groups' paces (step length,
    duration and width separately). Steps without the key, and groups with fewer than
    ``min_steps`` steady straight steps, are left as they are; with fewer than 2 such groups
    nothing is stretched.

    Args:
        steps: segmented steps.
        key: the ``Step.meta`` key naming the walker.
        min_steps: fewest steady straight steps for a group to be stretched.

    Returns:
        (steps, info): the steps in their order; info per group (key as str): its pace
        (:meth:`Pace.as_dict`) and its ``lateral``, ``forward`` and ``time`` factors.
    """
    groups: dict[object, list[int]] = {}
    for i, s in enumerate(steps):
        if key in s.meta:
            groups.setdefault(s.meta[key], []).append(i)
    paces = {}
    for g, idx in groups.items():
        try:
            pace = capture_pace([steps[i] for i in idx])
        except MjwalkError:
            continue
        if pace.n_steps >= min_steps:
            paces[g] = pace
    out = list(steps)
    if len(paces) < 2:
        return out, {}
    ref = Pace(
        float(np.median([p.step_length for p in paces.values()])),
        float(np.median([p.step_duration for p in paces.values()])),
        float(np.median([p.step_width for p in paces.values()])),
        0,
    )
    info = {}
    for g, p in paces.items():
        f = (ref.step_width / p.step_width, ref.step_length / p.step_length)
        t = ref.step_duration / p.step_duration
        for i in groups[g]:
            out[i] = stretch_step(steps[i], f[0], f[1], t)
        info[str(g)] = {"pace": p.as_dict(), "lateral": f[0], "forward": f[1], "time": t}
    return out, info
