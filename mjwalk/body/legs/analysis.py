"""Gait analysis of capture: sagittal leg angles, heel strikes and time-normalised gait cycles
of a :class:`~mjwalk.mocap.take.Take`, and a :class:`~mjwalk.body.legs.reference.ReferenceGait`
averaged from them; and the swing hip's peaks of a synthesized stair walk
(:func:`swing_hip_peaks`).

World frame: metres, z up; angles in radians.
"""

from __future__ import annotations

import itertools

import numpy as np
from scipy.signal import find_peaks

from mjwalk.body.legs.reference import ReferenceGait
from mjwalk.conventions import Side, side_prefix
from mjwalk.errors import CaptureError, InputError


def sagittal_angles(hip, knee, ankle, toe, yaw):
    """Hip (thigh) flexion, knee flexion and raw foot pitch (ankle -> toe vs floor) of one
    leg in the walking plane (the vertical plane along the heading).

    Args:
        hip: (T, 3) hip joint positions, metres, world frame (z up).
        knee: (T, 3) knee positions.
        ankle: (T, 3) ankle positions.
        toe: (T, 3) toe positions.
        yaw: (T,) the heading, radians from +x CCW.

    Returns:
        (hip flexion, knee flexion, foot pitch), each (T,), radians (flexion +, toes up +).
    """
    fwd = np.column_stack([np.cos(yaw), np.sin(yaw), np.zeros_like(yaw)])
    th, sh, ft = knee - hip, ankle - knee, toe - ankle
    hipf = np.arctan2((th * fwd).sum(1), -th[:, 2])
    kneef = hipf - np.arctan2((sh * fwd).sum(1), -sh[:, 2])
    pitch = np.arctan2(ft[:, 2], (ft * fwd).sum(1))
    return hipf, kneef, pitch


def swing_hip_peaks(walk, legs) -> list[tuple[float, float, float]]:
    """The swing hip of each inner step of a synthesized walk (a stair's flight: the first
    and last steps left out): its peak flexion over the swing, its flexion as the swing foot
    lands, and where in the swing the peak lies. Hip flexion is the synthesis's joint angle:
    the thigh relative to the pelvis (the thigh from the vertical in the walking plane plus
    the pelvis's forward tilt, which is zero but on a stair ascent: pelvistilt).

    Args:
        walk: a :class:`~mjwalk.plan.walkpath.WalkPath` with at least three steps.
        legs: its :class:`~mjwalk.body.legs.synthesis.LegMotion` (``contact``: 0 left
            stance, 1 right stance, 2 double support).

    Returns:
        per inner step (peak deg, at landing deg, the peak's share of the swing from lift-off
        to landing, 0-1).
    """
    out = []
    for st in walk.steps[1:-1]:
        s, other = st.side[0], 0 if st.side == "right" else 1  # the swing: the other's stance
        idx = np.arange(st.start, st.end + 1)
        air = idx[legs.contact[idx] == other]
        if not len(air):
            raise InputError(f"swing_hip_peaks: the step at sample {st.start} has no swing")
        lift, land = int(air[0]), min(int(air[-1]) + 1, len(legs.t) - 1)
        hip = np.rad2deg(legs.angles[f"hip_{s}_flex"])
        k = lift + int(np.argmax(hip[lift : land + 1]))
        out.append((float(hip[k]), float(hip[land]), (k - lift) / max(land - lift, 1)))
    return out


def heel_strikes(pitch: np.ndarray, fps: float) -> np.ndarray:
    """Sample indices of heel strikes: the foot's toes-up pitch peaks, at least 0.6 s apart
    and 10 deg prominent. The foot lands heel first with the toes highest, then rolls down.

    Args:
        pitch: (T,) foot pitch, radians, + toes up.
        fps: the sample rate, frames per second.

    Returns:
        (H,) increasing sample indices.
    """
    peaks, _ = find_peaks(pitch, distance=max(1, int(0.6 * fps)), prominence=np.deg2rad(10))
    return peaks


def gait_cycles(
    take, side: Side = "left", names: str = "UpperLeg_{},LowerLeg_{},Foot_{},Toes_{}", n: int = 101
) -> np.ndarray:
    """Time-normalised gait cycles of one leg of a capture :class:`~mjwalk.mocap.take.Take`.

    Args:
        take: a take with ``joints`` holding hip, knee, ankle and toe positions.
        side: the leg, "left" or "right".
        names: comma-separated joint-name patterns (hip, knee, ankle, toe), ``{}`` = the side's
            capital letter ("L"/"R", as in the bandai-walk skeleton).
        n: samples per cycle.

    Returns:
        (C, 3, n) per complete cycle (heel strike to heel strike, the first and last dropped):
        thigh flexion, knee flexion and foot pitch (radians; pitch relative to the flat foot,
        the median over 20-40 % of the cycle).
    """
    keys = [k.format(side_prefix(side).upper()) for k in names.split(",")]
    missing = [k for k in keys if k not in take.joints]
    if missing:
        raise CaptureError(
            f"{take.name}: gait_cycles needs joints {missing} (have {sorted(take.joints)[:8]}...)"
        )
    h, k, a, t = (np.asarray(take.joints[j], float) for j in keys)
    hipf, kneef, pitch = sagittal_angles(h, k, a, t, np.asarray(take.pelvis_yaw, float))
    hs = heel_strikes(pitch, take.fps)
    x = np.linspace(0, 1, n)
    rows = []
    for i0, i1 in itertools.pairwise(hs):
        s = np.linspace(0, 1, i1 - i0 + 1)
        rows.append([np.interp(x, s, v[i0 : i1 + 1]) for v in (hipf, kneef, pitch)])
    cycles = np.array(rows[1:-1]).reshape(-1, 3, n)
    if len(cycles):
        flat = np.median(cycles[:, 2, int(0.2 * (n - 1)) : int(0.4 * (n - 1)) + 1])
        cycles[:, 2] -= flat
    return cycles


def reference_from_takes(
    takes, side: Side = "left", names: str = "UpperLeg_{},LowerLeg_{},Foot_{},Toes_{}"
) -> ReferenceGait:
    """A reference gait from captured straight walks: the mean of their gait cycles.

    Args:
        takes: captures with the leg joints ``names`` (see :func:`gait_cycles`).
        side: the leg, "left" or "right".
        names: comma-separated joint-name patterns (hip, knee, ankle, toe).

    Returns:
        the :class:`ReferenceGait` (hip, knee, pitch over the cycle, radians); CaptureError
        without a complete cycle.
    """
    cyc = [c for t in takes for c in gait_cycles(t, side, names)]
    if not cyc:
        raise CaptureError("reference_from_takes: no complete gait cycle in the takes")
    m = np.mean(cyc, axis=0)
    return ReferenceGait(
        cycle=np.linspace(0, 1, m.shape[1]),
        hip=m[0],
        knee=m[1],
        pitch=m[2],
        source=f"{len(cyc)} captured cycles ({', '.join(t.name for t in takes)})",
    )
