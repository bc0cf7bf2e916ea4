"""Synthetic training data for the arm model: human-like reaches of one (left) arm.

Each reach is a minimum-jerk hand path (Flash & Hogan) from a start to an end hand position with
a slight upward curvature, the hand's direction turning from hanging to the approach direction,
shoulder/elbow from analytic two-link IK with a natural swivel angle (elbow down and slightly
out, varying from trial to trial), and for grasps a grip aperture that opens to a maximum growing
with object size (Jeannerod: about 0.8 cm per cm plus about 3.5 cm, peak at ~70 % of the
movement) and closes on the object, while the forearm rolls to the object's orientation.

Three constraint spaces (Al-Zubi & Sommer §5):
``"endpoints"``: constraint = start and end hand position (6,);
``"obstacle"``: constraint = obstacle position ratio B/A (1,) along the start-end line; the hand
path lifts over the obstacle with its peak above it;
``"grasp"``: constraint = object size (m, 0.04-0.12) and orientation (rad, 0-60 deg) (2,);
extras = grip aperture (m) and forearm roll (rad) per sample.

Frame: left shoulder at the origin, metres, x forward, y left, z up. The "hand position" is the
end of the hand segment (see :func:`mjwalk.arms.kinematics.end_effector`).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from mjwalk.arms.kinematics import (
    REST_HAND,
    arm_segment_lengths,
    end_effector,
    min_jerk,
    two_link_ik,
)
from mjwalk.conventions import DEFAULT_STATURE
from mjwalk.errors import MjwalkError

SPACES = ("endpoints", "obstacle", "grasp")


@dataclass
class ReachData:
    """A generated training set.

    Attributes:
        constraints: (p, d) constraint vectors (see module docstring per space).
        directions: (p, n, 3, 3) unit directions of upper arm, forearm, hand over time.
        extras: (p, n, 2) grip aperture (m) and forearm roll (rad), or None.
        lengths: (3,) segment lengths, metres.
        hand: (p, n, 3) hand positions, metres from the shoulder.
    """

    constraints: np.ndarray
    directions: np.ndarray
    extras: np.ndarray | None
    lengths: np.ndarray
    hand: np.ndarray


def grip_aperture(
    tau: np.ndarray, size: float, peak: float = 0.7, rest: float = 0.02
) -> np.ndarray:
    """Grip aperture (m) over normalized time ``tau``: opens from ``rest`` to the maximum
    0.8*size + 0.035 at ``peak`` and closes onto ``size`` at the end."""
    mga = 0.8 * size + 0.035
    a = np.where(
        tau < peak,
        rest + (mga - rest) * min_jerk(tau / peak),
        mga + (size - mga) * min_jerk((tau - peak) / (1 - peak)),
    )
    return a


def reach_trajectory(
    start: np.ndarray,
    end: np.ndarray,
    lengths: np.ndarray,
    rng: np.random.Generator,
    n: int = 20,
    curvature: float = 0.08,
    bump_at: float = 0.5,
    lift: float | None = None,
) -> tuple[np.ndarray, np.ndarray]:
    """Directions (n, 3, 3) and hand path (n, 3) of one reach from ``start`` to ``end``.

    ``curvature`` is the peak lift as a share of the start-end distance (used when ``lift``, a
    lift in metres, is None); ``bump_at`` places the peak along the path (0..1).
    """
    tau = np.linspace(0.0, 1.0, n)
    m = min_jerk(tau)
    d = end - start
    dist = float(np.linalg.norm(d))
    up = np.array([0.0, 0.0, 1.0]) - (d[2] / max(dist, 1e-9) ** 2) * d
    up /= max(np.linalg.norm(up), 1e-9)
    k = 4.0
    a, b = k * bump_at, k * (1 - bump_at)
    bump = m**a * (1 - m) ** b / (bump_at**a * (1 - bump_at) ** b)
    h = lift if lift is not None else curvature * dist
    hand = start + m[:, None] * d + (h * bump)[:, None] * up
    # Hand direction: from hanging forward-down to the approach direction (slightly down).
    d0 = np.array([0.25, 0.0, -1.0])
    app = np.array([d[0], d[1], 0.0])
    app = app / max(np.linalg.norm(app), 1e-9) + np.array([0.0, 0.0, -0.3])
    hd = (1 - m)[:, None] * (d0 / np.linalg.norm(d0)) + m[:, None] * (app / np.linalg.norm(app))
    hd /= np.linalg.norm(hd, axis=1, keepdims=True)
    wrist = hand - lengths[2] * hd
    swivel = np.radians(rng.normal(25.0, 6.0))  # elbow out of the vertical plane, per trial
    U = np.empty((n, 3, 3))
    for t in range(n):
        w = wrist[t]
        axis = w / np.linalg.norm(w)
        down = np.array([0.0, 0.0, -1.0]) - axis[2] * axis
        if np.linalg.norm(down) < 1e-6:
            down = np.array([1.0, 0.0, 0.0])
        down /= np.linalg.norm(down)
        side = np.cross(axis, down)
        hint = np.cos(swivel) * down - np.sin(swivel) * side  # outward (-y) for the left arm
        if hint[1] > 0:
            hint = np.cos(swivel) * down + np.sin(swivel) * side
        U[t, 0], U[t, 1] = two_link_ik(w, lengths[0], lengths[1], hint)
        U[t, 2] = hd[t]
    return U, hand


def _reachable(p, lengths):
    return np.linalg.norm(p) < 0.9 * (lengths[0] + lengths[1])


def generate(
    space: str, p: int, rng: np.random.Generator, n: int = 20, stature: float = DEFAULT_STATURE
) -> ReachData:
    """Generate ``p`` reaches of constraint ``space`` (one of :data:`SPACES`)."""
    if space not in SPACES:
        raise MjwalkError(f"reachgen: unknown constraint space {space!r} (choose from {SPACES})")
    L = arm_segment_lengths(stature)
    C: list[np.ndarray] = []
    U: list[np.ndarray] = []
    E: list[np.ndarray | None] = []
    Hs: list[np.ndarray] = []
    base_start = np.array(REST_HAND)
    base_end = np.array([0.45, -0.05, -0.15])
    tau = np.linspace(0.0, 1.0, n)
    while len(C) < p:
        start = base_start + rng.normal(0, 0.02, 3)
        if space == "endpoints":
            end = np.array(
                [rng.uniform(0.30, 0.50), rng.uniform(-0.15, 0.30), rng.uniform(-0.35, 0.15)]
            )
        else:
            end = base_end + rng.normal(0, 0.015, 3)
        if not (_reachable(end - 0.7 * L[2] * np.array([0.7, 0, -0.3]), L)):
            continue
        curv = rng.normal(0.08, 0.02)
        extras = None
        if space == "obstacle":
            ratio = rng.uniform(0.2, 0.8)
            lift = 0.12 + rng.normal(0, 0.01)
            dirs, hand = reach_trajectory(start, end, L, rng, n, bump_at=ratio, lift=lift)
            c = np.array([ratio])
        elif space == "grasp":
            size = rng.uniform(0.04, 0.12)
            orient = rng.uniform(0.0, np.radians(60))
            dirs, hand = reach_trajectory(start, end, L, rng, n, curvature=curv)
            peak = float(np.clip(rng.normal(0.7, 0.03), 0.6, 0.8))
            ap = grip_aperture(tau, size, peak) + rng.normal(0, 0.002)
            roll = orient * min_jerk(tau) + rng.normal(0, np.radians(2))
            extras = np.stack([ap, roll], axis=1)
            c = np.array([size, orient])
        else:
            dirs, hand = reach_trajectory(start, end, L, rng, n, curvature=curv)
            c = np.r_[hand[0], hand[-1]]
        if np.abs(end_effector(dirs, L) - hand).max() > 1e-6:
            continue  # the wrist left the arm's workspace somewhere: not a valid reach
        C.append(c)
        U.append(dirs)
        Hs.append(hand)
        E.append(extras)
    return ReachData(
        constraints=np.array(C),
        directions=np.array(U),
        extras=None if E[0] is None else np.array(E),
        lengths=L,
        hand=np.array(Hs),
    )
