"""Virtual-subject corpus: deterministic synthetic capture following agethen2018 §3.2.

The product ships no motion capture, so the step model is trained on takes generated here.
Each virtual subject (:class:`SubjectParams`, drawn by :func:`sample_subject`) performs the
paper's capture protocol:

1. ``free``: walking freely in a 6 m x 6 m space (``AREA``) with varying speed and
   curvature, including side steps and on-the-spot turning steps;
2. ``straight``: straight lines of 3 m and 4 m, starting and ending at rest;
3. ``pole``: walking towards a pole, passing it, turning by 45, 90, 135 or 180 degrees and
   walking on (path lengths 3 m and 4 m);
4. ``short`` (beyond the paper): walking to a spot 0.8-2.5 m away, the steps scaled so that an
   integer number of them ends there (step-length targeting, see ``_short_plan``).

**Step process.** A walk is a sequence of footsteps around a *walking line*: the centre point
``c_k`` advances by a step length along the body heading ``theta_k`` (plus a lateral part for
side steps) and the landing foot is placed half a step width to its side of ``c_k``, rotated
outward by the toe-out angle. Step lengths and durations follow a per-bout speed factor
(length ~ f^0.6, duration ~ f^-0.4) with step-to-step noise; heading changes are spread over
the steps of a turn, favouring one foot according to the subject's turning strategy. Every bout
starts standing (feet side by side), begins with a shorter gait-initiation step and ends with a
closing step that brings the feet side by side again.

**Contact timing.** Step ``k`` lasts ``T_k`` from the heel strike of the previous foot to the
heel strike of its swing foot: a double-support phase (``double_support * T_k``) then the swing.
During stance, ankle (0.08 m) and toe (0.02 m) are exactly stationary; during swing the foot
travels along a smooth arc (peak clearance ``clearance``) with a cycloid-like progress profile.
The true key frames are stored in ``Take.meta`` (``heel_strikes`` / ``toe_offs``, side ->
frame array; a heel strike is the first planted frame, a toe-off the first moving frame).

**Pelvis.** The zero-moment point ``p(t)`` is piecewise linear: under the stance foot during
single support (rolling from heel to forefoot, laterally ``zmp_offset`` from the walking line),
moving between the feet during double support, midway between them when standing. The
horizontal pelvis ``x(t)`` solves the linear inverted pendulum ``x'' = g/z0 (x - p)`` as a
boundary-value problem (at rest over ``p`` at both ends of a grid padded by 2 s) at 120 Hz:
one tridiagonal solve per take (``scipy.linalg.solve_banded``), which is the unique bounded
solution and gives the lateral sway towards the stance foot. The pelvis height bobs by ``bob``
(high in single support, low in double support); the pelvis yaw follows the walking heading
plus the transverse pelvic rotation (``pelvis_rotation``, extreme at heel strikes).

All outputs: 120 Hz, metres, z up, yaw radians CCW from +x (world frame).
"""

from __future__ import annotations

import math
from dataclasses import asdict

import numpy as np

from mjwalk.errors import MjwalkError
from mjwalk.gait.bout import BoutPlan, render_bout
from mjwalk.gait.subjects import SubjectParams, sample_subject
from mjwalk.mocap.take import Take

#: Version of the corpus generator: bump it whenever generated takes change, so cached models
#: trained on an older corpus are rebuilt (see mjwalk.gait.default).
CORPUS_VERSION = "2"

