"""The endpoint fit of a synthesized arm movement, compiled: the pose (rotation vector + log
angular scale, :func:`~mjwalk.arms.armpose.apply_pose`) that brings the hand at the first and
last sample closest to the given start and end positions (Al-Zubi & Sommer: the movement
"fitted to a start and end position").

The residual (hand minus target, metres, shoulder frame) is that of
:meth:`mjwalk.arms.reach.ReachModel._fit_endpoints`; a Levenberg-Marquardt iteration on its
four parameters (central-difference Jacobian) runs to machine precision in a few dozen
microseconds, where scipy's ``least_squares`` (trust-region reflective, numerical Jacobian)
took milliseconds per reach and stopped within its default tolerances (measured on station
cycles: up to 5e-6 rad from the optimum this solver reaches; ``tests/timeline/test_kernels.py``).
Angles in radians, lengths in metres.
"""

from __future__ import annotations

import math

import numpy as np

from mjwalk._jit import njit

#: |sphere log| below which a direction counts as the centre (armpose._EPS).
_EPS = 1e-12
#: Central-difference step of the Jacobian (radians / log scale): truncation error ~h^2.
_STEP = 1e-6
#: Iterations of the Levenberg-Marquardt loop; a solve that has not converged by then is
#: handed back as failed (the caller falls back to scipy).
_MAX_ITER = 200


@njit
def _rotvec_matrix(r0, r1, r2):
    """Row-major 9-tuple of :func:`mjwalk.arms.armpose.rotvec_matrix` (through the unit
    quaternion, Taylor series below 1e-3 rad)."""
    angle = math.sqrt(r0 * r0 + r1 * r1 + r2 * r2)
    if angle <= 1e-3:
        a2 = angle * angle
        scale = 0.5 - a2 / 48 + a2 * a2 / 3840
    else:
        scale = math.sin(angle / 2) / angle
    x, y, z = scale * r0, scale * r1, scale * r2
    w = math.cos(angle / 2)
    x2, y2, z2, w2 = x * x, y * y, z * z, w * w
    xy, zw, xz, yw, yz, xw = x * y, z * w, x * z, y * w, y * z, x * w
    return (
        x2 - y2 - z2 + w2,
        2 * (xy - zw),
        2 * (xz + yw),
        2 * (xy + zw),
        -x2 + y2 - z2 + w2,
        2 * (yz - xw),
        2 * (xz - yw),
        2 * (yz + xw),
        -x2 - y2 + z2 + w2,
    )


@njit
def _logs(center, a):
    """The pose-free part of the sphere log of each direction of ``a`` (K, S, 3) at
    ``center``: its tangent ``v`` (K, S, 3) before scaling, ``acos(cos) / |v|`` (K, S) (the
    factor the scale multiplies) and where ``|v|`` is ~zero (the centre itself: no tangent)."""
    k_n, s_n = a.shape[0], a.shape[1]
    v = np.empty((k_n, s_n, 3))
    f0 = np.empty((k_n, s_n))
    off = np.empty((k_n, s_n), dtype=np.bool_)
    for k in range(k_n):
        for j in range(s_n):
            u0, u1, u2 = a[k, j, 0], a[k, j, 1], a[k, j, 2]
            cos = u0 * center[0] + u1 * center[1] + u2 * center[2]
            cos = min(max(cos, -1.0), 1.0)
            v0, v1, v2 = u0 - cos * center[0], u1 - cos * center[1], u2 - cos * center[2]
            nv = math.sqrt(v0 * v0 + v1 * v1 + v2 * v2)
            v[k, j, 0], v[k, j, 1], v[k, j, 2] = v0, v1, v2
            off[k, j] = not nv > _EPS
            f0[k, j] = math.acos(cos) / nv if nv > _EPS else 0.0
    return v, f0, off


@njit
def _scaled(s, center, v, f0, off, out):
    """The directions (K, S, 3) into ``out``: each log (:func:`_logs`) scaled by ``s``, then
    the sphere's exp about ``center``."""
    for k in range(v.shape[0]):
        for j in range(v.shape[1]):
            # sphere_log, scaled by s, then sphere_exp about the centre
            if not off[k, j]:
                f = f0[k, j] * s
                w0, w1, w2 = v[k, j, 0] * f, v[k, j, 1] * f, v[k, j, 2] * f
            else:
                w0, w1, w2 = 0.0, 0.0, 0.0
            ang = math.sqrt(w0 * w0 + w1 * w1 + w2 * w2)
            c = math.cos(ang)
            if ang > _EPS:
                g = math.sin(ang) / ang
                d0, d1, d2 = c * center[0] + g * w0, c * center[1] + g * w1, c * center[2] + g * w2
            else:
                d0, d1, d2 = c * center[0], c * center[1], c * center[2]
            out[k, j, 0], out[k, j, 1], out[k, j, 2] = d0, d1, d2


