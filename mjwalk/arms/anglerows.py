"""Compiled row arithmetic of the arm kinematics in :mod:`mjwalk.arms.chain` (issue 50): the
two-link IK (:func:`ik_rows`), and the sums, products, clips and branch choices of
:func:`~mjwalk.arms.chain.arm_joint_angles` between its inverse trigonometric functions
(:func:`frame_terms`, :func:`hand_terms`, :func:`fill_angles`, :func:`unwrap_col`); and
the evenly spaced samples the per-reach code asks for again and again (:func:`unit_steps`).

Each kernel does the NumPy code it replaced element by element in the same order (row-wise
dot products summed left to right, ``np.einsum``'s sum from 0, ``np.clip``'s and
``np.maximum``'s NaN, ``np.unwrap``'s remainder, boundary fix and running sum), so the numbers
are the same to the bit (``tests/arms/test_anglerows.py`` compares them over seeded inputs).
The inverse trigonometric functions (``arcsin``, ``arccos``, ``arctan2``) and ``cos``/``sin``
stay NumPy's, called by :mod:`~mjwalk.arms.chain` between the kernels: NumPy's vectorised
versions differ from the C library's, which compiled code calls, in the last bit of about
one value in twelve on this machine's AVX-512 (measured; so they are not compiled).

Frames and units as in :mod:`mjwalk.arms.chain`: the shoulder's thorax frame, metres, radians.
"""

from __future__ import annotations

import functools
import math

import numpy as np

from mjwalk._jit import njit


@njit
def _clip(v, lo, hi):
    """``np.clip(v, lo, hi)`` of one value (a NaN kept, -0.0 kept)."""
    c = v if v != v or v > lo else lo
    return c if c != c or c < hi else hi


@njit
def _cross_rows(a, b0, b1, b2, out, i):
    """``np.cross(a[i], (b0, b1, b2))`` into ``out[i]``: NumPy's products and differences."""
    out[i, 0] = a[i, 1] * b2 - a[i, 2] * b1
    out[i, 1] = a[i, 2] * b0 - a[i, 0] * b2
    out[i, 2] = a[i, 0] * b1 - a[i, 1] * b0


@njit
def ik_rows(target, hint, l1, l2, lo, hi, c, l1sq, upper, fore):
    """:func:`~mjwalk.arms.chain.two_link_ik_rows` into ``upper`` and ``fore`` (n, 3): wrist
    ``target`` (n, 3) m from the shoulder, elbow ``hint`` (n, 3); ``lo``/``hi`` the clip of
    the shoulder-wrist distance, ``c`` = l1**2 - l2**2 and ``l1sq`` = l1**2 as the caller's
    scalar arithmetic gives them.

    Args:
        target: (n, 3) wrist positions, metres from the shoulder.
        hint: (n, 3) directions the elbows bend towards.
        l1: upper arm length, metres.
        l2: forearm length, metres.
        lo: the shortest shoulder-wrist distance, metres.
        hi: the longest, metres.
        c: l1**2 - l2**2, square metres.
        l1sq: l1**2, square metres.
        upper: (n, 3) out: unit upper-arm directions.
        fore: (n, 3) out: unit forearm directions.
    """
    n = target.shape[0]
    axis = np.empty((n, 3))
    perp = np.empty((n, 3))
    for i in range(n):
        t0, t1, t2 = target[i, 0], target[i, 1], target[i, 2]
        norm = np.sqrt(t0 * t0 + t1 * t1 + t2 * t2)
        m = norm if norm != norm or norm > 1e-9 else 1e-9
        axis[i, 0], axis[i, 1], axis[i, 2] = t0 / m, t1 / m, t2 / m
        k = hint[i, 0] * axis[i, 0] + hint[i, 1] * axis[i, 1] + hint[i, 2] * axis[i, 2]
        for j in range(3):
            perp[i, j] = hint[i, j] - k * axis[i, j]
        p0, p1, p2 = perp[i, 0], perp[i, 1], perp[i, 2]
        if np.sqrt(p0 * p0 + p1 * p1 + p2 * p2) < 1e-9:
            # a hint along the axis: any perpendicular, from y (or x)
            _cross_rows(axis, 0.0, 1.0, 0.0, perp, i)
            p0, p1, p2 = perp[i, 0], perp[i, 1], perp[i, 2]
            if np.sqrt(p0 * p0 + p1 * p1 + p2 * p2) < 1e-9:
                _cross_rows(axis, 1.0, 0.0, 0.0, perp, i)
        p0, p1, p2 = perp[i, 0], perp[i, 1], perp[i, 2]
        pn = np.sqrt(p0 * p0 + p1 * p1 + p2 * p2)
        d = _clip(norm, lo, hi)
        a = (c + d * d) / (2 * d)
        r = l1sq - a * a
        h = np.sqrt(r if r >= 0.0 or r != r else 0.0)
        for j in range(3):
            elbow = a * axis[i, j] + h * (perp[i, j] / pn)
            upper[i, j] = elbow / l1
            fore[i, j] = (d * axis[i, j] - elbow) / l2


