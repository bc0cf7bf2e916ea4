"""The per-frame arithmetic of :func:`mjwalk.ergonomics.angles.angles_from_points`, compiled:
one pass over all frames instead of some hundred NumPy calls on (F, 3) arrays (issue 50).

The kernels do the products, sums, square roots and divisions in the order the NumPy code did
them (its ``_unit``, ``_dot``, ``np.cross``, ``np.linalg.norm``, kept verbatim as the reference
in ``tests/ergonomics/test_anglejit.py``: the same floats, no fused
multiply-adds: :func:`mjwalk._jit.njit` keeps ``fastmath`` off); the arc tangents and arc
cosines stay NumPy's (:func:`trig_arguments` returns their arguments, the caller calls
``np.arctan2`` and ``np.arccos`` once on all of them): NumPy's vectorised ``arctan2``/``arccos``
differ from the C library's in the last bit on about 7-9 % of arguments, and the angles must
stay those of the NumPy code. Frames and units as in :mod:`mjwalk.ergonomics.angles` (world
metres, z up).
"""

from __future__ import annotations

import math

import numpy as np

from mjwalk._jit import njit

#: The joints of the kernel's point array, in its order (names of
#: :data:`mjwalk.ergonomics.angles.POINTS`).
KERNEL_POINTS = (
    "pelvis", "neck", "shoulder_l", "shoulder_r", "elbow_l", "elbow_r", "wrist_l", "wrist_r",
    "hip_l", "hip_r", "knee_l", "knee_r", "ankle_l", "ankle_r",
)  # fmt: skip
#: Rows of :func:`trig_arguments`' arc tangent arguments (y, x).
ATAN_ROWS = ("trunk_flexion", "trunk_side_bend", "shoulder_yaw", "hip_yaw", "neck_flexion",
             "neck_side_bend", "plane_l", "plane_r")  # fmt: skip
#: Rows of :func:`trig_arguments`' arc cosine arguments (clipped to [-1, 1]).
ACOS_ROWS = ("trunk_inclination", "arm_l", "arm_r", "elevation_l", "elevation_r", "elbow_l",
             "elbow_r", "knee_l", "knee_r")  # fmt: skip


@njit
def _clip1(x: float) -> float:
    """``np.clip(x, -1.0, 1.0)`` of one value (NaN stays NaN)."""
    if x < -1.0:
        return -1.0
    if x > 1.0:
        return 1.0
    return x


@njit
def _unit3(x: float, y: float, z: float) -> tuple[float, float, float]:
    """The NumPy code's ``_unit`` of one vector: divided by its norm, unless at most 1e-12."""
    n = math.sqrt(x * x + y * y + z * z)
    d = n if n > 1e-12 else 1.0
    return x / d, y / d, z / d