#: Floor space of the free-walking scenario, metres. The paper's tracking space is 3.3 m x 3.2 m
#: (agethen2018 §3.2); walking freely in so small a space turns nearly every step, far more than
#: the captured clips we calibrate on, so the virtual subjects walk freely in a 6 m x 6 m hall.
AREA = (6.0, 6.0)
#: Pole-protocol turning angles (degrees) and path lengths (metres), agethen2018 §3.2.
POLE_ANGLES = (45.0, 90.0, 135.0, 180.0)
LINE_LENGTHS = (3.0, 4.0)
#: Short walks (not in the paper's protocol; see ``_short_plan``): distances from standing to
#: standing (m, uniform), the initiation step's share of a scaled step, and how much longer than
#: the preferred step a subject stretches before taking one step more (both uniform, per walk),
#: at most ``SHORT_MAX_STEPS`` advancing steps (then the closing step); ``SHORT_TURN``: largest
#: heading change (degrees, uniform +-) over the advancing steps.
#: No capture we have holds a walk from or to a stand, so these ranges are not calibrated on
#: capture: they spread the initiation and the scale of the steps about the long bouts' 0.7-0.85
#: and 1.0. Walks of 0.6-1.4 m in at most two advancing steps cover the station's 1.1 m route T5
#: (the straight and pole bouts cover 2 m and more); few and short, so the model's forward
#: chains do not linger in short steps (docs/decisions/004-corpus-short-walks.md).
SHORT_RANGE = (0.6, 1.4)
SHORT_INITIATION = (0.6, 0.9)
SHORT_STRETCH = (0.75, 1.15)
SHORT_MAX_STEPS = 2
SHORT_TURN = 30.0
#: Paper's protocol minutes per subject: free 4, straight 2 + 2, pole 8 x 2 (agethen2018 §3.2),
#: plus short walks (``_short_plan``), which the paper's protocol lacks: without them the model's
#: first and closing steps barely vary and a walk to a spot about a metre away cannot end within
#: a tight goal area except by a detour.
PROTOCOL_MINUTES = {"free": 4.0, "straight": 4.0, "pole": 16.0, "short": 2.5}
#: Default minutes per subject (paper: 24, without the short walks; 25.5 leaves the paper's
#: scenarios the 23 minutes they had before the short walks). 12 subjects at this size give
#: > 20 000 captured transitions (see benchmarks/bench_corpus.py).
DEFAULT_MINUTES = 25.5

# ---------------------------------------------------------------------------------------------
# Step plans
# ---------------------------------------------------------------------------------------------


def _turn_profile(angle: float, p: SubjectParams, rng: np.random.Generator) -> np.ndarray:
    """Heading changes (rad) spreading ``angle`` over enough steps, bell-shaped."""
    m = max(1, math.ceil(abs(angle) / p.max_turn))
    w = np.sin(np.linspace(0, np.pi, m + 2)[1:-1]) * rng.uniform(0.8, 1.2, m)
    return angle * w / w.sum()


def _speed(p: SubjectParams, f: np.ndarray, rng: np.random.Generator) -> tuple:
    """Step lengths and durations for speed factors ``f`` with intra-subject noise."""
    n = f.shape[0]
    length = p.step_length * f**0.6 * (1 + p.length_cv * rng.standard_normal(n))
    dur = p.step_duration * f**-0.4 * (1 + p.duration_cv * rng.standard_normal(n))
    return length, dur