@njit
def upper_x(u, x, straight):
    """The upper arm's x axis of each row of ``u`` (n, S, 3) into ``x`` (n, 3): the forearm's
    part perpendicular to the upper arm, normalised; ``straight`` (n,) set where its norm is
    under 1e-3 (a straight elbow: ``x`` left unnormalised there for the caller).

    Args:
        u: (n, S, 3) unit segment directions, thorax frame.
        x: (n, 3) out: the upper arm frame's x axes.
        straight: (n,) out: straight elbows.
    """
    for i in range(u.shape[0]):
        d = u[i, 1, 0] * u[i, 0, 0] + u[i, 1, 1] * u[i, 0, 1] + u[i, 1, 2] * u[i, 0, 2]
        for j in range(3):
            x[i, j] = u[i, 1, j] - d * u[i, 0, j]
        norm = np.sqrt(x[i, 0] * x[i, 0] + x[i, 1] * x[i, 1] + x[i, 2] * x[i, 2])
        straight[i] = norm < 1e-3
        if not straight[i]:
            for j in range(3):
                x[i, j] = x[i, j] / norm


@njit
def frame_terms(u, x, y, terms, lock, gimbal):
    """The shoulder frame's y axis (``y`` (n, 3) = z x x, z = -upper arm) and the arguments of
    the inverse trigonometric functions into ``terms`` (6, n): the clipped sine of the Y-X-Z
    middle angle, the two (y, x) pairs of its outer angles' arctan2, the clipped cosine of
    the elbow; ``lock`` (n,) where |sine| > ``gimbal`` (decomposed by scipy).

    Args:
        u: (n, S, 3) unit segment directions, thorax frame.
        x: (n, 3) the upper arm frame's x axes (:func:`upper_x`).
        y: (n, 3) out: its y axes.
        terms: (6, n) out: the functions' arguments.
        lock: (n,) out: near gimbal lock.
        gimbal: the |sine| beyond which a frame is locked.
    """
    for i in range(u.shape[0]):
        z0, z1, z2 = -u[i, 0, 0], -u[i, 0, 1], -u[i, 0, 2]
        x0, x1, x2 = x[i, 0], x[i, 1], x[i, 2]
        y[i, 0] = z1 * x2 - z2 * x1
        y[i, 1] = z2 * x0 - z0 * x2
        y[i, 2] = z0 * x1 - z1 * x0
        sb = -z1
        terms[0, i] = _clip(sb, -1.0, 1.0)
        terms[1, i] = z0
        terms[2, i] = z2
        terms[3, i] = x1
        terms[4, i] = y[i, 1]
        e = u[i, 0, 0] * u[i, 1, 0] + u[i, 0, 1] * u[i, 1, 1] + u[i, 0, 2] * u[i, 1, 2]
        terms[5, i] = _clip(e, -1.0, 1.0)
        lock[i] = abs(sb) > gimbal


@njit
def hand_terms(u, x, y, ce, se, cp, sp, terms):
    """The hand's direction in the forearm frame (the shoulder frame's transpose, the elbow's
    and the pronation's rotations undone: cosines ``ce``/``cp`` and sines ``se``/``sp`` (n,))
    as the wrist's arcsin and arctan2 take it, into ``terms`` (3, n): the clipped sine of the
    deviation, then the flexion's (y, x).

    Args:
        u: (n, 3, 3) unit segment directions, thorax frame.
        x: (n, 3) the upper arm frame's x axes.
        y: (n, 3) its y axes.
        ce: (n,) cosines of minus the elbow angles.
        se: (n,) their sines.
        cp: (n,) cosines of minus the side's pronation.
        sp: (n,) their sines.
        terms: (3, n) out: the functions' arguments.
    """
    for i in range(u.shape[0]):
        h0 = 0.0 + x[i, 0] * u[i, 2, 0] + x[i, 1] * u[i, 2, 1] + x[i, 2] * u[i, 2, 2]
        h1 = 0.0 + y[i, 0] * u[i, 2, 0] + y[i, 1] * u[i, 2, 1] + y[i, 2] * u[i, 2, 2]
        h2 = 0.0 + -u[i, 0, 0] * u[i, 2, 0] + -u[i, 0, 1] * u[i, 2, 1] + -u[i, 0, 2] * u[i, 2, 2]
        g0 = ce[i] * h0 - se[i] * h2
        g2 = se[i] * h0 + ce[i] * h2
        f0 = cp[i] * g0 + sp[i] * h1
        f1 = -sp[i] * g0 + cp[i] * h1
        terms[0, i] = _clip(f1, -1.0, 1.0)
        terms[1, i] = f0
        terms[2, i] = -g2


