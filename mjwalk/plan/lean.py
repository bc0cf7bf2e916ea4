"""The stance leg's sideways lean: whether it can follow a step's pelvis within the ankle's
and the hip's ranges (:func:`stance_lean_ok`, compiled) and its NumPy form
(:func:`stance_lean`, for walks already planned and as the compiled check's reference).
"""

from __future__ import annotations

import math

import numpy as np

from mjwalk._jit import njit
from mjwalk.plan.slots import (
    P_ABDUCTION,
    P_ADDUCTION,
    P_EVERSION,
    P_HIP_Y,
    P_INVERSION,
    P_LEG_SPAN,
)
from mjwalk.plan.stepgeom import decode_real


def stance_lean(
    pelvis: np.ndarray, yaw: np.ndarray, stance: np.ndarray, stance_left: bool, par: np.ndarray
) -> tuple[np.ndarray, np.ndarray]:
    """The stance leg's sideways lean at pelvis samples, as :func:`stance_lean_ok` takes it
    (NumPy; the reference of the compiled check, and for walks already planned).

    Args:
        pelvis: (k, 2) pelvis positions, metres.
        yaw: (k,) pelvis headings, radians from +x, in the same frame.
        stance: (3,) the stance foot (x, y, heading), metres and radians, in the same frame.
        stance_left: whether the stance foot is the left one.
        par: :func:`~mjwalk.plan.slots.params` with the P_HIP_Y and P_LEG_SPAN slots.

    Returns:
        (ankle inversion, hip abduction) (k,) each, radians, anatomical signs (negative:
        eversion, adduction), of a straight leg keeping the sole level sideways.
    """
    s = 1.0 if stance_left else -1.0
    yaw = np.asarray(yaw, float)
    left = np.stack([-np.sin(yaw), np.cos(yaw)], -1)
    v = np.asarray(stance[:2], float) - (np.asarray(pelvis, float) + s * par[P_HIP_Y] * left)
    span = par[P_LEG_SPAN]
    h = np.sqrt(np.maximum(span**2 - (v**2).sum(-1), 1e-12))
    foot_left = np.array([-math.sin(stance[2]), math.cos(stance[2])])
    inv = s * np.arctan2(v @ foot_left, h)
    abd = s * np.arcsin(np.clip((v * left).sum(-1) / span, -1.0, 1.0))
    return inv, abd


def lean_in_range(inv: np.ndarray, abd: np.ndarray, par: np.ndarray) -> bool:
    """Whether every lean of :func:`stance_lean` is within the P_EVERSION .. P_ABDUCTION ranges.

    Args:
        inv: (k,) ankle inversions, radians (negative: eversion).
        abd: (k,) hip abductions, radians (negative: adduction).
        par: :func:`~mjwalk.plan.slots.params` with the P_EVERSION .. P_ABDUCTION slots.

    Returns:
        Whether every lean lies within its range.
    """
    return bool(
        np.all((inv >= -par[P_EVERSION]) & (inv <= par[P_INVERSION]))
        and np.all((abd >= -par[P_ADDUCTION]) & (abd <= par[P_ABDUCTION]))
    )


@njit
def stance_lean_ok(z, r, matrix, offset, loc, m, ankle, foot_heading, stance_left, par):
    """Whether the stance leg can follow the pelvis samples of one step without leaving the
    ankle's eversion/inversion or the hip's adduction/abduction range.

    The leg synthesis (:mod:`mjwalk.body.legs`) keeps the stance sole level sideways, so the
    ankle takes the whole sideways lean of the hip-to-ankle line in the stance foot's frame,
    ``atan2(u_y, h)`` (its inversion, :func:`~mjwalk.body.legs.leg_ik`), and the upright pelvis
    leaves the hip the sideways lean of that line in the pelvis frame. Both are taken with the
    leg stretched straight (``P_LEG_SPAN``: the hip as high above the ankle as it can be), so a
    step refused here cannot be followed at any pelvis height: the check is a necessary
    condition, not a model of the synthesis's pelvis height. The hip's lean is that of a
    straight, unrotated leg, ``asin(p_y / span)``.

    Args:
        z: (n, d) the standardized features.
        r: the row of the step.
        matrix: (d, 2m + 3) the decoder's complex matrix, with the pelvis yaw at the m samples
            in columns m + 2 .. 2m + 1 (real parts, radians relative to the step's frame).
        offset: (2m + 3,) the decoder's complex offset.
        loc: the decoded pelvis samples (m,) of the row, step frame (x right, y forward).
        m: pelvis samples per step.
        ankle: the stance foot (the point under its ankle), step frame, x + iy.
        foot_heading: the stance foot's heading relative to the step's frame (radians).
        stance_left: whether the stance foot is the left one.
        par: :func:`~mjwalk.plan.slots.params` with the P_HIP_Y .. P_ABDUCTION slots (metres,
            radians).
    """
    return lean_ok(
        z, r, matrix, offset, loc, m, ankle, foot_heading, stance_left, par, lean_limits(par)
    )


@njit
def lean_limits(par):
    """The stance-lean limits of ``par`` as slopes (atan2(y, h) and asin(y / span) are
    monotonic in y): tan of the eversion and inversion, sin of the adduction and abduction.

    Args:
        par: :func:`~mjwalk.plan.slots.params` with the P_EVERSION .. P_ABDUCTION slots
            (radians).
    """
    return (
        math.tan(par[P_EVERSION]),
        math.tan(par[P_INVERSION]),
        math.sin(par[P_ADDUCTION]),
        math.sin(par[P_ABDUCTION]),
    )


@njit
def lean_ok(z, r, matrix, offset, loc, m, ankle, foot_heading, stance_left, par, limits):
    """:func:`stance_lean_ok` with :func:`lean_limits` made once per batch of steps.

    Args:
        z: (n, d) the standardized features.
        r: the row of the step.
        matrix: (d, 2m + 3) the decoder's complex matrix.
        offset: (2m + 3,) the decoder's complex offset.
        loc: the decoded pelvis samples (m,) of the row, step frame, x + iy, metres.
        m: pelvis samples per step.
        ankle: the stance foot (the point under its ankle), step frame, x + iy, metres.
        foot_heading: the stance foot's heading relative to the step's frame, radians.
        stance_left: whether the stance foot is the left one.
        par: :func:`~mjwalk.plan.slots.params` with the P_HIP_Y .. P_ABDUCTION slots.
        limits: :func:`lean_limits` of ``par``.
    """
    s = 1.0 if stance_left else -1.0
    hip_y = par[P_HIP_Y]
    span = par[P_LEG_SPAN]
    foot = complex(math.cos(-foot_heading), math.sin(-foot_heading))
    tan_ev, tan_inv, sin_add, sin_abd = limits
    for j in range(m):
        psi = decode_real(z, r, matrix, offset, m + 2 + j)
        turn = complex(math.cos(psi), math.sin(psi))
        # the hip joint centre: the left one is hip_y to the pelvis's left (-x turned by psi)
        v = ankle - (loc[j] - s * hip_y * turn)  # hip to ankle, step frame
        h = math.sqrt(max(span * span - (v.real * v.real + v.imag * v.imag), 1e-12))
        # ankle: the sideways lean atan2(s u_y, h) in the stance foot's frame (left = -x
        # turned by its heading)
        inv = -s * (v * foot).real
        if inv < -tan_ev * h or inv > tan_inv * h:
            return False
        # hip: the sideways lean asin(s p_y / span) of a straight leg in the pelvis frame
        abd = -s * (v * turn.conjugate()).real
        if abd < -sin_add * span or abd > sin_abd * span:
            return False
    return True
