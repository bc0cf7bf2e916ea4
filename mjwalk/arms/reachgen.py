"""Synthetic training data for the arm model: human-like reaches of one (left) arm.

Each reach is a minimum-jerk hand path (Flash & Hogan) from a start to an end hand position with
a slight upward curvature; the hand in line with the forearm (a neutral wrist) while it is
carried, turning over the second half to the approach direction (out from the shoulder over the
target, slightly down) only as far as the wrist's functional range allows
(:data:`FUNCTIONAL_WRIST`); shoulder/elbow from analytic two-link IK with a natural swivel angle
(elbow down and slightly out, varying from trial to trial); every pose within the humanoid's
ranges of motion (others are drawn again); and for grasps a grip aperture that opens to a
maximum growing with object size (Jeannerod: about 0.8 cm per cm plus about 3.5 cm, peak at
~70 % of the movement) and closes on the object, while the forearm rolls to the object's
orientation.

Three constraint spaces (Al-Zubi & Sommer §5):
``"endpoints"``: constraint = start and end hand position (6,);
``"obstacle"``: constraint = obstacle position ratio B/A (1,) along the start-end line; the hand
path lifts over the obstacle with its peak above it;
``"grasp"``: constraint = object size (m, 0.04-0.12) and orientation (rad, 0-60 deg) (2,);
extras = grip aperture (m) and forearm roll (rad) per sample.

Frame: left shoulder at the origin, metres, x forward, y left, z up. The "hand position" is the
end of the hand segment (see :func:`mjwalk.arms.chain.end_effector`).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from mjwalk.anthropometry import ROM_DEG
from mjwalk.arms.chain import (
    ARM_JOINTS,
    REST_HAND,
    arm_joint_angles,
    arm_segment_lengths,
    end_effector,
    min_jerk,
    two_link_ik,
    wrist_in_range,
)
from mjwalk.conventions import DEFAULT_STATURE
from mjwalk.errors import MjwalkError

SPACES = ("endpoints", "obstacle", "grasp")
#: The wrist's functional range, degrees (lo, hi) for flexion (+) / extension (-) and ulnar (+)
#: / radial (-) deviation (the humanoid's sign convention, :data:`mjwalk.anthropometry.ROM_DEG`):
#: 40 deg flexion, 40 deg extension and 40 deg of radio-ulnar deviation (10 radial, 30 ulnar)
#: cover most activities of daily living (Ryu, Cooney, Askew, An & Chao 1991, "Functional
#: ranges of motion of the wrist joint", J. Hand Surg. 16A:409-419).
FUNCTIONAL_WRIST = ((-40.0, 40.0), (-10.0, 30.0))
#: Where ``"endpoints"`` reaches end: (lo, hi) metres along x, y, z of the left shoulder frame
#: (default stature; unreachable ends are drawn again). A standing operator's working area:
#: from a hand close in front of the chest (x 0.15) to the arm's reach (0.55, 0.72 of the arm);
#: across the body's midline (about 0.20 m medial of the shoulder joint, half the biacromial
#: breadth) by 10 cm, as the normal working area of each hand overlaps the other's in front of
#: the body (Barnes 1980, *Motion and Time Study*, 7th ed., ch. 17: normal and maximum working
#: areas), and as far out to the side (y 0.30); from 15 cm below the elbow (about -0.33 m; the
#: work height of heavy work, Grandjean 1988, *Fitting the Task to the Man*, 4th ed., ch. 4)
#: up to a top shelf: the standing vertical grip reach, about 1.12 of stature (Pheasant &
#: Haslegrave 2006, *Bodyspace*, 3rd ed., Table 2.5: 1950 mm for men of 1740 mm, 50th
#: percentile), 0.53 m above the shoulder of the default humanoid (z 0.55). The station's
#: fastens across the body at the car and a pick from a shelf at 1.85 m lie inside it, so the
#: model does not extrapolate to them.
END_BOX = ((0.15, 0.55), (-0.30, 0.30), (-0.48, 0.55))
#: Passes of the wrist-range projection in :func:`reach_trajectory` (each re-solves the arm for
#: the turned hand).
WRIST_ITERATIONS = 6


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
    0.8*size + 0.035 at ``peak`` and closes onto ``size`` at the end.

    Args:
        tau: (n,) normalized time in [0, 1].
        size: object size, metres.
        peak: normalized time of the maximum aperture.
        rest: aperture at the start, metres.

    Returns:
        (n,) apertures, metres.
    """
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

    Args:
        start: (3,) hand start, metres, shoulder frame.
        end: (3,) hand end, metres.
        lengths: (3,) segment lengths, metres.
        rng: random generator (draws the elbow swivel).
        n: samples.
        curvature: peak lift over the start-end distance.
        bump_at: normalized time of the peak lift.
        lift: peak lift, metres, or None.

    Returns:
        ``(directions (n, 3, 3), hand (n, 3))``.
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
    swivel = np.radians(rng.normal(25.0, 6.0))  # elbow out of the vertical plane, per trial
    # Hand direction: in line with the forearm while the hand is carried (a neutral wrist: the
    # arm solved with forearm and hand as one segment), turning to the approach direction
    # (towards the target, slightly down) over the second half, as the hand decelerates onto
    # its target (the grasp forms then: peak grip aperture at about 70 % of the movement,
    # :func:`grip_aperture`).
    u1c, neutral = _arm(hand, np.array([lengths[0], lengths[1] + lengths[2]]), swivel)
    elbows = lengths[0] * u1c  # the elbow of the neutral-wrist arm: it sets the elbow's plane
    app = np.array([end[0], end[1], 0.0])  # out from the shoulder, over the target
    app = app / max(np.linalg.norm(app), 1e-9) + np.array([0.0, 0.0, -0.3])
    w = min_jerk(np.clip(2.0 * tau - 1.0, 0.0, 1.0))[:, None]
    hd = (1 - w) * neutral + w * (app / np.linalg.norm(app))
    hd /= np.linalg.norm(hd, axis=1, keepdims=True)
    # the wrist within its functional range: where the hand direction above would bend it
    # further, the hand turns only as far as the range goes and the arm is re-solved for that
    # hand (a few times over: the forearm moves with the wrist).
    limits = np.radians(FUNCTIONAL_WRIST)
    return wrist_in_range(hand, hd, lengths, elbows, limits, iterations=WRIST_ITERATIONS), hand


