"""The pelvis tilted backward (posteriorly) in stair ascent (issue 47): how far, over which
samples, and the hip joints re-expressed so the legs stay where the leg synthesis put them.

The leg synthesis solves each leg in a pelvis that only turns about z (yaw), so its hip flexion
is the thigh's angle from the vertical. People ascending a step tilt the pelvis with the lead
femur's elevation (Bohannon & Smutnick 2010), posteriorly as in every study of that
pelvifemoral rhythm (Bohannon & Bass 2017), and published stair hip flexion is the thigh to the
pelvis. :func:`ascent_tilt` gives a walk's tilt per sample; :func:`tilt_pelvis` turns the
pelvis by it about the line through the hip joint centres (the humanoid's hips sit on the
pelvis body's y axis, so the hips, thighs, shanks and feet keep their world poses) and solves
each hip's rotation, flexion and abduction again in the tilted pelvis. The timeline flexes the
lumbar joint by as much (:func:`mjwalk.timeline.frames.timeline_from_walk`), so the trunk keeps
its pose over the tilted pelvis; the trunk's forward lean up a stair is the spine's, timed by
the same :func:`ascent_share` (:mod:`mjwalk.body.legs.trunklean`).

World frame: metres, seconds, radians, z up, yaw from +x CCW; tilt + = the pelvis's top forward
(about the pelvis's +y axis), - = backward (posterior).
"""

from __future__ import annotations

import math

import numpy as np

from mjwalk.body.legs.curves import smoothstep
from mjwalk.body.legs.ik import rot_x, rot_y, rot_z
from mjwalk.world.norms import MIN_RISER

#: Pelvic tilt held over a stair ascent, radians (negative: backward, posterior). Bohannon &
#: Smutnick, "Pelvifemoral kinematics while ascending single steps of different heights", J
#: Appl Biomech 26(3) 2010, 290-: over four step heights the lead femur elevates 47.2-89.6 deg
#: (means) and the pelvis tilts 2.6-9.7 deg in the sagittal plane, the two synergistic (r =
#: .852-.999; abstract verified here, the step heights and the tilt's sign not stated in it).
#: Their lowest step's mean, 2.6 deg at a femoral elevation of 47.2 deg, is the condition
#: nearest this model's 0.17 m risers (thigh elevation 54-57 deg, benchmarks/bench_levels.py),
#: and the smallest: it is taken, not an interpolation. The sign: the same first author's
#: systematic review of that "pelvifemoral rhythm" defines it as "the coordinated flexion of
#: the thigh and posterior tilting of the pelvis during hip flexion" and finds it in all nine
#: studies, posterior tilt 13.1-37.5 % of the hip flexion, tilt and flexion correlated r =
#: 0.89-1.00 (Bohannon & Bass, "Research describing pelvifemoral rhythm: a systematic review",
#: J Phys Ther Sci 29(11) 2017, 2039-2043, abstract verified here); standing unilateral hip
#: flexion, 18.1 % (Murray, Bohannon et al., Clin Biomech 17 (2002) 147-151, abstract). Whether
#: the review counts the 2010 study among its nine is not verified here: the direction is read
#: from the authors' definition of the rhythm they measured (was an ASSUMPTION of a forward
#: tilt, the abstract silent, before). ASSUMPTION: held through each ascending step rather than
#: following the femur within the step (the abstract gives maxima only).
STAIR_ASCENT_PELVIC_TILT = -math.radians(2.6)
#: Least rise of a step counted as a stair ascent, metres: DIN 18065's smallest riser
#: (:data:`mjwalk.world.norms.MIN_RISER`), less 1 cm. ASSUMPTION: a surveyed stair's riser may
#: read a few millimetres under its nominal height (DIN 18065's 5 mm tolerance, doubled).
ASCENT_MIN_RISE = MIN_RISER - 0.01


def ascent_share(walk, n: int) -> np.ndarray:
    """The share (0 to 1) of a held stair-ascent posture at every sample of a walk: 1 over
    each run of ascending steps (a step whose landing surface lies at least
    :data:`ASCENT_MIN_RISE` above its stance surface), eased in over the run's first step and
    out over the step after its last (the trailing foot's step off the last tread; over the
    run's last step if the walk ends there), 0 elsewhere. The pelvic tilt
    (:func:`ascent_tilt`) and the trunk's lean (:mod:`mjwalk.body.legs.trunklean`) follow it.

    Args:
        walk: a :class:`~mjwalk.plan.walkpath.WalkPath` (its steps' ``foot_z``/``stance_z``).
        n: the number of samples.

    Returns:
        (n,) the share, 0 to 1.
    """
    w = np.zeros(n)
    steps = walk.steps
    up = [s.foot_z - s.stance_z >= ASCENT_MIN_RISE for s in steps]
    k = 0
    while k < len(steps):
        if not up[k]:
            k += 1
            continue
        k1 = k
        while k1 + 1 < len(steps) and up[k1 + 1]:
            k1 += 1
        a, b = steps[k].start, steps[k1].end
        idx = np.arange(a, min(b, n - 1) + 1)
        ramp_in = smoothstep((idx - a) / max(steps[k].end - a, 1))
        if k1 + 1 < len(steps):  # out over the next (level) step
            nxt = steps[k1 + 1]
            w[idx] = ramp_in
            j = np.arange(nxt.start, min(nxt.end, n - 1) + 1)
            w[j] = np.maximum(w[j], 1.0 - smoothstep((j - nxt.start) / max(nxt.end - nxt.start, 1)))
        else:  # the walk ends on the flight: out over its last step
            c = steps[k1].start
            ramp_out = 1.0 - smoothstep((idx - c) / max(b - c, 1))
            w[idx] = np.minimum(ramp_in, ramp_out)
        k = k1 + 1
    return w


