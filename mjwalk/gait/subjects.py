"""Virtual subjects of the synthetic capture (:mod:`mjwalk.gait.corpus`): the figures that stay
fixed across one subject's takes (:class:`SubjectParams`), drawn by :func:`sample_subject` and
calibrated on the captured figures :data:`REAL_FIGURES`. Metres, seconds, radians."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from mjwalk.conventions import DEFAULT_STATURE

# Calibration figures (NOT data): measured with ``mjwalk.gait.segment`` on
# ../shared/data/bandai-walk (Bandai Namco Research Motion Dataset 2, 354 clips, CC BY-NC 4.0,
# Kobayashi et al. 2023, arXiv:2306.08861), all steps except gait initiations and
# terminations, with the default ``segment_take`` parameters, by
# ``python benchmarks/bench_corpus.py`` (which prints them beside the virtual corpus).
# Per quantity: (median, 25th percentile, 75th percentile, mean, standard deviation).
# "length": pelvis displacement over the step (m); "duration": heel strike to heel strike (s);
# "width": ankle distance across the mean foot yaw (m; the captured ankle->toe directions are
# noisy, which inflates this figure: the same clips give a median of 0.065 m measured across the
# pelvis chord instead, which is what ``step_width`` of the subjects is calibrated on);
# "sway": largest pelvis distance
# from the step's chord (m); "yaw": pelvis yaw change over the step (deg; +-12 deg by side is the
# transverse pelvic rotation); "speed": length / duration (m/s).
REAL_FIGURES: dict[str, dict[str, tuple[float, float, float, float, float]]] = {
    "walk": {  # 1332 steps from the 103 `walk` clips
        "length": (0.692, 0.651, 0.729, 0.693, 0.061),
        "duration": (0.550, 0.525, 0.575, 0.556, 0.038),
        "width": (0.102, 0.037, 0.163, 0.105, 0.073),
        "sway": (0.030, 0.026, 0.034, 0.031, 0.006),
        "yaw": (-0.07, -12.37, 12.22, -0.06, 15.74),
        "speed": (1.250, 1.166, 1.330, 1.248, 0.111),
    },
    "turn": {  # 2219 steps from the 251 `walk-turn-left/right` clips (one ~90 deg turn each)
        "length": (0.651, 0.609, 0.687, 0.643, 0.067),
        "duration": (0.567, 0.542, 0.592, 0.572, 0.042),
        "width": (0.096, 0.044, 0.165, 0.112, 0.084),
        "sway": (0.031, 0.023, 0.040, 0.033, 0.016),
        "yaw": (0.84, -13.10, 13.46, 0.27, 22.11),
        "speed": (1.138, 1.066, 1.207, 1.128, 0.117),
    },
    "all": {  # 3551 steps both groups pooled
        "length": (0.667, 0.624, 0.704, 0.662, 0.069),
        "duration": (0.558, 0.542, 0.592, 0.566, 0.041),
        "width": (0.097, 0.041, 0.164, 0.109, 0.080),
        "sway": (0.030, 0.025, 0.038, 0.032, 0.013),
        "yaw": (0.71, -12.77, 12.84, 0.14, 19.96),
        "speed": (1.175, 1.097, 1.257, 1.173, 0.129),
    },
}
#: Transverse pelvic rotation amplitude (deg) implied by the +-12.3 deg per-step yaw change.
REAL_PELVIS_ROTATION_DEG = 6.15


@dataclass(frozen=True)
class SubjectParams:
    """One virtual subject: the figures that stay fixed across their takes.

    Attributes:
        subject: subject id.
        stature: body height, metres (agethen2018: N(1.75, 0.04)).
        pelvis_height: standing pelvis height, metres; also the pendulum height z0.
        step_length: preferred pelvis advance per step, metres.
        step_duration: preferred step duration (heel strike to heel strike), seconds.
        step_width: lateral distance between the ankle centres, metres.
        zmp_offset: lateral distance of the single-support ZMP from the walking line, metres.
            Calibrated (about 0.10 m) so that the pendulum pelvis sways like the captured hip
            centre (about 3 cm per step); it exceeds half the ankle width because the captured
            pelvis also lists sideways over the stance leg, which a point-mass LIPM lacks.
        double_support: double-support share of a step's duration.
        pelvis_rotation: amplitude of the transverse pelvic rotation, radians.
        toe_out: outward rotation of each foot from the heading, radians.
        bob: vertical pelvis amplitude, metres.
        clearance: peak lift of the swing foot, metres.
        foot_length: ankle to toe (ball of foot) distance, metres.
        length_cv, duration_cv: step-to-step (intra-subject) coefficient of variation.
        speed_sd: standard deviation of the log speed factor between bouts.
        turn_strategy: ``"step"`` (turn on the outside foot's steps) or ``"spin"`` (inside foot).
        turn_share: share of a turn's heading change taken on the favoured foot's steps.
        max_turn: largest heading change of one step, radians.
        apa: backward ZMP shift of the anticipatory postural adjustment before the first
            step, metres.
    """

    subject: int
    stature: float
    pelvis_height: float
    step_length: float
    step_duration: float
    step_width: float
    zmp_offset: float
    double_support: float
    pelvis_rotation: float
    toe_out: float
    bob: float
    clearance: float
    foot_length: float
    length_cv: float
    duration_cv: float
    speed_sd: float
    turn_strategy: str
    turn_share: float
    max_turn: float
    apa: float


def sample_subject(rng: np.random.Generator, subject: int = 0) -> SubjectParams:
    """Draw one virtual subject (inter-subject variance), calibrated on ``REAL_FIGURES``.

    Lengths scale with stature (1.75 m reference); the spread of the preferred step length and
    duration between subjects is about half the captured spread, the rest is intra-subject.

    Args:
        rng: generator; its draws are taken in the field order of :class:`SubjectParams`.
        subject: the subject's id.

    Returns:
        The subject's parameters (metres, seconds, radians).
    """
    stature = float(rng.normal(DEFAULT_STATURE, 0.04))
    scale = stature / DEFAULT_STATURE
    return SubjectParams(
        subject=subject,
        stature=stature,
        pelvis_height=0.51 * stature,
        step_length=float(0.725 * scale * np.exp(rng.normal(0.0, 0.03))),
        step_duration=float(0.545 * np.exp(rng.normal(0.0, 0.02))),
        step_width=float(np.clip(rng.normal(0.06, 0.012), 0.03, 0.1) * scale),
        zmp_offset=float(np.clip(rng.normal(0.10, 0.008), 0.07, 0.13) * scale),
        double_support=float(rng.uniform(0.16, 0.22)),
        pelvis_rotation=float(np.radians(rng.normal(REAL_PELVIS_ROTATION_DEG, 1.0))),
        toe_out=float(np.radians(rng.normal(6.0, 2.5))),
        bob=float(rng.uniform(0.008, 0.016)),
        clearance=float(rng.uniform(0.08, 0.12)),
        foot_length=0.14 * scale,
        # above one person's (stride time CV "usually below 3 %", Beauchet et al., J NeuroEng
        # Rehabil 6:32, 2009): they keep the pooled calibration figures; lower values made the
        # planner loop on short routes (docs/decisions/003-corpus-step-variability.md)
        length_cv=float(rng.uniform(0.035, 0.05)),
        duration_cv=float(rng.uniform(0.04, 0.05)),
        speed_sd=float(rng.uniform(0.03, 0.06)),
        turn_strategy=str(rng.choice(["step", "spin"])),
        turn_share=float(rng.uniform(0.5, 0.8)),
        max_turn=float(np.radians(rng.uniform(30.0, 45.0))),
        apa=float(rng.uniform(0.04, 0.08)),
    )