def _arm(wrist: np.ndarray, lengths: np.ndarray, swivel: float) -> tuple[np.ndarray, np.ndarray]:
    """Upper arm and forearm directions (n, 3) putting the wrist on ``wrist`` (n, 3), the elbow
    turned ``swivel`` radians outwards from straight below the shoulder-wrist axis.

    Outwards is +y (left) for the left arm at the first pose and stays on the same side of the
    axis as it moves (no flip from one pose to the next). Until 2026-11 the elbow swung the
    other way, in: adducted 16-18 deg (median), 9 cm medial of the shoulder, into the chest."""
    u1 = np.empty_like(wrist)
    u2 = np.empty_like(wrist)
    v = np.array([0.0, 0.0, -1.0])
    prev = np.array([0.0, 1.0, 0.0])
    for t, w in enumerate(wrist):
        axis = w / np.linalg.norm(w)
        down = v - (v @ axis) * axis
        if np.linalg.norm(down) < 1e-6:  # the wrist straight below or above the shoulder
            down = np.array([1.0, 0.0, 0.0]) - axis[0] * axis
        down /= np.linalg.norm(down)
        side = np.cross(axis, down)
        if side @ prev < 0:
            side = -side
        prev = side
        hint = np.cos(swivel) * down + np.sin(swivel) * side
        u1[t], u2[t] = two_link_ik(w, lengths[0], lengths[1], hint)
    return u1, u2


#: The left arm's joint ranges (radians, order of :data:`~mjwalk.arms.chain.ARM_JOINTS`).
_ROM = np.radians([ROM_DEG[j] for j in ARM_JOINTS]).T


def _within_rom(directions: np.ndarray) -> bool:
    """Whether every pose of a left-arm movement (n, 3, 3) lies within the humanoid's joint
    ranges (no forearm pronation)."""
    q = arm_joint_angles(directions)
    return bool(((q >= _ROM[0] - 1e-9) & (q <= _ROM[1] + 1e-9)).all())


def _reachable(p, lengths):
    return np.linalg.norm(p) < 0.9 * (lengths[0] + lengths[1])


def generate(
    space: str, p: int, rng: np.random.Generator, n: int = 20, stature: float = DEFAULT_STATURE
) -> ReachData:
    """Generate ``p`` reaches of constraint ``space`` (one of :data:`SPACES`).

    Args:
        space: one of :data:`SPACES`.
        p: number of reaches.
        rng: random generator (start, end, curvature and swivel noise).
        n: samples per reach.
        stature: body height, metres.

    Returns:
        the reaches (:class:`ReachData`).
    """
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
            end = rng.uniform(*np.array(END_BOX).T)
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
        if not _within_rom(dirs):
            continue  # a joint beyond its range of motion (an elbow folded past 150 deg)
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
