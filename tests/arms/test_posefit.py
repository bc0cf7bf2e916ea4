"""The compiled endpoint pose fit (mjwalk.arms.posefit)."""

import numpy as np
import pytest

from mjwalk.arms.armpose import apply_pose
from mjwalk.arms.chain import end_effector
from mjwalk.arms.posefit import fit_endpoint_pose


def _aligned(seed):
    """(2, 2, 3) unit directions of upper arm and forearm at the first and last sample."""
    rng = np.random.default_rng(seed)
    a = np.array([[[0.0, 0.2, -1.0], [0.3, 0.1, -1.0]], [[0.6, 0.3, -0.8], [1.0, 0.2, 0.1]]])
    a = a + rng.normal(0.0, 0.02, a.shape)
    return a / np.linalg.norm(a, axis=-1, keepdims=True)


def test_the_pose_that_made_the_hand_ends_is_found_again():
    center = np.array([0.0, 0.0, -1.0])
    a = _aligned(0)
    lengths = np.array([0.3, 0.25])
    pose = np.array([0.1, -0.2, 0.15, 0.2])
    targets = end_effector(apply_pose(center, a, pose), lengths)  # (2, 3) metres
    x, ok = fit_endpoint_pose(center, a, lengths, targets, np.zeros(4))
    assert ok
    np.testing.assert_allclose(end_effector(apply_pose(center, a, x), lengths), targets, atol=1e-9)
    np.testing.assert_allclose(x, pose, atol=1e-6)


def test_a_scale_beyond_its_bounds_is_reported_as_not_converged():
    center = np.array([0.0, 0.0, -1.0])
    a = _aligned(1)
    lengths = np.array([0.3, 0.25])
    targets = end_effector(apply_pose(center, a, np.array([0.0, 0.0, 0.0, 0.8])), lengths)
    x, ok = fit_endpoint_pose(center, a, lengths, targets, np.zeros(4), (-0.3, 0.3))
    assert not ok  # the log scale ends on its bound: the caller hands it to scipy
    assert np.isclose(x[3], 0.3)


def _reference_solve():
    """The solve as it was before it computed its residual in parts (frozen, compiled the same
    way): every residual whole, the arccos of each direction's log and its exp map each time."""
    import math

    from numba import njit  # deferred: the frozen reference is compiled only for this test

    @njit
    def rot(r0, r1, r2):
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
            x2 - y2 - z2 + w2, 2 * (xy - zw), 2 * (xz + yw),
            2 * (xy + zw), -x2 + y2 - z2 + w2, 2 * (yz - xw),
            2 * (xz - yw), 2 * (yz + xw), -x2 - y2 + z2 + w2,
        )  # fmt: skip

    @njit
    def residual(x, center, a, lengths, targets, out):
        s = math.exp(x[3])
        m = rot(x[0], x[1], x[2])
        for k in range(a.shape[0]):
            h0 = 0.0
            h1 = 0.0
            h2 = 0.0
            for j in range(a.shape[1]):
                u0, u1, u2 = a[k, j, 0], a[k, j, 1], a[k, j, 2]
                cos = u0 * center[0] + u1 * center[1] + u2 * center[2]
                cos = min(max(cos, -1.0), 1.0)
                v0, v1, v2 = u0 - cos * center[0], u1 - cos * center[1], u2 - cos * center[2]
                nv = math.sqrt(v0 * v0 + v1 * v1 + v2 * v2)
                if nv > 1e-12:
                    f = math.acos(cos) / nv * s
                    w0, w1, w2 = v0 * f, v1 * f, v2 * f
                else:
                    w0, w1, w2 = 0.0, 0.0, 0.0
                ang = math.sqrt(w0 * w0 + w1 * w1 + w2 * w2)
                c = math.cos(ang)
                if ang > 1e-12:
                    g = math.sin(ang) / ang
                    d0, d1, d2 = (
                        c * center[0] + g * w0,
                        c * center[1] + g * w1,
                        c * center[2] + g * w2,
                    )
                else:
                    d0, d1, d2 = c * center[0], c * center[1], c * center[2]
                h0 += lengths[j] * (m[0] * d0 + m[1] * d1 + m[2] * d2)
                h1 += lengths[j] * (m[3] * d0 + m[4] * d1 + m[5] * d2)
                h2 += lengths[j] * (m[6] * d0 + m[7] * d1 + m[8] * d2)
            out[3 * k] = h0 - targets[k, 0]
            out[3 * k + 1] = h1 - targets[k, 1]
            out[3 * k + 2] = h2 - targets[k, 2]

    @njit
    def solve(center, a, lengths, targets, x0, lo, hi):
        m = 3 * a.shape[0]
        x = x0.copy()
        r = np.empty(m)
        residual(x, center, a, lengths, targets, r)
        cost = r @ r
        lam = 1e-3
        J = np.empty((m, 4))
        rp = np.empty(m)
        rm = np.empty(m)
        xt = np.empty(4)
        r_new = np.empty(m)
        for _ in range(200):
            for i in range(4):
                xt[:] = x
                xt[i] = x[i] + 1e-6
                residual(xt, center, a, lengths, targets, rp)
                xt[i] = x[i] - 1e-6
                residual(xt, center, a, lengths, targets, rm)
                J[:, i] = (rp - rm) / (2 * 1e-6)
            g = J.T @ r
            H = J.T @ J
            while True:
                A = H.copy()
                for i in range(4):
                    A[i, i] += lam * max(H[i, i], 1e-12)
                dx = -np.linalg.solve(A, g)
                xt[:] = x + dx
                xt[3] = min(max(xt[3], lo), hi)
                residual(xt, center, a, lengths, targets, r_new)
                c_new = r_new @ r_new
                if c_new <= cost:
                    step = np.abs(xt - x).max()
                    x[:] = xt
                    r[:] = r_new
                    done = cost - c_new <= 1e-15 * cost or step <= 1e-13
                    cost = c_new
                    lam = max(lam / 3, 1e-12)
                    if done:
                        return x, True
                    break
                lam *= 4
                if lam > 1e12:
                    return x, True
        return x, False

    return solve


@pytest.mark.slow  # among the fast tier's longest in a quiet warm run (10-21 s): its 5 min budget
def test_the_fit_gives_the_numbers_of_the_whole_residual_solve_bit_for_bit():
    """The residual computed in parts (the logs once, the scaled directions once per log
    scale) changes no bit of the pose: random two-sample problems with three segments, a
    direction on the centre itself (no tangent), and scales near and on the bound."""
    solve = _reference_solve()
    rng = np.random.default_rng(7)
    center = np.array([0.0, 0.0, -1.0])
    lengths = np.array([0.3, 0.25, 0.08])
    for trial in range(60):
        a = rng.normal(0.0, 0.5, (2, 3, 3)) + [0.0, 0.0, -1.0]
        a /= np.linalg.norm(a, axis=-1, keepdims=True)
        if trial % 10 == 0:
            a[0, 0] = center  # on the centre: the log has no tangent
        pose = rng.normal(0.0, 0.3, 4) * [1.0, 1.0, 1.0, 2.0]
        targets = end_effector(apply_pose(center, a, pose), lengths) + rng.normal(0, 0.01, (2, 3))
        x0 = rng.normal(0.0, 0.1, 4)
        got, ok = fit_endpoint_pose(center, a, lengths, targets, x0, (-1.0, 1.0))
        ref, ref_ok = solve(center, a, lengths, targets, x0.copy(), -1.0, 1.0)
        assert got.tobytes() == ref.tobytes()
        assert ok == (ref_ok and -1.0 + 1e-6 < ref[3] < 1.0 - 1e-6)