@njit
def trig_arguments(p, head_up, out_share, ys, xs, cs, fwd, fwd_c, out):
    """The arguments of the angles' arc tangents and arc cosines, frame by frame.

    Args:
        p: (14, F, 3) the joints :data:`KERNEL_POINTS`, world metres.
        head_up: (F, 3) the head's up direction (not necessarily unit).
        out_share: a wrist farther than this share of the upper arm's length outward of its
            shoulder is out to the side (:data:`mjwalk.ergonomics.angles.OUT_TO_SIDE_SHARE`).
        ys: (8, F) filled: the arc tangents' y, rows :data:`ATAN_ROWS`.
        xs: (8, F) filled: the arc tangents' x.
        cs: (9, F) filled: the arc cosines' arguments, clipped, rows :data:`ACOS_ROWS`.
        fwd: (F, 3) filled: the pelvis' horizontal forward direction.
        fwd_c: (2, F) filled: each upper arm's forward component in the trunk's frame.
        out: (F, 2) filled: each lower arm out to the side of the body (or across it).
    """
    n = p.shape[1]
    for f in range(n):
        # the pelvis' left (the hip line made horizontal) and forward (left x z)
        hl0, hl1, hl2 = _unit3(p[8, f, 0] - p[9, f, 0], p[8, f, 1] - p[9, f, 1], 0.0)
        f0 = hl1 * 1.0 - hl2 * 0.0
        f1 = hl2 * 0.0 - hl0 * 1.0
        f2 = hl0 * 0.0 - hl1 * 0.0
        fwd[f, 0], fwd[f, 1], fwd[f, 2] = f0, f1, f2
        u0, u1, u2 = _unit3(
            p[1, f, 0] - p[0, f, 0], p[1, f, 1] - p[0, f, 1], p[1, f, 2] - p[0, f, 2]
        )
        ys[0, f], xs[0, f] = u0 * f0 + u1 * f1 + u2 * f2, u2
        ys[1, f], xs[1, f] = u0 * hl0 + u1 * hl1 + u2 * hl2, u2
        cs[0, f] = _clip1(u2)
        s0, s1, s2 = p[2, f, 0] - p[3, f, 0], p[2, f, 1] - p[3, f, 1], p[2, f, 2] - p[3, f, 2]
        ys[2, f], xs[2, f] = s1, s0
        ys[3, f], xs[3, f] = hl1, hl0
        # the trunk's frame: up the trunk axis, left the shoulder line orthogonal to it
        d = s0 * u0 + s1 * u1 + s2 * u2
        l0, l1, l2 = _unit3(s0 - d * u0, s1 - d * u1, s2 - d * u2)
        c0 = l1 * u2 - l2 * u1
        c1 = l2 * u0 - l0 * u2
        c2 = l0 * u1 - l1 * u0
        h0, h1, h2 = _unit3(head_up[f, 0], head_up[f, 1], head_up[f, 2])
        hup = h0 * u0 + h1 * u1 + h2 * u2
        ys[4, f], xs[4, f] = h0 * c0 + h1 * c1 + h2 * c2, hup
        ys[5, f], xs[5, f] = h0 * l0 + h1 * l1 + h2 * l2, hup
        m0 = 0.5 * (p[2, f, 0] + p[3, f, 0])
        m1 = 0.5 * (p[2, f, 1] + p[3, f, 1])
        m2 = 0.5 * (p[2, f, 2] + p[3, f, 2])
        for s in range(2):
            o0, o1, o2 = (l0, l1, l2) if s == 0 else (-l0, -l1, -l2)
            sh, el, wr = 2 + s, 4 + s, 6 + s
            a0, a1, a2 = (
                p[el, f, 0] - p[sh, f, 0],
                p[el, f, 1] - p[sh, f, 1],
                p[el, f, 2] - p[sh, f, 2],
            )
            b0, b1, b2 = _unit3(p[wr, f, 0] - p[el, f, 0], p[wr, f, 1] - p[el, f, 1],
                                p[wr, f, 2] - p[el, f, 2])  # fmt: skip
            e0, e1, e2 = _unit3(a0, a1, a2)
            down_c = -(e0 * u0 + e1 * u1 + e2 * u2)
            fc = e0 * c0 + e1 * c1 + e2 * c2
            oc = e0 * o0 + e1 * o1 + e2 * o2
            cs[1 + s, f] = _clip1(down_c)
            ys[6 + s, f], xs[6 + s, f] = abs(oc), abs(fc)
            fwd_c[s, f] = fc
            cs[3 + s, f] = _clip1(-e2)
            cs[5 + s, f] = _clip1(e0 * b0 + e1 * b1 + e2 * b2)
            lat = (p[wr, f, 0] - m0) * o0 + (p[wr, f, 1] - m1) * o1 + (p[wr, f, 2] - m2) * o2
            sh_lat = (p[sh, f, 0] - m0) * o0 + (p[sh, f, 1] - m1) * o1 + (p[sh, f, 2] - m2) * o2
            u_len = math.sqrt(a0 * a0 + a1 * a1 + a2 * a2)
            out[f, s] = (lat < 0.0) or (lat - sh_lat > out_share * u_len)
            hp, kn, an = 8 + s, 10 + s, 12 + s
            t0, t1, t2 = _unit3(p[kn, f, 0] - p[hp, f, 0], p[kn, f, 1] - p[hp, f, 1],
                                p[kn, f, 2] - p[hp, f, 2])  # fmt: skip
            g0, g1, g2 = _unit3(p[an, f, 0] - p[kn, f, 0], p[an, f, 1] - p[kn, f, 1],
                                p[an, f, 2] - p[kn, f, 2])  # fmt: skip
            cs[7 + s, f] = _clip1(t0 * g0 + t1 * g1 + t2 * g2)


@njit
def z_offsets(xpos, xmat, cols, z, out):
    """Body origins from their geoms' poses: ``out[k, f] = xpos[f, cols[k]] - z[k] * R[:, 2]``
    with R the geom's rotation ``xmat[f, cols[k]]`` (row-major), for a geom at ``(0, 0, z[k])``
    in its body's frame, unrotated: the product ``R @ (0, 0, z)`` as BLAS gives it (the two
    zero terms add nothing), frame by frame (a frame's geoms lie side by side in the table).

    Args:
        xpos: (F, G, 3) geom positions, world metres.
        xmat: (F, G, 9) geom rotations (row-major).
        cols: (K,) the geoms' columns in ``xpos``/``xmat``.
        z: (K,) each geom's offset along its body's z axis, metres.
        out: (K, F, 3) filled: the bodies' origins, world metres.
    """
    for f in range(xpos.shape[0]):
        for k in range(len(cols)):
            c = cols[k]
            for i in range(3):
                out[k, f, i] = xpos[f, c, i] - xmat[f, c, 3 * i + 2] * z[k]


@njit
def gather(xpos, xmat, cols, pos, mat):
    """Copies of some columns of a geom table, frame by frame (contiguous, for NumPy's products).

    Args:
        xpos: (F, G, 3) geom positions.
        xmat: (F, G, 9) geom rotations.
        cols: (K,) the columns.
        pos: (K, F, 3) filled: ``xpos[:, cols[k]]``.
        mat: (K, F, 9) filled: ``xmat[:, cols[k]]``.
    """
    for f in range(xpos.shape[0]):
        for k in range(len(cols)):
            c = cols[k]
            for i in range(3):
                pos[k, f, i] = xpos[f, c, i]
            for i in range(9):
                mat[k, f, i] = xmat[f, c, i]


def point_array(p: dict[str, np.ndarray]) -> np.ndarray:
    """The (14, F, 3) float array of :data:`KERNEL_POINTS` from a dictionary of joints.

    Args:
        p: each joint of :data:`KERNEL_POINTS` as (F, 3), world metres.

    Returns:
        The points in the kernel's order.
    """
    return np.ascontiguousarray(np.stack([np.asarray(p[k], dtype=float) for k in KERNEL_POINTS]))


__all__ = [
    "ACOS_ROWS",
    "ATAN_ROWS",
    "KERNEL_POINTS",
    "gather",
    "point_array",
    "trig_arguments",
    "z_offsets",
]