def ascent_tilt(walk, n: int, tilt: float = STAIR_ASCENT_PELVIC_TILT) -> np.ndarray:
    """The pelvis's tilt at every sample of a walk: ``tilt`` times :func:`ascent_share` (held
    over each run of ascending steps, eased in and out at its ends), zero elsewhere.

    Args:
        walk: a :class:`~mjwalk.plan.walkpath.WalkPath` (its steps' ``foot_z``/``stance_z``).
        n: the number of samples.
        tilt: the held tilt, radians.

    Returns:
        (n,) tilt, radians (+ forward, - backward).
    """
    return tilt * ascent_share(walk, n)


def thigh_rotation(side: str, rot, flex, abd) -> np.ndarray:
    """The rotation of a thigh in the pelvis frame from its hip angles (the humanoid's hinges
    in order: rotation about (0, 0, -s), flexion about (0, -1, 0), abduction about (s, 0, 0);
    s = +1 left, -1 right).

    Args:
        side: "l" or "r".
        rot: (n,) hip rotation, radians.
        flex: (n,) hip flexion, radians.
        abd: (n,) hip abduction, radians.

    Returns:
        (n, 3, 3) rotation matrices.
    """
    s = 1.0 if side == "l" else -1.0
    return rot_z(-s * rot) @ rot_y(-flex) @ rot_x(s * abd)  # as ik.leg_fk


def tilt_pelvis(angles: dict[str, np.ndarray], tilt: np.ndarray) -> dict[str, np.ndarray]:
    """The hip angles of both legs in a pelvis tilted by ``tilt`` (+ forward), the thighs keeping
    their poses: R_new = Ry(-tilt) R_old, decomposed again into rotation, flexion and
    abduction. With no hip rotation or abduction the flexion grows by the tilt exactly (a
    backward tilt takes it off).

    Args:
        angles: joint name -> (n,) radians (``hip_{l,r}_{rot,flex,abd}`` read).
        tilt: (n,) pelvis tilt, radians (+ forward, - backward).

    Returns:
        a copy of ``angles`` with the six hip angles replaced where ``tilt`` is not zero.
    """
    out = dict(angles)
    on = np.flatnonzero(tilt)
    if not len(on):
        return out
    for side in "lr":
        s = 1.0 if side == "l" else -1.0
        names = [f"hip_{side}_{j}" for j in ("rot", "flex", "abd")]
        r = thigh_rotation(side, *(angles[j][on] for j in names))
        m = rot_y(-tilt[on]) @ r
        # the branch of the flexion nearest the old one plus the tilt (past 90 deg cos b < 0)
        sg = np.where(np.cos(angles[names[1]][on] + tilt[on]) < 0.0, -1.0, 1.0)
        b = np.arctan2(-m[:, 2, 0], sg * np.hypot(m[:, 0, 0], m[:, 1, 0]))
        a = np.arctan2(sg * m[:, 1, 0], sg * m[:, 0, 0])
        g = np.arctan2(sg * m[:, 2, 1], sg * m[:, 2, 2])
        for name, v in zip(names, (-s * a, -b, s * g), strict=True):
            new = angles[name].copy()
            new[on] = v
            out[name] = new
    return out


def pelvis_quat(yaw: np.ndarray, tilt: np.ndarray) -> np.ndarray:
    """Unit quaternions (w, x, y, z) of the pelvis turned by ``yaw`` about +z, then tilted by
    ``tilt`` about its own +y: Rz(yaw) Ry(tilt).

    Args:
        yaw: (N,) radians from +x CCW.
        tilt: (N,) radians, + forward, - backward.

    Returns:
        (N, 4) quaternions.
    """
    cz, sz = np.cos(yaw / 2), np.sin(yaw / 2)
    cy, sy = np.cos(tilt / 2), np.sin(tilt / 2)
    return np.column_stack([cz * cy, -sz * sy, cz * sy, sz * cy])