def _bout_plan(
    p: SubjectParams, rng: np.random.Generator, distance: float, turn: float = 0.0
) -> BoutPlan:
    """Straight walk of about ``distance`` metres, optionally turning by ``turn`` radians half
    way (the pole protocol); begins with a gait initiation and ends with a closing step."""
    f0 = float(np.exp(rng.normal(0.0, p.speed_sd)))
    turns = _turn_profile(turn, p, rng) if turn else np.zeros(0)
    n_mid = max(1, round((distance - 0.55 * p.step_length) / p.step_length))
    n = n_mid + 2
    f = f0 * np.exp(0.02 * rng.standard_normal(n))
    length, dur = _speed(p, f, rng)
    dtheta = np.radians(1.2) * rng.standard_normal(n)
    if turns.size:
        # Place the turn around the middle of the path; turning steps are shorter and slower.
        k0 = int(np.clip(n // 2 - turns.size // 2, 1, max(1, n - 1 - turns.size)))
        if k0 + turns.size > n - 1:
            extra = k0 + turns.size - (n - 1)
            length = np.concatenate([length, length[-1:].repeat(extra)])
            dur = np.concatenate([dur, dur[-1:].repeat(extra)])
            dtheta = np.concatenate([dtheta, np.zeros(extra)])
            n += extra
        sl = slice(k0, k0 + turns.size)
        dtheta[sl] += turns
        share = np.abs(turns) / p.max_turn
        length[sl] *= 1 - 0.15 * share
        dur[sl] *= 1 + 0.06 * share
    # Gait initiation (first) and closing (last) steps.
    length[0] *= rng.uniform(0.7, 0.85)
    dur[0] *= rng.uniform(1.0, 1.1)
    length[-1] *= rng.uniform(0.45, 0.6)
    dtheta[0] = dtheta[-1] = 0.0
    return BoutPlan(list(length), [0.0] * n, list(dtheta), list(dur))


def _short_plan(p: SubjectParams, rng: np.random.Generator, distance: float) -> BoutPlan:
    """A short walk from standing to standing to a spot ``distance`` metres away along the
    walking line (start stance centre to end stance centre), with *step-length targeting*:
    people walking a short way take the number of steps that fits and scale them, rather than
    walk full strides and miss the spot.

    The subject picks the fewest advancing steps ``k`` (gait initiation included, closing step
    not; at most ``SHORT_MAX_STEPS``) whose scaled length does not exceed the preferred one by
    more than a tolerance drawn per walk (``SHORT_STRETCH``): short walks take shorter steps,
    scale factors spread over about 0.5-1.2. The initiation share of a step
    (``SHORT_INITIATION``) varies more than in the long bouts; step-to-step noise is the
    subject's, then all advances are rescaled so the walk ends at the spot. The step durations
    are those of the bout's speed (the cadence stays, the steps shorten: with the speed law's
    durations for the scaled steps, 0.66 s a step on average, the model's slow short steps
    entered longer walks: station route T1's duration IQR 0.55 -> 1.11 s). The walker sets
    off turned by up to ``SHORT_TURN`` degrees from the line to the spot and turns onto it over
    the advancing steps (the line bends: the spot lies up to 1.5 % nearer)."""
    f0 = float(np.exp(rng.normal(0.0, p.speed_sd)))
    pref = p.step_length * f0**0.6
    r0 = float(rng.uniform(*SHORT_INITIATION))
    stretch = float(rng.uniform(*SHORT_STRETCH))
    k = min(SHORT_MAX_STEPS, max(1, math.ceil(distance / (stretch * pref) - r0 + 1.0 - 1e-9)))
    scale = distance / ((r0 + k - 1) * pref)
    length = np.full(k, scale * pref)
    length[0] *= r0
    length *= 1 + p.length_cv * rng.standard_normal(k)
    length *= distance / length.sum()  # the walk ends at the spot
    _, dur = _speed(p, f0 * np.exp(0.02 * rng.standard_normal(k + 1)), rng)
    dur[0] *= rng.uniform(1.0, 1.1)
    dtheta = np.radians(1.2) * rng.standard_normal(k + 1)
    # the walker sets off turned from the line to the spot and turns onto it while walking
    turn = np.radians(rng.uniform(-SHORT_TURN, SHORT_TURN))
    w = rng.uniform(0.5, 1.5, k)
    dtheta[:k] += turn * w / w.sum()
    dtheta[-1] = 0.0
    # the closing step lands beside the other foot (see render_bout): it advances the line by 0
    return BoutPlan([*length, 0.0], [0.0] * (k + 1), list(dtheta), list(dur))


def _free_plan(
    p: SubjectParams, rng: np.random.Generator, seconds: float, start: np.ndarray, theta: float
) -> BoutPlan:
    """Free walking in the tracking space for about ``seconds``: speed and curvature vary
    (AR(1) per step), occasional side steps and on-the-spot turns; steers back to the centre
    near the area's border."""
    half = 0.5 * np.asarray(AREA) - 0.3
    fwd, lat, dth, dur = [], [], [], []
    c = np.array(start, float)
    logf, kappa, t = 0.0, 0.0, 0.0
    queue: list[tuple[float, float, float, float]] = []  # pending (fwd, lat, dtheta, dur)
    k = 0
    while t < seconds or queue:
        if queue:
            a, b, d, T = queue.pop(0)
        elif k == 0:
            a, b, d, T = 0.78 * p.step_length, 0.0, 0.0, 1.05 * p.step_duration
        else:
            u = rng.random()
            if u < 0.01 and k > 2:  # a short run of side steps (even count), slow
                side = rng.choice([-1.0, 1.0])
                for _ in range(2 * int(rng.integers(1, 3))):
                    queue.append(
                        (0.05, side * rng.uniform(0.15, 0.25), 0.0, 1.15 * p.step_duration)
                    )
                continue
            if u < 0.012 and k > 2:  # turning on the spot: short, slow steps
                ang = rng.choice([-1.0, 1.0]) * np.radians(rng.uniform(90, 180))
                for d_ in _turn_profile(ang, p, rng):
                    queue.append(
                        (rng.uniform(0.2, 0.4) * p.step_length, 0.0, d_, 1.12 * p.step_duration)
                    )
                continue
            logf = 0.9 * logf + 0.04 * rng.standard_normal()
            kappa = 0.8 * kappa + np.radians(3.0) * rng.standard_normal()
            out = np.abs(c) > half
            d = kappa
            if out.any():
                to_centre = math.atan2(-c[1], -c[0])
                err = (to_centre - theta + np.pi) % (2 * np.pi) - np.pi
                d += np.clip(0.15 * err, -0.3 * p.max_turn, 0.3 * p.max_turn)
            f = np.exp(logf)
            L, T = _speed(p, np.array([f]), rng)
            a, b, T = float(L[0]) * (1 - 0.15 * abs(d) / p.max_turn), 0.0, float(T[0])
        th = theta + 0.5 * d
        c = (
            c
            + a * np.array([math.cos(th), math.sin(th)])
            + b * np.array([math.sin(th), -math.cos(th)])
        )
        theta += d
        fwd.append(a)
        lat.append(b)
        dth.append(d)
        dur.append(T)
        t += T
        k += 1
    fwd.append(0.5 * fwd[-1] if abs(lat[-1]) < 1e-9 else 0.0)  # closing step
    lat.append(0.0)
    dth.append(0.0)
    dur.append(p.step_duration)
    return BoutPlan(fwd, lat, dth, dur)


# ---------------------------------------------------------------------------------------------
# Protocol
# ---------------------------------------------------------------------------------------------


def subject_takes(
    p: SubjectParams, rng: np.random.Generator, minutes: float = DEFAULT_MINUTES
) -> list[Take]:
    """All takes of one subject: the paper's three scenarios in its time proportions, then the
    short walks (``PROTOCOL_MINUTES``).

    Args:
        p: the subject's gait parameters.
        rng: generator for every random draw (start poses, bouts, noise), used in order.
        minutes: capture time of the subject, minutes, split over the scenarios.

    Returns:
        The subject's takes at 120 Hz (world frame, metres, z up), named
        ``virtual-sNN-<protocol>-NNNN``, with ``meta`` as :func:`generate_corpus`.
    """
    total = sum(PROTOCOL_MINUTES.values())
    takes: list[Take] = []
    base = {"subject": p.subject, "params": asdict(p)}

    def emit(plan: BoutPlan, protocol: str, extra: dict, start, theta0) -> float:
        name = f"virtual-s{p.subject:02d}-{protocol}-{len(takes):04d}"
        take = render_bout(
            plan,
            p,
            rng,
            name,
            np.asarray(start, float),
            theta0,
            {**base, "protocol": protocol, **extra},
        )
        takes.append(take)
        return take.duration

    # (1) free walking, bouts of 30-60 s
    budget = 60.0 * minutes * PROTOCOL_MINUTES["free"] / total
    while budget > 0:
        theta0 = float(rng.uniform(-np.pi, np.pi))
        start = rng.uniform(-0.5, 0.5, 2)
        secs = min(float(rng.uniform(30, 60)), max(budget, 8.0))
        budget -= emit(_free_plan(p, rng, secs, start, theta0), "free", {}, start, theta0)
    # (2) straight lines of 3 m and 4 m
    for dist in LINE_LENGTHS:
        budget = 60.0 * minutes * PROTOCOL_MINUTES["straight"] / total / len(LINE_LENGTHS)
        while budget > 0:
            theta0 = float(rng.uniform(-np.pi, np.pi))
            plan = _bout_plan(p, rng, dist)
            budget -= emit(plan, "straight", {"distance": dist}, np.zeros(2), theta0)
    # (3) pole: walk, pass the pole, turn by the angle (left or right), walk on
    for ang in POLE_ANGLES:
        for dist in LINE_LENGTHS:
            budget = (
                60.0
                * minutes
                * PROTOCOL_MINUTES["pole"]
                / total
                / len(POLE_ANGLES)
                / len(LINE_LENGTHS)
            )
            while budget > 0:
                theta0 = float(rng.uniform(-np.pi, np.pi))
                turn = float(rng.choice([-1.0, 1.0]) * np.radians(ang))
                # the approach and the walk on after the turn are each ``dist`` long
                plan = _bout_plan(p, rng, 2.0 * dist, turn)
                extra = {"distance": dist, "turn_deg": float(np.degrees(turn))}
                budget -= emit(plan, "pole", extra, np.zeros(2), theta0)
    # (4) short walks to a spot, from standing to standing
    budget = 60.0 * minutes * PROTOCOL_MINUTES["short"] / total
    while budget > 0:
        theta0 = float(rng.uniform(-np.pi, np.pi))
        dist = float(rng.uniform(*SHORT_RANGE))
        plan = _short_plan(p, rng, dist)
        budget -= emit(plan, "short", {"distance": dist}, np.zeros(2), theta0)
    return takes


def generate_corpus(
    n_subjects: int = 12, seed: int = 0, *, minutes_per_subject: float | None = None
) -> list[Take]:
    """Generate the virtual-subject corpus (deterministic: same seed, same takes).

    Args:
        n_subjects: number of virtual subjects (agethen2018: 12).
        seed: seed; subject ``i`` draws from ``numpy.random.default_rng([seed, i])``, so a
            subject's takes do not depend on ``n_subjects``.
        minutes_per_subject: capture time per subject, split over the four scenarios in the
            proportions of ``PROTOCOL_MINUTES`` (free 4 : straight 4 : pole 16, the paper's,
            : short 2.5); default ``DEFAULT_MINUTES``.

    Returns:
        Takes at 120 Hz (metres, z up); ``meta`` holds ``subject``, ``protocol`` (``free``,
        ``straight``, ``pole``, ``short``), ``params`` and the true ``heel_strikes`` / ``toe_offs``.
    """
    if n_subjects < 1:
        raise MjwalkError(f"generate_corpus: n_subjects must be >= 1, got {n_subjects}")
    minutes = DEFAULT_MINUTES if minutes_per_subject is None else float(minutes_per_subject)
    if not minutes > 0:
        raise MjwalkError(f"generate_corpus: minutes_per_subject must be > 0, got {minutes}")
    takes: list[Take] = []
    for i in range(n_subjects):
        rng = np.random.default_rng([seed, i])
        takes.extend(subject_takes(sample_subject(rng, i), rng, minutes))
    return takes