@njit
def _hand(m, d, lengths, targets, out):
    """Hand minus target (K*3,) into ``out``: the directions ``d`` (K, S, 3) rotated by the
    row-major matrix ``m`` (9-tuple), summed with ``lengths`` (S,), minus ``targets``."""
    for k in range(d.shape[0]):
        h0 = 0.0
        h1 = 0.0
        h2 = 0.0
        for j in range(d.shape[1]):
            d0, d1, d2 = d[k, j, 0], d[k, j, 1], d[k, j, 2]
            h0 += lengths[j] * (m[0] * d0 + m[1] * d1 + m[2] * d2)
            h1 += lengths[j] * (m[3] * d0 + m[4] * d1 + m[5] * d2)
            h2 += lengths[j] * (m[6] * d0 + m[7] * d1 + m[8] * d2)
        out[3 * k] = h0 - targets[k, 0]
        out[3 * k + 1] = h1 - targets[k, 1]
        out[3 * k + 2] = h2 - targets[k, 2]


@njit
def _solve(center, a, lengths, targets, x0, lo, hi):
    """Levenberg-Marquardt for the pose (4,) from ``x0`` with x[3] kept in [lo, hi]; returns
    (pose, converged). The residual in parts: the directions' logs once (:func:`_logs`), the
    scaled directions once per log scale (:func:`_scaled`; the rotation's three Jacobian
    columns keep the pose's own), the rotation per residual (:func:`_hand`): the same numbers,
    in the same order, as the residual computed whole each time (which ran the logs' arccos
    and the exp map's sine and cosine about ten times an iteration)."""
    m = 3 * a.shape[0]
    x = x0.copy()
    v, f0, off = _logs(center, a)
    dx_ = np.empty(a.shape)  # the directions at x's log scale
    dt = np.empty(a.shape)  # ... at a trial's or a Jacobian column's
    r = np.empty(m)
    _scaled(math.exp(x[3]), center, v, f0, off, dx_)
    _hand(_rotvec_matrix(x[0], x[1], x[2]), dx_, lengths, targets, r)
    cost = r @ r
    lam = 1e-3
    J = np.empty((m, 4))
    rp = np.empty(m)
    rm = np.empty(m)
    xt = np.empty(4)
    r_new = np.empty(m)
    for _ in range(_MAX_ITER):
        for i in range(3):
            xt[:] = x
            xt[i] = x[i] + _STEP
            _hand(_rotvec_matrix(xt[0], xt[1], xt[2]), dx_, lengths, targets, rp)
            xt[i] = x[i] - _STEP
            _hand(_rotvec_matrix(xt[0], xt[1], xt[2]), dx_, lengths, targets, rm)
            J[:, i] = (rp - rm) / (2 * _STEP)
        rot = _rotvec_matrix(x[0], x[1], x[2])
        _scaled(math.exp(x[3] + _STEP), center, v, f0, off, dt)
        _hand(rot, dt, lengths, targets, rp)
        _scaled(math.exp(x[3] - _STEP), center, v, f0, off, dt)
        _hand(rot, dt, lengths, targets, rm)
        J[:, 3] = (rp - rm) / (2 * _STEP)
        g = J.T @ r
        H = J.T @ J
        while True:
            A = H.copy()
            for i in range(4):
                A[i, i] += lam * max(H[i, i], 1e-12)
            dx = -np.linalg.solve(A, g)
            xt[:] = x + dx
            xt[3] = min(max(xt[3], lo), hi)
            _scaled(math.exp(xt[3]), center, v, f0, off, dt)
            _hand(_rotvec_matrix(xt[0], xt[1], xt[2]), dt, lengths, targets, r_new)
            c_new = r_new @ r_new
            if c_new <= cost:
                step = np.abs(xt - x).max()
                x[:] = xt
                r[:] = r_new
                dx_[:] = dt
                done = cost - c_new <= 1e-15 * cost or step <= 1e-13
                cost = c_new
                lam = max(lam / 3, 1e-12)
                if done:
                    return x, True
                break
            lam *= 4
            if lam > 1e12:  # no descent at any damping: a minimum to working precision
                return x, True
    return x, False


def fit_endpoint_pose(
    center: np.ndarray,
    a: np.ndarray,
    lengths: np.ndarray,
    targets: np.ndarray,
    x0: np.ndarray,
    log_scale_bounds: tuple[float, float] = (-1.0, 1.0),
) -> tuple[np.ndarray, bool]:
    """The pose (4,) = (rotation vector, log angular scale) that brings the hand of the
    aligned directions ``a`` (K, S, 3) (the samples to fit, segment ``lengths`` (S,) metres)
    closest to ``targets`` (K, 3) in least squares, from ``x0``; the log scale kept within
    ``log_scale_bounds``. Returns (pose, converged); a pose on a bound also reports False,
    so the caller can hand that case to a solver that treats bounds exactly.

    Args:
        center: (3,) unit centre of the angular scaling.
        a: (K, S, 3) aligned directions of the samples to fit.
        lengths: (S,) segment lengths, metres.
        targets: (K, 3) hand targets, metres, shoulder frame.
        x0: (4,) initial pose.
        log_scale_bounds: (lo, hi) bounds of the log scale.

    Returns:
        ``(pose (4,), converged)``.
    """
    lo, hi = log_scale_bounds
    x, ok = _solve(
        np.ascontiguousarray(center, dtype=float),
        np.ascontiguousarray(a, dtype=float),
        np.ascontiguousarray(lengths, dtype=float),
        np.ascontiguousarray(targets, dtype=float),
        np.array(x0, dtype=float),
        float(lo),
        float(hi),
    )
    on_bound = not lo + 1e-6 < x[3] < hi - 1e-6
    return x, bool(ok and not on_bound)