@njit
def unwrap_col(q, k):
    """``q[:, k] = np.unwrap(q[:, k])`` in place: NumPy's arithmetic (period 2 pi, the
    remainder as ``np.mod`` takes it, the boundary fix, the running sum of the corrections).

    Args:
        q: (n, m) angles, radians (changed in place).
        k: the column.
    """
    n = q.shape[0]
    pi = np.pi
    period = 2.0 * pi
    acc = 0.0
    prev = q[0, k]
    for i in range(1, n):
        cur = q[i, k]
        dd = cur - prev
        ddmod = (dd - -pi) % period + -pi
        if ddmod == -pi and dd > 0:
            ddmod = pi
        ph = ddmod - dd
        if abs(dd) < pi:
            ph = 0.0
        acc = ph if i == 1 else acc + ph
        q[i, k] = cur + acc
        prev = cur


@njit
def fill_angles(q, a, b, c, elbow, pron, s, unwrap):
    """The shoulder's, elbow's and forearm's columns of ``q`` (n, 7): flexion -a, abduction
    s b, rotation -s c, the elbow, the pronation; with ``unwrap`` the flexion and rotation
    unwrapped along the rows (:func:`unwrap_col`).

    Args:
        q: (n, 7) out: joint angles, radians.
        a: (n,) the shoulder's Y angles, radians.
        b: (n,) its X angles.
        c: (n,) its Z angles.
        elbow: (n,) elbow flexion, radians.
        pron: (n,) forearm pronation, radians.
        s: +1 for the left arm, -1 for the right.
        unwrap: unwrap flexion and rotation along the rows.
    """
    for i in range(q.shape[0]):
        q[i, 0] = -a[i]
        q[i, 1] = s * b[i]
        q[i, 2] = -s * c[i]
        q[i, 3] = elbow[i]
        q[i, 4] = pron[i]
    if unwrap:
        unwrap_col(q, 0)
        unwrap_col(q, 2)


@njit
def retrace_rows(out, src, back):
    """Poses ``back`` (m, nq) retracing ``out`` (n, nq) backwards at the fractional frames
    ``src`` (m,) of the reversed sequence (0 to n - 1): each the blend ``(1 - w) a + w b`` of
    the two poses about it, the arithmetic of :func:`mjwalk.cycle.reaching._retraced`'s
    NumPy code (``floor``, the index clipped to the last frame, the weight ``src - i0``).

    Args:
        out: (n, nq) the reach's poses.
        src: (m,) fractional frames of the reversed poses, 0 to n - 1.
        back: (m, nq) out: the retracing poses.
    """
    n = out.shape[0]
    for k in range(src.shape[0]):
        i0 = min(int(np.floor(src[k])), n - 1)
        i1 = min(i0 + 1, n - 1)
        w = src[k] - i0
        for j in range(out.shape[1]):
            back[k, j] = (1.0 - w) * out[n - 1 - i0, j] + w * out[n - 1 - i1, j]


@functools.lru_cache(maxsize=512)
def _unit_steps(n: int) -> np.ndarray:
    steps = np.linspace(0.0, 1.0, n)
    steps.flags.writeable = False
    return steps


def unit_steps(n: int) -> np.ndarray:
    """``np.linspace(0.0, 1.0, n)`` (the same numbers), made once per ``n`` and copied.

    Args:
        n: the number of samples.

    Returns:
        (n,) a new array.
    """
    return _unit_steps(int(n)).copy()


def all_close(a: np.ndarray, b: np.ndarray) -> bool:
    """``np.allclose(a, b)`` (rtol 1e-5, atol 1e-8, NaNs unequal) of two equal-length 1-D
    vectors, element by element in Python floats: the same IEEE operations, without NumPy's
    per-call set-up (error state, broadcasting), for the per-reach code's (3,) directions.

    Args:
        a: (n,) values.
        b: (n,) values, the reference (its magnitude scales the tolerance).

    Returns:
        Whether every ``|a - b| <= 1e-8 + 1e-5 |b|`` (``b`` finite), or ``a == b``.
    """
    xs, ys = np.asarray(a, dtype=float).tolist(), np.asarray(b, dtype=float).tolist()
    pairs = zip(xs, ys, strict=True)
    for x, y in pairs:
        if not ((abs(x - y) <= 1e-8 + 1e-5 * abs(y) and math.isfinite(y)) or x == y):
            return False
    return True


def min_jerk(tau: np.ndarray) -> np.ndarray:
    """Minimum-jerk profile 10 t^3 - 15 t^4 + 6 t^5 on t in [0, 1].

    Args:
        tau: normalized time, clipped to [0, 1].

    Returns:
        the profile, 0 at tau <= 0 and 1 at tau >= 1, same shape as ``tau``.
    """
    tau = np.clip(tau, 0.0, 1.0)
    return tau**3 * (10 - 15 * tau + 6 * tau**2)


@functools.lru_cache(maxsize=512)
def _min_jerk_steps(n: int) -> np.ndarray:
    w = min_jerk(unit_steps(n))
    w.flags.writeable = False
    return w


def min_jerk_steps(n: int) -> np.ndarray:
    """:func:`min_jerk` of ``np.linspace(0.0, 1.0, n)``, made once per
    ``n`` and copied.

    Args:
        n: the number of samples.

    Returns:
        (n,) a new array, the same numbers.
    """
    return _min_jerk_steps(int(n)).copy()
